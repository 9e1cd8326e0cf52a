// Tests of the shot simulator against closed-form motion, symmetries of the table,
// energy, continuity and determinism.
#include "cueplan/physics/shot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "support/physics_checks.hpp"

namespace cueplan::physics {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A table without pockets, so long shots stay on the cloth.
Scene open_table() {
  Scene s;
  return s;
}

using test::kinetic_energy_of;

TEST(ShotSimulator, StunShotSlidesThenRollsAtFiveSevenths) {
  const Scene s = open_table();
  const double v = 0.4, g = s.cloth.gravity, mu = s.cloth.mu_slide, mr = s.cloth.mu_roll;
  const ShotResult r = simulate(s, {0.5, 0.889}, {v, 0.0, 0.0, 0.0});
  ASSERT_EQ(r.status, ShotStatus::rest) << r.message;
  ASSERT_GE(r.events.size(), 3u);
  const ShotEvent& roll = r.events[1];
  ASSERT_EQ(roll.type, EventType::slide_to_roll);
  // The slip v shrinks at 7/2 mu g: it vanishes at t = 2v / (7 mu g), at speed 5v/7,
  // after 12 v^2 / (49 mu g) of travel.
  EXPECT_NEAR(roll.time, 2 * v / (7 * mu * g), 1e-12);
  EXPECT_NEAR(roll.velocity.x, 5.0 * v / 7.0, 1e-12);
  EXPECT_NEAR(roll.position.x - 0.5, 12 * v * v / (49 * mu * g), 1e-12);
  // Then it rolls (5v/7)^2 / (2 mu_r g) further.
  const double rolled = std::pow(5 * v / 7, 2) / (2 * mr * g);
  EXPECT_NEAR(r.final_position.x, roll.position.x + rolled, 1e-9);
  EXPECT_EQ(r.cushion_hits, 0);
}

TEST(ShotSimulator, RollingBallStopsAfterClosedFormDistance) {
  const Scene s = open_table();
  for (double v : {0.2, 0.4, 0.6}) {
    const ShotResult r = simulate(s, {0.4, 0.5}, {v, 30.0, 1.0, 0.0});
    ASSERT_EQ(r.status, ShotStatus::rest) << r.message;
    const double d = v * v / (2 * s.cloth.mu_roll * s.cloth.gravity);
    EXPECT_NEAR(r.final_position.x, 0.4 + d * std::cos(30 * kDeg), 1e-9);
    EXPECT_NEAR(r.final_position.y, 0.5 + d * std::sin(30 * kDeg), 1e-9);
    EXPECT_NEAR(r.duration, v / (s.cloth.mu_roll * s.cloth.gravity), 1e-9);
  }
}

TEST(ShotSimulator, StraightHeadOnShotsStayOnTheirLine) {
  const Scene s = open_table();
  for (double aim : {0.0, 90.0, 180.0, 270.0}) {
    for (double kt : {-1.0, 0.0, 1.0, 2.0}) {
      const Vec2 start{s.length / 2, s.width / 2};
      const ShotResult r = simulate(s, start, {4.0, aim, kt, 0.0});
      ASSERT_EQ(r.status, ShotStatus::rest) << r.message;
      EXPECT_GE(r.cushion_hits, 1);
      if (aim == 0.0 || aim == 180.0)
        EXPECT_NEAR(r.final_position.y, start.y, 1e-12) << "aim " << aim << " k_T " << kt;
      else
        EXPECT_NEAR(r.final_position.x, start.x, 1e-12) << "aim " << aim << " k_T " << kt;
    }
  }
}

TEST(ShotSimulator, FrictionlessCushionMirrorsTheVelocityOnEveryCushion) {
  Scene s = open_table();
  s.ball_and_cushion.mu_cushion = 0.0;
  s.ball_and_cushion.mu_table = 0.0;  // at the cloth during the impact only
  s.ball_and_cushion.restitution = 1.0;
  // Aim at each cushion in turn, obliquely.
  for (double aim : {-60.0, 20.0, 70.0, 160.0}) {
    const ShotResult r = simulate(s, {1.8, 0.9}, {3.0, aim, 1.0, 0.5});
    ASSERT_EQ(r.status, ShotStatus::rest) << r.message;
    int checked = 0;
    for (size_t i = 1; i < r.events.size(); ++i) {
      const ShotEvent& e = r.events[i];
      if (e.type != EventType::cushion) continue;
      // Velocity just before: the path segment that ends at this event.
      const PathSegment* seg = nullptr;
      for (const PathSegment& p : r.path)
        if (std::abs(p.t1 - e.time) < 1e-12) seg = &p;
      ASSERT_NE(seg, nullptr);
      const double dt = seg->t1 - seg->t0;
      const Vec2 in{seg->v0.x + seg->accel.x * dt, seg->v0.y + seg->accel.y * dt};
      const bool across_x = e.cushion == 1 || e.cushion == 3;
      EXPECT_NEAR(e.velocity.x, across_x ? -in.x : in.x, 1e-9) << "cushion " << e.cushion;
      EXPECT_NEAR(e.velocity.y, across_x ? in.y : -in.y, 1e-9) << "cushion " << e.cushion;
      ++checked;
    }
    EXPECT_GE(checked, 1) << "aim " << aim;
  }
}

TEST(ShotSimulator, MirrorSymmetryOfTheTable) {
  const Scene s = snooker_scene();
  const Vec2 start{0.9, 0.6};
  for (const Shot& shot : {Shot{2.0, 25.0, 0.5, 0.8}, Shot{3.5, -40.0, -0.5, -1.0},
                           Shot{1.5, 100.0, 1.5, 0.0}}) {
    const ShotResult a = simulate(s, start, shot);
    // Across x = length / 2: aim -> 180 - aim, sidespin reverses.
    const ShotResult b = simulate(s, {s.length - start.x, start.y},
                                  {shot.speed, 180.0 - shot.aim_deg, shot.topspin_k,
                                   -shot.sidespin_k});
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.cushion_hits, b.cushion_hits);
    EXPECT_NEAR(b.final_position.x, s.length - a.final_position.x, 1e-8);
    EXPECT_NEAR(b.final_position.y, a.final_position.y, 1e-8);
    // Across y = width / 2: aim -> -aim, sidespin reverses.
    const ShotResult c = simulate(s, {start.x, s.width - start.y},
                                  {shot.speed, -shot.aim_deg, shot.topspin_k, -shot.sidespin_k});
    EXPECT_EQ(a.cushion_hits, c.cushion_hits);
    EXPECT_NEAR(c.final_position.x, a.final_position.x, 1e-8);
    EXPECT_NEAR(c.final_position.y, s.width - a.final_position.y, 1e-8);
  }
}

