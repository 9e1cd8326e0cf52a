// The event solver's root finder (physics/src/polynomial_roots.hpp) against roots known by
// construction: polynomials built as products of linear factors (t - r_i) with a
// quadratic factor that has no real root, so the real roots are the chosen r_i. Each
// root found must lie within the rounding of the polynomial's value there (its
// condition: a few ulps of the coefficients' sizes over the slope), none may be
// missed or invented, and a root found must be a sign change of the evaluated
// polynomial between neighbouring doubles (or an exact zero): what bisection to
// rounding returns.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "polynomial_roots.hpp"

namespace {

using cueplan::physics::detail::evaluate;
using cueplan::physics::detail::kMaxDegree;
using cueplan::physics::detail::roots_in;

// Coefficients (ascending) of scale * prod (t - r_i) * (t^2 + p t + q) when with_pair.
std::vector<double> from_roots(const std::vector<double>& roots, double scale, bool with_pair,
                               double p, double q) {
  std::vector<long double> c{static_cast<long double>(scale)};
  const auto times = [&c](long double k0, long double k1, long double k2) {
    std::vector<long double> out(c.size() + 2, 0.0L);
    for (size_t i = 0; i < c.size(); ++i) {
      out[i] += c[i] * k0;
      out[i + 1] += c[i] * k1;
      out[i + 2] += c[i] * k2;
    }
    while (out.size() > 1 && out.back() == 0.0L) out.pop_back();
    c = out;
  };
  for (double r : roots) times(-static_cast<long double>(r), 1.0L, 0.0L);
  if (with_pair) times(q, p, 1.0L);
  return {c.begin(), c.end()};
}

// How far from a true root r a computed root may lie: the evaluation's rounding (about
// 8 ulps of sum |c_i| |t|^i) over |p'(r)|, and never less than a few ulps of r.
double allowance(const std::vector<double>& c, double r) {
  double size = 0.0, slope = 0.0, power = 1.0;
  for (size_t i = 0; i < c.size(); ++i) {
    size += std::abs(c[i]) * power;
    if (i + 1 < c.size()) slope += static_cast<double>(i + 1) * c[i + 1] * power;
    power *= std::abs(r);
  }
  const double rounding = 8.0 * 0x1p-52 * size / std::max(std::abs(slope), 1e-300);
  return std::max(rounding, 4.0 * 0x1p-52 * std::max(std::abs(r), 1e-300));
}

// A sign change between neighbouring doubles at x, or an exact zero.
bool is_rounded_root(const std::vector<double>& c, double x) {
  const int degree = static_cast<int>(c.size()) - 1;
  const double f = evaluate(c.data(), degree, x);
  if (f == 0.0) return true;
  const double below = evaluate(c.data(), degree, std::nextafter(x, -INFINITY));
  const double above = evaluate(c.data(), degree, std::nextafter(x, INFINITY));
  return (below < 0.0) != (f < 0.0) || (above < 0.0) != (f < 0.0) || below == 0.0 ||
         above == 0.0;
}

TEST(PolynomialRoots, FindsEveryWellSeparatedRootToRounding) {
  std::mt19937_64 rng(20261207);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    // 1-4 real roots in (0, 5) s, at least 1e-6 apart (a touch of two roots has no sign
    // change and is not asked for), sometimes with a complex pair; scales from 1e-4 to 1e3.
    const bool pair = unit(rng) < 0.3;
    const int n = 1 + static_cast<int>(unit(rng) * (pair ? 2 : 4));
    std::vector<double> roots;
    for (int i = 0; i < n; ++i) roots.push_back(5.0 * unit(rng));
    std::sort(roots.begin(), roots.end());
    bool separated = true;
    for (int i = 1; i < n; ++i) separated = separated && roots[i] - roots[i - 1] > 1e-6;
    if (!separated) continue;
    const double scale = std::pow(10.0, -4.0 + 7.0 * unit(rng)) * (unit(rng) < 0.5 ? -1 : 1);
    const double p = 4.0 * unit(rng) - 2.0;
    const double q = 0.25 * p * p + 0.1 + unit(rng);  // p^2 < 4 q: no real root
    const std::vector<double> c = from_roots(roots, scale, pair, p, q);
    const int degree = static_cast<int>(c.size()) - 1;
    ASSERT_LE(degree, kMaxDegree);
    double found[kMaxDegree];
    const int m = roots_in(c.data(), degree, 0.0, 5.0, found);
    ASSERT_EQ(m, n) << "trial " << trial;
    for (int i = 0; i < m; ++i) {
      const double root = roots[static_cast<size_t>(i)];
      EXPECT_NEAR(found[i], root, allowance(c, root)) << "trial " << trial << " root " << i;
      EXPECT_TRUE(is_rounded_root(c, found[i])) << "trial " << trial << " root " << i;
      if (i > 0) {
        EXPECT_LT(found[i - 1], found[i]);
      }
    }
    ++checked;
  }
  EXPECT_GT(checked, 15000);
}

