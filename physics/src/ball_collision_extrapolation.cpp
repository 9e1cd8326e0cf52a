// The `extrapolation` method of the ball-ball collision: the equations of
// ball_collision_model.hpp integrated to a requested tolerance.
//
// Independent variable. The normal impulse P always slows the normal approach
// (da/dp = -2 + g_in - g_jn < 0, as |g| <= mu_s mu_b < 2/7), so t = -a rises
// monotonically through the whole collision, from -a0 through the end of compression
// at t = 0, and P and the work W become state components:
//   y = (u_it, u_jt, m, o_i, o_j, p, W),  m = (u_in + u_jn) / 2, u_in = m - t/2, u_jn = m + t/2,
//   dy/dt = (d/dp of each) / (dt/dp),  dW/dt = -t dp/dt.
//
// Integrator: Gragg-Bulirsch-Stoer extrapolation between events, landing on the end of
// compression (t = 0), the end of the collision (W = (1 - e_b^2) W_c) and a slip reaching
// zero, as extrapolation.hpp describes. The slips and what their zeros mean:
//   - between the balls, b: once it reaches zero the balls are geared and nothing drives
//     it again (db/dp is made of f and of the cloth friction, which vanishes with f_z), so
//     friction is zero for the rest of the collision and the remaining motion is linear in
//     p. The friction impulse that gears the balls is known in advance: the slips change
//     linearly with the impulses, so whatever b's path, sliding on to gearing delivers the
//     J that cancels b (close_gearing). Without cloth friction in play that is exact, and
//     the balls are geared at once when gearing is the next event. With it, closing errs
//     by the cloth's friction turning and the approach speed changing on the way, which
//     is O(|b|^2) and estimated; the integrator steps toward gearing until the estimate is
//     within the tolerance. Those steps cover half the way each: near zero b's direction
//     turns toward its slower-decaying component (b_t shrinks at 7 mu_b, b_z at 5 mu_b
//     per unit p, so b_t / |b| goes as |b|^(2/5)), which a step reaching zero would not
//     resolve;
//   - on the cloth, c of the ball pressed into it: it passes through zero (the cloth's
//     friction is too weak to hold it), turning its friction round, so its zero is landed
//     on like any kink in the right-hand side. A cloth slip at zero - from the start, as
//     for a ball at rest or rolling, or landed on - leaves it along the direction the
//     other impulses drive it (cloth_drive), and from then on, once it is above the
//     rounding, its friction opposes the slip itself: a residue left by the landing
//     points the friction astray only while the slip is of the residue's size.
#include <algorithm>
#include <array>
#include <cmath>

#include "ball_collision_model.hpp"

namespace cueplan::physics::detail {
namespace {

constexpr int kDim = 11;
using State = std::array<double, kDim>;
enum : int { kUit = 0, kUjt, kM, kOit, kOin, kOiz, kOjt, kOjn, kOjz, kP, kW };

// Unit direction of a slip, or the seed when it is too small to have one. (The square
// root rather than hypot: this is most of the right-hand side's cost, and slips stay far
// from overflow.)
PlanarSlip unit_of(PlanarSlip s, PlanarSlip seed, double tiny) {
  const double m = std::sqrt(s.x * s.x + s.y * s.y);
  if (m <= tiny) return seed;
  return {s.x / m, s.y / m};
}

class CollisionIntegrator {
 public:
  CollisionIntegrator(const ScaledCollision& collision, double tolerance, int max_steps,
                      CollisionOutcome* out)
      : c_(collision),
        tol_(tolerance),
        max_steps_(max_steps),
        out_(out),
        events_(EventThresholds::for_tolerance(tolerance)),
        stepper_(tolerance) {
    const ScaledBall& i = collision.i;
    const ScaledBall& j = collision.j;
    t_ = -(i.un - j.un);
    y_ = {i.ut, j.ut, 0.5 * (i.un + j.un), i.ot, i.on, i.oz, j.ot, j.on, j.oz, 0.0, 0.0};
  }

  void run();

