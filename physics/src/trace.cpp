// Sampling a simulated shot: every ball's state between and at its events
// (trace.hpp; the closed forms are the simulator's own, ball_motion.hpp).
#include "cueplan/physics/trace.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "ball_motion.hpp"

namespace cueplan::physics {
namespace {

// The events of ball k (the cue ball's are also ShotResult::events).
const std::vector<ShotEvent>& events_of(const ShotResult& r, size_t k) {
  return k == 0 && r.balls[0].events.empty() ? r.events : r.balls[k].events;
}

BallSample from_event(const detail::ClothModel& cloth, const ShotEvent& e, int ball) {
  BallSample s;
  s.time = e.time;
  s.ball = ball;
  s.position = e.position;
  s.velocity = e.velocity;
  s.spin = e.spin;
  s.motion = detail::piece_from(cloth, {e.position, e.velocity, e.spin}).motion;
  s.event = e.type;
  return s;
}

// The state `t` after event e, by the piece of motion that starts there.
BallSample after_event(const detail::ClothModel& cloth, const ShotEvent& e, int ball, double t) {
  detail::Ball b{e.position, e.velocity, e.spin};
  const detail::Piece piece = detail::piece_from(cloth, b);
  const double dt = t - e.time;
  // A piece ends at its own event (slide to roll, rest); later instants belong to the
  // next piece, which has its own event. Rounding may put t a hair past the end.
  detail::advance(cloth, piece, std::min(dt, piece.duration), &b);
  BallSample s;
  s.time = t;
  s.ball = ball;
  s.position = b.p;
  s.velocity = b.v;
  s.spin = b.w;
  s.motion = piece.motion;
  return s;
}

BallSample at_start(const ShotResult& r, size_t k, double t) {
  BallSample s;
  s.time = t;
  s.ball = static_cast<int>(k);
  s.position = r.balls[k].start;
  s.motion = Motion::resting;
  return s;
}

}  // namespace

BallSample ball_state_at(const ShotResult& result, const Scene& scene, int ball, double t) {
  const detail::ClothModel cloth(scene);
  const size_t k = static_cast<size_t>(ball);
  const std::vector<ShotEvent>& events = events_of(result, k);
  // The last event at or before t.
  const auto next = std::upper_bound(events.begin(), events.end(), t,
                                     [](double time, const ShotEvent& e) { return time < e.time; });
  if (next == events.begin()) return at_start(result, k, t);
  const ShotEvent& e = *(next - 1);
  if (e.type == EventType::pocket) {
    BallSample s = from_event(cloth, e, ball);
    s.time = t;
    s.event.reset();
    return s;
  }
  return after_event(cloth, e, ball, t);
}

ShotTrace trace_shot(const ShotResult& result, const Scene& scene, double dt,
                     std::size_t max_samples) {
  ShotTrace trace;
  if (!std::isfinite(dt) || !(dt > 0.0)) {
    trace.error = invalid({"interval"}, "must be positive and finite (s)", dt);
    return trace;
  }
  if (result.balls.empty()) {
    trace.error = invalid({"result"}, "holds no balls: nothing was simulated");
    return trace;
  }
  const detail::ClothModel cloth(scene);
  // The shot's last instant: its last event (a ball still moving when it ended was
  // brought to that instant, its path recorded up to it).
  double end = 0.0;
  size_t event_count = 0;
  for (size_t k = 0; k < result.balls.size(); ++k) {
    const std::vector<ShotEvent>& events = events_of(result, k);
    if (!events.empty()) end = std::max(end, events.back().time);
    event_count += events.size();
    for (const PathSegment& s : result.balls[k].path) end = std::max(end, s.t1);
  }
  trace.end_time = end;
  const double steps = std::floor(end / dt);
  const double rows = (steps + 1.0) * static_cast<double>(result.balls.size()) +
                      static_cast<double>(event_count);
  if (!(rows <= static_cast<double>(max_samples))) {
    trace.error = invalid(
        {"interval"},
        fmt::format("gives {:.4g} rows over the shot's {:.6g} s, more than the limit of {}: "
                    "take a longer interval",
                    rows, end, max_samples),
        dt);
    return trace;
  }
  const size_t n = static_cast<size_t>(steps);
  trace.samples.reserve(static_cast<size_t>(rows));

  for (size_t k = 0; k < result.balls.size(); ++k) {
    const int ball = static_cast<int>(k);
    const std::vector<ShotEvent>& events = events_of(result, k);
    size_t next = 0;  // the first event not yet given
    bool gone = false;
    for (size_t i = 0; i <= n && !gone; ++i) {
      const double t = static_cast<double>(i) * dt;
      if (t > end) break;
      // The events up to this instant, each as it left the ball.
      for (; next < events.size() && events[next].time <= t; ++next) {
        trace.samples.push_back(from_event(cloth, events[next], ball));
        if (events[next].type == EventType::pocket) gone = true;
      }
      if (gone || (next > 0 && events[next - 1].time == t)) continue;
      trace.samples.push_back(next == 0 ? at_start(result, k, t)
                                        : after_event(cloth, events[next - 1], ball, t));
    }
    for (; next < events.size(); ++next) trace.samples.push_back(from_event(cloth, events[next], ball));
  }
  // By time, then by ball; a ball's events keep their order.
  std::stable_sort(trace.samples.begin(), trace.samples.end(),
                   [](const BallSample& a, const BallSample& b) {
                     return a.time != b.time ? a.time < b.time : a.ball < b.ball;
                   });
  return trace;
}

}  // namespace cueplan::physics