TEST(ShotSimulator, KineticEnergyNeverRisesAlongThePath) {
  const Scene s = snooker_scene();
  for (double aim = 0.0; aim < 360.0; aim += 23.0) {
    const ShotResult r = simulate(s, {1.0, 0.7}, {3.0, aim, 2.0 * std::sin(aim), 1.2});
    double last = INFINITY;
    for (const ShotEvent& e : r.events) {
      const double k = kinetic_energy_of(s, e.velocity, e.spin);
      EXPECT_LE(k, last * (1 + 1e-12)) << to_string(e.type) << " aim " << aim;
      last = k;
    }
  }
}

TEST(ShotSimulator, ResultsContinuousInTheShotAwayFromEvents) {
  const Scene s = open_table();
  const Shot base{2.5, 33.0, 0.4, 0.6};
  const ShotResult a = simulate(s, {0.7, 0.4}, base);
  for (double step : {1e-6, 1e-7}) {
    Shot nudged = base;
    nudged.aim_deg += step;
    nudged.speed += step;
    nudged.sidespin_k += step;
    const ShotResult b = simulate(s, {0.7, 0.4}, nudged);
    ASSERT_EQ(a.cushion_hits, b.cushion_hits);
    const double moved = std::hypot(b.final_position.x - a.final_position.x,
                                    b.final_position.y - a.final_position.y);
    EXPECT_LT(moved, 100 * step) << "step " << step;
  }
}

TEST(ShotSimulator, SameInputBitIdenticalOutput) {
  const Scene s = snooker_scene();
  const Shot shot{2.7, 12.3, 1.1, -0.7};
  const ShotResult a = simulate(s, {0.8, 0.5}, shot);
  const ShotResult b = simulate(s, {0.8, 0.5}, shot);
  ASSERT_EQ(a.events.size(), b.events.size());
  EXPECT_EQ(std::memcmp(&a.final_position, &b.final_position, sizeof a.final_position), 0);
  for (size_t i = 0; i < a.events.size(); ++i) {
    EXPECT_EQ(a.events[i].time, b.events[i].time);
    EXPECT_EQ(a.events[i].position.x, b.events[i].position.x);
    EXPECT_EQ(a.events[i].position.y, b.events[i].position.y);
  }
}

TEST(ShotSimulator, StraightIntoACornerPocketIsPocketed) {
  const Scene s = snooker_scene();
  const ShotResult r = simulate(s, {0.5, 0.5}, {2.0, 225.0, 1.0, 0.0});
  EXPECT_EQ(r.status, ShotStatus::pocketed);
  ASSERT_EQ(r.events.back().type, EventType::pocket);
  EXPECT_EQ(r.events.back().index, 0);
  const Vec2 p = r.events.back().position;
  EXPECT_NEAR(std::hypot(p.x, p.y), s.pockets[0].radius, 1e-9);
}

