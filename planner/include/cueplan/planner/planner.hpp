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
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::planner {

class PositionField;  // position.hpp
class PositionCache;

// Global stage (NLopt): DIRECT-L, controlled random search with local mutation (CRS2),
// multi-level single linkage (MLSL, with the local method inside), improved stochastic
// ranking evolution (ISRES). Or (OMPL) ompl_kpiece1: KPIECE1 grows a tree of strokes,
// each a random perturbation of one already played, and spreads it over the table by
// where they land (a grid of landing positions), leaning toward the strokes that land
// nearest the target; half its budget goes to the uniform sample of strokes the tree
// starts from. Deterministic for a seed like the rest. OMPL reports each run on stderr
// unless the program has called quiet_ompl_messages() (route.hpp).
enum class GlobalMethod { direct_l, crs2, mlsl, isres, ompl_kpiece1 };
// Local polish (NLopt, derivative-free): BOBYQA, Subplex, COBYLA, Nelder-Mead.
enum class LocalMethod { bobyqa, sbplx, cobyla, neldermead };

const char* to_string(GlobalMethod method);
const char* to_string(LocalMethod method);
// Parse the names to_string gives ("direct_l", "crs2", ..., "ompl_kpiece1", "bobyqa", ...).
bool parse_global_method(const std::string& name, GlobalMethod* method);
bool parse_local_method(const std::string& name, LocalMethod* method);

// A player's execution error: independent Gaussian errors on each stroke. A noisy
// tip offset beyond the miscue limit (sqrt(k_T^2 + k_S^2) above the larger of
// physics::kMiscueSpin, i.e. d > R/2, and the problem's spin limit) is a miscue and counts as a failure,
// as does a noisy speed that is not positive; spin is never clamped.
struct NoiseModel {
  double aim_deg = 0.125;      // standard deviation of the aim (deg)
  double speed = 0.075;        // standard deviation of the speed (m/s)
  double tip_offset = 0.0005;  // standard deviation of the tip offset each way (m); k = 2.5 d / R
  // What side costs a player (docs/squirt.md). The tip lands less surely the further from
  // centre it is aimed: each way the offset's deviation grows by this fraction of the
  // offset intended that way. Through the squirt, an offset error is a direction error.
  double tip_offset_relative = 0.1;
  // A player allows for the squirt by aiming the cue off the line the ball must take, by
  // feel: that allowance errs by this fraction of the squirt (a deviation added to the
  // aim's in quadrature). Zero for a centre-ball stroke.
  double squirt_judgement = 0.1;
  // A tip offset error comes from the back hand's sway, which pivots the cue at the
  // bridge this far behind the tip (m): a tip that lands d to the right of where it
  // should has the cue turned d / bridge_length to the right as well, against the squirt
  // that d adds (back-hand english; docs/squirt.md). 0: the cue shifts sideways instead,
  // its direction unchanged.
  double bridge_length = 0.25;
  double scale = 1.0;          // multiplies every deviation (--noise)
  // Empty when usable; otherwise the first broken rule, fields named as these members.
  physics::Validation validate() const;
};

// A probability estimated from Monte Carlo strokes: successes / samples with its 95 %
// Wilson score interval (Wilson 1927), which stays inside [0, 1] and is not empty at
// 0 or all successes. With no samples, p = 0 and the interval is [0, 1].
struct Estimate {
  double p = 0.0;
  double low = 0.0;
  double high = 1.0;
  int samples = 0;    // strokes counted
  int successes = 0;  // of those, strokes that succeeded

  bool operator==(const Estimate&) const = default;
};
// successes of samples (0 <= successes <= samples) as an Estimate.
Estimate wilson_estimate(int successes, int samples);

// A stroke's chance of success under the execution noise, condition by condition.
// P(pot) counts the strokes that pot the named ball (a pot problem only); P(position)
// is the chance that the cue ball also stops in the landing zone given that it potted
// (its samples are the potting strokes), or, without a pot, simply of stopping there;
// P(both) is the chance of the whole shot: pot and position together (without a pot,
// equal to position).
//
// Position play (a problem with `next`): P(position) is the chance of stopping on the
// target given the pot (1 without a target); P(next) is the mean, over the noisy strokes
// that pot (and stop on the target), of P(next pot) from where the cue ball stops
// (PositionField), its interval the band that P holds over the middle 80 % of those
// landings (never narrower than the mean's normal 95 % interval) widened by kFieldError,
// the closed form's allowance: what the player may be left with (in a plan's reported
// strokes it also holds P(next pot) where the stroke as planned stops, +- kFieldError); P(both) is P(pot, position and next) counted on the same
// strokes, each landing's next pot drawn as made with its P (with a list of next pots,
// the look-ahead value: position.hpp), the Wilson interval of that count.
struct Success {
  std::optional<Estimate> pot;
  Estimate position;
  Estimate both;
  std::optional<Estimate> next;

  bool operator==(const Success&) const = default;
};

// The answer depends on the options and the seed only, not on `threads`, as long as
// the evaluation budget (not max_time_s) is what ends each stage.
//
// The default pairing and budget are measured (bench/README.md, "Planner"): CRS2 with
// BOBYQA solved the most problems at a tight budget and had the shortest median plan
// time of the pairings that solved all of them at 2000 evaluations. On obstacle fields
// (obstacle_field_problems, 12 and 16 balls; bench/README.md, "Obstacle fields") the
// OMPL stage ompl_kpiece1 tied CRS2 at 400, 1000 and 2000 evaluations without beating
// it measurably, so CRS2 stays the default for every scene; choose it with `global`.
struct PlannerOptions {
  GlobalMethod global = GlobalMethod::crs2;
  LocalMethod local = LocalMethod::bobyqa;
  int max_evaluations = 2000;  // shot simulations for the search, global and local together
  // Wall-clock budget (s) for the whole plan: search, exact verification, the side
  // variants, the success probabilities and the robust polish. Once it has passed,
  // nothing new is started; a Monte Carlo estimate it cuts short counts the strokes
  // it did simulate (Estimate::samples), and only the reported strokes are still
  // described (one simulation each).
  double max_time_s = 10.0;
  int local_starts = 6;        // distinct global candidates (best of their families) polished locally
  double global_share = 0.5;   // fraction of max_evaluations the global stage may use, (0, 1)
  // The global search's second half and the polishes derive from it. The first half
  // of the global search and the noise draws of every success estimate do not
  // (kReferenceSeed): whatever the seed, the same strokes are found and ranked, so the
  // advice is the same (issue 31, "Stable answers").
  uint64_t seed = 1;
  int threads = 1;             // local polishes run in parallel; the result does not change
  bool enforce_rigid_limit = false;  // reject shots whose cushion normal speed exceeds it
  bool robust = false;         // maximise the success probability, not the nominal miss
  NoiseModel noise;
  int robustness_samples = 200;      // Monte Carlo strokes per success probability (same
                                     // seed for every shot); 0: not estimated
  int robust_search_samples = 32;    // robust mode: common noise draws per objective call
  int robust_max_evaluations = 20000;  // robust mode: shot simulations for the robust polish
  int max_alternatives = 5;          // distinct solutions returned besides the best
  // Stop polishing at the first pass in which a stroke lands and skip the side
  // variants: the quickest landing stroke rather than the coach's choice among many
  // (the route planner's steering uses it). By default the polish goes on through the
  // families the budget allows and every solved stroke with side is tried without it.
  bool stop_at_first_solution = false;
  physics::SimulationOptions simulation;  // impact method (and table), accuracy, events
  // When `simulation` searches with the impact table, re-simulate the returned shots
  // with the exact method (accuracy 1e-9) and report those outcomes; a shot the exact
  // method moves out of the tolerance is polished again with it. Success
  // probabilities and the robust polish use `simulation` as it is (fast with a table).
  bool verify_exact = true;
  // A pot problem's aim is solved for each speed and spin (the 1-D root near the
  // ghost-ball line) and the search is over speed and spin; false searches the aim
  // like any other coordinate (bench/README.md, "Pot and position", compares them).
  bool solve_pot_aim = true;
  // Position play: where the position fields of problems with `next` are kept between
  // plans (not owned; may be shared by threads); null: each plan builds its own.
  PositionCache* position_cache = nullptr;

  // Empty when usable; otherwise the first broken rule, fields named as these members
  // ({"max_evaluations"}, {"noise", "scale"}, {"simulation", "impact_accuracy"}).
  physics::Validation validate() const;
};

enum class PlanStatus {
  solved,             // the best shot stops within the tolerance and meets every constraint
  no_solution_found,  // every local polish converged (or stopped improving) short of the
                      // target: a strong hint that none exists, not a proof (message says why)
  budget_exhausted,   // evaluations or time ran out before a solution was found
  unreachable,        // no direct, kick or bank route exists within the limits (each family
                      // screened or off the cushions; ruled_out and the message say why)
  invalid_input,      // nothing searched; message names the field
};
const char* to_string(PlanStatus status);

// A way of playing the shot, as a coach names it: the cushions met in order and the
// signs of the spins, with a band around zero (under half a quarter tip) for stun and
// no side. Strokes of equal families are "the same way" of playing it.
struct Family {
  std::vector<int> route;    // cushions in the order met (ShotEvent::cushion)
  int topspin = 0;           // +1 follow, 0 stun, -1 draw
  int sidespin = 0;          // +1 right, 0 none, -1 left
  bool ended_early = false;  // pocketed or obstacle: not a way to the target

  auto operator<=>(const Family&) const = default;
};
// In words, e.g. "2 cushions (y = W, x = L), follow, right spin".
std::string describe(const Family& family);

// A pot in a player's terms (pot problems only).
struct PotReport {
  std::string ball;          // the pot's ball
  int pocket = -1;           // index into Scene::pockets
  std::string pocket_name;   // as problem files name it
  bool made = false;         // the ball dropped in that pocket
  std::string striker;       // the ball that struck it: "cue", or a plant's first ball
  // Between the striking ball's path and the line of centres at contact (0: full ball);
  // cut_side +1 when the pot's ball leaves to the left of that path, -1 to the right.
  double cut_deg = 0.0;
  int cut_side = 0;
  std::string thickness;     // full, 3/4, half, 1/4 or thin: the ball covered, 1 - sin(cut)
  double throw_deg = 0.0;    // the pot's ball's direction against the line of centres (ccw)
  double ghost_aim_deg = 0.0;  // the aim of the ghost-ball line (no throw)
  double aim_allowance_deg = 0.0;  // the stroke's aim less the ghost-ball aim (ccw): how
                                   // the aim allows for the throw
  double margin_m = 0.0;     // the capture radius less the pocket centre's distance from
                             // the ball's line: how far inside the circle it passes
  double aim_margin_deg = 0.0;  // the least aim error, either way, that would miss it
  // A jawed pocket: how far the ball's line clears the nearer point (its rounding grown
  // by the contact offset R cos(theta), as the simulator meets it; < 0: the line meets
  // that point), and which point that is ("left" or "right", seen from the table).
  std::optional<double> jaw_clearance_m;
  std::string near_jaw;

  bool operator==(const PotReport&) const = default;
};

// Position play: the next pot from where a stroke leaves the cue ball, in a player's terms.
struct NextReport {
  std::string ball;          // the next pot's ball (the first of problem.next)
  int pocket = -1;
  std::string pocket_name;
  physics::Vec2 landing;     // where the stroke leaves the cue ball (m)
  double p = 0.0;            // P(next pot) from the landing (PositionField)
  double cut_deg = 0.0;      // the cut it leaves (0: full ball); cut_side as PotReport's
  int cut_side = 0;
  std::string thickness;     // full, 3/4, half, 1/4 or thin
  double distance_m = 0.0;   // cue ball to the next ball
  std::string screened_by;   // a ball in the way, or empty
  double zone_area_m2 = 0.0; // where P(next) is within 10 points of the best
  bool in_zone = false;      // the landing is in it
  double best_p = 0.0;       // the best value on the table, and where
  physics::Vec2 best;
  std::string words;         // "leaves a quarter-ball cut on the black, 40 cm"

  bool operator==(const NextReport&) const = default;
};

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
  Success success;                   // under the noise; all zero samples when not estimated
  double success_probability = 0.0;  // success.both.p: of succeeding under the noise
  Family family_key;                 // the way it plays the shot
  std::string family;                // family_key in words, e.g. "2 cushions (y = 0, x = L), follow, right spin"
  bool solves = false;               // within the tolerance and breaks no constraint
  std::string violations;            // constraints broken, in words; empty when none
  // The first condition of the problem the outcome breaks (problems::check_stroke),
  // with the reason in words; none when it solves the problem.
  problems::Failure failure = problems::Failure::none;
  std::string failure_reason;
  std::optional<PotReport> pot;      // pot problems: the pot of the reported strokes
  std::optional<NextReport> next;    // problems with `next`: what the landing leaves
  // The route in a player's words (problems that name a ball to strike: pots, escapes):
  // "one cushion off the top cushion, right-hand side, to hit the red full; the red
  // doubles off the bottom cushion into the top middle pocket". Set on reported strokes.
  std::string route_words;
  // An escape with `leave: safe`: the chance (0..1) of the easiest direct pot this stroke
  // leaves the opponent from where the cue ball stops (a geometric estimate under the aim
  // noise; kick.hpp, easiest_pot). Empty otherwise.
  std::optional<double> opponent_pot;
  physics::ImpactMethod impact_method = physics::ImpactMethod::exact;  // that gave this outcome
};

