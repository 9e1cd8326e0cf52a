// The pot planner: pots that a known stroke makes are solved; the reported stroke, played
// again, meets every condition of the problem; screened pots are proved unreachable and
// the proof agrees with simulation; the ranking and the side rule hold; and the answer
// depends on the seed only.
//
// Everything simulates with the exact impact method, so the suite needs no table cache.
#include <gtest/gtest.h>

#include <iostream>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "cueplan/planner/planner.hpp"
#include "cueplan/planner/spin_map.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::planner {
namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

problems::Problem parsed(const std::string& yaml) {
  const problems::LoadResult r = problems::parse_problem(yaml, "<test>");
  EXPECT_TRUE(r.ok()) << r.error;
  return r.ok() ? *r.problem : problems::Problem{};
}

problems::Problem shipped(const std::string& file) {
  const problems::LoadResult r = problems::load_problem(std::string(CUEPLAN_PROBLEMS_DIR) + "/" + file);
  EXPECT_TRUE(r.ok()) << r.error;
  return r.ok() ? *r.problem : problems::Problem{};
}

PlannerOptions options() {
  PlannerOptions o;
  o.simulation.record_path = false;
  o.robustness_samples = 100;
  return o;
}

const physics::BallOutcome* ball(const physics::ShotResult& r, const std::string& name) {
  for (const physics::BallOutcome& b : r.balls)
    if (b.name == name) return &b;
  return nullptr;
}

// Every condition of a pot problem, checked one by one on a fresh exact simulation of
// the stroke rather than through check_stroke.
void expect_pots_cleanly(const problems::Problem& p, const PlannedShot& s, const std::string& what) {
  SCOPED_TRACE(what + ": " + s.family);
  const problems::Limits& l = p.limits;
  EXPECT_GE(s.shot.speed, l.speed_min * (1 - 1e-12));
  EXPECT_LE(s.shot.speed, l.speed_max * (1 + 1e-12));
  EXPECT_LE(std::hypot(s.shot.topspin_k, s.shot.sidespin_k), l.spin_max * (1 + 1e-12));
  const physics::ShotResult r = physics::simulate(p.scene, p.cue_ball, s.shot);
  ASSERT_EQ(r.status, physics::ShotStatus::rest);  // cue ball not pocketed, no obstacle
  ASSERT_GT(r.first_contact, 0);
  EXPECT_EQ(r.balls[static_cast<size_t>(r.first_contact)].name, p.required_first_contact());
  const physics::BallOutcome* potted = ball(r, p.pot->ball);
  ASSERT_NE(potted, nullptr);
  EXPECT_TRUE(potted->pocketed);
  EXPECT_EQ(potted->pocket, p.pot->pocket);
  for (const physics::BallOutcome& b : r.balls)
    if (b.name != p.pot->ball) EXPECT_FALSE(b.pocketed) << b.name;
  EXPECT_GE(r.cushion_hits, l.cushions_min);
  EXPECT_LE(r.cushion_hits, l.cushions_max);
  if (p.has_target)
    EXPECT_LE(std::hypot(r.final_position.x - p.target.x, r.final_position.y - p.target.y),
              p.tolerance);
  EXPECT_TRUE(s.solves);
  EXPECT_EQ(s.failure, problems::Failure::none) << s.failure_reason;
}

// Pots a random stroke made (a direct pot, the cue ball at rest after 0-3 cushions): at
// least 95 % are solved, and every answer pots cleanly when played again.
TEST(PotPlannerTest, SolvesKnownStrokePots) {
  const std::vector<KnownShotProblem> known = known_pot_problems(40, 2026, {});
  int solved = 0;
  for (const KnownShotProblem& k : known) {
    // The witness really is one: it solves its problem.
    const physics::ShotResult w = physics::simulate(k.problem.scene, k.problem.cue_ball, k.shot);
    ASSERT_TRUE(problems::check_stroke(k.problem, k.shot, w).solves()) << k.problem.name;
    const PlanResult r = plan(k.problem, options());
    if (r.status != PlanStatus::solved) {
      // A miss is allowed (the count below holds the rate); say which one.
      std::cerr << k.problem.name << " not solved: " << r.message << "\n";
      continue;
    }
    ++solved;
    expect_pots_cleanly(k.problem, r.best, k.problem.name);
    for (const PlannedShot& a : r.alternatives)
      if (a.solves) expect_pots_cleanly(k.problem, a, k.problem.name + " alternative");
  }
  EXPECT_GE(solved, 38) << "of 40";
}

