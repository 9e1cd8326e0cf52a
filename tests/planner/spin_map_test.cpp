// Tests of the spin map: which grid spins it simulates, that each point is the
// simulator's own answer judged by the problem's own rule, that threads change nothing,
// and that bad inputs come back as a message.
#include "cueplan/planner/spin_map.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace cueplan::planner {
namespace {

namespace phys = cueplan::physics;
namespace prob = cueplan::problems;

prob::Problem shipped(const std::string& stem) {
  const prob::LoadResult loaded =
      prob::load_problem(std::string(CUEPLAN_PROBLEMS_DIR) + "/" + stem + ".yaml");
  EXPECT_TRUE(loaded.ok()) << loaded.error;
  return loaded.ok() ? *loaded.problem : prob::Problem{};
}

// The stroke the one-rail problem file records as solving it (k_T 0.8, k_S 0).
constexpr double kOneRailSpeed = 1.002;
constexpr double kOneRailAim = -60.36;

SpinMapOptions small_grid(int grid, double spin_max = 0.0) {
  SpinMapOptions options;
  options.grid = grid;
  options.spin_max = spin_max;
  return options;
}

TEST(SpinMap, GridPointsLieInsideTheDiscAndNoneIsMissing) {
  const prob::Problem problem = shipped("one_rail_position");
  const SpinMap map = spin_map(problem, kOneRailSpeed, kOneRailAim, small_grid(9));
  ASSERT_TRUE(map.message.empty()) << map.message;
  EXPECT_EQ(map.spin_max, problem.limits.spin_max);  // 0 asks for the problem's limit
  EXPECT_EQ(map.grid, 9);

  // Every grid node of the square within the disc, and nothing else.
  const double step = 2.0 * map.spin_max / 8.0;
  std::set<std::pair<int, int>> expected;
  for (int row = 0; row < 9; ++row)
    for (int col = 0; col < 9; ++col)
      if ((row - 4) * (row - 4) + (col - 4) * (col - 4) <= 16) expected.insert({row, col});
  std::set<std::pair<int, int>> seen;
  for (const SpinMapPoint& p : map.points) {
    EXPECT_LE(std::hypot(p.topspin_k, p.sidespin_k), map.spin_max * (1.0 + 1e-12));
    const double row = p.topspin_k / step + 4.0;
    const double col = p.sidespin_k / step + 4.0;
    EXPECT_NEAR(row, std::round(row), 1e-9);
    EXPECT_NEAR(col, std::round(col), 1e-9);
    seen.insert({static_cast<int>(std::lround(row)), static_cast<int>(std::lround(col))});
    // Tip offsets in ball radii: k = 2.5 d / R.
    EXPECT_NEAR(p.tip_right, p.sidespin_k / 2.5, 1e-15);
    EXPECT_NEAR(p.tip_up, p.topspin_k / 2.5, 1e-15);
  }
  EXPECT_EQ(seen, expected);
  EXPECT_EQ(map.points.size(), expected.size());
  // Row by row from the top: topspin never rises along the list.
  for (size_t i = 1; i < map.points.size(); ++i)
    EXPECT_LE(map.points[i].topspin_k, map.points[i - 1].topspin_k);
}

TEST(SpinMap, CentrePointEqualsADirectSimulation) {
  const prob::Problem problem = shipped("one_rail_position");
  const SpinMap map = spin_map(problem, kOneRailSpeed, kOneRailAim, small_grid(7));
  ASSERT_TRUE(map.message.empty()) << map.message;
  const SpinMapPoint* centre = nullptr;
  for (const SpinMapPoint& p : map.points)
    if (p.topspin_k == 0.0 && p.sidespin_k == 0.0) centre = &p;
  ASSERT_NE(centre, nullptr) << "an odd grid holds k = 0 exactly";

  phys::SimulationOptions options;
  options.record_path = false;  // as the map simulates; the outcome does not depend on it
  const phys::ShotResult direct = phys::simulate(problem.scene, problem.cue_ball,
                                                 {kOneRailSpeed, kOneRailAim, 0.0, 0.0}, options);
  EXPECT_EQ(centre->outcome, direct.status);
  EXPECT_EQ(centre->final_position.x, direct.final_position.x);
  EXPECT_EQ(centre->final_position.y, direct.final_position.y);
  EXPECT_EQ(centre->cushion_hits, direct.cushion_hits);
  EXPECT_EQ(centre->miss_distance, prob::miss_distance(problem, direct));
  EXPECT_EQ(centre->lands, prob::reaches_target(problem, direct));
}

TEST(SpinMap, LandingFlagsAgreeWithReachesTarget) {
  const prob::Problem problem = shipped("one_rail_position");
  // A disc of radius 0.8 on a 3-point grid holds the recorded solution (k_T 0.8, k_S 0)
  // at its top.
  const SpinMap map = spin_map(problem, kOneRailSpeed, kOneRailAim, small_grid(3, 0.8));
  ASSERT_TRUE(map.message.empty()) << map.message;
  ASSERT_EQ(map.points.size(), 5u);
  int landing = 0;
  for (const SpinMapPoint& p : map.points) {
    const phys::ShotResult r = phys::simulate(
        problem.scene, problem.cue_ball, {kOneRailSpeed, kOneRailAim, p.topspin_k, p.sidespin_k});
    EXPECT_EQ(p.lands, prob::reaches_target(problem, r))
        << "k_T " << p.topspin_k << ", k_S " << p.sidespin_k;
    EXPECT_NEAR(p.miss_distance, prob::miss_distance(problem, r), 1e-9);
    landing += p.lands ? 1 : 0;
  }
  EXPECT_EQ(map.landing, landing);
  EXPECT_TRUE(map.points.front().lands) << "the recorded solution lands";
  EXPECT_GE(map.landing, 1);
  EXPECT_LT(map.landing, 5) << "centre ball does not land where k_T 0.8 does";
}

TEST(SpinMap, ThreadsDoNotChangeTheMap) {
  const prob::Problem problem = shipped("two_rail_position");
  SpinMapOptions one = small_grid(11);
  SpinMapOptions two = one;
  two.threads = 2;
  SpinMapOptions three = one;
  three.threads = 3;
  const SpinMap a = spin_map(problem, 1.8, 30.0, one);
  for (const SpinMap& b :
       {spin_map(problem, 1.8, 30.0, two), spin_map(problem, 1.8, 30.0, three)}) {
    ASSERT_EQ(a.points.size(), b.points.size());
    EXPECT_EQ(a.landing, b.landing);
    for (size_t i = 0; i < a.points.size(); ++i) {
      const SpinMapPoint& p = a.points[i];
      const SpinMapPoint& q = b.points[i];
      EXPECT_EQ(p.topspin_k, q.topspin_k);
      EXPECT_EQ(p.sidespin_k, q.sidespin_k);
      EXPECT_EQ(p.outcome, q.outcome);
      EXPECT_EQ(p.final_position.x, q.final_position.x);
      EXPECT_EQ(p.final_position.y, q.final_position.y);
      EXPECT_EQ(p.cushion_hits, q.cushion_hits);
      EXPECT_EQ(p.lands, q.lands);
    }
  }
}

TEST(SpinMap, ProgressRisesToOneOnTheCallingThread) {
  const prob::Problem problem = shipped("one_rail_position");
  SpinMapOptions options = small_grid(9);
  options.threads = 2;
  std::vector<double> seen;
  const std::thread::id caller = std::this_thread::get_id();
  bool same_thread = true;
  options.progress = [&](double fraction) {
    seen.push_back(fraction);
    same_thread = same_thread && std::this_thread::get_id() == caller;
  };
  const SpinMap map = spin_map(problem, kOneRailSpeed, kOneRailAim, options);
  ASSERT_FALSE(map.points.empty());
  ASSERT_FALSE(seen.empty());
  EXPECT_TRUE(same_thread);
  EXPECT_EQ(seen.back(), 1.0);
  for (size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i], seen[i - 1]);
  EXPECT_GE(seen.front(), 0.0);
}

