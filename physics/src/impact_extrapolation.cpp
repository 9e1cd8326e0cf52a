// The `extrapolation` method: the impact equations integrated to a requested tolerance
// by extrapolated midpoint steps (the `exact` method is the Taylor series, impact_taylor.cpp).
//
// Independent variable. The cushion's normal impulse always slows the ball's normal
// approach (validate() guarantees du_y/dP_I < 0), so t = -u_y rises monotonically
// through the whole impact. Integrating in t puts the end of compression (eq. 16c,
// u_y = 0) at the fixed point t = 0, and P_I and the work W become state components:
//   y = (u_x, o_x, o_y, o_z, p, W),  dy/dt = (du_x, do_x, do_y, do_z, 1, c u_y) / (-du_y).
//
// Integrator: Gragg-Bulirsch-Stoer extrapolation between events, and the landing on the
// end of compression, the end of the impact (W = (1 - e^2) W_c, eq. 16b) and a slip
// reaching zero, as extrapolation.hpp describes. What is the cushion's own:
//   - a slip reaching zero: the contact then sticks if the friction that keeps the slip
//     at zero is inside its cone. A slip that is already small while its contact could
//     stick is closed at once by the friction impulse that cancels it (close_slip): near
//     zero the slip's direction turns on a scale of |slip|, so stepping the last stretch
//     costs steps in proportion to how slowly the slip shrinks, and the impulse lands it
//     to second order instead;
//   - a stick breaking (the friction needed leaves the cone): bracketed and found by
//     the Illinois method; the contact then slips against the friction it needed.
#include <algorithm>
#include <array>
#include <cmath>

#include "extrapolation.hpp"
#include "impact_methods.hpp"

namespace cueplan::physics::detail {
namespace {

constexpr int kDim = 6;
using State = std::array<double, kDim>;
enum : int { kUx = 0, kOx, kOy, kOz, kP, kW };

using ContactSlip = PlanarSlip;

class ExactIntegrator {
 public:
  ExactIntegrator(const ScaledImpact& impact, double tolerance, int max_steps,
                  std::vector<TraceSample>* trace, ScaledOutcome* out)
      : g_(impact.geometry),
        e_(impact.restitution),
        tol_(tolerance),
        max_steps_(max_steps),
        trace_(trace),
        out_(out),
        trace_from_(trace ? trace->size() : 0),
        stepper_(tolerance) {
    const Scaled& q = impact.incoming;
    t_ = -q.uy;
    y_ = {q.ux, q.ox, q.oy, q.oz, 0.0, 0.0};
    const EventThresholds events = EventThresholds::for_tolerance(tol_);
    zero_slip_ = events.zero_slip;
    young_slip_ = events.young_slip;
    close_slip_ = events.close_slip;  // see close_slip
    landing_ = events.landing;
    tiny_ = events.tiny;
  }

  void run();

 private:
  // What becomes of one step, from its plan to its events.
  enum class Target { none, compression_end, impact_end, slip_zero_i, slip_zero_c };
  struct Step : PlannedStep<kDim, Target> {
    bool moving_i = false, moving_c = false;  // slipping away from zero at its start
    bool broke = false;                       // a stick stopped holding inside it
  };

  // The stages of run(), in order.
  void start();
  bool plan_step(Step* s);
  bool take_step(Step* s);
  void land_stick_break(Step* s);
  void advance(const Step& s);
  bool resolve_events(const Step& s);
  void finish();

  Scaled scaled(double t, const State& y) const { return {y[kUx], -t, y[kOx], y[kOy], y[kOz]}; }

  // Friction at (t, y) for modes m. A slip growing from zero (young) has no direction
  // of its own worth trusting: below young_slip_ its direction is the quasi-static
  // one, against the friction that would keep that contact stuck in the current
  // state - the direction in which a slip leaves zero.
  Friction friction(double t, const State& y, Modes m) const {
    const Slips sl = slips_of(g_, scaled(t, y));
    Direction di = direction_of(sl.ix, sl.iy, seed_i_, tiny_);
    Direction dc = direction_of(sl.cx, sl.cy, seed_c_, tiny_);
    const bool young_i = !m.stick_i && young_i_;
    const bool young_c = !m.stick_c && young_c_;
    if (young_i || young_c) {
      const Friction held = friction_for(g_, {m.stick_i || young_i, m.stick_c || young_c}, di, dc);
      if (young_i) di = against(held.ix, held.iy, di);
      if (young_c) dc = against(held.cx, held.cy, dc);
    }
    return friction_for(g_, m, di, dc);
  }