// The event solver's own cases: a ball's distance to a cushion line, c0 + c1 t + c2 t^2
// (c0 < 0 on the table, moving in at c1, the cloth's friction in c2), up to the piece's
// end; the contact is the root of the quadratic formula (computed in long double).
TEST(PolynomialRoots, CushionContactsMatchTheQuadraticFormula) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int hits = 0;
  for (int trial = 0; trial < 50000; ++trial) {
    const double distance = 3.0 * unit(rng) * (unit(rng) < 0.05 ? 1e-9 : 1.0);
    const double speed = 5.0 * unit(rng) * unit(rng) + 1e-3;
    const double decel = unit(rng) < 0.5 ? 0.1 : 2.0;
    const double c[3] = {-distance, speed * unit(rng), -0.5 * decel * (2.0 * unit(rng) - 1.0)};
    const double horizon = 0.1 + 10.0 * unit(rng);
    double found[2];
    const int m = roots_in(c, 2, 0.0, horizon, found);
    // The first positive root of c2 t^2 + c1 t + c0, stably.
    const long double a = c[2], b = c[1], k = c[0];
    long double first = INFINITY;
    if (a == 0.0L) {
      if (b != 0.0L) first = -k / b;
    } else {
      const long double disc = b * b - 4.0L * a * k;
      if (disc >= 0.0L) {
        const long double s =
            b >= 0.0L ? -0.5L * (b + std::sqrt(disc)) : -0.5L * (b - std::sqrt(disc));
        const long double r1 = s / a, r2 = k / s;
        for (long double r : {r1, r2})
          if (r >= 0.0L && r < first) first = r;
      }
    }
    const bool inside = first <= static_cast<long double>(horizon);
    // A root within rounding of the horizon may be found or not.
    if (std::abs(static_cast<double>(first) - horizon) < 1e-12) continue;
    ASSERT_EQ(m > 0, inside) << "trial " << trial;
    if (m == 0) continue;
    const std::vector<double> cv(c, c + 3);
    EXPECT_NEAR(found[0], static_cast<double>(first), allowance(cv, static_cast<double>(first)))
        << "trial " << trial;
    EXPECT_TRUE(is_rounded_root(cv, found[0])) << "trial " << trial;
    ++hits;
  }
  EXPECT_GT(hits, 10000);
}

// Two close roots are both found while the evaluated polynomial still changes sign
// between them (its dip, gap^2 / 4, above the rounding of about 1e-16); a double root (a
// graze, no sign change) is not a root.
TEST(PolynomialRoots, CloseRootsAndGrazes) {
  for (double gap : {1e-3, 1e-5, 1e-6}) {
    const std::vector<double> c = from_roots({1.0, 1.0 + gap}, 1.0, false, 0.0, 0.0);
    double found[kMaxDegree];
    ASSERT_EQ(roots_in(c.data(), 2, 0.0, 2.0, found), 2) << gap;
    EXPECT_NEAR(found[0], 1.0, allowance(c, 1.0)) << gap;
    EXPECT_NEAR(found[1], 1.0 + gap, allowance(c, 1.0 + gap)) << gap;
  }
  const double graze[3] = {1.0, -2.0, 1.0};  // (t - 1)^2
  double found[2];
  const int m = roots_in(graze, 2, 0.0, 2.0, found);
  for (int i = 0; i < m; ++i) EXPECT_NEAR(found[i], 1.0, 1e-7);  // at most the touch itself
  const double none[3] = {1.0, 0.0, 1.0};  // 1 + t^2
  EXPECT_EQ(roots_in(none, 2, -5.0, 5.0, found), 0);
}

}  // namespace
