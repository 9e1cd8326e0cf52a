// The inverse problem: find the stroke - speed, aim, topspin, sidespin - whose cue ball
// comes to rest on the target after an allowed number of cushions, within the
// problem's limits. A global NLopt search over the bounded stroke space is followed by
// a derivative-free local polish from the best distinct starts; the distinct solutions
// found (cushion routes, draw or follow, left or right spin) are all returned, each
// with its chance of success under a player's execution noise.
//
// Pure functions of their arguments: no globals, no hidden statics; plan() with the
// same options and seed gives the same answer, and may run on many threads at once.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::planner {

// Global stage (NLopt): DIRECT-L, controlled random search with local mutation (CRS2),
// multi-level single linkage (MLSL, with the local method inside), improved stochastic
// ranking evolution (ISRES).
enum class GlobalMethod { direct_l, crs2, mlsl, isres };
// Local polish (NLopt, derivative-free): BOBYQA, Subplex, COBYLA, Nelder-Mead.
enum class LocalMethod { bobyqa, sbplx, cobyla, neldermead };

const char* to_string(GlobalMethod method);
const char* to_string(LocalMethod method);
// Parse the names to_string gives ("direct_l", "crs2", ..., "bobyqa", ...).
bool parse_global_method(const std::string& name, GlobalMethod* method);
bool parse_local_method(const std::string& name, LocalMethod* method);

// A player's execution error: independent Gaussian errors on each stroke.
struct NoiseModel {
  double aim_deg = 0.125;      // standard deviation of the aim (deg)
  double speed = 0.075;        // standard deviation of the speed (m/s)
  double tip_offset = 0.0005;  // standard deviation of the tip offset each way (m); k = 2.5 d / R
  double scale = 1.0;          // multiplies every deviation (--noise)
  std::string validate() const;
};

struct PlannerOptions {
  GlobalMethod global = GlobalMethod::crs2;
  LocalMethod local = LocalMethod::sbplx;
  int max_evaluations = 4000;  // shot simulations for the search, global and local together
  double max_time_s = 10.0;    // wall-clock budget for the search (s)
  int local_starts = 6;        // distinct global candidates polished locally
  uint64_t seed = 1;           // every random choice derives from it
  int threads = 1;             // local polishes run in parallel; the result does not change
  bool enforce_rigid_limit = false;  // reject shots whose cushion normal speed exceeds it
  bool robust = false;         // maximise the success probability, not the nominal miss
  NoiseModel noise;
  int robustness_samples = 200;      // Monte Carlo strokes per success probability
  int max_alternatives = 5;          // distinct solutions returned besides the best
  physics::SimulationOptions simulation;  // impact method (and table), accuracy, events

  // Empty when usable; otherwise one line naming the field.
  std::string validate() const;
};

enum class PlanStatus {
  solved,            // the best shot stops within the tolerance and meets every constraint
  unreachable,       // the search converged everywhere it looked without reaching the target
  budget_exhausted,  // evaluations or time ran out before a solution was found
  invalid_input,     // nothing searched; message names the field
};
const char* to_string(PlanStatus status);

// A stroke and what it does.
struct PlannedShot {
  physics::Shot shot;
  physics::ShotStatus outcome = physics::ShotStatus::rest;
  physics::Vec2 final_position;      // m
  double miss_distance = 0.0;        // m from the target; infinite unless at rest
  int cushion_hits = 0;
  std::vector<int> route;            // cushions in the order met (ShotEvent::cushion)
  bool within_limits = false;        // speed, spin, aim and cushion-count limits
  bool rigid_limit_exceeded = false;
  double max_cushion_normal_speed = 0.0;  // m/s
  double success_probability = 0.0;  // of stopping within the tolerance under the noise
  std::string family;                // route and spin in words, e.g. "2 cushions (y = 0, x = L), follow, right"
};

struct PlanResult {
  PlanStatus status = PlanStatus::invalid_input;
  std::string message;               // why, in a sentence (always set)
  PlannedShot best;
  std::vector<PlannedShot> alternatives;  // distinct families, best first
  int evaluations = 0;               // shot simulations made (search and robustness)
  double time_s = 0.0;               // wall clock
};

PlanResult plan(const problems::Problem& problem, const PlannerOptions& options);

// Fraction of `samples` noisy strokes around `shot` that stop within the problem's
// tolerance of the target (at rest, not pocketed, no obstacle, allowed cushions).
// Deterministic for a seed.
double success_probability(const problems::Problem& problem, const physics::Shot& shot,
                           const NoiseModel& noise, int samples, uint64_t seed,
                           const physics::SimulationOptions& simulation);

// Simulates a stroke on the problem's scene and describes it as a PlannedShot
// (success_probability left at 0).
PlannedShot evaluate(const problems::Problem& problem, const physics::Shot& shot,
                     const physics::SimulationOptions& simulation);

// The stroke in a player's terms: tip offsets as fractions of the ball radius
// (d = k R / 2.5) and words such as "half a tip of right, a quarter tip below centre".
struct TipOffset {
  double right = 0.0;  // sidespin offset / R, > 0 right of centre
  double up = 0.0;     // topspin offset / R, > 0 above centre (follow), < 0 draw
};
TipOffset tip_offset(const physics::Shot& shot);
std::string describe_stroke(const physics::Shot& shot);

}  // namespace cueplan::planner
