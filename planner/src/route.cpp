// plan_route(): multi-stroke routes on OMPL's control-based planners.
//
// Stages, in order:
//   1. check    - options, then a proof of unreachability (route_reach.cpp) if there is one;
//   2. setup    - the OMPL problem: the table state space, the stroke control space, the
//                 simulator as propagator, validity, the target-zone goal, the cost;
//   3. search   - SST, RRT or KPIECE1 until the time or propagation budget ends;
//   4. verify   - each stroke of the route re-simulated with the exact method from where
//                 the previous one stopped; the route stands only if every one holds;
//   5. report   - success probabilities, status and a sentence.
//
// The control is a stroke with an optional steering intent: (speed, aim, k_T, k_S,
// steer_x, steer_y, steer_seed). With steer_seed >= 0 the propagator first steers - it
// runs planner::plan from the state toward (steer_x, steer_y) with that seed - and plays
// the stroke found, or the stored stroke when steering finds none that comes to rest;
// with steer_seed < 0 it plays the stored stroke. The propagation stays a pure function
// of (state, control), so the strokes of a returned path are recovered exactly. This
// lets every planner use the directed sampler: RRT through a DirectedControlSampler
// (steering to the state it sampled), SST (whose OMPL 1.5 loop asks its control sampler
// for a control without a target) through the state its state sampler drew last, and
// KPIECE1 toward a point drawn by the control sampler itself.
#include <ompl/base/Goal.h>
#include <ompl/base/OptimizationObjective.h>
#include <ompl/base/PlannerData.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProjectionEvaluator.h>
#include <ompl/base/StateSampler.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/control/ControlSampler.h>
#include <ompl/control/DirectedControlSampler.h>
#include <ompl/control/PathControl.h>
#include <ompl/control/SimpleSetup.h>
#include <ompl/control/StatePropagator.h>
#include <ompl/control/planners/kpiece/KPIECE1.h>
#include <ompl/control/planners/rrt/RRT.h>
#include <ompl/control/planners/sst/SST.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <ompl/util/Console.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "cueplan/planner/route.hpp"
#include "task.hpp"