TEST(PotPlannerTest, SolvesEveryShippedPotProblem) {
  for (const char* file :
       {"pots/straight_pot_corner.yaml", "pots/cut_middle_pocket.yaml", "pots/plant_two_balls.yaml"}) {
    const problems::Problem p = shipped(file);
    const PlanResult r = plan(p, options());
    ASSERT_EQ(r.status, PlanStatus::solved) << file << ": " << r.message;
    expect_pots_cleanly(p, r.best, file);
    ASSERT_TRUE(r.best.pot.has_value());
    EXPECT_TRUE(r.best.pot->made);
    EXPECT_GT(r.best.pot->aim_margin_deg, 0.0);
    EXPECT_GT(r.best.pot->margin_m, 0.0);
  }
}

// The pot's numbers against the table's geometry: a straight pot is a full-ball hit
// with no throw to allow for; a cut's angle is the ghost-ball line's, within the throw.
TEST(PotPlannerTest, ReportsCutAndThrowAsTheGeometrySays) {
  const problems::Problem straight = shipped("pots/straight_pot_corner.yaml");
  const PlanResult s = plan(straight, options());
  ASSERT_EQ(s.status, PlanStatus::solved) << s.message;
  ASSERT_TRUE(s.best.pot);
  EXPECT_LT(s.best.pot->cut_deg, 1.0) << s.best.pot->throw_deg;
  EXPECT_EQ(s.best.pot->thickness, "full");
  EXPECT_NEAR(s.best.pot->ghost_aim_deg, -135.0, 1e-9);  // the diagonal, by construction

  const problems::Problem cut = shipped("pots/cut_middle_pocket.yaml");
  const PlanResult c = plan(cut, options());
  ASSERT_EQ(c.status, PlanStatus::solved) << c.message;
  ASSERT_TRUE(c.best.pot);
  // The ghost-ball cut: between the cue ball's line to the ghost and the red's to the pocket.
  const physics::Vec2 red = cut.scene.balls[0].position;
  const physics::Vec2 pocket = cut.scene.pockets[static_cast<size_t>(cut.pot->pocket)].centre;
  const double to_pocket = std::atan2(pocket.y - red.y, pocket.x - red.x);
  const physics::Vec2 ghost{red.x - 2 * cut.scene.radius() * std::cos(to_pocket),
                            red.y - 2 * cut.scene.radius() * std::sin(to_pocket)};
  const double cue_line = std::atan2(ghost.y - cut.cue_ball.y, ghost.x - cut.cue_ball.x);
  const double ghost_cut = std::abs(std::remainder(to_pocket - cue_line, 2 * std::numbers::pi)) * kDeg;
  // The stroke may send the red off the pocket's centre (by the capture radius less its
  // margin), and the throw turns it from the line of centres.
  const double distance = std::hypot(pocket.x - red.x, pocket.y - red.y);
  const double capture = cut.scene.pockets[static_cast<size_t>(cut.pot->pocket)].radius;
  const double off_centre = std::asin((capture - c.best.pot->margin_m) / distance) * kDeg;
  EXPECT_NEAR(c.best.pot->cut_deg, ghost_cut, std::abs(c.best.pot->throw_deg) + off_centre + 0.5)
      << "throw " << c.best.pot->throw_deg << ", off the centre by " << off_centre;
  EXPECT_NEAR(c.best.pot->ghost_aim_deg, cue_line * kDeg, 1e-9);
  EXPECT_GT(std::abs(c.best.pot->throw_deg), 0.05);  // a cut throws the object ball
}

// A blue on the red's line to the pocket: no direct pot, and no stroke aimed anywhere
// near the ghost ball pots the red cleanly (the proof checked by simulation). The limits
// allow no cushion before the contact and none off the red, so no kick or bank either
// (with the default limits the planner plays it off cushions: kick_test.cpp).
TEST(PotPlannerTest, AScreenedPotIsUnreachable) {
  const std::string no_kicks = "limits: {cushions_before_contact: 0, object_cushions: 0}\n";
  const std::string screened =
      "balls: {red: [1.0, 1.0], blue: [0.6, 0.6]}\npot: {ball: red, pocket: bottom_left}\n"
      "cue_ball: [1.5, 1.3]\n" + no_kicks;
  const problems::Problem p = parsed(screened);
  const PlanResult r = plan(p, options());
  EXPECT_EQ(r.status, PlanStatus::unreachable) << r.message;
  EXPECT_NE(r.message.find("no direct pot: red's path to the bottom_left pocket is screened by blue"),
            std::string::npos)
      << r.message;
  int clean = 0;
  for (double aim = -160.0; aim <= -120.0; aim += 0.05)
    for (double speed : {1.0, 2.5, 4.0}) {
      const physics::Shot shot{speed, aim, 0.0, 0.0};
      clean += problems::check_outcome(p, physics::simulate(p.scene, p.cue_ball, shot)).pot_made();
    }
  EXPECT_EQ(clean, 0);

  // The cue ball's path blocked instead: a yellow between it and every ghost ball.
  const problems::Problem q = parsed(
      "balls: {red: [1.0, 1.0], yellow: [1.3, 1.3]}\npot: {ball: red, pocket: bottom_left}\n"
      "cue_ball: [1.6, 1.6]\n" + no_kicks);
  const PlanResult rq = plan(q, options());
  EXPECT_EQ(rq.status, PlanStatus::unreachable) << rq.message;
  EXPECT_NE(rq.message.find("the cue ball's path"), std::string::npos) << rq.message;

  // Moved off the line the blue no longer screens: the pot is planned and made.
  const problems::Problem open = parsed(
      "balls: {red: [1.0, 1.0], blue: [0.6, 0.75]}\npot: {ball: red, pocket: bottom_left}\n"
      "cue_ball: [1.5, 1.3]\n");
  EXPECT_FALSE(problems::screened_pot(open).has_value());
  const PlanResult ro = plan(open, options());
  EXPECT_EQ(ro.status, PlanStatus::solved) << ro.message;
}