  static Direction against(double fx, double fy, Direction fallback) {
    const double n = std::hypot(fx, fy);
    if (!(n > 0.0)) return fallback;
    return {-fx / n, -fy / n};
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
                   StepReport* report) {
    return stepper_.step([this](double s, const State& z, State& dz) { rhs(s, z, dz); }, t, y, f0,
                         h, result, report);
  }
  void settle_modes(bool force_slip_i, bool force_slip_c);
  double stick_margin(double t, const State& y) const;
  bool locate_stick_break(double h, State& result, double* h_root);
  bool stick_would_hold(Contact contact) const;
  bool close_slip(Contact contact, bool compressing);
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
  size_t trace_from_;  // where this impact's samples start in trace_
  Extrapolator<kDim> stepper_;

  double t_ = 0.0;
  State y_{};
  Modes modes_;
  Direction seed_i_, seed_c_;
  bool young_i_ = false, young_c_ = false;  // slipping, grown from zero, still tiny
  double young_slip_ = 0.0;  // a young slip this large takes its own direction
  double zero_slip_ = 0.0;  // a slip this small has reached zero
  double tiny_ = 0.0;       // a slip this small has no direction of its own
  double close_slip_ = 0.0;  // a slip this small is closed when its contact can stick
  double landing_ = 0.0;    // an event this close in t has been reached
  int steps_ = 0;
  // Fraction of the predicted distance to a slip zero that a landing step covers:
  // 1 until a landing step fails to converge at the zero (where the slip direction
  // is not smooth), then 0.9, so the zero is approached ten times closer per step.
  double approach_ = 1.0;
  int mode_changes_ = 0;
  static constexpr int kMaxModeChanges = 8 * kMaxTransitions;

  bool compressing_ = true;
  double work_end_ = 0.0;       // W at the end of the impact, once compression has ended
  double h_ = 0.0;              // planned size of the next step
  double trace_cap_ = INFINITY;  // the longest step, so that a trace has enough samples
};

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
    // Each candidate is judged with the slip directions it would use: a zero-slip
    // contact that slips takes the young direction, not its residual slip's.
    young_i_ = zero_i && !m.stick_i;
    young_c_ = zero_c && !m.stick_c;
    const Friction f = friction(t_, y_, m);
    const bool ok_i = !m.stick_i || stick_margin_i(g_, f) >= 0.0;
    const bool ok_c = !m.stick_c || stick_margin_c(g_, f) >= 0.0;
    if (ok_i && ok_c) {
      chosen = m;
      break;
    }
  }
  approach_ = 1.0;
  young_i_ = zero_i && !chosen.stick_i;
  young_c_ = zero_c && !chosen.stick_c;
  if (chosen.stick_i != modes_.stick_i)
    out_->add_transition(Contact::cushion, chosen.stick_i, y_[kP]);
  if (chosen.stick_c != modes_.stick_c)
    out_->add_transition(Contact::table, chosen.stick_c, y_[kP]);
  modes_ = chosen;
  ++mode_changes_;
}

// Whether the given slipping contact could stick now, the other keeping its mode.
bool ExactIntegrator::stick_would_hold(Contact contact) const {
  Modes m = modes_;
  (contact == Contact::cushion ? m.stick_i : m.stick_c) = true;
  const Friction f = friction(t_, y_, m);
  return contact == Contact::cushion ? stick_margin_i(g_, f) >= 0.0 : stick_margin_c(g_, f) >= 0.0;
}