struct PlanResult {
  PlanStatus status = PlanStatus::invalid_input;
  std::string message;               // why, in a sentence (always set)
  // invalid_input: the broken rule, its fields named as PlannerOptions' members or, for
  // the problem, as Problem's ({"scene", "length"}, {"cue_ball"}; problems::file_field
  // names them as the file does, and the message does so already).
  std::optional<physics::ValidationError> error;
  PlannedShot best;
  std::vector<PlannedShot> alternatives;  // distinct families, best first
  int evaluations = 0;               // shot simulations made (search and robustness)
  double time_s = 0.0;               // wall clock
  int local_searches = 0;            // local polishes run
  int converged_searches = 0;        // of those, ended by their tolerances or stalled (not cut by a budget)
  // Problems with `next`: the position field the strokes were judged by (for the zone).
  std::shared_ptr<const PositionField> position_field;
  // Kicks, banks and escapes: the route families (by cushions before the contact and,
  // for a pot, the object ball's cushions) with no clear route, each with why: "direct:
  // no direct pot: ...", "one cushion: 12 mirror lines: 12 screened by red2, blue".
  std::vector<std::string> ruled_out;
  int kick_routes = 0;               // clear kick or bank routes the geometry allowed (tried cheapest first)
};

// The next pot from `landing` in a player's terms (a problem with `next`, its field).
NextReport next_report(const problems::Problem& problem, const PositionField& field,
                       physics::Vec2 landing);

