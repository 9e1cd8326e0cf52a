// Tests of plan_route(): multi-stroke routes on OMPL's planners. Every route returned is
// simulated again here, stroke by stroke, from where the previous stroke stopped, and
// judged by the problem's own checks rather than by what the planner reports.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/planner/route.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::planner {
namespace {

problems::Problem route_problem(const std::string& stem) {
  const problems::LoadResult r =
      problems::load_problem(std::string(CUEPLAN_PROBLEMS_DIR) + "/routes/" + stem + ".yaml");
  EXPECT_TRUE(r.ok()) << r.error;
  return r.ok() ? *r.problem : problems::Problem{};
}

double distance(physics::Vec2 a, physics::Vec2 b) { return std::hypot(a.x - b.x, a.y - b.y); }

// Short runs: stop at the first route (which is re-simulated before it is returned).
RouteOptions quick(RoutePlanner planner = RoutePlanner::sst,
                   RouteSampler sampler = RouteSampler::directed) {
  quiet_ompl_messages();  // keep the test log to the tests' own lines
  RouteOptions o;
  o.planner = planner;
  o.sampler = sampler;
  o.max_strokes = 2;
  o.max_time_s = 10.0;
  o.stop_at_first_solution = true;
  o.robustness_samples = 50;
  o.seed = 3;
  return o;
}

// The route, stroke by stroke, with the simulator's default (exact) options.
void expect_valid_route(const problems::Problem& p, const RouteResult& r) {
  ASSERT_EQ(r.status, RouteStatus::solved) << r.message;
  ASSERT_FALSE(r.strokes.empty());
  physics::Vec2 at = p.cue_ball;
  for (size_t i = 0; i < r.strokes.size(); ++i) {
    SCOPED_TRACE("stroke " + std::to_string(i + 1));
    const RouteStroke& s = r.strokes[i];
    EXPECT_NEAR(s.start.x, at.x, 1e-12);
    EXPECT_NEAR(s.start.y, at.y, 1e-12);
    EXPECT_EQ(problems::check_shot(p.limits, s.planned.shot), "");
    const physics::ShotResult out = physics::simulate(p.scene, at, s.planned.shot);
    ASSERT_EQ(out.status, physics::ShotStatus::rest);
    EXPECT_LE(out.cushion_hits, p.limits.cushions_max);
    EXPECT_FALSE(p.scene.check_position(out.final_position, {"landing"}));
    // The stated landing is where the stroke stops.
    EXPECT_LT(distance(out.final_position, s.planned.final_position), 1e-6);
    EXPECT_GE(s.planned.success_probability, 0.0);
    EXPECT_LE(s.planned.success_probability, 1.0);
    at = out.final_position;
  }
  EXPECT_LE(distance(at, p.target), p.tolerance);
  EXPECT_GE(r.strokes.back().planned.cushion_hits, p.limits.cushions_min);
  EXPECT_GE(r.time_to_first_solution_s, 0.0);
  EXPECT_LE(r.time_to_first_solution_s, r.time_s);
  EXPECT_GT(r.propagations, 0);
}

// ---- The shipped route problems ------------------------------------------------

TEST(RouteProblems, DeclareTheirStrokesAndTimeBudget) {
  for (const char* stem : {"two_stroke_speed_limit", "two_stroke_blocked"}) {
    const problems::Problem p = route_problem(stem);
    ASSERT_TRUE(p.max_strokes.has_value()) << stem;
    EXPECT_EQ(*p.max_strokes, 2) << stem;
    ASSERT_TRUE(p.time_budget_s.has_value()) << stem;
    EXPECT_GT(*p.time_budget_s, 0.0) << stem;
    EXPECT_EQ(unreachable_reason(p), "") << stem;
  }
}

// No stroke within 0.5 m/s stops within reach of a target 2.0 m away: a grid over the
// whole stroke space (speed, aim, spin over the miscue disc).
TEST(RouteProblems, SpeedLimitTargetIsBeyondEveryStroke) {
  const problems::Problem p = route_problem("two_stroke_speed_limit");
  physics::SimulationOptions sim;
  sim.record_path = false;
  double farthest = 0.0;
  for (double v = p.limits.speed_min; v <= p.limits.speed_max + 1e-9; v += 0.1)
    for (double aim = -180.0; aim < 180.0; aim += 15.0)
      for (double kt = -1.25; kt <= 1.25 + 1e-9; kt += 0.25)
        for (double ks = -1.25; ks <= 1.25 + 1e-9; ks += 0.25) {
          if (std::hypot(kt, ks) > p.limits.spin_max) continue;
          const physics::ShotResult r = physics::simulate(p.scene, p.cue_ball, {v, aim, kt, ks}, sim);
          if (r.status == physics::ShotStatus::rest)
            farthest = std::max(farthest, distance(r.final_position, p.cue_ball));
        }
  EXPECT_GT(farthest, 0.5);  // the grid did move the ball
  EXPECT_LT(farthest, distance(p.cue_ball, p.target) - p.tolerance - 0.3) << farthest;
}

// With no cushion allowed a stroke is a straight line, and the one line to the target
// passes within a ball's diameter of the wall.
TEST(RouteProblems, BlockedTargetHasNoClearStraightLine) {
  const problems::Problem p = route_problem("two_stroke_blocked");
  ASSERT_EQ(p.limits.cushions_max, 0);
  const physics::Vec2 a = p.cue_ball, b = p.target;
  const double length = distance(a, b);
  bool blocked = false;
  for (const physics::Vec2& o : p.scene.obstacles) {
    const double t = std::clamp(((o.x - a.x) * (b.x - a.x) + (o.y - a.y) * (b.y - a.y)) /
                                    (length * length),
                                0.0, 1.0);
    const physics::Vec2 nearest{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
    blocked = blocked || distance(nearest, o) < 2.0 * p.scene.radius();
  }
  EXPECT_TRUE(blocked);
}

// The one-stroke planner, with a large budget, finds no single stroke.
TEST(RouteProblems, NeitherIsSolvedByOneStroke) {
  for (const char* stem : {"two_stroke_speed_limit", "two_stroke_blocked"}) {
    const problems::Problem p = route_problem(stem);
    PlannerOptions o;
    o.max_evaluations = 6000;
    o.robustness_samples = 0;
    o.simulation.record_path = false;
    const PlanResult r = plan(p, o);
    EXPECT_NE(r.status, PlanStatus::solved) << stem << ": " << r.message;
  }
}

// ---- Routes --------------------------------------------------------------------

class RouteOnProblem : public testing::TestWithParam<std::string> {};

TEST_P(RouteOnProblem, SstFindsTwoStrokesThatHoldWhenResimulated) {
  const problems::Problem p = route_problem(GetParam());
  const RouteResult r = plan_route(p, quick());
  expect_valid_route(p, r);
  EXPECT_EQ(r.strokes.size(), 2u);
}

INSTANTIATE_TEST_SUITE_P(Shipped, RouteOnProblem,
                         testing::Values("two_stroke_speed_limit", "two_stroke_blocked"),
                         [](const testing::TestParamInfo<std::string>& param) {
                           return param.param;
                         });

TEST(Route, RrtFindsAValidRoute) {
  const problems::Problem p = route_problem("two_stroke_speed_limit");
  const RouteResult r = plan_route(p, quick(RoutePlanner::rrt));
  expect_valid_route(p, r);
}

TEST(Route, Kpiece1FindsAValidRoute) {
  const problems::Problem p = route_problem("two_stroke_speed_limit");
  const RouteResult r = plan_route(p, quick(RoutePlanner::kpiece1));
  expect_valid_route(p, r);
}

// Random strokes: either a route that holds or an honest budget_exhausted.
TEST(Route, RandomSamplerIsHonestEitherWay) {
  const problems::Problem p = route_problem("two_stroke_speed_limit");
  RouteOptions o = quick(RoutePlanner::sst, RouteSampler::random);
  o.max_time_s = 1.0;
  const RouteResult r = plan_route(p, o);
  if (r.status == RouteStatus::solved) {
    expect_valid_route(p, r);
  } else {
    EXPECT_EQ(r.status, RouteStatus::budget_exhausted) << r.message;
    EXPECT_EQ(r.steerings, 0);
  }
}

// max_strokes 1 is the single-stroke problem: blocked_direct_route has a two-cushion
// answer, and the route is that one stroke.
TEST(Route, OneStrokeRouteOnASingleStrokeProblem) {
  const problems::LoadResult loaded =
      problems::load_problem(std::string(CUEPLAN_PROBLEMS_DIR) + "/blocked_direct_route.yaml");
  ASSERT_TRUE(loaded.ok()) << loaded.error;
  const problems::Problem& p = *loaded.problem;
  RouteOptions o = quick();
  o.max_strokes = 1;
  const RouteResult r = plan_route(p, o);
  expect_valid_route(p, r);
  EXPECT_EQ(r.strokes.size(), 1u);
  EXPECT_TRUE(r.strokes[0].planned.solves);
}

// With one stroke allowed the target is out of reach, but that is not proven: the
// answer is budget_exhausted, never unreachable.
TEST(Route, OneStrokeTooFewIsBudgetExhaustedNotUnreachable) {
  const problems::Problem p = route_problem("two_stroke_speed_limit");
  RouteOptions o = quick();
  o.max_strokes = 1;
  o.max_time_s = 0.5;
  const RouteResult r = plan_route(p, o);
  EXPECT_EQ(r.status, RouteStatus::budget_exhausted) << r.message;
  EXPECT_TRUE(r.strokes.empty());
  EXPECT_NE(r.message.find("No route"), std::string::npos) << r.message;
}

// A budget in propagations, not time, ends the search at the same point each run.
TEST(Route, SameSeedAndPropagationBudgetRepeat) {
  const problems::Problem p = route_problem("two_stroke_blocked");
  RouteOptions o = quick();
  o.stop_at_first_solution = false;
  o.max_propagations = 40;
  const RouteResult a = plan_route(p, o);
  const RouteResult b = plan_route(p, o);
  EXPECT_EQ(a.status, RouteStatus::solved) << a.message;
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.propagations, b.propagations);
  EXPECT_EQ(a.tree_states, b.tree_states);
  ASSERT_EQ(a.strokes.size(), b.strokes.size());
  for (size_t i = 0; i < a.strokes.size(); ++i) {
    EXPECT_EQ(a.strokes[i].planned.shot.speed, b.strokes[i].planned.shot.speed);
    EXPECT_EQ(a.strokes[i].planned.shot.aim_deg, b.strokes[i].planned.shot.aim_deg);
  }
}

// ---- Impossible targets and bad input -------------------------------------------

// A ring of eight balls around the target: the gaps between them are narrower than a
// ball, so no stroke sequence can get in.
problems::Problem ringed_target() {
  problems::Problem p = route_problem("two_stroke_blocked");
  p.scene.obstacles.clear();
  const double ring = 0.08;
  for (int i = 0; i < 8; ++i) {
    const double a = 2.0 * 3.14159265358979 * i / 8;
    p.scene.obstacles.push_back({p.target.x + ring * std::cos(a), p.target.y + ring * std::sin(a)});
  }
  return p;
}

TEST(Route, RingedTargetIsReportedUnreachable) {
  const problems::Problem p = ringed_target();
  ASSERT_FALSE(p.scene.check_position(p.target, {"target"}));
  const RouteResult r = plan_route(p, quick());
  EXPECT_EQ(r.status, RouteStatus::unreachable);
  EXPECT_NE(r.message.find("wall it off"), std::string::npos) << r.message;
  EXPECT_EQ(r.propagations, 0);
  EXPECT_TRUE(r.strokes.empty());
}

// One ball taken out of the ring leaves a gap wider than a ball: no proof then.
TEST(Route, OpenRingIsNotClaimedUnreachable) {
  problems::Problem p = ringed_target();
  p.scene.obstacles.erase(p.scene.obstacles.begin());
  EXPECT_EQ(unreachable_reason(p), "");
}

TEST(Route, BadOptionsAreRejectedNamingTheField) {
  const problems::Problem p = route_problem("two_stroke_speed_limit");
  struct Case {
    const char* field;
    void (*spoil)(RouteOptions&);
  };
  const Case cases[] = {
      {"max_strokes", [](RouteOptions& o) { o.max_strokes = 0; }},
      {"max_time_s", [](RouteOptions& o) { o.max_time_s = -1.0; }},
      {"max_time_s", [](RouteOptions& o) { o.max_time_s = NAN; }},
      {"max_propagations", [](RouteOptions& o) { o.max_propagations = -3; }},
      {"steer_evaluations", [](RouteOptions& o) { o.steer_evaluations = 5; }},
      {"goal_bias", [](RouteOptions& o) { o.goal_bias = 1.0; }},
      {"intermediate_zone_m", [](RouteOptions& o) { o.intermediate_zone_m = 0.0; }},
      {"risk_samples", [](RouteOptions& o) { o.risk_samples = -1; }},
      {"robustness_samples", [](RouteOptions& o) { o.robustness_samples = -1; }},
  };
  for (const Case& c : cases) {
    RouteOptions o = quick();
    c.spoil(o);
    const physics::Validation e = o.validate();
    ASSERT_TRUE(e) << c.field;
    EXPECT_EQ(e->field.text(), c.field);
    const RouteResult r = plan_route(p, o);
    EXPECT_EQ(r.status, RouteStatus::invalid_input);
    ASSERT_TRUE(r.error) << c.field;
    EXPECT_EQ(r.error->field.text(), c.field);
    EXPECT_EQ(r.message.rfind(std::string(c.field) + " ", 0), 0u) << r.message;
  }
  EXPECT_FALSE(quick().validate());
}

TEST(RouteProblemFields, LoaderReadsAndChecksThem) {
  const char* base = "cue_ball: [0.8, 0.9]\ntarget: [2.8, 0.9]\n";
  const problems::LoadResult ok =
      problems::parse_problem(std::string(base) + "max_strokes: 3\ntime_budget_s: 2.5\n", "r.yaml");
  ASSERT_TRUE(ok.ok()) << ok.error;
  EXPECT_EQ(ok.problem->max_strokes, 3);
  EXPECT_EQ(ok.problem->time_budget_s, 2.5);
  const problems::LoadResult none = problems::parse_problem(base, "r.yaml");
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none.problem->max_strokes.has_value());
  EXPECT_FALSE(none.problem->time_budget_s.has_value());
  for (const char* bad : {"max_strokes: 0\n", "max_strokes: 1.5\n", "max_strokes: 101\n",
                          "time_budget_s: 0\n", "time_budget_s: -1\n", "time_budget_s: fast\n"}) {
    const problems::LoadResult r = problems::parse_problem(std::string(base) + bad, "r.yaml");
    ASSERT_FALSE(r.ok()) << bad;
    const std::string field = std::string(bad).substr(0, std::string(bad).find(':'));
    EXPECT_EQ(r.error.rfind("r.yaml:3: " + field + ": ", 0), 0u) << r.error;
  }
}

}  // namespace
}  // namespace cueplan::planner

namespace cueplan::planner {
namespace {

TEST(Route, ObjectBallsAreRefusedNamingTheField) {
  // A route's state is the cue ball alone; strokes that move object balls are not planned.
  problems::Problem p = route_problem("two_stroke_blocked");
  p.scene.balls = {{"red", {2.0, 1.4}}};
  const RouteResult r = plan_route(p, quick());
  EXPECT_EQ(r.status, RouteStatus::invalid_input);
  ASSERT_TRUE(r.error.has_value());
  EXPECT_EQ(r.error->field, (physics::FieldPath{"scene", "balls"}));
  EXPECT_NE(r.message.find("balls are not planned for by routes yet"), std::string::npos)
      << r.message;
  EXPECT_TRUE(r.strokes.empty());
}

}  // namespace
}  // namespace cueplan::planner
