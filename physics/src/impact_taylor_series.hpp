// The Taylor method's series kernel for its commonest step (private header): both
// contacts slipping, in the variable tau with dP/dtau = |u_C| (impact_taylor.cpp).
//
// The kernel is a template over the number type: `double` for one impact, or a GCC
// vector of doubles for several independent impacts side by side in SIMD lanes
// (impact_taylor_lanes.cpp). Every operation is an IEEE add, subtract, multiply,
// divide or square root applied lane by lane, in the same order for every type, and
// the files that instantiate it are built with -ffp-contract=off (no fused
// multiply-adds): a lane computes bit for bit what the scalar kernel computes.
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

// 1 / (k + 1): a coefficient of order k + 1 from a rate of order k.
constexpr auto kInverse = [] {
  std::array<double, kTerms> inv{};
  for (int i = 0; i < kTerms; ++i) inv[i] = 1.0 / (i + 1);
  return inv;
}();

template <class V>
struct Coefficients {
  V c[kState][kTerms];
};

// Per-impact constants of the kernels: the geometry and the linear maps of eqs. (14)
// in slip variables (impact_model.hpp).
struct Constants {
  Geometry g;
  double inv_1ps = 0.0;  // 1 / (1 + s): u_y = (y_C - y_I') / (1 + s)
  // Rates per unit tau of x_I, y_I', x_C, y_C, o_z as combinations of
  //   G = |u_C| e_I, H = e_Iy' u_C, u_C and |u_C| (both contacts slipping).
  double xi_gx = 0.0, xi_hx = 0.0, xi_xc = 0.0;
  double yi_gy = 0.0, yi_hy = 0.0, yi_yc = 0.0, yi_rc = 0.0;
  double xc_gx = 0.0, xc_hx = 0.0, xc_xc = 0.0;
  double yc_gy = 0.0, yc_hy = 0.0, yc_yc = 0.0, yc_rc = 0.0;
  double oz_gx = 0.0;

  static Constants from(const Geometry& g) {
    Constants k;
    k.g = g;
    k.inv_1ps = 1.0 / (1.0 + g.s);
    // Friction times dP/dtau: F_I = -mu_w G, F_C = -mu_s (s u_C + c mu_w H), and
    // d(slip)/dtau = |u_C| (0, s c, 0, -c) + K F.
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
    return k;
  }
};

template <class V>
[[gnu::always_inline]] inline V lane_sqrt(V x) {
  if constexpr (std::is_same_v<V, double>) {
    return std::sqrt(x);
  } else {
    V r = x;
    for (int i = 0; i < static_cast<int>(sizeof(V) / sizeof(double)); ++i) r[i] = std::sqrt(x[i]);
    return r;
  }
}