 private:
  enum class Target { none, compression_end, collision_end, gearing, cloth_zero };
  struct Step : PlannedStep<kDim, Target> {
    bool moving_b = false;         // the balls slipped at the step's start
    double gearing = INFINITY;     // predicted distance in t to the balls gearing
    double next_event = INFINITY;  // distance in t to the end of compression or of the collision
    bool moving_c = false;         // the pressed ball's cloth slip was away from zero
  };

  // The stages of run(), in order.
  void start();
  bool plan_step(Step* s);
  bool gear_now(const Step& s);
  bool take_step(Step* s);
  void advance(const Step& s);
  void resolve_events(const Step& s);
  void finish();

  struct Pair {
    ScaledBall i, j;
  };
  Pair scaled(double t, const State& y) const {
    return {{y[kUit], y[kM] - 0.5 * t, y[kOit], y[kOin], y[kOiz]},
            {y[kUjt], y[kM] + 0.5 * t, y[kOjt], y[kOjn], y[kOjz]}};
  }
  PlanarSlip slip_b(double t, const State& y) const {
    const Pair q = scaled(t, y);
    return ball_slip(q.i, q.j);
  }
  // The ball the friction presses into the cloth now (fixed until the balls gear).
  Pressed pressed() const {
    if (geared_ || c_.mu_s == 0.0) return Pressed::none;
    return pressed_by(-c_.mu_b * unit_of(slip_b(t_, y_), seed_b_, events_.tiny).y);
  }
  PlanarSlip slip_c(Pressed k, double t, const State& y) const {
    const Pair q = scaled(t, y);
    return cloth_slip(k == Pressed::i ? q.i : q.j);
  }

  // Friction at (t, y): none once geared; against the slip between the balls; and at the
  // cloth against the pressed ball's slip, or where it has none along the direction in
  // which it leaves zero.
  PairFriction friction(double t, const State& y) const {
    if (geared_) return {};
    const Pair q = scaled(t, y);
    const PlanarSlip db = unit_of(ball_slip(q.i, q.j), seed_b_, events_.tiny);
    const Pressed k = pressed_by(-c_.mu_b * db.y);
    PlanarSlip dc;
    if (k != Pressed::none) {
      dc = unit_of(cloth_slip(k == Pressed::i ? q.i : q.j), {}, events_.tiny);
      if (dc.x == 0.0 && dc.y == 0.0)
        dc = unit_of(cloth_drive(k, -c_.mu_b * db.x, -c_.mu_b * db.y), {}, 0.0);
    }
    return friction_for(c_, db.x, db.y, dc);
  }

  void rhs(double t, const State& y, State& dy) {
    ++out_->rhs_evaluations;
    const PairRates r = rates_for(friction(t, y));
    const double dp_dt = 1.0 / (r.j.un - r.i.un);  // dt/dp = -da/dp
    dy[kUit] = r.i.ut * dp_dt;
    dy[kUjt] = r.j.ut * dp_dt;
    dy[kM] = 0.5 * (r.i.un + r.j.un) * dp_dt;
    dy[kOit] = r.i.ot * dp_dt;
    dy[kOin] = r.i.on * dp_dt;
    dy[kOiz] = r.i.oz * dp_dt;
    dy[kOjt] = r.j.ot * dp_dt;
    dy[kOjn] = r.j.on * dp_dt;
    dy[kOjz] = r.j.oz * dp_dt;
    dy[kP] = dp_dt;
    dy[kW] = -t * dp_dt;  // a dp/dt with a = -t
  }

  bool extrapolate(const Step& s, State& result, StepReport* report) {
    return stepper_.step([this](double t, const State& z, State& dz) { rhs(t, z, dz); }, t_, y_,
                         s.f0, s.size, result, report);
  }
  bool close_gearing(double max_error);
  void gear() {
    geared_ = true;
    approach_ = 1.0;
    out_->add_transition(CollisionEvent::balls_geared, y_[kP]);
  }

