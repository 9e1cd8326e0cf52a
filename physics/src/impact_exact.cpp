// The `exact` method: the impact equations integrated to a requested tolerance.
//
// Independent variable. The cushion's normal impulse always slows the ball's normal
// approach (validate() guarantees du_y/dP_I < 0), so t = -u_y rises monotonically
// through the whole impact. Integrating in t puts the end of compression (eq. 16c,
// u_y = 0) at the fixed point t = 0, and P_I and the work W become state components:
//   y = (u_x, o_x, o_y, o_z, p, W),  dy/dt = (du_x, do_x, do_y, do_z, 1, c u_y) / (-du_y).
//
// Integrator. Between events the right-hand side is smooth, so steps are taken by
// Gragg-Bulirsch-Stoer extrapolation of the modified midpoint rule (order up to 16),
// which reaches tight tolerances in very few steps.
//
// Events, each landed on rather than stepped over:
//   - end of compression: t = 0, a fixed target;
//   - end of the impact: W = (1 - e^2) W_c (eq. 16b), landed by Newton steps on the
//     locally quadratic W(t);
//   - a slip reaching zero: landed by Newton steps on |slip|; the contact then sticks
//     if the friction that keeps the slip at zero is inside its cone;
//   - a stick breaking (the friction needed leaves the cone): bracketed and found by
//     the Illinois method; the contact then slips against the friction it needed.
#include <algorithm>
#include <array>
#include <cmath>

#include "impact_methods.hpp"

namespace cueplan::physics::detail {
namespace {

constexpr int kDim = 6;
using State = std::array<double, kDim>;
enum : int { kUx = 0, kOx, kOy, kOz, kP, kW };

constexpr int kMaxColumns = 8;  // midpoint runs of 2, 4, ..., 16 substeps

struct ContactSlip {
  double x = 0.0, y = 0.0;
  double magnitude() const { return std::hypot(x, y); }
};

class ExactIntegrator {
 public:
  ExactIntegrator(const ScaledImpact& impact, double tolerance, int max_steps,
                  std::vector<TraceSample>* trace, ScaledOutcome* out)
      : g_(impact.geometry),
        e_(impact.restitution),
        tol_(tolerance),
        max_steps_(max_steps),
        trace_(trace),
        out_(out) {
    const Scaled& q = impact.incoming;
    t_ = -q.uy;
    y_ = {q.ux, q.ox, q.oy, q.oz, 0.0, 0.0};
    zero_slip_ = tol_;
    tiny_ = 1e-3 * tol_;
  }

  void run();

 private:
  Scaled scaled(double t, const State& y) const { return {y[kUx], -t, y[kOx], y[kOy], y[kOz]}; }

  Friction friction(double t, const State& y, Modes m) const {
    const Slips sl = slips_of(g_, scaled(t, y));
    return friction_for(g_, m, direction_of(sl.ix, sl.iy, seed_i_, tiny_),
                        direction_of(sl.cx, sl.cy, seed_c_, tiny_));
  }

  void rhs(double t, const State& y, State& dy) {
    ++out_->rhs_evaluations;
    const Rates r = rates_for(g_, friction(t, y, modes_));
    const double dp_dt = -1.0 / r.uy;
    dy[kUx] = r.ux * dp_dt;
    dy[kOx] = r.ox * dp_dt;
    dy[kOy] = r.oy * dp_dt;
    dy[kOz] = r.oz * dp_dt;
    dy[kP] = dp_dt;
    dy[kW] = -g_.c * t * dp_dt;  // c u_y dp/dt with u_y = -t
  }

  bool extrapolate(double t, const State& y, const State& f0, double h, State& result,
                   int* columns);
  void settle_modes(bool force_slip_i, bool force_slip_c);
  double stick_margin(double t, const State& y) const;
  bool locate_stick_break(double h, State& result, double* h_root);
  void record() {
    if (trace_) trace_->push_back(scaled_sample(g_, scaled(t_, y_), y_[kP], y_[kW]));
  }
  ContactSlip slip_i(double t, const State& y) const {
    const Slips sl = slips_of(g_, scaled(t, y));
    return {sl.ix, sl.iy};
  }
  ContactSlip slip_c(double t, const State& y) const {
    const Slips sl = slips_of(g_, scaled(t, y));
    return {sl.cx, sl.cy};
  }

