// The statistics the planner ranks strokes by: Wilson intervals against published
// values, McNemar's exact test against a binomial sum computed another way, and the
// coach's order on outcomes built by hand.
#include "ranking.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "cueplan/planner/planner.hpp"
#include "robustness.hpp"

namespace cueplan::planner {
namespace {

// Newcombe (1998), "Two-sided confidence intervals for the single proportion",
// Statistics in Medicine 17, Table I, method 3 (score interval without continuity
// correction), to the four decimals printed there.
TEST(WilsonEstimateTest, MatchesNewcombesPublishedIntervals) {
  struct Case {
    int successes, samples;
    double low, high;
  };
  const Case cases[] = {{81, 263, 0.2553, 0.3662},
                        {15, 148, 0.0624, 0.1605},
                        {0, 20, 0.0000, 0.1611},
                        {1, 29, 0.0061, 0.1718}};
  for (const Case& c : cases) {
    SCOPED_TRACE(testing::Message() << c.successes << "/" << c.samples);
    const Estimate e = wilson_estimate(c.successes, c.samples);
    EXPECT_DOUBLE_EQ(e.p, static_cast<double>(c.successes) / c.samples);
    EXPECT_NEAR(e.low, c.low, 5e-5);
    EXPECT_NEAR(e.high, c.high, 5e-5);
    EXPECT_EQ(e.samples, c.samples);
    EXPECT_EQ(e.successes, c.successes);
  }
}

TEST(WilsonEstimateTest, StaysInsideTheUnitIntervalAndIsEmptyOnlyWithoutSamples) {
  const Estimate none = wilson_estimate(0, 0);
  EXPECT_EQ(none.p, 0.0);
  EXPECT_EQ(none.low, 0.0);
  EXPECT_EQ(none.high, 1.0);
  EXPECT_EQ(none.samples, 0);
  for (int n : {1, 5, 200, 100000})
    for (int k : {0, 1, n / 2, n - 1, n}) {
      if (k < 0 || k > n) continue;
      const Estimate e = wilson_estimate(k, n);
      SCOPED_TRACE(testing::Message() << k << "/" << n);
      EXPECT_GE(e.low, 0.0);
      EXPECT_LE(e.high, 1.0);
      EXPECT_LE(e.low, e.p);
      EXPECT_GE(e.high, e.p);
      EXPECT_LT(e.low, e.high);
    }
  // All successes: the upper bound is 1, the lower bound (z^2 / n below 1 when
  // expanded) is n / (n + z^2).
  const double z2 = 1.959963984540054 * 1.959963984540054;
  EXPECT_NEAR(wilson_estimate(29, 29).low, 29.0 / (29.0 + z2), 1e-12);
  EXPECT_EQ(wilson_estimate(29, 29).high, 1.0);
}

// The two-sided exact McNemar p-value from Pascal's triangle, exact in doubles up to
// n = 50 (C(50, 25) < 2^53).
double pascal_mcnemar(int a, int b) {
  const int n = a + b;
  std::vector<double> row{1.0};
  for (int i = 0; i < n; ++i) {
    std::vector<double> next(row.size() + 1, 0.0);
    for (size_t j = 0; j < row.size(); ++j) {
      next[j] += row[j];
      next[j + 1] += row[j];
    }
    row = std::move(next);
  }
  double tail = 0.0;
  for (int j = 0; j <= std::min(a, b); ++j) tail += row[static_cast<size_t>(j)];
  return std::min(1.0, 2.0 * tail / std::ldexp(1.0, n));
}

TEST(McNemarTest, EqualsTheBinomialTailFromPascalsTriangle) {
  for (int a = 0; a <= 25; ++a)
    for (int b = 0; b <= 25; ++b) {
      SCOPED_TRACE(testing::Message() << a << " against " << b);
      const double expected = a + b == 0 ? 1.0 : pascal_mcnemar(a, b);
      EXPECT_NEAR(detail::mcnemar_p_value(a, b), expected, 1e-12 * std::max(expected, 1e-300));
    }
  // Hand values: 0 of 5 discordant pairs one way is 2 / 32; 1 of 10 is 2 * 11 / 1024.
  EXPECT_DOUBLE_EQ(detail::mcnemar_p_value(0, 5), 0.0625);
  EXPECT_DOUBLE_EQ(detail::mcnemar_p_value(9, 1), 22.0 / 1024.0);
}

TEST(McNemarTest, LargeCountsAgreeWithTheNormalApproximation) {
  // n = 3000 discordant pairs (2^-n underflows a double): the continuity-corrected
  // normal tail is within a few per cent of the exact one here.
  const int a = 1450, b = 1550;
  const double z = (std::abs(a - b) - 1.0) / std::sqrt(a + b);
  const double normal = std::erfc(z / std::sqrt(2.0));
  const double exact = detail::mcnemar_p_value(a, b);
  EXPECT_GT(exact, 0.0);
  EXPECT_NEAR(exact, normal, 0.03 * normal);
}

std::vector<uint8_t> outcomes(int successes, int samples, int offset = 0) {
  std::vector<uint8_t> o(static_cast<size_t>(samples), 0);
  for (int i = 0; i < successes; ++i)
    o[static_cast<size_t>((i + offset) % samples)] = detail::kSucceeded;
  return o;
}

detail::RankItem item(const std::vector<uint8_t>& o, double effort) {
  int k = 0;
  for (uint8_t v : o) k += v == detail::kSucceeded;
  return {&o, wilson_estimate(k, static_cast<int>(o.size())), effort};
}

TEST(CoachOrderTest, EqualOutcomesPutTheSimplerStrokeFirst) {
  const std::vector<uint8_t> same = outcomes(20, 200);
  const std::vector<detail::RankItem> items{item(same, 1.4), item(same, 0.6), item(same, 0.9)};
  EXPECT_EQ(detail::coach_order(items), (std::vector<size_t>{1, 2, 0}));
}

TEST(CoachOrderTest, AMeasurablyBetterStrokeComesFirstHoweverHardItIs) {
  // 40 of 200 against 10 of 200 on the same draws (the 10 among the 40): McNemar
  // sees 30 discordant pairs all one way.
  const std::vector<uint8_t> good = outcomes(40, 200), poor = outcomes(10, 200);
  ASSERT_TRUE(detail::significantly_different(good, poor));
  const std::vector<detail::RankItem> items{item(poor, 0.2), item(good, 1.9)};
  EXPECT_EQ(detail::coach_order(items), (std::vector<size_t>{1, 0}));
}

TEST(CoachOrderTest, AStrokeNoSampleLandedIsNotPreferredToOneThatLands) {
  // 3 of 200 against 0 of 200: McNemar cannot tell them apart (p = 0.25), but the
  // simpler one never landed.
  const std::vector<uint8_t> some = outcomes(3, 200), none = outcomes(0, 200);
  ASSERT_FALSE(detail::significantly_different(some, none));
  const std::vector<detail::RankItem> items{item(none, 0.1), item(some, 1.0)};
  EXPECT_EQ(detail::coach_order(items).front(), 1u);
}

TEST(CoachOrderTest, AStrokeWhoseIntervalLiesBelowAnothersIsNotFirst) {
  // 16 of 50 and 30 of 50 on disjoint draws: 46 discordant pairs split 16 : 30, which
  // McNemar's test does not call significant (p = 0.054), yet the Wilson intervals
  // do not overlap ([0.208, 0.458] below [0.462, 0.724]).
  const std::vector<uint8_t> fewer = outcomes(16, 50), more = outcomes(30, 50, 16);
  ASSERT_FALSE(detail::significantly_different(fewer, more));
  const detail::RankItem simple = item(fewer, 0.1), hard = item(more, 1.5);
  ASSERT_LT(simple.both.high, hard.both.low);
  EXPECT_EQ(detail::coach_order({simple, hard}).front(), 1u);
}

TEST(CoachOrderTest, AStrokeDroppedFromTheRaceIsNotPreferredToOneSampledFully) {
  // The simpler stroke was dropped after 100 draws as measurably worse than a stroke
  // that later fell back; on those 100 draws the full stroke (19 of 200, 9 of its first
  // 100) cannot be told from it (5 of 100), and its interval reaches the other's.
  const std::vector<uint8_t> dropped = outcomes(5, 100);
  std::vector<uint8_t> full = outcomes(9, 200);
  for (size_t i = 100; i < 110; ++i) full[i] = detail::kSucceeded;
  ASSERT_FALSE(detail::significantly_different(dropped, full));
  const detail::RankItem simple = item(dropped, 0.2), hard = item(full, 0.5);
  ASSERT_GE(simple.both.high, hard.both.low);
  EXPECT_EQ(detail::coach_order({simple, hard}), (std::vector<size_t>{1, 0}));
}

TEST(CoachOrderTest, AmongTiedStrokesTheOneThatLeavesTheZoneComesFirst) {
  // Position play: three strokes the samples cannot tell apart; the simplest leaves a
  // position worth 0.25 as planned, the others 0.9 and 0.85. The coach plays for the
  // zone: the simpler of the two that leave it.
  const std::vector<uint8_t> a = outcomes(30, 200), b = outcomes(28, 200, 3), c = outcomes(31, 200, 7);
  ASSERT_FALSE(detail::significantly_different(a, b));
  ASSERT_FALSE(detail::significantly_different(a, c));
  detail::RankItem simple = item(a, 0.4), zone = item(b, 1.2), zone_harder = item(c, 1.6);
  simple.landing = 0.25;
  zone.landing = 0.85;
  zone_harder.landing = 0.9;
  EXPECT_EQ(detail::coach_order({simple, zone, zone_harder}), (std::vector<size_t>{1, 2, 0}));
  // Landings within kLandingBand of each other are alike: the simplest again.
  simple.landing = 0.82;
  EXPECT_EQ(detail::coach_order({simple, zone, zone_harder}).front(), 0u);
}

TEST(CoachOrderTest, ALandingNeverLiftsAMeasurablyWorseStroke) {
  const std::vector<uint8_t> good = outcomes(40, 200), poor = outcomes(10, 200);
  ASSERT_TRUE(detail::significantly_different(good, poor));
  detail::RankItem g = item(good, 1.0), p = item(poor, 0.2);
  g.landing = 0.1;
  p.landing = 1.0;
  EXPECT_EQ(detail::coach_order({p, g}), (std::vector<size_t>{1, 0}));
}

TEST(CoachOrderTest, TheFirstStrokesIntervalIsNeverBelowAnother) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 300; ++trial) {
    SCOPED_TRACE(trial);
    const int n = 50 + static_cast<int>(rng() % 200);
    std::vector<std::vector<uint8_t>> sets;
    const int count = 2 + static_cast<int>(rng() % 6);
    for (int i = 0; i < count; ++i)
      sets.push_back(
          outcomes(static_cast<int>(rng() % (n / 3 + 1)), n, static_cast<int>(rng() % n)));
    std::vector<detail::RankItem> items;
    for (const auto& s : sets) {
      items.push_back(item(s, static_cast<double>(rng() % 1000) / 500.0));
      if (trial % 2 == 1) items.back().landing = static_cast<double>(rng() % 1000) / 1000.0;
    }
    const std::vector<size_t> order = detail::coach_order(items);
    ASSERT_EQ(order.size(), items.size());
    const detail::RankItem& first = items[order.front()];
    for (const detail::RankItem& other : items) EXPECT_GE(first.both.high, other.both.low);
    // Every stroke appears once.
    std::vector<size_t> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    for (size_t i = 0; i < sorted.size(); ++i) EXPECT_EQ(sorted[i], i);
  }
}

}  // namespace
}  // namespace cueplan::planner
