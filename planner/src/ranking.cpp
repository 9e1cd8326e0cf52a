// McNemar's test, a stroke's effort and the coach's order.
#include "ranking.hpp"

#include <algorithm>
#include <cmath>

#include "robustness.hpp"

namespace cueplan::planner::detail {

double mcnemar_p_value(int only_a, int only_b) {
  const int n = only_a + only_b;
  const int k = std::min(only_a, only_b);
  if (n == 0 || 2 * k == n) return 1.0;
  // Sum of the binomial(n, 1/2) probabilities of 0..k, term by term in logs (2^-n
  // underflows for large n): log P(j + 1) = log P(j) + log((n - j) / (j + 1)).
  double log_term = -n * std::log(2.0);
  double max_log = log_term;
  std::vector<double> logs{log_term};
  for (int j = 0; j < k; ++j) {
    log_term += std::log(static_cast<double>(n - j) / (j + 1));
    logs.push_back(log_term);
    max_log = std::max(max_log, log_term);
  }
  double sum = 0.0;
  for (double l : logs) sum += std::exp(l - max_log);
  return std::min(1.0, 2.0 * sum * std::exp(max_log));
}

bool significantly_different(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  constexpr double kLevel = 0.05;
  const size_t n = std::min(a.size(), b.size());
  int only_a = 0, only_b = 0;
  for (size_t i = 0; i < n; ++i) {
    const bool sa = (a[i] & kSucceeded) == kSucceeded;
    const bool sb = (b[i] & kSucceeded) == kSucceeded;
    only_a += sa && !sb;
    only_b += sb && !sa;
  }
  return mcnemar_p_value(only_a, only_b) < kLevel;
}

double effort(const physics::Shot& shot, const problems::Limits& limits) {
  return shot.speed / limits.speed_max +
         std::hypot(shot.topspin_k, shot.sidespin_k) / limits.spin_max;
}

std::vector<size_t> coach_order(const std::vector<RankItem>& items) {
  std::vector<size_t> left(items.size()), order;
  for (size_t i = 0; i < items.size(); ++i) left[i] = i;
  while (!left.empty()) {
    size_t leader = left.front();
    double top_low = 0.0;
    for (size_t i : left) {
      const RankItem& c = items[i];
      const RankItem& l = items[leader];
      top_low = std::max(top_low, c.both.low);
      if (c.both.samples != l.both.samples) {
        if (c.both.samples > l.both.samples) leader = i;
        continue;
      }
      if (c.both.p > l.both.p || (c.both.p == l.both.p && c.effort < l.effort)) leader = i;
    }
    std::vector<size_t> contenders{leader};
    for (size_t i : left) {
      if (i == leader) continue;
      const RankItem& c = items[i];
      if (c.both.samples < items[leader].both.samples) continue;  // lost the race
      if (c.both.high < top_low) continue;
      if (c.both.successes == 0 && items[leader].both.successes > 0) continue;
      if (significantly_different(*c.outcomes, *items[leader].outcomes)) continue;
      contenders.push_back(i);
    }
    double best_landing = 0.0;
    for (size_t i : contenders) best_landing = std::max(best_landing, items[i].landing);
    size_t pick = leader;
    bool picked = false;
    for (size_t i : contenders) {
      const RankItem& c = items[i];
      if (c.landing < best_landing - kLandingBand) continue;
      const RankItem& p = items[pick];
      if (!picked || c.effort < p.effort || (c.effort == p.effort && c.both.p > p.both.p)) pick = i;
      picked = true;
    }
    order.push_back(pick);
    std::erase(left, pick);
  }
  return order;
}

}  // namespace cueplan::planner::detail