  const Geometry& g_;
  const double e_;
  const double tol_;
  const int max_steps_;
  std::vector<TraceSample>* trace_;
  ScaledOutcome* out_;

  double t_ = 0.0;
  State y_{};
  Modes modes_;
  Direction seed_i_, seed_c_;
  double zero_slip_ = 0.0;  // a slip this small has reached zero
  double tiny_ = 0.0;       // a slip this small has no direction of its own
  int steps_ = 0;
  int mode_changes_ = 0;
};

// One extrapolated step of size h from (t, y); f0 = f(t, y). Returns false when the
// extrapolation did not reach the tolerance within kMaxColumns columns.
bool ExactIntegrator::extrapolate(double t, const State& y, const State& f0, double h,
                                  State& result, int* columns) {
  std::array<State, kMaxColumns> prev{}, cur{};
  double err = 0.0;
  for (int k = 0; k < kMaxColumns; ++k) {
    const int n = 2 * (k + 1);
    const double hs = h / n;
    // Modified midpoint rule with n substeps.
    State z0 = y, z1, fz;
    for (int i = 0; i < kDim; ++i) z1[i] = y[i] + hs * f0[i];
    for (int m = 1; m < n; ++m) {
      rhs(t + m * hs, z1, fz);
      for (int i = 0; i < kDim; ++i) {
        const double z2 = z0[i] + 2.0 * hs * fz[i];
        z0[i] = z1[i];
        z1[i] = z2;
      }
    }
    // Richardson extrapolation in h^2 (Aitken-Neville).
    cur[0] = z1;
    for (int j = 1; j <= k; ++j) {
      const double ratio = static_cast<double>(n) / (2 * (k - j + 1));
      const double denom = ratio * ratio - 1.0;
      for (int i = 0; i < kDim; ++i)
        cur[j][i] = cur[j - 1][i] + (cur[j - 1][i] - prev[j - 1][i]) / denom;
    }
    if (k >= 1) {
      err = 0.0;
      for (int i = 0; i < kDim; ++i) err = std::max(err, std::abs(cur[k][i] - cur[k - 1][i]));
      if (!std::isfinite(err)) return false;
      if (err <= tol_) {
        result = cur[k];
        *columns = k + 1;
        return true;
      }
    }
    std::swap(prev, cur);
  }
  *columns = kMaxColumns;
  return false;
}

// Friction margin of the sticking contacts at (t, y): the smaller of the two, or +inf.
double ExactIntegrator::stick_margin(double t, const State& y) const {
  if (!modes_.stick_i && !modes_.stick_c) return INFINITY;
  const Friction f = friction(t, y, modes_);
  double m = INFINITY;
  if (modes_.stick_i) m = std::min(m, stick_margin_i(g_, f));
  if (modes_.stick_c) m = std::min(m, stick_margin_c(g_, f));
  return m;
}

// Chooses stick or slip for every contact whose slip is zero (or that sticks now),
// preferring stick wherever its friction fits the cone. A contact forced to slip
// (its stick has just broken) slips. Slipping contacts without a slip direction of
// their own take the direction against the friction that stick would have needed.
void ExactIntegrator::settle_modes(bool force_slip_i, bool force_slip_c) {
  const bool zero_i = modes_.stick_i || slip_i(t_, y_).magnitude() <= zero_slip_;
  const bool zero_c = modes_.stick_c || slip_c(t_, y_).magnitude() <= zero_slip_;
  const bool can_i = zero_i && !force_slip_i;
  const bool can_c = zero_c && !force_slip_c;

  // Seeds from the friction that full stick at the zero-slip contacts would need.
  {
    const Friction f = friction(t_, y_, {zero_i, zero_c});
    const double ni = std::hypot(f.ix, f.iy), nc = std::hypot(f.cx, f.cy);
    if (zero_i && ni > 0.0) seed_i_ = {-f.ix / ni, -f.iy / ni};
    if (zero_c && nc > 0.0) seed_c_ = {-f.cx / nc, -f.cy / nc};
  }

  const Modes candidates[4] = {{can_i, can_c}, {can_i, false}, {false, can_c}, {false, false}};
  Modes chosen{false, false};
  for (const Modes& m : candidates) {
    const Friction f = friction(t_, y_, m);
    const bool ok_i = !m.stick_i || stick_margin_i(g_, f) >= 0.0;
    const bool ok_c = !m.stick_c || stick_margin_c(g_, f) >= 0.0;
    if (ok_i && ok_c) {
      chosen = m;
      break;
    }
  }
  if (chosen.stick_i != modes_.stick_i)
    out_->add_transition(Contact::cushion, chosen.stick_i, y_[kP]);
  if (chosen.stick_c != modes_.stick_c)
    out_->add_transition(Contact::table, chosen.stick_c, y_[kP]);
  modes_ = chosen;
  ++mode_changes_;
}

// The stick margin went negative within a step of size h: find where it crosses
// zero (Illinois method on the step size) and return the state there.
bool ExactIntegrator::locate_stick_break(double h, State& result, double* h_root) {
  State f0;
  rhs(t_, y_, f0);
  double lo = 0.0, m_lo = stick_margin(t_, y_);
  double hi = h, m_hi = stick_margin(t_ + h, result);
  int side = 0;
  for (int iter = 0; iter < 60 && steps_ < max_steps_; ++iter) {
    double mid = (lo * m_hi - hi * m_lo) / (m_hi - m_lo);
    if (!(mid > lo && mid < hi)) mid = 0.5 * (lo + hi);
    State trial;
    int columns = 0;
    ++steps_;
    if (!extrapolate(t_, y_, f0, mid, trial, &columns)) {
      hi = mid;  // too long a step to converge: look nearer
      continue;
    }
    const double m = stick_margin(t_ + mid, trial);
    if (m >= 0.0) {
      lo = mid;
      m_lo = m;
      if (side == 1) m_hi *= 0.5;
      side = 1;
      result = trial;
    } else {
      hi = mid;
      m_hi = m;
      if (side == -1) m_lo *= 0.5;
      side = -1;
    }
    if (std::abs(m) <= 1e-3 * tol_ || hi - lo <= 1e-3 * tol_) break;
  }
  // Land on the last point where the stick still held (within the tolerance).
  if (lo == 0.0) return false;
  *h_root = lo;
  return true;
}

void ExactIntegrator::run() {
  const double t_start = t_;
  out_->cushion_slipping_at_start = true;
  out_->table_slipping_at_start = true;
  settle_modes(false, false);
  out_->transition_count = 0;  // the starting modes are not changes
  out_->cushion_slipping_at_start = !modes_.stick_i;
  out_->table_slipping_at_start = !modes_.stick_c;
  record();

  const double trace_cap = trace_ ? -t_start / 64.0 : INFINITY;
  bool compressing = true;
  double work_end = 0.0;
  double h = -t_start;  // try the whole compression in one step
  const int max_mode_changes = 8 * kMaxTransitions;

  while (steps_ < max_steps_) {
    State f0;
    rhs(t_, y_, f0);

    // The step: adaptive size, cut to land on the nearest predicted event.
    enum class Target { none, compression_end, impact_end, slip_zero_i, slip_zero_c };
    Target target = Target::none;
    double step = std::min(h, trace_cap);
    if (compressing) {
      if (-t_ <= step) {
        step = -t_;
        target = Target::compression_end;
      }
    } else {
      // W(t) is locally W + W' s + W'' s^2 / 2 with W' = -c t q, W'' = -c q,
      // q = dp/dt; solve for W = work_end.
      const double q = f0[kP];
      const double dw = y_[kW] - work_end;
      const double disc = t_ * t_ + 2.0 * dw / (g_.c * q);
      const double land = disc > 0.0 ? -t_ + std::sqrt(disc) : -t_;
      if (std::abs(land) <= 1e-3 * tol_ * std::max(1.0, t_)) break;  // landed
      if (land <= step) {
        step = land;
        target = Target::impact_end;
      }
    }
    // Slips heading for zero: Newton prediction of when they get there.
    auto predict = [&](bool sticking, ContactSlip sl, double dsx, double dsy, Target which) {
      if (sticking) return;
      const double mag = sl.magnitude();
      if (mag <= zero_slip_) return;
      const double rate = (sl.x * dsx + sl.y * dsy) / mag;
      if (rate >= 0.0) return;
      const double when = mag / -rate;
      if (when < step) {
        step = when;
        target = which;
      }
    };
    {
      // Slip rates per unit t from the state rates (eqs. 12, 13).
      const double dux = f0[kUx], duy = -1.0, dox = f0[kOx], doy = f0[kOy], doz = f0[kOz];
      const ContactSlip si = slip_i(t_, y_), sc = slip_c(t_, y_);
      predict(modes_.stick_i, si, dux + doy * g_.s - doz * g_.c, -duy * g_.s + dox,
              Target::slip_zero_i);
      predict(modes_.stick_c, sc, dux - doy, duy + dox, Target::slip_zero_c);
    }

    State next;
    int columns = 0;
    ++steps_;
    if (!extrapolate(t_, y_, f0, step, next, &columns)) {
      h = 0.3 * step;
      continue;
    }

    // A slip that reversed has been stepped through: take a shorter step.
    const ContactSlip si0 = slip_i(t_, y_), sc0 = slip_c(t_, y_);
    const ContactSlip si1 = slip_i(t_ + step, next), sc1 = slip_c(t_ + step, next);
    const bool through_i = !modes_.stick_i && si0.magnitude() > zero_slip_ &&
                           si0.x * si1.x + si0.y * si1.y < 0.0;
    const bool through_c = !modes_.stick_c && sc0.magnitude() > zero_slip_ &&
                           sc0.x * sc1.x + sc0.y * sc1.y < 0.0;
    if ((through_i && target == Target::slip_zero_i) ||
        (through_c && target == Target::slip_zero_c)) {
      h = 0.5 * step;
      continue;
    }

    // A stick that stopped holding inside the step: land where it breaks, or stay
    // put when it breaks at once.
    bool broke = false;
    if ((modes_.stick_i || modes_.stick_c) && stick_margin(t_ + step, next) < 0.0) {
      double h_root = 0.0;
      broke = true;
      if (locate_stick_break(step, next, &h_root)) {
        step = h_root;
        target = Target::none;
      } else {
        step = 0.0;
        next = y_;
        target = Target::none;
      }
    }

    t_ = (target == Target::compression_end) ? 0.0 : t_ + step;
    y_ = next;
    record();

    // Next adaptive step size from how many columns the extrapolation needed.
    h = columns <= 4 ? 4.0 * step : (columns <= 6 ? 1.5 * step : 0.7 * step);
    if (target != Target::none && target != Target::compression_end)
      h = std::max(h, std::abs(step));

    if (broke) {
      // The contact nearest its cone's edge is the one whose stick breaks.
      const Friction f = friction(t_, y_, modes_);
      const double mi = modes_.stick_i ? stick_margin_i(g_, f) : INFINITY;
      const double mc = modes_.stick_c ? stick_margin_c(g_, f) : INFINITY;
      settle_modes(mi <= mc, mc < mi);
    }
    if ((target == Target::slip_zero_i && slip_i(t_, y_).magnitude() <= zero_slip_) ||
        (target == Target::slip_zero_c && slip_c(t_, y_).magnitude() <= zero_slip_))
      settle_modes(false, false);
    if (mode_changes_ > max_mode_changes) break;

    if (compressing && target == Target::compression_end) {
      compressing = false;
      out_->impulse_compression = y_[kP];
      out_->work_compression = y_[kW];
      work_end = (1.0 - e_ * e_) * y_[kW];
      h = INFINITY;
    }
  }

  out_->outgoing = scaled(t_, y_);
  out_->impulse_total = y_[kP];
  out_->work_total = y_[kW];
  if (steps_ >= max_steps_ || mode_changes_ > max_mode_changes || compressing) {
    out_->status = ImpactStatus::step_limit;
    out_->failure = "exact integrator reached its step bound before the impact ended";
  }
}

}  // namespace

ScaledOutcome solve_exact(const ScaledImpact& impact, double tolerance, int max_steps,
                          std::vector<TraceSample>* trace) {
  ScaledOutcome out;
  ExactIntegrator integrator(impact, tolerance, max_steps, trace, &out);
  integrator.run();
  return out;
}

}  // namespace cueplan::physics::detail
