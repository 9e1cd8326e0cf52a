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

// |u_I|, |u_C| at order m >= 1 by the square-root recurrence
//   |u|_m = (u_0 . u_m + (sum_{j=1}^{m-1} u_j . u_{m-j} - |u|_j |u|_{m-j}) / 2) / |u|_0,
// the sum taken over half its range (it is symmetric). u[j] = (x_I, y_I', x_C, y_C),
// r[j] = (|u_I|, |u_I|, |u_C|, |u_C|). Older terms first, the newest (j = 1) last.
template <class T, class Q>
[[gnu::always_inline]] inline void radii(int m, const Q* u, const Q* r,
                                         const T& half_inv_ri, const T& half_inv_rc,
                                         const T& exi0, const T& eyi0, const T& ecx,
                                         const T& ecy, T* ri, T* rc) {
  const Q zero{};
  Q uu = zero, rr = zero;
  for (int j = 2; 2 * j < m; ++j) {
    uu = uu + u[j] * u[m - j];
    rr = rr + r[j] * r[m - j];
  }
  if (m >= 3) {
    uu = uu + u[1] * u[m - 1];
    rr = rr + r[1] * r[m - 1];
  }
  uu = uu + uu;
  rr = rr + rr;
  if (m % 2 == 0) {
    uu = uu + u[m / 2] * u[m / 2];
    rr = rr + r[m / 2] * r[m / 2];
  }
  const T si = (at(uu, 0) + at(uu, 1)) - at(rr, 0);
  const T sc = (at(uu, 2) + at(uu, 3)) - at(rr, 2);
  *ri = si * half_inv_ri + (exi0 * at(u[m], 0) + eyi0 * at(u[m], 1));
  *rc = sc * half_inv_rc + (ecx * at(u[m], 2) + ecy * at(u[m], 3));
}

