// The problem file's cue (`cue:`) and cue elevation (`limits.elevation_deg`): presets,
// the end mass and the squirt it stands for, defaults, and errors that name the field.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cueplan/problems/problem.hpp"

namespace cueplan::problems {
namespace {

constexpr const char* kPositions = "cue_ball: [1.0, 1.0]\ntarget: [2.0, 1.0]\n";

Problem parse_ok(const std::string& text) {
  LoadResult r = parse_problem(text, "test.yaml");
  EXPECT_TRUE(r.ok()) << r.error;
  return r.ok() ? *r.problem : Problem{};
}

// The error's "FILE:LINE: FIELD: " prefix and a phrase of it.
void expect_error(const std::string& text, int line, const std::string& field,
                  const std::string& says) {
  LoadResult r = parse_problem(text, "bad.yaml");
  ASSERT_FALSE(r.ok()) << "accepted:\n" << text;
  const std::string prefix = "bad.yaml:" + std::to_string(line) + ": " + field + ": ";
  EXPECT_EQ(r.error.substr(0, prefix.size()), prefix) << r.error;
  EXPECT_NE(r.error.find(says), std::string::npos) << r.error;
}

TEST(ProblemCue, DefaultsToTheSnookerCueAndALevelCue) {
  const Problem p = parse_ok(kPositions);
  EXPECT_EQ(p.scene.cue.end_mass, physics::snooker_cue().end_mass);
  EXPECT_EQ(p.limits.elevation_min_deg, 0.0);
  EXPECT_EQ(p.limits.elevation_max_deg, 0.0);
}

TEST(ProblemCue, PresetsAndEndMass) {
  EXPECT_EQ(parse_ok(std::string("cue: pool\n") + kPositions).scene.cue.end_mass,
            physics::pool_cue().end_mass);
  EXPECT_EQ(parse_ok(std::string("cue: snooker\n") + kPositions).scene.cue.end_mass,
            physics::snooker_cue().end_mass);
  EXPECT_EQ(parse_ok(std::string("cue: {end_mass: 0.0075}\n") + kPositions).scene.cue.end_mass,
            0.0075);
}

TEST(ProblemCue, SquirtAtHalfTipBecomesTheEndMassThatGivesIt) {
  for (double deg : {0.5, 1.0, 2.0, 3.0}) {
    const Problem p = parse_ok("ball: {radius: 0.028575, mass: 0.17}\ncue: {squirt_deg_at_half_tip: " +
                               std::to_string(deg) + "}\n" + kPositions);
    const physics::Scene& s = p.scene;
    // Half a tip: the offset R/4, k_S = 0.625.
    EXPECT_NEAR(physics::squirt_angle_deg(s.cue, s.ball_and_cushion.mass, s.radius(), 0.625), deg,
                1e-9);
  }
}

TEST(ProblemCue, ShippedPoolProblemsUseThePoolCue) {
  for (const char* name : {"pool_table", "pots/only_draw", "pots/pool_straight_follow"}) {
    const LoadResult r =
        load_problem(std::string(CUEPLAN_PROBLEMS_DIR) + "/" + name + ".yaml");
    ASSERT_TRUE(r.ok()) << r.error;
    EXPECT_EQ(r.problem->scene.cue.end_mass, physics::pool_cue().end_mass) << name;
  }
}

TEST(ProblemCue, ElevationLimits) {
  const Problem p = parse_ok(std::string(kPositions) + "limits: {elevation_deg: [5, 30]}\n");
  EXPECT_EQ(p.limits.elevation_min_deg, 5.0);
  EXPECT_EQ(p.limits.elevation_max_deg, 30.0);
  physics::Shot shot{1.0, 0.0, 0.0, 0.3};
  EXPECT_NE(check_shot(p.limits, shot), "");  // level: below the least elevation
  shot.elevation_deg = 10.0;
  EXPECT_EQ(check_shot(p.limits, shot), "");
  shot.elevation_deg = 31.0;
  EXPECT_NE(check_shot(p.limits, shot).find("elevation 31 deg lies outside [5, 30] deg"),
            std::string::npos);
  EXPECT_NE(check_shot(parse_ok(kPositions).limits, shot), "");  // default [0, 0]
}

TEST(ProblemCue, BadCueAndElevationNameTheField) {
  expect_error(std::string("cue: carom\n") + kPositions, 1, "cue", "must be one of snooker, pool");
  expect_error(std::string("cue: {end_mass: -0.01}\n") + kPositions, 1, "cue.end_mass",
               "positive");
  expect_error(std::string("cue: {end_mass: 0.01, squirt_deg_at_half_tip: 1}\n") + kPositions, 1,
               "cue.squirt_deg_at_half_tip", "not both");
  expect_error(std::string("cue: {squirt_deg_at_half_tip: 30}\n") + kPositions, 1,
               "cue.squirt_deg_at_half_tip", "rigid cue");
  expect_error(std::string("cue: {mass: 0.01}\n") + kPositions, 1, "cue.mass", "unknown key");
  expect_error(std::string("cue: {}\n") + kPositions, 1, "cue", "needs end_mass");
  expect_error(std::string(kPositions) + "limits:\n  elevation_deg: [30, 10]\n", 4,
               "limits.elevation_deg", "0 <= min <= max < 90");
  expect_error(std::string(kPositions) + "limits:\n  elevation_deg: [0, 90]\n", 4,
               "limits.elevation_deg", "0 <= min <= max < 90");
  expect_error(std::string(kPositions) + "limits:\n  elevation_deg: [-5, 10]\n", 4,
               "limits.elevation_deg[0]", "must not be negative");
  expect_error(std::string(kPositions) + "limits:\n  elevation_deg: 10\n", 4,
               "limits.elevation_deg", "[min, max]");
}

}  // namespace
}  // namespace cueplan::problems
