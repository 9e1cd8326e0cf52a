#include "cueplan/physics/ball_collision.hpp"

#include <cmath>
#include <numbers>

#include "ball_collision_model.hpp"
#include "cueplan/physics/vec2.hpp"

namespace cueplan::physics {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

bool positive_finite(double x) { return std::isfinite(x) && x > 0.0; }
bool non_negative_finite(double x) { return std::isfinite(x) && x >= 0.0; }

// Finite velocity and spin, on the cloth (no vertical velocity). The paths are built only
// for an error: this runs on every collision.
Validation validate_state(const BallState& s, const char* ball) {
  auto field = [&](const char* vector, const char* component) {
    return FieldPath{ball, vector, component};
  };
  if (!std::isfinite(s.velocity.x))
    return invalid(field("velocity", "x"), "must be finite (m/s)", s.velocity.x);
  if (!std::isfinite(s.velocity.y))
    return invalid(field("velocity", "y"), "must be finite (m/s)", s.velocity.y);
  if (!std::isfinite(s.spin.x))
    return invalid(field("spin", "x"), "must be finite (rad/s)", s.spin.x);
  if (!std::isfinite(s.spin.y))
    return invalid(field("spin", "y"), "must be finite (rad/s)", s.spin.y);
  if (!std::isfinite(s.spin.z))
    return invalid(field("spin", "z"), "must be finite (rad/s)", s.spin.z);
  if (s.velocity.z != 0.0)
    return invalid(field("velocity", "z"), "must be 0: the ball stays on the cloth", s.velocity.z);
  return std::nullopt;
}

CollisionResult invalid_result(const BallBallParams& params, ValidationError error) {
  CollisionResult r;
  r.status = CollisionStatus::invalid_input;
  r.model = params.model;
  r.message = error.message();
  r.error = std::move(error);
  return r;
}

// Velocity of the ball's contact point with the cloth, u = v + w x (-R z).
Vec3 cloth_slip(const BallState& s, double radius) {
  return {s.velocity.x - radius * s.spin.y, s.velocity.y + radius * s.spin.x, 0.0};
}

// The collision frame of a line of centres: t = n x z, n, z.
struct Frame {
  Vec3 t, n;
  Vec3 to_frame(Vec3 v) const { return {dot(v, t), dot(v, n), v.z}; }
  Vec3 to_table(Vec3 v) const { return v.x * t + v.y * n + Vec3{0.0, 0.0, v.z}; }
  BallState to_frame(const BallState& s) const { return {to_frame(s.velocity), to_frame(s.spin)}; }
  BallState to_table(const BallState& s) const { return {to_table(s.velocity), to_table(s.spin)}; }
};

// Alciatore's fit of the ball-ball friction to measured throw, for a slip speed in m/s.
double speed_dependent_friction(double slip_speed) {
  return 0.00995 + 0.108 * std::exp(-1.088 * slip_speed);
}

// The closed form (PHYSICS.md, "The closed-form alternative"): one normal impulse
// J = (1 + e_b) M a0 / 2 and one friction impulse against the slip at first contact,
// capped at the impulse that would stop a purely sideways slip.
CollisionResult closed_form(const BallBallParams& p, const BallState& i, const BallState& j) {
  CollisionResult r;
  r.status = CollisionStatus::ok;
  r.model = BallModel::frictional_inelastic;
  const double m = p.mass, radius = p.radius;
  const double a0 = i.velocity.y - j.velocity.y;
  const double normal = 0.5 * (1.0 + p.restitution) * m * a0;
  const double bt = i.velocity.x - j.velocity.x - radius * (i.spin.z + j.spin.z);
  const double bz = radius * (i.spin.x + j.spin.x);
  const double slip = vec2::length(bt, bz);
  double ft = 0.0, fz = 0.0;
  if (slip > 0.0) {
    const double mu =
        p.friction == BallFriction::speed_dependent ? speed_dependent_friction(slip) : p.mu_ball;
    const double magnitude = std::min(mu * normal, m * slip / 7.0);
    ft = -magnitude * bt / slip;
    fz = -magnitude * bz / slip;
  }
  // M dv_i = (F_t, -J), M dv_j = (-F_t, J), I dw_i = I dw_j = R (F_z, 0, -F_t).
  const double spin_per_impulse = 2.5 / (m * radius);  // R / I
  r.ball_i = i;
  r.ball_j = j;
  r.ball_i.velocity.x += ft / m;
  r.ball_i.velocity.y -= normal / m;
  r.ball_j.velocity.x -= ft / m;
  r.ball_j.velocity.y += normal / m;
  for (BallState* b : {&r.ball_i, &r.ball_j}) {
    b->spin.x += spin_per_impulse * fz;
    b->spin.z -= spin_per_impulse * ft;
  }
  // The normal impulse of a frictionless collision, compression half of it at e = 0.
  r.impulse_compression = 0.5 * m * a0;
  r.impulse_total = normal;
  r.work_compression = 0.25 * m * a0 * a0;
  r.work_total = (1.0 - p.restitution * p.restitution) * r.work_compression;
  r.balls_slipping_at_start = slip > 0.0;
  r.cloth_i_slipping_at_start = norm(cloth_slip(i, radius)) > 0.0;
  r.cloth_j_slipping_at_start = norm(cloth_slip(j, radius)) > 0.0;
  return r;
}

// Physical units from scaled ones: V for velocities, V/R for spins, M V for impulses
// and M V^2 for work.
CollisionResult to_result(const BallBallParams& p, const detail::CollisionOutcome& out,
                          double scale) {
  const double spin_unit = scale / p.radius;
  const double impulse_unit = p.mass * scale;
  const double work_unit = p.mass * scale * scale;
  auto state = [&](const detail::ScaledBall& b) {
    return BallState{{b.ut * scale, b.un * scale, 0.0},
                     {b.ot * spin_unit, b.on * spin_unit, b.oz * spin_unit}};
  };
  CollisionResult r;
  r.status = out.status;
  if (out.failure) r.message = out.failure;
  r.model = BallModel::mathavan_2014;
  r.ball_i = state(out.i);
  r.ball_j = state(out.j);
  r.impulse_compression = out.impulse_compression * impulse_unit;
  r.impulse_total = out.impulse_total * impulse_unit;
  r.work_compression = out.work_compression * work_unit;
  r.work_total = out.work_total * work_unit;
  r.balls_slipping_at_start = out.balls_slipping_at_start;
  r.cloth_i_slipping_at_start = out.cloth_i_slipping_at_start;
  r.cloth_j_slipping_at_start = out.cloth_j_slipping_at_start;
  r.transition_count = out.transition_count;
  for (int k = 0; k < out.transition_count; ++k) {
    r.transitions[k] = out.transitions[k];
    r.transitions[k].impulse *= impulse_unit;
  }
  r.rhs_evaluations = out.rhs_evaluations;
  return r;
}

}  // namespace

