// The impact equations in scaled form, shared by every method (private header).
//
// Scaling: velocities by a speed scale V (u = v / V), spins by V / R (o = w R / V),
// impulses by M V (p = P_I / (M V)) and work by M V^2. In these units the equations
// hold no mass or radius, which is why the outcome scales with V0 (PHYSICS.md).
//
// Friction per unit of cushion normal impulse, f = (fIx, fIy', fCx, fCy), enters
// eqs. (3a)-(4c) linearly; with I = 2MR^2/5 they give (s = sin th, c = cos th)
//   du_x = fIx + fCx                    do_x = 5/2 (fIy' + fCy)
//   du_y = -c - s fIy' + fCy            do_y = 5/2 (s fIx - fCx)
//   dW   = c u_y                        do_z = -5/2 c fIx
// and the slips at I and C change as  d(slip) = g + K f  with the symmetric matrix
//   K = [[7/2, 0, a, 0], [0, b, 0, d], [a, 0, 7/2, 0], [0, d, 0, 7/2]],
//   a = 1 - 5s/2, b = s^2 + 5/2, d = 5/2 - s, g = (0, s c, 0, -c).
// The table's normal impulse per unit P_I is p_C = s - c fIy' (eq. 3d).
//
// A slipping contact has Coulomb friction against its slip (eqs. 7, 10). A contact
// whose slip is zero sticks when the friction that keeps the slip at zero lies in
// its cone (the Filippov solution of Coulomb friction); it is found here from the
// linear system above, so an integrator never chatters there.
#pragma once

#include <cmath>

#include "cueplan/physics/cushion_impact.hpp"

namespace cueplan::physics::detail {

struct Geometry {
  double s = 0.4;  // sin(theta)
  double c = 0.0;  // cos(theta)
  double mu_w = 0.0;
  double mu_s = 0.0;
  double a = 0.0, b = 0.0, d = 0.0;

  static Geometry from(const CushionParams& params) {
    Geometry g;
    g.s = params.sin_theta();
    g.c = std::sqrt(1.0 - g.s * g.s);
    g.mu_w = params.mu_cushion;
    g.mu_s = params.mu_table;
    g.a = 1.0 - 2.5 * g.s;
    g.b = g.s * g.s + 2.5;
    g.d = 2.5 - g.s;
    return g;
  }
};

// Scaled centroid state (u_y is carried separately by the integrators that use it
// as their independent variable).
struct Scaled {
  double ux = 0.0, uy = 0.0;
  double ox = 0.0, oy = 0.0, oz = 0.0;
};

struct Slips {
  double ix = 0.0, iy = 0.0;  // at the cushion, along X and Y' (eq. 12)
  double cx = 0.0, cy = 0.0;  // at the table, along X and Y (eq. 13)
};

inline Slips slips_of(const Geometry& g, const Scaled& q) {
  return {q.ux + q.oy * g.s - q.oz * g.c, -q.uy * g.s + q.ox, q.ux - q.oy, q.uy + q.ox};
}

struct Friction {
  double ix = 0.0, iy = 0.0, cx = 0.0, cy = 0.0;
  double pc = 0.0;  // table normal impulse per unit P_I
};

// Which contacts stick; a slipping contact with (numerically) zero slip takes its
// direction from `seed`.
struct Modes {
  bool stick_i = false;
  bool stick_c = false;
};

struct Direction {
  double x = 1.0, y = 0.0;
};

// Unit direction of a slip, or the seed when the slip is too small to have one.
inline Direction direction_of(double x, double y, Direction seed, double tiny) {
  double r = std::sqrt(x * x + y * y);
  if (r <= tiny) return seed;
  return {x / r, y / r};
}

// Friction for the given modes and slip directions (slipping contacts only use them).
inline Friction friction_for(const Geometry& g, Modes m, Direction di, Direction dc) {
  Friction f;
  if (!m.stick_i && !m.stick_c) {
    f.ix = -g.mu_w * di.x;
    f.iy = -g.mu_w * di.y;
    f.pc = g.s - g.c * f.iy;
    f.cx = -g.mu_s * f.pc * dc.x;
    f.cy = -g.mu_s * f.pc * dc.y;
  } else if (m.stick_i && !m.stick_c) {
    // d(slip_I) = 0 with f_C = -mu_s (s - c fIy') dc
    f.iy = (-g.s * g.c + g.d * g.mu_s * g.s * dc.y) / (g.b + g.d * g.mu_s * g.c * dc.y);
    f.pc = g.s - g.c * f.iy;
    f.cx = -g.mu_s * f.pc * dc.x;
    f.cy = -g.mu_s * f.pc * dc.y;
    f.ix = -g.a * f.cx / 3.5;
  } else if (!m.stick_i && m.stick_c) {
    // d(slip_C) = 0 with f_I = -mu_w di
    f.ix = -g.mu_w * di.x;
    f.iy = -g.mu_w * di.y;
    f.pc = g.s - g.c * f.iy;
    f.cx = -g.a * f.ix / 3.5;
    f.cy = (g.c - g.d * f.iy) / 3.5;
  } else {
    // Both stick: the X block is homogeneous, the Y block is [b d; d 7/2] f = (-s c, c).
    const double det = 3.5 * g.b - g.d * g.d;
    f.ix = 0.0;
    f.cx = 0.0;
    f.iy = (-3.5 * g.s * g.c - g.d * g.c) / det;
    f.cy = (g.b * g.c + g.d * g.s * g.c) / det;
    f.pc = g.s - g.c * f.iy;
  }
  return f;
}

// How far each sticking contact's friction is inside its cone, scaled so that
// 0 is the cone's edge (negative: the stick cannot hold).
inline double stick_margin_i(const Geometry& g, const Friction& f) {
  return g.mu_w - std::sqrt(f.ix * f.ix + f.iy * f.iy);
}
inline double stick_margin_c(const Geometry& g, const Friction& f) {
  return g.mu_s * f.pc - std::sqrt(f.cx * f.cx + f.cy * f.cy);
}

struct Rates {
  double ux = 0.0, uy = 0.0, ox = 0.0, oy = 0.0, oz = 0.0;  // per unit scaled P_I
};

// Eqs. (14a)-(14f) written with the friction components.
inline Rates rates_for(const Geometry& g, const Friction& f) {
  return {f.ix + f.cx, -g.c - g.s * f.iy + f.cy, 2.5 * (f.iy + f.cy),
          2.5 * (g.s * f.ix - f.cx), -2.5 * g.c * f.ix};
}

// The lowest rate at which u_y can fall per unit P_I with any admissible friction:
// positive means the cushion always stops the ball, so every impact ends.
inline double worst_normal_deceleration(const Geometry& g) {
  return g.c - g.s * g.mu_w - g.mu_s * (g.s + g.c * g.mu_w);
}

}  // namespace cueplan::physics::detail
