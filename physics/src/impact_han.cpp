// The Han (2005) cushion model: one impulse at the cushion contact, in closed form
// (docs/cushion_models.md; I. Han, "Dynamics in carom and three cushion billiards",
// Journal of Mechanical Science and Technology 19 (2005) 976-984).
//
// Frame: the cushion frame of PHYSICS.md (X along the cushion, Y from the ball into it,
// Z up). The contact I lies at r = R (0, cos th, sin th) from the centre; its normal n
// points from I to the centre, and the tangent plane at I has the unit vectors
// X = (1, 0, 0) and t = (0, -sin th, cos th).
#include <fmt/compile.h>
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "impact_methods.hpp"

namespace cueplan::physics::detail {

ImpactResult resolve_han_2005(const CushionParams& params, const BallState& incoming) {
  const double m = params.mass;
  const double R = params.radius;
  const double inertia = 0.4 * m * R * R;
  const double s = params.sin_theta();
  const double c = params.cos_theta();
  const double e = params.restitution;
  const double mu = params.mu_cushion;
  const Vec3& v = incoming.velocity;
  const Vec3& w = incoming.spin;

  // Velocity of the ball's surface at I: v + w x r. Its part along -n is the approach
  // c vy; its tangential part is the slip (sigma_X, sigma_t), the slip of Mathavan's
  // eq. (12) as well.
  const double approach = c * v.y;
  const double slip_x = v.x + R * (w.y * s - w.z * c);
  const double slip_t = -v.y * s + R * w.x;
  const double slip = std::hypot(slip_x, slip_t);

  // Normal impulse (Han's P_zE): Newton's restitution of the approach at I, whose
  // effective mass is M (an impulse along n passes through the centre).
  const double normal = (1.0 + e) * m * approach;
  // Tangential impulse: the one that stops the slip (effective mass 2M/7, Han's
  // A = 7/(2M)) when Coulomb's cone holds it (stick), else mu P_zE against the slip.
  const double to_stop = slip * 2.0 * m / 7.0;
  const bool sticks = to_stop <= mu * normal;
  double fx = 0.0, ft = 0.0;
  if (sticks) {
    fx = -2.0 * m / 7.0 * slip_x;
    ft = -2.0 * m / 7.0 * slip_t;
  } else if (slip > 0.0) {
    fx = -mu * normal * slip_x / slip;
    ft = -mu * normal * slip_t / slip;
  }

  // The impulse in the cushion frame: P = P_zE n + fx X + ft t with n = (0, -c, -s).
  // The centre's vertical velocity it would give, (-s P_zE + c ft) / M, is dropped:
  // the ball stays on the cloth (the model's planar assumption).
  ImpactResult r;
  r.status = ImpactStatus::ok;
  r.model = CushionModel::han_2005;
  r.method_used = ImpactMethod::closed_form;
  r.outgoing.velocity = {v.x + fx / m, v.y + (-c * normal - s * ft) / m, 0.0};
  // Angular impulse r x P; the normal part passes through the centre.
  r.outgoing.spin = {w.x + R * ft / inertia, w.y + R * s * fx / inertia,
                     w.z - R * c * fx / inertia};
  r.rebound_speed = std::hypot(r.outgoing.velocity.x, r.outgoing.velocity.y);
  r.rebound_angle_deg =
      std::atan2(-r.outgoing.velocity.y, r.outgoing.velocity.x) * 180.0 / std::numbers::pi;
  r.impulse_compression = normal / (1.0 + e);
  r.impulse_total = normal;
  r.cushion_slipping_at_start = slip > 0.0;
  r.table_slipping_at_start = std::hypot(v.x - R * w.y, v.y + R * w.x) > 0.0;
  if (sticks && slip > 0.0) {
    // The slip reaches zero when the friction mu P has stopped it: P = to_stop / mu.
    r.transitions[0] = {Contact::cushion, true, to_stop / mu};
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
