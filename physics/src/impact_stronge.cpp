// A Stronge-type compliant cushion (stronge_compliant): the contact of ball and cushion
// nose is a normal spring, stiffer while it unloads (energetic restitution e), in
// parallel with a tangential spring in series with a Coulomb slider (docs/cushion_models.md;
// W. J. Stronge, "Planar impact of rough compliant bodies", International Journal of
// Impact Engineering 15 (1994) 435-450, and "Impact Mechanics", 2nd ed., Cambridge
// University Press 2018, the chapter on tangential compliance).
//
// Frame and contact geometry as impact_han.cpp: the cushion frame of PHYSICS.md, the
// contact I at r = R (0, cos th, sin th) from the centre, its normal n = (0, -c, -s) from I
// to the centre and the tangent plane (X, t), t = (0, -s, c). A sphere's contact point has
// the effective mass M along n and 2M/7 in the tangent plane, uncoupled.
//
// In the time tau = omega t (omega the normal spring's frequency with mass M) the normal
// force is known in closed form: F_n / (M omega) = v0 sin(tau) while it compresses
// (tau < pi/2), v0 cos((tau - pi/2) / e) while it unloads at e^-2 times the stiffness,
// until tau = (1 + e) pi / 2; v0 is the approach speed along -n. The tangential spring,
// eta^2 times softer than the normal one, carries the force q (per M omega, a 2-vector in
// the tangent plane) opposing the slip sigma of the ball's surface at I:
//   d sigma / d tau = -(7/2) q,   d q / d tau = sigma / eta^2 while it sticks,
// and |q| <= mu F_n / (M omega) (it slides on the cone, in the direction the spring is
// loaded). Stormer-Verlet steps (half a kick of q on sigma, q's drift, the other half),
// kStrongeSteps equal steps of tau, the cone applied by projection after each drift (a
// return map, as in discrete-element contact codes); the tangential impulse is -M times
// the integral of q over tau.
#include <fmt/compile.h>
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "impact_methods.hpp"

namespace cueplan::physics::detail {

ImpactResult resolve_stronge_compliant(const CushionParams& params, const BallState& incoming) {
  constexpr double kPi = std::numbers::pi;
  const double m = params.mass;
  const double R = params.radius;
  const double inertia = 0.4 * m * R * R;
  const double s = params.sin_theta();
  const double c = params.cos_theta();
  const double e = params.restitution;
  const double mu = params.mu_cushion;
  const double eta2 = params.eta_squared;
  const Vec3& v = incoming.velocity;
  const Vec3& w = incoming.spin;

  const double approach = c * v.y;  // v0
  double sx = v.x + R * (w.y * s - w.z * c);
  double st = -v.y * s + R * w.x;
  const bool slipping_at_start = std::hypot(sx, st) > 0.0;

  const double tau_c = 0.5 * kPi;
  const double tau_f = (1.0 + e) * tau_c;
  const double h = tau_f / kStrongeSteps;
  double qx = 0.0, qt = 0.0;  // tangential spring force / (M omega)
  double jx = 0.0, jt = 0.0;  // integral of the friction force / (M omega) over tau
  bool stuck = false;
  double stick_impulse = -1.0;  // normal impulse (N s) when the slider first holds
  for (int k = 1; k <= kStrongeSteps; ++k) {
    const double tau = k * h;
    const double f = tau <= tau_c ? std::sin(tau) : std::cos((tau - tau_c) / e);
    const double cap = mu * approach * std::max(0.0, f);
    // Half a kick of the spring on the slip, the spring's drift, the cone, the other half.
    sx -= 1.75 * h * qx;
    st -= 1.75 * h * qt;
    jx -= 0.5 * h * qx;
    jt -= 0.5 * h * qt;
    qx += h * sx / eta2;
    qt += h * st / eta2;
    const double q = std::hypot(qx, qt);
    stuck = q <= cap;
    if (!stuck) {
      const double scale = q > 0.0 ? cap / q : 0.0;
      qx *= scale;
      qt *= scale;
    } else if (stick_impulse < 0.0 && q > 0.0) {
      const double p = tau <= tau_c ? 1.0 - std::cos(tau) : 1.0 + e * std::sin((tau - tau_c) / e);
      stick_impulse = m * approach * p;
    }
    sx -= 1.75 * h * qx;
    st -= 1.75 * h * qt;
    jx -= 0.5 * h * qx;
    jt -= 0.5 * h * qt;
  }

  const double normal = (1.0 + e) * m * approach;
  const double fx = m * jx, ft = m * jt;
  // As in han_2005: the impulse P = P_n n + fx X + ft t acts on the centre and turns the
  // ball about it; the vertical velocity it would give is dropped (the ball stays on
  // the cloth).
  ImpactResult r;
  r.status = ImpactStatus::ok;
  r.model = CushionModel::stronge_compliant;
  r.method_used = ImpactMethod::closed_form;
  r.outgoing.velocity = {v.x + fx / m, v.y + (-c * normal - s * ft) / m, 0.0};
  r.outgoing.spin = {w.x + R * ft / inertia, w.y + R * s * fx / inertia,
                     w.z - R * c * fx / inertia};
  r.rebound_speed = std::hypot(r.outgoing.velocity.x, r.outgoing.velocity.y);
  r.rebound_angle_deg =
      std::atan2(-r.outgoing.velocity.y, r.outgoing.velocity.x) * 180.0 / std::numbers::pi;
  r.impulse_compression = m * approach;
  r.impulse_total = normal;
  r.cushion_slipping_at_start = slipping_at_start;
  r.table_slipping_at_start = std::hypot(v.x - R * w.y, v.y + R * w.x) > 0.0;
  if (stick_impulse >= 0.0) {
    r.transitions[0] = {Contact::cushion, true, stick_impulse};
    r.transition_count = 1;
  }
  if (v.y > params.rigid_speed_limit) {
    r.status = ImpactStatus::rigid_limit_exceeded;
    r.message = fmt::format(
        FMT_COMPILE("velocity.y is above the rigid-cushion limit (m/s), got {:.10g}"), v.y);
  }
  return r;
}

}  // namespace cueplan::physics::detail
