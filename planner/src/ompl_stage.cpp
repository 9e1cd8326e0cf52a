// The OMPL global stage (ompl_stage.hpp): state space, control sampler, propagator,
// projection and goal for KPIECE1, all built per call.
#include "ompl_stage.hpp"

#include <ompl/base/GoalTypes.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ProjectionEvaluator.h>
#include <ompl/base/goals/GoalRegion.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/control/ControlSampler.h>
#include <ompl/control/SpaceInformation.h>
#include <ompl/control/planners/kpiece/KPIECE1.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "robustness.hpp"

namespace cueplan::planner::detail {
namespace {

namespace ob = ompl::base;
namespace oc = ompl::control;
using Clock = std::chrono::steady_clock;

constexpr double kLandingCell = 0.05;   // m, KPIECE1's grid of landing positions
constexpr double kGoalBias = 0.6;       // share of expansions from the strokes nearest the target
constexpr double kStartShare = 0.5;     // of the budget, for the uniform starting sample
constexpr int kMinStarts = 8;
constexpr double kStepMin = 0.002, kStepMax = 0.15;  // unit-cube scale of a perturbation
constexpr double kScoreCap = 1000.0;    // m, scores stored in a state are clamped to it
// Streams of the seed.
constexpr uint64_t kStartStream = 1, kSamplerStream = 2, kPlannerStream = 3;

std::uint_fast32_t seed32(uint64_t seed, uint64_t stream) {
  return static_cast<std::uint_fast32_t>(stream_seed(seed, stream) & 0x7fffffffu) | 1u;
}

// The shared state of one search; the OMPL objects hold a pointer to it.
struct Context {
  LandingSearch settings;
  const LandingProbe* probe = nullptr;
  int evaluations = 0;
  int n = 0;  // stroke coordinates; a state is [u_0 .. u_{n-1}, x, y, score, valid]

  bool budget_left() const { return evaluations < settings.max_evaluations; }
  // Plays the stroke at u and writes it, with its landing, into v.
  void play(const double* u, double* v) {
    for (int i = 0; i < n; ++i) v[i] = u[i];
    v[n + 3] = 0.0;
    if (!budget_left()) return;
    ++evaluations;
    const Landing l = (*probe)(u);
    v[n] = std::clamp(l.position.x, -1.0, settings.table_length + 1.0);
    v[n + 1] = std::clamp(l.position.y, -1.0, settings.table_width + 1.0);
    v[n + 2] = std::isfinite(l.score) ? std::clamp(l.score, 0.0, kScoreCap) : kScoreCap;
    v[n + 3] = l.at_rest && std::isfinite(l.position.x) && std::isfinite(l.position.y) ? 1.0 : 0.0;
  }
};

double* values(ob::State* s) { return s->as<ob::RealVectorStateSpace::StateType>()->values; }
const double* values(const ob::State* s) {
  return s->as<ob::RealVectorStateSpace::StateType>()->values;
}

// A perturbation: a Gaussian step whose scale is log-uniform, so that both fine moves
// within an island and jumps to a neighbouring one are tried.
class StepSampler : public oc::ControlSampler {
 public:
  StepSampler(const oc::ControlSpace* space, const Context* ctx) : oc::ControlSampler(space), ctx_(ctx) {
    rng_.setLocalSeed(seed32(ctx->settings.seed, kSamplerStream));
  }
  void sample(oc::Control* control) override {
    double* d = control->as<oc::RealVectorControlSpace::ControlType>()->values;
    const double scale = kStepMin * std::exp(rng_.uniform01() * std::log(kStepMax / kStepMin));
    for (int i = 0; i < ctx_->n; ++i) d[i] = std::clamp(rng_.gaussian(0.0, scale), -1.0, 1.0);
  }

 private:
  const Context* ctx_;
};

class StepPropagator : public oc::StatePropagator {
 public:
  StepPropagator(const oc::SpaceInformationPtr& si, Context* ctx) : oc::StatePropagator(si), ctx_(ctx) {}
  void propagate(const ob::State* from, const oc::Control* control, double, ob::State* to) const override {
    const double* u = values(from);
    const double* d = control->as<oc::RealVectorControlSpace::ControlType>()->values;
    std::vector<double> next(static_cast<size_t>(ctx_->n));
    for (int i = 0; i < ctx_->n; ++i) {
      const double x = u[i] + d[i];
      next[i] = i == ctx_->settings.aim_coordinate ? x - std::floor(x) : std::clamp(x, 0.0, 1.0);
    }
    ctx_->play(next.data(), values(to));
  }
  bool canPropagateBackward() const override { return false; }

 private:
  Context* ctx_;
};

// KPIECE1's grid: where the stroke landed.
class LandingProjection : public ob::ProjectionEvaluator {
 public:
  LandingProjection(const ob::StateSpace* space, int n) : ob::ProjectionEvaluator(space), n_(n) {}
  unsigned int getDimension() const override { return 2; }
  void defaultCellSizes() override { cellSizes_ = {kLandingCell, kLandingCell}; }
  void project(const ob::State* state, Eigen::Ref<Eigen::VectorXd> projection) const override {
    projection[0] = values(state)[n_];
    projection[1] = values(state)[n_ + 1];
  }

