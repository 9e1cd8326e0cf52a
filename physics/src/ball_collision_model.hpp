// The ball-ball collision equations of Mathavan, Jackson & Parkin (2014) in scaled form,
// shared by the exact and the paper methods (private header; PHYSICS.md, "Ball-ball
// collision").
//
// Scaling: velocities by a speed scale V (u = v / V), spins by V / R (o = w R / V),
// impulses by M V (p = P / (M V)) and work by M V^2. With I = 2 M R^2 / 5 the
// equations per unit p hold no mass or radius (which is why the outcome scales with V):
//   du_i = (f_t + g_it, -1 + g_in)    do_i = 5/2 (f_z + g_in, -g_it, -f_t)
//   du_j = (-f_t + g_jt, 1 + g_jn)    do_j = 5/2 (f_z + g_jn, -g_jt, -f_t)
//   dW = a = u_in - u_jn,
// in the collision frame (t, n, z), with (x, y, z) = (t, n, z). f = (f_t, f_z) is the
// friction between the balls on ball i per unit p, g_k the cloth friction on ball k.
// The slips change as
//   d(b_t, b_z) = (7 f_t + g_it - g_jt, 5 f_z + 5/2 (g_in + g_jn))
//   dc_i = (f_t + 7/2 g_it, -1 + 5/2 f_z + 7/2 g_in)
//   dc_j = (-f_t + 7/2 g_jt, 1 + 5/2 f_z + 7/2 g_jn),
// so b_z never changes sign (|5/2 g_n| <= 5/2 mu_s |f_z| < 5 |f_z|), nor does the ball
// pressed into the cloth; and with 7/2 mu_s mu_b < 1 the cloth's friction cannot hold a
// cloth slip at zero against the normal impulse: it passes through.
#pragma once

#include <cmath>

#include "cueplan/physics/ball_collision.hpp"
#include "extrapolation.hpp"

namespace cueplan::physics::detail {

struct ScaledBall {
  double ut = 0.0, un = 0.0;            // velocity
  double ot = 0.0, on = 0.0, oz = 0.0;  // spin
};

// A collision posed in scaled units.
struct ScaledCollision {
  double mu_b = 0.0;
  double mu_s = 0.0;
  double restitution = 1.0;
  ScaledBall i, j;  // a = i.un - j.un > 0
};

// Slip of ball i relative to ball j at their contact, in (t, z).
inline PlanarSlip ball_slip(const ScaledBall& i, const ScaledBall& j) {
  return {i.ut - j.ut - (i.oz + j.oz), i.ot + j.ot};
}

// Slip of a ball on the cloth, in (t, n).
inline PlanarSlip cloth_slip(const ScaledBall& k) { return {k.ut - k.on, k.un + k.ot}; }

// Which ball the vertical friction presses into the cloth: i when f_z < 0, j when f_z > 0.
enum class Pressed { none, i, j };
inline Pressed pressed_by(double fz) {
  return fz < 0.0 ? Pressed::i : (fz > 0.0 ? Pressed::j : Pressed::none);
}

// Direction in which the pressed ball's cloth slip changes when the cloth's own friction
// is left out (dc above with g = 0): a cloth slip at zero leaves it along this direction,
// since the cloth friction against it is too weak to turn it.
inline PlanarSlip cloth_drive(Pressed pressed, double ft, double fz) {
  return pressed == Pressed::i ? PlanarSlip{ft, -1.0 + 2.5 * fz} : PlanarSlip{-ft, 1.0 + 2.5 * fz};
}

struct PairFriction {
  double ft = 0.0, fz = 0.0;    // between the balls, on ball i
  double git = 0.0, gin = 0.0;  // cloth on ball i
  double gjt = 0.0, gjn = 0.0;  // cloth on ball j
};

// Friction f = -mu_b (dx, dz) between the balls (d: the unit direction of their slip, or
// zero when geared) and the cloth's -mu_s |f_z| dc on the pressed ball (dc: the unit
// direction of its cloth slip, or zero).
inline PairFriction friction_for(const ScaledCollision& c, double dx, double dz, PlanarSlip dc) {
  PairFriction f;
  f.ft = -c.mu_b * dx;
  f.fz = -c.mu_b * dz;
  const double normal = std::abs(f.fz);  // the cloth's normal impulse per unit p
  switch (pressed_by(f.fz)) {
    case Pressed::i:
      f.git = -c.mu_s * normal * dc.x;
      f.gin = -c.mu_s * normal * dc.y;
      break;
    case Pressed::j:
      f.gjt = -c.mu_s * normal * dc.x;
      f.gjn = -c.mu_s * normal * dc.y;
      break;
    case Pressed::none: break;
  }
  return f;
}

struct PairRates {
  ScaledBall i, j;  // per unit p
};

// The equations above.
inline PairRates rates_for(const PairFriction& f) {
  PairRates r;
  r.i = {f.ft + f.git, -1.0 + f.gin, 2.5 * (f.fz + f.gin), -2.5 * f.git, -2.5 * f.ft};
  r.j = {-f.ft + f.gjt, 1.0 + f.gjn, 2.5 * (f.fz + f.gjn), -2.5 * f.gjt, -2.5 * f.ft};
  return r;
}

// What a method finds, in scaled units; resolve_collision turns it into a result.
struct CollisionOutcome {
  CollisionStatus status = CollisionStatus::ok;
  const char* failure = nullptr;  // set with step_limit
  ScaledBall i, j;
  double impulse_compression = 0.0;
  double impulse_total = 0.0;
  double work_compression = 0.0;
  double work_total = 0.0;
  bool balls_slipping_at_start = true;
  bool cloth_i_slipping_at_start = true;
  bool cloth_j_slipping_at_start = true;
  std::array<CollisionTransition, kMaxCollisionTransitions> transitions{};  // impulses scaled
  int transition_count = 0;
  int rhs_evaluations = 0;

  void add_transition(CollisionEvent event, double impulse) {
    if (transition_count < kMaxCollisionTransitions)
      transitions[transition_count++] = {event, impulse};
  }
};

CollisionOutcome collide_taylor(const ScaledCollision& collision, double tolerance, int max_steps);
CollisionOutcome collide_exact(const ScaledCollision& collision, double tolerance, int max_steps);
CollisionOutcome collide_paper(const ScaledCollision& collision, int steps);

}  // namespace cueplan::physics::detail