TEST(SpinMap, BadInputsGiveAMessageAndNoPoints) {
  const prob::Problem problem = shipped("one_rail_position");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  SpinMapOptions negative_threads = small_grid(5);
  negative_threads.threads = -1;
  const struct {
    const char* name;
    double speed, aim;
    SpinMapOptions options;
    const char* field;
  } cases[] = {
      {"grid of two", 1.0, 0.0, small_grid(2), "grid"},
      {"zero speed", 0.0, 0.0, small_grid(5), "speed"},
      {"negative speed", -1.0, 0.0, small_grid(5), "speed"},
      {"speed not a number", nan, 0.0, small_grid(5), "speed"},
      {"infinite aim", 1.0, inf, small_grid(5), "aim"},
      {"negative spin limit", 1.0, 0.0, small_grid(5, -0.5), "spin_max"},
      {"negative threads", 1.0, 0.0, negative_threads, "threads"},
  };
  for (const auto& c : cases) {
    const SpinMap map = spin_map(problem, c.speed, c.aim, c.options);
    EXPECT_TRUE(map.points.empty()) << c.name;
    EXPECT_EQ(map.landing, 0) << c.name;
    EXPECT_NE(map.message.find(c.field), std::string::npos) << c.name << ": " << map.message;
  }
}

// At noise scale 0 every noisy stroke is the cell's own stroke: the success is 1 where
// the cell lands and 0 where it does not, on a position and on a pot problem.
TEST(SpinMapSuccess, ZeroNoiseGivesTheMapsOwnOutcome) {
  const struct {
    const char* stem;
    double speed, aim, spin_max;
  } cases[] = {{"one_rail_position", kOneRailSpeed, kOneRailAim, 0.8},
               {"pots/straight_pot_corner", 2.64, 225.0, 1.14}};
  for (const auto& c : cases) {
    const prob::Problem problem = shipped(c.stem);
    // The recorded solutions lie on the rim of these discs (k_T 0.8 and -1.14).
    SpinMapOptions options = small_grid(5, c.spin_max);
    options.threads = 2;
    options.success_samples = 3;
    options.noise.scale = 0.0;
    const SpinMap map = spin_map(problem, c.speed, c.aim, options);
    ASSERT_TRUE(map.message.empty()) << c.stem << ": " << map.message;
    EXPECT_TRUE(map.success_complete);
    EXPECT_EQ(map.success_cells, static_cast<int>(map.points.size()));
    EXPECT_GE(map.landing, 1) << c.stem;
    EXPECT_LT(map.landing, static_cast<int>(map.points.size())) << c.stem;
    for (const SpinMapPoint& p : map.points) {
      ASSERT_TRUE(p.success.has_value());
      EXPECT_EQ(*p.success, p.lands ? 1.0 : 0.0)
          << c.stem << ": k_T " << p.topspin_k << ", k_S " << p.sidespin_k;
    }
  }
}

