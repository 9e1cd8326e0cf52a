// vec2::length (and norm, which calls it) against the length computed in long double:
// within 2 ulps over the range the simulator meets (three roundings in the sum of
// squares, halved by the root, and the root's own: at most 2 unit roundoffs relative),
// and hypot's answers where a square would underflow or overflow in double.
#include "cueplan/physics/vec2.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace cueplan::physics {
namespace {

// |x - reference| in units of the last place of reference.
double ulps(double x, long double reference) {
  const double r = static_cast<double>(reference);
  const double ulp = std::nextafter(r, std::numeric_limits<double>::infinity()) - r;
  return static_cast<double>(std::fabs(static_cast<long double>(x) - reference) / ulp);
}

long double reference_length(double x, double y) {
  const long double lx = x, ly = y;
  return std::sqrt(lx * lx + ly * ly);  // long double: no under- or overflow here
}

TEST(Vec2Length, WithinAnUlpOfTheLongDoubleLength) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0), exponent(-12.0, 12.0);
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const double x = mantissa(rng) * std::exp2(exponent(rng));
    const double y = i % 5 == 0 ? x * (1.0 + 1e-9 * mantissa(rng))
                                : mantissa(rng) * std::exp2(exponent(rng));
    worst = std::max(worst, ulps(vec2::length(x, y), reference_length(x, y)));
  }
  EXPECT_LE(worst, 2.0);
  EXPECT_GT(worst, 0.5);  // not correctly rounded: the sum's rounding shows (1.14 here)
}

TEST(Vec2Length, ExactWhereTheLengthIsExact) {
  EXPECT_EQ(vec2::length(3.0, 4.0), 5.0);
  EXPECT_EQ(vec2::length(-0.75, 0.0), 0.75);
  EXPECT_EQ(vec2::length(0.0, 0.0), 0.0);
  EXPECT_EQ(vec2::norm({0.0, -2.5}), 2.5);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> any(-100.0, 100.0);
  for (int i = 0; i < 10000; ++i) {  // sqrt(fl(x^2)) = |x| in binary floating point
    const double x = any(rng);
    EXPECT_EQ(vec2::length(x, 0.0), std::fabs(x));
    EXPECT_EQ(vec2::length(0.0, x), std::fabs(x));
  }
}

TEST(Vec2Length, TinyHugeAndNonFiniteComponentsAreHypots) {
  for (const double x : {1e-200, 3e-170, 1e-310, 1e200, 7e160, 1.7e308})
    for (const double y : {0.0, 2e-200, 1e-310, 5e199, -1e300}) {
      EXPECT_EQ(vec2::length(x, y), std::hypot(x, y)) << x << " " << y;
      EXPECT_TRUE(std::isfinite(vec2::length(x, y)) || std::isinf(std::hypot(x, y)));
    }
  EXPECT_GT(vec2::length(1e-200, 1e-200), 0.0);  // the squares underflow; the length does not
  EXPECT_EQ(vec2::length(INFINITY, NAN), INFINITY);
  EXPECT_TRUE(std::isnan(vec2::length(NAN, 1.0)));
  EXPECT_EQ(vec2::length(-INFINITY, 1.0), INFINITY);
}

}  // namespace
}  // namespace cueplan::physics