// sum_{j=1}^{m-1} a[j] * b[m-j], the terms with index m - 1 (j = 1 and j = m - 1)
// last: they are the newest.
template <class Q>
[[gnu::always_inline]] inline Q inner_sum(int m, const Q* a, const Q* b) {
  Q acc{};
  for (int j = 2; j <= m - 2; ++j) acc = acc + a[j] * b[m - j];
  if (m >= 2) acc = acc + a[m - 1] * b[1];
  if (m >= 3) acc = acc + a[1] * b[m - 1];
  return acc;
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

// The Taylor coefficients, to order n + 1, of a step with both contacts slipping in
// tau (dP/dtau = |u_C|). On entry s.c[.][0] hold the state, both slips nonzero; on
// exit s.c[.][0..n+1] are filled. In tau the cloth friction times dP/dtau is
// -mu_s p_C u_C, a polynomial; only the cushion's slip direction e_I needs the
// quotient recurrence e_m = (u_m - sum_{j=1}^{m} |u|_j e_{m-j}) / |u|_0.
template <class T, class Q>
[[gnu::always_inline]] inline void series_tau(const Constants& k, int n, Coefficients<T>& s) {
  Q u[kTerms], r[kTerms];
  Q ta[kTerms], tb[kTerms];  // (|u_I|, |u_I|, u_y, -), (e_Ix, e_Iy, |u_C|, -)
  Q ga[kTerms], gb[kTerms];  // (|u_C|, |u_C|, e_Iy, e_Iy), (e_Ix, e_Iy, x_C, y_C)
  T ri[kTerms], rc[kTerms], exi[kTerms], eyi[kTerms], uy[kTerms];
  const T zero{};
  const Geometry& g = k.g;
  const Start<T, Q> a = start<T, Q>(k, s);
  const T inv_ri = a.inv_ri, half_inv_ri = a.half_inv_ri, half_inv_rc = a.half_inv_rc;
  const T ecx = a.ecx, ecy = a.ecy;
  u[0] = a.u0;
  ri[0] = a.ri;
  rc[0] = a.rc;
  exi[0] = a.exi;
  eyi[0] = a.eyi;
  const T exi_r = exi[0] * inv_ri, eyi_r = eyi[0] * inv_ri;
  uy[0] = a.uy;
  r[0] = quad<Q>(ri[0], ri[0], rc[0], rc[0]);
  ta[0] = quad<Q>(ri[0], ri[0], uy[0], zero);
  tb[0] = quad<Q>(exi[0], eyi[0], rc[0], zero);
  ga[0] = quad<Q>(rc[0], rc[0], eyi[0], eyi[0]);
  gb[0] = quad<Q>(exi[0], eyi[0], at(u[0], 2), at(u[0], 3));

  for (int m = 0; m <= n; ++m) {
    Q gh;
    T q;
    if (m == 0) {
      gh = Q{} + ga[0] * gb[0];
      q = zero + uy[0] * rc[0];
    } else {
      radii<T, Q>(m, u, r, half_inv_ri, half_inv_rc, exi[0], eyi[0], ecx, ecy, &ri[m], &rc[m]);
      r[m] = quad<Q>(ri[m], ri[m], rc[m], rc[m]);
      const Q t = inner_sum<Q>(m, ta, tb);
      exi[m] = (at(u[m], 0) - at(t, 0)) * inv_ri - ri[m] * exi_r;
      eyi[m] = (at(u[m], 1) - at(t, 1)) * inv_ri - ri[m] * eyi_r;
      uy[m] = (at(u[m], 3) - at(u[m], 1)) * k.inv_1ps;
      ta[m] = quad<Q>(ri[m], ri[m], uy[m], zero);
      tb[m] = quad<Q>(exi[m], eyi[m], rc[m], zero);
      ga[m] = quad<Q>(rc[m], rc[m], eyi[m], eyi[m]);
      gb[m] = quad<Q>(exi[m], eyi[m], at(u[m], 2), at(u[m], 3));
      gh = inner_sum<Q>(m, ga, gb);
      gh = gh + ga[m] * gb[0];
      gh = gh + ga[0] * gb[m];
      q = (at(t, 2) + uy[0] * rc[m]) + uy[m] * rc[0];
    }
    const T gx = at(gh, 0), gy = at(gh, 1), hx = at(gh, 2), hy = at(gh, 3);
    const T xc = at(u[m], 2), yc = at(u[m], 3);
    const double inv = kInverse[m];
    const T xi1 = ((k.xi_hx * hx + k.xi_xc * xc) + k.xi_gx * gx) * inv;
    const T yi1 = (((k.yi_hy * hy + k.yi_yc * yc) + k.yi_rc * rc[m]) + k.yi_gy * gy) * inv;
    const T xc1 = ((k.xc_hx * hx + k.xc_xc * xc) + k.xc_gx * gx) * inv;
    const T yc1 = (((k.yc_hy * hy + k.yc_yc * yc) + k.yc_rc * rc[m]) + k.yc_gy * gy) * inv;
    u[m + 1] = quad<Q>(xi1, yi1, xc1, yc1);
    store(s, m + 1, xi1, yi1, xc1, yc1, T((k.oz_gx * gx) * inv), T((g.c * q) * inv),
          T(rc[m] * inv));
  }
}

// The same in sigma (dP/dsigma = |u_I| |u_C|), where both frictions times dP/dsigma
// are polynomials in the slips and their sizes: -mu_w |u_C| u_I and
// -mu_s (s |u_I| + c mu_w y_I') u_C. No quotient recurrence at all.
template <class T, class Q>
[[gnu::always_inline]] inline void series_sigma(const Constants& k, int n, Coefficients<T>& s) {
  Q u[kTerms], r[kTerms];
  Q pa[kTerms];              // (|u_C|, |u_C|, w, w), w = s |u_I| + c mu_w y_I'
  Q qa[kTerms], qb[kTerms];  // (|u_I|, u_y, -, -), (|u_C|, rho, -, -)
  T ri[kTerms], rc[kTerms], uy[kTerms], rho[kTerms];
  const T zero{};
  const Geometry& g = k.g;
  const Start<T, Q> a = start<T, Q>(k, s);
  const T half_inv_ri = a.half_inv_ri, half_inv_rc = a.half_inv_rc;
  const T exi0 = a.exi, eyi0 = a.eyi, ecx = a.ecx, ecy = a.ecy;
  u[0] = a.u0;
  ri[0] = a.ri;
  rc[0] = a.rc;
  uy[0] = a.uy;
  rho[0] = zero + ri[0] * rc[0];
  r[0] = quad<Q>(ri[0], ri[0], rc[0], rc[0]);
  const T w0 = g.s * ri[0] + k.cmw * at(u[0], 1);
  pa[0] = quad<Q>(rc[0], rc[0], w0, w0);
  qa[0] = quad<Q>(ri[0], uy[0], zero, zero);
  qb[0] = quad<Q>(rc[0], rho[0], zero, zero);

  for (int m = 0; m <= n; ++m) {
    Q f;  // (|u_C| x_I, |u_C| y_I', w x_C, w y_C) at order m
    T qw;       // u_y rho at order m
    if (m == 0) {
      f = Q{} + pa[0] * u[0];
      qw = zero + uy[0] * rho[0];
    } else {
      radii<T, Q>(m, u, r, half_inv_ri, half_inv_rc, exi0, eyi0, ecx, ecy, &ri[m], &rc[m]);
      r[m] = quad<Q>(ri[m], ri[m], rc[m], rc[m]);
      uy[m] = (at(u[m], 3) - at(u[m], 1)) * k.inv_1ps;
      const T wm = g.s * ri[m] + k.cmw * at(u[m], 1);
      pa[m] = quad<Q>(rc[m], rc[m], wm, wm);
      const Q t = inner_sum<Q>(m, qa, qb);
      rho[m] = (at(t, 0) + ri[m] * rc[0]) + ri[0] * rc[m];
      qw = (at(t, 1) + uy[m] * rho[0]) + uy[0] * rho[m];
      qa[m] = quad<Q>(ri[m], uy[m], zero, zero);
      qb[m] = quad<Q>(rc[m], rho[m], zero, zero);
      f = inner_sum<Q>(m, pa, u);
      f = f + pa[m] * u[0];
      f = f + pa[0] * u[m];
    }
    const T m0 = at(f, 0), m1 = at(f, 1), m2 = at(f, 2), m3 = at(f, 3);
    const double inv = kInverse[m];
    const T xi1 = (k.s_xi_m2 * m2 + k.s_xi_m0 * m0) * inv;
    const T yi1 = ((k.s_yi_rho * rho[m] + k.s_yi_m3 * m3) + k.s_yi_m1 * m1) * inv;
    const T xc1 = (k.s_xc_m2 * m2 + k.s_xc_m0 * m0) * inv;
    const T yc1 = ((k.s_yc_rho * rho[m] + k.s_yc_m3 * m3) + k.s_yc_m1 * m1) * inv;
    u[m + 1] = quad<Q>(xi1, yi1, xc1, yc1);
    store(s, m + 1, xi1, yi1, xc1, yc1, T((k.s_oz_m0 * m0) * inv), T((g.c * qw) * inv),
          T(rho[m] * inv));
  }
}

}  // namespace cueplan::physics::detail::taylor