  const ScaledCollision& c_;
  const double tol_;
  const int max_steps_;
  CollisionOutcome* out_;
  const EventThresholds events_;
  Extrapolator<kDim> stepper_;

  double t_ = 0.0;
  State y_{};
  bool geared_ = false;          // b reached zero: no friction from here on
  PlanarSlip seed_b_{1.0, 0.0};  // b's last direction, for where it has none
  int steps_ = 0;
  // Fraction of the predicted distance to a slip zero that a landing step covers: 1
  // until a landing step fails to converge there, then 0.9 (see extrapolation.hpp).
  double approach_ = 1.0;
  bool compressing_ = true;
  double work_end_ = 0.0;  // W at the end of the collision, once compression has ended
  double h_ = 0.0;         // planned size of the next step
};

// The collision, stage by stage:
//   start           the slips at first contact;
//   then step by step until the collision ends -
//   plan_step       the adaptive size, cut to land on the nearest predicted event;
//   gear_now        the balls geared at once where closing them costs less than the
//                   tolerance, and the step planned again;
//   take_step       one extrapolated step; one that failed to converge, or stepped a
//                   slip through zero, is retried shorter;
//   advance         to the step's end, and the next step's size;
//   resolve_events  the balls geared, a cloth slip through zero, the end of compression;
//   finish          the outgoing state and the status.
void CollisionIntegrator::run() {
  start();
  while (steps_ < max_steps_) {
    Step s;
    if (!plan_step(&s)) break;  // the collision has ended
    if (gear_now(s)) continue;
    if (!take_step(&s)) continue;
    advance(s);
    resolve_events(s);
  }
  finish();
}

void CollisionIntegrator::start() {
  const PlanarSlip b = slip_b(t_, y_);
  geared_ = b.magnitude() <= events_.zero_slip;
  if (!geared_) seed_b_ = unit_of(b, seed_b_, 0.0);
  out_->balls_slipping_at_start = !geared_;
  out_->cloth_i_slipping_at_start = slip_c(Pressed::i, t_, y_).magnitude() > events_.zero_slip;
  out_->cloth_j_slipping_at_start = slip_c(Pressed::j, t_, y_).magnitude() > events_.zero_slip;
  compressing_ = true;
  h_ = 0.4 * -t_;  // first guess; the extrapolation adapts it at once
}

// The step: adaptive size, cut to land on the nearest predicted event. False when the
// end of the collision has been reached.
bool CollisionIntegrator::plan_step(Step* s) {
  rhs(t_, y_, s->f0);
  const State& f0 = s->f0;
  s->target = Target::none;
  s->size = h_;
  if (compressing_) {
    s->next_event = -t_;
    if (-t_ <= s->size) {
      s->size = -t_;
      s->target = Target::compression_end;
    }
  } else {
    // W(t) is locally quadratic with dW/dt = -t q, q = dp/dt.
    const double dw = y_[kW] - work_end_;
    const double land = distance_to_work_end(t_, dw, f0[kP]);
    if (work_end_reached(land, events_.landing, y_[kW], dw, work_end_)) return false;
    s->next_event = land;
    if (aim_at_work_end(land, &s->size) == EndStep::lands) s->target = Target::collision_end;
  }
  // Slips heading for zero: Newton prediction of when they get there.
  auto predict = [&](PlanarSlip sl, double dsx, double dsy, double approach, Target which) {
    if (sl.magnitude() <= events_.zero_slip) return;
    switch (limit_step_by_slip(sl, dsx, dsy, approach, false, &s->size)) {
      case SlipLimit::lands: s->target = which; break;
      case SlipLimit::turns: s->target = Target::none; break;
      case SlipLimit::none: break;
    }
  };
  // Slip rates per unit t from the state rates (u_in = m - t/2, u_jn = m + t/2).
  const double duin = f0[kM] - 0.5, dujn = f0[kM] + 0.5;
  const Pressed k = pressed();
  if (!geared_) {
    const PlanarSlip b = slip_b(t_, y_);
    const double dbx = f0[kUit] - f0[kUjt] - (f0[kOiz] + f0[kOjz]), dbz = f0[kOit] + f0[kOjt];
    const double rate = (b.x * dbx + b.y * dbz) / b.magnitude();
    if (rate < 0.0) s->gearing = b.magnitude() / -rate;
    // With the cloth in play, half the way to gearing at a time (see above).
    predict(b, dbx, dbz, k == Pressed::none ? approach_ : 0.5 * approach_, Target::gearing);
  }
  if (k == Pressed::i)
    predict(slip_c(k, t_, y_), f0[kUit] - f0[kOin], duin + f0[kOit], approach_, Target::cloth_zero);
  if (k == Pressed::j)
    predict(slip_c(k, t_, y_), f0[kUjt] - f0[kOjn], dujn + f0[kOjt], approach_, Target::cloth_zero);
  return true;
}

// The balls gear within this step, before the end of compression or of the collision:
// when closing them now errs by less than the tolerance, they are geared here. True when
// they were (the step is then planned again).
bool CollisionIntegrator::gear_now(const Step& s) {
  if (s.target != Target::gearing || !(s.gearing < s.next_event)) return false;
  if (!close_gearing(tol_)) return false;
  gear();
  return true;
}

// One extrapolated step. False when it must be retried (h_ says how long): it did not
// converge, or it reversed a slip - stepped through its zero instead of landing on it.
bool CollisionIntegrator::take_step(Step* s) {
  ++steps_;
  if (!extrapolate(*s, s->next, &s->report)) {
    h_ = s->report.next_h;
    if (s->target == Target::gearing || s->target == Target::cloth_zero) approach_ = 0.9;
    return false;
  }
  const double t1 = t_ + s->size;
  const PlanarSlip b0 = slip_b(t_, y_), b1 = slip_b(t1, s->next);
  s->moving_b = !geared_ && b0.magnitude() > events_.zero_slip;
  const Pressed k = pressed();
  bool reversed = s->moving_b && stepped_through(b0, b1, events_.zero_slip);
  if (k != Pressed::none) {
    const PlanarSlip c0 = slip_c(k, t_, y_), c1 = slip_c(k, t1, s->next);
    s->moving_c = c0.magnitude() > events_.zero_slip;
    reversed = reversed || (s->moving_c && stepped_through(c0, c1, events_.zero_slip));
  }
  if (reversed) {
    h_ = 0.5 * std::abs(s->size);
    return false;
  }
  return true;
}

void CollisionIntegrator::advance(const Step& s) {
  t_ = (s.target == Target::compression_end) ? 0.0 : t_ + s.size;
  y_ = s.next;
  if (!geared_) seed_b_ = unit_of(slip_b(t_, y_), seed_b_, events_.tiny);
  if (s.size != 0.0) h_ = next_step_size(h_, s.report.next_h, s.size, s.target != Target::none);
}

void CollisionIntegrator::resolve_events(const Step& s) {
  // The pressed ball's cloth slip landed on zero: it passes through.
  const Pressed k = pressed();
  if (s.moving_c && k != Pressed::none && slip_c(k, t_, y_).magnitude() <= events_.zero_slip) {
    approach_ = 1.0;
    out_->add_transition(k == Pressed::i ? CollisionEvent::cloth_i_through_zero
                                         : CollisionEvent::cloth_j_through_zero,
                         y_[kP]);
  }
  // The balls geared: a slip landed within the zero threshold is closed (its error is
  // far below the tolerance) unless that would move the end of compression.
  if (!geared_ && slip_b(t_, y_).magnitude() <= events_.zero_slip) {
    if (s.target != Target::compression_end) close_gearing(INFINITY);
    gear();
  }
  if (compressing_ && s.target == Target::compression_end) {
    compressing_ = false;
    out_->impulse_compression = y_[kP];
    out_->work_compression = y_[kW];
    work_end_ = (1.0 - c_.restitution * c_.restitution) * y_[kW];
  }
}

// Cancels the slip b between the balls with the friction impulse J (on ball i, in (t, z))
// that zeroes it at a fixed P, together with the cloth's impulse on the pressed ball that
// comes with it (mu_s |J_z| against that ball's cloth slip). The slips change linearly
// with these impulses (ball_collision_model.hpp), so J is what sliding on to gearing
// delivers, whatever b's path. Sliding on spreads the cloth's impulse over the impulse dp
// it takes to gear, while the cloth slip c turns and the approach speed changes: closing
// errs by about mu_s |J_z| dp (1 + |dc/dp| / |c|) / 2, nothing without the cloth. Returns
// false, changing nothing, when that estimate exceeds max_error or the cloth's impulse
// would carry the approach speed through zero.
bool CollisionIntegrator::close_gearing(double max_error) {
  const Pair q = scaled(t_, y_);
  const PlanarSlip b = ball_slip(q.i, q.j);
  const PairFriction f = friction(t_, y_);
  // The cloth's friction per unit of its normal impulse |J_z|, on ball i and ball j
  // (zero on the ball not pressed), written per unit of J_z: J_z has f_z's sign.
  const double normal = std::abs(f.fz);
  double kit = 0.0, kin = 0.0, kjt = 0.0, kjn = 0.0;
  if (normal > 0.0) {
    const double sign = f.fz > 0.0 ? 1.0 : -1.0;
    kit = sign * f.git / normal;
    kin = sign * f.gin / normal;
    kjt = sign * f.gjt / normal;
    kjn = sign * f.gjn / normal;
  }
  // d(b_t, b_z) = (7 J_t + (k_it - k_jt) J_z, (5 + 5/2 (k_in + k_jn)) J_z) = -b.
  const double jz = -b.y / (5.0 + 2.5 * (kin + kjn));
  const double jt = (-b.x - (kit - kjt) * jz) / 7.0;
  const double git = kit * jz, gin = kin * jz, gjt = kjt * jz, gjn = kjn * jz;
  const Pressed k = pressed();
  if (k != Pressed::none && std::isfinite(max_error)) {
    const PairRates r = rates_for(f);
    const double db = (b.x * (r.i.ut - r.j.ut - (r.i.oz + r.j.oz)) + b.y * (r.i.ot + r.j.ot)) /
                      b.magnitude();  // d|b|/dp
    const ScaledBall& rk = k == Pressed::i ? r.i : r.j;
    const PlanarSlip dc = {rk.ut - rk.on, rk.un + rk.ot};
    const double dp = b.magnitude() / -db;
    const double error =
        0.5 * c_.mu_s * std::abs(jz) * dp * (1.0 + dc.magnitude() / slip_c(k, t_, y_).magnitude());
    if (!(db < 0.0) || !(error <= max_error)) return false;
  }
  const double t = t_ - (gin - gjn);  // t = -a, a = u_in - u_jn
  if (compressing_ ? t >= 0.0 : t <= 0.0) return false;
  t_ = t;
  y_[kUit] += jt + git;
  y_[kUjt] += -jt + gjt;
  y_[kM] += 0.5 * (gin + gjn);
  y_[kOit] += 2.5 * (jz + gin);
  y_[kOin] += -2.5 * git;
  y_[kOiz] += -2.5 * jt;
  y_[kOjt] += 2.5 * (jz + gjn);
  y_[kOjn] += -2.5 * gjt;
  y_[kOjz] += -2.5 * jt;
  return true;
}

void CollisionIntegrator::finish() {
  const Pair q = scaled(t_, y_);
  out_->i = q.i;
  out_->j = q.j;
  out_->impulse_total = y_[kP];
  out_->work_total = y_[kW];
  if (steps_ >= max_steps_ || compressing_) {
    out_->status = CollisionStatus::step_limit;
    out_->failure = "exact integrator reached its step bound before the collision ended";
  }
}

}  // namespace

CollisionOutcome collide_exact(const ScaledCollision& collision, double tolerance, int max_steps) {
  CollisionOutcome out;
  CollisionIntegrator integrator(collision, tolerance, max_steps, &out);
  integrator.run();
  return out;
}

}  // namespace cueplan::physics::detail
