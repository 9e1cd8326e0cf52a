#include "cueplan/physics/cushion_impact.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "cueplan/physics/impact_table.hpp"
#include "impact_methods.hpp"

namespace cueplan::physics {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

bool positive_finite(double x) { return std::isfinite(x) && x > 0.0; }

Validation validate_state(const BallState& in) {
  const Vec3& v = in.velocity;
  const Vec3& w = in.spin;
  if (!std::isfinite(v.x)) return invalid({"velocity", "x"}, "must be finite (m/s)", v.x);
  if (!std::isfinite(v.y)) return invalid({"velocity", "y"}, "must be finite (m/s)", v.y);
  if (!std::isfinite(w.x)) return invalid({"spin", "x"}, "must be finite (rad/s)", w.x);
  if (!std::isfinite(w.y)) return invalid({"spin", "y"}, "must be finite (rad/s)", w.y);
  if (!std::isfinite(w.z)) return invalid({"spin", "z"}, "must be finite (rad/s)", w.z);
  if (v.z != 0.0) return invalid({"velocity", "z"}, "must be 0: the ball rolls on the cloth", v.z);
  if (!(v.y > 0.0))
    return invalid({"velocity", "y"}, "must be positive: the ball must move into the cushion",
                   v.y);
  return {};
}

}  // namespace

double CushionParams::cos_theta() const {
  const double s = sin_theta();
  return std::sqrt(1.0 - s * s);
}

Validation CushionParams::validate() const {
  if (!positive_finite(mass)) return invalid({"mass"}, "must be positive and finite (kg)", mass);
  if (!positive_finite(radius))
    return invalid({"radius"}, "must be positive and finite (m)", radius);
  if (!std::isfinite(cushion_height) || !(cushion_height > radius) ||
      !(cushion_height < 2.0 * radius))
    return invalid({"cushion_height"},
                   "must lie between radius and 2*radius (m): the cushion touches the ball "
                   "above its equator",
                   cushion_height);
  if (!std::isfinite(mu_cushion) || mu_cushion < 0.0)
    return invalid({"mu_cushion"}, "must be finite and not negative", mu_cushion);
  if (!std::isfinite(mu_table) || mu_table < 0.0)
    return invalid({"mu_table"}, "must be finite and not negative", mu_table);
  if (!std::isfinite(restitution) || !(restitution > 0.0) || restitution > 1.0)
    return invalid({"restitution"}, "must lie in (0, 1]", restitution);
  if (!positive_finite(rigid_speed_limit))
    return invalid({"rigid_speed_limit"}, "must be positive and finite (m/s)", rigid_speed_limit);
  const double s = sin_theta();
  const double c = cos_theta();
  if (model == CushionModel::stronge_compliant &&
      !(std::isfinite(eta_squared) && eta_squared > 0.875 && eta_squared < 3.5))
    return invalid({"eta_squared"},
                   "must lie in (0.875, 3.5) for cushion_model stronge_compliant: the tangential "
                   "spring must vibrate between 1 and 2 times as fast as the normal one",
                   eta_squared);
  if (model == CushionModel::han_2005 || model == CushionModel::stronge_compliant) {
    // The worst friction (mu P_zE pressing the ball down along the tangent) must still
    // turn the centre round: vy' / vy = 1 - (1 + e) c (c - mu s) < 0.
    if (!((1.0 + restitution) * c * (c - mu_cushion * s) > 1.0)) {
      ValidationError e = invalid({"restitution"},
                                  "is too small together with {other} for cushion_model "
                                  "han_2005 or stronge_compliant: (1 + restitution) cos(theta) (cos(theta) - "
                                  "mu_cushion sin(theta)) must exceed 1, or a ball may leave "
                                  "the cushion still moving into it",
                                  restitution);
      e.other = FieldPath{"mu_cushion"};
      return e;
    }
    return {};
  }
  if (model != CushionModel::mathavan_2010)
    return invalid({"model"}, "must be mathavan_2010, han_2005 or stronge_compliant",
                   static_cast<int>(model));
  // The table must keep pushing up: p_C = s - c fIy' > 0 for any |fIy'| <= mu_w.
  if (!(mu_cushion < s / c))
    return invalid({"mu_cushion"},
                   "must be below tan(theta) of the cushion contact, or the cushion lifts the "
                   "ball off the cloth",
                   mu_cushion);
  if (!(detail::worst_normal_deceleration(detail::Geometry::from(*this)) > 0.0)) {
    ValidationError e = invalid({"mu_table"},
                                "is too large together with {other}: friction could stop the "
                                "cushion from turning the ball round",
                                mu_table);
    e.other = FieldPath{"mu_cushion"};
    return e;
  }
  return {};
}