TEST(ShotSimulator, ObstacleOnTheLineIsHitAtTwoRadii) {
  Scene s = open_table();
  s.obstacles = {{1.5, 0.5}};
  const ShotResult r = simulate(s, {0.8, 0.5}, {1.5, 0.0, 0.0, 0.0});
  EXPECT_EQ(r.status, ShotStatus::hit_obstacle);
  EXPECT_NEAR(r.final_position.x, 1.5 - 2 * s.radius(), 1e-9);
  // A scene whose obstacle is off the line is not hit.
  s.obstacles = {{1.5, 0.5 + 2.01 * s.radius()}};
  EXPECT_EQ(simulate(s, {0.8, 0.5}, {1.5, 0.0, 0.0, 0.0}).status, ShotStatus::rest);
}

TEST(ShotSimulator, BadInputNamesTheField) {
  Scene s = open_table();
  // The field that is wrong, as data, and the same in the message.
  const auto field_of = [](const ShotResult& r) {
    EXPECT_EQ(r.status, ShotStatus::invalid_input);
    EXPECT_TRUE(r.error.has_value());
    if (r.error) {
      EXPECT_EQ(r.message, r.error->message());
    }
    return r.error ? r.error->field : FieldPath{};
  };
  EXPECT_EQ(field_of(simulate(s, {-0.1, 0.5}, {})), FieldPath{"cue_ball"});
  EXPECT_EQ(field_of(simulate(s, {0.5, 0.5}, {NAN, 0, 0, 0})), (FieldPath{"shot", "speed"}));
  EXPECT_EQ(field_of(simulate(s, {0.5, 0.5}, {-1, 0, 0, 0})), (FieldPath{"shot", "speed"}));
  EXPECT_EQ(field_of(simulate(s, {0.5, 0.5}, {1, NAN, 0, 0})), (FieldPath{"shot", "aim_deg"}));
  SimulationOptions no_events;
  no_events.max_events = 0;
  EXPECT_EQ(field_of(simulate(s, {0.5, 0.5}, {}, no_events)), FieldPath{"max_events"});
  s.length = -2.0;
  EXPECT_EQ(field_of(simulate(s, {0.5, 0.5}, {})), FieldPath{"length"});
  s = open_table();
  s.cloth.mu_roll = 0.0;
  EXPECT_EQ(field_of(simulate(s, {0.5, 0.5}, {})), (FieldPath{"cloth", "mu_roll"}));
  s = open_table();
  s.ball_and_cushion.mass = -1.0;
  EXPECT_EQ(field_of(simulate(s, {0.5, 0.5}, {})), (FieldPath{"ball_and_cushion", "mass"}));
  s = open_table();
  s.obstacles = {{0.51, 0.5}};
  const ShotResult r = simulate(s, {0.5, 0.5}, {});
  EXPECT_EQ(field_of(r), FieldPath{"cue_ball"});
  ASSERT_TRUE(r.error && r.error->other);
  EXPECT_EQ(*r.error->other, (FieldPath{"obstacles", 0}));
  EXPECT_NE(r.message.find("overlaps obstacles[0]"), std::string::npos) << r.message;
}

TEST(ShotSimulator, CompiledSceneIsCheckedOnceAndGivesTheSameShots) {
  Scene s = open_table();
  s.obstacles = {{2.5, 1.2}};
  const CompiledScene compiled(s);
  ASSERT_TRUE(compiled.ok());
  const Shot shot{2.2, 37.0, 0.4, -0.6};
  const ShotResult a = simulate(compiled, {0.9, 0.6}, shot);
  const ShotResult b = simulate(s, {0.9, 0.6}, shot);
  ASSERT_EQ(a.status, ShotStatus::rest);
  EXPECT_EQ(a.final_position.x, b.final_position.x);
  EXPECT_EQ(a.final_position.y, b.final_position.y);
  EXPECT_EQ(a.events.size(), b.events.size());
  // An unusable scene compiles to its error, and every simulation of it reports it.
  s.width = std::nan("");
  const CompiledScene broken(s);
  ASSERT_FALSE(broken.ok());
  EXPECT_EQ(broken.error()->field, FieldPath{"width"});
  const ShotResult r = simulate(broken, {0.9, 0.6}, shot);
  EXPECT_EQ(r.status, ShotStatus::invalid_input);
  EXPECT_EQ(r.error->field, FieldPath{"width"});
}

