// Run-outs: a sequence of pots under a game's rules (problems/game.hpp), chosen stroke
// by stroke, and how often the run clears the table under a player's execution noise.
//
// At each stroke the legal (ball, pocket) pots are tried with a few stroke families
// (speeds and draw, stun or follow), the aim of each solved by the pot planner's aim
// root; each stroke is played under the noise a few times, and scored by the mean, over
// those noisy strokes, of the value of where the cue ball stops for the pots that
// follow (a look-ahead of K pots: a beam search over sequences, PositionValue below).
// The `planner` policy plays the stroke of the highest score; `greedy` plays the stroke
// most likely to pot its ball, with no thought of position.
//
// Banks and kicks: when no direct pot is on (none found, or none pots under the noise
// as often as kFallbackBelow), the legal balls are also tried off the cushions
// with the kick planner's routes (kick.hpp: the object ball off one or two cushions into
// its pocket, the cue ball off one or two before it strikes, or both), the cheapest
// kMostRoutes routes over every legal (ball, pocket), each solved on the simulator; in
// nine-ball also combinations (the lowest ball struck first, driven onto another that
// drops). Those strokes are scored the same way (noisy strokes judged by the game,
// the value of where the cue ball stops), and compete with the direct ones.
//
// P(run-out): the policy is played `samples` times from the layout, each noisy stroke
// simulated and the policy re-planned from where the balls stop, until the run clears,
// fouls or misses. Deterministic for a seed and thread count (the thread count does not
// change the answer). No globals: safe to call from many threads.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/problems/game.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::planner {

enum class RunPolicy { planner, greedy };
const char* to_string(RunPolicy policy);
bool parse_run_policy(const std::string& name, RunPolicy* policy);

// POSITION OBJECTIVE: the value of the cue ball at `cue` for the pot(s) to come, in
// [0, 1], with `balls` on the table and the run at `state` (1 when the run is complete).
// The run-out planner takes any such function; position_estimate() is its own, on the
// position-play field (P(next pot) from a cue-ball position, position.hpp). It is called
// from many threads at once.
using PositionValue = std::function<double(physics::Vec2 cue, const problems::GameState& state,
                                           const std::vector<physics::ObjectBall>& balls)>;

// The chance that a player with `noise` pots `ball` into `pocket` from `cue`, with
// `balls` on the table: the position field's P(next pot) (PositionField::pot_chance;
// docs/position.md): 0 when the cut is beyond kMostCut or a ball screens the cue ball's
// path to the ghost ball or the ball's path to the pocket, or without that ball or pocket.
double pot_chance_estimate(const physics::Scene& scene, physics::Vec2 cue, const std::string& ball,
                           int pocket, const std::vector<physics::ObjectBall>& balls,
                           const NoiseModel& noise);

// The POSITION OBJECTIVE with a look-ahead of `lookahead` pots (>= 1): the best product
// over legal sequences of the pots' chances (pot_chance_estimate, from position fields
// built without their grid and kept per layout of the balls while the function lives),
// the first pot from `cue`, each later one from the better of a few places the cue ball
// could be sent to from the previous ball (its ghost ball, drawn back, followed through,
// or rolled either side), kept to the `beam` best partial sequences at each depth.
PositionValue position_estimate(const physics::Scene& scene, const NoiseModel& noise, int lookahead,
                                int beam = 4);

// When no direct stroke pots at least this often under the noise (none of its dozen
// noisy strokes, with the default pot_samples), banks, kicks and combinations are tried
// too; the routes tried at most, cheapest first. A higher bar (0.15) let a route whose
// dozen noisy strokes happened to pot more often replace a direct pot that was in fact
// better (bench/README.md "Run-outs": snooker layout 9 fell from 0.45 to 0.05 balls).
inline constexpr double kFallbackBelow = 0.05;
inline constexpr int kMostRoutes = 8;

struct RunoutOptions {
  RunPolicy policy = RunPolicy::planner;
  int lookahead = 2;        // pots scored beyond the one played (>= 1)
  int samples = 100;        // rollouts for P(run-out) (0: only the plan)
  int pot_samples = 12;     // noisy strokes per candidate stroke while choosing
  int max_shots = 40;       // a run that has not ended after this many strokes ends
  int report_samples = 100;  // noisy strokes per P(pot) of the plan's shots (RunShot::pot)
  uint64_t seed = 1;
  int threads = 0;          // 0: one per core
  NoiseModel noise;
  physics::SimulationOptions simulation;
  // POSITION OBJECTIVE: empty for position_estimate(scene, noise, lookahead).
  PositionValue position;
  // Called on the calling thread with the rollouts finished so far (may be empty).
  std::function<void(int done, int total)> progress;
};

// One stroke of a run.
struct RunShot {
  std::string ball;
  int pocket = -1;
  std::string pocket_name;
  physics::Shot shot;
  physics::Vec2 cue_from;      // where the cue ball lay
  physics::Vec2 cue_to;        // where the stroke (without noise) leaves it
  std::vector<physics::PathSegment> path;  // the cue ball's path, without noise
  double p_pot = 0.0;          // P(pot and stay at the table) under the noise, while choosing
  int p_samples = 0;
  Estimate pot;                // the plan's shots: P(pot and stay at the table) from
                               // report_samples noisy strokes, judged by the game
  double score = 0.0;          // the policy's score: mean position value (planner) or p_pot
  std::string next_ball;       // the ball the position value aims at next (empty at the end)
  // The route, from the stroke played without noise: "direct", "one-cushion bank",
  // "one-cushion kick", "one-cushion kick and one-cushion bank", "combination off the 1", ...
  std::string route = "direct";
  // The route in a player's words (kick.hpp route_words): "one cushion off the top
  // cushion, to hit the 1 half ball; the 1 into the bottom middle pocket".
  std::string route_words;
  std::string verdict;         // without noise: "potted", or why the run ends
  int points = 0;
};

// The run played without noise from the layout: the plan a player would follow.
struct RunPlan {
  std::vector<RunShot> shots;
  bool cleared = false;
  int potted = 0;
  int score = 0;         // snooker: the break
  std::string ended;     // why the run stopped short (empty when cleared)
};

struct RunDeath {
  int shot = 0;          // the stroke (from 1) the run died on
  std::string reason;    // "missed the pot", "foul: cue ball potted", "no pot on", ...
  int count = 0;
};

struct RunoutResult {
  RunPlan plan;
  Estimate runout;             // clearances of the rollouts, Wilson interval
  double mean_potted = 0.0;
  double mean_score = 0.0;     // snooker: the mean break
  std::vector<RunDeath> deaths;  // most frequent first
  double decision_time_s = 0.0;  // the plan's first decision (wall clock)
  double time_s = 0.0;
};

// The stroke the policy plays from (state, balls, cue); none when no legal pot is found.
std::optional<RunShot> choose_stroke(const problems::Problem& layout, const problems::GameState& state,
                                     const std::vector<physics::ObjectBall>& balls, physics::Vec2 cue,
                                     const RunoutOptions& options, uint64_t seed, int threads);

// The plan and, with samples > 0, P(run-out). `layout` is a checked problem whose balls
// and cue ball are the layout (its pot and target unused).
RunoutResult plan_runout(const problems::Problem& layout, const problems::GameState& start,
                         const RunoutOptions& options);

}  // namespace cueplan::planner