const char* to_string(BallModel model) {
  switch (model) {
    case BallModel::mathavan_2014: return "mathavan_2014";
    case BallModel::frictional_inelastic: return "frictional_inelastic";
  }
  return "unknown";
}

const char* to_string(BallFriction friction) {
  switch (friction) {
    case BallFriction::constant: return "constant";
    case BallFriction::speed_dependent: return "speed_dependent";
  }
  return "unknown";
}

const char* to_string(CollisionMethod method) {
  switch (method) {
    case CollisionMethod::exact: return "exact";
    case CollisionMethod::paper: return "paper";
    case CollisionMethod::extrapolation: return "extrapolation";
  }
  return "unknown";
}

const char* to_string(CollisionStatus status) {
  switch (status) {
    case CollisionStatus::ok: return "ok";
    case CollisionStatus::invalid_input: return "invalid_input";
    case CollisionStatus::step_limit: return "step_limit";
  }
  return "unknown";
}

const char* to_string(CollisionEvent event) {
  switch (event) {
    case CollisionEvent::balls_geared: return "balls_geared";
    case CollisionEvent::cloth_i_through_zero: return "cloth_i_through_zero";
    case CollisionEvent::cloth_j_through_zero: return "cloth_j_through_zero";
  }
  return "unknown";
}

