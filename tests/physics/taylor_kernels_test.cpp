// The one-impact fast kernels of the Taylor method (physics/src/impact_taylor_series.hpp)
// in every build the CPU runs (SSE2, AVX2, AVX-512VL) against a reference written as
// plain loops, each order's sums formed where they are used: every coefficient must be
// bit for bit the reference's (the kernels may reorder work, never an operation), on
// random states, orders and geometries.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "impact_taylor.hpp"

namespace {

using namespace cueplan::physics;
using namespace cueplan::physics::detail;
using namespace cueplan::physics::detail::taylor;
using Q = QuadOf<double>;

// |u_I|, |u_C| at order m >= 1 (square-root recurrence; see the kernels' header).
void radii(int m, const Q* u, const Q* r, double half_inv_ri, double half_inv_rc, double exi0,
           double eyi0, double ecx, double ecy, double* ri, double* rc) {
  Q uu{}, rr{};
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
  const double si = (uu.e[0] + uu.e[1]) - rr.e[0];
  const double sc = (uu.e[2] + uu.e[3]) - rr.e[2];
  *ri = si * half_inv_ri + (exi0 * u[m].e[0] + eyi0 * u[m].e[1]);
  *rc = sc * half_inv_rc + (ecx * u[m].e[2] + ecy * u[m].e[3]);
}

// sum_{j=1}^{m-1} a[j] b[m-j], j = 2 .. m - 2 first, then j = m - 1, then j = 1.
Q inner_sum(int m, const Q* a, const Q* b) {
  Q acc{};
  for (int j = 2; j <= m - 2; ++j) acc = acc + a[j] * b[m - j];
  if (m >= 2) acc = acc + a[m - 1] * b[1];
  if (m >= 3) acc = acc + a[1] * b[m - 1];
  return acc;
}

void reference_tau(const Constants& k, int n, Coefficients<double>& s) {
  Q u[kTerms], r[kTerms], ta[kTerms], tb[kTerms], ga[kTerms], gb[kTerms];
  double ri[kTerms], rc[kTerms], exi[kTerms], eyi[kTerms], uy[kTerms];
  const Start<double, Q> a = start<double, Q>(k, s);
  u[0] = a.u0;
  ri[0] = a.ri;
  rc[0] = a.rc;
  exi[0] = a.exi;
  eyi[0] = a.eyi;
  uy[0] = a.uy;
  const double exi_r = exi[0] * a.inv_ri, eyi_r = eyi[0] * a.inv_ri;
  r[0] = Q{{ri[0], ri[0], rc[0], rc[0]}};
  ta[0] = Q{{ri[0], ri[0], uy[0], 0.0}};
  tb[0] = Q{{exi[0], eyi[0], rc[0], 0.0}};
  ga[0] = Q{{rc[0], rc[0], eyi[0], eyi[0]}};
  gb[0] = Q{{exi[0], eyi[0], u[0].e[2], u[0].e[3]}};
  for (int m = 0; m <= n; ++m) {
    Q gh;
    double q;
    if (m == 0) {
      gh = Q{} + ga[0] * gb[0];
      q = 0.0 + uy[0] * rc[0];
    } else {
      radii(m, u, r, a.half_inv_ri, a.half_inv_rc, exi[0], eyi[0], a.ecx, a.ecy, &ri[m], &rc[m]);
      r[m] = Q{{ri[m], ri[m], rc[m], rc[m]}};
      const Q t = inner_sum(m, ta, tb);
      exi[m] = (u[m].e[0] - t.e[0]) * a.inv_ri - ri[m] * exi_r;
      eyi[m] = (u[m].e[1] - t.e[1]) * a.inv_ri - ri[m] * eyi_r;
      uy[m] = (u[m].e[3] - u[m].e[1]) * k.inv_1ps;
      ta[m] = Q{{ri[m], ri[m], uy[m], 0.0}};
      tb[m] = Q{{exi[m], eyi[m], rc[m], 0.0}};
      ga[m] = Q{{rc[m], rc[m], eyi[m], eyi[m]}};
      gb[m] = Q{{exi[m], eyi[m], u[m].e[2], u[m].e[3]}};
      gh = inner_sum(m, ga, gb);
      gh = gh + ga[m] * gb[0];
      gh = gh + ga[0] * gb[m];
      q = (t.e[2] + uy[0] * rc[m]) + uy[m] * rc[0];
    }
    const double gx = gh.e[0], gy = gh.e[1], hx = gh.e[2], hy = gh.e[3];
    const double xc = u[m].e[2], yc = u[m].e[3], inv = kInverse[m];
    const double xi1 = ((k.xi_hx * hx + k.xi_xc * xc) + k.xi_gx * gx) * inv;
    const double yi1 = (((k.yi_hy * hy + k.yi_yc * yc) + k.yi_rc * rc[m]) + k.yi_gy * gy) * inv;
    const double xc1 = ((k.xc_hx * hx + k.xc_xc * xc) + k.xc_gx * gx) * inv;
    const double yc1 = (((k.yc_hy * hy + k.yc_yc * yc) + k.yc_rc * rc[m]) + k.yc_gy * gy) * inv;
    u[m + 1] = Q{{xi1, yi1, xc1, yc1}};
    store(s, m + 1, xi1, yi1, xc1, yc1, (k.oz_gx * gx) * inv, (k.g.c * q) * inv, rc[m] * inv);
  }
}

void reference_sigma(const Constants& k, int n, Coefficients<double>& s) {
  Q u[kTerms], r[kTerms], pa[kTerms], qa[kTerms], qb[kTerms];
  double ri[kTerms], rc[kTerms], uy[kTerms], rho[kTerms];
  const Geometry& g = k.g;
  const Start<double, Q> a = start<double, Q>(k, s);
  u[0] = a.u0;
  ri[0] = a.ri;
  rc[0] = a.rc;
  uy[0] = a.uy;
  rho[0] = 0.0 + ri[0] * rc[0];
  r[0] = Q{{ri[0], ri[0], rc[0], rc[0]}};
  const double w0 = g.s * ri[0] + k.cmw * u[0].e[1];
  pa[0] = Q{{rc[0], rc[0], w0, w0}};
  qa[0] = Q{{ri[0], uy[0], 0.0, 0.0}};
  qb[0] = Q{{rc[0], rho[0], 0.0, 0.0}};
  for (int m = 0; m <= n; ++m) {
    Q f;
    double qw;
    if (m == 0) {
      f = Q{} + pa[0] * u[0];
      qw = 0.0 + uy[0] * rho[0];
    } else {
      radii(m, u, r, a.half_inv_ri, a.half_inv_rc, a.exi, a.eyi, a.ecx, a.ecy, &ri[m], &rc[m]);
      r[m] = Q{{ri[m], ri[m], rc[m], rc[m]}};
      uy[m] = (u[m].e[3] - u[m].e[1]) * k.inv_1ps;
      const double wm = g.s * ri[m] + k.cmw * u[m].e[1];
      pa[m] = Q{{rc[m], rc[m], wm, wm}};
      const Q t = inner_sum(m, qa, qb);
      rho[m] = (t.e[0] + ri[m] * rc[0]) + ri[0] * rc[m];
      qw = (t.e[1] + uy[m] * rho[0]) + uy[0] * rho[m];
      qa[m] = Q{{ri[m], uy[m], 0.0, 0.0}};
      qb[m] = Q{{rc[m], rho[m], 0.0, 0.0}};
      f = inner_sum(m, pa, u);
      f = f + pa[m] * u[0];
      f = f + pa[0] * u[m];
    }
    const double m0 = f.e[0], m1 = f.e[1], m2 = f.e[2], m3 = f.e[3], inv = kInverse[m];
    const double xi1 = (k.s_xi_m2 * m2 + k.s_xi_m0 * m0) * inv;
    const double yi1 = ((k.s_yi_rho * rho[m] + k.s_yi_m3 * m3) + k.s_yi_m1 * m1) * inv;
    const double xc1 = (k.s_xc_m2 * m2 + k.s_xc_m0 * m0) * inv;
    const double yc1 = ((k.s_yc_rho * rho[m] + k.s_yc_m3 * m3) + k.s_yc_m1 * m1) * inv;
    u[m + 1] = Q{{xi1, yi1, xc1, yc1}};
    store(s, m + 1, xi1, yi1, xc1, yc1, (k.s_oz_m0 * m0) * inv, (g.c * qw) * inv, rho[m] * inv);
  }
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(TaylorKernels, EveryBuildMatchesThePlainLoopsBitForBit) {
  std::mt19937_64 rng(16);
  std::uniform_real_distribution<double> slip(-2.0, 2.0), unit(0.0, 1.0);
  int builds_run = 0, compared = 0;
  for (int trial = 0; trial < 400; ++trial) {
    CushionParams params;
    params.cushion_height = 0.034 + 0.012 * unit(rng);
    params.mu_cushion = 0.05 + 0.4 * unit(rng);
    params.mu_table = 0.05 + 0.3 * unit(rng);
    const Constants k = Constants::from(Geometry::from(params));
    const int order = 6 + trial % (kMaxOrder - 5);
    Coefficients<double> state{};
    for (int c = 0; c < 4; ++c) state.c[c][0] = slip(rng);
    state.c[kOZ][0] = slip(rng);
    for (Kernel kernel : {Kernel::tau, Kernel::sigma}) {
      Coefficients<double> want = state;
      (kernel == Kernel::tau ? reference_tau : reference_sigma)(k, order, want);
      for (KernelIsa isa : {KernelIsa::sse2, KernelIsa::avx2, KernelIsa::avx512}) {
        Coefficients<double> got = state;
        if (!fast_series_on(isa, kernel, k, order, got)) continue;
        ++builds_run;
        for (int c = 0; c < kState; ++c)
          for (int j = 1; j <= order + 1; ++j) {
            ++compared;
            ASSERT_TRUE(same_bits(got.c[c][j], want.c[c][j]))
                << "kernel " << (kernel == Kernel::tau ? "tau" : "sigma") << " build "
                << static_cast<int>(isa) << " order " << order << " series " << c
                << " coefficient " << j << ": " << got.c[c][j] << " vs " << want.c[c][j];
          }
      }
    }
  }
  EXPECT_GE(builds_run, 800);  // SSE2 runs everywhere: 400 trials x 2 kernels at least
  EXPECT_GT(compared, 0);
}

}  // namespace