 private:
  int n_;
};

// Landed within the goal score; the distance is the score above it.
class ScoreGoal : public ob::GoalRegion {
 public:
  ScoreGoal(const ob::SpaceInformationPtr& si, const Context* ctx) : ob::GoalRegion(si), ctx_(ctx) {
    setThreshold(std::numeric_limits<double>::min());  // isSatisfied: distance < threshold
  }
  double distanceGoal(const ob::State* state) const override {
    return std::max(0.0, values(state)[ctx_->n + 2] - ctx_->settings.goal_score);
  }

 private:
  const Context* ctx_;
};

// KPIECE1 with its own random stream seeded.
class SeededKpiece : public oc::KPIECE1 {
 public:
  SeededKpiece(const oc::SpaceInformationPtr& si, std::uint_fast32_t seed) : oc::KPIECE1(si) {
    rng_.setLocalSeed(seed);
  }
};

}  // namespace

void explore_landings(const LandingSearch& settings, const LandingProbe& probe) {
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(
                         std::chrono::duration<double>(std::max(0.0, settings.max_time_s)));
  auto out_of_time = [&] { return Clock::now() >= deadline; };
  Context ctx;
  ctx.settings = settings;
  ctx.probe = &probe;
  ctx.n = settings.dimension;
  const int n = ctx.n;
  if (n < 1 || settings.max_evaluations < 1) return;

  auto space = std::make_shared<ob::RealVectorStateSpace>(static_cast<unsigned>(n + 4));
  ob::RealVectorBounds bounds(static_cast<unsigned>(n + 4));
  for (int i = 0; i < n; ++i) bounds.setLow(i, 0.0), bounds.setHigh(i, 1.0);
  bounds.setLow(n, -1.0), bounds.setHigh(n, settings.table_length + 1.0);
  bounds.setLow(n + 1, -1.0), bounds.setHigh(n + 1, settings.table_width + 1.0);
  bounds.setLow(n + 2, 0.0), bounds.setHigh(n + 2, kScoreCap);
  bounds.setLow(n + 3, 0.0), bounds.setHigh(n + 3, 1.0);
  space->setBounds(bounds);

  auto controls = std::make_shared<oc::RealVectorControlSpace>(space, static_cast<unsigned>(n));
  ob::RealVectorBounds step(static_cast<unsigned>(n));
  step.setLow(-1.0);
  step.setHigh(1.0);
  controls->setBounds(step);
  controls->setControlSamplerAllocator([&ctx](const oc::ControlSpace* cs) -> oc::ControlSamplerPtr {
    return std::make_shared<StepSampler>(cs, &ctx);
  });

  auto si = std::make_shared<oc::SpaceInformation>(space, controls);
  si->setStatePropagator(std::make_shared<StepPropagator>(si, &ctx));
  si->setStateValidityChecker([n](const ob::State* s) { return values(s)[n + 3] > 0.5; });
  si->setPropagationStepSize(1.0);
  si->setMinMaxControlDuration(1, 1);
  si->setup();

  // Starts: a seeded uniform sample of the cube; the strokes that come to rest.
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  auto goal = std::make_shared<ScoreGoal>(si, &ctx);
  pdef->setGoal(goal);
  std::mt19937_64 rng(stream_seed(settings.seed, kStartStream));
  const int start_budget = std::max(kMinStarts, static_cast<int>(kStartShare * settings.max_evaluations));
  ob::State* state = si->allocState();
  std::vector<double> u(static_cast<size_t>(n));
  bool any_start = false, goal_met = false;
  // Until some stroke comes to rest, the uniform sample goes on.
  for (int i = 0; ctx.budget_left() && !out_of_time() && !goal_met && (i < start_budget || !any_start); ++i) {
    for (double& x : u) x = static_cast<double>(rng() >> 11) * 0x1.0p-53;
    ctx.play(u.data(), values(state));
    if (!si->isValid(state)) continue;
    pdef->addStartState(state);
    any_start = true;
    goal_met = goal->isSatisfied(state);
  }
  si->freeState(state);
  if (!any_start || goal_met || !ctx.budget_left() || out_of_time()) return;

  auto planner = std::make_shared<SeededKpiece>(si, seed32(settings.seed, kPlannerStream));
  // The space's own default projection is replaced when the space is set up; the
  // planner is given this one directly.
  auto projection = std::make_shared<LandingProjection>(space.get(), n);
  projection->setCellSizes({kLandingCell, kLandingCell});
  planner->setProjectionEvaluator(projection);
  planner->setGoalBias(kGoalBias);
  planner->setProblemDefinition(pdef);
  planner->setup();
  planner->solve(ob::PlannerTerminationCondition([&] { return !ctx.budget_left() || out_of_time(); }));
}

}  // namespace cueplan::planner::detail
