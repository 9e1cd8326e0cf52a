// The `exact` method of the ball-ball collision: the equations of
// ball_collision_model.hpp as Taylor-mode series in a regularised variable (the scheme
// of the cushion impact's exact method, impact_taylor.cpp, for this model).
//
// State. Friction depends only on the directions of two slips: b between the balls and
// c on the cloth of the ball the vertical friction presses into it (ball i while b_z > 0,
// ball j while b_z < 0; b_z never changes sign, so the pressed ball is fixed until the
// balls gear). Everything else is linear in the impulses, so a step carries, from its
// start, the normal impulse p, the friction impulse F = (F_t, F_z) between the balls (on
// ball i), the cloth's impulse G = (G_t, G_n) on the pressed ball, and the work W of the
// phase (compression, then restitution counted from its start). With s = +1 when ball i
// is pressed and -1 when ball j is:
//   b = b0 + (7 F_t + s G_t, 5 F_z + 5/2 G_n),   a = a0 - 2 p + s G_n,
//   c = c0 + (s F_t + 7/2 G_t, -s p + 5/2 F_z + 7/2 G_n),
// and per unit p: dF = -mu_b b / |b|, dG = -mu_s N c / |c| with N = mu_b |b_z| / |b|.
//
// Variable. A step's variable sigma has dp/dsigma = |b| (tau) while the balls slip:
// then dF/dsigma = -mu_b b and the cloth's normal impulse N |b| = mu_b s b_z are
// polynomials in the state, and the slip between the balls, whose direction turns as
// |b|^(2/5) near gearing in p (b_t shrinks at 7 mu_b, b_z at 5 mu_b), decays smoothly,
// exponentially in sigma. The cloth slip's direction c / |c|:
//   - by the quotient recurrence while c is far from zero against its rate;
//   - while c is small against its rate (passing close to zero), regularised as well,
//     dp/dsigma = |b| |c|, which makes dG/dsigma = -mu_s mu_b s b_z c a polynomial
//     and the pass smooth;
//   - heading straight for zero (its closest approach within the tolerance, as in the
//     head-on plane) by the quotient, which continues |c| analytically through its
//     zero: the step lands there and c leaves zero anew;
//   - leaving zero (an object ball at rest, a rolling cue ball, after such a landing):
//     c = (p - p0) v with v analytic, v(0) along the drive of the other impulses
//     (cloth_drive; the cloth's friction, at most 7/2 mu_s mu_b < 1 of it, cannot turn
//     it); each order of v solves a 2 x 2 system, diagonal in (v0, v0 turned).
// Once geared (b = 0) nothing drives friction again and the rest is closed form.
//
// Steps. Each step computes the series to order N (1.25 per decimal digit of the
// tolerance, 16 at 1e-12) and its length from the last two coefficients,
// h = min_j (tol / |X_j|)^(1/j), then ends early at its first event, a root of one of
// its polynomials: the end of compression (a = 0), the end of the collision (the
// restitution work reaching -e^2 W_c), |b| reaching the size at which closing the
// balls' slip errs by the tolerance, a cloth slip heading straight for zero reaching it.
//
// Gearing. b decays exponentially in sigma and never reaches zero: it is closed by the
// friction impulse that cancels it at a fixed p, together with the cloth's impulse that
// comes with it, once that errs by less than the tolerance: the slips change linearly
// with the impulses, so only the spreading of the cloth's impulse over the impulse it
// takes to gear is left out, an error of about mu_s |J_z| dp (1 + |dc/dp| / |c|) / 2, of
// order |b|^2. Without cloth friction in play closing is exact, and is done at once
// when gearing certainly comes before the end of the collision; and a slip with b_z = 0
// (a stun shot: no ball pressed) keeps its direction, so its friction is constant and
// the whole collision is closed form.
#include <algorithm>
#include <cmath>

#include "ball_collision_model.hpp"
#include "polynomial_roots.hpp"