CushionParams params_for_radius(double radius) {
  CushionParams params;
  params.radius = radius;
  params.cushion_height = 1.4 * radius;
  return params;
}

BallState incoming_state(double speed, double alpha_deg, double topspin, double sidespin) {
  const double ca = std::cos(alpha_deg * kDegree);
  const double sa = std::sin(alpha_deg * kDegree);
  BallState state;
  state.velocity = {speed * ca, speed * sa, 0.0};
  state.spin = {-topspin * sa, topspin * ca, sidespin};
  return state;
}

BallState incoming_state_k(double speed, double alpha_deg, double topspin_k, double sidespin_k,
                           double radius) {
  return incoming_state(speed, alpha_deg, topspin_k * speed / radius,
                        sidespin_k * speed / radius);
}

double kinetic_energy(const CushionParams& params, const BallState& state) {
  const double inertia = 0.4 * params.mass * params.radius * params.radius;
  return 0.5 * params.mass * dot(state.velocity, state.velocity) +
         0.5 * inertia * dot(state.spin, state.spin);
}

const char* to_string(ImpactMethod method) {
  switch (method) {
    case ImpactMethod::exact: return "exact";
    case ImpactMethod::extrapolation: return "extrapolation";
    case ImpactMethod::paper: return "paper";
    case ImpactMethod::table: return "table";
    case ImpactMethod::closed_form: return "closed_form";
  }
  return "unknown";
}

const char* to_string(CushionModel model) {
  switch (model) {
    case CushionModel::mathavan_2010: return "mathavan_2010";
    case CushionModel::han_2005: return "han_2005";
    case CushionModel::stronge_compliant: return "stronge_compliant";
  }
  return "unknown";
}

bool parse_cushion_model(const std::string& name, CushionModel* model) {
  for (CushionModel m : {CushionModel::mathavan_2010, CushionModel::han_2005,
                         CushionModel::stronge_compliant}) {
    if (name == to_string(m)) {
      *model = m;
      return true;
    }
  }
  return false;
}

const char* to_string(ImpactStatus status) {
  switch (status) {
    case ImpactStatus::ok: return "ok";
    case ImpactStatus::rigid_limit_exceeded: return "rigid_limit_exceeded";
    case ImpactStatus::invalid_input: return "invalid_input";
    case ImpactStatus::step_limit: return "step_limit";
  }
  return "unknown";
}

const char* to_string(Contact contact) {
  return contact == Contact::cushion ? "cushion" : "table";
}

bool parse_method(const std::string& name, ImpactMethod* method) {
  for (ImpactMethod m : {ImpactMethod::exact, ImpactMethod::extrapolation, ImpactMethod::paper,
                         ImpactMethod::table}) {
    if (name == to_string(m)) {
      *method = m;
      return true;
    }
  }
  return false;
}

namespace detail {

TraceSample scaled_sample(const Geometry& g, const Scaled& q, double impulse, double work) {
  const Slips sl = slips_of(g, q);
  TraceSample t;
  t.impulse = impulse;
  t.slip_cushion = std::hypot(sl.ix, sl.iy);
  t.phi_cushion_deg = std::atan2(sl.iy, sl.ix) / kDegree;
  t.slip_table = std::hypot(sl.cx, sl.cy);
  t.phi_table_deg = std::atan2(sl.cy, sl.cx) / kDegree;
  t.work = work;
  t.state.velocity = {q.ux, q.uy, 0.0};
  t.state.spin = {q.ox, q.oy, q.oz};
  return t;
}

}  // namespace detail