// The seed of the reference search (the first half of the global stage) and of the
// noise draws plan() estimates every success on, whatever PlannerOptions::seed:
// plan()'s success of a stroke equals estimate_success(..., kReferenceSeed, ...).
inline constexpr uint64_t kReferenceSeed = 0x636f616368ULL;  // "coach"

PlanResult plan(const problems::Problem& problem, const PlannerOptions& options);

// Fraction of `samples` noisy strokes around `shot` that stop within the problem's
// tolerance of the target (at rest, not pocketed, no obstacle, allowed cushions).
// Deterministic for a seed.
double success_probability(const problems::Problem& problem, const physics::Shot& shot,
                           const NoiseModel& noise, int samples, uint64_t seed,
                           const physics::SimulationOptions& simulation);

// The chance of success of `shot` with its intervals, from `samples` noisy strokes
// (the same draws as success_probability for the same seed: common random numbers).
// Deterministic for a seed.
Success estimate_success(const problems::Problem& problem, const physics::Shot& shot,
                         const NoiseModel& noise, int samples, uint64_t seed,
                         const physics::SimulationOptions& simulation);

// Simulates a stroke on the problem's scene and describes it as a PlannedShot
// (success_probability left at 0).
PlannedShot evaluate(const problems::Problem& problem, const physics::Shot& shot,
                     const physics::SimulationOptions& simulation);

