// Routes of several strokes: when no single stroke brings the cue ball to rest on the
// target - the lines are blocked by other balls, the target is beyond the speed limit,
// or the only one-stroke answers are fragile - a short sequence of strokes that does.
//
// A kinodynamic planning problem on OMPL's control-based planners (SST, RRT, KPIECE1):
//   state       the cue ball at rest on the table (x, y; the obstacles stay where they are);
//   control     one stroke (speed, aim, k_T, k_S) within the problem's limits;
//   propagator  the shot simulator, one stroke per propagation;
//   validity    at rest on the table, not pocketed, no obstacle contact, at most
//               max_strokes strokes from the start;
//   goal        at rest within 0.9 of the problem's tolerance of the target (the margin
//               absorbs the exact re-simulation below).
// With max_strokes 1 the same search answers a single-stroke problem among many
// obstacles: the tree is then the start and its one-stroke children.
// With the directed sampler each stroke steers from a tree node toward a sampled point
// by running planner::plan (a few hundred evaluations, no robustness samples, no exact
// verification), so the tree grows by real strokes; when steering finds no stroke that
// comes to rest, a random one is played. RRT gets its strokes from a
// DirectedControlSampler aimed at the state it sampled; SST and KPIECE1 (whose OMPL 1.5
// loops ask a plain ControlSampler) steer toward the state SST sampled last, or toward
// a point the sampler draws (route.cpp says how). The random sampler plays uniformly
// random strokes within the limits instead.
//
// Cost, minimised by SST: the number of strokes first, then the summed failure risk
// (1 - success probability under the NoiseModel) of the strokes: a route of n strokes
// costs n + w * sum(risk) with w = 1 / (max_strokes + 1), so that one stroke fewer
// always wins. The risk of a stroke is estimated once, when it is propagated, and kept
// with the state it reaches; a stroke that lands in the target zone is judged against
// that zone, any other against a circle of intermediate_zone_m around its landing.
//
// A route is returned only after every stroke has been simulated again from where the
// previous one stopped, with the exact impact method at accuracy 1e-9: each must come
// to rest on the table without a pocket or an obstacle, and the last in the zone.
//
// Strokes: every stroke keeps the problem's speed, spin and aim limits and meets at most
// limits.cushions_max cushions; the last must also meet at least limits.cushions_min.
//
// No globals, no hidden statics: each call builds its own OMPL objects and seeds every
// random stream OMPL lets it reach (planner, samplers) from options.seed. OMPL's nearest-
// neighbour structures draw from its process-wide seed, which this function does not
// change; runs ended by max_propagations (not by time) repeat exactly in practice.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::planner {

enum class RoutePlanner { sst, rrt, kpiece1 };
enum class RouteSampler { directed, random };
const char* to_string(RoutePlanner planner);
const char* to_string(RouteSampler sampler);
// Parse the names to_string gives ("sst", "rrt", "kpiece1"; "directed", "random").
bool parse_route_planner(const std::string& name, RoutePlanner* planner);
bool parse_route_sampler(const std::string& name, RouteSampler* sampler);

struct RouteOptions {
  RoutePlanner planner = RoutePlanner::sst;
  RouteSampler sampler = RouteSampler::directed;
  int max_strokes = 3;          // strokes a route may take, [1, 100]
  double max_time_s = 5.0;      // wall-clock budget of the tree search (s)
  // Also end the search after this many propagations (strokes simulated by the tree,
  // steering and risk estimates not counted); 0: no limit. Runs ended by it repeat.
  int max_propagations = 0;
  // SST improves its route until the budget ends; with this it stops at the first one.
  // RRT and KPIECE1 always stop at their first route.
  bool stop_at_first_solution = false;
  uint64_t seed = 1;
  int steer_evaluations = 300;  // shot simulations per directed steering (planner::plan)
  double goal_bias = 0.2;       // share of sampled targets drawn from the target zone, [0, 1)
  double intermediate_zone_m = 0.05;  // m, zone an intermediate stroke's success is judged by
  NoiseModel noise;
  int risk_samples = 24;        // noisy strokes per risk estimate while planning; 0: no risk term
  int robustness_samples = 200; // noisy strokes per reported success probability; 0: not estimated
  // Simulation while planning; the returned route is re-simulated exactly (1e-9).
  physics::SimulationOptions simulation = planning_simulation();

  // Empty when usable; otherwise the first broken rule, fields named as these members.
  physics::Validation validate() const;

  static physics::SimulationOptions planning_simulation() {
    physics::SimulationOptions s;
    s.impact_accuracy = 1e-6;  // fast exact impacts; the route is verified at 1e-9
    s.record_path = false;
    return s;
  }
};

enum class RouteStatus {
  solved,            // a route whose every stroke re-simulates valid and ends in the zone
  unreachable,       // proven: no stroke sequence can reach the zone (message says why)
  budget_exhausted,  // no route found (or none survived re-simulation) within the budget
  invalid_input,     // nothing planned; message names the field
};
const char* to_string(RouteStatus status);

// One stroke of a route, as re-simulated with the exact method.
struct RouteStroke {
  physics::Vec2 start;  // m, where the cue ball lies before it
  // shot, outcome, final_position, miss_distance (from the problem's target),
  // cushion_hits, route, within_limits, family, solves (this stroke alone solves the
  // problem), violations; success_probability: of landing within the stroke's zone.
  PlannedShot planned;
  double zone_radius = 0.0;  // m, around zone_centre: the zone its success is judged by
  physics::Vec2 zone_centre;  // m: the target for the last stroke, else its own landing
};

struct RouteResult {
  RouteStatus status = RouteStatus::invalid_input;
  std::string message;  // why, in a sentence (always set)
  // invalid_input: the broken rule, fields named as RouteOptions' or Problem's members.
  std::optional<physics::ValidationError> error;
  std::vector<RouteStroke> strokes;  // solved: the route, first stroke first
  double route_success_probability = 0.0;  // product of the strokes' (solved)
  double time_s = 0.0;                     // wall clock, all stages
  double time_to_first_solution_s = -1.0;  // s into the search; < 0 when none was found
  int tree_states = 0;      // states in the planner's tree when it stopped
  int propagations = 0;     // strokes the tree simulated
  int steerings = 0;        // directed steerings (planner::plan calls)
  int evaluations = 0;      // shot simulations, all stages
};

RouteResult plan_route(const problems::Problem& problem, const RouteOptions& options);

// Proof of unreachability, or empty: a sound, conservative check that the ball's centre
// cannot travel from the cue ball to the target without touching an obstacle ball or
// entering a pocket (a grid over the table in which only cells wholly inside a forbidden
// disc are closed). Used by plan_route before searching.
std::string unreachable_reason(const problems::Problem& problem);

// OMPL reports its progress on stderr through one process-wide log level. A program that
// prints its own report calls this once to keep OMPL to errors; it is the one function
// here that changes process-wide state.
void quiet_ompl_messages();

}  // namespace cueplan::planner
