// The `exact` method: the impact equations integrated as Taylor-mode series.
//
// State. Friction depends only on the two slip directions, so the state is carried as
// the slips themselves - (x_I, y_I') at the cushion, (x_C, y_C) at the cloth - with
// o_z, the work W of the current phase and the impulse p (impact_model.hpp units).
// They determine the centroid state: u_y = (y_C - y_I') / (1 + s), o_x = y_C - u_y,
// o_y = (x_I - x_C + c o_z) / (1 + s), u_x = x_C + o_y. A sticking contact's slip is
// held at exactly zero and not integrated.
//
// Steps. Each step computes the state's Taylor coefficients to order N (16 at the
// default tolerance 1e-12) by the recurrences of Taylor-mode arithmetic (products,
// square roots, quotients), chooses its length from the last two coefficients,
// h = min_j (tol / |X_j|)^(1/j), and ends early at the first event, a root of one of
// the step's polynomials. In order, a step: plans its variable and kernel
// (plan_step), computes its series (a fast kernel or General::run), then take_step:
// its length, its events, the state at its end, and the modes that follow.
//
// Variable. A step's variable sigma has dP/dsigma = |u_C|^a |u_I|^b:
//   - a = 1 whenever the cloth slips: that contact is isotropic, so in tau (dP/dtau =
//     |u_C|) the cloth friction times dP/dtau is the polynomial -mu_s p_C u_C, and a
//     slip passing close to zero, which in P turns half round on a scale of its own
//     size, turns on a scale of order one (the equations near zero slip are invariant
//     under scaling the slip). A slip can then never reach zero: it approaches a stick
//     exponentially in sigma, and is closed (below) once small.
//   - b = 1 while the cushion slip is small against its rate of change (it grows from
//     zero, heads for a stick, or passes close to zero), for the same reasons.
//   - A slip heading straight for zero (its closest approach below the crossing
//     threshold, as in the head-on plane) is stepped in P instead, where it is a simple
//     root of |u| continued analytically through zero: the step lands on it.
//
// Events, each a root on the step's polynomials:
//   - end of compression, u_y = 0 (eq. 16c), which changes nothing in the equations: the
//     step goes on through it, and the work of restitution is counted from there (the
//     series of W re-expanded about it), so that the end of the impact, W = -e^2 W_c
//     (eq. 16b as W_total = (1 - e^2) W_c), keeps full precision when e is small;
//   - a slip stepped in P reaching zero; the contact then sticks if the friction that
//     keeps it stuck lies in its cone (the Filippov solution), else it slips on;
//   - a stick breaking: its stick margin mu p_C - |f| (from the state) reaching zero.
// A slip whose contact could stick and that is below close_slip is closed at once by
// the friction impulse that cancels it (error of order slip^2); one within the
// tolerance of zero is zero (it sticks, or leaves zero anew).
//
// Slips growing from zero. At natural roll (the cloth slip starts at zero), after a
// slip has crossed zero or after a stick breaks, the slip's direction is not given by
// the state. The step is then taken in P with u = P^m v: m = 1 where a stick failed
// (the slip grows like P, in the direction d where v(0) = rate(d) is parallel to d)
// and m = 2 where a stick broke at the edge of its cone (it grows like P^2 in the
// direction against the friction that held it). The solution is analytic in P there;
// its coefficients follow from the rates' order-k coefficient, which is affine in v's
// unknown top coefficients: each order solves a small linear system.
//
// The two commonest steps (both contacts slipping, in tau or in sigma) have their own
// kernels (impact_taylor_series.hpp), shared with the SIMD lanes of resolve_impacts;
// every other step uses the general kernel below.

// Vectors of four doubles pass between the kernels' inlined helpers only.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "impact_taylor.hpp"
#include "polynomial_roots.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string_view>