namespace cueplan::physics::detail {
namespace {

constexpr int kMaxOrder = 24;
constexpr int kTerms = kMaxOrder + 2;
static_assert(kTerms <= kMaxSeriesTerms);

enum : int { kP = 0, kFt, kFz, kGt, kGn, kW, kSeries };

// How a step handles the pressed ball's cloth slip.
enum class Cloth {
  none,        // no ball pressed (b_z = 0, or no cloth friction)
  divide,      // c / |c| by the quotient recurrence
  regularise,  // dp/dsigma = |b| |c|
  young,       // c = (p - p0) v, leaving zero
};

// The cloth slip is regularised while below this fraction of its rate times half the
// approach speed at first contact (about the compression's impulse).
constexpr double kRegularise = 0.3;

struct Series {
  double c[kSeries][kTerms];
};

// sum_{j=lo}^{hi} a[j] b[k - j]
inline double conv(const double* a, const double* b, int k, int lo, int hi) {
  double v = 0.0;
  for (int j = lo; j <= hi; ++j) v += a[j] * b[k - j];
  return v;
}

// |(x, y)| at order k, given its orders below k: the square-root recurrence
// r_k = (sum_{j=0}^{k} x_j x_{k-j} + y_j y_{k-j} - sum_{j=1}^{k-1} r_j r_{k-j}) / (2 r_0).
inline double radius(const double* x, const double* y, const double* r, int k) {
  if (k == 0) return std::sqrt(x[0] * x[0] + y[0] * y[0]);
  return 0.5 * (conv(x, x, k, 0, k) + conv(y, y, k, 0, k) - conv(r, r, k, 1, k - 1)) / r[0];
}

class TaylorCollision {
 public:
  TaylorCollision(const ScaledCollision& collision, double tolerance, int max_steps,
                  CollisionOutcome* out);
  void run();

 private:
  PlanarSlip slip_b() const { return ball_slip(i_, j_); }
  PlanarSlip slip_c() const { return cloth_slip(pressed_ == Pressed::i ? i_ : j_); }
  double approach() const { return i_.un - j_.un; }
  void apply(double dp, double ft, double fz, double gt, double gn);
  Cloth choose_cloth(bool* straight) const;
  int series(Cloth cloth, int n, Series& s) const;
  void step();
  double closing_error(double* db_dp) const;
  bool close_gearing(bool exact);
  double impulse_to_end() const;
  bool gears_before_end() const;
  bool gears_in_time() const;
  void finish_sliding(double ft);
  void finish_geared() { finish_sliding(0.0); }

  const ScaledCollision& c_;
  const double tol_;
  const int max_steps_;
  CollisionOutcome* out_;
  const int order_;

