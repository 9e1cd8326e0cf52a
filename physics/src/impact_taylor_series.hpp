// The Taylor method's series kernels for its two commonest steps (private header):
// both contacts slipping, in tau (dP/dtau = |u_C|) or in sigma (dP/dsigma =
// |u_I| |u_C|); impact_taylor.cpp describes the method.
//
// Each kernel is written once, over a number type T and a quad type Q (four values
// handled together). For one impact T is double and a quad holds, for example, the
// slips (x_I, y_I', x_C, y_C) in SIMD registers: the work of one impact runs in SIMD
// lanes of its own. For a batch (impact_taylor_lanes.cpp) T is a SIMD vector holding
// one value of several impacts and a quad is four such vectors.
// Every operation is an IEEE add, subtract, multiply, divide or square root applied
// element by element, in the same order in both cases, and the files that use the
// kernels are built with -ffp-contract=off (no fused multiply-adds): every impact
// gets bit for bit the same series however it is run.
#pragma once

#include <array>
#include <cmath>
#include <type_traits>

#include "impact_model.hpp"

namespace cueplan::physics::detail::taylor {

constexpr int kMaxOrder = 24;          // series order N at most
constexpr int kTerms = kMaxOrder + 2;  // a step's coefficients 0 .. N+1

// The series of one step, in its variable sigma: the state (slips at the cushion I and
// at the cloth C, spin o_z, work W of the current phase, impulse p).
enum SeriesIndex : int {
  kXI = 0,  // x_I: slip at the cushion along X (eq. 12a)
  kYI,      // y_I': slip at the cushion along Y' (eq. 12b)
  kXC,      // x_C: slip at the cloth along X (eq. 13a)
  kYC,      // y_C: slip at the cloth along Y (eq. 13b)
  kOZ,      // o_z = w_z R / V
  kW,       // work at I along its normal since the phase began (compression, restitution)
  kP,       // cushion normal impulse P_I / (M V)
  kState
};

template <class T>
struct Coefficients {
  T c[kState][kTerms];
};

// 1 / (k + 1): a coefficient of order k + 1 from a rate of order k.
constexpr auto kInverse = [] {
  std::array<double, kTerms> inv{};
  for (int i = 0; i < kTerms; ++i) inv[i] = 1.0 / (i + 1);
  return inv;
}();

// Per-impact constants of the kernels: the geometry and eqs. (14) in slip variables
// (impact_model.hpp), d(slip)/dsigma = rho (0, s c, 0, -c) + K F with F the friction
// times rho = dP/dsigma.
struct Constants {
  Geometry g;
  double inv_1ps = 0.0;  // 1 / (1 + s): u_y = (y_C - y_I') / (1 + s)
  // tau: F_I = -mu_w G, F_C = -mu_s (s u_C + c mu_w H) with G = |u_C| e_I, H = e_Iy' u_C.
  double xi_gx = 0.0, xi_hx = 0.0, xi_xc = 0.0;
  double yi_gy = 0.0, yi_hy = 0.0, yi_yc = 0.0, yi_rc = 0.0;
  double xc_gx = 0.0, xc_hx = 0.0, xc_xc = 0.0;
  double yc_gy = 0.0, yc_hy = 0.0, yc_yc = 0.0, yc_rc = 0.0;
  double oz_gx = 0.0;
  // sigma: F_I = -mu_w |u_C| u_I, F_C = -mu_s (s |u_I| + c mu_w y_I') u_C.
  double cmw = 0.0;  // c mu_w
  double s_xi_m0 = 0.0, s_xi_m2 = 0.0;
  double s_yi_rho = 0.0, s_yi_m1 = 0.0, s_yi_m3 = 0.0;
  double s_xc_m0 = 0.0, s_xc_m2 = 0.0;
  double s_yc_rho = 0.0, s_yc_m1 = 0.0, s_yc_m3 = 0.0;
  double s_oz_m0 = 0.0;

