// The position field (planner/position.hpp): P(next pot) from a cue-ball position.
// Sanity of the closed form (screens, straight pots, distance, cushions, the ball too
// close), the zone and the cache; and the estimate checked against the planner's own
// P(pot) from plan() at positions spread over the table (docs/position.md).
#include "cueplan/planner/position.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "cueplan/planner/planner.hpp"
#include "cueplan/problems/problem.hpp"
#include "task.hpp"

namespace cueplan::planner {
namespace {

using physics::Vec2;

problems::Problem parse(const std::string& yaml) {
  const problems::LoadResult r = problems::parse_problem(yaml, "<position test>");
  EXPECT_TRUE(r.ok()) << r.error;
  return r.ok() ? *r.problem : problems::Problem{};
}

// Snooker (the default table, jawed pockets): a red to pot now, the black on its spot
// to pot next into the top-right corner.
problems::Problem red_then_black(const std::string& extra_balls = "") {
  return parse("balls: {red: [0.6, 0.6], black: [3.245, 0.889]" + extra_balls +
               "}\npot: {ball: red, pocket: bottom_left}\n"
               "next: {ball: black, pocket: top_right}\ncue_ball: [1.1, 1.1]\n");
}

// The point `along` m from the black back along its line from the top-right pocket,
// turned by `cut_deg`: a cue ball there plays a cut of about that much.
Vec2 behind_black(const PositionField& f, double along, double cut_deg) {
  const Vec2 black{3.245, 0.889};
  const physics::Pocket& pocket = f.layout().pockets[5];
  const double a = std::atan2(pocket.centre.y - black.y, pocket.centre.x - black.x) + M_PI +
                   cut_deg * M_PI / 180.0;
  return {black.x + along * std::cos(a), black.y + along * std::sin(a)};
}

TEST(PositionField, StraightOnScoresHighAndFallsWithDistance) {
  const problems::Problem p = red_then_black();
  const PositionField f = PositionField::for_problem(p, NoiseModel{});
  double last = 1.0;
  for (double d : {0.15, 0.3, 0.6, 0.9}) {
    const double v = f.value(behind_black(f, d, 0.0));
    EXPECT_LE(v, last + 1e-12) << "at " << d << " m";
    last = v;
  }
  EXPECT_GT(f.value(behind_black(f, 0.2, 0.0)), 0.9);
  EXPECT_LT(f.value(behind_black(f, 0.9, 0.0)), 0.6);
  // A cut costs: the same distance at 45 degrees is worth less than straight on.
  EXPECT_LT(f.value(behind_black(f, 0.6, 45.0)), f.value(behind_black(f, 0.6, 0.0)));
  const NextShot s = f.next_shot(behind_black(f, 0.6, 45.0));
  EXPECT_NEAR(s.cut_deg, 45.0, 6.0);  // measured at the ghost ball, not the black
  EXPECT_NEAR(s.cue_distance_m, 0.6, 1e-9);
}

TEST(PositionField, ScreenedPositionsScoreZero) {
  // A blocker halfway between a cue position and the black: that position scores 0,
  // the same position without it does not.
  const problems::Problem open = red_then_black();
  const PositionField clear = PositionField::for_problem(open, NoiseModel{});
  const Vec2 cue = behind_black(clear, 0.8, 10.0);
  const Vec2 mid{0.5 * (cue.x + 3.245), 0.5 * (cue.y + 0.889)};
  const problems::Problem blocked = red_then_black(", blue: [" + std::to_string(mid.x) + ", " +
                                                   std::to_string(mid.y) + "]");
  const PositionField screened = PositionField::for_problem(blocked, NoiseModel{});
  EXPECT_GT(clear.value(cue), 0.3);
  EXPECT_EQ(screened.value(cue), 0.0);
  EXPECT_EQ(screened.next_shot(cue).screened_by, "blue");
  // A ball on the black's way to the pocket screens it from everywhere.
  const problems::Problem in_jaws = red_then_black(", pink: [3.40, 1.40]");
  const PositionField none = PositionField::for_problem(in_jaws, NoiseModel{});
  EXPECT_EQ(none.best_value(), 0.0);
  EXPECT_EQ(none.next_shot(cue).screened_by, "pink");
  // Cuts beyond kMostCut: the far side of the black.
  EXPECT_EQ(clear.value(behind_black(clear, 0.5, 120.0)), 0.0);
}

TEST(PositionField, FrozenOnACushionOrTooCloseToCueScoresLow) {
  const problems::Problem p = red_then_black();
  const PositionField f = PositionField::for_problem(p, NoiseModel{});
  // On the black's line to the pocket, back at the bottom cushion: frozen there (the cue
  // over the cushion) and 10 cm off it.
  const double r = f.layout().contact_offset();
  const Vec2 pocket = f.layout().pockets[5].centre;
  const Vec2 black{3.245, 0.889};
  auto on_line_at_y = [&](double y) {
    const double t = (y - black.y) / (pocket.y - black.y);
    return Vec2{black.x + t * (pocket.x - black.x), y};
  };
  const Vec2 frozen = on_line_at_y(r + 0.001), free = on_line_at_y(r + 0.10);
  EXPECT_TRUE(f.next_shot(frozen).near_cushion);
  EXPECT_FALSE(f.next_shot(free).near_cushion);
  EXPECT_LT(f.value(frozen), 0.6 * f.value(free));
  // Touching the black: no room to cue.
  const Vec2 touching = behind_black(f, 2.0 * f.layout().radius() + 0.001, 0.0);
  EXPECT_TRUE(f.next_shot(touching).too_close);
  EXPECT_LT(f.value(touching), 0.1);
  // Inside a ball, off the table: no value.
  EXPECT_EQ(f.value(black), 0.0);
  EXPECT_EQ(f.value(Vec2{-0.1, 0.5}), 0.0);
}

TEST(PositionField, ZoneHoldsTheBestAndIsWithinTenPointsOfIt) {
  const problems::Problem p = red_then_black();
  const PositionField f = PositionField::for_problem(p, NoiseModel{});
  EXPECT_GT(f.best_value(), 0.9);
  EXPECT_TRUE(f.in_zone(f.best()));
  EXPECT_NEAR(f.value(f.best()), f.best_value(), 1e-12);
  // The zone is a real area, not a spot (at least 100 cm^2), and far from the whole table.
  EXPECT_GT(f.zone_area_m2(), 0.01);
  EXPECT_LT(f.zone_area_m2(), 0.5 * p.scene.length * p.scene.width);
  int in = 0;
  for (int j = 0; j < f.rows(); ++j)
    for (int i = 0; i < f.columns(); ++i)
      if (f.cell_value(i, j) >= f.best_value() - kZoneWidth) ++in;
  EXPECT_NEAR(in * f.cell() * f.cell(), f.zone_area_m2(), 1e-12);
  EXPECT_FALSE(f.in_zone(behind_black(f, 0.9, 0.0)));
}

TEST(PositionField, LookAheadLowersPositionsFromWhichTheThirdCannotBeReached) {
  // Black next, then a blue in the middle of the table behind a wall of obstacles on the
  // black's side: the look-ahead value never exceeds P(black) and somewhere falls below.
  const problems::Problem one = red_then_black(", blue: [1.7845, 0.889]");
  problems::Problem two = one;
  two.next.push_back({"blue", 1});  // bottom_middle
  const PositionField f1 = PositionField::for_problem(one, NoiseModel{});
  const PositionField f2 = PositionField::for_problem(two, NoiseModel{});
  bool lower = false;
  for (int j = 0; j < f1.rows(); j += 5)
    for (int i = 0; i < f1.columns(); i += 5) {
      const Vec2 c = f1.cell_centre(i, j);
      EXPECT_LE(f2.value(c), f1.value(c) + 1e-12);
      lower = lower || f2.value(c) < f1.value(c) - 0.05;
    }
  EXPECT_TRUE(lower);
  EXPECT_GT(f2.best_value(), 0.5);
}

TEST(PositionField, ALazyGridAnswersAsTheEagerOneFromManyThreads) {
  // One pot and a list of two: a lazy field (the grid filled at the first call that
  // needs it, here from four threads at once) answers exactly as an eager one.
  problems::Problem two = red_then_black(", blue: [1.7845, 0.889]");
  two.next.push_back({"blue", 1});
  for (const problems::Problem& p : {red_then_black(), two}) {
    const PositionField eager = PositionField::for_problem(p, NoiseModel{});
    const PositionField lazy = PositionField::for_problem(p, NoiseModel{}, 0.02, FieldGrid::lazy);
    const Vec2 c = behind_black(eager, 0.6, 20.0);
    std::vector<double> values(4), best(4);
    std::vector<std::thread> threads;
    for (size_t i = 0; i < values.size(); ++i)
      threads.emplace_back([&, i] {
        values[i] = i % 2 ? lazy.value(c) : lazy.next_shot(c).p;
        best[i] = lazy.best_value();
      });
    for (std::thread& t : threads) t.join();
    for (size_t i = 0; i < values.size(); ++i) {
      EXPECT_EQ(values[i], i % 2 ? eager.value(c) : eager.next_shot(c).p);
      EXPECT_EQ(best[i], eager.best_value());
    }
    EXPECT_EQ(lazy.zone_area_m2(), eager.zone_area_m2());
    EXPECT_EQ(lazy.best().x, eager.best().x);
    EXPECT_EQ(lazy.best().y, eager.best().y);
    for (int j = 0; j < eager.rows(); j += 7)
      for (int i = 0; i < eager.columns(); i += 7) EXPECT_EQ(lazy.cell_value(i, j), eager.cell_value(i, j));
  }
  // One pot's chance without a field kept: the field's P at that point.
  const problems::Problem p = red_then_black();
  const PositionField f = PositionField::for_problem(p, NoiseModel{});
  const Vec2 c = behind_black(f, 0.5, 30.0);
  EXPECT_EQ(PositionField::pot_chance(f.layout(), c, "black", p.next.front().pocket, NoiseModel{}),
            f.next_shot(c).p);
}

TEST(PositionCache, BuildsOnceAndSharesBetweenThreads) {
  const problems::Problem p = red_then_black();
  PositionCache cache;
  std::vector<std::shared_ptr<const PositionField>> got(4);
  std::vector<std::thread> threads;
  for (size_t i = 0; i < got.size(); ++i)
    threads.emplace_back([&, i] { got[i] = cache.get(p, NoiseModel{}); });
  for (std::thread& t : threads) t.join();
  for (const auto& g : got) EXPECT_EQ(g.get(), got[0].get());
  EXPECT_EQ(cache.size(), 1u);
  NoiseModel twice;
  twice.scale = 2.0;
  EXPECT_NE(cache.get(p, twice).get(), got[0].get());
  EXPECT_EQ(cache.size(), 2u);
  // Twice the noise: worse wherever it is not certain.
  const Vec2 c = behind_black(*got[0], 0.6, 20.0);
  EXPECT_LT(cache.get(p, twice)->value(c), got[0]->value(c));
}

// The closed form against the planner: at cue positions spread over the table, the
// planner's best stroke's P(pot) under the same noise (plan(), 200 noisy strokes) and the
// field's P(next pot) for the same ball and pocket.
struct Spot {
  const char* name;
  double x, y;  // the cue ball (m)
};
constexpr Spot kSpots[] = {
    {"close_straight", 3.164, 0.652}, {"mid_straight", 3.019, 0.227}, {"close_quarter", 3.252, 0.539},
    {"mid_quarter", 2.799, 0.225},    {"mid_half", 2.70, 0.60},       {"close_thin", 3.481, 0.566},
    {"mid_thin", 2.405, 0.565},       {"long_quarter", 2.00, 0.15},   {"long_half", 1.60, 0.90},
    {"far_baulk", 0.70, 0.40},        {"far_cushion_side", 1.20, 1.50}, {"behind_across", 3.10, 1.30},
};

double rank_correlation(const std::vector<double>& a, const std::vector<double>& b) {
  auto ranks = [](const std::vector<double>& v) {
    std::vector<size_t> order(v.size());
    for (size_t i = 0; i < v.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t i, size_t j) { return v[i] < v[j]; });
    std::vector<double> r(v.size());
    for (size_t k = 0; k < order.size();) {  // average ranks of ties
      size_t e = k;
      while (e + 1 < order.size() && v[order[e + 1]] == v[order[k]]) ++e;
      for (size_t m = k; m <= e; ++m) r[order[m]] = 0.5 * static_cast<double>(k + e);
      k = e + 1;
    }
    return r;
  };
  const std::vector<double> ra = ranks(a), rb = ranks(b);
  double ma = 0, mb = 0;
  for (size_t i = 0; i < ra.size(); ++i) ma += ra[i], mb += rb[i];
  ma /= static_cast<double>(ra.size());
  mb /= static_cast<double>(rb.size());
  double sab = 0, saa = 0, sbb = 0;
  for (size_t i = 0; i < ra.size(); ++i) {
    sab += (ra[i] - ma) * (rb[i] - mb);
    saa += (ra[i] - ma) * (ra[i] - ma);
    sbb += (rb[i] - mb) * (rb[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

TEST(PositionFieldValidation, AgreesWithThePlannersPotChanceOverTheTable) {
  const problems::Problem layout = red_then_black();
  const PositionField f = PositionField::for_problem(layout, NoiseModel{});
  std::vector<double> field, planned;
  double worst = 0.0;
  for (const Spot& s : kSpots) {
    const Vec2 cue{s.x, s.y};
    // The next pot as a problem of its own: the black from there, the red gone.
    problems::Problem pot = parse("balls: {black: [3.245, 0.889]}\npot: {ball: black, pocket: "
                                  "top_right}\ncue_ball: [" +
                                  std::to_string(cue.x) + ", " + std::to_string(cue.y) + "]\n");
    PlannerOptions o;
    o.simulation.record_path = false;
    o.robustness_samples = 200;
    const PlanResult r = plan(pot, o);
    const double planner_p = r.status == PlanStatus::solved && r.best.success.pot
                                 ? r.best.success.pot->p
                                 : 0.0;
    const double field_p = f.next_shot(cue).p;
    if (f.next_shot(cue).impossible_cut) {
      // The field judges direct pots; where none can be cut in, the planner may still
      // find a kick or bank (route_words says which) - not the field's to judge.
      std::cout << s.name << ": no direct pot (cut " << f.next_shot(cue).cut_deg
                << " deg); planner " << planner_p << " " << r.best.route_words << "\n";
      EXPECT_EQ(field_p, 0.0) << s.name;
      if (planner_p > 0.0) EXPECT_FALSE(r.best.route_words.empty()) << s.name;
      continue;
    }
    field.push_back(field_p);
    planned.push_back(planner_p);
    worst = std::max(worst, std::abs(field_p - planner_p));
    std::cout << s.name << ": cue (" << cue.x << ", " << cue.y << "), cut "
              << f.next_shot(cue).cut_deg << " deg: field " << field_p << ", planner "
              << planner_p << "\n";
    EXPECT_NEAR(field_p, planner_p, kFieldError) << s.name;
  }
  const double rho = rank_correlation(field, planned);
  std::cout << "largest difference " << worst << ", rank correlation " << rho << "\n";
  EXPECT_GE(rho, 0.8);
}

// A landing's worth with a stroke's spread (Task::landing_worth, which ranks the
// position grid's strokes): the value itself without a speed error; about the value in
// the middle of a flat zone; well below it on a zone's edge, where one speed error
// further or shorter leaves the next pot worth little.
TEST(LandingWorth, FallsOnAZonesEdgeAndNotInItsMiddle) {
  const problems::Problem p = red_then_black();
  detail::Task task(p);
  task.next_field = std::make_shared<const PositionField>(PositionField::for_problem(p, NoiseModel{}));
  const PositionField& f = *task.next_field;
  // A stroke at 2 m/s that meets the red and runs 1 m along +x to `end`: the spread is
  // 2 x 0.075 / 2 x 1 m = 7.5 cm each way.
  const auto stroke_to = [](Vec2 end) {
    physics::ShotResult r;
    r.status = physics::ShotStatus::rest;
    r.final_position = end;
    physics::ShotEvent strike, contact, rest;
    strike.type = physics::EventType::strike;
    strike.position = {end.x - 1.5, end.y};
    strike.velocity = {2.0, 0.0};
    contact.type = physics::EventType::ball_contact;
    contact.position = {end.x - 1.0, end.y};
    rest.type = physics::EventType::rest;
    rest.position = end;
    r.events = {strike, contact, rest};
    return r;
  };
  const double best = f.best_value();
  const double d = 0.075;
  std::optional<Vec2> middle, edge;
  for (int j = 0; j < f.rows(); ++j)
    for (int i = 0; i < f.columns(); ++i) {
      const Vec2 c = f.cell_centre(i, j);
      if (f.value(c) < 0.95 * best) continue;
      double low = 1.0;
      for (const Vec2 o : {Vec2{d, 0.0}, Vec2{-d, 0.0}, Vec2{0.0, d}, Vec2{0.0, -d}})
        low = std::min(low, f.value({c.x + o.x, c.y + o.y}));
      if (!middle && low >= 0.95 * best) middle = c;
      if (!edge && low < 0.3 * best) edge = c;
    }
  ASSERT_TRUE(middle && edge) << "the layout's zone has no flat middle or sharp edge";
  task.landing_speed_sd = 0.0;
  EXPECT_EQ(task.landing_worth(stroke_to(*edge)), f.value(*edge));
  task.landing_speed_sd = 0.075;
  EXPECT_NEAR(task.landing_worth(stroke_to(*middle)), f.value(*middle), 0.05 * best);
  EXPECT_LT(task.landing_worth(stroke_to(*edge)), f.value(*edge) - 0.1 * best);
}

// Position play end to end on the shipped example: the planner pots the red, reports
// P(pot), P(next) and P(both) with intervals and what the landing leaves; solving the
// black from where the cue ball stops agrees with the reported success.next.
TEST(PositionPlay, SolvesTheShippedRedThenBlackAndTheNextPotAgrees) {
  const problems::LoadResult loaded =
      problems::load_problem(std::string(CUEPLAN_PROBLEMS_DIR) + "/pots/red_then_black.yaml");
  ASSERT_TRUE(loaded.ok()) << loaded.error;
  const problems::Problem& p = *loaded.problem;
  PlannerOptions o;
  o.simulation.record_path = false;
  PositionCache cache;
  o.position_cache = &cache;
  const PlanResult r = plan(p, o);
  ASSERT_EQ(r.status, PlanStatus::solved) << r.message;
  EXPECT_EQ(cache.size(), 1u);
  ASSERT_TRUE(r.position_field);
  const PlannedShot& b = r.best;
  // Played again independently: the red drops in its pocket.
  const physics::ShotResult again = physics::simulate(p.scene, p.cue_ball, b.shot);
  EXPECT_TRUE(problems::makes_pot(p, again));
  ASSERT_TRUE(b.success.pot && b.success.next);
  EXPECT_GT(b.success.next->samples, 0);
  EXPECT_LE(b.success.next->low, b.success.next->p);
  EXPECT_GE(b.success.next->high, b.success.next->p);
  EXPECT_LE(b.success.both.p, b.success.pot->p);
  // P(both) is counted with the next pot drawn at each landing: about P(pot) E[P(next)].
  EXPECT_NEAR(b.success.both.p, b.success.pot->p * b.success.next->p, 0.1);
  ASSERT_TRUE(b.next.has_value());
  EXPECT_EQ(b.next->ball, "black");
  EXPECT_EQ(b.next->pocket_name, "bottom_right");
  EXPECT_TRUE(b.next->in_zone) << b.next->words;
  EXPECT_GT(b.next->zone_area_m2, 0.0);
  EXPECT_NE(b.next->words.find("on the black"), std::string::npos) << b.next->words;
  EXPECT_NE(r.message.find("the next pot (black into the bottom_right)"), std::string::npos)
      << r.message;
  // The next pot solved from where the cue ball stops, the red gone.
  problems::Problem next = parse("balls: {black: [3.245, 0.889]}\npot: {ball: black, pocket: "
                                 "bottom_right}\ncue_ball: [" +
                                 std::to_string(b.final_position.x) + ", " +
                                 std::to_string(b.final_position.y) + "]\n");
  const PlanResult n = plan(next, o);
  ASSERT_EQ(n.status, PlanStatus::solved) << n.message;
  ASSERT_TRUE(n.best.success.pot);
  std::cout << "landing (" << b.final_position.x << ", " << b.final_position.y << "): reported "
            << "next " << b.success.next->p << " [" << b.success.next->low << ", "
            << b.success.next->high << "], field there " << b.next->p << ", planner's P(pot) "
            << n.best.success.pot->p << "\n";
  EXPECT_GE(n.best.success.pot->p, 0.6);
  EXPECT_GE(n.best.success.pot->p, b.success.next->low);
  EXPECT_LE(n.best.success.pot->p, b.success.next->high);
}

}  // namespace
}  // namespace cueplan::planner