namespace {

// Physical units from scaled ones: V for velocities, V/R for spins, M V for
// impulses and M V^2 for work.
ImpactResult to_result(const CushionParams& params, const detail::ScaledOutcome& out,
                       double scale, std::vector<TraceSample>* trace, size_t trace_from) {
  const double spin_unit = scale / params.radius;
  const double impulse_unit = params.mass * scale;
  const double work_unit = params.mass * scale * scale;
  ImpactResult r;
  r.status = out.status;
  if (out.failure) r.message = out.failure;
  r.outgoing.velocity = {out.outgoing.ux * scale, out.outgoing.uy * scale, 0.0};
  r.outgoing.spin = {out.outgoing.ox * spin_unit, out.outgoing.oy * spin_unit,
                     out.outgoing.oz * spin_unit};
  r.rebound_speed = std::hypot(r.outgoing.velocity.x, r.outgoing.velocity.y);
  r.rebound_angle_deg = std::atan2(-r.outgoing.velocity.y, r.outgoing.velocity.x) / kDegree;
  r.impulse_compression = out.impulse_compression * impulse_unit;
  r.impulse_total = out.impulse_total * impulse_unit;
  r.work_compression = out.work_compression * work_unit;
  r.work_total = out.work_total * work_unit;
  r.cushion_slipping_at_start = out.cushion_slipping_at_start;
  r.table_slipping_at_start = out.table_slipping_at_start;
  r.transition_count = out.transition_count;
  for (int i = 0; i < out.transition_count; ++i) {
    r.transitions[i] = out.transitions[i];
    r.transitions[i].impulse *= impulse_unit;
  }
  r.rhs_evaluations = out.rhs_evaluations;
  if (trace) {
    for (size_t i = trace_from; i < trace->size(); ++i) {
      TraceSample& t = (*trace)[i];
      t.impulse *= impulse_unit;
      t.slip_cushion *= scale;
      t.slip_table *= scale;
      t.work *= work_unit;
      t.state.velocity = scale * t.state.velocity;
      t.state.spin = spin_unit * t.state.spin;
    }
  }
  return r;
}

// The tolerances the exact method accepts.
bool tolerance_in_range(double tolerance) {
  return std::isfinite(tolerance) && tolerance >= 1e-15 && tolerance <= 1e-2;
}

ImpactResult invalid_result(ValidationError error) {
  ImpactResult r;
  r.status = ImpactStatus::invalid_input;
  r.message = error.message();
  r.error = std::move(error);
  return r;
}

}  // namespace

Validation ImpactOptions::validate() const {
  if (method != ImpactMethod::exact && method != ImpactMethod::extrapolation &&
      method != ImpactMethod::paper && method != ImpactMethod::table &&
      method != ImpactMethod::closed_form)
    return invalid({"method"}, "must be exact, extrapolation, paper, table or closed_form",
                   static_cast<int>(method));
  if (paper_steps < 1) return invalid({"paper_steps"}, "must be at least 1", paper_steps);
  if (!tolerance_in_range(tolerance))
    return invalid({"tolerance"}, "must lie in [1e-15, 1e-2]", tolerance);
  if (max_steps < 1) return invalid({"max_steps"}, "must be at least 1", max_steps);
  if (table_fallback_tolerance != 0.0 && !tolerance_in_range(table_fallback_tolerance))
    return invalid({"table_fallback_tolerance"},
                   "must be 0 (matched to the table) or lie in [1e-15, 1e-2]",
                   table_fallback_tolerance);
  if (batch_lanes != 0 && batch_lanes != 1 && batch_lanes != 2 && batch_lanes != 4 &&
      batch_lanes != 8)
    return invalid({"batch_lanes"}, "must be 0 (widest), 1, 2, 4 or 8", batch_lanes);
  return {};
}

