// Tests of the shot trace: its rows at events are the event list, between events it is
// the path segments, and its spins obey the cloth's laws of PHYSICS.md - checked against
// the velocities of the same rows, not against the code that made them.
#include "cueplan/physics/trace.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

namespace cueplan::physics {
namespace {

// A break-like shot: a sliding, side-spun cue ball into two object balls, cushions after.
struct Case {
  Scene scene;
  ShotResult result;
};

Case two_ball_shot() {
  Case c;
  c.scene = snooker_scene();
  c.scene.balls = {{"red", {1.9, 0.95}}, {"yellow", {2.6, 1.3}}};
  c.result = simulate(c.scene, {0.8, 0.7}, Shot{2.2, 12.0, -0.4, 0.6});
  return c;
}

double g_slide(const Scene& s) { return s.cloth.mu_slide * s.cloth.gravity; }

TEST(ShotTrace, RowsAtEventsAreTheEventList) {
  const Case c = two_ball_shot();
  ASSERT_EQ(c.result.status, ShotStatus::rest) << c.result.message;
  ASSERT_GT(c.result.balls[1].events.size(), 0u) << "the shot should strike the red";
  const ShotTrace t = trace_shot(c.result, c.scene, 0.01);
  ASSERT_FALSE(t.error) << t.error->message();
  for (size_t k = 0; k < c.result.balls.size(); ++k) {
    std::vector<const BallSample*> rows;
    for (const BallSample& s : t.samples)
      if (s.ball == static_cast<int>(k) && s.event) rows.push_back(&s);
    const std::vector<ShotEvent>& events = c.result.balls[k].events;
    ASSERT_EQ(rows.size(), events.size()) << k;
    for (size_t i = 0; i < events.size(); ++i) {
      EXPECT_EQ(*rows[i]->event, events[i].type);
      EXPECT_NEAR(rows[i]->time, events[i].time, 1e-12);
      EXPECT_NEAR(rows[i]->position.x, events[i].position.x, 1e-9);
      EXPECT_NEAR(rows[i]->position.y, events[i].position.y, 1e-9);
      EXPECT_NEAR(rows[i]->velocity.x, events[i].velocity.x, 1e-9);
      EXPECT_NEAR(rows[i]->velocity.y, events[i].velocity.y, 1e-9);
    }
  }
  // Sorted by time; the samples on the grid for every ball on the table.
  for (size_t i = 1; i < t.samples.size(); ++i)
    ASSERT_LE(t.samples[i - 1].time, t.samples[i].time);
  EXPECT_NEAR(t.end_time, c.result.balls[0].events.back().time, 1e-12);
}

// Between events each position is the segment's p0 + v0 dt + a dt^2 / 2 and each velocity
// v0 + a dt; and the state a ball reaches at its next event (approached from just before)
// is where that event finds it.
TEST(ShotTrace, BetweenEventsTheTraceFollowsThePathSegments) {
  const Case c = two_ball_shot();
  const ShotTrace t = trace_shot(c.result, c.scene, 0.003);
  ASSERT_FALSE(t.error);
  int compared = 0;
  for (const BallSample& s : t.samples) {
    if (s.event) continue;
    for (const PathSegment& seg : c.result.balls[static_cast<size_t>(s.ball)].path) {
      if (!(s.time > seg.t0 && s.time < seg.t1)) continue;
      const Vec2 p = seg.at(s.time);
      EXPECT_NEAR(s.position.x, p.x, 1e-9);
      EXPECT_NEAR(s.position.y, p.y, 1e-9);
      EXPECT_NEAR(s.velocity.x, seg.v0.x + seg.accel.x * (s.time - seg.t0), 1e-9);
      EXPECT_NEAR(s.velocity.y, seg.v0.y + seg.accel.y * (s.time - seg.t0), 1e-9);
      ++compared;
    }
  }
  EXPECT_GT(compared, 1000);
  // Continuity into each event that does not move the ball (cushions and contacts change
  // the velocity, not the position).
  for (size_t k = 0; k < c.result.balls.size(); ++k) {
    const std::vector<ShotEvent>& events = c.result.balls[k].events;
    for (size_t i = 1; i < events.size(); ++i) {
      const double before = events[i].time - 1e-9;
      if (!(before > events[i - 1].time)) continue;
      const BallSample s = ball_state_at(c.result, c.scene, static_cast<int>(k), before);
      const double speed = std::hypot(s.velocity.x, s.velocity.y);
      EXPECT_NEAR(s.position.x, events[i].position.x, speed * 1e-9 + 1e-12) << k << " " << i;
      EXPECT_NEAR(s.position.y, events[i].position.y, speed * 1e-9 + 1e-12) << k << " " << i;
      if (events[i].type == EventType::slide_to_roll || events[i].type == EventType::spin_stop) {
        EXPECT_NEAR(s.velocity.x, events[i].velocity.x, 1e-8);
        EXPECT_NEAR(s.velocity.y, events[i].velocity.y, 1e-8);
      }
    }
  }
}

// The cloth's laws, checked on the trace's own rows: while sliding, dv/dt = -mu_s g u/|u|
// and d(w_x, w_y)/dt = (5 mu_s g / 2R) z x u/|u| with u = (vx - R wy, vy + R wx) read from
// the earlier row; rolling rows have w = (-vy/R, vx/R); sidespin falls at 5 mu_sp g / (2R).
// At slide to roll the contact point's velocity, falling at (7/2) mu_s g from the last
// sliding row, reaches zero at the event's time.
TEST(ShotTrace, SpinsObeyTheClothLaws) {
  const Case c = two_ball_shot();
  const double dt = 0.002;
  const ShotTrace t = trace_shot(c.result, c.scene, dt);
  ASSERT_FALSE(t.error);
  const double R = c.scene.radius();
  const double a = g_slide(c.scene);
  const double spin_rate = 2.5 * a / R;
  const double side_rate = 2.5 * c.scene.cloth.mu_spin * c.scene.cloth.gravity / R;
  std::map<int, const BallSample*> last;  // each ball's previous row
  int slides = 0, rolls = 0, landings = 0, sides = 0;
  for (const BallSample& s : t.samples) {
    const BallSample* prev = last[s.ball];
    last[s.ball] = &s;
    if (s.motion == Motion::rolling && !s.event) {
      EXPECT_NEAR(s.spin.x, -s.velocity.y / R, 1e-9 / R);
      EXPECT_NEAR(s.spin.y, s.velocity.x / R, 1e-9 / R);
      ++rolls;
    }
    if (prev == nullptr || prev->motion != Motion::sliding) continue;
    const double h = s.time - prev->time;
    if (h <= 0.0) continue;
    const double ux = prev->velocity.x - R * prev->spin.y, uy = prev->velocity.y + R * prev->spin.x;
    const double u = std::hypot(ux, uy);
    if (s.event && *s.event == EventType::slide_to_roll) {
      // |u| falls at 7/2 mu_s g and reaches zero here.
      EXPECT_NEAR(u - 3.5 * a * h, 0.0, 1e-9) << s.ball << " at " << s.time;
      ++landings;
      continue;
    }
    if (s.event) continue;  // a cushion or contact changed the state
    EXPECT_NEAR((s.velocity.x - prev->velocity.x) / h, -a * ux / u, 1e-6);
    EXPECT_NEAR((s.velocity.y - prev->velocity.y) / h, -a * uy / u, 1e-6);
    EXPECT_NEAR((s.spin.x - prev->spin.x) / h, -spin_rate * uy / u, 1e-5);
    EXPECT_NEAR((s.spin.y - prev->spin.y) / h, spin_rate * ux / u, 1e-5);
    if (std::abs(prev->spin.z) > side_rate * h) {
      EXPECT_NEAR(std::abs(prev->spin.z) - std::abs(s.spin.z), side_rate * h, 1e-9);
      ++sides;
    }
    ++slides;
  }
  EXPECT_GT(slides, 50);
  EXPECT_GT(rolls, 50);
  EXPECT_GT(landings, 1);
  EXPECT_GT(sides, 20);
}

TEST(ShotTrace, BallsNotStruckRestAndPocketedBallsLeave) {
  Scene scene = snooker_scene();
  // A straight pot of the red along the diagonal into the top-right corner; the blue is
  // never touched.
  const double back = scene.length - scene.width;  // the corner's diagonal: y = x - back
  scene.balls = {{"red", {3.2, 3.2 - back}}, {"blue", {0.4, 1.5}}};
  const Vec2 cue{2.7, 2.7 - back};
  const ShotResult r = simulate(scene, cue, Shot{2.0, 45.0, 0.0, 0.0});
  ASSERT_NE(r.status, ShotStatus::invalid_input) << r.message;
  ASSERT_TRUE(r.balls[1].pocketed) << "the red should be potted";
  const ShotTrace t = trace_shot(r, scene, 0.05);
  ASSERT_FALSE(t.error);
  double pocket_time = 0.0;
  for (const ShotEvent& e : r.balls[1].events)
    if (e.type == EventType::pocket) pocket_time = e.time;
  int blue_rows = 0;
  for (const BallSample& s : t.samples) {
    if (s.ball == 2) {
      EXPECT_EQ(s.position.x, 0.4);
      EXPECT_EQ(s.position.y, 1.5);
      EXPECT_EQ(s.velocity.x, 0.0);
      EXPECT_EQ(s.motion, Motion::resting);
      ++blue_rows;
    }
    if (s.ball == 1) {
      EXPECT_LE(s.time, pocket_time);
    }
  }
  EXPECT_EQ(blue_rows, static_cast<int>(std::floor(t.end_time / 0.05)) + 1);
}

TEST(ShotTrace, RefusesBadIntervalsAndTooManyRows) {
  const Case c = two_ball_shot();
  for (double dt : {0.0, -0.1, std::nan(""), static_cast<double>(INFINITY)}) {
    const ShotTrace t = trace_shot(c.result, c.scene, dt);
    ASSERT_TRUE(t.error) << dt;
    EXPECT_EQ(t.error->field, FieldPath{"interval"});
    EXPECT_TRUE(t.samples.empty());
  }
  const ShotTrace huge = trace_shot(c.result, c.scene, 1e-9);
  ASSERT_TRUE(huge.error);
  EXPECT_NE(huge.error->message().find("more than the limit"), std::string::npos)
      << huge.error->message();
  EXPECT_TRUE(huge.samples.empty());
  // The bound is on the rows the trace can have at most: every ball at every grid instant
  // plus every event. One under it refused, at it accepted.
  const ShotTrace fine = trace_shot(c.result, c.scene, 0.01);
  ASSERT_FALSE(fine.error);
  size_t events = 0;
  for (const BallOutcome& b : c.result.balls) events += b.events.size();
  const size_t most =
      c.result.balls.size() * (static_cast<size_t>(std::floor(fine.end_time / 0.01)) + 1) + events;
  EXPECT_LE(fine.samples.size(), most);
  EXPECT_TRUE(trace_shot(c.result, c.scene, 0.01, most - 1).error);
  EXPECT_FALSE(trace_shot(c.result, c.scene, 0.01, most).error);
  ShotResult nothing;
  EXPECT_EQ(trace_shot(nothing, c.scene, 0.01).error->field, FieldPath{"result"});
}

}  // namespace
}  // namespace cueplan::physics