// The default answer's success interval is never below an alternative's, and the
// estimates are consistent: P(both) = P(pot) P(position | pot) count by count.
TEST(PotPlannerTest, RanksByTheChanceOfPotAndPosition) {
  for (const KnownShotProblem& k : known_pot_problems(8, 77, {})) {
    const PlanResult r = plan(k.problem, options());
    if (r.status != PlanStatus::solved) continue;
    for (const PlannedShot* s : [&] {
           std::vector<const PlannedShot*> all{&r.best};
           for (const PlannedShot& a : r.alternatives) all.push_back(&a);
           return all;
         }()) {
      ASSERT_TRUE(s->success.pot.has_value());
      const Estimate& pot = *s->success.pot;
      EXPECT_EQ(pot.samples, s->success.both.samples);
      EXPECT_EQ(s->success.position.samples, pot.successes);
      EXPECT_EQ(s->success.position.successes, s->success.both.successes);
      EXPECT_LE(s->success.both.successes, pot.successes);
    }
    for (const PlannedShot& a : r.alternatives)
      if (a.success.both.samples == r.best.success.both.samples)
        EXPECT_GE(r.best.success.both.high, a.success.both.low) << k.problem.name;
  }
}

// A pure pot (no target) is ranked by P(pot) alone; P(both) is P(pot).
TEST(PotPlannerTest, APurePotIsRankedByThePotAlone) {
  const problems::Problem p =
      parsed("balls: {red: [0.6, 0.6]}\npot: {ball: red, pocket: bottom_left}\ncue_ball: [1.1, 1.1]\n");
  EXPECT_FALSE(p.has_target);
  EXPECT_EQ(p.limits.cushions_min, 0);
  EXPECT_EQ(p.limits.cushions_max, 3);
  const PlanResult r = plan(p, options());
  ASSERT_EQ(r.status, PlanStatus::solved) << r.message;
  ASSERT_TRUE(r.best.success.pot);
  EXPECT_EQ(r.best.success.both, *r.best.success.pot);
  for (const PlannedShot& a : r.alternatives)
    if (a.success.pot && a.success.pot->samples == r.best.success.pot->samples)
      EXPECT_GE(r.best.success.pot->high, a.success.pot->low);
}

// On a pot where the cue ball meets no cushion, side cannot steer it (it acts at
// cushions): the answer carries none that the samples cannot justify.
TEST(PotPlannerTest, SpinThatChangesNothingIsNotRecommended) {
  const problems::Problem p = parsed(
      "balls: {red: [1.95, 0.22]}\npot: {ball: red, pocket: bottom_middle}\ncue_ball: [2.5, 0.6]\n"
      "target: [1.4, 1.1]\ntolerance: 0.05\nlimits: {cushions: 0}\n");
  const PlanResult r = plan(p, options());
  ASSERT_EQ(r.status, PlanStatus::solved) << r.message;
  if (std::abs(r.best.shot.sidespin_k) >= physics::kSpinPerTipOffset / 32.0) {
    // Kept only if the stroke without it succeeds measurably less often.
    physics::Shot plain = r.best.shot;
    plain.sidespin_k = 0.0;
    const Success with = estimate_success(p, r.best.shot, options().noise, 400, 9, {});
    const Success without = estimate_success(p, plain, options().noise, 400, 9, {});
    EXPECT_GT(with.both.low, without.both.high) << "side kept that does nothing measurable";
  }
}