// The Taylor coefficients, to order n + 1, of a step with both contacts slipping in
// tau (dP/dtau = |u_C|). On entry s.c[0..kState)[0] hold the state, with both slips
// nonzero; on exit s.c[0..kState)[0..n+1] are filled.
//
// Standard recurrences of Taylor-mode series: Cauchy products, the square root
// |u|_k = (u_0 . u_k + (sum_{j=1}^{k-1} u_j . u_{k-j} - |u|_j |u|_{k-j}) / 2) / |u|_0
// and the quotient e_k = (u_k - sum_{j=1}^{k} |u|_j e_{k-j}) / |u|_0. In tau the cloth
// friction times dP/dtau is -mu_s p_C u_C, a polynomial, and only the cushion's slip
// direction e_I needs a quotient. Each sum adds its terms of lower order first and the
// newest last, so that the chain from one order to the next stays short.
template <class V>
[[gnu::always_inline]] inline void slip_slip_tau(const Constants& k, int n, Coefficients<V>& s) {
  V* xi = s.c[kXI];
  V* yi = s.c[kYI];
  V* xc = s.c[kXC];
  V* yc = s.c[kYC];
  V* oz = s.c[kOZ];
  V* w = s.c[kW];
  V* p = s.c[kP];
  V ri[kTerms], rc[kTerms], exi[kTerms], eyi[kTerms], uy[kTerms];
  const Geometry& g = k.g;
  const V zero{};

  ri[0] = lane_sqrt(xi[0] * xi[0] + yi[0] * yi[0]);
  rc[0] = lane_sqrt(xc[0] * xc[0] + yc[0] * yc[0]);
  const V inv_ri = 1.0 / ri[0];
  const V inv_rc = 1.0 / rc[0];
  const V half_inv_ri = 0.5 * inv_ri, half_inv_rc = 0.5 * inv_rc;
  exi[0] = xi[0] * inv_ri;
  eyi[0] = yi[0] * inv_ri;
  const V ecx = xc[0] * inv_rc, ecy = yc[0] * inv_rc;
  const V exi_r = exi[0] * inv_ri, eyi_r = eyi[0] * inv_ri;

  for (int m = 0; m <= n; ++m) {
    if (m > 0) {
      // |u_I|_m and |u_C|_m
      V si = zero, sc = zero;
      for (int j = 1; 2 * j < m; ++j) {
        si = si + ((xi[j] * xi[m - j] + yi[j] * yi[m - j]) - ri[j] * ri[m - j]);
        sc = sc + ((xc[j] * xc[m - j] + yc[j] * yc[m - j]) - rc[j] * rc[m - j]);
      }
      si = si + si;
      sc = sc + sc;
      if (m % 2 == 0) {
        const int h = m / 2;
        si = si + ((xi[h] * xi[h] + yi[h] * yi[h]) - ri[h] * ri[h]);
        sc = sc + ((xc[h] * xc[h] + yc[h] * yc[h]) - rc[h] * rc[h]);
      }
      ri[m] = si * half_inv_ri + (exi[0] * xi[m] + eyi[0] * yi[m]);
      rc[m] = sc * half_inv_rc + (ecx * xc[m] + ecy * yc[m]);
      // e_I at order m
      V tx = zero, ty = zero;
      for (int j = m - 1; j >= 1; --j) {
        tx = tx + ri[j] * exi[m - j];
        ty = ty + ri[j] * eyi[m - j];
      }
      exi[m] = (xi[m] - tx) * inv_ri - ri[m] * exi_r;
      eyi[m] = (yi[m] - ty) * inv_ri - ri[m] * eyi_r;
    }
    uy[m] = (yc[m] - yi[m]) * k.inv_1ps;

    // G = |u_C| e_I, H = e_Iy' u_C, Q = u_y |u_C| at order m, newest terms last.
    V gx = zero, gy = zero, hx = zero, hy = zero, q = zero;
    for (int j = 1; j < m; ++j) {
      gx = gx + rc[j] * exi[m - j];
      gy = gy + rc[j] * eyi[m - j];
      hx = hx + eyi[j] * xc[m - j];
      hy = hy + eyi[j] * yc[m - j];
      q = q + uy[j] * rc[m - j];
    }
    if (m > 0) {
      gx = gx + rc[m] * exi[0];
      gy = gy + rc[m] * eyi[0];
      hx = hx + eyi[0] * xc[m];
      hy = hy + eyi[0] * yc[m];
      q = q + uy[0] * rc[m];
    }
    gx = gx + rc[0] * exi[m];
    gy = gy + rc[0] * eyi[m];
    hx = hx + eyi[m] * xc[0];
    hy = hy + eyi[m] * yc[0];
    q = q + uy[m] * rc[0];

    const double inv = kInverse[m];
    xi[m + 1] = ((k.xi_hx * hx + k.xi_xc * xc[m]) + k.xi_gx * gx) * inv;
    yi[m + 1] = (((k.yi_hy * hy + k.yi_yc * yc[m]) + k.yi_rc * rc[m]) + k.yi_gy * gy) * inv;
    xc[m + 1] = ((k.xc_hx * hx + k.xc_xc * xc[m]) + k.xc_gx * gx) * inv;
    yc[m + 1] = (((k.yc_hy * hy + k.yc_yc * yc[m]) + k.yc_rc * rc[m]) + k.yc_gy * gy) * inv;
    oz[m + 1] = (k.oz_gx * gx) * inv;
    w[m + 1] = (g.c * q) * inv;
    p[m + 1] = rc[m] * inv;
  }
}

}  // namespace cueplan::physics::detail::taylor
