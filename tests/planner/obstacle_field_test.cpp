// Obstacle fields: the generator's problems are real (their witness lands, nothing
// overlaps), and the OMPL global stage (GlobalMethod::ompl_kpiece1) returns shots within
// the limits, solves most of them, honours its budget and repeats for a seed.
//
// Everything simulates with the exact impact method, so the suite needs no table cache.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cueplan/planner/planner.hpp"
#include "cueplan/planner/route.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::planner {
namespace {

constexpr int kObstacles = 12;

physics::SimulationOptions exact_simulation() {
  physics::SimulationOptions s;
  s.record_path = false;
  return s;
}

PlannerOptions ompl_options() {
  PlannerOptions o;
  o.global = GlobalMethod::ompl_kpiece1;
  o.simulation = exact_simulation();
  o.robustness_samples = 0;
  return o;
}

// Every constraint of the problem, checked on a fresh simulation of the shot.
void expect_within_limits(const problems::Problem& p, const PlannedShot& s, const std::string& what) {
  SCOPED_TRACE(p.name + ", " + what + ": " + s.family);
  EXPECT_EQ(problems::check_shot(p.limits, s.shot), "");
  const physics::ShotResult r = physics::simulate(p.scene, p.cue_ball, s.shot, exact_simulation());
  if (!s.solves) return;
  EXPECT_EQ(r.status, physics::ShotStatus::rest);
  EXPECT_GE(r.cushion_hits, p.limits.cushions_min);
  EXPECT_LE(r.cushion_hits, p.limits.cushions_max);
  EXPECT_LE(std::hypot(r.final_position.x - p.target.x, r.final_position.y - p.target.y),
            p.tolerance * (1 + 1e-9));
}

TEST(ObstacleFieldTest, WitnessShotLandsOnTheTargetBetweenTheBalls) {
  const auto problems = obstacle_field_problems(8, kObstacles, 11, exact_simulation());
  ASSERT_EQ(problems.size(), 8u);
  for (const KnownShotProblem& k : problems) {
    const problems::Problem& p = k.problem;
    SCOPED_TRACE(p.name);
    ASSERT_EQ(p.scene.obstacles.size(), static_cast<size_t>(kObstacles));
    EXPECT_FALSE(problems::validate(p)) << problems::file_message(*problems::validate(p));
    for (size_t i = 0; i < p.scene.obstacles.size(); ++i)
      for (size_t j = i + 1; j < p.scene.obstacles.size(); ++j) {
        const physics::Vec2 a = p.scene.obstacles[i], b = p.scene.obstacles[j];
        EXPECT_GE(std::hypot(a.x - b.x, a.y - b.y), 2.0 * p.scene.radius());
      }
    EXPECT_EQ(problems::check_shot(p.limits, k.shot), "");
    const physics::ShotResult r = physics::simulate(p.scene, p.cue_ball, k.shot, exact_simulation());
    EXPECT_EQ(r.status, physics::ShotStatus::rest);
    EXPECT_GE(r.cushion_hits, p.limits.cushions_min);
    EXPECT_LE(r.cushion_hits, p.limits.cushions_max);
    EXPECT_LE(r.cushion_hits, 3);
    EXPECT_LE(std::hypot(r.final_position.x - p.target.x, r.final_position.y - p.target.y), 1e-9);
  }
}

TEST(ObstacleFieldTest, GeneratorRepeatsForASeed) {
  const auto a = obstacle_field_problems(3, kObstacles, 5, exact_simulation());
  const auto b = obstacle_field_problems(3, kObstacles, 5, exact_simulation());
  const auto c = obstacle_field_problems(3, kObstacles, 6, exact_simulation());
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].problem.cue_ball.x, b[i].problem.cue_ball.x);
    EXPECT_EQ(a[i].problem.target.y, b[i].problem.target.y);
    EXPECT_EQ(a[i].shot.aim_deg, b[i].shot.aim_deg);
  }
  EXPECT_NE(a[0].problem.cue_ball.x, c[0].problem.cue_ball.x);
}

TEST(ObstacleFieldTest, GlobalMethodNamesRoundTrip) {
  for (GlobalMethod m : {GlobalMethod::direct_l, GlobalMethod::crs2, GlobalMethod::mlsl,
                         GlobalMethod::isres, GlobalMethod::ompl_kpiece1}) {
    GlobalMethod parsed = GlobalMethod::isres;
    ASSERT_TRUE(parse_global_method(to_string(m), &parsed)) << to_string(m);
    EXPECT_EQ(parsed, m);
  }
  EXPECT_STREQ(to_string(GlobalMethod::crs2), "crs2");
  EXPECT_STREQ(to_string(GlobalMethod::ompl_kpiece1), "ompl_kpiece1");
}

TEST(ObstacleFieldTest, OmplStageSolvesMostWithShotsWithinLimits) {
  quiet_ompl_messages();  // keep the test log to the tests' own lines
  const auto problems = obstacle_field_problems(6, kObstacles, 3, exact_simulation());
  int solved = 0;
  for (const KnownShotProblem& k : problems) {
    const PlanResult r = plan(k.problem, ompl_options());
    ASSERT_NE(r.status, PlanStatus::invalid_input) << r.message;
    if (r.status == PlanStatus::solved) ++solved;
    EXPECT_EQ(r.status == PlanStatus::solved, r.best.solves) << r.message;
    expect_within_limits(k.problem, r.best, "best");
    for (const PlannedShot& alt : r.alternatives) expect_within_limits(k.problem, alt, "alternative");
  }
  EXPECT_GE(solved, 4) << "of " << problems.size();
}

TEST(ObstacleFieldTest, OmplStageHonoursTheEvaluationBudget) {
  quiet_ompl_messages();
  const auto problems = obstacle_field_problems(2, kObstacles, 4, exact_simulation());
  for (const KnownShotProblem& k : problems) {
    PlannerOptions o = ompl_options();
    o.max_evaluations = 300;
    const PlanResult r = plan(k.problem, o);
    ASSERT_NE(r.status, PlanStatus::invalid_input) << r.message;
    // The search's budget, plus one simulation to describe each polished shot.
    EXPECT_LE(r.evaluations, o.max_evaluations + std::max(1, r.local_searches)) << r.message;
  }
}

TEST(ObstacleFieldTest, OmplStageRepeatsForASeedOnAnyThreadCount) {
  quiet_ompl_messages();
  const auto problems = obstacle_field_problems(2, kObstacles, 8, exact_simulation());
  for (const KnownShotProblem& k : problems) {
    PlannerOptions o = ompl_options();
    o.max_evaluations = 1000;
    o.seed = 42;
    const PlanResult a = plan(k.problem, o);
    o.threads = 2;
    const PlanResult b = plan(k.problem, o);
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.message, b.message);
    EXPECT_EQ(a.evaluations, b.evaluations);
    EXPECT_EQ(a.best.shot.speed, b.best.shot.speed);
    EXPECT_EQ(a.best.shot.aim_deg, b.best.shot.aim_deg);
    EXPECT_EQ(a.best.shot.topspin_k, b.best.shot.topspin_k);
    EXPECT_EQ(a.best.shot.sidespin_k, b.best.shot.sidespin_k);
    EXPECT_EQ(a.alternatives.size(), b.alternatives.size());
  }
}

}  // namespace
}  // namespace cueplan::planner