namespace {

template <class Enum, size_t N>
bool parse_name(const std::string& name, const Enum (&values)[N], Enum* out) {
  for (Enum v : values) {
    if (name == to_string(v)) {
      *out = v;
      return true;
    }
  }
  return false;
}

}  // namespace

bool parse_ball_model(const std::string& name, BallModel* out) {
  constexpr BallModel kAll[] = {BallModel::mathavan_2014, BallModel::frictional_inelastic};
  return parse_name(name, kAll, out);
}

bool parse_ball_friction(const std::string& name, BallFriction* out) {
  constexpr BallFriction kAll[] = {BallFriction::constant, BallFriction::speed_dependent};
  return parse_name(name, kAll, out);
}

bool parse_collision_method(const std::string& name, CollisionMethod* out) {
  constexpr CollisionMethod kAll[] = {CollisionMethod::exact, CollisionMethod::paper,
                                      CollisionMethod::extrapolation};
  return parse_name(name, kAll, out);
}

Validation BallBallParams::validate() const {
  if (!positive_finite(mass)) return invalid({"mass"}, "must be positive and finite (kg)", mass);
  if (!positive_finite(radius))
    return invalid({"radius"}, "must be positive and finite (m)", radius);
  if (!non_negative_finite(mu_ball))
    return invalid({"mu_ball"}, "must be finite and not negative", mu_ball);
  if (!std::isfinite(restitution) || !(restitution > 0.0) || restitution > 1.0)
    return invalid({"restitution"}, "must lie in (0, 1]", restitution);
  if (!non_negative_finite(mu_table))
    return invalid({"mu_table"}, "must be finite and not negative", mu_table);
  if (model != BallModel::mathavan_2014 && model != BallModel::frictional_inelastic)
    return invalid({"model"}, "must be mathavan_2014 or frictional_inelastic",
                   static_cast<double>(model));
  if (friction != BallFriction::constant && friction != BallFriction::speed_dependent)
    return invalid({"friction"}, "must be constant or speed_dependent",
                   static_cast<double>(friction));
  // A cloth slip passes through zero only while 7/2 mu_s mu_b < 1 (ball_collision_model.hpp).
  if (model == BallModel::mathavan_2014 && !(3.5 * mu_ball * mu_table < 1.0)) {
    ValidationError why = invalid({"mu_ball"},
                                  "times {other} must be below 2/7 for mathavan_2014: a larger "
                                  "friction could hold a ball's slip on the cloth at zero, which "
                                  "the model does not describe",
                                  mu_ball);
    why.other = FieldPath{"mu_table"};
    return why;
  }
  return std::nullopt;
}

Validation CollisionOptions::validate() const {
  if (method != CollisionMethod::exact && method != CollisionMethod::paper &&
      method != CollisionMethod::extrapolation)
    return invalid({"method"}, "must be exact, extrapolation or paper",
                   static_cast<double>(method));
  if (method == CollisionMethod::paper && paper_steps < 1)
    return invalid({"paper_steps"}, "must be at least 1", paper_steps);
  if (method != CollisionMethod::paper) {
    if (!std::isfinite(tolerance) || !(tolerance >= 1e-15) || !(tolerance <= 1e-2))
      return invalid({"tolerance"}, "must lie in [1e-15, 1e-2]", tolerance);
    if (max_steps < 1) return invalid({"max_steps"}, "must be at least 1", max_steps);
  }
  return std::nullopt;
}