// With noise: the estimates are the planner's success probability of each cell's stroke
// (estimate_success with the same seed), the same for any number of threads, and the
// map itself is the map without them.
TEST(SpinMapSuccess, EstimatesMatchEstimateSuccessAndThreadsDoNotChangeThem) {
  const prob::Problem problem = shipped("one_rail_position");
  const SpinMap plain = spin_map(problem, kOneRailSpeed, kOneRailAim, small_grid(7));
  SpinMapOptions options = small_grid(7);
  options.success_samples = 24;
  // Half a club player's scatter: some cells then succeed on some draws and not others.
  options.noise.scale = 0.5;
  options.seed = 7;
  const SpinMap one = spin_map(problem, kOneRailSpeed, kOneRailAim, options);
  options.threads = 3;
  const SpinMap three = spin_map(problem, kOneRailSpeed, kOneRailAim, options);
  ASSERT_EQ(one.points.size(), plain.points.size());
  ASSERT_EQ(three.points.size(), plain.points.size());
  EXPECT_EQ(one.success_samples, 24);
  int between = 0;
  for (size_t i = 0; i < plain.points.size(); ++i) {
    const SpinMapPoint& p = one.points[i];
    EXPECT_FALSE(plain.points[i].success.has_value());
    EXPECT_EQ(p.lands, plain.points[i].lands);
    EXPECT_EQ(p.final_position.x, plain.points[i].final_position.x);
    ASSERT_TRUE(p.success.has_value());
    EXPECT_EQ(p.success, three.points[i].success);
    const Success s = estimate_success(problem, {kOneRailSpeed, p.aim_deg, p.topspin_k,
                                                 p.sidespin_k},
                                       options.noise, 24, 7, options.simulation);
    EXPECT_EQ(*p.success, s.both.p) << "k_T " << p.topspin_k << ", k_S " << p.sidespin_k;
    between += *p.success > 0.0 && *p.success < 1.0;
  }
  EXPECT_GE(between, 1) << "some cell is neither always nor never made under the noise";
}

TEST(SpinMapSuccess, PartsDeadlineProgressAndBadInputs) {
  const prob::Problem problem = shipped("one_rail_position");
  SpinMapOptions options = small_grid(7);
  options.success_samples = 4;
  options.success_first = 2;
  options.success_count = 3;
  std::vector<double> seen;
  options.progress = [&](double f) { seen.push_back(f); };
  const SpinMap part = spin_map(problem, kOneRailSpeed, kOneRailAim, options);
  for (size_t i = 0; i < part.points.size(); ++i)
    EXPECT_EQ(part.points[i].success.has_value(), i >= 2 && i < 5) << i;
  EXPECT_EQ(part.success_cells, 3);
  EXPECT_TRUE(part.success_complete);
  ASSERT_FALSE(seen.empty());
  EXPECT_EQ(seen.back(), 1.0);
  for (size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i], seen[i - 1]);

  options.success_first = 0;
  options.success_count = static_cast<size_t>(-1);
  options.progress = nullptr;
  options.deadline = std::chrono::steady_clock::now();
  const SpinMap late = spin_map(problem, kOneRailSpeed, kOneRailAim, options);
  EXPECT_FALSE(late.points.empty());
  EXPECT_EQ(late.success_cells, 0);
  EXPECT_FALSE(late.success_complete);

  SpinMapOptions bad = small_grid(5);
  bad.success_samples = -1;
  EXPECT_NE(spin_map(problem, 1.0, 0.0, bad).message.find("success_samples"), std::string::npos);
  bad.success_samples = 4;
  bad.noise.scale = -1.0;
  const SpinMap noisy = spin_map(problem, 1.0, 0.0, bad);
  EXPECT_TRUE(noisy.points.empty());
  EXPECT_NE(noisy.message.find("noise.scale"), std::string::npos) << noisy.message;
}

}  // namespace
}  // namespace cueplan::planner