// Problems whose answer is known, for tests and benchmarks: on a snooker table (with
// its pockets, no obstacles) a random cue-ball position and a random stroke within the
// default limits (speed 0.3-3 m/s, any aim, spin within 1.25) that comes to rest after
// 0-3 cushions; the target is where it stops (tolerance 0.02 m) and the cushion limits
// are exactly its count. Deterministic for a seed.
struct KnownShotProblem {
  problems::Problem problem;
  physics::Shot shot;  // a stroke that lands on the target
};
std::vector<KnownShotProblem> known_shot_problems(int count, uint64_t seed,
                                                  const physics::SimulationOptions& simulation);

// Pot problems whose answer is known, for tests and benchmarks: on a snooker table a
// random cue-ball position, one object ball ("red") at a random place, and a random
// stroke within the default limits aimed to strike it (cuts up to about 64 degrees)
// that pots it directly (the red meets no cushion or other ball on its way in) and
// cleanly and leaves the cue ball at rest after 0-3 cushions; the pot is
// the red into the pocket it dropped in, the target where the cue ball stops
// (tolerance 0.02 m), the cushion limits a pot's default [0, 3]. Deterministic for a seed.
std::vector<KnownShotProblem> known_pot_problems(int count, uint64_t seed,
                                                 const physics::SimulationOptions& simulation);

// Problems whose feasible strokes are split into many small islands: a snooker table
// with `obstacles` balls (1-30) at random places (not touching each other, the cushions
// or a pocket), a random cue-ball position and a random stroke within the default
// limits that comes to rest after 0-3 cushions without touching a ball or a pocket;
// the target is where it stops (tolerance 0.02 m), the cushion limits its count. Only
// scenes where at least a quarter of the strokes near the witness (aim within 3 deg,
// speed within 15 %, spin within 0.3) touch a ball or a pocket are kept, so the witness
// lies in a narrow gap. Deterministic for a seed.
std::vector<KnownShotProblem> obstacle_field_problems(int count, int obstacles, uint64_t seed,
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