namespace cueplan::planner {
namespace {

namespace ob = ompl::base;
namespace oc = ompl::control;
using Clock = std::chrono::steady_clock;

constexpr double kPi = 3.14159265358979323846;
constexpr double kExactAccuracy = 1e-9;   // verification, as planner::plan verifies
constexpr double kSteerTolerance = 0.02;  // m, zone of a steering sub-problem
constexpr double kGoalShrink = 0.9;       // planning goal radius / tolerance: room for re-simulation
constexpr int kSteerStarts = 2;           // local polishes per steering
constexpr double kSteerTimeS = 10.0;      // never reached: the evaluation budget ends a steering
constexpr double kSelectionRadius = 0.2;  // m, SST's best-cost neighbourhood
constexpr double kPruningRadius = 0.1;    // m, SST's witness radius
constexpr double kCellSize = 0.1;         // m, KPIECE1's projection grid
// Streams derived from the seed (splitmix64 of seed + stream).
constexpr uint64_t kPlannerStream = 1, kRiskStream = 2, kSuccessStream = 3, kSamplerStream = 16;

// State: x, y (m), the risk of the stroke that reached it, its cushion count, strokes
// from the start. Distances are over x, y and the stroke count, one table diagonal per
// stroke, so the tree is layered by depth: a sampled target carries a depth below
// max_strokes and is steered to from the nearest node of that depth, never from a node
// with no stroke left while one with a stroke left exists. An invalid outcome has
// x = kOffTable.
enum : unsigned { kX = 0, kY = 1, kRisk = 2, kCushions = 3, kStrokes = 4, kStateDims = 5 };
constexpr double kOffTable = -1.0;
// Control: the stroke, then the steering intent.
enum : unsigned {
  kSpeed = 0, kAim = 1, kTopspin = 2, kSidespin = 3, kSteerX = 4, kSteerY = 5, kSteerSeed = 6,
  kControlDims = 7
};
constexpr double kMostSeed = 2147483647.0;

uint64_t mix(uint64_t seed, uint64_t stream) {
  uint64_t z = seed + 0x9E3779B97F4A7C15ull * (stream + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
std::uint_fast32_t seed32(uint64_t seed, uint64_t stream) {
  const auto s = static_cast<std::uint_fast32_t>(mix(seed, stream) & 0x7FFFFFFFu);
  return s == 0 ? 1 : s;  // OMPL refuses 0
}

double* values(ob::State* s) { return s->as<ob::RealVectorStateSpace::StateType>()->values; }
const double* values(const ob::State* s) {
  return s->as<ob::RealVectorStateSpace::StateType>()->values;
}
double* values(oc::Control* c) { return c->as<oc::RealVectorControlSpace::ControlType>()->values; }
const double* values(const oc::Control* c) {
  return c->as<oc::RealVectorControlSpace::ControlType>()->values;
}

// Everything the OMPL callbacks share for one plan_route call, with its counters.
struct Context {
  const problems::Problem* problem = nullptr;
  const detail::Task* task = nullptr;  // the problem, checked, with its scene compiled
  const RouteOptions* options = nullptr;
  double goal_radius = 0.0;  // m, planning goal
  double risk_weight = 0.0;  // w in n + w * sum(risk)
  // The state the planner's state sampler (or goal) drew last, for SST's control sampler.
  bool hint_fresh = false;
  physics::Vec2 hint;
  uint64_t next_stream = kSamplerStream;  // a stream for each sampler OMPL allocates
  // Counters.
  int propagations = 0;
  int steerings = 0;
  int evaluations = 0;
  double first_solution_s = -1.0;
  Clock::time_point search_start;
};

// ---------------------------------------------------------------------------
// Strokes from controls.

physics::Shot stored_stroke(const double* u, const problems::Limits& limits) {
  physics::Shot s{u[kSpeed], u[kAim], u[kTopspin], u[kSidespin]};
  const double spin = std::hypot(s.topspin_k, s.sidespin_k);
  if (spin > limits.spin_max) {  // keep within the miscue disc
    s.topspin_k *= limits.spin_max / spin;
    s.sidespin_k *= limits.spin_max / spin;
  }
  s.speed = std::clamp(s.speed, limits.speed_min, limits.speed_max);
  return s;
}

// planner::plan from `from` toward `to`: the best stroke that comes to rest, if any.
bool steer(const problems::Problem& problem, const RouteOptions& options, physics::Vec2 from,
           physics::Vec2 to, uint64_t seed, physics::Shot* shot, int* evaluations) {
  problems::Problem sub = problem;
  sub.cue_ball = from;
  sub.target = to;
  sub.tolerance = kSteerTolerance;
  sub.limits.cushions_min = 0;
  PlannerOptions o;
  o.max_evaluations = options.steer_evaluations;
  o.max_time_s = kSteerTimeS;
  o.local_starts = kSteerStarts;
  o.seed = seed;
  o.threads = 1;
  o.robustness_samples = 0;
  o.max_alternatives = 0;
  o.stop_at_first_solution = true;
  o.verify_exact = false;
  o.simulation = options.simulation;
  o.simulation.record_path = false;
  const PlanResult r = plan(sub, o);
  *evaluations += r.evaluations;
  if (r.status == PlanStatus::invalid_input || r.best.outcome != physics::ShotStatus::rest)
    return false;
  *shot = r.best.shot;
  return true;
}

// The stroke a control plays from `from`: steered when it says so, else the stored one.
// A steering target inside the goal stands for the goal: the stroke aims at its centre.
physics::Shot resolve(Context& ctx, physics::Vec2 from, const double* u) {
  if (u[kSteerSeed] >= 0.0) {
    ++ctx.steerings;
    const problems::Problem& p = *ctx.problem;
    physics::Vec2 to{u[kSteerX], u[kSteerY]};
    if (std::hypot(to.x - p.target.x, to.y - p.target.y) <= ctx.goal_radius) to = p.target;
    physics::Shot s;
    if (steer(p, *ctx.options, from, to, static_cast<uint64_t>(u[kSteerSeed]), &s,
              &ctx.evaluations))
      return s;
  }
  return stored_stroke(u, ctx.problem->limits);
}

// The zone a stroke from `from` that lands at `landing` is judged by, as a problem.
problems::Problem zone_problem(const problems::Problem& problem, const RouteOptions& options,
                               physics::Vec2 from, physics::Vec2 landing, bool final_stroke) {
  problems::Problem z = problem;
  z.cue_ball = from;
  if (!final_stroke) {
    z.target = landing;
    z.tolerance = options.intermediate_zone_m;
    z.limits.cushions_min = 0;
  }
  return z;
}

bool in_goal(const Context& ctx, physics::Vec2 p, int cushions, double radius) {
  const problems::Problem& pr = *ctx.problem;
  return std::hypot(p.x - pr.target.x, p.y - pr.target.y) <= radius &&
         cushions >= pr.limits.cushions_min;
}

// ---------------------------------------------------------------------------
// OMPL pieces.

// x and y on the table and the depth in strokes; a metric in metres over the three.
class TableSpace : public ob::RealVectorStateSpace {
 public:
  TableSpace(const physics::Scene& scene, int max_strokes, int cushions_max)
      : ob::RealVectorStateSpace(kStateDims),
        layer_(std::hypot(scene.length, scene.width)),
        extent_(layer_ * (max_strokes + 2)) {
    ob::RealVectorBounds b(kStateDims);
    b.setLow(kX, 0.0);
    b.setHigh(kX, scene.length);
    b.setLow(kY, 0.0);
    b.setHigh(kY, scene.width);
    b.setLow(kRisk, 0.0);
    b.setHigh(kRisk, 1.0);
    b.setLow(kCushions, 0.0);
    b.setHigh(kCushions, std::max(1, cushions_max));
    b.setLow(kStrokes, 0.0);
    b.setHigh(kStrokes, max_strokes + 1);
    setBounds(b);
    setName("table");
  }
  double distance(const ob::State* a, const ob::State* b) const override {
    const double* p = values(a);
    const double* q = values(b);
    return std::hypot(p[kX] - q[kX], p[kY] - q[kY]) +
           layer_ * std::abs(p[kStrokes] - q[kStrokes]);
  }
  double getMaximumExtent() const override { return extent_; }
  void registerProjections() override;

 private:
  double layer_;   // m per stroke of depth
  double extent_;
};

// KPIECE1's grid: the ball's x and y.
class TableProjection : public ob::ProjectionEvaluator {
 public:
  explicit TableProjection(const ob::StateSpace* space) : ob::ProjectionEvaluator(space) {}
  unsigned int getDimension() const override { return 2; }
  void defaultCellSizes() override { cellSizes_ = {kCellSize, kCellSize}; }
  void project(const ob::State* state, Eigen::Ref<Eigen::VectorXd> projection) const override {
    projection(0) = values(state)[kX];
    projection(1) = values(state)[kY];
  }
};

void TableSpace::registerProjections() {
  registerDefaultProjection(std::make_shared<TableProjection>(this));
}

// Uniform on the cloth between the cushions; remembers what it drew (Context::hint).
class TableSampler : public ob::StateSampler {
 public:
  TableSampler(const ob::StateSpace* space, Context* ctx)
      : ob::StateSampler(space), ctx_(ctx) {
    rng_.setLocalSeed(seed32(ctx->options->seed, ctx->next_stream++));
  }
  void sampleUniform(ob::State* state) override {
    const physics::Scene& s = ctx_->problem->scene;
    const double off = s.contact_offset();
    set(state, {rng_.uniformReal(off, s.length - off), rng_.uniformReal(off, s.width - off)});
  }
  void sampleUniformNear(ob::State* state, const ob::State* near, double distance) override {
    const double* n = values(near);
    set(state, clamp({n[kX] + rng_.uniformReal(-distance, distance),
                      n[kY] + rng_.uniformReal(-distance, distance)}));
  }
  void sampleGaussian(ob::State* state, const ob::State* mean, double stdDev) override {
    const double* m = values(mean);
    set(state, clamp({rng_.gaussian(m[kX], stdDev), rng_.gaussian(m[kY], stdDev)}));
  }

 private:
  physics::Vec2 clamp(physics::Vec2 p) const {
    const physics::Scene& s = ctx_->problem->scene;
    const double off = s.contact_offset();
    return {std::clamp(p.x, off, s.length - off), std::clamp(p.y, off, s.width - off)};
  }
  // A point with a depth from which a stroke is still allowed.
  void set(ob::State* state, physics::Vec2 p) {
    double* v = values(state);
    v[kX] = p.x;
    v[kY] = p.y;
    v[kRisk] = 0.0;
    v[kCushions] = 0.0;
    v[kStrokes] = rng_.uniformInt(0, ctx_->options->max_strokes - 1);
    ctx_->hint = p;
    ctx_->hint_fresh = true;
  }
  Context* ctx_;
};

// A stroke within the limits, uniformly: speed, aim, and spin over the miscue disc.
void random_stroke(ompl::RNG& rng, const problems::Limits& l, double* u) {
  u[kSpeed] = rng.uniformReal(l.speed_min, l.speed_max);
  switch (l.aim.mode) {
    case problems::AimMode::free: u[kAim] = rng.uniformReal(-180.0, 180.0); break;
    case problems::AimMode::fixed: u[kAim] = l.aim.lo_deg; break;
    case problems::AimMode::range: u[kAim] = rng.uniformReal(l.aim.lo_deg, l.aim.hi_deg); break;
  }
  const double r = l.spin_max * std::sqrt(rng.uniform01());
  const double theta = rng.uniformReal(-kPi, kPi);
  u[kTopspin] = r * std::cos(theta);
  u[kSidespin] = r * std::sin(theta);
}

// A point to steer to: in the planning goal with probability goal_bias, else on the cloth.
physics::Vec2 random_target(ompl::RNG& rng, const Context& ctx) {
  const problems::Problem& p = *ctx.problem;
  if (rng.uniform01() < ctx.options->goal_bias) {
    const double r = ctx.goal_radius * std::sqrt(rng.uniform01());
    const double theta = rng.uniformReal(-kPi, kPi);
    return {p.target.x + r * std::cos(theta), p.target.y + r * std::sin(theta)};
  }
  const double off = p.scene.contact_offset();
  return {rng.uniformReal(off, p.scene.length - off), rng.uniformReal(off, p.scene.width - off)};
}

// The control sampler: a random stroke, and with the directed sampler a steering intent
// toward the planner's last sampled state (SST) or a point of its own (KPIECE1, or when
// no fresh sample is there).
class StrokeSampler : public oc::ControlSampler {
 public:
  StrokeSampler(const oc::ControlSpace* space, Context* ctx) : oc::ControlSampler(space), ctx_(ctx) {
    rng_.setLocalSeed(seed32(ctx->options->seed, ctx->next_stream++));
  }
  void sample(oc::Control* control) override { fill(control, true); }
  void sample(oc::Control* control, const ob::State*) override { fill(control, false); }
  void sampleNext(oc::Control* control, const oc::Control*) override { fill(control, false); }
  void sampleNext(oc::Control* control, const oc::Control*, const ob::State*) override {
    fill(control, false);
  }
  // With `target` given, steer to it.
  void fill_toward(oc::Control* control, physics::Vec2 target) {
    double* u = values(control);
    random_stroke(rng_, ctx_->problem->limits, u);
    u[kSteerX] = target.x;
    u[kSteerY] = target.y;
    u[kSteerSeed] = static_cast<double>(rng_.uniformInt(0, static_cast<int>(kMostSeed)));
  }

 private:
  void fill(oc::Control* control, bool may_use_hint) {
    double* u = values(control);
    if (ctx_->options->sampler == RouteSampler::random) {
      random_stroke(rng_, ctx_->problem->limits, u);
      u[kSteerX] = u[kSteerY] = 0.0;
      u[kSteerSeed] = -1.0;
      return;
    }
    const bool hint = may_use_hint && ctx_->hint_fresh;
    ctx_->hint_fresh = false;
    fill_toward(control, hint ? ctx_->hint : random_target(rng_, *ctx_));
  }
  Context* ctx_;
};

// RRT's directed sampler: steer to the state it sampled, then propagate.
class SteeringSampler : public oc::DirectedControlSampler {
 public:
  SteeringSampler(const oc::SpaceInformation* si, Context* ctx)
      : oc::DirectedControlSampler(si), strokes_(si->getControlSpace().get(), ctx) {}
  unsigned int sampleTo(oc::Control* control, const ob::State* source, ob::State* dest) override {
    strokes_.fill_toward(control, {values(dest)[kX], values(dest)[kY]});
    return si_->propagateWhileValid(source, control, 1, dest);
  }
  unsigned int sampleTo(oc::Control* control, const oc::Control*, const ob::State* source,
                        ob::State* dest) override {
    return sampleTo(control, source, dest);
  }

 private:
  StrokeSampler strokes_;
};

// One stroke per propagation: the shot simulator from the source state.
class StrokePropagator : public oc::StatePropagator {
 public:
  StrokePropagator(const oc::SpaceInformationPtr& si, Context* ctx)
      : oc::StatePropagator(si), ctx_(ctx) {}
  void propagate(const ob::State* state, const oc::Control* control, double,
                 ob::State* result) const override {
    Context& ctx = *ctx_;
    const problems::Problem& p = *ctx.problem;
    const RouteOptions& o = *ctx.options;
    ++ctx.propagations;
    const double* in = values(state);
    double* out = values(result);
    const physics::Vec2 from{in[kX], in[kY]};
    const double strokes = in[kStrokes] + 1.0;
    const physics::Shot shot = resolve(ctx, from, values(control));
    const physics::ShotResult r = ctx.task->simulate_from(from, shot, o.simulation);
    ++ctx.evaluations;
    out[kStrokes] = strokes;
    out[kCushions] = r.cushion_hits;
    out[kRisk] = 1.0;
    if (r.status != physics::ShotStatus::rest || r.cushion_hits > p.limits.cushions_max) {
      out[kX] = out[kY] = kOffTable;  // invalid: pocketed, obstacle, failed, too many cushions
      return;
    }
    out[kX] = r.final_position.x;
    out[kY] = r.final_position.y;
    if (o.risk_samples == 0) {
      out[kRisk] = 0.0;
      return;
    }
    const bool final_stroke = in_goal(ctx, r.final_position, r.cushion_hits, ctx.goal_radius);
    const problems::Problem zone = zone_problem(p, o, from, r.final_position, final_stroke);
    out[kRisk] = 1.0 - success_probability(zone, shot, o.noise, o.risk_samples,
                                           mix(o.seed, kRiskStream), o.simulation);
    ctx.evaluations += o.risk_samples;
  }
  bool canPropagateBackward() const override { return false; }

 private:
  Context* ctx_;
};

// At rest within the planning goal radius of the target after at least one stroke.
class TargetZone : public ob::GoalSampleableRegion {
 public:
  TargetZone(const ob::SpaceInformationPtr& si, Context* ctx)
      : ob::GoalSampleableRegion(si), ctx_(ctx) {
    rng_.setLocalSeed(seed32(ctx->options->seed, ctx->next_stream++));
  }
  double distanceGoal(const ob::State* st) const override {
    const double* v = values(st);
    const problems::Problem& p = *ctx_->problem;
    const double d = std::hypot(v[kX] - p.target.x, v[kY] - p.target.y);
    const double short_of_cushions = v[kCushions] < p.limits.cushions_min ? 1.0 : 0.0;
    const double no_stroke = v[kStrokes] < 1.0 ? 1.0 : 0.0;
    return std::max(0.0, d - ctx_->goal_radius) + short_of_cushions + no_stroke;
  }
  bool isSatisfied(const ob::State* st, double* distance) const override {
    const double d = distanceGoal(st);
    if (distance != nullptr) *distance = d;
    const bool yes = d <= 0.0;
    if (yes && ctx_->first_solution_s < 0.0)
      ctx_->first_solution_s =
          std::chrono::duration<double>(Clock::now() - ctx_->search_start).count();
    return yes;
  }
  void sampleGoal(ob::State* st) const override {
    const problems::Problem& p = *ctx_->problem;
    const double r = ctx_->goal_radius * std::sqrt(rng_.uniform01());
    const double theta = rng_.uniformReal(-kPi, kPi);
    double* v = values(st);
    v[kX] = p.target.x + r * std::cos(theta);
    v[kY] = p.target.y + r * std::sin(theta);
    v[kRisk] = 0.0;
    v[kCushions] = p.limits.cushions_min;
    v[kStrokes] = rng_.uniformInt(0, ctx_->options->max_strokes - 1);  // the depth to steer from
    ctx_->hint = {v[kX], v[kY]};
    ctx_->hint_fresh = true;
  }
  unsigned int maxSampleCount() const override { return std::numeric_limits<unsigned>::max(); }

 private:
  Context* ctx_;
  mutable ompl::RNG rng_;
};

// n strokes + w * summed risk; w < 1 / max_strokes keeps one stroke fewer always better.
class StrokesThenRisk : public ob::OptimizationObjective {
 public:
  StrokesThenRisk(const ob::SpaceInformationPtr& si, double risk_weight, bool any_route_will_do)
      : ob::OptimizationObjective(si), w_(risk_weight) {
    description_ = "strokes, then summed failure risk";
    // SST stops at a route whose cost beats the threshold.
    setCostThreshold(any_route_will_do ? infiniteCost() : ob::Cost(0.0));
  }
  ob::Cost stateCost(const ob::State*) const override { return identityCost(); }
  ob::Cost motionCost(const ob::State*, const ob::State* s2) const override {
    return ob::Cost(1.0 + w_ * values(s2)[kRisk]);
  }

 private:
  double w_;
};

template <class Planner>
class Seeded : public Planner {
 public:
  Seeded(const oc::SpaceInformationPtr& si, std::uint_fast32_t seed) : Planner(si) {
    this->rng_.setLocalSeed(seed);
  }
};

// SST, seeded, and without the leak of OMPL 1.5's: its freeMemory() deletes the witness
// motions but not the state and control each one allocated, so they are freed here
// first (and set to null, so that an OMPL that frees them itself frees nothing twice).
class SeededSst : public Seeded<oc::SST> {
 public:
  using Seeded<oc::SST>::Seeded;
  ~SeededSst() override { free_witness_memory(); }
  void clear() override {
    free_witness_memory();
    oc::SST::clear();
  }

 private:
  void free_witness_memory() {
    if (!witnesses_) return;
    std::vector<Motion*> witnesses;
    witnesses_->list(witnesses);
    for (Motion* w : witnesses) {
      if (w->state_ != nullptr) si_->freeState(w->state_);
      if (w->control_ != nullptr) siC_->freeControl(w->control_);
      w->state_ = nullptr;
      w->control_ = nullptr;
    }
  }
};

// ---------------------------------------------------------------------------
// Verification of a found path, stroke by stroke.

struct Verified {
  bool ok = false;
  std::string why;  // when not ok
  std::vector<RouteStroke> strokes;
};

Verified verify(Context& ctx, const std::vector<physics::Shot>& shots) {
  const problems::Problem& p = *ctx.problem;
  const RouteOptions& o = *ctx.options;
  physics::SimulationOptions exact;
  exact.impact_method = physics::ImpactMethod::exact;
  exact.impact_accuracy = kExactAccuracy;
  exact.max_events = o.simulation.max_events;
  exact.record_path = false;

  Verified v;
  physics::Vec2 at = p.cue_ball;
  for (size_t i = 0; i < shots.size(); ++i) {
    const bool last = i + 1 == shots.size();
    problems::Problem from_here = p;
    from_here.cue_ball = at;
    RouteStroke s;
    s.start = at;
    s.planned = evaluate(from_here, shots[i], exact);
    ++ctx.evaluations;
    const PlannedShot& e = s.planned;
    const std::string n = "stroke " + std::to_string(i + 1);
    if (e.outcome != physics::ShotStatus::rest) {
      v.why = n + " ends " + physics::to_string(e.outcome) + " when simulated exactly";
      return v;
    }
    if (const std::string l = problems::check_shot(p.limits, e.shot); !l.empty()) {
      v.why = n + " breaks a limit: " + l;
      return v;
    }
    if (e.cushion_hits > p.limits.cushions_max) {
      v.why = n + " meets " + std::to_string(e.cushion_hits) + " cushions, more than allowed";
      return v;
    }
    if (last && !(e.miss_distance <= p.tolerance && e.cushion_hits >= p.limits.cushions_min)) {
      v.why = n + fmt::format(" stops {:.1f} mm from the target when simulated exactly", 1e3 * e.miss_distance);
      return v;
    }
    s.zone_centre = last ? p.target : e.final_position;
    s.zone_radius = last ? p.tolerance : o.intermediate_zone_m;
    if (o.robustness_samples > 0) {
      const problems::Problem zone = zone_problem(p, o, at, e.final_position, last);
      s.planned.success = estimate_success(zone, e.shot, o.noise, o.robustness_samples,
                                           mix(o.seed, kSuccessStream), exact);
      s.planned.success_probability = s.planned.success.both.p;
      ctx.evaluations += o.robustness_samples;
    }
    at = e.final_position;
    v.strokes.push_back(std::move(s));
  }
  v.ok = true;
  return v;
}

RouteResult finish(RouteResult r, const Context& ctx, Clock::time_point start) {
  r.time_s = std::chrono::duration<double>(Clock::now() - start).count();
  r.propagations = ctx.propagations;
  r.steerings = ctx.steerings;
  r.evaluations = ctx.evaluations;
  r.time_to_first_solution_s = ctx.first_solution_s;
  return r;
}

}  // namespace

const char* to_string(RoutePlanner planner) {
  switch (planner) {
    case RoutePlanner::sst: return "sst";
    case RoutePlanner::rrt: return "rrt";
    case RoutePlanner::kpiece1: return "kpiece1";
  }
  return "?";
}

const char* to_string(RouteSampler sampler) {
  return sampler == RouteSampler::directed ? "directed" : "random";
}

const char* to_string(RouteStatus status) {
  switch (status) {
    case RouteStatus::solved: return "solved";
    case RouteStatus::unreachable: return "unreachable";
    case RouteStatus::budget_exhausted: return "budget_exhausted";
    case RouteStatus::invalid_input: return "invalid_input";
  }
  return "?";
}

bool parse_route_planner(const std::string& name, RoutePlanner* planner) {
  for (RoutePlanner p : {RoutePlanner::sst, RoutePlanner::rrt, RoutePlanner::kpiece1})
    if (name == to_string(p)) {
      *planner = p;
      return true;
    }
  return false;
}

bool parse_route_sampler(const std::string& name, RouteSampler* sampler) {
  for (RouteSampler s : {RouteSampler::directed, RouteSampler::random})
    if (name == to_string(s)) {
      *sampler = s;
      return true;
    }
  return false;
}

physics::Validation RouteOptions::validate() const {
  using physics::invalid;
  const auto bad = [](const char* field, const char* rule, double value) {
    return invalid({field}, rule, value);
  };
  if (planner != RoutePlanner::sst && planner != RoutePlanner::rrt &&
      planner != RoutePlanner::kpiece1)
    return bad("planner", "must be sst, rrt or kpiece1", static_cast<int>(planner));
  if (sampler != RouteSampler::directed && sampler != RouteSampler::random)
    return bad("sampler", "must be directed or random", static_cast<int>(sampler));
  if (max_strokes < 1 || max_strokes > problems::kMostStrokes)
    return bad("max_strokes", "must lie in [1, 100]", max_strokes);
  if (!std::isfinite(max_time_s) || !(max_time_s > 0.0))
    return bad("max_time_s", "must be positive and finite (s)", max_time_s);
  if (max_propagations < 0) return bad("max_propagations", "must not be negative", max_propagations);
  if (steer_evaluations < 10) return bad("steer_evaluations", "must be at least 10", steer_evaluations);
  if (!(goal_bias >= 0.0 && goal_bias < 1.0)) return bad("goal_bias", "must lie in [0, 1)", goal_bias);
  if (!std::isfinite(intermediate_zone_m) || !(intermediate_zone_m > 0.0))
    return bad("intermediate_zone_m", "must be positive and finite (m)", intermediate_zone_m);
  if (physics::Validation e = noise.validate()) return e->under({"noise"});
  if (risk_samples < 0) return bad("risk_samples", "must not be negative", risk_samples);
  if (robustness_samples < 0)
    return bad("robustness_samples", "must not be negative", robustness_samples);
  if (simulation.max_events < 1)
    return invalid({"simulation", "max_events"}, "must be at least 1", simulation.max_events);
  if (!std::isfinite(simulation.impact_accuracy) || !(simulation.impact_accuracy > 0.0))
    return invalid({"simulation", "impact_accuracy"}, "must be positive and finite",
                   simulation.impact_accuracy);
  if (simulation.impact_method == physics::ImpactMethod::table && simulation.table == nullptr)
    return invalid({"simulation", "table"}, "must be given for the table impact method");
  return {};
}

void quiet_ompl_messages() { ompl::msg::setLogLevel(ompl::msg::LOG_ERROR); }

namespace {

// Stage 2: the OMPL problem - the table state space, the stroke control space, the
// simulator as propagator, validity, the target-zone goal, the cost and the planner.
std::unique_ptr<oc::SimpleSetup> make_setup(Context& ctx) {
  const problems::Problem& problem = *ctx.problem;
  const RouteOptions& options = *ctx.options;
  auto space = std::make_shared<TableSpace>(problem.scene, options.max_strokes,
                                            problem.limits.cushions_max);
  space->setStateSamplerAllocator(
      [&ctx](const ob::StateSpace* s) { return std::make_shared<TableSampler>(s, &ctx); });
  auto controls = std::make_shared<oc::RealVectorControlSpace>(space, kControlDims);
  {
    const problems::Limits& l = problem.limits;
    ob::RealVectorBounds b(kControlDims);
    b.setLow(kSpeed, l.speed_min);
    b.setHigh(kSpeed, l.speed_max);
    b.setLow(kAim, l.aim.mode == problems::AimMode::free ? -180.0 : l.aim.lo_deg);
    b.setHigh(kAim, l.aim.mode == problems::AimMode::free ? 180.0 : l.aim.hi_deg);
    b.setLow(kTopspin, -l.spin_max);
    b.setHigh(kTopspin, l.spin_max);
    b.setLow(kSidespin, -l.spin_max);
    b.setHigh(kSidespin, l.spin_max);
    b.setLow(kSteerX, 0.0);
    b.setHigh(kSteerX, problem.scene.length);
    b.setLow(kSteerY, 0.0);
    b.setHigh(kSteerY, problem.scene.width);
    b.setLow(kSteerSeed, -1.0);
    b.setHigh(kSteerSeed, kMostSeed);
    controls->setBounds(b);
  }
  controls->setControlSamplerAllocator(
      [&ctx](const oc::ControlSpace* c) { return std::make_shared<StrokeSampler>(c, &ctx); });

  auto setup = std::make_unique<oc::SimpleSetup>(controls);
  const oc::SpaceInformationPtr& si = setup->getSpaceInformation();
  si->setMinMaxControlDuration(1, 1);
  si->setPropagationStepSize(1.0);
  if (options.sampler == RouteSampler::directed)
    si->setDirectedControlSamplerAllocator([&ctx](const oc::SpaceInformation* s) {
      return std::make_shared<SteeringSampler>(s, &ctx);
    });
  setup->setStatePropagator(std::make_shared<StrokePropagator>(si, &ctx));
  setup->setStateValidityChecker([&problem, &options](const ob::State* s) {
    const double* v = values(s);
    if (!(v[kStrokes] <= options.max_strokes) || v[kX] == kOffTable) return false;
    return !problem.scene.check_position({v[kX], v[kY]}, {"ball"});
  });
  ob::ScopedState<> first(space);
  first[kX] = problem.cue_ball.x;
  first[kY] = problem.cue_ball.y;
  first[kRisk] = 0.0;
  first[kCushions] = 0.0;
  first[kStrokes] = 0.0;
  setup->setStartState(first);
  setup->setGoal(std::make_shared<TargetZone>(si, &ctx));
  const bool any_route = options.stop_at_first_solution;
  setup->getProblemDefinition()->setOptimizationObjective(
      std::make_shared<StrokesThenRisk>(si, ctx.risk_weight, any_route));

  const std::uint_fast32_t planner_seed = seed32(options.seed, kPlannerStream);
  switch (options.planner) {
    case RoutePlanner::sst: {
      auto p = std::make_shared<SeededSst>(si, planner_seed);
      p->setGoalBias(options.goal_bias);
      p->setSelectionRadius(kSelectionRadius);
      p->setPruningRadius(kPruningRadius);
      setup->setPlanner(p);
      break;
    }
    case RoutePlanner::rrt: {
      auto p = std::make_shared<Seeded<oc::RRT>>(si, planner_seed);
      p->setGoalBias(options.goal_bias);
      setup->setPlanner(p);
      break;
    }
    case RoutePlanner::kpiece1: {
      auto p = std::make_shared<Seeded<oc::KPIECE1>>(si, planner_seed);
      p->setGoalBias(options.goal_bias);
      setup->setPlanner(p);
      break;
    }
  }
  return setup;
}

// Stage 3: the tree search until the time or propagation budget ends; true when it
// found a route.
bool search(Context& ctx, oc::SimpleSetup& setup, RouteResult* result) {
  const RouteOptions& options = *ctx.options;
  setup.setup();
  ctx.search_start = Clock::now();
  const Clock::time_point deadline =
      ctx.search_start + std::chrono::duration_cast<Clock::duration>(
                             std::chrono::duration<double>(options.max_time_s));
  const ob::PlannerTerminationCondition stop([&]() {
    if (Clock::now() >= deadline) return true;
    return options.max_propagations > 0 && ctx.propagations >= options.max_propagations;
  });
  const ob::PlannerStatus status = setup.solve(stop);
  ob::PlannerData data(setup.getSpaceInformation());
  setup.getPlannerData(data);
  result->tree_states = static_cast<int>(data.numVertices());
  return status == ob::PlannerStatus::EXACT_SOLUTION;
}

// What the search was allowed, in words.
std::string budget_text(const RouteOptions& options) {
  return fmt::format("{:.3g} s", options.max_time_s) +
         (options.max_propagations > 0
              ? " or " + std::to_string(options.max_propagations) + " propagations"
              : std::string());
}

}  // namespace

RouteResult plan_route(const problems::Problem& problem, const RouteOptions& options) {
  const Clock::time_point start = Clock::now();
  Context ctx;
  ctx.problem = &problem;
  ctx.options = &options;
  ctx.goal_radius = kGoalShrink * problem.tolerance;
  ctx.risk_weight = 1.0 / (options.max_strokes + 1);

  RouteResult result;
  // 1. Check.
  if (physics::Validation e = options.validate()) {
    result.message = e->message();
    result.error = std::move(e);
    return finish(result, ctx, start);
  }
  if (physics::Validation e = problems::validate(problem)) {
    result.message = "problem: " + problems::file_message(*e);
    result.error = std::move(e);
    return finish(result, ctx, start);
  }
  if (!problem.scene.balls.empty()) {
    // Each stroke would move them, and the route's state is the cue ball alone.
    result.error =
        physics::invalid({"scene", "balls"},
                         "are not planned for by routes yet: a route's state is the cue ball "
                         "alone, and each stroke could move the object balls");
    result.message = "problem: " + problems::file_message(*result.error);
    return finish(result, ctx, start);
  }
  const detail::Task task(problem);
  ctx.task = &task;
  if (std::string why = unreachable_reason(problem); !why.empty()) {
    result.status = RouteStatus::unreachable;
    result.message = why;
    return finish(result, ctx, start);
  }

  // 2. Setup, 3. search.
  const std::unique_ptr<oc::SimpleSetup> setup = make_setup(ctx);
  if (!search(ctx, *setup, &result)) {
    const double search_s = std::chrono::duration<double>(Clock::now() - ctx.search_start).count();
    result.status = RouteStatus::budget_exhausted;
    result.message = "No route of at most " + std::to_string(options.max_strokes) +
                     (options.max_strokes == 1 ? " stroke" : " strokes") + " found within " +
                     budget_text(options) +
                     fmt::format(" (searched {:.3g} s, {} states in the tree).", search_s,
                                 result.tree_states);
    return finish(result, ctx, start);
  }

  // 4. Verify: recover each stroke from its state and control, then re-simulate exactly.
  const oc::PathControl& path = setup->getSolutionPath();
  std::vector<physics::Shot> shots;
  for (unsigned i = 0; i < path.getControlCount(); ++i) {
    const double* v = values(path.getState(i));
    shots.push_back(resolve(ctx, {v[kX], v[kY]}, values(path.getControl(i))));
  }
  Verified v = verify(ctx, shots);
  if (!v.ok) {
    result.status = RouteStatus::budget_exhausted;
    result.message = "The route found did not hold up: " + v.why + "; no other route within " +
                     budget_text(options) + ".";
    return finish(result, ctx, start);
  }

  // 5. Report.
  result.status = RouteStatus::solved;
  result.strokes = std::move(v.strokes);
  result.route_success_probability = 1.0;
  for (const RouteStroke& s : result.strokes)
    result.route_success_probability *= s.planned.success_probability;
  const int n = static_cast<int>(result.strokes.size());
  result.message = "Route of " + std::to_string(n) + (n == 1 ? " stroke" : " strokes") +
                   " found by " + to_string(options.planner) + " with the " +
                   to_string(options.sampler) + " sampler" +
                   fmt::format("; its last stroke stops {:.2g} mm from the target when "
                               "re-simulated exactly.",
                               1e3 * result.strokes.back().planned.miss_distance);
  return finish(result, ctx, start);
}

}  // namespace cueplan::planner