TEST(ShotSimulator, BallPressedIntoACushionNeverPassesIt) {
  // A ball touching cushion 1 is struck away from it, slowly and with strong draw and
  // sidespin: friction on the cloth brings it back, and the bounces shrink until
  // rounding leaves no approach speed while friction still presses it in. (Found by
  // tests/stress: the ball used to slide through the cushion line.)
  Scene s;
  s.ball_and_cushion.mass = 0.44756117091267494;
  s.ball_and_cushion.radius = 0.052967668150026403;
  s.ball_and_cushion.cushion_height = 0.074154735410036962;
  s.ball_and_cushion.mu_cushion = 0.041673810263415004;
  s.ball_and_cushion.mu_table = 0.10542796027394329;
  s.ball_and_cushion.restitution = 0.4375778233307076;
  s.length = 0.20743495229725895;
  s.width = 0.28078497030525806;
  s.obstacles = {{0.048545669736559514, 0.079323252473017053}};
  const Shot away{0.000854227200685668, -149.29294200792324, -20.0, -15.867214661462407};
  const ShotResult r = simulate(s, {s.length - s.contact_offset(), 0.1302956509535601}, away);
  EXPECT_GE(r.cushion_hits, 10);
  EXPECT_LE(test::audit_path(s, r).max_outside, 1e-12);
  EXPECT_EQ(r.status, ShotStatus::impact_failed);
  EXPECT_NE(r.message.find("pressed"), std::string::npos) << r.message;
}

// The same ball rolling along the cushion it touches, its approach speed only the
// rounding of cos(90 deg), with nothing pressing it in: it rolls on to rest.
TEST(ShotSimulator, BallRollingAlongACushionItTouchesIsNotPressed) {
  const Scene s = open_table();
  const Vec2 on_line{s.length - s.contact_offset(), 0.5};
  const ShotResult r = simulate(s, on_line, {0.5, 90.0, 1.0, 0.0});
  EXPECT_EQ(r.status, ShotStatus::rest) << r.message;
  EXPECT_NEAR(r.final_position.x, on_line.x, 1e-12);
  EXPECT_GT(r.final_position.y, on_line.y + 0.1);
}

TEST(ShotSimulator, EventCapEndsWithAClearStatus) {
  const Scene s = open_table();
  SimulationOptions o;
  o.max_events = 3;
  const ShotResult r = simulate(s, {0.5, 0.5}, {4.0, 10.0, 0.0, 2.0}, o);
  EXPECT_EQ(r.status, ShotStatus::event_limit);
  EXPECT_FALSE(r.message.empty());
}

}  // namespace
}  // namespace cueplan::physics

namespace cueplan::physics {
namespace {

TEST(ShotSimulator, ChosenImpactMethodIsReportedAndFollowsTheOptions) {
  const Scene s = open_table();
  SimulationOptions o;
  EXPECT_EQ(chosen_impact_method(s, o), ImpactMethod::exact);
  o.impact_method = ImpactMethod::paper;
  EXPECT_EQ(chosen_impact_method(s, o), ImpactMethod::paper);
  const ShotResult r = simulate(s, {0.5, 0.5}, {2.0, 20.0, 1.0, 0.0}, o);
  EXPECT_EQ(r.impact_method, ImpactMethod::paper);
  EXPECT_EQ(r.table_impacts, 0);
  // Asking for the table without one falls back to exact rather than failing.
  o.impact_method = ImpactMethod::table;
  EXPECT_EQ(chosen_impact_method(s, o), ImpactMethod::exact);
}

// The default impact accuracy (exact at a tenth of it) against a converged run of the
// other exact method (extrapolation at 1e-14): one-, two- and three-cushion shots end
// in the same place to within a nanometre (measured: 6e-11 m; an impact accuracy of
// 1e-7 instead of 1e-9 moves them by 1.5e-8 m).
TEST(ShotSimulator, DefaultImpactAccuracyAgreesWithAConvergedSimulation) {
  const Scene s = open_table();
  SimulationOptions converged;
  converged.impact_method = ImpactMethod::extrapolation;
  converged.impact_accuracy = 1e-12;
  for (const Shot& shot : {Shot{0.70, 60.0, 0.5, 0.0}, Shot{0.90, 30.0, 1.0, 0.5},
                           Shot{1.72, 15.0, 1.0, 1.0}, Shot{2.5, 33.0, 0.4, 0.6},
                           Shot{3.0, -70.0, -1.5, -1.0}}) {
    const ShotResult a = simulate(s, {0.8, 0.5}, shot);
    const ShotResult b = simulate(s, {0.8, 0.5}, shot, converged);
    ASSERT_EQ(a.status, ShotStatus::rest);
    ASSERT_EQ(a.cushion_hits, b.cushion_hits) << "speed " << shot.speed;
    EXPECT_GE(a.cushion_hits, 1);
    EXPECT_LT(std::hypot(a.final_position.x - b.final_position.x,
                         a.final_position.y - b.final_position.y),
              1e-9)
        << "speed " << shot.speed << " aim " << shot.aim_deg;
  }
}

}  // namespace
}  // namespace cueplan::physics
