// Every ball's state through a simulated shot, sampled at a fixed interval and at each
// of its events: what a user plots, animates or holds against a video.
//
// The states come from the shot's events and the closed forms of "Ball on the cloth"
// (PHYSICS.md) between them: from each event, the ball slides (dv/dt = -mu_s g u/|u|,
// dw/dt = (5 mu_s g / 2R) z x u/|u|) or rolls (w at rolling spin), and its sidespin
// decays at 5 mu_sp g / (2R) - the same closed forms the simulator moved it by, so the
// positions agree with ShotResult's path segments to rounding.
//
// A pure function of its arguments: no globals, safe from many threads.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "cueplan/physics/validation.hpp"

namespace cueplan::physics {

// One ball at one instant.
struct BallSample {
  double time = 0.0;  // s since the strike
  int ball = 0;       // index into ShotResult::balls (0: the cue ball)
  Vec2 position;      // m, table frame
  Vec2 velocity;      // m/s
  Vec3 spin;          // rad/s
  Motion motion = Motion::resting;  // of the piece that follows (at an event: after it)
  // At an event of this ball: the event (its state is the event's, just after it).
  // Empty for a sample at a multiple of the interval.
  std::optional<EventType> event;
};

// Bound on the rows of one trace.
inline constexpr std::size_t kMaxTraceSamples = 1'000'000;

struct ShotTrace {
  // invalid_input-like errors: {"interval"} (not positive and finite, or so small that
  // the trace would hold more than max_samples rows), {"result"} (nothing simulated).
  Validation error;
  double end_time = 0.0;            // s, the last instant sampled: the shot's last event
  std::vector<BallSample> samples;  // by time; at one time by ball, then in event order
};

// Ball `ball` (index into result.balls) at time t (s) of a shot simulated on `scene`:
// from its last event at or before t, moved on by the cloth's closed forms (at an event's
// own time, the state just after it). A ball not yet struck lies at its start; after a
// pocket event the ball is where it entered (no longer on the table). `ball` must be a
// valid index and t >= 0; `event` is left empty.
BallSample ball_state_at(const ShotResult& result, const Scene& scene, int ball, double t);

// The trace of a simulated shot on `scene` (the scene it was simulated on): every ball at
// t = 0, dt, 2 dt, ... up to the shot's last event, and at every one of its events. A ball
// never struck lies at its start; a pocketed ball has no samples after its pocket event.
// At a multiple of dt where the ball has an event, only the event's row is given.
// max_samples bounds the rows the trace may have at most, (floor(end / dt) + 1) rows per
// ball plus one per event; beyond it the trace is refused (error on "interval").
ShotTrace trace_shot(const ShotResult& result, const Scene& scene, double dt,
                     std::size_t max_samples = kMaxTraceSamples);

}  // namespace cueplan::physics