// Cancels the slip at one contact with the friction impulse J that zeroes it, at a
// fixed P_I. The other contact answers as its mode says: a sticking one with the
// friction that keeps its slip, a slipping table with the change of its friction
// through its normal impulse (p_C falls by c J_Iy); a slipping cushion not at all
// (its friction follows P_I alone). The slips change by K J (impact_model.hpp), so
// this is what sliding on to the zero would add beyond sticking from here, to first
// order: landing here errs by O(|slip|^2 / rate), not O(|slip|), and it dissipates.
// Returns false, changing nothing, when the impulse would carry u_y through zero.
bool ExactIntegrator::close_slip(Contact contact, bool compressing) {
  const bool at_cushion = contact == Contact::cushion;
  // A slipping table's friction per unit of its normal impulse.
  double table_x = 0.0, table_y = 0.0;
  if (at_cushion && !modes_.stick_c) {
    const Friction f = friction(t_, y_, modes_);
    if (f.pc > 0.0) {
      table_x = f.cx / f.pc;
      table_y = f.cy / f.pc;
    }
  }
  auto impulse = [&](double jx, double jy) {
    Friction j;
    if (at_cushion) {
      j.ix = jx;
      j.iy = jy;
      j.cx = modes_.stick_c ? -g_.a * jx / 3.5 : -g_.c * jy * table_x;
      j.cy = modes_.stick_c ? -g_.d * jy / 3.5 : -g_.c * jy * table_y;
    } else {
      j.cx = jx;
      j.cy = jy;
      if (modes_.stick_i) {
        j.ix = -g_.a * jx / 3.5;
        j.iy = -g_.d * jy / g_.b;
      }
    }
    return j;
  };
  // State change for a friction impulse: rates_for (impact_model.hpp) less the
  // normal impulse's own term, written out so that -c is not added and taken away
  // again (that would cost the tiny impulses here their last digits in u_y).
  auto change = [&](const Friction& j) -> Scaled {
    return {j.ix + j.cx, -g_.s * j.iy + j.cy, 2.5 * (j.iy + j.cy), 2.5 * (g_.s * j.ix - j.cx),
            -2.5 * g_.c * j.ix};
  };
  auto slip_change = [&](double jx, double jy) {  // slips are linear in the state
    const Slips d = slips_of(g_, change(impulse(jx, jy)));
    return at_cushion ? ContactSlip{d.ix, d.iy} : ContactSlip{d.cx, d.cy};
  };
  const ContactSlip s = at_cushion ? slip_i(t_, y_) : slip_c(t_, y_);
  const ContactSlip a = slip_change(1.0, 0.0), b = slip_change(0.0, 1.0);
  const double det = a.x * b.y - b.x * a.y;
  if (!(std::abs(det) > 1e-9)) return false;
  const Scaled d = change(impulse((b.x * s.y - b.y * s.x) / det, (a.y * s.x - a.x * s.y) / det));
  if (compressing ? t_ - d.uy >= 0.0 : t_ - d.uy <= 0.0) return false;
  t_ -= d.uy;  // t = -u_y
  y_[kUx] += d.ux;
  y_[kOx] += d.ox;
  y_[kOy] += d.oy;
  y_[kOz] += d.oz;
  return true;
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
    StepReport report;
    ++steps_;
    if (!extrapolate(t_, y_, f0, mid, trial, &report)) {
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
    if (std::abs(m) <= 1e-3 * tol_ || hi - lo <= landing_) break;
  }
  // Land on the last point where the stick still held (within the tolerance).
  if (lo == 0.0) return false;
  *h_root = lo;
  return true;
}

// The impact, stage by stage:
//   start             the contacts' modes at first contact, the first trace sample;
//   then step by step until the impact ends -
//   plan_step         the adaptive size, cut to land on the nearest predicted event;
//   take_step         one extrapolated step; one that failed to converge, or stepped a
//                     slip through zero, is retried shorter;
//   land_stick_break  a stick that stopped holding inside the step ends it where it breaks;
//   advance           to the step's end, recorded, and the next step's size;
//   resolve_events    new modes where a stick broke or a slip reached zero, small slips
//                     closed, the end of compression noted;
//   finish            the outgoing state, the trace kept monotone, the status.
void ExactIntegrator::run() {
  start();
  while (steps_ < max_steps_) {
    Step s;
    if (!plan_step(&s)) break;  // the impact has ended
    if (!take_step(&s)) continue;
    land_stick_break(&s);
    advance(s);
    if (!resolve_events(s)) break;  // more mode changes than any impact needs
  }
  finish();
}