  static Constants from(const Geometry& g) {
    Constants k;
    k.g = g;
    k.inv_1ps = 1.0 / (1.0 + g.s);
    const double ms = g.mu_s * g.s, msw = g.mu_s * g.c * g.mu_w;
    k.xi_gx = -3.5 * g.mu_w;
    k.xi_hx = -g.a * msw;
    k.xi_xc = -g.a * ms;
    k.yi_gy = -g.b * g.mu_w;
    k.yi_hy = -g.d * msw;
    k.yi_yc = -g.d * ms;
    k.yi_rc = g.s * g.c;
    k.xc_gx = -g.a * g.mu_w;
    k.xc_hx = -3.5 * msw;
    k.xc_xc = -3.5 * ms;
    k.yc_gy = -g.d * g.mu_w;
    k.yc_hy = -3.5 * msw;
    k.yc_yc = -3.5 * ms;
    k.yc_rc = -g.c;
    k.oz_gx = 2.5 * g.c * g.mu_w;
    k.cmw = g.c * g.mu_w;
    k.s_xi_m0 = -3.5 * g.mu_w;
    k.s_xi_m2 = -g.a * g.mu_s;
    k.s_yi_rho = g.s * g.c;
    k.s_yi_m1 = -g.b * g.mu_w;
    k.s_yi_m3 = -g.d * g.mu_s;
    k.s_xc_m0 = -g.a * g.mu_w;
    k.s_xc_m2 = -3.5 * g.mu_s;
    k.s_yc_rho = -g.c;
    k.s_yc_m1 = -g.d * g.mu_w;
    k.s_yc_m3 = -3.5 * g.mu_s;
    k.s_oz_m0 = 2.5 * g.c * g.mu_w;
    return k;
  }
};

// ---------------------------------------------------------------------------
// Quads: four values of T handled together. For one impact (T = double) a quad is a
// SIMD vector of four doubles (QuadAVX, for AVX2) or two vectors of two (QuadSSE2,
// for SSE2: GCC splits a four-double vector badly without AVX); for a batch it is four
// T's, each a vector of several impacts' values (QuadOf). All three apply the same
// IEEE operation to each of the four elements.

typedef double Double2 __attribute__((vector_size(16)));
typedef double Double4 __attribute__((vector_size(32)));

template <class T>
struct QuadOf {
  T e[4];
};

struct QuadSSE2 {
  Double2 lo, hi;
};

struct QuadAVX {
  Double4 v;
};

template <class T>
[[gnu::always_inline]] inline QuadOf<T> operator+(const QuadOf<T>& a, const QuadOf<T>& b) {
  return {{a.e[0] + b.e[0], a.e[1] + b.e[1], a.e[2] + b.e[2], a.e[3] + b.e[3]}};
}
template <class T>
[[gnu::always_inline]] inline QuadOf<T> operator*(const QuadOf<T>& a, const QuadOf<T>& b) {
  return {{a.e[0] * b.e[0], a.e[1] * b.e[1], a.e[2] * b.e[2], a.e[3] * b.e[3]}};
}
[[gnu::always_inline]] inline QuadSSE2 operator+(const QuadSSE2& a, const QuadSSE2& b) {
  return {a.lo + b.lo, a.hi + b.hi};
}
[[gnu::always_inline]] inline QuadSSE2 operator*(const QuadSSE2& a, const QuadSSE2& b) {
  return {a.lo * b.lo, a.hi * b.hi};
}
[[gnu::always_inline]] inline QuadAVX operator+(const QuadAVX& a, const QuadAVX& b) {
  return {a.v + b.v};
}
[[gnu::always_inline]] inline QuadAVX operator*(const QuadAVX& a, const QuadAVX& b) {
  return {a.v * b.v};
}

template <class T>
[[gnu::always_inline]] inline T at(const QuadOf<T>& q, int i) {
  return q.e[i];
}
[[gnu::always_inline]] inline double at(const QuadSSE2& q, int i) {
  return i < 2 ? q.lo[i] : q.hi[i - 2];
}
[[gnu::always_inline]] inline double at(const QuadAVX& q, int i) { return q.v[i]; }

template <class Q, class T>
[[gnu::always_inline]] inline Q quad(T a, T b, T c, T d) {
  if constexpr (std::is_same_v<Q, QuadSSE2>)
    return {Double2{a, b}, Double2{c, d}};
  else if constexpr (std::is_same_v<Q, QuadAVX>)
    return {Double4{a, b, c, d}};
  else
    return {{a, b, c, d}};
}

template <class T>
[[gnu::always_inline]] inline T lane_sqrt(T x) {
  if constexpr (std::is_same_v<T, double>) {
    return std::sqrt(x);
  } else {
    T r = x;
    for (int i = 0; i < static_cast<int>(sizeof(T) / sizeof(double)); ++i) r[i] = std::sqrt(x[i]);
    return r;
  }
}

// Each order m of a kernel waits for the last: u_m -> |u_I|_m, |u_C|_m -> e_I,m ->
// the products -> u_{m+1} is its critical chain, and it is computed in T's alone (no
// quads on it). The Cauchy sums of order m need only the terms of orders below m, so
// they are formed beside the chain, ahead of time: the sum of order m + 1 is completed
// (its newest terms, of index m, added) as soon as index m is known, and its older part,
// the head (terms of index <= m - 1), one order before that. Each sum still adds the
// same terms in the same order as a single loop would: the head from zero, oldest
// index pair first, then the newest terms.

// For one impact (T = double) the sums are formed ahead as above; for a batch (T a
// vector of impacts) the chain is already as wide as the vector, the kernel is bound by
// its throughput, and each order forms its sums where it needs them (fewer values kept).
template <class T>
constexpr bool kAhead = std::is_same_v<T, double>;

// The head of sum_{j=1}^{m-1} a[j] * b[m-j]: from zero, j = 2 .. m - 2 (indices <= m - 2).
template <class Q>
[[gnu::always_inline]] inline Q head_sum(int m, const Q* a, const Q* b) {
  Q acc{};
  for (int j = 2; j <= m - 2; ++j) acc = acc + a[j] * b[m - j];
  return acc;
}

// The sum completed: the head, then the terms of index m - 1 (j = m - 1, then j = 1).
template <class Q>
[[gnu::always_inline]] inline Q tail_sum(int m, Q acc, const Q* a, const Q* b) {
  if (m >= 2) acc = acc + a[m - 1] * b[1];
  if (m >= 3) acc = acc + a[1] * b[m - 1];
  return acc;
}

// |u_I|, |u_C| at order m >= 1 by the square-root recurrence
//   |u|_m = (u_0 . u_m + (sum_{j=1}^{m-1} u_j . u_{m-j} - |u|_j |u|_{m-j}) / 2) / |u|_0,
// the sum taken over half its range (it is symmetric). u[j] = (x_I, y_I', x_C, y_C),
// r[j] = (|u_I|, |u_I|, |u_C|, |u_C|). The sum's head (j >= 2, indices <= m - 2) first,
// then j = 1, then the middle term; `si`, `sc` hold the sums for the two contacts, and
// |u|_m = s / (2 |u|_0) + e_0 . u_m.
template <class Q>
struct SquareSums {
  Q uu{}, rr{};
};

template <class Q>
[[gnu::always_inline]] inline SquareSums<Q> square_head(int m, const Q* u, const Q* r) {
  SquareSums<Q> h;
  for (int j = 2; 2 * j < m; ++j) {
    h.uu = h.uu + u[j] * u[m - j];
    h.rr = h.rr + r[j] * r[m - j];
  }
  return h;
}

template <class T, class Q>
[[gnu::always_inline]] inline void square_tail(int m, SquareSums<Q> h, const Q* u, const Q* r,
                                               T* si, T* sc) {
  if (m >= 3) {
    h.uu = h.uu + u[1] * u[m - 1];
    h.rr = h.rr + r[1] * r[m - 1];
  }
  h.uu = h.uu + h.uu;
  h.rr = h.rr + h.rr;
  if (m % 2 == 0) {
    h.uu = h.uu + u[m / 2] * u[m / 2];
    h.rr = h.rr + r[m / 2] * r[m / 2];
  }
  *si = (at(h.uu, 0) + at(h.uu, 1)) - at(h.rr, 0);
  *sc = (at(h.uu, 2) + at(h.uu, 3)) - at(h.rr, 2);
}

// Writes a kernel's coefficients of order j: the slips, o_z, W and p.
template <class T>
[[gnu::always_inline]] inline void store(Coefficients<T>& s, int j, const T& xi, const T& yi,
                                         const T& xc, const T& yc, const T& oz, const T& w,
                                         const T& p) {
  s.c[kXI][j] = xi;
  s.c[kYI][j] = yi;
  s.c[kXC][j] = xc;
  s.c[kYC][j] = yc;
  s.c[kOZ][j] = oz;
  s.c[kW][j] = w;
  s.c[kP][j] = p;
}

// Order 0 of both kernels: the slips, their sizes, 1 / size and the directions.
template <class T, class Q>
struct Start {
  Q u0;
  T ri, rc;                    // |u_I|, |u_C|
  T inv_ri, inv_rc;            // their inverses
  T half_inv_ri, half_inv_rc;  // and halves of those
  T exi, eyi, ecx, ecy;        // e_I, e_C
  T uy;                        // u_y
};

template <class T, class Q>
[[gnu::always_inline]] inline Start<T, Q> start(const Constants& k, const Coefficients<T>& s) {
  Start<T, Q> a;
  a.u0 = quad<Q>(s.c[kXI][0], s.c[kYI][0], s.c[kXC][0], s.c[kYC][0]);
  const Q sq = a.u0 * a.u0;
  a.ri = lane_sqrt((at(sq, 0) + at(sq, 1)));
  a.rc = lane_sqrt((at(sq, 2) + at(sq, 3)));
  a.inv_ri = 1.0 / a.ri;
  a.inv_rc = 1.0 / a.rc;
  a.half_inv_ri = 0.5 * a.inv_ri;
  a.half_inv_rc = 0.5 * a.inv_rc;
  a.exi = at(a.u0, 0) * a.inv_ri;
  a.eyi = at(a.u0, 1) * a.inv_ri;
  a.ecx = at(a.u0, 2) * a.inv_rc;
  a.ecy = at(a.u0, 3) * a.inv_rc;
  a.uy = (at(a.u0, 3) - at(a.u0, 1)) * k.inv_1ps;
  return a;
}

// Eight values handled together: two quads side by side. One impact's kernels keep two
// sums over the same indices in one (the same IEEE operations as two quads).
template <class Q>
struct OctOf {
  Q lo, hi;
};
template <class Q>
[[gnu::always_inline]] inline OctOf<Q> operator+(const OctOf<Q>& a, const OctOf<Q>& b) {
  return {a.lo + b.lo, a.hi + b.hi};
}
template <class Q>
[[gnu::always_inline]] inline OctOf<Q> operator*(const OctOf<Q>& a, const OctOf<Q>& b) {
  return {a.lo * b.lo, a.hi * b.hi};
}
template <class Q>
[[gnu::always_inline]] inline double at(const OctOf<Q>& o, int i) {
  return i < 4 ? at(o.lo, i) : at(o.hi, i - 4);
}

template <class O>
[[gnu::always_inline]] inline O oct(double a, double b, double c, double d, double e, double f,
                                    double g, double h) {
  return {quad<decltype(O::lo)>(a, b, c, d), quad<decltype(O::lo)>(e, f, g, h)};
}

// The square-root recurrence's sums (square_head, square_tail) on w[j] = (u_j, r_j):
// the elements 0-3 are the slips' sum, 4-7 the sizes'.
template <class O>
[[gnu::always_inline]] inline O square_head_oct(int m, const O* w) {
  O h{};
  for (int j = 2; 2 * j < m; ++j) h = h + w[j] * w[m - j];
  return h;
}
template <class O>
[[gnu::always_inline]] inline void square_tail_oct(int m, O h, const O* w, double* si,
                                                   double* sc) {
  if (m >= 3) h = h + w[1] * w[m - 1];
  h = h + h;
  if (m % 2 == 0) h = h + w[m / 2] * w[m / 2];
  *si = (at(h, 0) + at(h, 1)) - at(h, 4);
  *sc = (at(h, 2) + at(h, 3)) - at(h, 6);
}

// One impact's chain in pairs (T = double): the slips as X = (x_I, x_C) and Y = (y_I',
// y_C), the sizes as (|u_I|, |u_C|), e_I, G and H as pairs (x, y); each pair is one SIMD
// operation of two where the scalar chain has two, the same IEEE operations element by
// element and in the same order. Beside it the sums in octs: (u, r) for the sizes and
// the tau kernel's two product sums (ta tb, ga gb) in one.
template <class T>
constexpr bool kPaired = std::is_same_v<T, double>;

template <class O, class Q>
[[gnu::always_inline]] inline void series_tau_paired(const Constants& k, int n,
                                                     Coefficients<double>& s,
                                                     const Start<double, Q>& a) {
  using P = Double2;
  O w[kTerms];               // (x_I, y_I', x_C, y_C, |u_I|, |u_I|, |u_C|, |u_C|)
  O ab[kTerms], cd[kTerms];  // (ta, ga) and (tb, gb) of series_tau
  O head_w[kTerms], head_p[kTerms];
  const Geometry& g = k.g;
  const double ri0 = a.ri, rc0 = a.rc, inv_ri = a.inv_ri, exi0 = a.exi, eyi0 = a.eyi;
  const double uy0 = a.uy, xi0 = at(a.u0, 0), yi0 = at(a.u0, 1), xc0 = at(a.u0, 2),
               yc0 = at(a.u0, 3);
  const P half_inv = {a.half_inv_ri, a.half_inv_rc};
  const P ex = {exi0, a.ecx}, ey = {eyi0, a.ecy};
  const P e_r = {exi0 * inv_ri, eyi0 * inv_ri};
  const P e0 = {exi0, eyi0}, c0 = {xc0, yc0};
  const P inv_ri2 = {inv_ri, inv_ri}, rc02 = {rc0, rc0}, eyi02 = {eyi0, eyi0};
  const P k_hx = {k.xi_hx, k.xc_hx}, k_xc = {k.xi_xc, k.xc_xc}, k_gx = {k.xi_gx, k.xc_gx};
  const P k_hy = {k.yi_hy, k.yc_hy}, k_yc = {k.yi_yc, k.yc_yc}, k_rc = {k.yi_rc, k.yc_rc},
          k_gy = {k.yi_gy, k.yc_gy};
  ab[0] = oct<O>(ri0, ri0, uy0, 0.0, rc0, rc0, eyi0, eyi0);
  cd[0] = oct<O>(exi0, eyi0, rc0, 0.0, exi0, eyi0, xc0, yc0);
  head_w[1] = head_p[1] = O{};
  P x = {xi0, xc0}, y = {yi0, yc0};  // u_m
  P sums_r{}, t01{}, g01{}, g23{};
  double t2 = 0.0;
  auto sums = [&](int o, const O& hw, const O& hp) [[gnu::always_inline]] {
    double si, sc;
    square_tail_oct<O>(o, hw, w, &si, &sc);
    sums_r = P{si, sc};
    const O t = tail_sum<O>(o, hp, ab, cd);
    t01 = P{at(t, 0), at(t, 1)};
    t2 = at(t, 2);
    g01 = P{at(t, 4), at(t, 5)};
    g23 = P{at(t, 6), at(t, 7)};
  };
  for (int m = 0;; ++m) {
    P rr, e, gg, hh;  // (|u_I|, |u_C|)_m, e_I,m, G_m, H_m
    double uym, q;
    if (m == 0) {
      rr = P{ri0, rc0};
      e = e0;
      uym = uy0;
      gg = P{0.0, 0.0} + rc02 * e0;
      hh = P{0.0, 0.0} + eyi02 * c0;
      q = 0.0 + uy0 * rc0;
    } else {
      rr = sums_r * half_inv + (ex * x + ey * y);
      const P xy_i = {x[0], y[0]}, xy_c = {x[1], y[1]};
      e = (xy_i - t01) * inv_ri2 - rr[0] * e_r;
      uym = (y[1] - y[0]) * k.inv_1ps;
      gg = (g01 + rr[1] * e0) + rc02 * e;
      hh = (g23 + e[1] * c0) + eyi02 * xy_c;
      q = (t2 + uy0 * rr[1]) + uym * rc0;
    }
    const double inv = kInverse[m];
    const P x1 = ((k_hx * hh[0] + k_xc * x[1]) + k_gx * gg[0]) * inv;
    const P y1 = (((k_hy * hh[1] + k_yc * y[1]) + k_rc * rr[1]) + k_gy * gg[1]) * inv;
    store(s, m + 1, x1[0], y1[0], x1[1], y1[1], (k.oz_gx * gg[0]) * inv, (g.c * q) * inv,
          rr[1] * inv);
    if (m == n) break;

    // Index m into the sums (u_m with |u|_m), the sums of order m + 1 and the heads of
    // order m + 2.
    const double rim = rr[0], rcm = rr[1], exim = e[0], eyim = e[1];
    w[m] = oct<O>(x[0], y[0], x[1], y[1], rim, rim, rcm, rcm);
    if (m > 0) {
      ab[m] = oct<O>(rim, rim, uym, 0.0, rcm, rcm, eyim, eyim);
      cd[m] = oct<O>(exim, eyim, rcm, 0.0, exim, eyim, x[1], y[1]);
    }
    sums(m + 1, head_w[m + 1], head_p[m + 1]);
    if (m + 2 <= n) {
      head_w[m + 2] = square_head_oct<O>(m + 2, w);
      head_p[m + 2] = head_sum<O>(m + 2, ab, cd);
    }
    x = x1;
    y = y1;
  }
}

// The Taylor coefficients, to order n + 1, of a step with both contacts slipping in
// tau (dP/dtau = |u_C|). On entry s.c[.][0] hold the state, both slips nonzero; on
// exit s.c[.][0..n+1] are filled. In tau the cloth friction times dP/dtau is
// -mu_s p_C u_C, a polynomial; only the cushion's slip direction e_I needs the
// quotient recurrence e_m = (u_m - sum_{j=1}^{m} |u|_j e_{m-j}) / |u|_0.
template <class T, class Q>
[[gnu::always_inline]] inline void series_tau_in_t(const Constants& k, int n, Coefficients<T>& s) {
  Q u[kTerms], r[kTerms];
  Q ta[kTerms], tb[kTerms];  // (|u_I|, |u_I|, u_y, -), (e_Ix, e_Iy, |u_C|, -)
  Q ga[kTerms], gb[kTerms];  // (|u_C|, |u_C|, e_Iy, e_Iy), (e_Ix, e_Iy, x_C, y_C)
  // The heads of the sums of the orders ahead (index: the order).
  Q head_t[kTerms], head_g[kTerms];
  SquareSums<Q> head_r[kTerms];
  const T zero{};
  const Geometry& g = k.g;
  const Start<T, Q> a = start<T, Q>(k, s);
  const T inv_ri = a.inv_ri, half_inv_ri = a.half_inv_ri, half_inv_rc = a.half_inv_rc;
  const T ri0 = a.ri, rc0 = a.rc, exi0 = a.exi, eyi0 = a.eyi, ecx = a.ecx, ecy = a.ecy;
  const T uy0 = a.uy, xc0 = at(a.u0, 2), yc0 = at(a.u0, 3);
  const T exi_r = exi0 * inv_ri, eyi_r = eyi0 * inv_ri;
  u[0] = a.u0;
  r[0] = quad<Q>(ri0, ri0, rc0, rc0);
  ta[0] = quad<Q>(ri0, ri0, uy0, zero);
  tb[0] = quad<Q>(exi0, eyi0, rc0, zero);
  ga[0] = quad<Q>(rc0, rc0, eyi0, eyi0);
  gb[0] = quad<Q>(exi0, eyi0, xc0, yc0);
  head_t[1] = head_g[1] = Q{};
  head_r[1] = SquareSums<Q>{};

  T xi = at(a.u0, 0), yi = at(a.u0, 1), xc = xc0, yc = yc0;  // u_m
  T si = zero, sc = zero;                                      // the sums of order m
  T t0 = zero, t1 = zero, t2 = zero, g0 = zero, g1 = zero, g2 = zero, g3 = zero;
  // The sums of order o completed from their heads.
  auto sums = [&](int o, const SquareSums<Q>& hr, const Q& ht,
                  const Q& hg) [[gnu::always_inline]] {
    square_tail<T, Q>(o, hr, u, r, &si, &sc);
    const Q t = tail_sum<Q>(o, ht, ta, tb);
    const Q gh = tail_sum<Q>(o, hg, ga, gb);
    t0 = at(t, 0);
    t1 = at(t, 1);
    t2 = at(t, 2);
    g0 = at(gh, 0);
    g1 = at(gh, 1);
    g2 = at(gh, 2);
    g3 = at(gh, 3);
  };
  for (int m = 0;; ++m) {
    // The chain: |u|_m, e_I,m, u_y,m, then G = |u_C| e_I and H = e_Iy' u_C at order m.
    T rim, rcm, exim, eyim, uym, gx, gy, hx, hy, q;
    if (m == 0) {
      rim = ri0;
      rcm = rc0;
      exim = exi0;
      eyim = eyi0;
      uym = uy0;
      gx = zero + rc0 * exi0;
      gy = zero + rc0 * eyi0;
      hx = zero + eyi0 * xc0;
      hy = zero + eyi0 * yc0;
      q = zero + uy0 * rc0;
    } else {
      if constexpr (!kAhead<T>) sums(m, square_head<Q>(m, u, r), head_sum<Q>(m, ta, tb),
                                     head_sum<Q>(m, ga, gb));
      rim = si * half_inv_ri + (exi0 * xi + eyi0 * yi);
      rcm = sc * half_inv_rc + (ecx * xc + ecy * yc);
      exim = (xi - t0) * inv_ri - rim * exi_r;
      eyim = (yi - t1) * inv_ri - rim * eyi_r;
      uym = (yc - yi) * k.inv_1ps;
      gx = (g0 + rcm * exi0) + rc0 * exim;
      gy = (g1 + rcm * eyi0) + rc0 * eyim;
      hx = (g2 + eyim * xc0) + eyi0 * xc;
      hy = (g3 + eyim * yc0) + eyi0 * yc;
      q = (t2 + uy0 * rcm) + uym * rc0;
    }
    const double inv = kInverse[m];
    const T xi1 = ((k.xi_hx * hx + k.xi_xc * xc) + k.xi_gx * gx) * inv;
    const T yi1 = (((k.yi_hy * hy + k.yi_yc * yc) + k.yi_rc * rcm) + k.yi_gy * gy) * inv;
    const T xc1 = ((k.xc_hx * hx + k.xc_xc * xc) + k.xc_gx * gx) * inv;
    const T yc1 = (((k.yc_hy * hy + k.yc_yc * yc) + k.yc_rc * rcm) + k.yc_gy * gy) * inv;
    store(s, m + 1, xi1, yi1, xc1, yc1, T((k.oz_gx * gx) * inv), T((g.c * q) * inv),
          T(rcm * inv));
    if (m == n) break;

    // Beside the chain: index m into the sums, the sums of order m + 1 completed and
    // the heads of order m + 2.
    if (m > 0) {
      r[m] = quad<Q>(rim, rim, rcm, rcm);
      ta[m] = quad<Q>(rim, rim, uym, zero);
      tb[m] = quad<Q>(exim, eyim, rcm, zero);
      ga[m] = quad<Q>(rcm, rcm, eyim, eyim);
      gb[m] = quad<Q>(exim, eyim, xc, yc);
    }
    u[m + 1] = quad<Q>(xi1, yi1, xc1, yc1);
    if constexpr (kAhead<T>) sums(m + 1, head_r[m + 1], head_t[m + 1], head_g[m + 1]);
    if (kAhead<T> && m + 2 <= n) {
      head_r[m + 2] = square_head<Q>(m + 2, u, r);
      head_t[m + 2] = head_sum<Q>(m + 2, ta, tb);
      head_g[m + 2] = head_sum<Q>(m + 2, ga, gb);
    }
    xi = xi1;
    yi = yi1;
    xc = xc1;
    yc = yc1;
  }
}

// One impact (T = double): the chain in pairs (series_tau_paired, the same coefficients
// to the bit); a batch: the chain in T's.
template <class T, class Q>
[[gnu::always_inline]] inline void series_tau(const Constants& k, int n, Coefficients<T>& s) {
  if constexpr (kPaired<T>)
    series_tau_paired<OctOf<Q>, Q>(k, n, s, start<T, Q>(k, s));
  else
    series_tau_in_t<T, Q>(k, n, s);
}

// The same in sigma (dP/dsigma = |u_I| |u_C|), where both frictions times dP/dsigma
// are polynomials in the slips and their sizes: -mu_w |u_C| u_I and
// -mu_s (s |u_I| + c mu_w y_I') u_C. No quotient recurrence at all.
template <class T, class Q>
[[gnu::always_inline]] inline void series_sigma(const Constants& k, int n, Coefficients<T>& s) {
  Q u[kTerms], r[kTerms];
  Q pa[kTerms];              // (|u_C|, |u_C|, w, w), w = s |u_I| + c mu_w y_I'
  Q qa[kTerms], qb[kTerms];  // (|u_I|, u_y, -, -), (|u_C|, rho, -, -)
  Q head_q[kTerms], head_f[kTerms];
  SquareSums<Q> head_r[kTerms];
  const T zero{};
  const Geometry& g = k.g;
  const Start<T, Q> a = start<T, Q>(k, s);
  const T half_inv_ri = a.half_inv_ri, half_inv_rc = a.half_inv_rc;
  const T ri0 = a.ri, rc0 = a.rc, exi0 = a.exi, eyi0 = a.eyi, ecx = a.ecx, ecy = a.ecy;
  const T uy0 = a.uy, xi0 = at(a.u0, 0), yi0 = at(a.u0, 1), xc0 = at(a.u0, 2),
          yc0 = at(a.u0, 3);
  const T rho0 = zero + ri0 * rc0;
  const T w0 = g.s * ri0 + k.cmw * yi0;
  u[0] = a.u0;
  r[0] = quad<Q>(ri0, ri0, rc0, rc0);
  pa[0] = quad<Q>(rc0, rc0, w0, w0);
  qa[0] = quad<Q>(ri0, uy0, zero, zero);
  qb[0] = quad<Q>(rc0, rho0, zero, zero);
  head_q[1] = head_f[1] = Q{};
  head_r[1] = SquareSums<Q>{};

  T xi = xi0, yi = yi0, xc = xc0, yc = yc0;  // u_m
  T si = zero, sc = zero, t0 = zero, t1 = zero, f0 = zero, f1 = zero, f2 = zero, f3 = zero;
  auto sums = [&](int o, const SquareSums<Q>& hr, const Q& hq,
                  const Q& hf) [[gnu::always_inline]] {
    square_tail<T, Q>(o, hr, u, r, &si, &sc);
    const Q t = tail_sum<Q>(o, hq, qa, qb);
    const Q f = tail_sum<Q>(o, hf, pa, u);
    t0 = at(t, 0);
    t1 = at(t, 1);
    f0 = at(f, 0);
    f1 = at(f, 1);
    f2 = at(f, 2);
    f3 = at(f, 3);
  };
  for (int m = 0;; ++m) {
    // The chain: |u|_m, u_y,m, w_m, rho_m = (|u_I| |u_C|)_m, then (|u_C| x_I, |u_C| y_I',
    // w x_C, w y_C) and u_y rho at order m.
    T rim, rcm, uym, wm, rhom, m0, m1, m2, m3, qw;
    if (m == 0) {
      rim = ri0;
      rcm = rc0;
      uym = uy0;
      wm = w0;
      rhom = rho0;
      m0 = zero + rc0 * xi0;
      m1 = zero + rc0 * yi0;
      m2 = zero + w0 * xc0;
      m3 = zero + w0 * yc0;
      qw = zero + uy0 * rho0;
    } else {
      if constexpr (!kAhead<T>) sums(m, square_head<Q>(m, u, r), head_sum<Q>(m, qa, qb),
                                     head_sum<Q>(m, pa, u));
      rim = si * half_inv_ri + (exi0 * xi + eyi0 * yi);
      rcm = sc * half_inv_rc + (ecx * xc + ecy * yc);
      uym = (yc - yi) * k.inv_1ps;
      wm = g.s * rim + k.cmw * yi;
      rhom = (t0 + rim * rc0) + ri0 * rcm;
      qw = (t1 + uym * rho0) + uy0 * rhom;
      m0 = (f0 + rcm * xi0) + rc0 * xi;
      m1 = (f1 + rcm * yi0) + rc0 * yi;
      m2 = (f2 + wm * xc0) + w0 * xc;
      m3 = (f3 + wm * yc0) + w0 * yc;
    }
    const double inv = kInverse[m];
    const T xi1 = (k.s_xi_m2 * m2 + k.s_xi_m0 * m0) * inv;
    const T yi1 = ((k.s_yi_rho * rhom + k.s_yi_m3 * m3) + k.s_yi_m1 * m1) * inv;
    const T xc1 = (k.s_xc_m2 * m2 + k.s_xc_m0 * m0) * inv;
    const T yc1 = ((k.s_yc_rho * rhom + k.s_yc_m3 * m3) + k.s_yc_m1 * m1) * inv;
    store(s, m + 1, xi1, yi1, xc1, yc1, T((k.s_oz_m0 * m0) * inv), T((g.c * qw) * inv),
          T(rhom * inv));
    if (m == n) break;

    if (m > 0) {
      r[m] = quad<Q>(rim, rim, rcm, rcm);
      pa[m] = quad<Q>(rcm, rcm, wm, wm);
      qa[m] = quad<Q>(rim, uym, zero, zero);
      qb[m] = quad<Q>(rcm, rhom, zero, zero);
    }
    u[m + 1] = quad<Q>(xi1, yi1, xc1, yc1);
    if constexpr (kAhead<T>) sums(m + 1, head_r[m + 1], head_q[m + 1], head_f[m + 1]);
    if (kAhead<T> && m + 2 <= n) {
      head_r[m + 2] = square_head<Q>(m + 2, u, r);
      head_q[m + 2] = head_sum<Q>(m + 2, qa, qb);
      head_f[m + 2] = head_sum<Q>(m + 2, pa, u);
    }
    xi = xi1;
    yi = yi1;
    xc = xc1;
    yc = yc1;
  }
}

}  // namespace cueplan::physics::detail::taylor
