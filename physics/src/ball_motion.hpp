// A ball on the cloth between events, in closed form (PHYSICS.md, "Ball on the cloth"),
// and the contacts its quadratic path meets: circles (pockets, obstacles) and another
// ball's path. Private to the shot simulator.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "cueplan/physics/shot.hpp"
#include "cueplan/physics/vec2.hpp"
#include "polynomial_roots.hpp"

namespace cueplan::physics::detail {

inline constexpr double kNever = std::numeric_limits<double>::infinity();

using vec2::operator+;
using vec2::operator-;
using vec2::operator*;
using vec2::dot;
using vec2::norm;

// A ball's state on the cloth.
struct Ball {
  Vec2 p;  // m
  Vec2 v;  // m/s
  Vec3 w;  // rad/s
};

// Rates of the cloth model (PHYSICS.md, "Ball on the cloth").
struct ClothModel {
  double radius;
  double slide_decel;  // mu_s g
  double roll_decel;   // mu_r g
  double spin_decel;   // 5 mu_sp g / (2R), for w_z
  double slide_spin;   // 5 mu_s g / (2R), for the horizontal spin while sliding

  explicit ClothModel(const Scene& s)
      : radius(s.radius()),
        slide_decel(s.cloth.mu_slide * s.cloth.gravity),
        roll_decel(s.cloth.mu_roll * s.cloth.gravity),
        spin_decel(2.5 * s.cloth.mu_spin * s.cloth.gravity / s.radius()),
        slide_spin(2.5 * s.cloth.mu_slide * s.cloth.gravity / s.radius()) {}

