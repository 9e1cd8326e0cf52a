// A straight pot into a pool corner pocket with the WPA pocket geometry (`pockets: pool`),
// the pool cue's squirt and the default execution noise: the pot a player makes most of
// the time. The cue ball 0.6 m from the object ball, the object ball 0.6 m from the
// pocket, both on the corner's bisector. Alciatore's TP 3.6 gives the pocket about 1.5 in
// of effective target for this approach; over 0.6 m that is an aim tolerance of about
// +-0.18 deg for the object ball, roughly +-0.09 deg at the cue with a full-ball contact:
// with aim noise 0.125 deg (and speed, tip and squirt errors) the pot should drop on
// well over half the strokes - the bar is 65 %.
//
// Also: no side is recommended for a straight pot (squirt makes side cost accuracy).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

#include "cueplan/planner/planner.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::planner {
namespace {

problems::Problem straight_pool_pot() {
  const double L = 2.54, W = 1.27, d = 0.6 / std::sqrt(2.0);
  const double ox = L - 2 * 0.0286 / std::sqrt(2.0) - d, oy = W - 2 * 0.0286 / std::sqrt(2.0) - d;
  const std::string yaml =
      "table: {length: 2.54, width: 1.27, pockets: pool}\n"
      "ball: {radius: 0.028575, mass: 0.17}\n"
      "cue: pool\n"
      "balls: {\"1\": [" + std::to_string(ox) + ", " + std::to_string(oy) + "]}\n"
      "pot: {ball: \"1\", pocket: top_right}\n"
      "cue_ball: [" + std::to_string(ox - d) + ", " + std::to_string(oy - d) + "]\n";
  const problems::LoadResult r = problems::parse_problem(yaml, "<straight pool pot>");
  EXPECT_TRUE(r.ok()) << r.error;
  return r.ok() ? *r.problem : problems::Problem{};
}

TEST(StraightPoolPot, IsMadeAtLeastTwoThirdsOfTheTimeWithoutSide) {
  const problems::Problem p = straight_pool_pot();
  ASSERT_TRUE(p.pot.has_value());
  PlannerOptions o;
  o.simulation.record_path = false;
  o.robustness_samples = 400;
  const PlanResult plan = planner::plan(p, o);
  ASSERT_EQ(plan.status, PlanStatus::solved) << plan.message;
  const PlannedShot& best = plan.best;

  // Played again, independently of the planner's own verdict, the ball drops.
  const physics::ShotResult r = physics::simulate(p.scene, p.cue_ball, best.shot);
  bool dropped = false;
  for (const physics::BallOutcome& b : r.balls)
    if (b.name == "1") dropped = b.pocketed && b.pocket == p.pot->pocket;
  EXPECT_TRUE(dropped);

  ASSERT_TRUE(best.success.pot.has_value());
  std::cout << "straight pool pot: P(pot) " << best.success.pot->p << " (95 % "
            << best.success.pot->low << "-" << best.success.pot->high << "), " << best.family
            << ", " << best.shot.speed << " m/s\n";
  EXPECT_EQ(best.success.pot->samples, 400);
  EXPECT_GE(best.success.pot->p, 0.65) << "P(pot) " << best.success.pot->p << " ["
                                       << best.success.pot->low << ", " << best.success.pot->high
                                       << "]";
  EXPECT_EQ(best.family_key.sidespin, 0) << best.family << ", k_S " << best.shot.sidespin_k;
}

}  // namespace
}  // namespace cueplan::planner
