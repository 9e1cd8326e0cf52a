// The paper's numerical scheme (section 3.4): explicit steps of fixed size in the
// cushion normal impulse, dP_I = (1 + e) M V0 sin(alpha) / N, work by the trapezoidal
// rule (eq. 16a), compression stopped at the first step where the normal approach
// speed is no longer positive (eq. 16c) and the impact at the first step where
// W <= (1 - e^2) W_c (eq. 16b). A contact whose slip is exactly zero has no
// friction (eqs. 15a, 15b); elsewhere friction follows the slip direction, so near a
// stick the scheme chatters around it with an amplitude of one step: first order.
#include <cmath>

#include "impact_methods.hpp"

namespace cueplan::physics::detail {

ScaledOutcome solve_paper(const ScaledImpact& impact, int steps,
                          std::vector<TraceSample>* trace) {
  const Geometry& g = impact.geometry;
  const double e = impact.restitution;
  ScaledOutcome out;
  Scaled q = impact.incoming;
  const double dp = (1.0 + e) * q.uy / steps;

  const Slips start = slips_of(g, q);
  out.cushion_slipping_at_start = start.ix != 0.0 || start.iy != 0.0;
  out.table_slipping_at_start = start.cx != 0.0 || start.cy != 0.0;

  // Each step lowers u_y by at least worst_normal_deceleration * dp, which bounds
  // both phases.
  const double worst = worst_normal_deceleration(g);
  const long long max_iterations = static_cast<long long>(4.0 * steps / worst) + 16;

  bool compressing = true;
  double p = 0.0, work = 0.0, work_end = 0.0;
  if (trace) trace->push_back(scaled_sample(g, q, p, work));
  for (long long n = 0; n < max_iterations; ++n) {
    const Slips sl = slips_of(g, q);
    const double si = std::sqrt(sl.ix * sl.ix + sl.iy * sl.iy);
    const double sc = std::sqrt(sl.cx * sl.cx + sl.cy * sl.cy);
    Friction f;
    if (si > 0.0) {
      f.ix = -g.mu_w * sl.ix / si;
      f.iy = -g.mu_w * sl.iy / si;
    }
    f.pc = g.s - g.c * f.iy;
    if (sc > 0.0) {
      f.cx = -g.mu_s * f.pc * sl.cx / sc;
      f.cy = -g.mu_s * f.pc * sl.cy / sc;
    }
    ++out.rhs_evaluations;
    const Rates r = rates_for(g, f);

    // eq. (17a) and its five companions
    const double uy_before = q.uy;
    q.ux += r.ux * dp;
    q.uy += r.uy * dp;
    q.ox += r.ox * dp;
    q.oy += r.oy * dp;
    q.oz += r.oz * dp;
    p += dp;
    // eq. (16a): dW/dP_I = c u_y
    work += dp * g.c * 0.5 * (uy_before + q.uy);
    if (trace) trace->push_back(scaled_sample(g, q, p, work));

    if (compressing && q.uy <= 0.0) {
      compressing = false;
      out.impulse_compression = p;
      out.work_compression = work;
      work_end = (1.0 - e * e) * work;
    }
    if (!compressing && work <= work_end) {
      out.outgoing = q;
      out.impulse_total = p;
      out.work_total = work;
      return out;
    }
  }
  out.status = ImpactStatus::step_limit;
  out.failure = "paper scheme did not reach the end of the impact within its step bound";
  out.outgoing = q;
  return out;
}

}  // namespace cueplan::physics::detail
