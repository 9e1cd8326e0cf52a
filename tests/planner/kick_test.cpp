// Kicks, banks and escapes: snookered layouts with a known one- or two-cushion escape
// are escaped (the reported stroke, simulated again here, strikes the ball on first and
// leaves the cue ball on the table); banks and doubles that a known stroke makes are
// potted; a ball ringed by others is unreachable with every family's reason; the shipped
// examples hold what their headers say.
//
// The layouts are generated here, and each one's escape or bank is shown to exist by
// this file's own search (mirror lines and a scan of aims, or a random stroke that
// makes it), independent of the planner's. Everything simulates with the exact impact
// method, so the suite needs no table cache.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cueplan/planner/planner.hpp"
#include "cueplan/problems/ball_names.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::planner {
namespace {

using physics::Vec2;
constexpr double kDeg = 180.0 / std::numbers::pi;

std::optional<problems::Problem> parsed(const std::string& yaml) {
  const problems::LoadResult r = problems::parse_problem(yaml, "<test>");
  if (!r.ok()) return std::nullopt;
  return *r.problem;
}

problems::Problem shipped(const std::string& file) {
  const problems::LoadResult r =
      problems::load_problem(std::string(CUEPLAN_PROBLEMS_DIR) + "/" + file);
  EXPECT_TRUE(r.ok()) << r.error;
  return r.ok() ? *r.problem : problems::Problem{};
}

PlannerOptions options() {
  PlannerOptions o;
  o.simulation.record_path = false;
  o.robustness_samples = 100;
  o.max_time_s = 20.0;
  return o;
}

// A legal hit as the rules judge it, from an independent simulation of the stroke.
bool legal_hit(const problems::Problem& p, const physics::Shot& shot) {
  const physics::ShotResult r = physics::simulate(p.scene, p.cue_ball, shot);
  if (r.status != physics::ShotStatus::rest || r.first_contact <= 0) return false;
  return problems::contact_allowed(*p.first_contact,
                                   r.balls[static_cast<size_t>(r.first_contact)].name, p.scene.balls);
}

// The aim (deg) of the mirror line from `from` off `cushions` to `to`, the lines inset
// by the contact offset.
double mirror_aim(const physics::Scene& s, Vec2 from, const std::vector<int>& cushions, Vec2 to) {
  const double k = s.contact_offset();
  for (size_t j = cushions.size(); j-- > 0;) {
    switch (cushions[j]) {
      case 0: to.y = 2 * k - to.y; break;
      case 1: to.x = 2 * (s.length - k) - to.x; break;
      case 2: to.y = 2 * (s.width - k) - to.y; break;
      default: to.x = 2 * k - to.x; break;
    }
  }
  return std::atan2(to.y - from.y, to.x - from.x) * kDeg;
}

// A snookered layout: the cue ball, a red, and a wall of three colours across the line
// between them, so that no straight stroke reaches the red; the escape exists (found by
// scanning aims around every one- and two-cushion mirror line at one speed).
struct Snooker {
  problems::Problem problem;
  physics::Shot escape;  // a known legal hit
};

std::optional<Snooker> snooker_layout(std::mt19937_64& rng) {
  const double length = 3.569, width = 1.778, r = 0.02625;
  std::uniform_real_distribution<double> ux(0.3, length - 0.3), uy(0.25, width - 0.25),
      uf(0.35, 0.6), ud(0.9, 2.2), ua(-std::numbers::pi, std::numbers::pi);
  const Vec2 cue{ux(rng), uy(rng)};
  const double d = ud(rng), a = ua(rng);
  const Vec2 red{cue.x + d * std::cos(a), cue.y + d * std::sin(a)};
  if (red.x < 0.15 || red.x > length - 0.15 || red.y < 0.15 || red.y > width - 0.15)
    return std::nullopt;
  const double f = uf(rng);
  const Vec2 u{std::cos(a), std::sin(a)}, n{-std::sin(a), std::cos(a)};
  const Vec2 mid{cue.x + f * d * u.x, cue.y + f * d * u.y};
  std::string yaml = fmt::format("balls:\n  red: [{:.4f}, {:.4f}]\n", red.x, red.y);
  const char* names[] = {"blue", "pink", "black"};
  for (int i = -1; i <= 1; ++i)
    yaml += fmt::format("  {}: [{:.4f}, {:.4f}]\n", names[i + 1], mid.x + 2.05 * r * i * n.x,
                        mid.y + 2.05 * r * i * n.y);
  yaml += fmt::format("first_contact: any_red\ncue_ball: [{:.4f}, {:.4f}]\n", cue.x, cue.y);
  std::optional<problems::Problem> p = parsed(yaml);
  if (!p) return std::nullopt;
  // Snookered: no straight stroke strikes the red first (aims across the red and beyond).
  const double half = std::asin(std::min(1.0, 2 * r / d)) * kDeg + 1.0;
  for (double aim = a * kDeg - half; aim <= a * kDeg + half; aim += 0.01) {
    physics::Shot s{2.0, aim, 0.0, 0.0};
    const physics::ShotResult out = physics::simulate(p->scene, p->cue_ball, s);
    if (out.first_contact > 0 && out.balls[static_cast<size_t>(out.first_contact)].name == "red" &&
        problems::cushions_before_contact(out) == 0)
      return std::nullopt;
  }
  // A known escape off one or two cushions.
  std::vector<std::vector<int>> routes;
  for (int c = 0; c < 4; ++c) routes.push_back({c});
  for (int c = 0; c < 4; ++c)
    for (int e = 0; e < 4; ++e)
      if (c != e) routes.push_back({c, e});
  for (const std::vector<int>& route : routes) {
    const double seed = mirror_aim(p->scene, cue, route, red);
    for (double off = 0.0; off <= 1.0; off += 0.02)
      for (double sign : {1.0, -1.0}) {
        const physics::Shot s{2.5, seed + sign * off, 0.0, 0.0};
        const physics::ShotResult out = physics::simulate(p->scene, p->cue_ball, s);
        if (problems::check_outcome(*p, out).solves() &&
            problems::cushions_before_contact(out) == static_cast<int>(route.size()))
          return Snooker{*p, s};
      }
  }
  return std::nullopt;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

TEST(KickPlannerTest, SnookeredLayoutsWithAKnownEscapeAreEscaped) {
  std::mt19937_64 rng(2028);
  std::vector<Snooker> layouts;
  for (int tries = 0; layouts.size() < 30 && tries < 3000; ++tries)
    if (std::optional<Snooker> s = snooker_layout(rng)) layouts.push_back(std::move(*s));
  ASSERT_EQ(layouts.size(), 30u);
  int escaped = 0;
  std::vector<double> times;
  for (const Snooker& s : layouts) {
    ASSERT_TRUE(legal_hit(s.problem, s.escape));  // the known escape holds
    const PlanResult r = plan(s.problem, options());
    times.push_back(r.time_s);
    // Re-simulated independently: the ball on first, the cue ball left on the table.
    const bool ok = r.status == PlanStatus::solved && legal_hit(s.problem, r.best.shot);
    escaped += ok ? 1 : 0;
    if (!ok)
      std::cout << "not escaped: " << to_string(r.status) << ": " << r.message << '\n';
    else
      EXPECT_FALSE(r.best.route_words.empty());
    // Direct is ruled out, with its screen named.
    ASSERT_FALSE(r.ruled_out.empty()) << r.message;
    EXPECT_EQ(r.ruled_out.front().rfind("direct: ", 0), 0u) << r.ruled_out.front();
  }
  std::cout << "escaped " << escaped << " of " << layouts.size() << " snookered layouts; plan "
            << "time median " << median(times) << " s, max "
            << *std::max_element(times.begin(), times.end()) << " s\n";
  EXPECT_GE(escaped, 27);  // >= 90 %
  EXPECT_LE(median(times), 2.0);
}

// A bank or double made by a known stroke: a random stroke at a red that sends it into
// a pocket off one or two cushions.
struct Bank {
  problems::Problem problem;
  physics::Shot stroke;
};

std::optional<Bank> bank_layout(std::mt19937_64& rng) {
  const double length = 3.569, width = 1.778, r = 0.02625;
  std::uniform_real_distribution<double> ux(0.3, length - 0.3), uy(0.25, width - 0.25),
      ud(0.4, 1.3), ua(-std::numbers::pi, std::numbers::pi), ub(-1.5, 1.5), uv(2.0, 4.5);
  const Vec2 cue{ux(rng), uy(rng)};
  const double d = ud(rng), a = ua(rng);
  const Vec2 red{cue.x + d * std::cos(a), cue.y + d * std::sin(a)};
  const std::string balls = fmt::format("balls: {{red: [{:.4f}, {:.4f}]}}\ncue_ball: [{:.4f}, {:.4f}]\n",
                                        red.x, red.y, cue.x, cue.y);
  std::optional<problems::Problem> open = parsed(balls + "first_contact: red\n");
  if (!open) return std::nullopt;
  for (int k = 0; k < 40; ++k) {
    const double b = ub(rng) * r;
    const physics::Shot s{uv(rng), a * kDeg + std::asin(b / d) * kDeg, 0.0, 0.0};
    const physics::ShotResult out = physics::simulate(open->scene, open->cue_ball, s);
    if (out.status != physics::ShotStatus::rest || out.first_contact != 1) continue;
    const physics::BallOutcome& ball = out.balls[1];
    if (!ball.pocketed || ball.cushion_hits < 1 || ball.cushion_hits > 2 ||
        problems::cushions_before_contact(out) != 0)
      continue;
    std::optional<problems::Problem> p = parsed(
        balls + fmt::format("pot: {{ball: red, pocket: {}}}\nlimits: {{object_cushions: [1, 2], "
                            "cushions_before_contact: 0}}\n",
                            problems::kPocketNames[ball.pocket]));
    if (!p || !problems::check_stroke(*p, s, out).solves()) continue;
    return Bank{*p, s};
  }
  return std::nullopt;
}

TEST(KickPlannerTest, BanksAndDoublesWithAKnownStrokeArePotted) {
  std::mt19937_64 rng(2029);
  std::vector<Bank> layouts;
  for (int tries = 0; layouts.size() < 12 && tries < 4000; ++tries)
    if (std::optional<Bank> b = bank_layout(rng)) layouts.push_back(std::move(*b));
  ASSERT_EQ(layouts.size(), 12u);
  int potted = 0;
  std::vector<double> times;
  for (const Bank& b : layouts) {
    const PlanResult r = plan(b.problem, options());
    times.push_back(r.time_s);
    const physics::ShotResult again =
        physics::simulate(b.problem.scene, b.problem.cue_ball, r.best.shot);
    const bool ok = r.status == PlanStatus::solved &&
                    problems::check_stroke(b.problem, r.best.shot, again).solves() &&
                    again.balls[1].cushion_hits >= 1;
    potted += ok ? 1 : 0;
    if (!ok) std::cout << "not potted: " << to_string(r.status) << ": " << r.message << '\n';
    else EXPECT_NE(r.best.route_words.find("off"), std::string::npos) << r.best.route_words;
  }
  std::cout << "potted " << potted << " of " << layouts.size() << " banks and doubles; plan time "
            << "median " << median(times) << " s, max "
            << *std::max_element(times.begin(), times.end()) << " s\n";
  EXPECT_GE(potted, 11);  // >= 90 %
  EXPECT_LE(median(times), 3.0);
}

// A red ringed by six colours, too close for a ball to pass between them: no route
// reaches it, and every family says why.
TEST(KickPlannerTest, ARingedBallIsUnreachableWithEveryFamilysReason) {
  const double r = 0.02625;
  std::string yaml = "balls:\n  red: [1.8, 0.9]\n";
  const char* names[] = {"yellow", "green", "brown", "blue", "pink", "black"};
  for (int i = 0; i < 6; ++i) {
    const double t = i * std::numbers::pi / 3.0;
    yaml += fmt::format("  {}: [{:.5f}, {:.5f}]\n", names[i], 1.8 + 2.1 * r * std::cos(t),
                        0.9 + 2.1 * r * std::sin(t));
  }
  const std::optional<problems::Problem> escape =
      parsed(yaml + "first_contact: red\ncue_ball: [0.7, 0.5]\n");
  ASSERT_TRUE(escape);
  const PlanResult e = plan(*escape, options());
  EXPECT_EQ(e.status, PlanStatus::unreachable) << e.message;
  ASSERT_EQ(e.ruled_out.size(), 4u);  // direct, one, two and three cushions
  EXPECT_EQ(e.ruled_out[0].rfind("direct: ", 0), 0u) << e.ruled_out[0];
  EXPECT_EQ(e.ruled_out[1].rfind("one cushion: ", 0), 0u) << e.ruled_out[1];
  for (const std::string& why : e.ruled_out) EXPECT_NE(why.find("screened by"), std::string::npos) << why;
  EXPECT_NE(e.message.find("no direct, kick or bank route"), std::string::npos) << e.message;
  // The same red to pot: every family of kicks and banks is screened too.
  const std::optional<problems::Problem> pot =
      parsed(yaml + "pot: {ball: red, pocket: top_left}\ncue_ball: [0.7, 0.5]\n");
  ASSERT_TRUE(pot);
  const PlanResult p = plan(*pot, options());
  EXPECT_EQ(p.status, PlanStatus::unreachable) << p.message;
  EXPECT_GE(p.ruled_out.size(), 10u);  // direct and 3 x 3 + 2 kick and bank families
}

// A pot screened on the direct line is no longer refused: played off a cushion.
TEST(KickPlannerTest, AScreenedPotIsPlayedOffACushion) {
  const std::optional<problems::Problem> p = parsed(
      "balls: {red: [1.0, 1.0], blue: [0.6, 0.6]}\npot: {ball: red, pocket: bottom_left}\n"
      "cue_ball: [1.5, 1.3]\n");
  ASSERT_TRUE(p);
  const PlanResult r = plan(*p, options());
  ASSERT_EQ(r.status, PlanStatus::solved) << r.message;
  const physics::ShotResult again = physics::simulate(p->scene, p->cue_ball, r.best.shot);
  EXPECT_TRUE(problems::check_stroke(*p, r.best.shot, again).solves());
  EXPECT_GE(problems::cushions_before_contact(again) + again.balls[1].cushion_hits, 1);
  ASSERT_FALSE(r.ruled_out.empty());
  EXPECT_NE(r.ruled_out.front().find("screened by blue"), std::string::npos);
  EXPECT_NE(r.message.find("doubles off"), std::string::npos) << r.message;
}

// `leave: safe`: every reported escape has its leave judged, and the best is the one
// with the most P(legal hit) x P(the opponent misses the easiest pot left).
TEST(KickPlannerTest, ASafeLeaveRanksEscapesByWhatTheyLeave) {
  problems::Problem p = shipped("escapes/one_cushion_escape.yaml");
  p.leave_safe = true;
  const PlanResult r = plan(p, options());
  ASSERT_EQ(r.status, PlanStatus::solved) << r.message;
  ASSERT_TRUE(r.best.opponent_pot.has_value());
  EXPECT_NE(r.message.find("leaves the opponent at best"), std::string::npos) << r.message;
  const auto value = [](const PlannedShot& s) {
    return s.success.both.p * (1.0 - s.opponent_pot.value_or(1.0));
  };
  for (const PlannedShot& a : r.alternatives) {
    ASSERT_TRUE(a.opponent_pot.has_value());
    EXPECT_GE(value(r.best), value(a));
  }
  // Without it, no leave is judged.
  p.leave_safe = false;
  EXPECT_FALSE(plan(p, options()).best.opponent_pot.has_value());
}

// The shipped examples: the escapes escape, the banks pot off the cushions they say, and
// the bank that needs side is played with side and fails without it.
TEST(KickPlannerTest, ShippedExamplesAreSolvedAsTheirHeadersSay) {
  for (const char* file : {"escapes/one_cushion_escape.yaml", "escapes/two_cushion_escape.yaml",
                           "escapes/pool_kick_at_the_nine.yaml", "banks/cross_side_double.yaml",
                           "banks/side_only_bank.yaml"}) {
    const problems::Problem p = shipped(file);
    const PlanResult r = plan(p, options());
    EXPECT_EQ(r.status, PlanStatus::solved) << file << ": " << r.message;
    const physics::ShotResult again = physics::simulate(p.scene, p.cue_ball, r.best.shot);
    EXPECT_TRUE(problems::check_stroke(p, r.best.shot, again).solves()) << file;
    std::cout << file << ": " << r.best.route_words << " (" << r.time_s << " s, "
              << 100.0 * r.best.success_probability << " %)\n";
  }
  const problems::Problem two = shipped("escapes/two_cushion_escape.yaml");
  EXPECT_EQ(problems::cushions_before_contact(
                physics::simulate(two.scene, two.cue_ball, plan(two, options()).best.shot)),
            2);
  const problems::Problem as_shipped = shipped("banks/side_only_bank.yaml");
  problems::Problem side = as_shipped;
  const PlanResult with = plan(side, options());
  EXPECT_GE(std::abs(with.best.shot.sidespin_k), 0.25) << with.message;
  side.limits.spin_max = 0.01;  // no side (nor follow or draw) to speak of
  const PlanResult without = plan(side, options());
  EXPECT_NE(without.status, PlanStatus::solved) << without.message;
  // Independently of the planner: no stroke without side pots it near the side stroke's
  // line (aims within 4 degrees, every 0.01, at five speeds within the limit, stun,
  // follow and draw).
  int pots = 0;
  for (double aim = with.best.shot.aim_deg - 4.0; aim <= with.best.shot.aim_deg + 4.0; aim += 0.01)
    for (double speed : {1.2, 1.5, 1.8, 2.1, 2.4})
      for (double top : {0.0, 0.5, -0.5}) {
        const physics::Shot s{speed, aim, top, 0.0};
        pots += problems::check_stroke(as_shipped, s,
                                       physics::simulate(as_shipped.scene, as_shipped.cue_ball, s))
                    .solves();
      }
  EXPECT_EQ(pots, 0);
}

}  // namespace
}  // namespace cueplan::planner
