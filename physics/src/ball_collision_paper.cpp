// The `paper` method of the ball-ball collision: the equations of
// ball_collision_model.hpp in explicit steps of fixed size in the normal impulse,
// dP = (1 + e_b) M a0 / (2 N) (N steps when there is no friction), the work by the
// trapezoidal rule, compression stopped at the first step where the normal approach
// speed is no longer positive and the collision at the first step where
// W <= (1 - e_b^2) W_c - the scheme of the cushion's paper method. Friction follows the
// slips' directions and is zero where a slip is exactly zero, so where the balls gear the
// scheme chatters about b = 0 with an amplitude of one step: first order.
#include <cmath>

#include "ball_collision_model.hpp"

namespace cueplan::physics::detail {

namespace {

// Unit direction of a slip, or zero where it is exactly zero.
PlanarSlip unit_or_zero(PlanarSlip s) {
  const double m = s.magnitude();
  return m > 0.0 ? PlanarSlip{s.x / m, s.y / m} : PlanarSlip{};
}

void add(ScaledBall* k, const ScaledBall& rate, double dp) {
  k->ut += rate.ut * dp;
  k->un += rate.un * dp;
  k->ot += rate.ot * dp;
  k->on += rate.on * dp;
  k->oz += rate.oz * dp;
}

}  // namespace

CollisionOutcome collide_paper(const ScaledCollision& c, int steps) {
  CollisionOutcome out;
  ScaledBall bi = c.i, bj = c.j;
  const double a0 = bi.un - bj.un;
  const double dp = (1.0 + c.restitution) * a0 / (2.0 * steps);

  const PlanarSlip b0 = ball_slip(bi, bj), ci0 = cloth_slip(bi), cj0 = cloth_slip(bj);
  out.balls_slipping_at_start = b0.x != 0.0 || b0.y != 0.0;
  out.cloth_i_slipping_at_start = ci0.x != 0.0 || ci0.y != 0.0;
  out.cloth_j_slipping_at_start = cj0.x != 0.0 || cj0.y != 0.0;

  // Each step lowers a by at least (2 - mu_s mu_b) dp, which bounds both phases.
  const double worst = 2.0 - c.mu_s * c.mu_b;
  const long long max_iterations = static_cast<long long>(4.0 * steps / worst) + 16;

  bool compressing = true;
  double p = 0.0, work = 0.0, work_end = 0.0;
  for (long long n = 0; n < max_iterations; ++n) {
    const PlanarSlip db = unit_or_zero(ball_slip(bi, bj));
    const double fz = -c.mu_b * db.y;
    const Pressed pressed = pressed_by(fz);
    const PlanarSlip dc = pressed == Pressed::i   ? unit_or_zero(cloth_slip(bi))
                          : pressed == Pressed::j ? unit_or_zero(cloth_slip(bj))
                                                  : PlanarSlip{};
    ++out.rhs_evaluations;
    const PairRates r = rates_for(friction_for(c, db.x, db.y, dc));

    const double a_before = bi.un - bj.un;
    add(&bi, r.i, dp);
    add(&bj, r.j, dp);
    p += dp;
    const double a = bi.un - bj.un;
    work += dp * 0.5 * (a_before + a);  // dW/dP = a

    if (compressing && a <= 0.0) {
      compressing = false;
      out.impulse_compression = p;
      out.work_compression = work;
      work_end = (1.0 - c.restitution * c.restitution) * work;
    }
    if (!compressing && work <= work_end) {
      out.i = bi;
      out.j = bj;
      out.impulse_total = p;
      out.work_total = work;
      return out;
    }
  }
  out.status = CollisionStatus::step_limit;
  out.failure = "paper scheme did not reach the end of the collision within its step bound";
  out.i = bi;
  out.j = bj;
  return out;
}

}  // namespace cueplan::physics::detail