  // Velocity of the contact point with the cloth: v + w x (-R z).
  Vec2 slip(const Ball& b) const { return {b.v.x - radius * b.w.y, b.v.y + radius * b.w.x}; }
};

// A piece of motion with constant acceleration, from a state until its motion changes.
struct Piece {
  Motion motion = Motion::resting;
  Vec2 accel;
  Vec2 spin_rate;            // d(w_x, w_y)/dt while sliding
  double duration = kNever;  // until slide to roll, or rest
};

inline Piece piece_from(const ClothModel& m, const Ball& b) {
  Piece piece;
  const Vec2 u = m.slip(b);
  const double us = norm(u);
  const double speed = norm(b.v);
  const double scale = speed + m.radius * vec2::length(b.w.x, b.w.y);
  if (us > 1e-12 * scale && us > 0.0) {
    // Sliding: friction against the slip, which keeps its direction and shrinks
    // at 7/2 mu_s g.
    const Vec2 d = (1.0 / us) * u;
    piece.motion = Motion::sliding;
    piece.accel = -m.slide_decel * d;
    piece.spin_rate = {-m.slide_spin * d.y, m.slide_spin * d.x};
    piece.duration = 2.0 * us / (7.0 * m.slide_decel);
  } else if (speed > 0.0) {
    piece.motion = Motion::rolling;
    piece.accel = (-m.roll_decel / speed) * b.v;
    piece.duration = speed / m.roll_decel;
  }
  return piece;
}

// The ball `dt` further along its piece (a resting ball only spins down).
inline void advance(const ClothModel& m, const Piece& piece, double dt, Ball* b) {
  b->p = b->p + dt * b->v + (0.5 * dt * dt) * piece.accel;
  b->v = b->v + dt * piece.accel;
  if (piece.motion == Motion::sliding) {
    b->w.x += piece.spin_rate.x * dt;
    b->w.y += piece.spin_rate.y * dt;
  } else {
    b->w.x = -b->v.y / m.radius;
    b->w.y = b->v.x / m.radius;
  }
  // Sidespin decays toward zero in every phase.
  const double drop = m.spin_decel * dt;
  b->w.z = b->w.z > 0.0 ? std::max(0.0, b->w.z - drop) : std::min(0.0, b->w.z + drop);
}

// Position coefficients of a piece: p(t) = a0 + a1 t + a2 t^2.
struct Quadratic {
  Vec2 a0, a1, a2;
};

// The box a quadratic path sweeps over [0, horizon].
struct Box {
  double xlo, xhi, ylo, yhi;
};

inline Box box_of(const Quadratic& q, double horizon) {
  auto range = [&](double p0, double v, double a2, double* lo, double* hi) {
    const double end = p0 + v * horizon + a2 * horizon * horizon;
    *lo = std::min(p0, end);
    *hi = std::max(p0, end);
    if (a2 != 0.0) {
      const double t = -v / (2.0 * a2);
      if (t > 0.0 && t < horizon) {
        const double mid = p0 + v * t + a2 * t * t;
        *lo = std::min(*lo, mid);
        *hi = std::max(*hi, mid);
      }
    }
  };
  Box box;
  range(q.a0.x, q.a1.x, q.a2.x, &box.xlo, &box.xhi);
  range(q.a0.y, q.a1.y, q.a2.y, &box.ylo, &box.yhi);
  return box;
}

// |d(t)|^2 - r^2 for d(t) = d0 + d1 t + d2 t^2: a quartic in t, coefficients c[0..4].
inline void distance_quartic(Vec2 d0, Vec2 d1, Vec2 d2, double r, double* c) {
  c[0] = dot(d0, d0) - r * r;
  c[1] = 2.0 * dot(d0, d1);
  c[2] = dot(d1, d1) + 2.0 * dot(d0, d2);
  c[3] = 2.0 * dot(d1, d2);
  c[4] = dot(d2, d2);
}

// First time in [0, horizon] at which the centre enters the circle (c, r), or kNever.
// The path's bounding box is tested first, which rules out most circles cheaply.
inline double entry_time(const Quadratic& q, double horizon, Vec2 c, double r) {
  const Box b = box_of(q, horizon);
  if (c.x + r < b.xlo || c.x - r > b.xhi || c.y + r < b.ylo || c.y - r > b.yhi) return kNever;
  double coeff[5];
  distance_quartic(q.a0 - c, q.a1, q.a2, r, coeff);
  if (coeff[0] <= 0.0) return coeff[1] < 0.0 || coeff[0] < 0.0 ? 0.0 : kNever;
  double roots[kMaxDegree];
  const int n = roots_in(coeff, 4, 0.0, horizon, roots);
  return n > 0 ? roots[0] : kNever;
}

// When two balls next meet: the time, and whether they were touching already (within
// 2R, as rounding leaves balls that have just collided) when they began to approach.
struct Meeting {
  double time = kNever;
  bool touching = false;
  double parts = kNever;  // where, after a crossing into 2R, the paths part again (if
                          // within the horizon): how far a graze reaches
};

// The first contact in (after, horizon] - in [0, horizon] when `after` is negative - of
// two balls on the paths qi and qj (about the same instant), or none. With
// f(t) = |p_j(t) - p_i(t)|^2 - diameter^2, a quartic, balls apart meet where f falls
// through zero; balls that start touching (f(0) <= 0) meet as soon as they approach
// (f' < 0), now or where f' turns negative before f has risen above zero. Boxes first:
// most pairs are apart.
inline Meeting contact_time(const Quadratic& qi, const Quadratic& qj, double horizon,
                            double diameter, double after) {
  const Box a = box_of(qi, horizon), b = box_of(qj, horizon);
  if (a.xlo > b.xhi + diameter || b.xlo > a.xhi + diameter || a.ylo > b.yhi + diameter ||
      b.ylo > a.yhi + diameter)
    return {};
  double c[5];
  distance_quartic(qj.a0 - qi.a0, qj.a1 - qi.a1, qj.a2 - qi.a2, diameter, c);
  // Touching (or a rounding inside) and approaching now.
  if (after < 0.0 && c[0] <= 0.0 && c[1] < 0.0) return {0.0, true};
  const double slope[4] = {c[1], 2.0 * c[2], 3.0 * c[3], 4.0 * c[4]};  // f'
  double roots[kMaxDegree];
  double rises_at = kNever;  // where f first rises through zero (the balls part)
  const int n = roots_in(c, 4, 0.0, horizon, roots);
  for (int k = 0; k < n; ++k) {
    const double t = roots[k];
    // Which way f crosses: its sign half-way to the next root (or to the horizon), far
    // from both, rather than f' at the root, which rounding decides for balls that move
    // together.
    const double beyond = k + 1 < n ? 0.5 * (t + roots[k + 1]) : 0.5 * (t + horizon);
    const double next = beyond > t ? evaluate(c, 4, beyond) : evaluate(slope, 3, t);
    if (next > 0.0 && rises_at == kNever) rises_at = t;
    // The distance falls through 2R here: an approach, not a parting.
    if (t > after && next < 0.0) {
      if (c[0] > 0.0 || rises_at < t) return {t, false, k + 1 < n ? roots[k + 1] : kNever};
      break;  // touching until then: the turn below comes first
    }
  }
  if (c[0] > 0.0) return {};
  // Touching (or a rounding inside) and parting now: they meet again where f' turns
  // negative, if f has not risen above zero by then.
  double turns[kMaxDegree];
  const int m = roots_in(slope, 3, 0.0, horizon, turns);
  for (int k = 0; k < m; ++k) {
    const double t = turns[k];
    if (!(t > after) || !(t < rises_at)) continue;
    const double curve[3] = {slope[1], 2.0 * slope[2], 3.0 * slope[3]};  // f''
    if (evaluate(curve, 2, t) < 0.0) return {t, true};
  }
  return {};
}

// Upper bound on how far the ball can still travel (sliding, then rolling to rest).
inline double reach(const ClothModel& m, const Ball& b) {
  const double slide_time = 2.0 * norm(m.slip(b)) / (7.0 * m.slide_decel);
  const double top_speed = norm(b.v) + m.slide_decel * slide_time;
  return top_speed * slide_time + top_speed * top_speed / (2.0 * m.roll_decel);
}

}  // namespace cueplan::physics::detail