namespace cueplan::physics::detail {
namespace taylor {
namespace {

constexpr int kI = 0, kC = 1;
constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
constexpr int kMaxYoung = 2;
// A slip leaving zero whose rate there is below this grows like P^2 (its stick broke
// at the edge of its cone), above it like P.
constexpr double kLinearStart = 1e-9;
// Newton steps on a young slip's direction (each two evaluations of order 0), per sweep
// over the young slips (at most 4 sweeps, for two of them).
constexpr int kMaxDirectionIterations = 20;
// Lateral parts of the slips and sidespin below this, relative to the normal parts,
// are rounding of a head-on impact.
constexpr double kPlaneRounding = 1e-15;
// A stick whose friction lies outside its cone by less than this fraction of mu holds.
constexpr double kMarginRounding = 1e-12;
// The cushion slip is regularised while it is below this fraction of its rate times
// the compression's impulse (about u_y / c): small against its rate of change.
constexpr double kRegI = 0.3;

// The polynomial c[0..degree] (its coefficient j at c[j * J]) re-expanded about x0:
// out[j] is the coefficient of
// (h - x0)^j (repeated synthetic division: pass i sets out[k] += out[k + 1] x0 for k
// from degree - 1 down to i). Passes run four at a time in one sweep, pass i + p a
// step behind pass i + p - 1, each carrying its newest value in a register: four
// independent chains, the same operations in the same order within each pass.
template <int J>
void shift_to(const double* c, int degree, double x0, double* out) {
  for (int j = 0; j <= degree; ++j) out[j] = c[j * J];
  constexpr int kFused = 4;
  int i = 0;
  for (; i + kFused <= degree; i += kFused) {
    double carry[kFused];  // pass i + p's value at index k + p + 1
    for (double& v : carry) v = out[degree];
    int k = degree - 1;
    for (; k > degree - kFused; --k)  // pass i + p starts at k = degree - 1 - p
      for (int p = degree - 1 - k; p >= 0; --p)
        carry[p] = (p == 0 ? out[k] : carry[p - 1]) + carry[p] * x0;
    for (; k >= i; --k) {
      for (int p = kFused - 1; p > 0; --p) carry[p] = carry[p - 1] + carry[p] * x0;
      carry[0] = out[k] + carry[0] * x0;
      out[k + kFused - 1] = carry[kFused - 1];
    }
    for (int p = 0; p < kFused - 1; ++p) out[i + p] = carry[p];
  }
  for (; i < degree; ++i)
    for (int k = degree - 1; k >= i; --k) out[k] += out[k + 1] * x0;
}

// The state at h from a step's series.
template <int L>
void state_at(SeriesView<L> s, int degree, double h, double q[kState]) {
  polys_at<kState, L>(s.at, kTerms * L, degree, h, q);
}

double cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// Two doubles, or two 64-bit integers, side by side in a SIMD register.
typedef double Pair __attribute__((vector_size(16)));
typedef int64_t IntPair __attribute__((vector_size(16)));
typedef uint64_t BitPair __attribute__((vector_size(16)));

Pair abs(Pair x) { return reinterpret_cast<Pair>(reinterpret_cast<BitPair>(x) & ~(1ULL << 63)); }

// x^(-1/n) for x in [1e-300, 1e300] to about 1e-4 relative (a step size needs no
// more), from the binary exponent and short polynomials for log2 on [1, 2) and 2^f on
// [0, 1); two at once, lane by lane.
Pair inverse_roots(Pair x, Pair n) {
  const BitPair bits = reinterpret_cast<BitPair>(x);
  const IntPair exponent = reinterpret_cast<IntPair>((bits >> 52) & 0x7ff) - 1023;
  const Pair m = reinterpret_cast<Pair>((bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL);
  const Pair t = m - 1.0;  // log2(1 + t), t in [0, 1)
  const Pair log2m =
      t * (1.4425449 + t * (-0.7181452 + t * (0.4575485 + t * (-0.2779042 + t * 0.0958945))));
  const Pair y = -(__builtin_convertvector(exponent, Pair) + log2m) / n;  // |y| < 1000 / n
  const IntPair whole = __builtin_convertvector(y + 1100.0, IntPair) - 1100;  // floor(y)
  const Pair f = y - __builtin_convertvector(whole, Pair);  // 2^f, f in [0, 1)
  const Pair p = 1.0 + f * (0.6931472 + f * (0.2402265 + f * (0.0555041 + f * (0.0096181 + f * 0.0013333))));
  return p * reinterpret_cast<Pair>((whole + 1023) << 52);
}

// x^(-1/n) for x > 0 (std::pow outside [1e-300, 1e300]).
double inverse_root(double x, int n) {
  if (!(x >= 1e-300 && x <= 1e300)) return std::pow(x, -1.0 / n);
  return inverse_roots(Pair{x, x}, Pair{1.0 * n, 1.0 * n})[0];
}

// |(x, y)| (the slips and frictions here are far from overflow and underflow).
double norm(double x, double y) { return std::sqrt(x * x + y * y); }

// Where f falls through zero in (lo, hi], f(lo) = f_lo >= 0 > f(hi): the Illinois
// method, ending within rounding of the root on the side where f >= 0.
template <class F>
double sign_change(F&& f, double lo, double f_lo, double hi) {
  double f_hi = f(hi);
  int side = 0;
  for (int iter = 0; iter < 100 && hi - lo > 2.0 * kEpsilon * hi; ++iter) {
    double x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    const double fx = f(x);
    if (fx >= 0.0) {
      lo = x;
      f_lo = fx;
      if (side == 1) f_hi *= 0.5;
      side = 1;
    } else {
      hi = x;
      f_hi = fx;
      if (side == -1) f_lo *= 0.5;
      side = -1;
    }
  }
  return lo;
}

// Solves a x = b for n <= 4 by Gaussian elimination with partial pivoting; false when
// singular.
bool solve_linear(int n, double a[4][4], double b[4], double x[4]) {
  for (int col = 0; col < n; ++col) {
    int pivot = col;
    for (int r = col + 1; r < n; ++r)
      if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
    if (!(std::abs(a[pivot][col]) > 0.0)) return false;
    if (pivot != col) {
      for (int j = 0; j < n; ++j) std::swap(a[col][j], a[pivot][j]);
      std::swap(b[col], b[pivot]);
    }
    for (int r = col + 1; r < n; ++r) {
      const double f = a[r][col] / a[col][col];
      for (int j = col; j < n; ++j) a[r][j] -= f * a[col][j];
      b[r] -= f * b[col];
    }
  }
  for (int r = n - 1; r >= 0; --r) {
    double v = b[r];
    for (int j = r + 1; j < n; ++j) v -= a[r][j] * x[j];
    x[r] = v / a[r][r];
  }
  for (int r = 0; r < n; ++r)
    if (!std::isfinite(x[r])) return false;
  return true;
}

double conv(const double* a, const double* b, int k) {
  double v = 0.0;
  for (int j = 0; j <= k; ++j) v += a[j] * b[k - j];
  return v;
}

// The fast kernels for one impact: its quads in SSE2 (every x86-64 CPU) or AVX2.
void tau_sse2(const Constants& k, int n, Coefficients<double>& s) {
  series_tau<double, QuadSSE2>(k, n, s);
}
void sigma_sse2(const Constants& k, int n, Coefficients<double>& s) {
  series_sigma<double, QuadSSE2>(k, n, s);
}
__attribute__((target("avx2"))) void tau_avx2(const Constants& k, int n, Coefficients<double>& s) {
  series_tau<double, QuadAVX>(k, n, s);
}
__attribute__((target("avx2"))) void sigma_avx2(const Constants& k, int n,
                                                Coefficients<double>& s) {
  series_sigma<double, QuadAVX>(k, n, s);
}
// The same quads with AVX-512's 32 registers (fewer values kept in memory).
__attribute__((target("avx2,avx512f,avx512vl"))) void tau_avx512(const Constants& k, int n,
                                                                 Coefficients<double>& s) {
  series_tau<double, QuadAVX>(k, n, s);
}
__attribute__((target("avx2,avx512f,avx512vl"))) void sigma_avx512(const Constants& k, int n,
                                                                   Coefficients<double>& s) {
  series_sigma<double, QuadAVX>(k, n, s);
}

}  // namespace

Settings Settings::from(double tolerance, int max_steps) {
  Settings s;
  s.tolerance = tolerance;
  s.max_steps = max_steps;
  // Order: about 1.25 per decimal digit asked (16 at 1e-12), within [6, kMaxOrder].
  const double digits = -std::log10(tolerance);
  s.order = std::clamp(static_cast<int>(std::lround(0.5 + 1.25 * digits)), 6, kMaxOrder);
  // A slip within the tolerance of zero is zero (its sign is below what a step
  // resolves): it sticks, or leaves zero anew.
  s.zero_slip = tolerance;
  s.cross_slip = tolerance;
  s.close_slip = std::min(1e-4, 0.1 * std::sqrt(tolerance));
  return s;
}

// ---------------------------------------------------------------------------
// The general kernel: any modes, any variable, slips growing from zero.

class Integrator::General {
 public:
  General(const Integrator& it, Coefficients<double>& s) : it_(it), s_(s), g_(it.g_) {}

  // Fills s_ to order n + 1. Returns the number of order evaluations (the work), or
  // -1 when a slip growing from zero has no consistent direction.
  int run(int n);

 private:
  struct ContactSeries {
    bool stick = false;
    bool reg = false;
    int young = 0;  // 0, or m of u = P^m v
    double* x = nullptr;  // the state series of the slip
    double* y = nullptr;
    double r[kTerms] = {}, ex[kTerms] = {}, ey[kTerms] = {};
    // A young slip: v's series, its leading direction e0 and normal n, and n . v_k.
    double vx[kTerms] = {}, vy[kTerms] = {};
    double e0x = 1.0, e0y = 0.0, nx = 0.0, ny = 1.0;
    double b[kTerms] = {};
  };

  void slip_recurrence(ContactSeries& X, const double* x, const double* y, int k);
  void derive(int k);
  void rates(int k, double out[kState]);
  bool young_origin();
  void young_trial(int k, const double* z);
  void young_residual(int k, const double* z, double* res, double rate[kState]);
  void measure_jacobian(double rate[kState]);
  bool young_order(int k, double rate[kState]);

