// How a coach ranks strokes that all land: by how often they succeed under the
// execution noise, and, among strokes whose success rates the samples cannot tell
// apart, the simplest - slower, with less spin.
#pragma once

#include <cstdint>
#include <vector>

#include "cueplan/planner/planner.hpp"

namespace cueplan::planner::detail {

// Two-sided exact McNemar test: the chance, if two strokes were equally good, of a
// split of the discordant draws at least as uneven as `only_a` (draws where only the
// first succeeded) against `only_b` (only the second): 2 P(X <= min) for X binomial
// with n = only_a + only_b and p = 1/2, at most 1.
double mcnemar_p_value(int only_a, int only_b);

// True when two strokes' outcome bits (kSucceeded, draw by draw on the same draws,
// compared over the draws both have) differ at the 5 % level by McNemar's test.
bool significantly_different(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);

// What a stroke asks of the player: its speed as a fraction of the problem's speed
// limit plus its tip offset from centre as a fraction of the spin limit's, each in
// [0, 1]. Lower is simpler.
double effort(const physics::Shot& shot, const problems::Limits& limits);

// A stroke to be ranked: its outcomes on the common draws, their estimate and its effort;
// with position play, the value of the position its planned stroke leaves (the position
// field at its nominal landing, 0..1; 0 for every stroke without a next pot).
struct RankItem {
  const std::vector<uint8_t>* outcomes = nullptr;
  Estimate both;
  double effort = 0.0;
  double landing = 0.0;
};

// Contenders whose planned landings are worth within this of the best contender's are
// played for alike (position.hpp's kZoneWidth: the zone's own width).
inline constexpr double kLandingBand = 0.10;

// The coach's order, as indices into `items`, best first. Repeatedly: the leader is,
// of the strokes sampled the most, the one with the highest success rate (ties: less
// effort, then the lower index) - a stroke with fewer samples was dropped from the race
// of estimates as measurably worse than another; the contenders are the leader and
// every stroke sampled as often that McNemar's test cannot tell from it whose interval
// reaches the highest lower bound of those left and which succeeded at
// least once if the leader did (a stroke no sample landed is no way to play the shot
// while another lands sometimes); of the contenders whose planned landing is worth
// within kLandingBand of the best contender's (a coach plays for the zone when the
// odds cannot tell the ways apart: the stroke as planned must leave the next ball),
// the simplest (least effort; ties: higher rate, then lower index) comes next. So the first
// stroke's interval is never below another's, and a harder stroke comes first only
// when it succeeds measurably more often.
std::vector<size_t> coach_order(const std::vector<RankItem>& items);

}  // namespace cueplan::planner::detail