  ScaledBall i_, j_;
  double p_ = 0.0;
  double w_ = 0.0;           // work of the phase
  double work_c_ = 0.0;      // W at the end of compression
  bool compressing_ = true;
  bool geared_ = false;
  bool ended_ = false;
  Pressed pressed_ = Pressed::none;
  double s_ = 0.0;           // +1: ball i pressed, -1: ball j
  bool young_ = false;       // the cloth slip is leaving zero
  PlanarSlip c_zero_;        // its residue where it left
  double p_scale_ = 1.0;     // about the compression's impulse
  int steps_ = 0;
};

TaylorCollision::TaylorCollision(const ScaledCollision& collision, double tolerance,
                                 int max_steps, CollisionOutcome* out)
    : c_(collision),
      tol_(tolerance),
      max_steps_(max_steps),
      out_(out),
      order_(std::clamp(static_cast<int>(std::lround(0.5 - 1.25 * std::log10(tolerance))), 6,
                        kMaxOrder)),
      i_(collision.i),
      j_(collision.j) {
  p_scale_ = 0.5 * approach();
  const PlanarSlip b = slip_b();
  out_->balls_slipping_at_start = b.magnitude() > tol_;
  out_->cloth_i_slipping_at_start = cloth_slip(i_).magnitude() > tol_;
  out_->cloth_j_slipping_at_start = cloth_slip(j_).magnitude() > tol_;
  geared_ = !out_->balls_slipping_at_start || c_.mu_b == 0.0;
  if (!geared_ && c_.mu_s > 0.0 && b.y != 0.0) {
    pressed_ = pressed_by(-b.y);
    s_ = b.y > 0.0 ? 1.0 : -1.0;
    const PlanarSlip c = slip_c();
    if (c.magnitude() <= tol_) {
      young_ = true;
      c_zero_ = c;
    }
  }
}

// Adds the impulses of a stretch (per the equations of ball_collision_model.hpp).
void TaylorCollision::apply(double dp, double ft, double fz, double gt, double gn) {
  double git = 0.0, gin = 0.0, gjt = 0.0, gjn = 0.0;
  if (pressed_ == Pressed::i) {
    git = gt;
    gin = gn;
  } else if (pressed_ == Pressed::j) {
    gjt = gt;
    gjn = gn;
  }
  i_.ut += ft + git;
  i_.un += -dp + gin;
  i_.ot += 2.5 * (fz + gin);
  i_.on += -2.5 * git;
  i_.oz += -2.5 * ft;
  j_.ut += -ft + gjt;
  j_.un += dp + gjn;
  j_.ot += 2.5 * (fz + gjn);
  j_.on += -2.5 * gjt;
  j_.oz += -2.5 * ft;
  p_ += dp;
}

// The rate of the pressed ball's cloth slip per unit p, its friction against the slip's
// direction e (or, at zero, against the drive).
PlanarSlip cloth_rate(double mu_s, double s, PlanarSlip b, PlanarSlip e, double mu_b) {
  const double rb = b.magnitude();
  const double ft = -mu_b * b.x / rb, fz = -mu_b * b.y / rb, normal = mu_b * std::abs(b.y) / rb;
  return {s * ft - 3.5 * mu_s * normal * e.x, -s + 2.5 * fz - 3.5 * mu_s * normal * e.y};
}

Cloth TaylorCollision::choose_cloth(bool* straight) const {
  *straight = false;
  if (pressed_ == Pressed::none) return Cloth::none;
  if (young_) return Cloth::young;
  const PlanarSlip c = slip_c();
  const double rc = c.magnitude();
  const PlanarSlip dc = cloth_rate(c_.mu_s, s_, slip_b(), {c.x / rc, c.y / rc}, c_.mu_b);
  const double rate = dc.magnitude();
  const double ahead = -(c.x * dc.x + c.y * dc.y) / rate;  // distance to closest approach
  const double closest = std::abs(c.x * dc.y - c.y * dc.x) / rate;
  if (ahead > 0.0 && closest <= tol_) {
    *straight = true;
    return Cloth::divide;
  }
  return rc < kRegularise * rate * p_scale_ ? Cloth::regularise : Cloth::divide;
}

// The step's series to order n (coefficients 0..n of the increments from its start);
// returns the orders computed (the work).
int TaylorCollision::series(Cloth cloth, int n, Series& s) const {
  double bt[kTerms], bz[kTerms], ct[kTerms], cn[kTerms], a[kTerms];
  double rb[kTerms], rc[kTerms], rho[kTerms];
  double ex[kTerms], ey[kTerms];           // c / |c| (or v / |v|)
  double vx[kTerms], vy[kTerms], rv[kTerms];  // young: c - c_zero = (p - p0) v
  const PlanarSlip b0 = slip_b();
  const PlanarSlip c0 = pressed_ == Pressed::none ? PlanarSlip{} : slip_c();
  const double a0 = approach();
  const double mu_b = c_.mu_b, beta = -c_.mu_s * c_.mu_b * s_;  // dG/dtau = beta b_z e
  for (int q = 0; q < kSeries; ++q) s.c[q][0] = 0.0;
  double nx = 0.0, ny = 0.0;  // young: v0 turned a quarter
  for (int k = 0; k < n; ++k) {
    const double first = k == 0 ? 1.0 : 0.0;
    bt[k] = first * b0.x + 7.0 * s.c[kFt][k] + s_ * s.c[kGt][k];
    bz[k] = first * b0.y + 5.0 * s.c[kFz][k] + 2.5 * s.c[kGn][k];
    a[k] = first * a0 - 2.0 * s.c[kP][k] + s_ * s.c[kGn][k];
    ct[k] = first * c0.x + s_ * s.c[kFt][k] + 3.5 * s.c[kGt][k];
    cn[k] = first * c0.y - s_ * s.c[kP][k] + 2.5 * s.c[kFz][k] + 3.5 * s.c[kGn][k];
    rb[k] = radius(bt, bz, rb, k);
    double dft = 0.0, dfz = 0.0, dgt = 0.0, dgn = 0.0;
    switch (cloth) {
      case Cloth::none:
        rho[k] = rb[k];
        dft = -mu_b * bt[k];
        dfz = -mu_b * bz[k];
        break;
      case Cloth::divide:
        rc[k] = radius(ct, cn, rc, k);
        ex[k] = (ct[k] - conv(rc, ex, k, 1, k)) / rc[0];
        ey[k] = (cn[k] - conv(rc, ey, k, 1, k)) / rc[0];
        rho[k] = rb[k];
        dft = -mu_b * bt[k];
        dfz = -mu_b * bz[k];
        dgt = beta * conv(bz, ex, k, 0, k);
        dgn = beta * conv(bz, ey, k, 0, k);
        break;
      case Cloth::regularise:
        rc[k] = radius(ct, cn, rc, k);
        rho[k] = conv(rb, rc, k, 0, k);
        dft = -mu_b * conv(bt, rc, k, 0, k);
        dfz = -mu_b * conv(bz, rc, k, 0, k);
        dgt = beta * conv(bz, ct, k, 0, k);
        dgn = beta * conv(bz, cn, k, 0, k);
        break;
      case Cloth::young: {
        rho[k] = rb[k];
        dft = -mu_b * bt[k];
        dfz = -mu_b * bz[k];
        // P_j = rho_{j-1} / j: p's coefficients; P_{k+1} is known now.
        const double p1 = rho[0];
        const double inv = 1.0 / (k + 1);
        // The known part of (c - c_zero)'s coefficient k + 1 (all but the cloth's
        // friction of order k in e_k).
        double zx = (s_ * dft + 3.5 * beta * conv(bz, ex, k, 1, k)) * inv;
        double zy = (-s_ * rho[k] + 2.5 * dfz + 3.5 * beta * conv(bz, ey, k, 1, k)) * inv;
        if (k == 0) {
          // v0 = D - 7/2 mu_s N e0, e0 along the drive D.
          const PlanarSlip d = cloth_drive(pressed_, -mu_b * b0.x / rb[0], -mu_b * b0.y / rb[0]);
          const double rd = d.magnitude();
          ex[0] = d.x / rd;
          ey[0] = d.y / rd;
          nx = -ey[0];
          ny = ex[0];
          zx += 3.5 * beta * bz[0] * ex[0];
          zy += 3.5 * beta * bz[0] * ey[0];
          vx[0] = zx / p1;
          vy[0] = zy / p1;
          rv[0] = vx[0] * ex[0] + vy[0] * ey[0];
        } else {
          // p1 v_k + sum_{j>=2} P_j v_{k+1-j} = z + gamma e_k, e_k = perp(v_k) / |v|_0 + y_k
          for (int j = 2; j <= k + 1; ++j) {
            const double pj = rho[j - 1] / j;
            zx -= pj * vx[k + 1 - j];
            zy -= pj * vy[k + 1 - j];
          }
          const double gamma = 3.5 * beta * bz[0] * inv;
          const double rest = conv(vx, vx, k, 1, k - 1) + conv(vy, vy, k, 1, k - 1) -
                              conv(rv, rv, k, 1, k - 1);
          const double half = 0.5 * rest / rv[0];  // |v|_k = e0 . v_k + half
          const double yx = (-conv(rv, ex, k, 1, k - 1) - half * ex[0]) / rv[0];
          const double yy = (-conv(rv, ey, k, 1, k - 1) - half * ey[0]) / rv[0];
          zx += gamma * yx;
          zy += gamma * yy;
          const double along = (zx * ex[0] + zy * ey[0]) / p1;
          const double across = (zx * nx + zy * ny) / (p1 - gamma / rv[0]);
          vx[k] = along * ex[0] + across * nx;
          vy[k] = along * ey[0] + across * ny;
          rv[k] = along + half;
          ex[k] = (vx[k] - conv(rv, ex, k, 1, k)) / rv[0];
          ey[k] = (vy[k] - conv(rv, ey, k, 1, k)) / rv[0];
        }
        dgt = beta * conv(bz, ex, k, 0, k);
        dgn = beta * conv(bz, ey, k, 0, k);
        break;
      }
    }
    const double inv = 1.0 / (k + 1);
    s.c[kP][k + 1] = rho[k] * inv;
    s.c[kFt][k + 1] = dft * inv;
    s.c[kFz][k + 1] = dfz * inv;
    s.c[kGt][k + 1] = dgt * inv;
    s.c[kGn][k + 1] = dgn * inv;
    s.c[kW][k + 1] = conv(a, rho, k, 0, k) * inv;
  }
  return n;
}

// The pressed ball's cloth friction would turn c by dc/dp: the error of closing the slip
// between the balls now (see the top), and d|b|/dp.
double TaylorCollision::closing_error(double* db_dp) const {
  const PlanarSlip b = slip_b();
  const double rb = b.magnitude();
  const double ft = -c_.mu_b * b.x / rb, fz = -c_.mu_b * b.y / rb;
  if (pressed_ == Pressed::none) {
    *db_dp = (b.x * 7.0 * ft + b.y * 5.0 * fz) / rb;
    return 0.0;
  }
  const PlanarSlip c = slip_c();
  const double rc = c.magnitude();
  if (!(rc > tol_)) {
    *db_dp = 0.0;
    return INFINITY;
  }
  const PlanarSlip e{c.x / rc, c.y / rc};
  const double normal = c_.mu_b * std::abs(b.y) / rb;
  const double gt = -c_.mu_s * normal * e.x, gn = -c_.mu_s * normal * e.y;
  *db_dp = (b.x * (7.0 * ft + s_ * gt) + b.y * (5.0 * fz + 2.5 * gn)) / rb;
  if (!(*db_dp < 0.0)) return INFINITY;
  const double jz = -b.y / (5.0 + 2.5 * c_.mu_s * s_ * e.y);
  const PlanarSlip dc = cloth_rate(c_.mu_s, s_, b, e, c_.mu_b);
  const double dp = rb / -*db_dp;
  return 0.5 * c_.mu_s * std::abs(jz) * dp * (1.0 + dc.magnitude() / rc);
}

// Cancels b with the friction impulse J between the balls and the cloth's impulse that
// comes with it, mu_s |J_z| against the pressed ball's slip. False, changing nothing,
// when the cloth's impulse would carry the approach speed through zero.
bool TaylorCollision::close_gearing(bool exact) {
  const PlanarSlip b = slip_b();
  double jz = -b.y / 5.0, gt = 0.0, gn = 0.0, jt;
  if (pressed_ != Pressed::none && !exact) {
    const PlanarSlip c = slip_c();
    const double rc = c.magnitude();
    const PlanarSlip e{c.x / rc, c.y / rc};
    jz = -b.y / (5.0 + 2.5 * c_.mu_s * s_ * e.y);
    gt = c_.mu_s * s_ * jz * e.x;  // -mu_s |J_z| e, |J_z| = -s J_z
    gn = c_.mu_s * s_ * jz * e.y;
    jt = (-b.x - c_.mu_s * jz * e.x) / 7.0;
  } else {
    jt = -b.x / 7.0;
  }
  const double a = approach() + s_ * gn;
  if (compressing_ ? !(a > 0.0) : !(a < 0.0)) return false;
  apply(0.0, jt, jz, gt, gn);
  geared_ = true;
  out_->add_transition(CollisionEvent::balls_geared, p_);
  return true;
}

// Without cloth friction the approach speed falls as 2 p whatever the friction: the
// impulse left to the end of the collision in closed form.
double TaylorCollision::impulse_to_end() const {
  const double a = approach();
  if (compressing_) return 0.5 * a + c_.restitution * std::sqrt(w_ + 0.25 * a * a);
  const double q = w_ + c_.restitution * c_.restitution * work_c_;
  return q > 0.0 ? 2.0 * q / (std::sqrt(a * a + 4.0 * q) - a) : 0.0;
}

// Without cloth friction |b| falls at least 5 mu_b per unit p (exactly 7 mu_b when b_z
// is zero), so whether gearing comes before the end is known.
bool TaylorCollision::gears_before_end() const {
  const PlanarSlip b = slip_b();
  return b.magnitude() / ((b.y == 0.0 ? 7.0 : 5.0) * c_.mu_b) < impulse_to_end();
}

// With cloth friction the same, conservatively: |b| falls at least (5 - 5/2 mu_s) mu_b
// per unit p, and the approach speed at 2 -+ mu_s mu_b (> 2 - 2/7) per unit p, so the
// collision lasts at least 0.8 of its length without the cloth.
bool TaylorCollision::gears_in_time() const {
  const double fall = (5.0 - 2.5 * c_.mu_s) * c_.mu_b;
  return fall > 0.0 && slip_b().magnitude() / fall < 0.8 * impulse_to_end();
}

// To the end with a constant friction f_t between the balls and none on the cloth (no
// friction once geared; a sideways slip b = (b_t, 0) that does not gear in time): a falls
// as 2 p, W = integral of a dp, in closed form.
void TaylorCollision::finish_sliding(double ft) {
  const double e = c_.restitution;
  double a = approach();
  if (compressing_) {
    const double dp = 0.5 * std::max(a, 0.0);
    work_c_ = w_ + 0.5 * a * dp;
    apply(dp, ft * dp, 0.0, 0.0, 0.0);
    out_->impulse_compression = p_;
    out_->work_compression = work_c_;
    compressing_ = false;
    w_ = 0.0;
    a = approach();
  }
  const double q = w_ + e * e * work_c_;
  const double dp = q > 0.0 ? 2.0 * q / (std::sqrt(a * a + 4.0 * q) - a) : 0.0;
  apply(dp, ft * dp, 0.0, 0.0, 0.0);
  w_ = -e * e * work_c_;
  ended_ = true;
}

void TaylorCollision::step() {
  ++steps_;
  if (pressed_ != Pressed::none && !young_ && slip_c().magnitude() <= tol_) {
    young_ = true;  // at zero: it leaves along its drive
    c_zero_ = slip_c();
  }
  bool straight = false;
  const Cloth cloth = choose_cloth(&straight);
  Series s;
  const int n = order_;
  out_->rhs_evaluations += series(cloth, n, s);

  // Length from the last two coefficients.
  double h = INFINITY;
  for (int j = n - 1; j <= n; ++j) {
    double m = 0.0;
    for (int q = 0; q < kSeries; ++q) m = std::max(m, std::abs(s.c[q][j]));
    if (m > 0.0) h = std::min(h, std::pow(tol_ / m, 1.0 / j));
  }
  if (!std::isfinite(h)) h = 1.0 / tol_;

  enum Event { kNone, kCompression, kEnd, kGear, kCross };
  Event event = kNone;
  double at = h;
  double poly[kTerms];
  // End of compression: a = 0.
  if (compressing_) {
    const double a0 = approach();
    for (int k = 0; k <= n; ++k)
      poly[k] = (k == 0 ? a0 : 0.0) - 2.0 * s.c[kP][k] + s_ * s.c[kGn][k];
    if (poly_at(poly, n, at) <= 0.0) {
      at = poly[0] > 0.0 ? root_in(poly, n, at) : 0.0;
      event = kCompression;
    }
  } else {
    // End of the collision: W of restitution reaching -e^2 W_c.
    for (int k = 0; k <= n; ++k) poly[k] = s.c[kW][k];
    poly[0] = w_ + c_.restitution * c_.restitution * work_c_;
    if (poly_at(poly, n, at) <= 0.0) {
      at = poly[0] > 0.0 ? root_in(poly, n, at) : 0.0;
      event = kEnd;
    }
  }
  // |b| down to where closing errs by the tolerance (the error goes as |b|^2).
  double db_dp = 0.0;
  const double error = closing_error(&db_dp);
  if (pressed_ != Pressed::none && error > 0.0 && std::isfinite(error)) {
    const double rb = slip_b().magnitude();
    const double target = rb * std::sqrt(0.8 * tol_ / error);
    const double fall = (5.0 - 2.5 * c_.mu_s) * c_.mu_b;  // as in gears_in_time
    if (target < rb && fall > 0.0 && target / fall < 0.8 * impulse_to_end()) {
    double bt[kTerms], bz[kTerms];
    const PlanarSlip b0 = slip_b();
    for (int k = 0; k <= n; ++k) {
      bt[k] = (k == 0 ? b0.x : 0.0) + 7.0 * s.c[kFt][k] + s_ * s.c[kGt][k];
      bz[k] = (k == 0 ? b0.y : 0.0) + 5.0 * s.c[kFz][k] + 2.5 * s.c[kGn][k];
    }
    const double x = poly_at(bt, n, at), z = poly_at(bz, n, at);
    if (std::sqrt(x * x + z * z) <= target) {
      // along b's direction at the start: b . e0 falls through target there
      const double ex = b0.x / rb, ez = b0.y / rb;
      for (int k = 0; k <= n; ++k) poly[k] = ex * bt[k] + ez * bz[k];
      poly[0] -= target;
      if (poly[0] > 0.0) {
        at = root_in(poly, n, at);
        event = kGear;
      }
    }
    }
  }
  // A cloth slip heading straight for zero: its component along its start.
  if (straight) {
    const PlanarSlip c0 = slip_c();
    const double rc = c0.magnitude(), ex = c0.x / rc, ey = c0.y / rc;
    for (int k = 0; k <= n; ++k) {
      const double ct = (k == 0 ? c0.x : 0.0) + s_ * s.c[kFt][k] + 3.5 * s.c[kGt][k];
      const double cn = (k == 0 ? c0.y : 0.0) - s_ * s.c[kP][k] + 2.5 * s.c[kFz][k] +
                        3.5 * s.c[kGn][k];
      poly[k] = ex * ct + ey * cn;
    }
    if (poly_at(poly, n, at) <= 0.0) {
      at = root_in(poly, n, at);
      event = kCross;
    }
  }

  double d[kSeries];
  for (int q = 0; q < kSeries; ++q) d[q] = poly_at(s.c[q], n, at);
  apply(d[kP], d[kFt], d[kFz], d[kGt], d[kGn]);
  w_ += d[kW];
  if (cloth == Cloth::young) young_ = false;

  switch (event) {
    case kCompression:
      compressing_ = false;
      work_c_ = w_;
      w_ = 0.0;
      out_->impulse_compression = p_;
      out_->work_compression = work_c_;
      break;
    case kEnd:
      w_ = -c_.restitution * c_.restitution * work_c_;
      ended_ = true;
      return;
    case kCross:
      young_ = true;
      c_zero_ = slip_c();
      out_->add_transition(pressed_ == Pressed::i ? CollisionEvent::cloth_i_through_zero
                                                  : CollisionEvent::cloth_j_through_zero,
                           p_);
      break;
    case kGear:
    case kNone: break;
  }
  // Close the balls' slip once that errs by less than the tolerance.
  if (pressed_ == Pressed::none) {
    if (gears_before_end()) close_gearing(true);
  } else if (closing_error(&db_dp) <= tol_ && gears_in_time()) {
    close_gearing(false);
  }
}

void TaylorCollision::run() {
  if (!geared_ && pressed_ == Pressed::none) {
    if (gears_before_end()) {
      close_gearing(true);
    } else if (slip_b().y == 0.0) {
      finish_sliding(-c_.mu_b * (slip_b().x > 0.0 ? 1.0 : -1.0));  // b stays along t
    }
  }
  while (!ended_ && !geared_ && steps_ < max_steps_) step();
  if (geared_ && !ended_) finish_geared();
  out_->i = i_;
  out_->j = j_;
  out_->impulse_total = p_;
  out_->work_total = compressing_ ? w_ : work_c_ + w_;
  if (!ended_) {
    out_->status = CollisionStatus::step_limit;
    out_->failure = "exact integrator reached its step bound before the collision ended";
  }
}

}  // namespace

CollisionOutcome collide_taylor(const ScaledCollision& collision, double tolerance,
                                int max_steps) {
  CollisionOutcome out;
  TaylorCollision integrator(collision, tolerance, max_steps, &out);
  integrator.run();
  return out;
}

}  // namespace cueplan::physics::detail