// What every impact of a call shares: the parameters and the options, checked once.
Validation detail::check_impact_inputs(const CushionParams& params, const ImpactOptions& options) {
  if (Validation e = params.validate()) return e;
  if (Validation e = options.validate()) return e;
  // The methods are Mathavan's; the han_2005 model is one closed form whatever they say.
  if (params.model == CushionModel::han_2005 || params.model == CushionModel::stronge_compliant)
    return {};
  if (options.method == ImpactMethod::closed_form)
    return invalid({"method"},
                   "closed_form resolves the han_2005 cushion model only; mathavan_2010 takes "
                   "exact, extrapolation, paper or table");
  if (options.method == ImpactMethod::table && options.table == nullptr)
    return invalid({"table"}, "must be a built impact table for method table");
  return {};
}

namespace {

// An impact made ready to solve.
struct Prepared {
  ImpactMethod method = ImpactMethod::exact;  // the method that solves it
  double tolerance = 0.0;
  detail::ScaledImpact impact;
};

// The exact method's tolerance: the options' own, or for the impacts the table does
// not answer, the one asked for the table's fallbacks (0: matched to the table).
double exact_tolerance(const ImpactOptions& options) {
  if (options.method != ImpactMethod::table || options.table == nullptr) return options.tolerance;
  return options.table_fallback_tolerance != 0.0 ? options.table_fallback_tolerance
                                                 : options.table->fallback_tolerance();
}

double speed_scale(const BallState& incoming) {
  return std::hypot(incoming.velocity.x, incoming.velocity.y);
}

// Stage 1 of resolve_impact: the incoming state's checks, the table's answer where it
// has one, the method and tolerance to use, and the impact in scaled units. `params`
// and `options` have been validated (check_impact_inputs).
// Returns the answer when there is one already (invalid input, or the table's);
// otherwise fills *prep.
std::optional<ImpactResult> prepare(const CushionParams& params, const BallState& incoming,
                                    const ImpactOptions& options, Prepared* prep) {
  if (Validation e = validate_state(incoming)) return invalid_result(std::move(*e));
  if (params.model == CushionModel::han_2005) return detail::resolve_han_2005(params, incoming);
  if (params.model == CushionModel::stronge_compliant)
    return detail::resolve_stronge_compliant(params, incoming);
  if (options.method == ImpactMethod::table) {
    ImpactResult r;
    if (options.table->resolve(params, incoming, &r)) return r;
    // Outside the table's domain or parameters, or a fallback cell: the exact method,
    // as accurate as the table.
  }
  const double tolerance = exact_tolerance(options);

  prep->method = options.method == ImpactMethod::table ? ImpactMethod::exact : options.method;
  prep->tolerance = tolerance;
  detail::ScaledImpact& impact = prep->impact;
  impact.geometry = detail::Geometry::from(params);
  impact.restitution = params.restitution;
  impact.speed_scale = speed_scale(incoming);
  const double v = impact.speed_scale;
  const double o = params.radius / v;
  impact.incoming = {incoming.velocity.x / v, incoming.velocity.y / v, incoming.spin.x * o,
                     incoming.spin.y * o, incoming.spin.z * o};
  return std::nullopt;
}

// Stage 2: the method, in scaled units.
detail::ScaledOutcome solve(const Prepared& prep, const ImpactOptions& options) {
  switch (prep.method) {
    case ImpactMethod::paper:
      return detail::solve_paper(prep.impact, options.paper_steps, options.trace);
    case ImpactMethod::extrapolation:
      return detail::solve_exact(prep.impact, prep.tolerance, options.max_steps, options.trace);
    default:
      return detail::solve_taylor(prep.impact, prep.tolerance, options.max_steps, options.trace);
  }
}

// Stage 3: physical units, the method used and the rigid-limit flag.
ImpactResult complete(const CushionParams& params, const BallState& incoming,
                      const Prepared& prep, const detail::ScaledOutcome& out,
                      std::vector<TraceSample>* trace, size_t trace_from) {
  ImpactResult r = to_result(params, out, prep.impact.speed_scale, trace, trace_from);
  r.method_used = prep.method;
  if (r.status == ImpactStatus::ok && incoming.velocity.y > params.rigid_speed_limit) {
    r.status = ImpactStatus::rigid_limit_exceeded;
    r.message = fmt::format(
        FMT_COMPILE("velocity.y is above the rigid-cushion limit (m/s), got {:.10g}"),
        incoming.velocity.y);
  }
  return r;
}

}  // namespace