void ExactIntegrator::start() {
  const double t_start = t_;
  out_->cushion_slipping_at_start = true;
  out_->table_slipping_at_start = true;
  settle_modes(false, false);
  out_->transition_count = 0;  // the starting modes are not changes
  out_->cushion_slipping_at_start = !modes_.stick_i;
  out_->table_slipping_at_start = !modes_.stick_c;
  record();

  trace_cap_ = trace_ ? -t_start / 64.0 : INFINITY;
  compressing_ = true;
  work_end_ = 0.0;
  h_ = 0.4 * -t_start;  // first guess; the extrapolation adapts it at once
}

// The step: adaptive size, cut to land on the nearest predicted event. False when the
// end of the impact has been reached.
bool ExactIntegrator::plan_step(Step* s) {
  rhs(t_, y_, s->f0);
  const State& f0 = s->f0;
  s->target = Target::none;
  s->size = std::min(h_, trace_cap_);
  if (compressing_) {
    if (-t_ <= s->size) {
      s->size = -t_;
      s->target = Target::compression_end;
    }
  } else {
    // W(t) is locally quadratic with dW/dt = -c t q, q = dp/dt.
    const double q = f0[kP];
    const double dw = y_[kW] - work_end_;
    const double land = distance_to_work_end(t_, dw, g_.c * q);
    if (work_end_reached(land, landing_, y_[kW], dw, work_end_)) return false;
    if (aim_at_work_end(land, &s->size) == EndStep::lands) s->target = Target::impact_end;
  }
  // Slips heading for zero: Newton prediction of when they get there.
  auto predict = [&](bool sticking, bool young, ContactSlip sl, double dsx, double dsy,
                     Target which) {
    if (sticking || sl.magnitude() <= zero_slip_) return;
    switch (limit_step_by_slip(sl, dsx, dsy, approach_, young, &s->size)) {
      case SlipLimit::lands: s->target = which; break;
      case SlipLimit::turns: s->target = Target::none; break;
      case SlipLimit::none: break;
    }
  };
  {
    // Slip rates per unit t from the state rates (eqs. 12, 13).
    const double dux = f0[kUx], duy = -1.0, dox = f0[kOx], doy = f0[kOy], doz = f0[kOz];
    const ContactSlip si = slip_i(t_, y_), sc = slip_c(t_, y_);
    predict(modes_.stick_i, young_i_, si, dux + doy * g_.s - doz * g_.c, -duy * g_.s + dox,
            Target::slip_zero_i);
    predict(modes_.stick_c, young_c_, sc, dux - doy, duy + dox, Target::slip_zero_c);
  }
  return true;
}

// One extrapolated step. False when it must be retried (h_ says how long): it did not
// converge, or it reversed a slip - stepped through its zero instead of landing on it.
bool ExactIntegrator::take_step(Step* s) {
  ++steps_;
  if (!extrapolate(t_, y_, s->f0, s->size, s->next, &s->report)) {
    h_ = s->report.next_h;
    if (s->target == Target::slip_zero_i || s->target == Target::slip_zero_c) approach_ = 0.9;
    return false;
  }
  const ContactSlip si0 = slip_i(t_, y_), sc0 = slip_c(t_, y_);
  const ContactSlip si1 = slip_i(t_ + s->size, s->next), sc1 = slip_c(t_ + s->size, s->next);
  s->moving_i = !modes_.stick_i && si0.magnitude() > zero_slip_;
  s->moving_c = !modes_.stick_c && sc0.magnitude() > zero_slip_;
  if ((s->moving_i && stepped_through(si0, si1, zero_slip_)) ||
      (s->moving_c && stepped_through(sc0, sc1, zero_slip_))) {
    h_ = 0.5 * std::abs(s->size);
    return false;
  }
  return true;
}