TEST(PotPlannerTest, TheSeedAndNotTheThreadsDecideTheAnswer) {
  const problems::Problem p = shipped("pots/cut_middle_pocket.yaml");
  PlannerOptions one = options();
  one.threads = 1;
  one.max_time_s = 600.0;
  PlannerOptions two = one;
  two.threads = 2;
  const PlanResult a = plan(p, one), b = plan(p, two), c = plan(p, one);
  for (const PlanResult* r : {&b, &c}) {
    EXPECT_EQ(r->status, a.status);
    EXPECT_EQ(r->best.shot.speed, a.best.shot.speed);
    EXPECT_EQ(r->best.shot.aim_deg, a.best.shot.aim_deg);
    EXPECT_EQ(r->best.shot.topspin_k, a.best.shot.topspin_k);
    EXPECT_EQ(r->best.shot.sidespin_k, a.best.shot.sidespin_k);
    EXPECT_EQ(r->best.success, a.best.success);
    EXPECT_EQ(r->best.pot, a.best.pot);
    EXPECT_EQ(r->evaluations, a.evaluations);
    ASSERT_EQ(r->alternatives.size(), a.alternatives.size());
  }
}

// The conditions one by one, each reported with its reason.
TEST(PotConditionsTest, EachBrokenConditionIsNamed) {
  const problems::Problem p = parsed(
      "balls: {red: [0.6, 0.6], blue: [2.0, 1.4]}\npot: {ball: red, pocket: bottom_left}\n"
      "cue_ball: [1.1, 1.1]\ntarget: [2.0, 0.5]\ntolerance: 0.05\n");
  const auto verdict = [&](const physics::Shot& s) {
    return problems::check_stroke(p, s, physics::simulate(p.scene, p.cue_ball, s));
  };
  // Straight at the red with draw: potted, the cue ball drawn back, far from the target.
  EXPECT_EQ(verdict({2.85, -135.0, -1.03, 0.0}).failure, problems::Failure::off_target);
  EXPECT_TRUE(verdict({2.85, -135.0, -1.03, 0.0}).pot_made());
  EXPECT_FALSE(verdict({2.85, -135.0, -1.03, 0.0}).solves());
  // Away from every ball.
  const problems::Verdict none = verdict({1.0, 90.0, 0.0, 0.0});
  EXPECT_EQ(none.failure, problems::Failure::first_contact);
  EXPECT_NE(none.reason.find("strikes no ball"), std::string::npos) << none.reason;
  // At the blue first.
  const double to_blue = std::atan2(1.4 - 1.1, 2.0 - 1.1) * kDeg;
  const problems::Verdict blue = verdict({1.0, to_blue, 0.0, 0.0});
  EXPECT_EQ(blue.failure, problems::Failure::first_contact);
  EXPECT_NE(blue.reason.find("strikes blue first, not red"), std::string::npos) << blue.reason;
  // A thin touch on the red: it does not drop.
  const problems::Verdict thin = verdict({0.6, -135.0 + 2.0, 0.0, 0.0});
  EXPECT_EQ(thin.failure, problems::Failure::pot_missed);
  // With follow the cue ball runs after the red into the pocket.
  EXPECT_EQ(verdict({3.0, -135.0, 1.2, 0.0}).failure, problems::Failure::cue_ball_pocketed);
  // A stroke outside the limits is judged first.
  EXPECT_EQ(verdict({9.0, -135.0, 0.0, 0.0}).failure, problems::Failure::outside_limits);
}

// On a pot problem the spin map solves each spin's aim: every cell said to pot pots when
// struck at its aim, and a cell lands only if that stroke solves the problem.
TEST(PotSpinMapTest, EachSpinsAimKeepsThePot) {
  const problems::Problem p = shipped("pots/plant_two_balls.yaml");
  SpinMapOptions o;
  o.grid = 9;
  const SpinMap map = spin_map(p, 2.978, 23.75, o);
  ASSERT_FALSE(map.points.empty()) << map.message;
  int potting = 0;
  for (const SpinMapPoint& q : map.points) {
    const physics::Shot shot{map.speed, q.aim_deg, q.topspin_k, q.sidespin_k};
    const physics::ShotResult r = physics::simulate(p.scene, p.cue_ball, shot);
    EXPECT_EQ(q.lands, problems::check_stroke(p, shot, r).solves());
    if (!q.pots) continue;
    ++potting;
    EXPECT_TRUE(problems::makes_pot(p, r)) << q.topspin_k << ", " << q.sidespin_k;
    // The cue ball's direction (the cue's aim turned by the squirt) near the given aim:
    // a few tenths for the throw.
    const double squirt = physics::squirt_angle_deg(p.scene.cue, p.scene.ball_and_cushion.mass,
                                                    p.scene.radius(), q.sidespin_k);
    EXPECT_NEAR(q.aim_deg + squirt, 23.75, 1.0);
  }
  EXPECT_GT(potting, static_cast<int>(map.points.size()) / 2);
  EXPECT_EQ(map.not_potting, static_cast<int>(map.points.size()) - potting);
}

}  // namespace
}  // namespace cueplan::planner