CollisionResult resolve_collision(const BallBallParams& params, const BallState& ball_i,
                                  const BallState& ball_j, const CollisionOptions& options) {
  if (Validation why = params.validate()) return invalid_result(params, *why);
  if (params.model == BallModel::mathavan_2014)
    if (Validation why = options.validate()) return invalid_result(params, *why);
  if (Validation why = validate_state(ball_i, "ball_i")) return invalid_result(params, *why);
  if (Validation why = validate_state(ball_j, "ball_j")) return invalid_result(params, *why);
  if (!(ball_i.velocity.y > ball_j.velocity.y)) {
    ValidationError why = invalid({"ball_i", "velocity", "y"},
                                  "must exceed {other}: the balls must approach along the line "
                                  "of centres (m/s)",
                                  ball_i.velocity.y);
    why.other = FieldPath{"ball_j", "velocity", "y"};
    return invalid_result(params, std::move(why));
  }
  if (params.model == BallModel::frictional_inelastic) return closed_form(params, ball_i, ball_j);

  // Scaled by the faster ball's speed (ball_collision_model.hpp).
  const double v = std::max(vec2::length(ball_i.velocity.x, ball_i.velocity.y),
                            vec2::length(ball_j.velocity.x, ball_j.velocity.y));
  const double o = params.radius / v;
  auto scaled = [&](const BallState& b) {
    return detail::ScaledBall{b.velocity.x / v, b.velocity.y / v, b.spin.x * o, b.spin.y * o,
                              b.spin.z * o};
  };
  const detail::ScaledCollision collision{params.mu_ball, params.mu_table, params.restitution,
                                          scaled(ball_i), scaled(ball_j)};
  detail::CollisionOutcome out;
  switch (options.method) {
    case CollisionMethod::paper: out = detail::collide_paper(collision, options.paper_steps); break;
    case CollisionMethod::extrapolation:
      out = detail::collide_exact(collision, options.tolerance, options.max_steps);
      break;
    case CollisionMethod::exact:
      out = detail::collide_taylor(collision, options.tolerance, options.max_steps);
      break;
  }
  CollisionResult r = to_result(params, out, v);
  r.method_used = options.method;
  return r;
}

CollisionResult resolve_table_collision(const BallBallParams& params, Vec3 centre_i,
                                        const BallState& ball_i, Vec3 centre_j,
                                        const BallState& ball_j, const CollisionOptions& options) {
  for (const auto& [centre, name] :
       {std::pair{centre_i, "centre_i"}, std::pair{centre_j, "centre_j"}}) {
    if (!std::isfinite(centre.x))
      return invalid_result(params, invalid({name, "x"}, "must be finite (m)", centre.x));
    if (!std::isfinite(centre.y))
      return invalid_result(params, invalid({name, "y"}, "must be finite (m)", centre.y));
  }
  const double dx = centre_j.x - centre_i.x, dy = centre_j.y - centre_i.y;
  const double distance = vec2::length(dx, dy);
  if (!(distance > 0.0)) {
    ValidationError why = invalid({"centre_j"}, "must differ from {other} in x or y");
    why.other = FieldPath{"centre_i"};
    return invalid_result(params, std::move(why));
  }
  if (Validation why = params.validate()) return invalid_result(params, *why);
  if (Validation why = validate_state(ball_i, "ball_i")) return invalid_result(params, *why);
  if (Validation why = validate_state(ball_j, "ball_j")) return invalid_result(params, *why);
  const Frame frame{{dy / distance, -dx / distance, 0.0}, {dx / distance, dy / distance, 0.0}};
  const BallState in_i = frame.to_frame(ball_i), in_j = frame.to_frame(ball_j);
  if (!(in_i.velocity.y > in_j.velocity.y)) {
    ValidationError why = invalid({"ball_i", "velocity"},
                                  "must carry ball_i toward {other} faster than ball_j moves "
                                  "away along the line of centres");
    why.other = FieldPath{"centre_j"};
    return invalid_result(params, std::move(why));
  }
  CollisionResult r = resolve_collision(params, in_i, in_j, options);
  if (r.status != CollisionStatus::invalid_input) {
    r.ball_i = frame.to_table(r.ball_i);
    r.ball_j = frame.to_table(r.ball_j);
  }
  return r;
}

Vec3 rolling_velocity(const BallState& state, double radius) {
  const Vec3 u = cloth_slip(state, radius);
  return {state.velocity.x - 2.0 / 7.0 * u.x, state.velocity.y - 2.0 / 7.0 * u.y, 0.0};
}

CutShot cut_shot(double speed, double cut_deg, Vec3 spin, double radius) {
  const double c = cut_deg * kDegree;
  CutShot shot;
  shot.object_centre = {2.0 * radius * std::cos(c), -2.0 * radius * std::sin(c), 0.0};
  shot.cue_ball = {{speed, 0.0, 0.0}, spin};
  return shot;
}

}  // namespace cueplan::physics