ImpactResult resolve_impact(const CushionParams& params, const BallState& incoming,
                            const ImpactOptions& options) {
  if (Validation e = detail::check_impact_inputs(params, options))
    return invalid_result(std::move(*e));
  return detail::resolve_checked_impact(params, incoming, options);
}

// The stages of an impact, in order: prepare (the state's checks, the table, scaling),
// solve (the method), complete (units and flags).
ImpactResult detail::resolve_checked_impact(const CushionParams& params,
                                            const BallState& incoming,
                                            const ImpactOptions& options) {
  Prepared prep;
  if (std::optional<ImpactResult> answer = prepare(params, incoming, options, &prep))
    return std::move(*answer);
  const size_t trace_from = options.trace ? options.trace->size() : 0;
  const detail::ScaledOutcome out = solve(prep, options);
  return complete(params, incoming, prep, out, options.trace, trace_from);
}

namespace {

// The impacts of a batch for the exact method's lanes, prepared one at a time as a
// lane asks for one; every other impact (answered, invalid, another method) is
// resolved on the way, in the order of the batch.
class BatchSource final : public detail::BatchImpacts {
 public:
  BatchSource(const CushionParams& params, std::span<const BallState> in,
              std::span<ImpactResult> out, const ImpactOptions& options)
      : params_(params), in_(in), out_(out), options_(options), speed_scale_(in.size()) {}

  bool next(detail::ScaledImpact* impact, size_t* id) override {
    while (next_ < in_.size()) {
      const size_t i = next_++;
      Prepared prep;
      if (std::optional<ImpactResult> answer = prepare(params_, in_[i], options_, &prep))
        out_[i] = std::move(*answer);
      else if (prep.method != ImpactMethod::exact)
        out_[i] = complete(params_, in_[i], prep, solve(prep, options_), nullptr, 0);
      else {
        *impact = prep.impact;
        *id = i;
        speed_scale_[i] = prep.impact.speed_scale;
        return true;
      }
    }
    return false;
  }

  void done(size_t id, const detail::ScaledOutcome& outcome) override {
    Prepared prep;  // what complete reads of it: the method (exact) and the speed scale
    prep.impact.speed_scale = speed_scale_[id];
    out_[id] = complete(params_, in_[id], prep, outcome, nullptr, 0);
  }

 private:
  const CushionParams& params_;
  std::span<const BallState> in_;
  std::span<ImpactResult> out_;
  const ImpactOptions& options_;
  std::vector<double> speed_scale_;  // of the impacts handed to the lanes
  size_t next_ = 0;
};

}  // namespace

// The same stages for many impacts; the exact method's share solved in SIMD lanes.
void resolve_impacts(const CushionParams& params, std::span<const BallState> in,
                     std::span<ImpactResult> out, const ImpactOptions& options) {
  auto refuse_all = [&](const ValidationError& error) {
    for (ImpactResult& r : out) r = invalid_result(error);
  };
  if (out.size() != in.size())
    return refuse_all(invalid({"out"}, "must have as many elements as the impacts (in)",
                              static_cast<double>(out.size())));
  if (options.trace != nullptr)
    return refuse_all(invalid({"trace"}, "must be null: a batch records no slip histories"));
  if (Validation e = detail::check_impact_inputs(params, options)) return refuse_all(*e);

  // One tolerance for every impact the exact method solves: the options' own, or the
  // table's fallback one.
  BatchSource source(params, in, out, options);
  detail::solve_taylor_batch(detail::Geometry::from(params), exact_tolerance(options),
                             options.max_steps, options.batch_lanes, source);
}

}  // namespace cueplan::physics
