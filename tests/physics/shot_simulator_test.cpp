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

// ---- Several balls on the table (PHYSICS.md, "Several balls on the table") ----------

namespace cueplan::physics {
namespace {

constexpr double kTieWindow = 1e-12;  // s, PHYSICS.md's window for simultaneous events

Scene with_balls(Scene s, std::vector<ObjectBall> balls) {
  s.balls = std::move(balls);
  return s;
}

double distance(Vec2 a, Vec2 b) { return std::hypot(a.x - b.x, a.y - b.y); }

// A stroke along +x that arrives `travel` m further on at speed `arrival` with no spin
// at all (a stun at contact), in closed form: with draw k_T < 0 the slip u = V (1 - k_T)
// points forward while sliding, so v falls at mu_s g and w_y rises at 5 mu_s g / (2R);
// w_y reaches zero at t_c = -2 k_T V / (5 mu_s g), when the ball has gone
// V t_c - mu_s g t_c^2 / 2 at speed V - mu_s g t_c (and it still slides: k_T > -2.5).
Shot stun_on_arrival(const Scene& s, double arrival, double travel) {
  const double a = s.cloth.mu_slide * s.cloth.gravity;
  const double t = (-arrival + std::sqrt(arrival * arrival + 2.0 * a * travel)) / a;
  const double v = arrival + a * t;
  return {v, 0.0, -2.5 * a * t / v, 0.0};
}

// Where a ball that leaves at speed v along +x with no spin comes to rest: it slides
// 12 v^2 / (49 mu_s g), then rolls (5 v / 7)^2 / (2 mu_r g) (PHYSICS.md).
double stun_travel(const Scene& s, double v) {
  const double g = s.cloth.gravity;
  return 12.0 * v * v / (49.0 * s.cloth.mu_slide * g) +
         std::pow(5.0 * v / 7.0, 2) / (2.0 * s.cloth.mu_roll * g);
}

// The event of `ball` that is its contact with `other`, the n-th such (from 0).
const ShotEvent* contact_event(const BallOutcome& ball, int other, int nth = 0) {
  for (const ShotEvent& e : ball.events)
    if (e.type == EventType::ball_contact && e.other == other && nth-- == 0) return &e;
  return nullptr;
}

// The path segment of a ball that ends at time t.
const PathSegment* segment_ending(const BallOutcome& ball, double t) {
  for (const PathSegment& p : ball.path)
    if (p.t1 == t) return &p;
  return nullptr;
}

TEST(ShotSimulatorBalls, EventsWithinAPicosecondComeInTheContractsOrder) {
  // A rolling ball sent head-on at the end cushion with just the sidespin that runs out
  // as it arrives (closed form: it rolls d = V t - mu_r g t^2 / 2; w_z falls at
  // 5 mu_sp g / (2R)): the cushion and the spin stop fall within 1e-12 s of each other,
  // in either order or at once, and the cushion, the earlier kind, comes first.
  const Scene s = open_table();
  const double a = s.cloth.mu_roll * s.cloth.gravity;
  const double spin_decel = 2.5 * s.cloth.mu_spin * s.cloth.gravity / s.radius();
  const Vec2 start{2.0, 0.889};
  const double d = s.length - s.contact_offset() - start.x;
  int checked = 0;
  for (double v : {0.6, 0.75, 0.9, 1.1, 1.3}) {
    const double t = (v - std::sqrt(v * v - 2.0 * a * d)) / a;
    for (double offset : {-5e-13, -1e-13, 0.0, 1e-13, 5e-13}) {
      const double ks = spin_decel * (t + offset) * s.radius() / v;
      // The cue aimed off +x by the squirt, so that the ball runs along +x.
      const double aim = -squirt_angle_deg(s.cue, s.ball_and_cushion.mass, s.radius(), ks);
      const ShotResult r = simulate(s, start, {v, aim, 1.0, ks});
      ASSERT_GE(r.events.size(), 3u);
      EXPECT_EQ(r.events[1].type, EventType::cushion) << "v " << v << " offset " << offset;
      EXPECT_NEAR(r.events[1].time, t, 1e-9);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 25);
}

TEST(ShotSimulatorBalls, UntouchedObjectBallsLeaveTheCueBallsShotBitIdentical) {
  // Balls far from the cue ball's path change nothing it does: its events are found as
  // if they were not there.
  const Scene bare = snooker_scene();
  const Scene crowded =
      with_balls(bare, {{"red", {3.2, 0.2}}, {"blue", {1.7845, 0.889}}, {"pink", {0.2, 1.6}}});
  for (const Shot& shot : {Shot{1.002, -60.36, 0.8, 0.0}, Shot{2.0, 20.0, -0.4, 0.7}}) {
    const ShotResult a = simulate(bare, {0.9, 1.2}, shot);
    const ShotResult b = simulate(crowded, {0.9, 1.2}, shot);
    ASSERT_EQ(b.first_contact, -1);
    ASSERT_EQ(a.events.size(), b.events.size());
    EXPECT_EQ(std::memcmp(&a.final_position, &b.final_position, sizeof a.final_position), 0);
    for (size_t i = 0; i < a.events.size(); ++i) {
      EXPECT_EQ(a.events[i].time, b.events[i].time) << i;
      EXPECT_EQ(a.events[i].position.x, b.events[i].position.x) << i;
      EXPECT_EQ(a.events[i].velocity.y, b.events[i].velocity.y) << i;
      EXPECT_EQ(a.events[i].spin.z, b.events[i].spin.z) << i;
    }
    ASSERT_EQ(b.balls.size(), 4u);
    for (size_t k = 1; k < b.balls.size(); ++k) {
      EXPECT_TRUE(b.balls[k].events.empty()) << b.balls[k].name;
      EXPECT_EQ(b.balls[k].final_position.x, crowded.balls[k - 1].position.x);
      EXPECT_EQ(b.balls[k].final_position.y, crowded.balls[k - 1].position.y);
    }
  }
}

TEST(ShotSimulatorBalls, OutcomesListTheCueBallFirstThenTheObjectBalls) {
  const Scene s = with_balls(snooker_scene(), {{"red", {1.5, 0.5}}, {"black", {3.0, 1.5}}});
  const ShotResult r = simulate(s, {0.8, 0.5}, {1.5, 0.0, 1.0, 0.0});
  ASSERT_EQ(r.balls.size(), 3u);
  EXPECT_EQ(r.balls[0].name, "cue");
  EXPECT_EQ(r.balls[1].name, "red");
  EXPECT_EQ(r.balls[2].name, "black");
  EXPECT_EQ(r.balls[0].start.x, 0.8);
  EXPECT_EQ(r.balls[1].start.x, 1.5);
  // The cue ball's record is the top-level one.
  EXPECT_EQ(r.balls[0].events.size(), r.events.size());
  EXPECT_EQ(r.balls[0].path.size(), r.path.size());
  EXPECT_EQ(r.balls[0].final_position.x, r.final_position.x);
  EXPECT_EQ(r.balls[0].cushion_hits, r.cushion_hits);
  EXPECT_EQ(r.first_contact, 1);
  for (const BallOutcome& b : r.balls)
    for (const ShotEvent& e : b.events) EXPECT_EQ(&b - r.balls.data(), e.ball);
}

TEST(ShotSimulatorBalls, FullBallStunStopsTheCueBallDeadAndSendsTheObjectBallOn) {
  // mu_ball = 0, e = 1: a head-on hit by a cue ball with no spin exchanges the
  // velocities, so the cue ball stops where it met the object ball, and the object ball
  // slides and rolls off as a stun shot of that speed would (closed form).
  for (BallModel model : {BallModel::mathavan_2014, BallModel::frictional_inelastic}) {
    Scene s = open_table();
    s.ball_contact.mu_ball = 0.0;
    s.ball_contact.restitution = 1.0;
    s.ball_contact.model = model;
    const double arrival = 0.8, travel = 0.6, r = s.radius();
    const Vec2 cue{0.5, 0.889};
    const Vec2 red{cue.x + travel + 2.0 * r, cue.y};
    s.balls = {{"red", red}};
    const ShotResult out = simulate(s, cue, stun_on_arrival(s, arrival, travel));
    ASSERT_EQ(out.status, ShotStatus::rest) << out.message;
    const ShotEvent* hit = contact_event(out.balls[0], 1);
    ASSERT_NE(hit, nullptr);
    EXPECT_NEAR(hit->position.x, cue.x + travel, 1e-9);
    // Exactly the cue ball's arrival state went into the object ball.
    const ShotEvent* struck = contact_event(out.balls[1], 0);
    ASSERT_NE(struck, nullptr);
    EXPECT_NEAR(struck->velocity.x, arrival, 1e-8 * arrival) << to_string(model);
    EXPECT_NEAR(struck->velocity.y, 0.0, 1e-12);
    EXPECT_NEAR(std::hypot(hit->velocity.x, hit->velocity.y), 0.0, 1e-8 * arrival);
    EXPECT_NEAR(out.final_position.x, cue.x + travel, 1e-9);
    EXPECT_NEAR(out.final_position.y, cue.y, 1e-12);
    EXPECT_NEAR(out.balls[1].final_position.x, red.x + stun_travel(s, arrival), 1e-6);
    EXPECT_NEAR(out.balls[1].final_position.y, red.y, 1e-12);
    EXPECT_EQ(out.first_contact, 1);
  }
}

TEST(ShotSimulatorBalls, StraightPotIntoACornerWithTheDefaults) {
  // The object ball on the diagonal to the bottom-left corner, the cue ball behind it on
  // the same line, a stun stroke: the object ball drops into bottom_left (pocket 0) and
  // the cue ball stays on the table near where it struck.
  const Scene s = with_balls(snooker_scene(), {{"red", {0.6, 0.6}}});
  const double d = 0.5;  // m from the cue ball's centre to the contact, along the diagonal
  const double step = (d + 2.0 * s.radius()) / std::sqrt(2.0);
  const Vec2 cue{0.6 + step, 0.6 + step};
  Shot shot = stun_on_arrival(s, 1.2, d);
  shot.aim_deg = 225.0;
  const ShotResult r = simulate(s, cue, shot);
  ASSERT_EQ(r.status, ShotStatus::rest) << r.message;
  EXPECT_EQ(r.first_contact, 1);
  EXPECT_TRUE(r.balls[1].pocketed);
  EXPECT_EQ(r.balls[1].pocket, 0);
  ASSERT_FALSE(r.balls[1].events.empty());
  EXPECT_EQ(r.balls[1].events.back().type, EventType::pocket);
  // A stun with e = 0.89 leaves the cue ball (1 - e) / 2 of its speed: it creeps on a
  // little and stops short of the object ball's spot.
  EXPECT_LT(distance(r.final_position, {0.6, 0.6}), 2.0 * s.radius());
  EXPECT_FALSE(r.balls[0].pocketed);
}

TEST(ShotSimulatorBalls, ABallSentIntoACushionComesBackIntoTheCueBall) {
  // A stun sends the red to the end cushion x = L; it comes straight back and strikes
  // the cue ball, which had stopped on the line: everything stays on y = 0.889, and the
  // second contact comes when the red, rolling back from its last event, has closed the
  // distance to 2R (its motion solved in closed form here).
  const Scene base = open_table();
  const Vec2 cue{0.5, 0.889};
  const double travel = 0.7;
  const Scene s = with_balls(base, {{"red", {cue.x + travel + 2.0 * base.radius(), cue.y}}});
  const ShotResult r = simulate(s, cue, stun_on_arrival(s, 2.2, travel));
  ASSERT_EQ(r.status, ShotStatus::rest) << r.message;
  const BallOutcome& red = r.balls[1];
  ASSERT_NE(contact_event(red, 0, 0), nullptr);
  const ShotEvent* back = contact_event(red, 0, 1);
  ASSERT_NE(back, nullptr) << "the red never came back to the cue ball";
  // Between the contacts: the red met cushion 1 (x = L); the cue ball came to rest.
  bool cushion = false;
  const ShotEvent* last_before = nullptr;
  for (const ShotEvent& e : red.events) {
    if (e.time >= back->time) break;
    cushion = cushion || (e.type == EventType::cushion && e.cushion == 1);
    last_before = &e;
  }
  EXPECT_TRUE(cushion);
  const ShotEvent* cue_back = contact_event(r.balls[0], 1, 1);
  ASSERT_NE(cue_back, nullptr);
  const ShotEvent& cue_rest = *(cue_back - 1);
  ASSERT_EQ(cue_rest.type, EventType::rest);
  EXPECT_EQ(cue_back->time, back->time);
  EXPECT_NEAR(distance(back->position, cue_back->position), 2.0 * s.radius(), 1e-9);
  for (const BallOutcome& b : r.balls)
    for (const ShotEvent& e : b.events)
      EXPECT_NEAR(e.position.y, cue.y, 1e-12) << to_string(e.type);
  // The red rolls back from its last event: x(t) = x0 + v0 t + a t^2 / 2 with a the
  // rolling resistance against v0; it meets the cue ball when x = cue_rest.x + 2R.
  ASSERT_NE(last_before, nullptr);
  ASSERT_EQ(last_before->type, EventType::slide_to_roll);
  const double v0 = last_before->velocity.x;  // < 0, toward the cue ball
  ASSERT_LT(v0, 0.0);
  const double a = s.cloth.mu_roll * s.cloth.gravity;  // decelerates: +a against -x motion
  const double gap = cue_rest.position.x + 2.0 * s.radius() - last_before->position.x;  // < 0
  const double t = (-v0 - std::sqrt(v0 * v0 + 2.0 * a * gap)) / a;  // root of a t^2/2 + v0 t = gap
  EXPECT_NEAR(back->time, last_before->time + t, 1e-9);
  // After it the cue ball moves off toward x = 0.
  EXPECT_LT(cue_back->velocity.x, 0.0);
}

TEST(ShotSimulatorBalls, MomentumAndEnergyAcrossEveryCollision) {
  // A rolling cue ball (k_T = 1 from the start, no sidespin) cuts an object ball at rest:
  // its state at contact is known from its path (velocity, spin = rolling). The closed
  // form keeps the total momentum (its friction is between the balls); with
  // mathavan_2014 and mu_ball = 0 nothing but the normal impulse acts, which keeps it
  // too; no collision adds kinetic energy.
  struct Case {
    const char* name;
    BallModel model;
    double mu_ball;
  };
  for (const Case& c : {Case{"closed_form", BallModel::frictional_inelastic, 0.05},
                        Case{"mathavan_frictionless", BallModel::mathavan_2014, 0.0},
                        Case{"mathavan", BallModel::mathavan_2014, 0.05}}) {
    for (double cut_offset : {0.0, 0.3, 0.8, 1.5}) {
      Scene s = open_table();
      s.ball_contact.model = c.model;
      s.ball_contact.mu_ball = c.mu_ball;
      s.balls = {{"red", {1.6, 0.9 + cut_offset * s.radius()}}};
      const ShotResult r = simulate(s, {0.6, 0.9}, {1.3, 0.0, 1.0, 0.0});
      ASSERT_EQ(r.status, ShotStatus::rest) << r.message;
      const ShotEvent* after_cue = contact_event(r.balls[0], 1);
      const ShotEvent* after_red = contact_event(r.balls[1], 0);
      ASSERT_TRUE(after_cue && after_red) << c.name;
      const PathSegment* in = segment_ending(r.balls[0], after_cue->time);
      ASSERT_NE(in, nullptr);
      const double dt = in->t1 - in->t0;
      const Vec2 v{in->v0.x + in->accel.x * dt, in->v0.y + in->accel.y * dt};
      ASSERT_EQ(in->motion, Motion::rolling);
      const Vec3 w{-v.y / s.radius(), v.x / s.radius(), 0.0};
      const double m = s.ball_and_cushion.mass;
      const Vec2 p_before = {m * v.x, m * v.y};
      const Vec2 p_after = {m * (after_cue->velocity.x + after_red->velocity.x),
                            m * (after_cue->velocity.y + after_red->velocity.y)};
      const double e_before = test::kinetic_energy_of(s, v, w);
      const double e_after = test::kinetic_energy_of(s, after_cue->velocity, after_cue->spin) +
                             test::kinetic_energy_of(s, after_red->velocity, after_red->spin);
      EXPECT_LE(e_after, e_before * (1 + 1e-9)) << c.name << " offset " << cut_offset;
      if (std::string(c.name) != "mathavan") {
        EXPECT_NEAR(p_after.x, p_before.x, 1e-8 * m * 1.3) << c.name << " offset " << cut_offset;
        EXPECT_NEAR(p_after.y, p_before.y, 1e-8 * m * 1.3) << c.name << " offset " << cut_offset;
      }
      // The event's impulse is the normal impulse along the line of centres: the object
      // ball at rest leaves with J / M along it.
      const Vec2 n{(after_red->position.x - after_cue->position.x) / (2.0 * s.radius()),
                   (after_red->position.y - after_cue->position.y) / (2.0 * s.radius())};
      if (c.mu_ball == 0.0) {
        const double along = after_red->velocity.x * n.x + after_red->velocity.y * n.y;
        EXPECT_NEAR(after_red->impulse / m, along, 1e-8) << cut_offset;
      }
    }
  }
}

// The mirror image of a scene across y = width / 2.
Scene mirrored(Scene s) {
  for (ObjectBall& b : s.balls) b.position.y = s.width - b.position.y;
  for (Vec2& o : s.obstacles) o.y = s.width - o.y;
  return s;
}

TEST(ShotSimulatorBalls, MirrorSymmetryOfAWholeMultiBallShot) {
  // Across y = W/2: positions y -> W - y, aim -> -aim, sidespin reverses; every ball's
  // outcome mirrors (pockets: bottom <-> top, index k <-> k + 3).
  const Scene s = with_balls(snooker_scene(), {{"red", {1.5, 0.62}},
                                               {"yellow", {2.1, 0.75}},
                                               {"green", {2.6, 1.2}},
                                               {"brown", {1.0, 1.3}}});
  const Vec2 cue{0.7, 0.5};
  // The cue ball's directions 12, 11 and 12 deg: the cue aimed off them by the squirt.
  const auto squirt = [&](double k) {
    return squirt_angle_deg(s.cue, s.ball_and_cushion.mass, s.radius(), k);
  };
  for (const Shot& shot : {Shot{2.5, 12.0 - squirt(0.5), 0.6, 0.5},
                           Shot{3.0, 11.0 - squirt(-0.5), -0.5, -0.5},
                           Shot{2.2, 12.0 - squirt(0.8), 0.2, 0.8}}) {
    const ShotResult a = simulate(s, cue, shot);
    const ShotResult b = simulate(mirrored(s), {cue.x, s.width - cue.y},
                                  {shot.speed, -shot.aim_deg, shot.topspin_k, -shot.sidespin_k});
    ASSERT_EQ(a.status, b.status) << a.message;
    ASSERT_GE(a.first_contact, 1) << "the cue ball must strike a ball";
    EXPECT_EQ(a.first_contact, b.first_contact);
    int moved = 0;
    for (size_t k = 0; k < a.balls.size(); ++k) {
      const BallOutcome &x = a.balls[k], &y = b.balls[k];
      EXPECT_EQ(x.events.size(), y.events.size()) << x.name;
      EXPECT_EQ(x.cushion_hits, y.cushion_hits) << x.name;
      EXPECT_EQ(x.pocketed, y.pocketed) << x.name;
      if (x.pocketed) {
        EXPECT_EQ(y.pocket, (x.pocket + 3) % 6) << x.name;
      }
      EXPECT_NEAR(y.final_position.x, x.final_position.x, 1e-8) << x.name;
      EXPECT_NEAR(y.final_position.y, s.width - x.final_position.y, 1e-8) << x.name;
      moved += x.events.empty() ? 0 : 1;
    }
    EXPECT_GE(moved, 3) << "the shot must move at least two object balls";
  }
}

// Every event of every ball, bit for bit.
bool same_events(const ShotResult& a, const ShotResult& b) {
  if (a.balls.size() != b.balls.size()) return false;
  for (size_t k = 0; k < a.balls.size(); ++k) {
    const auto& x = a.balls[k].events;
    const auto& y = b.balls[k].events;
    if (x.size() != y.size()) return false;
    for (size_t i = 0; i < x.size(); ++i)
      if (x[i].type != y[i].type || std::memcmp(&x[i].time, &y[i].time, sizeof(double)) != 0 ||
          std::memcmp(&x[i].position, &y[i].position, sizeof(Vec2)) != 0 ||
          std::memcmp(&x[i].velocity, &y[i].velocity, sizeof(Vec2)) != 0 ||
          std::memcmp(&x[i].spin, &y[i].spin, sizeof(Vec3)) != 0 || x[i].other != y[i].other)
        return false;
  }
  return true;
}

TEST(ShotSimulatorBalls, SameInputBitIdenticalOutput) {
  const Scene s = with_balls(
      snooker_scene(), {{"red", {1.5, 0.62}}, {"yellow", {2.1, 0.75}}, {"green", {2.6, 1.2}}});
  const CompiledScene compiled(s);
  const Shot shot{2.5, 8.0, 0.6, 0.5};
  const ShotResult a = simulate(compiled, {0.7, 0.5}, shot);
  const ShotResult b = simulate(compiled, {0.7, 0.5}, shot);
  const ShotResult c = simulate(s, {0.7, 0.5}, shot);
  EXPECT_TRUE(same_events(a, b));
  EXPECT_TRUE(same_events(a, c));
}

TEST(ShotSimulatorBalls, SimultaneousContactsAreTakenLowerIndexFirst) {
  // The cue ball runs straight between two balls placed symmetrically about its line and
  // meets both at one instant (to rounding): the contact with the lower index comes
  // first, whichever side that ball lies on, and both are resolved in turn.
  const Scene base = open_table();
  const double r = base.radius();
  const Vec2 cue{0.8, 0.889};
  const Vec2 left{1.6, cue.y + r}, right{1.6, cue.y - r};
  for (bool left_first : {true, false}) {
    const Scene s =
        with_balls(base, left_first ? std::vector<ObjectBall>{{"a", left}, {"b", right}}
                                    : std::vector<ObjectBall>{{"a", right}, {"b", left}});
    const ShotResult out = simulate(s, cue, {1.4, 0.0, 1.0, 0.0});
    ASSERT_EQ(out.status, ShotStatus::rest) << out.message;
    EXPECT_EQ(out.first_contact, 1);
    const ShotEvent* first = contact_event(out.balls[0], 1);
    const ShotEvent* second = contact_event(out.balls[0], 2);
    ASSERT_TRUE(first && second);
    EXPECT_LT(first, second);  // in the cue ball's events, in this order
    EXPECT_LE(second->time - first->time, kTieWindow);
    // Both balls were struck and move off on their own sides of the line.
    EXPECT_GT(std::abs(out.balls[1].final_position.y - s.balls[0].position.y), 0.01);
    EXPECT_GT(std::abs(out.balls[2].final_position.y - s.balls[1].position.y), 0.01);
  }
}

TEST(ShotSimulatorBalls, TouchingBallsAtRestDoNotCollide) {
  // Two balls touching (centres exactly 2R apart) while the cue ball plays elsewhere,
  // then a third ball touching the cue ball's target: nothing moves that is not struck.
  const Scene base = snooker_scene();
  const double r = base.radius();
  const Scene s = with_balls(
      base, {{"red", {2.0, 1.2}}, {"blue", {2.0 + 2.0 * r, 1.2}}, {"pink", {2.0, 1.2 + 2.0 * r}}});
  const ShotResult out = simulate(s, {0.8, 0.4}, {1.0, 10.0, 1.0, 0.0});
  ASSERT_EQ(out.status, ShotStatus::rest) << out.message;
  EXPECT_EQ(out.first_contact, -1);
  for (size_t k = 1; k < out.balls.size(); ++k) {
    EXPECT_TRUE(out.balls[k].events.empty()) << out.balls[k].name;
    EXPECT_EQ(out.balls[k].final_position.x, out.balls[k].start.x);
    EXPECT_EQ(out.balls[k].final_position.y, out.balls[k].start.y);
  }
  // A cue ball that starts touching a ball and is struck away from it leaves it alone.
  const Scene t = with_balls(base, {{"red", {1.0 + 2.0 * r, 0.8}}});
  const ShotResult away = simulate(t, {1.0, 0.8}, {1.0, 180.0, 0.0, 0.0});
  EXPECT_EQ(away.first_contact, -1);
  EXPECT_TRUE(away.balls[1].events.empty());
}

TEST(ShotSimulatorBalls, ACueBallTouchingABallAndStruckIntoItStrikesItAtOnce) {
  // Touching the red (centres 2R apart, to rounding) and struck into it with so much
  // draw and side that its sliding path, had it passed through the red, would curve back
  // into it: the contact is at the strike. (Found by tests/stress: the search took that
  // later crossing, and the cue ball passed through the ball it touched.)
  const Scene base = open_table();
  const Vec2 cue{1.7189536803862029, 0.27281055635889884};
  const Scene s = with_balls(base, {{"red", {1.770333613125048, 0.28359723850642415}}});
  ASSERT_NEAR(distance(cue, s.balls[0].position), 2.0 * base.radius(), 1e-15);
  const ShotResult out =
      simulate(s, cue, {2.5726842885268324, 33.705710236601703, -11.690763779515461, 20.0});
  ASSERT_GE(out.events.size(), 2u);
  EXPECT_EQ(out.events[1].type, EventType::ball_contact);
  EXPECT_EQ(out.events[1].other, 1);
  EXPECT_LT(out.events[1].time, 1e-12);
  EXPECT_EQ(out.first_contact, 1);
}

TEST(ShotSimulatorBalls, BallsPressedTogetherEndTheShotWithAClearStatus) {
  // A slow follow stroke into a line of three small balls: each contact leaves the cue
  // ball pushing again, in ever smaller contacts, until they touch with no approach speed
  // left and friction presses them together - a push, which is not modelled (as a ball
  // pressed into a cushion is not). The balls never overlap on the way. (Found by
  // tests/stress.)
  Scene s = snooker_scene();
  CushionParams& p = s.ball_and_cushion;
  p.mass = 0.36062119036811202;
  p.radius = 0.0074285252134941261;
  p.cushion_height = 0.010399935298891777;
  p.mu_cushion = 0.0;
  p.mu_table = 0.069609172366957267;
  p.restitution = 0.70161242557227022;
  s.pockets = standard_pockets(s.length, s.width, 0.012628492862940014);
  s.ball_contact = {0.099583784507537021, 0.35955239409947637, BallModel::frictional_inelastic,
                    BallFriction::speed_dependent};
  s.balls = {{"b0", {1.7848539958760878, 1.5904609665006728}},
             {"b1", {1.4240861082171488, 1.1222063922935124}},
             {"b3", {1.8113007168782131, 1.6016874351128259}}};
  SimulationOptions o;
  o.impact_method = ImpactMethod::paper;
  const ShotResult r = simulate(
      s, {1.8734887317845283, 1.6280858607377551},
      {0.15166072420801507, 203.00092073839812, 1.0283022534065649, 0.24355939043714142}, o);
  EXPECT_EQ(r.status, ShotStatus::collision_failed);
  EXPECT_NE(r.message.find("pressed together"), std::string::npos) << r.message;
  double end = 0.0;
  for (const BallOutcome& b : r.balls)
    for (const ShotEvent& e : b.events) end = std::max(end, e.time);
  const double d2 = 2.0 * s.radius();
  for (double t = 0.0; t <= end; t += end / 2000.0)
    for (size_t i = 0; i < r.balls.size(); ++i)
      for (size_t j = i + 1; j < r.balls.size(); ++j)
        EXPECT_GE(distance(test::position_at(r.balls[i], t), test::position_at(r.balls[j], t)),
                  d2 * (1.0 - 1e-9))
            << r.balls[i].name << " and " << r.balls[j].name << " at t " << t;
}

TEST(ShotSimulatorBalls, NewtonsCradleSendsOnlyTheLastBallOn) {
  // Two balls touching in a line, struck full by a cue ball with no spin at contact;
  // e = 1 and no friction between the balls: pair by pair, the cue ball stops, the
  // middle ball takes the velocity and gives it on at once, and only the last leaves,
  // with the cue ball's arrival velocity.
  for (BallModel model : {BallModel::mathavan_2014, BallModel::frictional_inelastic}) {
    Scene s = open_table();
    s.ball_contact.mu_ball = 0.0;
    s.ball_contact.restitution = 1.0;
    s.ball_contact.model = model;
    const double r = s.radius(), arrival = 0.9, travel = 0.5;
    const Vec2 cue{0.6, 0.889};
    const Vec2 middle{cue.x + travel + 2.0 * r, cue.y}, last{middle.x + 2.0 * r, cue.y};
    s.balls = {{"middle", middle}, {"last", last}};
    const ShotResult out = simulate(s, cue, stun_on_arrival(s, arrival, travel));
    ASSERT_EQ(out.status, ShotStatus::rest) << out.message;
    const BallOutcome &m = out.balls[1], &l = out.balls[2];
    ASSERT_NE(contact_event(m, 0), nullptr);
    const ShotEvent* handed_on = contact_event(m, 2);
    ASSERT_NE(handed_on, nullptr);
    EXPECT_NEAR(std::hypot(handed_on->velocity.x, handed_on->velocity.y), 0.0, 1e-8 * arrival);
    const ShotEvent* leaves = contact_event(l, 1);
    ASSERT_NE(leaves, nullptr);
    EXPECT_NEAR(leaves->velocity.x, arrival, 1e-8 * arrival) << to_string(model);
    EXPECT_NEAR(distance(m.final_position, middle), 0.0, 1e-9) << to_string(model);
    EXPECT_NEAR(out.final_position.x, cue.x + travel, 1e-9);
    EXPECT_NEAR(l.final_position.x, last.x + stun_travel(s, arrival), 1e-6);
    // Struck once each: the cue ball never catches up again.
    EXPECT_EQ(contact_event(m, 0, 1), nullptr);
  }
}

// The aim (deg) from `cue` at the ghost ball that sends `object` toward `to`: the cue
// ball's centre 2R behind the object ball on that line.
double aim_to_pot(const Scene& s, Vec2 cue, Vec2 object, Vec2 to) {
  const double d = distance(object, to);
  const Vec2 ghost{object.x - 2.0 * s.radius() * (to.x - object.x) / d,
                   object.y - 2.0 * s.radius() * (to.y - object.y) / d};
  return std::atan2(ghost.y - cue.y, ghost.x - cue.x) / kDeg;
}

TEST(ShotSimulatorBalls, APocketedObjectBallLeavesTheTableAndTheShotGoesOn) {
  // A cut of about 30 degrees pots the red into the bottom-left corner; the cue ball goes
  // off the line of centres, meets a cushion and comes to rest long after.
  const Scene s = with_balls(snooker_scene(), {{"red", {0.25, 0.25}}});
  const Vec2 cue{1.0, 0.5};
  const ShotResult r = simulate(s, cue, {2.0, aim_to_pot(s, cue, {0.25, 0.25}, {0, 0}), 1.0, 0.0});
  ASSERT_EQ(r.status, ShotStatus::rest) << r.message;
  ASSERT_TRUE(r.balls[1].pocketed);
  EXPECT_EQ(r.balls[1].pocket, 0);
  EXPECT_EQ(r.balls[1].events.back().type, EventType::pocket);
  EXPECT_NEAR(distance(r.balls[1].final_position, {0, 0}), s.pockets[0].radius, 1e-9);
  const double potted = r.balls[1].events.back().time;
  EXPECT_GT(r.events.back().time, potted + 1.0);
  EXPECT_GE(r.cushion_hits, 1);
}

TEST(ShotSimulatorBalls, APocketedCueBallEndsOnlyItsOwnMotion) {
  // A stun cut: the cue ball leaves at right angles to the line of centres into the
  // bottom-middle pocket, the red goes on up the table and comes to rest after it.
  const Scene base = snooker_scene();
  const Vec2 cue{0.6, 0.3}, contact{1.5, 0.3}, pocket = base.pockets[1].centre;
  const double d = distance(contact, pocket);
  const Vec2 along{(pocket.x - contact.x) / d, (pocket.y - contact.y) / d};
  const Vec2 red{contact.x - 2.0 * base.radius() * along.y,
                 contact.y + 2.0 * base.radius() * along.x};
  const Scene s = with_balls(base, {{"red", red}});
  const ShotResult r = simulate(s, cue, stun_on_arrival(s, 2.0, contact.x - cue.x));
  ASSERT_EQ(r.status, ShotStatus::pocketed) << r.message;
  EXPECT_TRUE(r.balls[0].pocketed);
  EXPECT_EQ(r.balls[0].pocket, 1);
  EXPECT_EQ(r.first_contact, 1);
  ASSERT_FALSE(r.balls[1].pocketed);
  ASSERT_FALSE(r.balls[1].events.empty());
  EXPECT_EQ(r.balls[1].events.back().type, EventType::rest);
  EXPECT_GT(r.balls[1].events.back().time, r.events.back().time + 1.0);
  EXPECT_GE(r.balls[1].cushion_hits, 1);
  // The cue ball's outcome is its own: where and when it dropped.
  EXPECT_EQ(r.duration, r.events.back().time);
  EXPECT_EQ(r.final_position.x, r.events.back().position.x);
}

TEST(ShotSimulatorBalls, AnObjectBallOnAnObstacleEndsTheShot) {
  Scene s = with_balls(open_table(), {{"red", {1.5, 0.5}}});
  s.obstacles = {{2.5, 0.5}};
  const ShotResult r = simulate(s, {0.8, 0.5}, stun_on_arrival(s, 1.5, 0.7 - 2 * s.radius()));
  EXPECT_EQ(r.status, ShotStatus::hit_obstacle);
  ASSERT_FALSE(r.balls[1].events.empty());
  EXPECT_EQ(r.balls[1].events.back().type, EventType::obstacle);
  EXPECT_NEAR(r.balls[1].final_position.x, 2.5 - 2.0 * s.radius(), 1e-9);
}

TEST(ShotSimulatorBalls, TheEventCapCountsEveryBallsEvents) {
  const Scene s = with_balls(snooker_scene(), {{"red", {1.5, 0.62}}, {"yellow", {2.1, 0.75}}});
  const ShotResult full = simulate(s, {0.7, 0.5}, {2.5, 8.0, 0.6, 0.5});
  ASSERT_EQ(full.status, ShotStatus::rest);
  size_t all = 0;
  for (const BallOutcome& b : full.balls) all += b.events.size();
  ASSERT_GT(all, full.events.size());
  SimulationOptions o;
  o.max_events = static_cast<int>(all) - 2;
  const ShotResult capped = simulate(s, {0.7, 0.5}, {2.5, 8.0, 0.6, 0.5}, o);
  EXPECT_EQ(capped.status, ShotStatus::event_limit);
  size_t counted = 0;
  for (const BallOutcome& b : capped.balls) counted += b.events.size();
  EXPECT_LE(counted, static_cast<size_t>(o.max_events) + 4);  // the bound of SimulationOptions
  EXPECT_GE(counted, static_cast<size_t>(o.max_events) + 1);
}

TEST(ShotSimulatorBalls, EveryBallsPathMeetsItsEventsAndNeverGainsEnergy) {
  const Scene s = with_balls(snooker_scene(), {{"red", {1.5, 0.62}},
                                               {"yellow", {2.1, 0.75}},
                                               {"green", {2.6, 1.2}},
                                               {"brown", {1.0, 1.3}}});
  for (const Shot& shot : {Shot{2.5, 12.0, 0.6, 0.5}, Shot{3.0, 11.0, -0.5, -0.5}}) {
    const ShotResult r = simulate(s, {0.7, 0.5}, shot);
    EXPECT_TRUE(test::all_finite(r));
    for (const BallOutcome& b : r.balls) {
      const test::PathAudit a = test::audit_path(s, b.events, b.path);
      EXPECT_TRUE(a.times_ordered) << b.name;
      EXPECT_TRUE(a.segments_matched) << b.name;
      EXPECT_LT(a.max_gap, 1e-12) << b.name;
      EXPECT_LT(a.max_energy_gain, 1e-10) << b.name << " at " << a.where;
      EXPECT_LT(a.max_outside, 1e-12) << b.name;
    }
  }
}

TEST(ShotSimulatorBalls, BadObjectBallsAreNamedByField) {
  const Scene base = snooker_scene();
  const double r = base.radius();
  const auto error_of = [](const Scene& s, Vec2 cue = {0.5, 0.5}) {
    const ShotResult out = simulate(s, cue, {});
    EXPECT_EQ(out.status, ShotStatus::invalid_input);
    return out.error.value_or(ValidationError{});
  };
  ValidationError e = error_of(with_balls(base, {{"red", {-0.2, 0.5}}}));
  EXPECT_EQ(e.field, (FieldPath{"balls", "red"}));
  EXPECT_NE(e.message().find("off the table"), std::string::npos) << e.message();
  e = error_of(with_balls(base, {{"red", {1.5, 0.5}}, {"blue", {1.5 + r, 0.5}}}));
  EXPECT_EQ(e.field, (FieldPath{"balls", "red"}));
  EXPECT_EQ(e.other, (FieldPath{"balls", "blue"}));
  EXPECT_EQ(e.message(), "balls.red overlaps balls.blue");
  Scene on_obstacle = with_balls(base, {{"red", {1.5, 0.5}}});
  on_obstacle.obstacles = {{1.5, 0.5 + r}};
  e = error_of(on_obstacle);
  EXPECT_EQ(e.other, (FieldPath{"obstacles", 0}));
  e = error_of(with_balls(base, {{"red", {base.length / 2, 0.03}}}));
  EXPECT_EQ(e.other, (FieldPath{"pockets", 1}));
  e = error_of(with_balls(base, {{"", {1.5, 0.5}}}));
  EXPECT_EQ(e.field, (FieldPath{"balls", 0, "name"}));
  e = error_of(with_balls(base, {{"cue", {1.5, 0.5}}}));
  EXPECT_EQ(e.field, (FieldPath{"balls", 0, "name"}));
  e = error_of(with_balls(base, {{"red", {1.5, 0.5}}, {"red", {2.5, 0.5}}}));
  EXPECT_EQ(e.field, (FieldPath{"balls", 1, "name"}));
  EXPECT_EQ(e.other, (FieldPath{"balls", 0, "name"}));
  e = error_of(with_balls(base, {{"red", {1.5, NAN}}}));
  EXPECT_EQ(e.field, (FieldPath{"balls", "red"}));
  // The cue ball on an object ball.
  e = error_of(with_balls(base, {{"red", {0.5 + r, 0.5}}}));
  EXPECT_EQ(e.field, FieldPath{"cue_ball"});
  EXPECT_EQ(e.other, (FieldPath{"balls", "red"}));
  // Touching is fine.
  EXPECT_EQ(simulate(with_balls(base, {{"red", {0.5 + 2 * r, 0.5}}}), {0.5, 0.5}, {}).status,
            ShotStatus::rest);
  // The collision's parameters, under ball_contact or on the scene's own fields.
  Scene c = base;
  c.ball_contact.mu_ball = -0.1;
  EXPECT_EQ(error_of(c).field, (FieldPath{"ball_contact", "mu_ball"}));
  c = base;
  c.ball_contact.restitution = 0.0;
  EXPECT_EQ(error_of(c).field, (FieldPath{"ball_contact", "restitution"}));
  c = base;
  c.ball_contact.model = static_cast<BallModel>(7);
  EXPECT_EQ(error_of(c).field, (FieldPath{"ball_contact", "model"}));
  c = base;
  c.ball_contact.mu_ball = 2.0;
  c.cloth.mu_slide = 0.2;
  e = error_of(c);
  EXPECT_EQ(e.field, (FieldPath{"ball_contact", "mu_ball"}));
  EXPECT_EQ(e.other, (FieldPath{"cloth", "mu_slide"}));
}

}  // namespace
}  // namespace cueplan::physics

namespace cueplan::physics {
namespace {

// A shot followed to a horizon (SimulationOptions::max_time) is the full shot cut there:
// the same events before it, every ball where the full shot has it at that time, and the
// time_limit status; a horizon after the shot ends changes nothing; a bad one is refused.
TEST(ShotSimulatorBalls, AHorizonCutsTheShotWhereTheFullShotIs) {
  const Scene s = with_balls(snooker_scene(), {{"red", {1.5, 0.62}}, {"yellow", {2.1, 0.75}}});
  const Shot shot{2.5, 8.0, 0.6, 0.5};
  const ShotResult full = simulate(s, {0.7, 0.5}, shot);
  ASSERT_EQ(full.status, ShotStatus::rest) << full.message;
  ASSERT_GE(full.events.size(), 4u);
  const double horizon = 0.5 * (full.events[2].time + full.events[3].time);
  SimulationOptions o;
  o.max_time = horizon;
  const ShotResult cut = simulate(s, {0.7, 0.5}, shot, o);
  EXPECT_EQ(cut.status, ShotStatus::time_limit) << cut.message;
  ASSERT_EQ(cut.balls.size(), full.balls.size());
  for (size_t k = 0; k < full.balls.size(); ++k) {
    const BallOutcome& f = full.balls[k];
    const BallOutcome& c = cut.balls[k];
    // Where the full shot has ball k at the horizon.
    Vec2 there = f.start;
    for (const PathSegment& seg : f.path)
      if (horizon >= seg.t0 && horizon <= seg.t1) there = seg.at(horizon);
    if (!f.path.empty() && horizon > f.path.back().t1) there = f.final_position;
    EXPECT_NEAR(c.final_position.x, there.x, 1e-12) << f.name;
    EXPECT_NEAR(c.final_position.y, there.y, 1e-12) << f.name;
    size_t before = 0;
    for (const ShotEvent& e : f.events) before += e.time <= horizon;
    EXPECT_EQ(c.events.size(), before) << f.name;
    if (!f.path.empty() && f.path.back().t1 > horizon) {  // still moving there
      ASSERT_FALSE(c.path.empty()) << f.name;
      EXPECT_NEAR(c.path.back().t1, horizon, 1e-12) << f.name;
    }
  }
  o.max_time = full.duration + 1.0;
  const ShotResult late = simulate(s, {0.7, 0.5}, shot, o);
  EXPECT_EQ(late.status, ShotStatus::rest);
  EXPECT_EQ(late.final_position.x, full.final_position.x);
  EXPECT_EQ(late.events.size(), full.events.size());
  o.max_time = std::nan("");
  const ShotResult bad = simulate(s, {0.7, 0.5}, shot, o);
  EXPECT_EQ(bad.status, ShotStatus::invalid_input);
  EXPECT_NE(bad.message.find("max_time"), std::string::npos) << bad.message;
}

}  // namespace
}  // namespace cueplan::physics