  const Integrator& it_;
  Coefficients<double>& s_;
  const Geometry& g_;
  ContactSeries c_[2];
  int young_[kMaxYoung] = {};
  int young_count_ = 0;
  // d(young slips' rates at order k) / d(their directions' coefficient of order k):
  // the same at every order k >= 1 (it is the order-0 Jacobian).
  double jacobian_[4][4] = {};
  // The same for every value rates() writes at order k (the friction series, dP/dsigma,
  // the rates): each is affine in those coefficients with the same slope at every
  // order, so the solution of an order moves them without another evaluation.
  static constexpr int kSeriesArrays = 12;
  static constexpr int kAffine = kSeriesArrays + kState;
  double slope_[kAffine][4] = {};
  void affine_values(int k, const double rate[kState], double out[kAffine]);
  int evaluations_ = 0;
  double uy_[kTerms] = {};
  double fix_[kTerms] = {}, fiy_[kTerms] = {}, fcx_[kTerms] = {}, fcy_[kTerms] = {};
  double pc_[kTerms] = {}, num_[kTerms] = {}, den_[kTerms] = {};
  double rho_[kTerms] = {};
  double Fix_[kTerms] = {}, Fiy_[kTerms] = {}, Fcx_[kTerms] = {}, Fcy_[kTerms] = {};
  bool kk_ready_ = false;
  Friction kk_;
};

// |u| and u / |u| at order k from the series (x, y) (k >= 1; order 0 set by the caller).
// The sums run over pairs (j, k - j) and in two halves: short dependency chains, which
// is what a young step's time goes to.
void Integrator::General::slip_recurrence(ContactSeries& X, const double* x, const double* y,
                                          int k) {
  const double inv = 1.0 / X.r[0];
  // |u|^2 at order k less the products r_j r_{k-j}, 0 < j < k (each pair once, doubled).
  double sx = 0.0, sy = 0.0, sr = 0.0;
  int j = 0;
  for (; 2 * j < k; ++j) {
    sx += x[j] * x[k - j];
    sy += y[j] * y[k - j];
    if (j > 0) sr += X.r[j] * X.r[k - j];
  }
  double sum = 2.0 * ((sx + sy) - sr);
  if (2 * j == k) sum += x[j] * x[j] + y[j] * y[j] - X.r[j] * X.r[j];
  X.r[k] = 0.5 * sum * inv;
  double tx0 = x[k], ty0 = y[k], tx1 = 0.0, ty1 = 0.0;
  for (j = 1; j + 1 <= k; j += 2) {
    tx0 -= X.r[j] * X.ex[k - j];
    ty0 -= X.r[j] * X.ey[k - j];
    tx1 += X.r[j + 1] * X.ex[k - j - 1];
    ty1 += X.r[j + 1] * X.ey[k - j - 1];
  }
  if (j == k) {
    tx0 -= X.r[k] * X.ex[0];
    ty0 -= X.r[k] * X.ey[0];
  }
  X.ex[k] = (tx0 - tx1) * inv;
  X.ey[k] = (ty0 - ty1) * inv;
}

// u_y and the slipping (not young) contacts' |u|, e at order k.
void Integrator::General::derive(int k) {
  uy_[k] = (s_.c[kYC][k] - s_.c[kYI][k]) * it_.k_.inv_1ps;
  for (int i = 0; i < 2; ++i) {
    ContactSeries& X = c_[i];
    if (X.stick || X.young) continue;
    if (k == 0) {
      X.r[0] = norm(X.x[0], X.y[0]);
      X.ex[0] = X.x[0] / X.r[0];
      X.ey[0] = X.y[0] / X.r[0];
    } else {
      slip_recurrence(X, X.x, X.y, k);
    }
  }
}

// Friction (per unit P), dP/dsigma and the rates per unit sigma at order k.
void Integrator::General::rates(int k, double out[kState]) {
  ++evaluations_;
  const Geometry& g = g_;
  const ContactSeries& I = c_[kI];
  const ContactSeries& C = c_[kC];
  const double first = k == 0 ? 1.0 : 0.0;
  if (!I.stick) {
    fix_[k] = -g.mu_w * I.ex[k];
    fiy_[k] = -g.mu_w * I.ey[k];
  }
  if (!I.stick && !C.stick) {
    pc_[k] = g.s * first - g.c * fiy_[k];
    fcx_[k] = -g.mu_s * conv(pc_, C.ex, k);
    fcy_[k] = -g.mu_s * conv(pc_, C.ey, k);
  } else if (I.stick && !C.stick) {
    // eq. for d(slip_I) = 0 (impact_model.hpp friction_for) as a quotient of series
    num_[k] = -g.s * g.c * first + g.d * g.mu_s * g.s * C.ey[k];
    den_[k] = g.b * first + g.d * g.mu_s * g.c * C.ey[k];
    double q = num_[k];
    for (int j = 1; j <= k; ++j) q -= den_[j] * fiy_[k - j];
    fiy_[k] = q / den_[0];
    pc_[k] = g.s * first - g.c * fiy_[k];
    fcx_[k] = -g.mu_s * conv(pc_, C.ex, k);
    fcy_[k] = -g.mu_s * conv(pc_, C.ey, k);
    fix_[k] = -g.a * fcx_[k] / 3.5;
  } else if (!I.stick && C.stick) {
    pc_[k] = g.s * first - g.c * fiy_[k];
    fcx_[k] = -g.a * fix_[k] / 3.5;
    fcy_[k] = (g.c * first - g.d * fiy_[k]) / 3.5;
  } else {
    if (!kk_ready_) {
      kk_ = friction_for(g, {true, true}, {}, {});
      kk_ready_ = true;
    }
    fix_[k] = first * kk_.ix;
    fiy_[k] = first * kk_.iy;
    fcx_[k] = first * kk_.cx;
    fcy_[k] = first * kk_.cy;
    pc_[k] = first * kk_.pc;
  }

  // dP/dsigma and friction times it.
  const bool ri = I.reg, rc = C.reg;
  if (ri && rc)
    rho_[k] = conv(I.r, C.r, k);
  else if (ri)
    rho_[k] = I.r[k];
  else if (rc)
    rho_[k] = C.r[k];
  else
    rho_[k] = first;
  double uy_rho;
  if (ri || rc) {
    Fix_[k] = conv(rho_, fix_, k);
    Fiy_[k] = conv(rho_, fiy_, k);
    Fcx_[k] = conv(rho_, fcx_, k);
    Fcy_[k] = conv(rho_, fcy_, k);
    uy_rho = conv(uy_, rho_, k);
  } else {
    Fix_[k] = fix_[k];
    Fiy_[k] = fiy_[k];
    Fcx_[k] = fcx_[k];
    Fcy_[k] = fcy_[k];
    uy_rho = uy_[k];
  }
  // d(slip)/dsigma = rho (0, s c, 0, -c) + K F; eqs. (14) for o_z and W.
  out[kXI] = 3.5 * Fix_[k] + g.a * Fcx_[k];
  out[kYI] = g.s * g.c * rho_[k] + g.b * Fiy_[k] + g.d * Fcy_[k];
  out[kXC] = g.a * Fix_[k] + 3.5 * Fcx_[k];
  out[kYC] = -g.c * rho_[k] + g.d * Fiy_[k] + 3.5 * Fcy_[k];
  out[kOZ] = -2.5 * g.c * Fix_[k];
  out[kW] = g.c * uy_rho;
  out[kP] = rho_[k];
}

// Order 0 of the young slips. A slip that grows like P has its rate at zero slip
// parallel to its direction and pointing away from zero: found by Newton steps on
// the angle from the seed. A slip whose stick has just broken at the edge of its cone
// has zero rate there and grows like P^2, against the friction that held it; but when
// the other contact changes mode at the same point the rate jumps, and the slip grows
// like P after all - so every young slip is tried as one growing like P first.
bool Integrator::General::young_origin() {
  double rate[kState];
  auto rate_of = [&](const ContactSeries& Y, double* rx, double* ry) {
    rates(0, rate);
    const bool at_i = &Y == &c_[kI];
    *rx = rate[at_i ? kXI : kXC];
    *ry = rate[at_i ? kYI : kYC];
  };
  // Newton steps on the angle from the direction (ex[0], ey[0]); true when they end
  // with the rate parallel to it and pointing away from zero (the rate is parallel
  // to the direction opposite too: that is no solution).
  auto newton = [&](ContactSeries& Y) {
    double angle = std::atan2(Y.ey[0], Y.ex[0]);
    double rx, ry;
    for (int iter = 0; iter < kMaxDirectionIterations; ++iter) {
      rate_of(Y, &rx, &ry);
      const double f = cross(Y.ex[0], Y.ey[0], rx, ry);
      if (std::abs(f) <= 4.0 * kEpsilon * norm(rx, ry)) break;
      const double ex = Y.ex[0], ey = Y.ey[0], step = 1e-7;
      Y.ex[0] = std::cos(angle + step);
      Y.ey[0] = std::sin(angle + step);
      double ax, ay;
      rate_of(Y, &ax, &ay);
      double delta = -f / ((cross(Y.ex[0], Y.ey[0], ax, ay) - f) / step);
      if (!std::isfinite(delta)) {
        Y.ex[0] = ex;
        Y.ey[0] = ey;
        break;
      }
      angle += std::clamp(delta, -0.5, 0.5);
      Y.ex[0] = std::cos(angle);
      Y.ey[0] = std::sin(angle);
    }
    rate_of(Y, &rx, &ry);
    const double grow = rx * Y.ex[0] + ry * Y.ey[0];
    return grow > kLinearStart && std::abs(cross(Y.ex[0], Y.ey[0], rx, ry)) <= 1e-9 * norm(rx, ry);
  };
  for (int i = 0; i < young_count_; ++i) {
    ContactSeries& Y = c_[young_[i]];
    Y.ex[0] = Y.e0x;
    Y.ey[0] = Y.e0y;
    Y.young = 1;
  }
  // From the seed, then its opposite and the two perpendiculars (exact vectors: an
  // exact axis stays exact); with two young slips, sweeps over both.
  bool linear[kMaxYoung] = {};
  const int sweeps = young_count_ > 1 ? 4 : 1;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    for (int i = 0; i < young_count_; ++i) {
      ContactSeries& Y = c_[young_[i]];
      const double sx = Y.e0x, sy = Y.e0y;
      const double starts[5][2] = {{Y.ex[0], Y.ey[0]}, {sx, sy}, {-sx, -sy}, {-sy, sx}, {sy, -sx}};
      linear[i] = false;
      for (int k = sweep == 0 ? 1 : 0; k < 5 && !linear[i]; ++k) {
        Y.ex[0] = starts[k][0];
        Y.ey[0] = starts[k][1];
        linear[i] = newton(Y);
      }
      if (!linear[i]) {
        Y.ex[0] = sx;
        Y.ey[0] = sy;
      }
    }
  }
  rates(0, rate);
  for (int i = 0; i < young_count_; ++i) {
    ContactSeries& Y = c_[young_[i]];
    const bool at_i = young_[i] == kI;
    const double rx = rate[at_i ? kXI : kXC], ry = rate[at_i ? kYI : kYC];
    const double size = norm(rx, ry);
    const double grow = rx * Y.ex[0] + ry * Y.ey[0];
    // Grows like P: its rate is along it, away from zero, and not within rounding of
    // zero (a stick that broke at the edge of its cone leaves a rate of that order).
    if (linear[i] && grow > kLinearStart && std::abs(cross(Y.ex[0], Y.ey[0], rx, ry)) <= 1e-9 * size) {
      Y.e0x = Y.ex[0];
      Y.e0y = Y.ey[0];
      Y.r[0] = grow;
      Y.vx[0] = grow * Y.e0x;
      Y.vy[0] = grow * Y.e0y;
    } else {
      // (A stick that fails only within rounding of its cone's edge leaves no linear
      // growth either: such a slip too grows like P^2.)
      Y.young = 2;
      Y.ex[0] = Y.e0x;
      Y.ey[0] = Y.e0y;
      Y.r[0] = 1.0;  // found at order 1
    }
    Y.nx = -Y.e0y;
    Y.ny = Y.e0x;
  }
  rates(0, rate);
  return true;
}

// The young slips' order-k data for the unknowns z: v_k for m = 1; for m = 2 the
// component of v_{k-1} along e0 and that of v_k along n (at k = 1: |v_0| and the
// direction's first coefficient along n).
void Integrator::General::young_trial(int k, const double* z) {
  for (int i = 0; i < young_count_; ++i) {
    ContactSeries& Y = c_[young_[i]];
    const double z0 = z[2 * i], z1 = z[2 * i + 1];
    if (Y.young == 1) {
      Y.vx[k] = z0;
      Y.vy[k] = z1;
      slip_recurrence(Y, Y.vx, Y.vy, k);
    } else if (k == 1) {
      Y.r[0] = z0;
      Y.vx[0] = z0 * Y.e0x;
      Y.vy[0] = z0 * Y.e0y;
      Y.ex[1] = z1 * Y.nx;
      Y.ey[1] = z1 * Y.ny;
      Y.vx[1] = z1 * z0 * Y.nx;
      Y.vy[1] = z1 * z0 * Y.ny;
      Y.r[1] = 0.0;
    } else {
      Y.vx[k - 1] = z0 * Y.e0x + Y.b[k - 1] * Y.nx;
      Y.vy[k - 1] = z0 * Y.e0y + Y.b[k - 1] * Y.ny;
      slip_recurrence(Y, Y.vx, Y.vy, k - 1);
      Y.vx[k] = z1 * Y.nx;
      Y.vy[k] = z1 * Y.ny;
      slip_recurrence(Y, Y.vx, Y.vy, k);
    }
  }
}

// The young slips' rates at order k less (k + 1) times their state coefficient of
// order k + 1 (v_k for m = 1, v_{k-1} for m = 2): zero at the solution.
void Integrator::General::young_residual(int k, const double* z, double* res,
                                         double rate[kState]) {
  young_trial(k, z);
  rates(k, rate);
  for (int i = 0; i < young_count_; ++i) {
    const ContactSeries& Y = c_[young_[i]];
    const bool at_i = young_[i] == kI;
    const int j = Y.young == 1 ? k : k - 1;
    res[2 * i] = rate[at_i ? kXI : kXC] - (k + 1) * Y.vx[j];
    res[2 * i + 1] = rate[at_i ? kYI : kYC] - (k + 1) * Y.vy[j];
  }
}

// The Jacobian of the young slips' rates at order k in their directions' coefficients
// of order k, measured at k = 1 (the rates are affine in them, with the order-0
// Jacobian as the linear part at every order).
void Integrator::General::measure_jacobian(double rate[kState]) {
  const int dim = 2 * young_count_;
  const double zero[4] = {};
  double base[4], moved[4];
  auto young_rates = [&](double* out) {
    rates(1, rate);
    for (int i = 0; i < young_count_; ++i) {
      const bool at_i = young_[i] == kI;
      out[2 * i] = rate[at_i ? kXI : kXC];
      out[2 * i + 1] = rate[at_i ? kYI : kYC];
    }
  };
  double base_all[kAffine], moved_all[kAffine];
  young_trial(1, zero);
  young_rates(base);
  affine_values(1, rate, base_all);
  for (int j = 0; j < dim; ++j) {
    young_trial(1, zero);
    ContactSeries& Y = c_[young_[j / 2]];
    (j % 2 == 0 ? Y.ex[1] : Y.ey[1]) += 1.0;
    young_rates(moved);
    affine_values(1, rate, moved_all);
    for (int r = 0; r < dim; ++r) jacobian_[r][j] = moved[r] - base[r];
    for (int r = 0; r < kAffine; ++r) slope_[r][j] = moved_all[r] - base_all[r];
  }
}

// Every value rates(k) writes: its series' coefficients of order k, then the rates.
void Integrator::General::affine_values(int k, const double rate[kState], double out[kAffine]) {
  const double* series[kSeriesArrays] = {fix_, fiy_, fcx_, fcy_, pc_, num_,
                                         den_, rho_, Fix_, Fiy_, Fcx_, Fcy_};
  for (int a = 0; a < kSeriesArrays; ++a) out[a] = series[a][k];
  for (int q = 0; q < kState; ++q) out[kSeriesArrays + q] = rate[q];
}

// Solves order k (>= 1) of the young slips: the residual at zero unknowns, the
// linear map from the Jacobian and the recurrences' own dependence on the unknowns,
// then the rates at the solution.
bool Integrator::General::young_order(int k, double rate[kState]) {
  const int dim = 2 * young_count_;
  double z[4] = {}, res0[4], res[4], a[4][4] = {}, b[4];
  young_residual(k, z, res0, rate);
  // d(direction coefficient k) / d(unknowns), and the residual's own terms.
  double de[4][4] = {};  // rows: e_k components of the young slips; columns: unknowns
  for (int i = 0; i < young_count_; ++i) {
    const ContactSeries& Y = c_[young_[i]];
    const int x = 2 * i, y = 2 * i + 1;
    if (Y.young == 1) {
      // e_k = ... + (I - e0 e0^T) v_k / |v|_0; residual -(k + 1) v_k
      const double inv = 1.0 / Y.r[0];
      de[x][x] = (1.0 - Y.e0x * Y.e0x) * inv;
      de[x][y] = -Y.e0x * Y.e0y * inv;
      de[y][x] = -Y.e0y * Y.e0x * inv;
      de[y][y] = (1.0 - Y.e0y * Y.e0y) * inv;
      a[x][x] -= k + 1;
      a[y][y] -= k + 1;
    } else if (k == 1) {
      // unknowns |v|_0 (residual -2 |v|_0 e0) and beta (e_1 = beta n)
      de[x][y] = Y.nx;
      de[y][y] = Y.ny;
      a[x][x] -= 2.0 * Y.e0x;
      a[y][x] -= 2.0 * Y.e0y;
    } else {
      // unknowns e0 . v_{k-1} (e_k moves by -e_1 / |v|_0; residual -(k + 1) e0) and
      // n . v_k (e_k moves by n / |v|_0)
      const double inv = 1.0 / Y.r[0];
      de[x][x] = -Y.ex[1] * inv;
      de[y][x] = -Y.ey[1] * inv;
      de[x][y] = Y.nx * inv;
      de[y][y] = Y.ny * inv;
      a[x][x] -= (k + 1) * Y.e0x;
      a[y][x] -= (k + 1) * Y.e0y;
    }
  }
  for (int r = 0; r < dim; ++r)
    for (int c = 0; c < dim; ++c)
      for (int m = 0; m < dim; ++m) a[r][c] += jacobian_[r][m] * de[m][c];
  for (int r = 0; r < dim; ++r) b[r] = -res0[r];
  if (!solve_linear(dim, a, b, z)) return false;
  for (int i = 0; i < young_count_; ++i)
    if (c_[young_[i]].young == 2 && k == 1 && !(z[2 * i] > 0.0)) return false;  // not growing
  if (k == 1) {
    young_residual(k, z, res, rate);
  } else {
    // The young series at the solution, and what rates(k) would write there: its
    // values at zero unknowns moved along their slopes by the directions' change.
    double move[4] = {};
    for (int m = 0; m < dim; ++m)
      for (int c = 0; c < dim; ++c) move[m] += de[m][c] * z[c];
    bool linear = true;
    for (int i = 0; i < young_count_; ++i) linear = linear && c_[young_[i]].young == 1;
    if (linear) {
      // v_k = z: |v|_k moves by e0 . z, e_k by (I - e0 e0^T) z / |v|_0 (de z).
      for (int i = 0; i < young_count_; ++i) {
        ContactSeries& Y = c_[young_[i]];
        const double z0 = z[2 * i], z1 = z[2 * i + 1];
        Y.vx[k] = z0;
        Y.vy[k] = z1;
        Y.r[k] += Y.e0x * z0 + Y.e0y * z1;
        Y.ex[k] += move[2 * i];
        Y.ey[k] += move[2 * i + 1];
      }
    } else {
      young_trial(k, z);
    }
    double* series[kSeriesArrays] = {fix_, fiy_, fcx_, fcy_, pc_, num_,
                                     den_, rho_, Fix_, Fiy_, Fcx_, Fcy_};
    for (int r = 0; r < kAffine; ++r) {
      double v = 0.0;
      for (int m = 0; m < dim; ++m) v += slope_[r][m] * move[m];
      if (r < kSeriesArrays)
        series[r][k] += v;
      else
        rate[r - kSeriesArrays] += v;
    }
  }
  for (int i = 0; i < young_count_; ++i) {
    ContactSeries& Y = c_[young_[i]];
    if (Y.young == 2) Y.b[k] = k == 1 ? z[2 * i + 1] * z[2 * i] : z[2 * i + 1];
  }
  return true;
}

int Integrator::General::run(int n) {
  for (int i = 0; i < 2; ++i) {
    ContactSeries& X = c_[i];
    const ContactMode& m = it_.mode_[i];
    X.stick = m.stick;
    X.reg = it_.plan_.reg[i];
    X.young = m.stick ? 0 : m.young;
    X.x = s_.c[i == kI ? kXI : kXC];
    X.y = s_.c[i == kI ? kYI : kYC];
    if (X.young) {
      young_[young_count_++] = i;
      X.e0x = m.seed.x;
      X.e0y = m.seed.y;
    }
    if (X.stick || X.young) {
      for (int k = 0; k < kTerms; ++k) X.x[k] = X.y[k] = 0.0;
    }
  }
  double rate[kState];
  for (int k = 0; k <= n; ++k) {
    derive(k);
    if (young_count_ == 0) {
      rates(k, rate);
    } else if (k == 0) {
      if (!young_origin()) return -1;
      rates(0, rate);
    } else {
      if (k == 1) measure_jacobian(rate);
      if (!young_order(k, rate)) return -1;
    }
    const double inv = kInverse[k];
    for (int q = 0; q < kState; ++q) s_.c[q][k + 1] = rate[q] * inv;
    for (int i = 0; i < 2; ++i) {
      ContactSeries& X = c_[i];
      if (X.stick) {
        X.x[k + 1] = X.y[k + 1] = 0.0;
      } else if (X.young) {
        const int j = k + 1 - X.young;
        X.x[k + 1] = j >= 0 ? X.vx[j] : 0.0;
        X.y[k + 1] = j >= 0 ? X.vy[j] : 0.0;
      }
    }
  }
  return evaluations_;
}

// ---------------------------------------------------------------------------
// The integrator.

Integrator::Integrator(const ScaledImpact& impact, const Constants& constants,
                       const Settings& settings, std::vector<TraceSample>* trace,
                       ScaledOutcome* out)
    : k_(constants),
      g_(constants.g),
      set_(settings),
      e_(impact.restitution),
      trace_(trace),
      out_(out) {
  const Slips sl = slips_of(g_, impact.incoming);
  q_[kXI] = sl.ix;
  q_[kYI] = sl.iy;
  q_[kXC] = sl.cx;
  q_[kYC] = sl.cy;
  q_[kOZ] = impact.incoming.oz;
  q_[kW] = 0.0;
  q_[kP] = 0.0;
  uy_start_ = impact.incoming.uy;
  // An impact within rounding of the head-on plane (no motion along the cushion, no
  // sidespin) is solved in it: its lateral parts are rounding, and the series would
  // carry them, amplified, up to the tolerance instead of keeping the plane's symmetry.
  const double plane = std::max({1.0, std::abs(q_[kYI]), std::abs(q_[kYC])});
  if (std::max({std::abs(q_[kXI]), std::abs(q_[kXC]), std::abs(q_[kOZ])}) <= kPlaneRounding * plane)
    q_[kXI] = q_[kXC] = q_[kOZ] = 0.0;
  // A first guess of a step's length in P: the whole compression, about u_y / c.
  step_impulse_ = uy_start_ / g_.c;
  *out_ = ScaledOutcome{};
  for (int i = 0; i < 2; ++i)
    if (slip_size(i) <= set_.zero_slip) {
      q_[i == kI ? kXI : kXC] = 0.0;
      q_[i == kI ? kYI : kYC] = 0.0;
    }
  settle_modes(false, false);
  out_->transition_count = 0;  // the starting modes are not changes
  out_->cushion_slipping_at_start = !mode_[kI].stick;
  out_->table_slipping_at_start = !mode_[kC].stick;
  mode_changes_ = 0;
  record_trace<1>(nullptr, 0, 0.0);
}

// The centroid state of the series state q.
Scaled Integrator::centroid(const double* q) const {
  Scaled c;
  c.uy = (q[kYC] - q[kYI]) * k_.inv_1ps;
  c.ox = q[kYC] - c.uy;
  c.oz = q[kOZ];
  c.oy = (q[kXI] - q[kXC] + g_.c * q[kOZ]) * k_.inv_1ps;
  c.ux = q[kXC] + c.oy;
  return c;
}

double Integrator::slip_size(int contact) const {
  return contact == kI ? norm(q_[kXI], q_[kYI]) : norm(q_[kXC], q_[kYC]);
}

Integrator::Shape Integrator::shape(int contact) const {
  const double x = q_[contact == kI ? kXI : kXC], y = q_[contact == kI ? kYI : kYC];
  const double r = norm(x, y);
  return {r, x / r, y / r};
}

// A slipping contact's direction: its slip's, or for a young one its seed.
Direction Integrator::direction(int contact) const { return direction(contact, shape(contact)); }

Direction Integrator::direction(int contact, const Shape& shape) const {
  if (mode_[contact].young || !(shape.r > 0.0)) return mode_[contact].seed;
  return {shape.ex, shape.ey};
}

// Rates of the slips per unit P at the state plan_step plans from: x_I, y_I', x_C, y_C.
void Integrator::slip_rates(double rates[4]) const {
  const Friction f = friction_for(g_, {mode_[kI].stick, mode_[kC].stick},
                                  direction(kI, planned_[kI]), direction(kC, planned_[kC]));
  const Rates r = rates_for(g_, f);
  rates[0] = r.ux + r.oy * g_.s - r.oz * g_.c;
  rates[1] = -r.uy * g_.s + r.ox;
  rates[2] = r.ux - r.oy;
  rates[3] = r.uy + r.ox;
}

// The stick margin of a sticking contact at the state q (impact_model.hpp): its
// friction depends on the other contact's slip direction alone.
double Integrator::stick_margin_at(int contact, const double* q) const {
  auto dir = [&](int c) {
    const double x = q[c == kI ? kXI : kXC], y = q[c == kI ? kYI : kYC];
    const double r = std::sqrt(x * x + y * y);
    if (!slipping(c) || mode_[c].young || !(r > 0.0)) return mode_[c].seed;
    return Direction{x / r, y / r};
  };
  const Friction f = friction_for(g_, {mode_[kI].stick, mode_[kC].stick}, dir(kI), dir(kC));
  return margin_of(contact, f);
}

// How far a stick's friction lies inside its cone (impact_model.hpp), with the cone
// widened by rounding: a stick at the edge within 1e-12 of mu holds.
double Integrator::margin_of(int contact, const Friction& f) const {
  return contact == kI ? stick_margin_i(g_, f) + kMarginRounding * g_.mu_w
                       : stick_margin_c(g_, f) + kMarginRounding * g_.mu_s;
}

bool Integrator::stick_would_hold(int contact) const {
  Modes m{mode_[kI].stick, mode_[kC].stick};
  (contact == kI ? m.stick_i : m.stick_c) = true;
  const Friction f = friction_for(g_, m, direction(kI), direction(kC));
  return margin_of(contact, f) >= 0.0;
}

// Cancels the small slip at one contact with the friction impulse J that zeroes it,
// at fixed P. The other contact answers as its mode says: a sticking one with the
// friction that keeps its slip at zero, a slipping cloth through its normal impulse
// (p_C falls by c J_Iy, its friction keeps its direction), a slipping cushion not at
// all (its friction follows P alone). This is what sliding on to the zero would add
// beyond sticking from here, to first order: the error is of order slip^2.
// Returns false, changing nothing, when the impulse would carry u_y through zero.
bool Integrator::close_slip(int contact) {
  const Geometry& g = g_;
  double j[4] = {};  // J_Ix, J_Iy, J_Cx, J_Cy
  if (contact == kI) {
    const double ux = q_[kXI], uy = q_[kYI];
    if (mode_[kC].stick) {
      j[0] = -ux / (3.5 - g.a * g.a / 3.5);
      j[1] = -uy / (g.b - g.d * g.d / 3.5);
      j[2] = -g.a * j[0] / 3.5;
      j[3] = -g.d * j[1] / 3.5;
    } else {
      const Direction dc = direction(kC);
      // du_I = (3.5 J_Ix + a mu_s c dc.x J_Iy, (b + d mu_s c dc.y) J_Iy) = -u_I
      const double t = g.mu_s * g.c;
      j[1] = -uy / (g.b + g.d * t * dc.y);
      j[0] = (-ux - g.a * t * dc.x * j[1]) / 3.5;
      j[2] = t * j[1] * dc.x;
      j[3] = t * j[1] * dc.y;
    }
  } else {
    const double ux = q_[kXC], uy = q_[kYC];
    if (mode_[kI].stick) {
      j[2] = -ux / (3.5 - g.a * g.a / 3.5);
      j[3] = -uy / (3.5 - g.d * g.d / g.b);
      j[0] = -g.a * j[2] / 3.5;
      j[1] = -g.d * j[3] / g.b;
    } else {
      j[2] = -ux / 3.5;
      j[3] = -uy / 3.5;
    }
  }
  for (double v : j)
    if (!std::isfinite(v)) return false;
  const double duy = -g.s * j[1] + j[3];
  const double uy = (q_[kYC] - q_[kYI]) * k_.inv_1ps;
  if (compressing_ ? uy + duy <= 0.0 : uy + duy >= 0.0) return false;
  q_[kXI] += 3.5 * j[0] + g.a * j[2];
  q_[kYI] += g.b * j[1] + g.d * j[3];
  q_[kXC] += g.a * j[0] + 3.5 * j[2];
  q_[kYC] += g.d * j[1] + 3.5 * j[3];
  q_[kOZ] += -2.5 * g.c * j[0];
  q_[contact == kI ? kXI : kXC] = 0.0;
  q_[contact == kI ? kYI : kYC] = 0.0;
  return true;
}

// Chooses stick or slip for every contact whose slip is zero (or that sticks now),
// preferring stick wherever its friction fits the cone. A contact forced to slip
// (its stick has just broken) slips. A zero slip that slips is young: it takes the
// direction against the friction that stick would have needed (for one that grows
// like P the young step refines it).
void Integrator::settle_modes(bool force_slip_i, bool force_slip_c) {
  const bool zero_i = mode_[kI].stick || slip_size(kI) == 0.0;
  const bool zero_c = mode_[kC].stick || slip_size(kC) == 0.0;
  if (!zero_i && !zero_c) return;
  const bool can_i = zero_i && !force_slip_i;
  const bool can_c = zero_c && !force_slip_c;
  Direction di = zero_i ? mode_[kI].seed : direction(kI);
  Direction dc = zero_c ? mode_[kC].seed : direction(kC);
  auto against = [](double fx, double fy, Direction fallback) {
    const double n = norm(fx, fy);
    return n > 0.0 ? Direction{-fx / n, -fy / n} : fallback;
  };
  {
    const Friction f = friction_for(g_, {zero_i, zero_c}, di, dc);
    if (zero_i) di = against(f.ix, f.iy, di);
    if (zero_c) dc = against(f.cx, f.cy, dc);
  }
  const Modes candidates[4] = {{can_i, can_c}, {can_i, false}, {false, can_c}, {false, false}};
  Modes chosen{false, false};
  Direction young_i = di, young_c = dc;
  for (const Modes& m : candidates) {
    // Judged with the directions the candidate would use: a zero slip that slips
    // leaves against the friction that would hold it, the other contact as chosen.
    const bool yi = zero_i && !m.stick_i, yc = zero_c && !m.stick_c;
    Direction ti = di, tc = dc;
    if (yi || yc) {
      const Friction held = friction_for(g_, {m.stick_i || yi, m.stick_c || yc}, di, dc);
      if (yi) ti = against(held.ix, held.iy, di);
      if (yc) tc = against(held.cx, held.cy, dc);
    }
    const Friction f = friction_for(g_, m, ti, tc);
    const bool ok_i = !m.stick_i || margin_of(kI, f) >= 0.0;
    const bool ok_c = !m.stick_c || margin_of(kC, f) >= 0.0;
    if (ok_i && ok_c) {
      chosen = m;
      young_i = ti;
      young_c = tc;
      break;
    }
  }
  if (chosen.stick_i != mode_[kI].stick) out_->add_transition(Contact::cushion, chosen.stick_i, q_[kP]);
  if (chosen.stick_c != mode_[kC].stick) out_->add_transition(Contact::table, chosen.stick_c, q_[kP]);
  const bool zero[2] = {zero_i, zero_c};
  const bool stick[2] = {chosen.stick_i, chosen.stick_c};
  const bool force[2] = {force_slip_i, force_slip_c};
  const Direction young[2] = {young_i, young_c};
  for (int i = 0; i < 2; ++i) {
    if (!zero[i]) continue;
    mode_[i].stick = stick[i];
    mode_[i].young = stick[i] ? 0 : (force[i] ? 2 : 1);
    mode_[i].seed = young[i];
    q_[i == kI ? kXI : kXC] = 0.0;
    q_[i == kI ? kYI : kYC] = 0.0;
  }
  ++mode_changes_;
}

// Chooses the next step's variable and kernel.
Kernel Integrator::plan_step() {
  for (int i = 0; i < 2; ++i) planned_[i] = shape(i);  // (take_step reads them too)
  plan_ = Plan{};
  plan_.young = (slipping(kI) && mode_[kI].young) || (slipping(kC) && mode_[kC].young);
  if (plan_.young) return Kernel::general;
  double rate[4];
  slip_rates(rate);
  for (int i = 0; i < 2; ++i) {
    if (!slipping(i)) continue;
    const double x = q_[i == kI ? kXI : kXC], y = q_[i == kI ? kYI : kYC];
    const double dx = rate[2 * i], dy = rate[2 * i + 1];
    const double r = planned_[i].r, speed = norm(dx, dy);
    const double closing = -(x * dx + y * dy) / r;  // -d|u|/dP
    // Heading straight for zero within reach: step in P and land on the root - unless
    // it is there within rounding of its rate, where the quotient u / |u| would divide
    // rounding by rounding (regularised, it is zeroed as it falls below cross_slip).
    const bool straight = closing > 0.0 && r < 3.0 * closing * step_impulse_ &&
                          r > 1e-10 * closing * uy_start_ / g_.c &&
                          std::abs(cross(x, y, dx, dy)) <= set_.cross_slip * speed;
    // (A contact without friction is never regularised: nothing there depends on its
    // slip, and in P its rates are constant, its series exact.)
    const bool friction = (i == kI ? g_.mu_w : g_.mu_s) > 0.0;
    if (straight || !friction)
      plan_.reg[i] = false;
    else
      plan_.reg[i] = i == kC || r < kRegI * speed * uy_start_ / g_.c;
  }
  if (!slipping(kI) || !slipping(kC) || !plan_.reg[kC]) return Kernel::general;
  return plan_.reg[kI] ? Kernel::sigma : Kernel::tau;
}

void Integrator::take_planned_step() {
  for (int attempt = 0; attempt < 2; ++attempt) {
    Coefficients<double> s;
    for (int q = 0; q < kState; ++q) s.c[q][0] = q_[q];
    General general(*this, s);
    const int evaluations = general.run(set_.order);
    if (evaluations >= 0) {
      out_->rhs_evaluations += evaluations;
      take_step(SeriesView<1>{s.c[0]}, set_.order);
      return;
    }
    // A slip that cannot leave zero at all (its stick fails only within rounding):
    // the contact sticks.
    for (int i = 0; i < 2; ++i)
      if (slipping(i) && mode_[i].young) {
        mode_[i] = ContactMode{true, 0, mode_[i].seed};
        out_->add_transition(i == kI ? Contact::cushion : Contact::table, true, q_[kP]);
      }
    plan_step();  // (the general kernel takes any kind of step)
  }
  fail("Taylor integrator found no direction for a slip growing from zero");
}

void Integrator::finish_fast_step(const Coefficients<double>& series) {
  out_->rhs_evaluations += set_.order + 1;
  take_step(SeriesView<1>{series.c[0]}, set_.order);
}

template <int L>
void Integrator::finish_fast_step(SeriesView<L> series, double h, const double* at_h) {
  out_->rhs_evaluations += set_.order + 1;
  take_step(series, set_.order, h, at_h);
}

template <int L>
double Integrator::fast_step_length(SeriesView<L> series) const {
  return step_length(series, set_.order);
}

// The step's length from its last two coefficients: the largest h at which each is
// within the tolerance (never below the rounding of the state).
// (Both orders side by side: worst = (order n, order n + 1).)
template <int L>
double Integrator::step_size(SeriesView<L> s, int n) const {
  const double tol = set_.tolerance;
  Pair worst = {0.0, 0.0};
  for (int q = 0; q < kState; ++q) {
    const double floor = 4.0 * kEpsilon * std::abs(s(q, 0));
    const double scale = floor > tol ? tol / floor : 1.0;
    Pair last;
    if constexpr (L == 1)
      __builtin_memcpy(&last, s.series(q) + n, sizeof last);
    else
      last = Pair{s(q, n), s(q, n + 1)};
    const Pair v = abs(last) * scale;
    worst = worst < v ? v : worst;  // std::max, lane by lane
  }
  worst /= tol;
  double h = INFINITY;
  if (worst[0] >= 1e-300 && worst[0] <= 1e300 && worst[1] >= 1e-300 && worst[1] <= 1e300) {
    const Pair r = inverse_roots(worst, Pair{1.0 * n, n + 1.0});
    h = std::min(h, r[0]);
    h = std::min(h, r[1]);
    return h;
  }
  if (worst[0] > 0.0) h = std::min(h, inverse_root(worst[0], n));
  if (worst[1] > 0.0) h = std::min(h, inverse_root(worst[1], n + 1));
  return h;
}

template <int L>
void Integrator::take_step(SeriesView<L> s, int n) {
  const double h = step_length(s, n);
  double at_h[kState];
  state_at(s, n + 1, h, at_h);
  take_step(s, n, h, at_h);
}

template <int L>
double Integrator::step_length(SeriesView<L> s, int n) const {
  double h = step_size(s, n);
  // Never much beyond the end of the phase: u_y falls at least at
  // worst_normal_deceleration per unit P (validate()), and W with it.
  const double rho = s(kP, 1);
  const double wnd = worst_normal_deceleration(g_);
  const double uy = (q_[kYC] - q_[kYI]) * k_.inv_1ps;
  // (Restitution then lasts at most e sqrt(2) times as long, W falling like P^2.)
  const double remaining =
      compressing_ ? 2.5 * std::max(uy, 0.0) / wnd
                   : std::sqrt(2.0 * std::max(q_[kW] - work_target_, 0.0) / (g_.c * wnd)) +
                         std::max(uy, 0.0) / wnd;
  if (rho > 0.0) h = std::min(h, 2.0 * remaining / rho + 1e-300);
  return h;
}

template <int L>
void Integrator::take_step(SeriesView<L> s, int n, double h, const double* at_h) {
  ++steps_;
  const int deg = n + 1;
  const double rho = s(kP, 1);
  if (!(h > 0.0) || !std::isfinite(h)) {
    fail("Taylor integrator found no usable step");
    return;
  }
  step_impulse_ = h * rho;

  // Events: the first root on the step's polynomials. The end of compression does
  // not change the equations, so the step goes on through it; from there the work of
  // restitution is the series of W expanded about that point less its value there,
  // accurate even when it is a tiny fraction of W_c (e small).
  enum Event { kImpactEnd, kSlipZeroI, kSlipZeroC, kBreakI, kBreakC, kEvents };
  double when[kEvents];
  std::fill(when, when + kEvents, INFINITY);
  double poly[kTerms];  // coefficients 0 .. deg of the event at hand
  poly[0] = 0.0;  // (each use sets it first; this tells the compiler so)
  double compression_end = INFINITY, work_c = 0.0, impulse_c = 0.0;
  double rest[kTerms];  // work since the end of compression, about it
  // at_h: the state at the step's full length; where no event function changes sign on
  // it, that is where the step ends.
  if (compressing_) {
    if ((at_h[kYC] - at_h[kYI]) * k_.inv_1ps <= 0.0) {
      for (int j = 0; j <= deg; ++j) poly[j] = (s(kYC, j) - s(kYI, j)) * k_.inv_1ps;
      compression_end = poly[0] > 0.0 ? root_in(poly, deg, h) : 0.0;
      work_c = poly_at<L>(s.series(kW), deg, compression_end);
      impulse_c = poly_at<L>(s.series(kP), deg, compression_end);
      shift_to<L>(s.series(kW), deg, compression_end, rest);
      rest[0] = 0.0;
      for (int j = 0; j <= deg; ++j) poly[j] = rest[j];
      poly[0] += e_ * e_ * work_c;  // W_rest + e^2 W_c, zero at the end of the impact
      const double left = h - compression_end;
      if (left > 0.0 && poly_at(poly, deg, left) <= 0.0)
        when[kImpactEnd] = compression_end + root_in(poly, deg, left);
    }
  } else if (at_h[kW] - work_target_ <= 0.0) {
    for (int j = 0; j <= deg; ++j) poly[j] = s(kW, j);
    poly[0] -= work_target_;
    when[kImpactEnd] = poly[0] > 0.0 ? root_in(poly, deg, h) : 0.0;
  }
  for (int i = 0; i < 2; ++i) {
    const int ix = i == kI ? kXI : kXC, iy = i == kI ? kYI : kYC;
    if (slipping(i) && !mode_[i].young && !plan_.reg[i]) {
      // A slip stepped in P reaches zero where its component along its first
      // direction does, and it is zero there (else it only passes by).
      const double ex = planned_[i].ex, ey = planned_[i].ey;
      if (ex * at_h[ix] + ey * at_h[iy] <= 0.0) {
        for (int j = 0; j <= deg; ++j) poly[j] = ex * s(ix, j) + ey * s(iy, j);
        const double at = root_in(poly, deg, h);
        const double across =
            -ey * poly_at<L>(s.series(ix), deg, at) + ex * poly_at<L>(s.series(iy), deg, at);
        if (std::abs(across) <= set_.cross_slip) when[kSlipZeroI + i] = at;
      }
    } else if (!slipping(i)) {
      // A stick breaks where its margin, from the state, falls through zero.
      auto margin = [&](double x) {
        double q[kState];
        state_at(s, deg, x, q);
        return stick_margin_at(i, q);
      };
      const double m0 = stick_margin_at(i, q_);
      if (m0 < 0.0)
        when[kBreakI + i] = 0.0;
      else if (stick_margin_at(i, at_h) < 0.0)
        when[kBreakI + i] = sign_change(margin, 0.0, m0, h);
    }
  }
  double end = h;
  for (double w : when) end = std::min(end, w);
  auto at_end = [&](int event) { return when[event] <= end * (1.0 + 1e-12); };

  if (trace_) record_trace(&s, n, end);
  if (end == h)
    std::copy(at_h, at_h + kState, q_);
  else
    state_at(s, deg, end, q_);
  for (int i = 0; i < 2; ++i)
    if (!slipping(i)) {
      q_[i == kI ? kXI : kXC] = 0.0;
      q_[i == kI ? kYI : kYC] = 0.0;
    }
  // A young slip has grown in this step (a step of zero length leaves it young).
  if (end > 0.0)
    for (ContactMode& m : mode_) m.young = 0;

  const bool compression_ended = compression_end <= end * (1.0 + 1e-12);
  if (compression_ended) {
    compressing_ = false;
    out_->impulse_compression = impulse_c;
    work_compression_ = work_c;
    out_->work_compression = work_c;
    work_target_ = -e_ * e_ * work_c;
    q_[kW] = end > compression_end ? poly_at(rest, deg, end - compression_end) : 0.0;
  }
  if (at_end(kImpactEnd)) {
    done_ = true;
    return;
  }
  bool settle = false;
  bool force[2] = {false, false};
  for (int i = 0; i < 2; ++i) {
    if (at_end(kSlipZeroI + i)) {
      q_[i == kI ? kXI : kXC] = 0.0;
      q_[i == kI ? kYI : kYC] = 0.0;
      settle = true;
    }
    if (at_end(kBreakI + i)) {
      force[i] = true;
      settle = true;
    }
  }
  // Small slips: closed where the contact can stick, zero where they have crossed.
  for (int i = 0; i < 2; ++i) {
    if (!slipping(i) || mode_[i].young || at_end(kSlipZeroI + i)) continue;
    const double r = slip_size(i);
    if (r <= set_.zero_slip) {
      q_[i == kI ? kXI : kXC] = 0.0;
      q_[i == kI ? kYI : kYC] = 0.0;
      settle = true;
    } else if (r <= set_.close_slip && stick_would_hold(i)) {
      if (close_slip(i)) settle = true;
    } else if (r <= set_.cross_slip) {
      q_[i == kI ? kXI : kXC] = 0.0;
      q_[i == kI ? kYI : kYC] = 0.0;
      settle = true;
    }
  }
  if (force[kI] || force[kC]) {
    // The contact nearest its cone's edge is the one whose stick breaks.
    const bool both = force[kI] && force[kC];
    if (both) {
      const double mi = stick_margin_at(kI, q_), mc = stick_margin_at(kC, q_);
      force[kI] = mi <= mc;
      force[kC] = mc < mi;
    }
  }
  if (settle) settle_modes(force[kI], force[kC]);
  if (mode_changes_ > 8 * kMaxTransitions) fail("Taylor integrator changed modes too often");
  if (!done_ && steps_ >= set_.max_steps)
    fail("Taylor integrator reached its step bound before the impact ended");
}

template <int L>
void Integrator::record_trace(const SeriesView<L>* s, int n, double h) {
  if (!trace_) return;
  auto sample = [&](const double* q) {
    const double work = compressing_ ? q[kW] : work_compression_ + q[kW];
    trace_->push_back(scaled_sample(g_, centroid(q), q[kP], work));
  };
  if (s == nullptr) {
    sample(q_);
    return;
  }
  // Points inside the step from its polynomials, and its end.
  constexpr int kPoints = 8;
  for (int i = 1; i <= kPoints; ++i) {
    double q[kState];
    state_at(*s, n + 1, h * i / kPoints, q);
    sample(q);
  }
}

void Integrator::fail(const char* why) {
  if (done_) return;
  done_ = true;
  out_->status = ImpactStatus::step_limit;
  out_->failure = why;
}

bool fast_series_on(KernelIsa isa, Kernel kernel, const Constants& constants, int order,
                    Coefficients<double>& s) {
  using Series = void (*)(const Constants&, int, Coefficients<double>&);
  const bool tau = kernel == Kernel::tau;
  Series series = tau ? tau_sse2 : sigma_sse2;
  if (isa == KernelIsa::avx2) {
    if (!__builtin_cpu_supports("avx2")) return false;
    series = tau ? tau_avx2 : sigma_avx2;
  } else if (isa == KernelIsa::avx512) {
    if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("avx512vl")) return false;
    series = tau ? tau_avx512 : sigma_avx512;
  }
  series(constants, order, s);
  return true;
}

KernelIsa widest_isa() {
  // Immutable once set (a thread-safe static initialisation), like the CPU's features.
  static const KernelIsa widest = [] {
    KernelIsa isa = !__builtin_cpu_supports("avx2")        ? KernelIsa::sse2
                    : !__builtin_cpu_supports("avx512vl") ? KernelIsa::avx2
                                                          : KernelIsa::avx512;
    if (const char* cap = std::getenv("CUEPLAN_SIMD")) {
      const std::string_view c(cap);
      if (c == "sse2") isa = KernelIsa::sse2;
      if (c == "avx2" && isa == KernelIsa::avx512) isa = KernelIsa::avx2;
    }
    return isa;
  }();
  return widest;
}

void fast_series(Kernel kernel, const Constants& constants, int order, Coefficients<double>& s) {
  fast_series_on(widest_isa(), kernel, constants, order, s);
}

void Integrator::run() {
  Coefficients<double> s;
  while (!done_) {
    const Kernel kernel = plan_step();
    if (kernel == Kernel::general) {
      take_planned_step();
      continue;
    }
    for (int q = 0; q < kState; ++q) s.c[q][0] = q_[q];
    fast_series(kernel, k_, set_.order, s);
    finish_fast_step(s);
  }
  finish();
}

void Integrator::finish() {
  out_->outgoing = centroid(q_);
  out_->impulse_total = q_[kP];
  out_->work_total = compressing_ ? q_[kW] : work_compression_ + q_[kW];
  if (compressing_ && out_->status == ImpactStatus::ok) {
    out_->status = ImpactStatus::step_limit;
    out_->failure = "Taylor integrator stopped before the end of compression";
  }
}

// The batch's lanes (impact_taylor_lanes.cpp).
template void Integrator::finish_fast_step<2>(SeriesView<2>, double, const double*);
template void Integrator::finish_fast_step<4>(SeriesView<4>, double, const double*);
template void Integrator::finish_fast_step<8>(SeriesView<8>, double, const double*);
template double Integrator::fast_step_length<2>(SeriesView<2>) const;
template double Integrator::fast_step_length<4>(SeriesView<4>) const;
template double Integrator::fast_step_length<8>(SeriesView<8>) const;

}  // namespace taylor

ScaledOutcome solve_taylor(const ScaledImpact& impact, double tolerance, int max_steps,
                           std::vector<TraceSample>* trace) {
  const taylor::Constants constants = taylor::Constants::from(impact.geometry);
  const taylor::Settings settings = taylor::Settings::from(tolerance, max_steps);
  ScaledOutcome out;
  taylor::Integrator integrator(impact, constants, settings, trace, &out);
  integrator.run();
  return out;
}

}  // namespace cueplan::physics::detail
