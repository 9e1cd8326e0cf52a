// Tests of the problem-file loader: the shipped examples, defaults, the mapping onto
// the physics Scene, and one precise error (file, line, field) for each kind of bad input.
#include "cueplan/problems/ball_names.hpp"
#include "cueplan/problems/problem.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace cueplan::problems {
namespace {

namespace fs = std::filesystem;

// The files directly in problems/ and in problems/pots/ (the examples with object balls
// and a pot), problems/escapes/ and problems/banks/ (kicks, escapes, banks), as stems relative to problems/: "one_rail_position", "pots/plant_two_balls".
std::vector<std::string> shipped_examples() {
  std::vector<std::string> names;
  for (const char* dir : {"", "pots/", "escapes/", "banks/"}) {
    const std::string path = std::string(CUEPLAN_PROBLEMS_DIR) + "/" + dir;
    if (!fs::is_directory(path)) continue;
    for (const auto& entry : fs::directory_iterator(path)) {
      if (entry.path().extension() == ".yaml")
        names.push_back(std::string(dir) + entry.path().stem().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::string example_path(const std::string& name) {
  return std::string(CUEPLAN_PROBLEMS_DIR) + "/" + name + ".yaml";
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The format reference's full example (problems/README.md), every field given.
constexpr const char* kFullExample = R"(name: one-rail position            # optional
table:                             # optional; defaults: a snooker table
  length: 3.569                    # m between cushion noses (x)
  width: 1.778                     # m (y)
  pockets: standard                # none, standard, snooker, pool, carom or a mapping
  pocket_radius: 0.045             # m, capture circle around each pocket point
ball: {radius: 0.02625, mass: 0.1406}
physics: {mu_slide: 0.212, mu_roll: 0.01, mu_spin: 0.0117, mu_cushion: 0.14,
          restitution: 0.98, cushion_height: 0.03675, gravity: 9.81}
cue_ball: [0.8, 0.5]               # m
target: [2.6, 1.2]                 # m, where the cue ball should stop
tolerance: 0.02                    # m, radius of the landing zone
obstacles: [[1.5, 0.9]]            # other balls at rest; optional
limits:                            # search space and constraints for the planner
  speed: [0.2, 4.5]                # m/s
  spin: 1.25                       # max sqrt(k_T^2 + k_S^2) (miscue limit)
  aim_deg: free                    # free, a number, or [lo, hi]
  cushions: [1, 3]                 # cushion contacts allowed before rest
)";

// The two required fields, for files that test the others.
constexpr const char* kPositions = "cue_ball: [1.0, 1.0]\ntarget: [2.0, 1.0]\n";

Problem parse_ok(const std::string& text) {
  LoadResult r = parse_problem(text, "test.yaml");
  EXPECT_TRUE(r.ok()) << r.error;
  EXPECT_TRUE(r.error.empty());
  return r.ok() ? *r.problem : Problem{};
}

// ---- Shipped examples ----------------------------------------------------------

TEST(ShippedProblems, AtLeastEightShipWithEveryKindOfShot) {
  const std::vector<std::string> names = shipped_examples();
  EXPECT_GE(names.size(), 8u);
  for (const char* required :
       {"one_rail_position", "two_rail_position", "three_rail_position", "blocked_direct_route",
        "pool_table", "paper_figure8_rolling", "paper_figure9_topspin",
        "paper_figure10_sidespin"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), required), names.end()) << required;
  }
}

class ShippedProblem : public testing::TestWithParam<std::string> {};

TEST_P(ShippedProblem, LoadsWithoutError) {
  const LoadResult r = load_problem(example_path(GetParam()));
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.problem->source, example_path(GetParam()));
  EXPECT_FALSE(r.problem->name.empty());
  EXPECT_FALSE(describe(*r.problem).empty());
}

// Each file records a shot that solves it; simulate it and check that it still does.
TEST_P(ShippedProblem, WitnessShotInItsHeaderReachesTheTarget) {
  const std::string text = read_text(example_path(GetParam()));
  const std::string mark = "# reachable, e.g. speed ";
  const std::size_t at = text.find(mark);
  ASSERT_NE(at, std::string::npos) << "no witness line in " << GetParam();
  physics::Shot shot;
  int cushions = -1;
  ASSERT_EQ(std::sscanf(text.c_str() + at + mark.size(),
                        "%lf m/s, aim %lf deg, k_T %lf, k_S %lf: lands %*f m from target after %d",
                        &shot.speed, &shot.aim_deg, &shot.topspin_k, &shot.sidespin_k, &cushions),
            5)
      << text.substr(at, text.find('\n', at) - at);
  const LoadResult r = parse_problem(text, GetParam());
  ASSERT_TRUE(r.ok()) << r.error;
  const Problem& p = *r.problem;
  EXPECT_EQ(check_shot(p.limits, shot), "");
  const physics::ShotResult outcome = physics::simulate(p.scene, p.cue_ball, shot);
  EXPECT_TRUE(reaches_target(p, outcome))
      << "status " << physics::to_string(outcome.status) << ", rests at ("
      << outcome.final_position.x << ", " << outcome.final_position.y << "), "
      << miss_distance(p, outcome) << " m from the target after " << outcome.cushion_hits
      << " cushions";
  EXPECT_EQ(outcome.cushion_hits, cushions);
  // Recorded to a few mm inside a 15-50 mm zone: flag a drift before it breaks.
  EXPECT_LT(miss_distance(p, outcome), 0.005);
  // A file with a pot: the witness makes it, striking the named ball first.
  if (p.pot) {
    EXPECT_TRUE(makes_pot(p, outcome))
        << p.pot->ball << " not in " << pocket_name(p.scene, p.pot->pocket);
    const std::string potting =
        "potting " + p.pot->ball + " in " + pocket_name(p.scene, p.pot->pocket);
    EXPECT_NE(text.substr(at, text.find('\n', at) - at).find(potting), std::string::npos)
        << "the witness line should say '" << potting << "'";
  }
  if (p.first_contact) {
    ASSERT_GT(outcome.first_contact, 0);
    EXPECT_TRUE(contact_allowed(*p.first_contact,
                                outcome.balls[static_cast<size_t>(outcome.first_contact)].name,
                                p.scene.balls))
        << outcome.balls[static_cast<size_t>(outcome.first_contact)].name << " first, not "
        << *p.first_contact;
  }
}

INSTANTIATE_TEST_SUITE_P(Problems, ShippedProblem, testing::ValuesIn(shipped_examples()),
                         [](const testing::TestParamInfo<std::string>& param) {
                           std::string name = param.param;
                           std::replace(name.begin(), name.end(), '/', '_');
                           return name;
                         });

TEST(ShippedProblems, PotExamplesHoldObjectBallsAndAPot) {
  int pots = 0;
  bool two_object_balls = false;
  for (const std::string& name : shipped_examples()) {
    if (name.rfind("pots/", 0) != 0) continue;
    const LoadResult r = load_problem(example_path(name));
    ASSERT_TRUE(r.ok()) << r.error;
    EXPECT_FALSE(r.problem->scene.balls.empty()) << name;
    EXPECT_TRUE(r.problem->pot.has_value()) << name;
    two_object_balls = two_object_balls || r.problem->scene.balls.size() >= 2;
    ++pots;
  }
  EXPECT_GE(pots, 3);
  EXPECT_TRUE(two_object_balls) << "a plant or kiss needs two object balls";
}

TEST(ShippedProblems, BlockedRouteHasNoClearStraightPath) {
  const LoadResult r = load_problem(example_path("blocked_direct_route"));
  ASSERT_TRUE(r.ok()) << r.error;
  const Problem& p = *r.problem;
  const double dx = p.target.x - p.cue_ball.x, dy = p.target.y - p.cue_ball.y;
  const double length2 = dx * dx + dy * dy;
  bool blocked = false;
  for (const physics::Vec2 o : p.scene.obstacles) {
    const double t =
        std::clamp(((o.x - p.cue_ball.x) * dx + (o.y - p.cue_ball.y) * dy) / length2, 0.0, 1.0);
    const double gap = std::hypot(p.cue_ball.x + t * dx - o.x, p.cue_ball.y + t * dy - o.y);
    blocked = blocked || gap < 2.0 * p.scene.radius();
  }
  EXPECT_TRUE(blocked);
  EXPECT_EQ(p.limits.cushions_min, 0);  // the direct route would be allowed if it were free
}

// ---- Defaults and values -------------------------------------------------------

TEST(ProblemDefaults, OmittedFieldsTakeTheirDocumentedDefaults) {
  const Problem p = parse_ok("cue_ball: [0.8, 0.5]\ntarget: [2.6, 1.2]\n");
  const physics::PocketPreset preset = *physics::pocket_preset("snooker");
  const std::vector<physics::Pocket> jawed =
      physics::jawed_pockets(3.569, 1.778, preset.corner, preset.middle);
  EXPECT_EQ(p.name, "test");  // stem of the source name
  EXPECT_EQ(p.source, "test.yaml");
  EXPECT_DOUBLE_EQ(p.scene.length, 3.569);
  EXPECT_DOUBLE_EQ(p.scene.width, 1.778);
  // Without table.pockets: the snooker preset's jawed pockets.
  ASSERT_EQ(p.scene.pockets.size(), jawed.size());
  for (std::size_t i = 0; i < jawed.size(); ++i) {
    EXPECT_DOUBLE_EQ(p.scene.pockets[i].centre.x, jawed[i].centre.x) << i;
    EXPECT_DOUBLE_EQ(p.scene.pockets[i].centre.y, jawed[i].centre.y) << i;
    ASSERT_TRUE(p.scene.pockets[i].jaws.has_value()) << i;
    EXPECT_DOUBLE_EQ(p.scene.pockets[i].jaws->shape.mouth, i == 1 || i == 4 ? preset.middle.mouth
                                                                            : preset.corner.mouth);
  }
  // With pocket_radius alone: the standard capture circles, as before.
  const Problem circles = parse_ok("table: {pocket_radius: 0.045}\ncue_ball: [0.8, 0.5]\ntarget: [2.6, 1.2]\n");
  const physics::Scene snooker = physics::snooker_scene();
  ASSERT_EQ(circles.scene.pockets.size(), snooker.pockets.size());
  for (std::size_t i = 0; i < snooker.pockets.size(); ++i) {
    EXPECT_DOUBLE_EQ(circles.scene.pockets[i].centre.x, snooker.pockets[i].centre.x) << i;
    EXPECT_DOUBLE_EQ(circles.scene.pockets[i].centre.y, snooker.pockets[i].centre.y) << i;
    EXPECT_DOUBLE_EQ(circles.scene.pockets[i].radius, kDefaultPocketRadius) << i;
    EXPECT_FALSE(circles.scene.pockets[i].jaws.has_value()) << i;
  }
  // Presets and a mapping whose missing keys take the snooker preset's values.
  const Problem pool = parse_ok("table: {pockets: pool}\ncue_ball: [0.8, 0.5]\ntarget: [2.6, 1.2]\n");
  EXPECT_DOUBLE_EQ(pool.scene.pockets[0].jaws->shape.mouth, physics::pocket_preset("pool")->corner.mouth);
  EXPECT_TRUE(parse_ok("table: {pockets: carom}\ncue_ball: [0.8, 0.5]\ntarget: [2.6, 1.2]\n").scene.pockets.empty());
  const Problem mixed = parse_ok(
      "table: {pockets: {corner: {mouth: 0.09}}}\ncue_ball: [0.8, 0.5]\ntarget: [2.6, 1.2]\n");
  EXPECT_DOUBLE_EQ(mixed.scene.pockets[0].jaws->shape.mouth, 0.09);
  EXPECT_DOUBLE_EQ(mixed.scene.pockets[0].jaws->shape.shelf, preset.corner.shelf);
  EXPECT_DOUBLE_EQ(mixed.scene.pockets[1].jaws->shape.mouth, preset.middle.mouth);
  const physics::CushionParams paper;
  EXPECT_DOUBLE_EQ(p.scene.ball_and_cushion.radius, paper.radius);
  EXPECT_DOUBLE_EQ(p.scene.ball_and_cushion.mass, paper.mass);
  EXPECT_DOUBLE_EQ(p.scene.ball_and_cushion.cushion_height, paper.cushion_height);
  EXPECT_DOUBLE_EQ(p.scene.ball_and_cushion.mu_cushion, paper.mu_cushion);
  EXPECT_DOUBLE_EQ(p.scene.ball_and_cushion.mu_table, paper.mu_table);
  EXPECT_DOUBLE_EQ(p.scene.ball_and_cushion.restitution, paper.restitution);
  const physics::ClothParams cloth;
  EXPECT_DOUBLE_EQ(p.scene.cloth.mu_slide, cloth.mu_slide);
  EXPECT_DOUBLE_EQ(p.scene.cloth.mu_roll, cloth.mu_roll);
  EXPECT_DOUBLE_EQ(p.scene.cloth.mu_spin, cloth.mu_spin);
  EXPECT_DOUBLE_EQ(p.scene.cloth.gravity, cloth.gravity);
  EXPECT_TRUE(p.scene.obstacles.empty());
  EXPECT_DOUBLE_EQ(p.tolerance, kDefaultTolerance);
  EXPECT_DOUBLE_EQ(p.limits.speed_min, 0.2);
  EXPECT_DOUBLE_EQ(p.limits.speed_max, 4.5);
  EXPECT_DOUBLE_EQ(p.limits.spin_max, 1.25);
  EXPECT_EQ(p.limits.aim.mode, AimMode::free);
  EXPECT_EQ(p.limits.cushions_min, 1);
  EXPECT_EQ(p.limits.cushions_max, 3);
}

TEST(ProblemValues, FullFormatExampleRoundTripsEveryValue) {
  const Problem p = parse_ok(kFullExample);
  EXPECT_EQ(p.name, "one-rail position");
  EXPECT_DOUBLE_EQ(p.scene.length, 3.569);
  EXPECT_DOUBLE_EQ(p.scene.width, 1.778);
  ASSERT_EQ(p.scene.pockets.size(), 6u);
  EXPECT_DOUBLE_EQ(p.scene.pockets[4].centre.x, 3.569 / 2);
  EXPECT_DOUBLE_EQ(p.scene.pockets[4].centre.y, 1.778);
  EXPECT_DOUBLE_EQ(p.scene.pockets[4].radius, 0.045);
  EXPECT_DOUBLE_EQ(p.scene.ball_and_cushion.radius, 0.02625);
  EXPECT_DOUBLE_EQ(p.scene.ball_and_cushion.mass, 0.1406);
  EXPECT_DOUBLE_EQ(p.scene.cloth.mu_slide, 0.212);
  EXPECT_DOUBLE_EQ(p.scene.ball_and_cushion.mu_table, 0.212);
  EXPECT_DOUBLE_EQ(p.scene.cloth.mu_roll, 0.01);
  EXPECT_DOUBLE_EQ(p.scene.cloth.mu_spin, 0.0117);
  EXPECT_DOUBLE_EQ(p.scene.ball_and_cushion.mu_cushion, 0.14);
  EXPECT_DOUBLE_EQ(p.scene.ball_and_cushion.restitution, 0.98);
  EXPECT_DOUBLE_EQ(p.scene.ball_and_cushion.cushion_height, 0.03675);
  EXPECT_DOUBLE_EQ(p.scene.cloth.gravity, 9.81);
  EXPECT_DOUBLE_EQ(p.cue_ball.x, 0.8);
  EXPECT_DOUBLE_EQ(p.cue_ball.y, 0.5);
  EXPECT_DOUBLE_EQ(p.target.x, 2.6);
  EXPECT_DOUBLE_EQ(p.target.y, 1.2);
  EXPECT_DOUBLE_EQ(p.tolerance, 0.02);
  ASSERT_EQ(p.scene.obstacles.size(), 1u);
  EXPECT_DOUBLE_EQ(p.scene.obstacles[0].x, 1.5);
  EXPECT_DOUBLE_EQ(p.scene.obstacles[0].y, 0.9);
  EXPECT_DOUBLE_EQ(p.limits.speed_min, 0.2);
  EXPECT_DOUBLE_EQ(p.limits.speed_max, 4.5);
  EXPECT_DOUBLE_EQ(p.limits.spin_max, 1.25);
  EXPECT_EQ(p.limits.aim.mode, AimMode::free);
  EXPECT_EQ(p.limits.cushions_min, 1);
  EXPECT_EQ(p.limits.cushions_max, 3);
}

TEST(ProblemValues, OtherValuesReachTheirSceneFields) {
  const Problem p = parse_ok(
      "table: {length: 3.0, width: 1.5, pocket_radius: 0.05}\n"
      "physics: {mu_slide: 0.2, mu_roll: 0.008, mu_spin: 0.03, mu_cushion: 0.12,\n"
      "          restitution: 0.9, cushion_height: 0.035, gravity: 9.8}\n"
      "cue_ball: [1, 1]\ntarget: [2, 1]\ntolerance: 0.01\n");
  EXPECT_DOUBLE_EQ(p.scene.pockets[2].centre.x, 3.0);
  EXPECT_DOUBLE_EQ(p.scene.pockets[5].centre.y, 1.5);
  EXPECT_DOUBLE_EQ(p.scene.pockets[1].radius, 0.05);
  EXPECT_DOUBLE_EQ(p.scene.cloth.mu_slide, 0.2);
  EXPECT_DOUBLE_EQ(p.scene.ball_and_cushion.mu_table, 0.2);
  EXPECT_DOUBLE_EQ(p.scene.cloth.mu_roll, 0.008);
  EXPECT_DOUBLE_EQ(p.scene.cloth.mu_spin, 0.03);
  EXPECT_DOUBLE_EQ(p.scene.ball_and_cushion.mu_cushion, 0.12);
  EXPECT_DOUBLE_EQ(p.scene.ball_and_cushion.restitution, 0.9);
  EXPECT_DOUBLE_EQ(p.scene.ball_and_cushion.cushion_height, 0.035);
  EXPECT_DOUBLE_EQ(p.scene.cloth.gravity, 9.8);
  EXPECT_DOUBLE_EQ(p.tolerance, 0.01);
}

TEST(ProblemValues, PoolBallGetsCushionHeightOfSevenFifthsItsRadius) {
  const Problem p = parse_ok(
      "table: {length: 2.54, width: 1.27}\nball: {radius: 0.028575, mass: 0.17}\n"
      "cue_ball: [0.6, 0.4]\ntarget: [1.9, 0.9]\n");
  EXPECT_NEAR(p.scene.ball_and_cushion.cushion_height, 1.4 * 0.028575, 1e-15);
  EXPECT_NEAR(p.scene.ball_and_cushion.cushion_height, 0.0400, 5e-6);
  EXPECT_NEAR(p.scene.ball_and_cushion.sin_theta(), 0.4, 1e-12);
}

TEST(ProblemValues, PocketsNoneLeavesAnOpenTable) {
  const Problem p = parse_ok("table: {pockets: none}\ncue_ball: [0.03, 0.03]\ntarget: [2, 1]\n");
  EXPECT_TRUE(p.scene.pockets.empty());
  EXPECT_DOUBLE_EQ(p.cue_ball.x, 0.03);  // a corner is cloth when there is no pocket
}

TEST(ProblemValues, SingleCushionCountMeansExactlyThatMany) {
  const Problem p = parse_ok("cue_ball: [1, 1]\ntarget: [2, 1]\nlimits: {cushions: 2}\n");
  EXPECT_EQ(p.limits.cushions_min, 2);
  EXPECT_EQ(p.limits.cushions_max, 2);
  const Problem none = parse_ok("cue_ball: [1, 1]\ntarget: [2, 1]\nlimits: {cushions: [0, 0]}\n");
  EXPECT_EQ(none.limits.cushions_max, 0);
}

TEST(ProblemValues, AimIsFreeFixedOrARange) {
  const Problem fixed = parse_ok("cue_ball: [1, 1]\ntarget: [2, 1]\nlimits: {aim_deg: -45}\n");
  EXPECT_EQ(fixed.limits.aim.mode, AimMode::fixed);
  EXPECT_DOUBLE_EQ(fixed.limits.aim.lo_deg, -45.0);
  EXPECT_DOUBLE_EQ(fixed.limits.aim.hi_deg, -45.0);
  const Problem range =
      parse_ok("cue_ball: [1, 1]\ntarget: [2, 1]\nlimits: {aim_deg: [170, 190]}\n");
  EXPECT_EQ(range.limits.aim.mode, AimMode::range);
  EXPECT_DOUBLE_EQ(range.limits.aim.lo_deg, 170.0);
  EXPECT_DOUBLE_EQ(range.limits.aim.hi_deg, 190.0);
}

TEST(ProblemValues, ExplicitNumberTagsAndExponentsAreNumbers) {
  const Problem p = parse_ok("cue_ball: [!!float 1, 1e0]\ntarget: [+2.0, .5]\n");
  EXPECT_DOUBLE_EQ(p.cue_ball.x, 1.0);
  EXPECT_DOUBLE_EQ(p.cue_ball.y, 1.0);
  EXPECT_DOUBLE_EQ(p.target.x, 2.0);
  EXPECT_DOUBLE_EQ(p.target.y, 0.5);
}

TEST(ProblemValues, CushionModelReachesTheScene) {
  EXPECT_EQ(parse_ok("cue_ball: [1, 1]\ntarget: [2, 1]\n").scene.ball_and_cushion.model,
            physics::CushionModel::mathavan_2010);
  const Problem p = parse_ok(
      "physics: {cushion_model: han_2005, mu_cushion: 0.3, restitution: 0.85}\n"
      "cue_ball: [1, 1]\ntarget: [2, 1]\n");
  EXPECT_EQ(p.scene.ball_and_cushion.model, physics::CushionModel::han_2005);
  // Mathavan's mu_w < tan(theta) (0.436 here) does not bind Han's model: 0.5 loads.
  const Problem high = parse_ok(
      "physics: {cushion_model: han_2005, mu_cushion: 0.5}\ncue_ball: [1, 1]\ntarget: [2, 1]\n");
  EXPECT_DOUBLE_EQ(high.scene.ball_and_cushion.mu_cushion, 0.5);
  EXPECT_EQ(parse_ok("physics: {cushion_model: mathavan_2010}\ncue_ball: [1, 1]\ntarget: [2, 1]\n")
                .scene.ball_and_cushion.model,
            physics::CushionModel::mathavan_2010);
  const Problem stronge = parse_ok(
      "physics: {cushion_model: stronge_compliant, eta_squared: 1.2}\n"
      "cue_ball: [1, 1]\ntarget: [2, 1]\n");
  EXPECT_EQ(stronge.scene.ball_and_cushion.model, physics::CushionModel::stronge_compliant);
  EXPECT_DOUBLE_EQ(stronge.scene.ball_and_cushion.eta_squared, 1.2);
}

TEST(ProblemValues, ObjectBallsPotAndBallPhysicsReachTheirFields) {
  const Problem p = parse_ok(
      "physics: {mu_ball: 0.06, ball_restitution: 0.93, ball_model: frictional_inelastic,\n"
      "          ball_friction: speed_dependent}\n"
      "balls:\n  red: [1.5, 0.9]\n  yellow: [2.0, 0.4]\n"
      "pot: {ball: yellow, pocket: bottom_right}\nfirst_contact: red\n"
      "cue_ball: [1, 1]\ntarget: [1.5, 0.9]\n");
  ASSERT_EQ(p.scene.balls.size(), 2u);
  EXPECT_EQ(p.scene.balls[0].name, "red");  // in the file's order
  EXPECT_DOUBLE_EQ(p.scene.balls[0].position.x, 1.5);
  EXPECT_DOUBLE_EQ(p.scene.balls[0].position.y, 0.9);
  EXPECT_EQ(p.scene.balls[1].name, "yellow");
  EXPECT_DOUBLE_EQ(p.scene.balls[1].position.y, 0.4);
  EXPECT_DOUBLE_EQ(p.scene.ball_contact.mu_ball, 0.06);
  EXPECT_DOUBLE_EQ(p.scene.ball_contact.restitution, 0.93);
  EXPECT_EQ(p.scene.ball_contact.model, physics::BallModel::frictional_inelastic);
  EXPECT_EQ(p.scene.ball_contact.friction, physics::BallFriction::speed_dependent);
  ASSERT_TRUE(p.pot.has_value());
  EXPECT_EQ(p.pot->ball, "yellow");
  EXPECT_EQ(p.pot->pocket, 2);
  EXPECT_EQ(pocket_name(p.scene, p.pot->pocket), "bottom_right");
  EXPECT_EQ(p.first_contact, "red");
  // The target may be where an object ball lies: the shot can move it away.
  EXPECT_DOUBLE_EQ(p.target.x, 1.5);
  const std::string text = describe(p);
  for (const char* part : {"object balls red, yellow", "frictional_inelastic",
                           "pot yellow into bottom_right", "first contact red"})
    EXPECT_NE(text.find(part), std::string::npos) << part << " not in:\n" << text;
  // Left out: no balls, the collision defaults of PHYSICS.md, no pot.
  const Problem bare = parse_ok(kPositions);
  EXPECT_TRUE(bare.scene.balls.empty());
  EXPECT_DOUBLE_EQ(bare.scene.ball_contact.mu_ball, 0.05);
  EXPECT_DOUBLE_EQ(bare.scene.ball_contact.restitution, 0.89);
  EXPECT_EQ(bare.scene.ball_contact.model, physics::BallModel::mathavan_2014);
  EXPECT_FALSE(bare.pot.has_value());
  EXPECT_FALSE(bare.first_contact.has_value());
}

TEST(ProblemValues, NextPotsAndNamedObstaclesReachTheirFields) {
  // One next pot: the target may be left out (position play on the black).
  const Problem one = parse_ok(
      "balls: {red3: [1.5, 0.9], black: [3.2, 0.9]}\npot: {ball: red3, pocket: top_left}\n"
      "next: {ball: black, pocket: top_right}\ncue_ball: [1, 1]\n");
  EXPECT_FALSE(one.has_target);
  ASSERT_EQ(one.next.size(), 1u);
  EXPECT_EQ(one.next[0].ball, "black");
  EXPECT_EQ(pocket_name(one.scene, one.next[0].pocket), "top_right");
  EXPECT_NE(describe(one).find("then black into top_right"), std::string::npos) << describe(one);
  // A list of three, in the order played; with a target as well.
  const Problem three = parse_ok(
      "balls: {red: [1.5, 0.9], yellow: [0.8, 0.4], green: [0.8, 1.4], brown: [0.8, 0.9]}\n"
      "pot: {ball: red, pocket: top_left}\n"
      "next:\n  - {ball: yellow, pocket: bottom_left}\n  - {ball: green, pocket: top_left}\n"
      "  - {ball: brown, pocket: bottom_middle}\ncue_ball: [2, 1]\ntarget: [2.5, 1]\n");
  EXPECT_TRUE(three.has_target);
  ASSERT_EQ(three.next.size(), 3u);
  EXPECT_EQ(three.next[2].ball, "brown");
  EXPECT_EQ(three.next[2].pocket, 1);
  // Obstacles named like balls.
  const Problem named = parse_ok(
      "obstacles: {pink: [2.7, 0.9], blue: [1.78, 0.9]}\ncue_ball: [1, 1]\ntarget: [2, 1.3]\n");
  ASSERT_EQ(named.scene.obstacles.size(), 2u);
  EXPECT_EQ(named.obstacle_names, (std::vector<std::string>{"pink", "blue"}));
  EXPECT_DOUBLE_EQ(named.scene.obstacles[1].x, 1.78);
}

TEST(ProblemShotChecks, APotIsMadeOnlyByItsBallInItsPocket) {
  const Problem p = parse_ok("balls: {red: [1.5, 0.9]}\npot: {ball: red, pocket: top_left}\n" +
                             std::string(kPositions));
  physics::ShotResult r;
  r.balls.resize(2);
  r.balls[0].name = "cue";
  r.balls[1].name = "red";
  EXPECT_FALSE(makes_pot(p, r));
  r.balls[1].pocketed = true;
  r.balls[1].pocket = 3;  // top_left
  EXPECT_TRUE(makes_pot(p, r));
  r.balls[1].pocket = 4;
  EXPECT_FALSE(makes_pot(p, r));
  r.balls[0].pocketed = true;  // the cue ball in top_left is not the red
  r.balls[0].pocket = 3;
  r.balls[1].pocketed = false;
  EXPECT_FALSE(makes_pot(p, r));
  EXPECT_FALSE(makes_pot(parse_ok(kPositions), r));
}

// validate() is the one check: a problem built in code gets the loader's rules.
TEST(ProblemValidate, PotAndFirstContactMustNameWhatIsOnTheTable) {
  Problem p = parse_ok("balls: {red: [1.5, 0.9]}\n" + std::string(kPositions));
  p.pot = Pot{"blue", 0};
  ASSERT_TRUE(validate(p).has_value());
  EXPECT_EQ(validate(p)->field, (physics::FieldPath{"pot", "ball"}));
  p.pot = Pot{"red", 6};
  ASSERT_TRUE(validate(p).has_value());
  EXPECT_EQ(validate(p)->field, (physics::FieldPath{"pot", "pocket"}));
  p.pot = Pot{"red", 5};
  EXPECT_FALSE(validate(p).has_value());
  p.first_contact = "cue";
  ASSERT_TRUE(validate(p).has_value());
  EXPECT_EQ(file_field(validate(p)->field), "first_contact");
  p.first_contact.reset();
  p.scene.balls.push_back({"blue", {1.5, 0.91}});
  ASSERT_TRUE(validate(p).has_value());
  EXPECT_EQ(file_message(*validate(p)), "balls.red overlaps balls.blue");
  p.scene.balls.pop_back();
  p.scene.ball_contact.restitution = 0.0;
  ASSERT_TRUE(validate(p).has_value());
  EXPECT_EQ(file_field(validate(p)->field), "physics.ball_restitution");
}

TEST(ProblemValues, KickRangesFirstContactClassesAndEscapes) {
  const Problem d = parse_ok(kPositions);
  EXPECT_EQ(d.limits.cushions_before_contact_min, 0);
  EXPECT_EQ(d.limits.cushions_before_contact_max, 3);
  EXPECT_EQ(d.limits.object_cushions_min, 0);
  EXPECT_EQ(d.limits.object_cushions_max, 2);
  const Problem p = parse_ok(
      "balls: {red1: [1.5, 0.9], red2: [2.0, 0.5], blue: [1.8, 1.2]}\nfirst_contact: any_red\n"
      "cue_ball: [1, 1]\nleave: safe\nlimits: {cushions_before_contact: [1, 2], object_cushions: 1}\n");
  EXPECT_EQ(p.limits.cushions_before_contact_min, 1);
  EXPECT_EQ(p.limits.cushions_before_contact_max, 2);
  EXPECT_EQ(p.limits.object_cushions_min, 1);
  EXPECT_EQ(p.limits.object_cushions_max, 1);
  EXPECT_TRUE(p.is_escape());
  EXPECT_FALSE(p.has_target);
  EXPECT_TRUE(p.leave_safe);
  EXPECT_EQ(*p.first_contact, "any_red");
  // After the contact an escape's cue ball may meet any number of cushions.
  EXPECT_EQ(p.limits.cushions_min, 0);
  EXPECT_GE(p.limits.cushions_max, 100);
}

// ---- Shots against a problem ---------------------------------------------------

// A class of first contact: striking a ball outside it is a foul; the cushions before the
// contact and the pot's ball's cushions are counted against their ranges.
TEST(ProblemShotChecks, ClassFirstContactFoulsAndKickCushionCounts) {
  Problem p = parse_ok(
      "balls: {red1: [1.5, 0.9], blue: [2.0, 0.5]}\nfirst_contact: any_red\ncue_ball: [1, 1]\n");
  physics::ShotResult r;
  r.status = physics::ShotStatus::rest;
  r.balls.resize(3);
  r.balls[0].name = "cue";
  r.balls[1].name = "red1";
  r.balls[2].name = "blue";
  physics::ShotEvent cushion;
  cushion.type = physics::EventType::cushion;
  physics::ShotEvent contact;
  contact.type = physics::EventType::ball_contact;
  r.balls[0].events = {cushion, contact, cushion};
  r.first_contact = 2;
  Verdict v = check_outcome(p, r);
  EXPECT_EQ(v.failure, Failure::first_contact);
  EXPECT_EQ(v.reason, "foul: first contact on blue (any_red asked for)");
  r.first_contact = 1;
  EXPECT_TRUE(check_outcome(p, r).solves()) << check_outcome(p, r).reason;
  EXPECT_EQ(cushions_before_contact(r), 1);
  p.limits.cushions_before_contact_max = 0;
  v = check_outcome(p, r);
  EXPECT_EQ(v.failure, Failure::cushions);
  EXPECT_NE(v.reason.find("1 cushion before it strikes red1"), std::string::npos) << v.reason;
  r.first_contact = -1;
  EXPECT_EQ(check_outcome(p, r).failure, Failure::first_contact);
  // A pot's ball off too many cushions.
  Problem q = parse_ok("balls: {red1: [1.5, 0.9]}\npot: {ball: red1, pocket: top_left}\n"
                       "limits: {object_cushions: [1, 1]}\ncue_ball: [1, 1]\n");
  r.first_contact = 1;
  r.balls[1].pocketed = true;
  r.balls[1].pocket = 3;
  r.balls[1].cushion_hits = 2;
  v = check_outcome(q, r);
  EXPECT_EQ(v.failure, Failure::cushions);
  EXPECT_NE(v.reason.find("red1 meets 2 cushions before it drops, outside the allowed 1"),
            std::string::npos)
      << v.reason;
  r.balls[1].cushion_hits = 1;
  EXPECT_TRUE(check_outcome(q, r).solves()) << check_outcome(q, r).reason;
}


// The planner's inner loops count outcomes with outcome_failure, which leaves the reason
// unwritten: it must name the same broken condition as check_outcome, for every kind.
TEST(ProblemShotChecks, OutcomeFailureNamesTheConditionCheckOutcomeNames) {
  const Problem p = parse_ok("balls: {red1: [1.5, 0.9], blue: [2.0, 0.5]}\n"
                             "pot: {ball: red1, pocket: top_left}\n" +
                             std::string(kPositions));
  physics::ShotResult r;
  r.balls.resize(3);
  r.balls[0].name = "cue";
  r.balls[1].name = "red1";
  r.balls[2].name = "blue";
  std::vector<Failure> seen;
  const auto expect_same = [&](Failure expected) {
    const Verdict v = check_outcome(p, r);
    EXPECT_EQ(v.failure, expected) << v.reason;
    EXPECT_EQ(outcome_failure(p, r), v.failure) << v.reason;
    EXPECT_EQ(v.failure == Failure::none, v.reason.empty()) << v.reason;
    seen.push_back(outcome_failure(p, r));
  };
  r.status = physics::ShotStatus::pocketed;
  expect_same(Failure::cue_ball_pocketed);
  r.status = physics::ShotStatus::hit_obstacle;
  r.balls[2].events.push_back({});
  r.balls[2].events.back().type = physics::EventType::obstacle;
  expect_same(Failure::obstacle);
  r.balls[2].events.clear();
  r.status = physics::ShotStatus::event_limit;
  expect_same(Failure::no_outcome);
  r.status = physics::ShotStatus::rest;
  r.first_contact = -1;
  expect_same(Failure::first_contact);
  r.first_contact = 2;
  expect_same(Failure::first_contact);
  r.first_contact = 1;
  expect_same(Failure::pot_missed);
  r.balls[1].jaw_hits = 1;  // rattled in the jaws
  expect_same(Failure::pot_missed);
  r.balls[1].pocketed = true;
  r.balls[1].pocket = 4;
  expect_same(Failure::wrong_pocket);
  r.balls[1].pocket = 3;  // top_left
  r.balls[2].pocketed = true;
  r.balls[2].pocket = 0;
  expect_same(Failure::other_ball_pocketed);
  r.balls[2].pocketed = false;
  r.cushion_hits = 5;  // the default limits allow 1 to 3
  expect_same(Failure::cushions);
  r.cushion_hits = 2;
  r.final_position = {2.5, 1.0};
  expect_same(Failure::off_target);
  r.final_position = {2.005, 1.0};
  expect_same(Failure::none);
  for (const Failure f : {Failure::no_outcome, Failure::obstacle, Failure::cue_ball_pocketed,
                          Failure::first_contact, Failure::pot_missed, Failure::wrong_pocket,
                          Failure::other_ball_pocketed, Failure::cushions, Failure::off_target,
                          Failure::none})
    EXPECT_NE(std::find(seen.begin(), seen.end(), f), seen.end()) << to_string(f);
  EXPECT_TRUE(pot_made(Failure::off_target));
  EXPECT_FALSE(pot_made(Failure::wrong_pocket));
}

TEST(ProblemShotChecks, LimitsBoundSpeedSpinAndAimModuloTurns) {
  Limits l;
  EXPECT_EQ(check_shot(l, {1.0, 10.0, 1.0, 0.0}), "");
  EXPECT_EQ(check_shot(l, {4.5, 10.0, 0.75, 1.0}), "");  // both bounds are inside
  EXPECT_NE(check_shot(l, {0.1, 10.0, 1.0, 0.0}), "");
  EXPECT_NE(check_shot(l, {5.0, 10.0, 1.0, 0.0}), "");
  EXPECT_NE(check_shot(l, {1.0, 10.0, 1.0, 1.0}), "");  // sqrt(2) > 1.25
  EXPECT_NE(check_shot(l, {1.0, NAN, 0.0, 0.0}), "");
  l.aim = {AimMode::range, 170.0, 190.0};
  EXPECT_EQ(check_shot(l, {1.0, 180.0, 0.0, 0.0}), "");
  EXPECT_EQ(check_shot(l, {1.0, -175.0, 0.0, 0.0}), "");  // = 185 deg
  EXPECT_NE(check_shot(l, {1.0, 0.0, 0.0, 0.0}), "");
  l.aim = {AimMode::fixed, -45.0, -45.0};
  EXPECT_EQ(check_shot(l, {1.0, 315.0, 0.0, 0.0}), "");
  EXPECT_NE(check_shot(l, {1.0, -44.0, 0.0, 0.0}), "");
}

TEST(ProblemShotChecks, OnlyARestWithinToleranceAfterAllowedCushionsReachesTheTarget) {
  Problem p = parse_ok("cue_ball: [1, 1]\ntarget: [2, 1]\ntolerance: 0.02\n");
  physics::ShotResult r;
  r.status = physics::ShotStatus::rest;
  r.final_position = {2.01, 1.01};
  r.cushion_hits = 1;
  EXPECT_NEAR(miss_distance(p, r), std::hypot(0.01, 0.01), 1e-12);
  EXPECT_TRUE(reaches_target(p, r));
  r.cushion_hits = 0;  // default limits ask for 1 to 3 cushions
  EXPECT_FALSE(reaches_target(p, r));
  r.cushion_hits = 4;
  EXPECT_FALSE(reaches_target(p, r));
  r.cushion_hits = 2;
  r.final_position = {2.03, 1.0};
  EXPECT_FALSE(reaches_target(p, r));
  r.final_position = {2.0, 1.0};
  r.status = physics::ShotStatus::pocketed;
  EXPECT_FALSE(reaches_target(p, r));
  EXPECT_TRUE(std::isinf(miss_distance(p, r)));
}

TEST(ProblemDescribe, SummaryGivesPositionsAndLimitsWithUnits) {
  const std::string text = describe(parse_ok(kFullExample));
  for (const char* part : {"one-rail position", "test.yaml", "3.569 x 1.778 m", "6 pockets",
                           "26.25 mm", "(0.8000, 0.5000) m", "(2.6000, 1.2000) m", "20 mm",
                           "1 obstacle", "0.2-4.5 m/s", "aim free", "1-3 cushions"})
    EXPECT_NE(text.find(part), std::string::npos) << part << " not in:\n" << text;
}

// ---- Bad input -----------------------------------------------------------------

struct BadInput {
  const char* name;
  const char* yaml;
  int line;           // expected line (0: the message has no line)
  const char* field;  // expected field
  const char* says;   // a phrase the message must contain
};

void PrintTo(const BadInput& c, std::ostream* os) { *os << c.name; }

class BadProblemFile : public testing::TestWithParam<BadInput> {};

TEST_P(BadProblemFile, ErrorNamesFileLineAndFieldWithoutThrowing) {
  const BadInput& c = GetParam();
  LoadResult r;
  ASSERT_NO_THROW(r = parse_problem(c.yaml, "bad.yaml"));
  ASSERT_FALSE(r.ok()) << "accepted:\n" << c.yaml;
  const std::string prefix = c.line > 0 ? "bad.yaml:" + std::to_string(c.line) + ": " +
                                              c.field + ": "
                                        : "bad.yaml: " + std::string(c.field) + ": ";
  EXPECT_EQ(r.error.substr(0, prefix.size()), prefix) << r.error;
  EXPECT_NE(r.error.find(c.says), std::string::npos) << r.error;
  EXPECT_EQ(r.error.find('\n'), std::string::npos) << "one line: " << r.error;
}

const BadInput kBadInputs[] = {
    {"UnknownTopLevelKey", "cue_ball: [1, 1]\ntarget: [2, 1]\ntolerence: 0.02\n", 3, "tolerence",
     "did you mean tolerance"},
    {"UnknownNestedKey", "table:\n  length: 3.5\n  widht: 1.7\ncue_ball: [1, 1]\ntarget: [2, 1]\n",
     3, "table.widht", "unknown key"},
    {"UnknownKeyInFlowMapping",
     "cue_ball: [1, 1]\ntarget: [2, 1]\nlimits: {speed: [1, 2], spn: 1}\n", 3, "limits.spn",
     "did you mean spin"},
    {"MappingWhereNumber", "cue_ball: [1, 1]\ntarget: [2, 1]\ntolerance: {a: 1}\n", 3, "tolerance",
     "must be a number, got a mapping"},
    {"NumberWherePoint", "cue_ball: 0.5\ntarget: [2, 1]\n", 1, "cue_ball", "got \"0.5\""},
    {"NumberWhereMapping", "ball: 0.03\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 1, "ball",
     "must be a mapping"},
    {"StringInsteadOfNumber", "cue_ball: [1, 1]\ntarget: [2, 1]\ntolerance: \"0.02\"\n", 3,
     "tolerance", "quoted string"},
    {"WordInsteadOfNumber", "cue_ball: [1, one]\ntarget: [2, 1]\n", 1, "cue_ball[1]",
     "must be a number"},
    {"BooleanInsteadOfNumber", "cue_ball: [1, 1]\ntarget: [2, 1]\nlimits:\n  spin: true\n", 4,
     "limits.spin", "must be a number"},
    {"HexNumber", "cue_ball: [1, 1]\ntarget: [2, 1]\nlimits: {spin: 0x1}\n", 3, "limits.spin",
     "must be a number"},
    {"NaN", "ball:\n  radius: .nan\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 2, "ball.radius",
     "finite"},
    {"PositiveInfinity", "cue_ball: [1, 1]\ntarget: [2, 1]\nlimits:\n  speed: [0.2, .inf]\n", 4,
     "limits.speed[1]", "finite"},
    {"NegativeInfinityInPoint", "cue_ball: [-.inf, 1]\ntarget: [2, 1]\n", 1, "cue_ball[0]",
     "finite"},
    {"OverflowingNumber", "cue_ball: [1e999, 1]\ntarget: [2, 1]\n", 1, "cue_ball[0]", "finite"},
    {"NegativeLength", "table:\n  length: -3.569\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 2,
     "table.length", "positive"},
    {"ZeroRadius", "ball: {radius: 0, mass: 0.1}\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 1,
     "ball.radius", "positive"},
    {"NegativePocketRadius", "table: {pocket_radius: -0.04}\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 1,
     "table.pocket_radius", "positive"},
    {"UnknownPocketsWord", "table:\n  pockets: six\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 2,
     "table.pockets", "must be none, standard, snooker, pool, carom or a mapping"},
    {"NarrowCornerMouth", "table:\n  pockets:\n    corner: {mouth: 0.05}\ncue_ball: [1, 1]\ntarget: [2, 1]\n",
     3, "table.pockets.corner.mouth", "0.05 m is narrower than a ball (0.0525 m)"},
    {"NegativeMiddleShelf",
     "table:\n  pockets:\n    middle:\n      shelf: -0.01\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 4,
     "table.pockets.middle.shelf", "must not be negative"},
    {"CrossingFacings", "table:\n  pockets: {corner: {wall_angle_deg: 40}}\ncue_ball: [1, 1]\ntarget: [2, 1]\n",
     2, "table.pockets.corner.wall_angle_deg", "facings cross"},
    {"NegativePointRadius",
     "table:\n  pockets: {middle: {point_radius: -0.001}}\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 2,
     "table.pockets.middle.point_radius", "must not be negative"},
    {"HoleTooSmall",
     "table:\n  pockets: {corner: {hole_radius: 0.03, wall_angle_deg: 0}}\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 2,
     "table.pockets.corner.hole_radius", "does not close the channel"},
    {"UnknownPocketShapeKey",
     "table:\n  pockets: {corner: {mouth_width: 0.09}}\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 2,
     "table.pockets.corner.mouth_width", "mouth"},
    {"PoolPresetTooSmallForBall",
     "table: {pockets: pool}\nball: {radius: 0.06}\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 1,
     "table.pockets", "narrower than a ball"},
    {"ZeroSlidingFriction", "physics:\n  mu_slide: 0\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 2,
     "physics.mu_slide", "positive"},
    {"RestitutionAboveOne",
     "cue_ball: [1, 1]\ntarget: [2, 1]\nphysics:\n  gravity: 9.81\n  restitution: 1.2\n", 5,
     "physics.restitution", "(0, 1]"},
    {"CushionBelowBallCentre",
     "physics: {cushion_height: 0.02}\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 1,
     "physics.cushion_height", "between radius and 2*radius"},
    {"CushionFrictionTooHigh", "physics: {mu_cushion: 0.5}\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 1,
     "physics.mu_cushion", "tan(theta)"},
    {"BallTooBigForTable", "ball: {radius: 1.0}\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 1,
     "ball.radius", "leaves no room for the ball on the table"},
    {"CueBallOffTable", "cue_ball: [0.01, 0.5]\ntarget: [2, 1]\n", 1, "cue_ball",
     "lies off the table"},
    {"TargetOffTable", "cue_ball: [1, 1]\ntarget:\n  - 2.0\n  - 1.77\n", 2, "target",
     "lies off the table"},
    {"CueBallInsideObstacle", "obstacles:\n  - [1.0, 1.0]\ncue_ball: [1.02, 1.0]\ntarget: [2, 1]\n",
     3, "cue_ball", "overlaps obstacles[0]"},
    {"TargetInsideObstacle", "obstacles: [[2.0, 1.0]]\ncue_ball: [1, 1]\ntarget: [2.03, 1.0]\n", 3,
     "target", "overlaps obstacles[0]"},
    {"ObstacleOffTable",
     "obstacles:\n  - [1.0, 1.0]\n  - [5.0, 1.0]\ncue_ball: [0.5, 0.5]\n"
     "target: [2, 1]\n",
     3, "obstacles[1]", "off the table"},
    {"ObstaclesOverlap",
     "obstacles:\n  - [1.0, 1.0]\n  - [1.03, 1.0]\ncue_ball: [0.5, 0.5]\n"
     "target: [2, 1]\n",
     3, "obstacles[1]", "overlaps obstacles[0]"},
    {"TargetInPocket", "cue_ball: [1, 1]\ntarget: [0.0, 0.0]\n", 2, "target",
     "lies inside the bottom_left pocket"},
    {"CueBallInMiddlePocket", "cue_ball: [1.7845, 1.79]\ntarget: [1, 1]\n", 1, "cue_ball",
     "lies inside the top_middle pocket"},
    {"PointOfThree", "cue_ball: [1, 1, 1]\ntarget: [2, 1]\n", 1, "cue_ball", "got 3 elements"},
    {"PointOfOne", "cue_ball: [1, 1]\ntarget: [2]\n", 2, "target", "got 1 element"},
    {"SpeedLimitsOfThree", "cue_ball: [1, 1]\ntarget: [2, 1]\nlimits:\n  speed: [1, 2, 3]\n", 4,
     "limits.speed", "[min, max]"},
    {"ObstaclesNotAList", "obstacles: [1.0, 1.0]\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 1,
     "obstacles[0]", "point [x, y]"},
    {"MissingCueBall", "# a comment line first\ntarget: [2, 1]\ntolerance: 0.02\n", 2, "cue_ball",
     "missing"},
    {"MissingTarget", "name: no target\ncue_ball: [1, 1]\n", 1, "target", "missing"},
    {"ZeroTolerance", "cue_ball: [1, 1]\ntarget: [2, 1]\ntolerance: 0\n", 3, "tolerance",
     "positive"},
    {"NegativeTolerance", "cue_ball: [1, 1]\ntarget: [2, 1]\ntolerance: -0.01\n", 3, "tolerance",
     "positive"},
    {"EmptyValue", "cue_ball: [1, 1]\ntarget: [2, 1]\ntolerance:\nlimits: {spin: 1}\n", 3,
     "tolerance", "got nothing"},
    {"SpeedLimitsReversed", "cue_ball: [1, 1]\ntarget: [2, 1]\nlimits:\n  speed: [3.0, 1.0]\n", 4,
     "limits.speed", "min must be below max"},
    {"SpeedLimitZero", "cue_ball: [1, 1]\ntarget: [2, 1]\nlimits:\n  speed: [0, 1.0]\n", 4,
     "limits.speed[0]", "positive"},
    {"SpinLimitNegative", "cue_ball: [1, 1]\ntarget: [2, 1]\nlimits:\n  spin: -1\n", 4,
     "limits.spin", "positive"},
    // What no cue can give (problems/stroke_ranges.hpp): a tip 1.2 R off centre, 50 m/s.
    {"SpinLimitBeyondTheMiscueLimit", "cue_ball: [1, 1]\ntarget: [2, 1]\nlimits:\n  spin: 3\n", 4,
     "limits.spin", "1.20 ball radii from the ball's centre"},
    {"SpeedLimitNoCueGives", "cue_ball: [1, 1]\ntarget: [2, 1]\nlimits:\n  speed: [0.2, 50]\n",
     4, "limits.speed[1]", "must be at most 20 m/s"},
    {"NonIntegerCushions", "cue_ball: [1, 1]\ntarget: [2, 1]\nlimits:\n  cushions: [1.5, 3]\n", 4,
     "limits.cushions[0]", "whole number"},
    {"NonIntegerCushionCount", "cue_ball: [1, 1]\ntarget: [2, 1]\nlimits:\n  cushions: 2.5\n", 4,
     "limits.cushions", "whole number"},
    {"NegativeCushions", "cue_ball: [1, 1]\ntarget: [2, 1]\nlimits:\n  cushions: [-1, 3]\n", 4,
     "limits.cushions[0]", "must lie in [0, 1000]"},
    {"CushionsReversed", "cue_ball: [1, 1]\ntarget: [2, 1]\nlimits:\n  cushions: [3, 1]\n", 4,
     "limits.cushions", "lo must not exceed hi"},
    {"AimRangeReversed", "cue_ball: [1, 1]\ntarget: [2, 1]\nlimits:\n  aim_deg: [30, 10]\n", 4,
     "limits.aim_deg", "lo < hi"},
    {"AimRangeOverATurn", "cue_ball: [1, 1]\ntarget: [2, 1]\nlimits:\n  aim_deg: [-200, 200]\n", 4,
     "limits.aim_deg", "lo + 360"},
    {"AimUnknownWord", "cue_ball: [1, 1]\ntarget: [2, 1]\nlimits:\n  aim_deg: any\n", 4,
     "limits.aim_deg", "free, an angle"},
    {"DuplicatedKey", "cue_ball: [1, 1]\ntarget: [2, 1]\ncue_ball: [1.2, 1]\n", 3, "cue_ball",
     "duplicated key (first given at line 1)"},
    {"DuplicatedKeyInFlowMapping",
     "cue_ball: [1, 1]\ntarget: [2, 1]\nball: {radius: 0.03, radius: 0.02}\n", 3, "ball.radius",
     "duplicated key"},
    {"EmptyName", "name: ''\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 1, "name", "must not be empty"},
    {"EmptyFile", "", 1, "(document)", "empty"},
    {"OnlyComments", "# nothing here\n# still nothing\n", 1, "(document)", "empty"},
    {"DocumentIsASequence", "- cue_ball\n- target\n", 1, "(document)", "got a sequence"},
    {"DocumentIsAScalar", "hello\n", 1, "(document)", "must be a mapping"},
    {"TwoDocuments", "cue_ball: [1, 1]\ntarget: [2, 1]\n---\ncue_ball: [1, 1]\n", 4, "(document)",
     "second YAML document"},
    {"UnclosedFlowSequence", "cue_ball: [1, 1\ntarget: [2, 1]\n", 2, "yaml",
     "end of sequence flow not found"},
    {"BadIndentation", "table:\n  length: 3.5\n width: 1.7\ncue_ball: [1, 1]\n", 3, "yaml",
     "column"},
    {"TabIndentation", "table:\n\tlength: 3.5\n", 2, "yaml", ""},
    // Object balls, the collision between balls, the pot.
    {"BallOffTable",
     "balls:\n  red: [1.5, 0.9]\n  blue: [5.0, 1.0]\ncue_ball: [1, 1]\n"
     "target: [2, 1]\n",
     3, "balls.blue", "lies off the table"},
    {"BallsOverlap",
     "balls: {red: [1.5, 0.9], blue: [1.52, 0.9]}\ncue_ball: [1, 1]\n"
     "target: [2, 1]\n",
     1, "balls.red", "overlaps balls.blue"},
    {"BallOnObstacle",
     "obstacles: [[1.5, 0.9]]\nballs:\n  red: [1.52, 0.9]\n"
     "cue_ball: [1, 1]\ntarget: [2, 1]\n",
     3, "balls.red", "overlaps obstacles[0]"},
    {"BallInMiddlePocket", "balls:\n  red: [1.7845, -0.01]\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 2,
     "balls.red", "lies inside the bottom_middle pocket"},
    {"BallNamedCue", "balls:\n  cue: [1.5, 0.9]\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 2,
     "balls.cue", "names the cue ball"},
    {"BallsAsAList", "balls: [[1.5, 0.9]]\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 1, "balls",
     "must be a mapping from each object ball's name to its centre [x, y]"},
    {"BallNotAPoint", "balls: {red: 1.5}\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 1, "balls.red",
     "point [x, y]"},
    {"BallTwice",
     "balls:\n  red: [1.5, 0.9]\n  red: [2.0, 0.9]\ncue_ball: [1, 1]\n"
     "target: [2, 1]\n",
     3, "balls.red", "duplicated key (first given at line 2)"},
    {"CueBallOnBall", "balls: {red: [1.02, 1.0]}\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 2,
     "cue_ball", "overlaps balls.red"},
    {"UnknownBallModel", "physics: {ball_model: mathavan_2041}\ncue_ball: [1, 1]\ntarget: [2, 1]\n",
     1, "physics.ball_model",
     "must be one of mathavan_2014, frictional_inelastic, got \"mathavan_2041\" (did you mean "
     "mathavan_2014?)"},
    {"StrongeStiffnessRatioOutOfRange",
     "physics: {cushion_model: stronge_compliant, eta_squared: 4}\ncue_ball: [1, 1]\n"
     "target: [2, 1]\n",
     1, "physics.eta_squared", "must lie in (0.875, 3.5) for cushion_model stronge_compliant"},
    {"UnknownCushionModel", "physics:\n  cushion_model: han_2006\ncue_ball: [1, 1]\ntarget: [2, 1]\n",
     2, "physics.cushion_model",
     "must be one of mathavan_2010, han_2005, stronge_compliant, got \"han_2006\" (did you mean "
     "han_2005?)"},
    {"HanRestitutionTooLow",
     "physics:\n  cushion_model: han_2005\n  restitution: 0.1\ncue_ball: [1, 1]\ntarget: [2, 1]\n",
     3, "physics.restitution", "is too small together with physics.mu_cushion for cushion_model han_2005"},
    {"UnknownBallFriction", "physics:\n  ball_friction: speed\ncue_ball: [1, 1]\ntarget: [2, 1]\n",
     2, "physics.ball_friction", "must be one of constant, speed_dependent"},
    {"BallRestitutionAboveOne",
     "physics:\n  ball_restitution: 1.2\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 2,
     "physics.ball_restitution", "must lie in (0, 1], got 1.2"},
    {"NegativeBallFriction", "physics: {mu_ball: -0.1}\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 1,
     "physics.mu_ball", "must not be negative"},
    {"BallFrictionTooHigh",
     "physics:\n  mu_slide: 0.2\n  mu_ball: 2.0\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 3,
     "physics.mu_ball", "times physics.mu_slide must be below 2/7"},
    {"PotOfAnUnknownBall",
     "balls: {red: [1.5, 0.9]}\npot: {ball: rde, pocket: top_left}\ncue_ball: [1, 1]\n"
     "target: [2, 1]\n",
     2, "pot.ball", "got \"rde\" (did you mean red?)"},
    {"PotIntoAnUnknownPocket",
     "balls: {red: [1.5, 0.9]}\npot:\n  ball: red\n  pocket: top_centre\ncue_ball: [1, 1]\n"
     "target: [2, 1]\n",
     4, "pot.pocket", "must be one of bottom_left, bottom_middle"},
    {"PotOnATableWithoutPockets",
     "table: {pockets: none}\nballs: {red: [1.5, 0.9]}\npot: {ball: red, pocket: top_left}\n"
     "cue_ball: [1, 1]\ntarget: [2, 1]\n",
     3, "pot.pocket", "the table has none (table.pockets: none)"},
    {"PotWithoutAPocket",
     "balls: {red: [1.5, 0.9]}\npot: {ball: red}\ncue_ball: [1, 1]\n"
     "target: [2, 1]\n",
     2, "pot.pocket", "missing"},
    {"PotUnknownKey",
     "balls: {red: [1.5, 0.9]}\npot: {ball: red, pocket: top_left, spin: 1}\ncue_ball: [1, 1]\n"
     "target: [2, 1]\n",
     2, "pot.spin", "unknown key; expected one of ball, pocket"},
    {"FirstContactUnknown",
     "balls: {red: [1.5, 0.9], blue: [2.0, 0.9]}\nfirst_contact: bleu\ncue_ball: [1, 1]\n"
     "target: [2, 1]\n",
     2, "first_contact",
     "must be the name of a ball in balls or a class of balls: red, blue, any_red, lowest, solids, "
     "stripes, any_colour, got \"bleu\" (did you "
     "mean blue?)"},
    {"CushionsBeforeContactBackwards",
     "limits: {cushions_before_contact: [3, 1]}\ncue_ball: [1.0, 1.0]\ntarget: [2.0, 1.0]\n", 1,
     "limits.cushions_before_contact", "min must not exceed max, got [3, 1]"},
    {"CushionsBeforeContactNegative",
     "limits: {cushions_before_contact: -1}\ncue_ball: [1.0, 1.0]\ntarget: [2.0, 1.0]\n", 1,
     "limits.cushions_before_contact", "must lie in [0, 1000], got -1"},
    {"ObjectCushionsNotWhole", "limits: {object_cushions: [0, 1.5]}\ncue_ball: [1.0, 1.0]\ntarget: [2.0, 1.0]\n",
     1, "limits.object_cushions[1]", "must be a whole number, got 1.5"},
    {"ObjectCushionsThreeNumbers",
     "limits: {object_cushions: [0, 1, 2]}\ncue_ball: [1.0, 1.0]\ntarget: [2.0, 1.0]\n", 1,
     "limits.object_cushions", "a count n or a range [min, max]"},
    {"FirstContactClassWithNoMember",
     "balls: {red: [1.5, 0.9]}\nfirst_contact: stripes\ncue_ball: [1, 1]\n", 2, "first_contact",
     "names the class stripes, but no ball in balls belongs to it"},
    {"LeaveNotSafe",
     "balls: {red: [1.5, 0.9]}\nfirst_contact: any_red\ncue_ball: [1, 1]\nleave: open\n", 4,
     "leave", "must be safe"},
    {"LeaveSafeWithATarget",
     "balls: {red: [1.5, 0.9]}\nfirst_contact: red\nleave: safe\ncue_ball: [1.0, 1.0]\ntarget: [2.0, 1.0]\n", 3,
     "leave", "applies to an escape only"},
    {"EscapeWithoutFirstContact", "balls: {red: [1.5, 0.9]}\ncue_ball: [1, 1]\n", 1, "target",
     "optional with a pot or a first_contact"},
    {"FirstContactWithoutBalls", "first_contact: red\ncue_ball: [1, 1]\ntarget: [2, 1]\n", 1,
     "first_contact", "names an object ball, but the file has no balls"},
    {"NextWithoutAPot",
     "balls: {red: [1.5, 0.9], black: [3.2, 0.9]}\nnext: {ball: black, pocket: top_right}\n"
     "cue_ball: [1, 1]\ntarget: [2, 1]\n",
     2, "next", "needs a pot"},
    {"NextOfAnUnknownBall",
     "balls: {red: [1.5, 0.9], black: [3.2, 0.9]}\npot: {ball: red, pocket: top_left}\n"
     "next: {ball: blak, pocket: top_right}\ncue_ball: [1, 1]\n",
     3, "next.ball", "got \"blak\" (did you mean black?)"},
    {"NextIntoAnUnknownPocket",
     "balls: {red: [1.5, 0.9], black: [3.2, 0.9]}\npot: {ball: red, pocket: top_left}\n"
     "next:\n  ball: black\n  pocket: top_centre\ncue_ball: [1, 1]\n",
     5, "next.pocket", "must be one of bottom_left"},
    {"NextIsThePotsBall",
     "balls: {red: [1.5, 0.9], black: [3.2, 0.9]}\npot: {ball: red, pocket: top_left}\n"
     "next: {ball: red, pocket: top_right}\ncue_ball: [1, 1]\n",
     3, "next.ball", "names the pot's own ball"},
    {"NextListTooLong",
     "balls: {red: [1.5, 0.9], a: [3.2, 0.9], b: [3.2, 0.5], c: [2.5, 0.5], d: [2.5, 1.5]}\n"
     "pot: {ball: red, pocket: top_left}\n"
     "next: [{ball: a, pocket: top_right}, {ball: b, pocket: top_right}, {ball: c, pocket: "
     "top_right}, {ball: d, pocket: top_right}]\ncue_ball: [1, 1]\n",
     3, "next", "must list 1 to 3 pots"},
    {"NextListRepeatsABall",
     "balls: {red: [1.5, 0.9], black: [3.2, 0.9]}\npot: {ball: red, pocket: top_left}\n"
     "next:\n  - {ball: black, pocket: top_right}\n  - {ball: black, pocket: bottom_right}\n"
     "cue_ball: [1, 1]\n",
     5, "next[1].ball", "a second time"},
    {"NextNotAPair",
     "balls: {red: [1.5, 0.9], black: [3.2, 0.9]}\npot: {ball: red, pocket: top_left}\n"
     "next: black\ncue_ball: [1, 1]\n",
     3, "next", "must be {ball: NAME, pocket: POCKET}"},
    {"NextUnknownKey",
     "balls: {red: [1.5, 0.9], black: [3.2, 0.9]}\npot: {ball: red, pocket: top_left}\n"
     "next: {ball: black, pocket: top_right, spin: 1}\ncue_ball: [1, 1]\n",
     3, "next.spin", "unknown key; expected one of ball, pocket"},
};

INSTANTIATE_TEST_SUITE_P(Problems, BadProblemFile, testing::ValuesIn(kBadInputs),
                         [](const testing::TestParamInfo<BadInput>& param) {
                           return std::string(param.param.name);
                         });

TEST(BadProblemFiles, UnreadableFileNamesItsPath) {
  const std::string path = "/nonexistent-dir/no_such_problem.yaml";
  LoadResult r;
  ASSERT_NO_THROW(r = load_problem(path));
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.error.rfind(path + ": cannot open", 0), 0u) << r.error;
}

TEST(BadProblemFiles, DirectoryIsNotAProblemFile) {
  const LoadResult r = load_problem(CUEPLAN_PROBLEMS_DIR);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.error.rfind(std::string(CUEPLAN_PROBLEMS_DIR) + ": is a directory", 0), 0u)
      << r.error;
}

TEST(BadProblemFiles, LoadedFileErrorsCarryThePath) {
  const fs::path path =
      fs::temp_directory_path() / ("cueplan_problem_test_" + std::to_string(::getpid()) + ".yaml");
  {
    std::ofstream out(path);
    out << "cue_ball: [1, 1]\ntarget: [2, 1]\ntolerance: .nan\n";
  }
  const LoadResult r = load_problem(path.string());
  fs::remove(path);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.error.rfind(path.string() + ":3: tolerance: ", 0), 0u) << r.error;
}

// Whatever a cut-off file holds, the loader answers with a problem or one error line.
TEST(BadProblemFiles, EveryPrefixOfAValidFileLoadsOrFailsCleanly) {
  const std::string text = kFullExample;
  for (std::size_t n = 0; n <= text.size(); ++n) {
    LoadResult r;
    ASSERT_NO_THROW(r = parse_problem(text.substr(0, n), "cut.yaml")) << n;
    EXPECT_NE(r.ok(), !r.error.empty()) << n;
    if (!r.ok()) {
      EXPECT_EQ(r.error.rfind("cut.yaml:", 0), 0u) << n << ": " << r.error;
    }
  }
}

}  // namespace
}  // namespace cueplan::problems