// A stick that stopped holding inside the step: land where it breaks, or stay put when
// it breaks at once.
void ExactIntegrator::land_stick_break(Step* s) {
  if (!(modes_.stick_i || modes_.stick_c) || !(stick_margin(t_ + s->size, s->next) < 0.0)) return;
  double h_root = 0.0;
  s->broke = true;
  if (locate_stick_break(s->size, s->next, &h_root)) {
    s->size = h_root;
    s->target = Target::none;
    // A landing step can overshoot the end of the impact; a stick that breaks
    // only beyond the end held throughout (the landing then steps back).
    if (!compressing_ && s->next[kW] < work_end_) s->broke = false;
  } else {
    s->size = 0.0;
    s->next = y_;
    s->target = Target::none;
  }
}

void ExactIntegrator::advance(const Step& s) {
  t_ = (s.target == Target::compression_end) ? 0.0 : t_ + s.size;
  y_ = s.next;
  record();
  if (young_i_ && slip_i(t_, y_).magnitude() > young_slip_) young_i_ = false;
  if (young_c_ && slip_c(t_, y_).magnitude() > young_slip_) young_c_ = false;
  // (A stick that broke at once leaves the point unmoved: keep the planned size.)
  if (s.size != 0.0) h_ = next_step_size(h_, s.report.next_h, s.size, s.target != Target::none);
}

// Modes after the step's events. False when the modes changed more often than any
// impact needs (a chattering stick: the integration stops with step_limit).
bool ExactIntegrator::resolve_events(const Step& s) {
  if (s.broke) {
    // The contact nearest its cone's edge is the one whose stick breaks.
    const Friction f = friction(t_, y_, modes_);
    const double mi = modes_.stick_i ? stick_margin_i(g_, f) : INFINITY;
    const double mc = modes_.stick_c ? stick_margin_c(g_, f) : INFINITY;
    settle_modes(mi <= mc, mc < mi);
  }
  // A small slip at a contact that could stick is closed now (slips grown from
  // zero are left to grow: their stick has just failed). Not on the end of
  // compression, which the impulse would move.
  bool closed = false;
  const bool may_close = s.target != Target::compression_end;
  if (may_close && !modes_.stick_i && !young_i_ && slip_i(t_, y_).magnitude() <= close_slip_ &&
      stick_would_hold(Contact::cushion))
    closed = close_slip(Contact::cushion, compressing_);
  if (may_close && !modes_.stick_c && !young_c_ && slip_c(t_, y_).magnitude() <= close_slip_ &&
      stick_would_hold(Contact::table))
    closed = close_slip(Contact::table, compressing_) || closed;
  if (closed) record();
  // Every slip that reached zero in this step, targeted or not (two events can
  // coincide: while the cushion sticks, the table slip vanishes exactly at the
  // end of compression).
  if (closed || (s.moving_i && slip_i(t_, y_).magnitude() <= zero_slip_) ||
      (s.moving_c && slip_c(t_, y_).magnitude() <= zero_slip_))
    settle_modes(false, false);
  if (mode_changes_ > kMaxModeChanges) return false;

  if (compressing_ && s.target == Target::compression_end) {
    compressing_ = false;
    out_->impulse_compression = y_[kP];
    out_->work_compression = y_[kW];
    work_end_ = (1.0 - e_ * e_) * y_[kW];
  }
  return true;
}

void ExactIntegrator::finish() {
  // The landing on the end of the impact may have stepped past it and back: keep
  // the history monotone in P_I.
  if (trace_) {
    const double p_end = y_[kP];
    trace_->erase(std::remove_if(trace_->begin() + static_cast<std::ptrdiff_t>(trace_from_),
                                 trace_->end(),
                                 [&](const TraceSample& t) { return t.impulse > p_end; }),
                  trace_->end());
    if (trace_->size() == trace_from_ || trace_->back().impulse != p_end) record();
  }
  out_->outgoing = scaled(t_, y_);
  out_->impulse_total = y_[kP];
  out_->work_total = y_[kW];
  if (steps_ >= max_steps_ || mode_changes_ > kMaxModeChanges || compressing_) {
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
