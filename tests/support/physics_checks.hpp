// Checks on physics results shared by the unit, property and stress tests: how far
// two impact outcomes differ, whether every number in a result is finite, and how
// much kinetic energy a shot's path gains anywhere (PHYSICS.md, "Ball on the cloth",
// rebuilt here from the recorded path rather than taken from the simulator).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "cueplan/physics/cushion_impact.hpp"
#include "cueplan/physics/impact_table.hpp"
#include "cueplan/physics/shot.hpp"

namespace cueplan::physics::test {

// Largest difference of two outgoing states, in units of the incoming speed v0
// (spins as R w).
inline double state_difference(const CushionParams& p, const ImpactResult& a, const ImpactResult& b,
                               double v0) {
  const Vec3 dv = a.outgoing.velocity - b.outgoing.velocity;
  const Vec3 dw = a.outgoing.spin - b.outgoing.spin;
  const double m = std::max({std::abs(dv.x), std::abs(dv.y), p.radius * std::abs(dw.x),
                             p.radius * std::abs(dw.y), p.radius * std::abs(dw.z)});
  return m / v0;
}

// A tiny impact table that builds in a fraction of a second, for tests that build several
// (saving, loading, caching); too coarse for accuracy.
inline ImpactTableOptions tiny_table_options() {
  ImpactTableOptions o;
  o.alpha_nodes = 5;
  o.topspin_nodes = 9;
  o.sidespin_nodes = 5;
  o.roll_alpha_nodes = 5;
  o.roll_sidespin_nodes = 5;
  o.cell_tolerance = 1e-2;
  return o;
}

// Every number an impact result reports is finite.
inline bool all_finite(const ImpactResult& r) {
  return is_finite(r.outgoing.velocity) && is_finite(r.outgoing.spin) &&
         std::isfinite(r.rebound_speed) && std::isfinite(r.rebound_angle_deg) &&
         std::isfinite(r.impulse_compression) && std::isfinite(r.impulse_total) &&
         std::isfinite(r.work_compression) && std::isfinite(r.work_total);
}

// Kinetic energy (J) of the ball with planar velocity v and spin w.
inline double kinetic_energy_of(const Scene& s, Vec2 v, Vec3 w) {
  BallState b;
  b.velocity = {v.x, v.y, 0.0};
  b.spin = w;
  return kinetic_energy(s.ball_and_cushion, b);
}

inline bool finite2(Vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }

// Every number a shot result reports is finite, for every ball.
inline bool all_finite(const ShotResult& r) {
  if (!finite2(r.final_position) || !std::isfinite(r.duration) ||
      !std::isfinite(r.max_cushion_normal_speed))
    return false;
  const auto finite_events = [](const std::vector<ShotEvent>& events) {
    for (const ShotEvent& e : events)
      if (!std::isfinite(e.time) || !finite2(e.position) || !finite2(e.velocity) ||
          !is_finite(e.spin) || !std::isfinite(e.normal_speed) || !std::isfinite(e.impulse))
        return false;
    return true;
  };
  const auto finite_path = [](const std::vector<PathSegment>& path) {
    for (const PathSegment& s : path)
      if (!std::isfinite(s.t0) || !std::isfinite(s.t1) || !finite2(s.p0) || !finite2(s.v0) ||
          !finite2(s.accel))
        return false;
    return true;
  };
  if (!finite_events(r.events) || !finite_path(r.path)) return false;
  for (const BallOutcome& b : r.balls)
    if (!finite2(b.final_position) || !std::isfinite(b.max_cushion_normal_speed) ||
        !finite_events(b.events) || !finite_path(b.path))
      return false;
  return true;
}

// What walking a shot's events and path found.
struct PathAudit {
  // Largest relative rise of kinetic energy, (after - before) / before, across a cushion
  // impact and everywhere else.
  double max_impact_energy_gain = 0.0;
  double max_energy_gain = 0.0;
  double max_gap = 0.0;          // m, largest jump between a segment's end and the next event
  double max_outside = 0.0;      // m, farthest a centre got past a cushion contact line
  bool times_ordered = true;     // event and segment times never go back, and meet
  bool segments_matched = true;  // every segment starts at an event
  std::string where;             // the event or segment of max_energy_gain
  // Each contact with another ball: the ball's kinetic energy just before (the end of
  // the segment or the state of the event before it; 0 when it lay untouched) and just
  // after, for the caller to add up over both balls.
  struct Contact {
    double time = 0.0;
    int other = -1;
    double before = 0.0, after = 0.0;
  };
  std::vector<Contact> contacts;
};

// Walks the events in order, and inside every path segment rebuilds the state at
// `samples` interior times from the segment's start event with the cloth laws of
// PHYSICS.md: while sliding dw/dt = (5 / 2R) z x (-a) (a = mu_s g along -u), while
// rolling w = (-v_y, v_x) / R, and w_z falls at 5 mu_sp g / (2R) toward zero.
//
// For one ball's events and path (ShotResult::balls[k]): its kinetic energy may rise only
// where another ball strikes it (ball_contact events, not counted).
inline PathAudit audit_path(const Scene& s, const std::vector<ShotEvent>& events,
                            const std::vector<PathSegment>& path, int samples = 4) {
  PathAudit audit;
  const double radius = s.radius();
  const double spin_decel = 2.5 * s.cloth.mu_spin * s.cloth.gravity / radius;
  const double off = s.contact_offset();
  auto outside = [&](Vec2 p) {
    return std::max({off - p.x, p.x - (s.length - off), off - p.y, p.y - (s.width - off), 0.0});
  };
  double last = INFINITY;
  // Times are seconds since the strike, so a segment's length, rebuilt as t1 - t0, is
  // known to an ulp of t1: the state at its end to how fast the energy falls times that.
  // On the long segments of a shot this is far below rounding; on the nanosecond ones of
  // balls pressed together it is not.
  double last_allowance = 0.0;
  auto visit = [&](double energy, const std::string& where, bool impact, bool contact = false) {
    double gain = 0.0;
    if (std::isfinite(last) && energy > last + last_allowance)
      gain = last > 0.0 ? (energy - last - last_allowance) / last : INFINITY;
    last_allowance = 0.0;
    if (contact) {
      audit.contacts.back().before = std::isfinite(last) ? last : 0.0;
      audit.contacts.back().after = energy;
      last = energy;
      return;
    }
    double& worst = impact ? audit.max_impact_energy_gain : audit.max_energy_gain;
    if (gain > worst) {
      worst = gain;
      if (!impact) audit.where = where;
    }
    last = energy;
  };
  // Each segment starts from the state of the last event logged before it: the first
  // run of events that matches its start exactly (time, position, velocity). Events
  // without a segment between them happened at one instant.
  auto starts = [](const ShotEvent& e, const PathSegment& seg) {
    return e.time == seg.t0 && e.position.x == seg.p0.x && e.position.y == seg.p0.y &&
           e.velocity.x == seg.v0.x && e.velocity.y == seg.v0.y;
  };
  size_t next_event = 0;
  auto take_event = [&] {
    const ShotEvent& e = events[next_event];
    if (next_event > 0 && e.time < events[next_event - 1].time) audit.times_ordered = false;
    audit.max_outside = std::max(audit.max_outside, outside(e.position));
    if (e.type == EventType::ball_contact) audit.contacts.push_back({e.time, e.other});
    visit(kinetic_energy_of(s, e.velocity, e.spin),
          std::string("event ") + std::to_string(next_event) + " (" + to_string(e.type) + ")",
          e.type == EventType::cushion, e.type == EventType::ball_contact);
    ++next_event;
  };
  for (size_t i = 0; i < path.size(); ++i) {
    const PathSegment& seg = path[i];
    if (seg.t1 < seg.t0) audit.times_ordered = false;
    while (next_event < events.size() && !starts(events[next_event], seg)) take_event();
    // (A segment of zero length by rounding starts where the next one does.)
    while (next_event + 1 < events.size() && starts(events[next_event + 1], seg) &&
           !(i + 1 < path.size() && starts(events[next_event + 1], path[i + 1])))
      take_event();
    if (next_event == events.size()) {
      audit.segments_matched = false;
      break;
    }
    const ShotEvent& start = events[next_event];
    take_event();
    const Vec3 w0 = start.spin;
    for (int k = 1; k <= samples + 1; ++k) {
      const double dt = (seg.t1 - seg.t0) * k / (samples + 1);
      const Vec2 v{seg.v0.x + seg.accel.x * dt, seg.v0.y + seg.accel.y * dt};
      Vec3 w = w0;
      if (seg.motion == Motion::sliding) {
        w.x += 2.5 / radius * seg.accel.y * dt;
        w.y -= 2.5 / radius * seg.accel.x * dt;
      } else {
        w.x = -v.y / radius;
        w.y = v.x / radius;
      }
      const double drop = spin_decel * dt;
      w.z = w0.z > 0.0 ? std::max(0.0, w0.z - drop) : std::min(0.0, w0.z + drop);
      const Vec2 p = seg.at(seg.t0 + dt);
      audit.max_outside = std::max(audit.max_outside, outside(p));
      // The last sample is the segment's end, just before the next event.
      visit(kinetic_energy_of(s, v, w),
            "segment " + std::to_string(i) + " at t = " + std::to_string(seg.t0 + dt), false);
      if (k == samples + 1) {
        // dE/dt bounded by M |v| |a| + I |w| (5 / 2R) |a| + I |w_z| spin_decel.
        const double m = s.ball_and_cushion.mass, inertia = 0.4 * m * radius * radius;
        const double a = std::hypot(seg.accel.x, seg.accel.y);
        const double rate = m * std::hypot(v.x, v.y) * a +
                            inertia * std::hypot(w.x, w.y) * 2.5 / radius * a +
                            inertia * std::abs(w.z) * spin_decel;
        last_allowance = rate * 4.0 * (std::nextafter(seg.t1, INFINITY) - seg.t1);
      }
    }
    // The segment ends where the next event happens.
    if (next_event < events.size()) {
      const Vec2 end = seg.at(seg.t1);
      const Vec2 at = events[next_event].position;
      audit.max_gap = std::max(audit.max_gap, std::hypot(end.x - at.x, end.y - at.y));
      if (events[next_event].time != seg.t1) audit.times_ordered = false;
    }
  }
  while (next_event < events.size()) take_event();
  return audit;
}

// Where a ball is at time t, from its recorded path: on the segment that covers t,
// else where its last event before t left it, else where it started.
inline Vec2 position_at(const BallOutcome& b, double t) {
  for (const PathSegment& seg : b.path)
    if (seg.t0 <= t && t <= seg.t1) return seg.at(t);
  Vec2 p = b.start;
  for (const ShotEvent& e : b.events)
    if (e.time <= t) p = e.position;
  return p;
}

// What walking every ball of a shot and the contacts between them found.
struct ContactAudit {
  int contacts = 0;
  bool paired = true;            // every contact logged for both its balls, at one time
  double max_gap = 0.0;          // largest |distance - 2R| at a contact, in units of 2R
  double max_energy_gain = 0.0;  // largest relative rise of two balls' kinetic energy
                                 // across their contact
  double max_overlap = 0.0;      // deepest two balls (or a ball and an obstacle) overlap,
                                 // in units of 2R, at every event and half-way along
                                 // every segment up to the shot's end
};

// Each contact of balls i < j from both balls' events and audits (audits[k] =
// audit_path of ball k): the n-th contact of i with j is the n-th of j with i.
inline ContactAudit audit_contacts(const Scene& s, const ShotResult& r,
                                   const std::vector<PathAudit>& audits) {
  ContactAudit out;
  const double d2 = 2.0 * s.radius();
  for (size_t k = 0; k < r.balls.size(); ++k) {
    size_t seen = 0;
    std::vector<int> with(r.balls.size(), 0);  // contacts with each other ball so far
    for (const ShotEvent& e : r.balls[k].events) {
      if (e.type != EventType::ball_contact) continue;
      const PathAudit::Contact& mine = audits[k].contacts.at(seen++);
      const int nth = with.at(static_cast<size_t>(e.other))++;
      if (e.other < static_cast<int>(k)) continue;  // counted from the lower index
      ++out.contacts;
      const size_t j = static_cast<size_t>(e.other);
      const ShotEvent* theirs = nullptr;
      const PathAudit::Contact* their_energy = nullptr;
      size_t n = 0;
      int theirs_nth = 0;
      for (const ShotEvent& f : r.balls[j].events) {
        if (f.type != EventType::ball_contact) continue;
        if (f.other == static_cast<int>(k) && theirs_nth++ == nth && f.time == e.time) {
          theirs = &f;
          their_energy = &audits[j].contacts.at(n);
        }
        ++n;
      }
      if (theirs == nullptr) {
        out.paired = false;
        continue;
      }
      const double gap = std::abs(
          std::hypot(e.position.x - theirs->position.x, e.position.y - theirs->position.y) - d2);
      out.max_gap = std::max(out.max_gap, gap / d2);
      const double before = mine.before + their_energy->before;
      const double after = mine.after + their_energy->after;
      if (before > 0.0) out.max_energy_gain = std::max(out.max_energy_gain, (after - before) / before);
    }
  }
  // Overlaps, where every ball is at each event time and half-way along each segment.
  std::vector<double> times;
  double end = 0.0;
  for (const BallOutcome& b : r.balls) {
    for (const ShotEvent& e : b.events) times.push_back(e.time), end = std::max(end, e.time);
    for (const PathSegment& seg : b.path) times.push_back(0.5 * (seg.t0 + seg.t1));
  }
  const auto on_table = [](const BallOutcome& b, double t) {
    return !b.pocketed || b.events.back().time > t;
  };
  std::vector<Vec2> at(r.balls.size());
  for (const double t : times) {
    if (t > end) continue;
    for (size_t k = 0; k < r.balls.size(); ++k) at[k] = position_at(r.balls[k], t);
    for (size_t i = 0; i < r.balls.size(); ++i) {
      if (!on_table(r.balls[i], t)) continue;
      for (size_t j = i + 1; j < r.balls.size(); ++j)
        if (on_table(r.balls[j], t))
          out.max_overlap = std::max(
              out.max_overlap, (d2 - std::hypot(at[i].x - at[j].x, at[i].y - at[j].y)) / d2);
      for (const Vec2& o : s.obstacles)
        out.max_overlap =
            std::max(out.max_overlap, (d2 - std::hypot(at[i].x - o.x, at[i].y - o.y)) / d2);
    }
  }
  return out;
}

// The cue ball's (ShotResult::events and ::path).
inline PathAudit audit_path(const Scene& s, const ShotResult& r, int samples = 4) {
  return audit_path(s, r.events, r.path, samples);
}

}  // namespace cueplan::physics::test
