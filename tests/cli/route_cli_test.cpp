// Tests of `cueplan route`, run as a separate process the way a user runs it: the
// stroke sequence it prints, its JSON keys, the drawing, its exit codes, and that each
// stroke it reports is the simulator's when played from where the previous one stopped.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.hpp"
#include "cueplan/physics/shot.hpp"
#include "cueplan/problems/problem.hpp"

namespace cli_test {

const char* const kScratchName = "cueplan_route_test_";

namespace {

namespace fs = std::filesystem;
namespace phys = cueplan::physics;
namespace prob = cueplan::problems;
using nlohmann::json;

std::string route_path(const std::string& stem) {
  return std::string(CUEPLAN_PROBLEMS_DIR) + "/routes/" + stem + ".yaml";
}

// A quick, reproducible search: the first route, a fixed seed, few noisy samples.
std::string route_command(const std::string& stem, const std::string& extra = {}) {
  return "route '" + route_path(stem) + "' --first --seed 5 --samples 40" +
         (extra.empty() ? "" : " " + extra);
}

json parsed(const ProcessResult& run) {
  try {
    return json::parse(run.out);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not JSON (" << e.what() << "):\n" << run.out << run.err;
    return json::object();
  }
}

TEST(Route, TextListsEachStrokeInPlayersTermsWithUnits) {
  const ProcessResult run = cueplan(route_command("two_stroke_speed_limit"));
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_EQ(run.err, "");
  for (const char* needle : {"status          solved", "strokes         2 (at most 2)",
                             "stroke 1        ", "stroke 2        ", "    shot        V = ",
                             " m/s at aim ", "    from        x = ", "    landing     x = ",
                             "    cushions    ", "    success     ", " noisy strokes stop ",
                             "in the target zone", " mm from the target", "route success   ",
                             "time            ", "search          sst with the directed sampler"})
    EXPECT_NE(run.out.find(needle), std::string::npos) << needle << "\n" << run.out;
}

// Each stroke of the JSON route, played with the simulator from where the previous one
// stopped, comes to rest where the JSON says, and the last in the target zone.
TEST(Route, JsonStrokesReplayStrokeByStroke) {
  const ProcessResult run = cueplan(route_command("two_stroke_blocked", "--json"));
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const json j = parsed(run);
  for (const char* key : {"status", "strokes", "time_s", "message", "time_to_first_solution_s"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j.value("status", ""), "solved");
  ASSERT_TRUE(j["strokes"].is_array());
  ASSERT_EQ(j["strokes"].size(), 2u);
  EXPECT_GT(j["time_s"].get<double>(), 0.0);

  const prob::Problem p = *prob::load_problem(route_path("two_stroke_blocked")).problem;
  phys::Vec2 at = p.cue_ball;
  for (const json& s : j["strokes"]) {
    for (const char* key : {"shot", "final_position", "start", "success_probability", "stroke",
                            "cushion_hits", "outcome"})
      ASSERT_TRUE(s.contains(key)) << key;
    EXPECT_NEAR(s["start"][0].get<double>(), at.x, 1e-9);
    EXPECT_NEAR(s["start"][1].get<double>(), at.y, 1e-9);
    const json& shot = s["shot"];
    const phys::Shot stroke{shot["speed"].get<double>(), shot["aim_deg"].get<double>(),
                            shot["topspin_k"].get<double>(), shot["sidespin_k"].get<double>()};
    const phys::ShotResult r = phys::simulate(p.scene, at, stroke);
    ASSERT_EQ(r.status, phys::ShotStatus::rest);
    EXPECT_NEAR(r.final_position.x, s["final_position"][0].get<double>(), 1e-6);
    EXPECT_NEAR(r.final_position.y, s["final_position"][1].get<double>(), 1e-6);
    at = r.final_position;
  }
  EXPECT_LE(std::hypot(at.x - p.target.x, at.y - p.target.y), p.tolerance);
}

TEST(Route, SvgDrawsEveryStroke) {
  const fs::path svg = scratch() / "route.svg";
  const ProcessResult run =
      cueplan(route_command("two_stroke_speed_limit", "--svg '" + svg.string() + "'"));
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  ASSERT_TRUE(fs::exists(svg));
  const std::string text = read_text(svg);
  EXPECT_NE(text.find("<svg"), std::string::npos);
  EXPECT_NE(text.find("route of 2 strokes"), std::string::npos);
  EXPECT_NE(run.out.find("drawing         " + svg.string()), std::string::npos);
}

// One stroke is too few here, and that is not a proof: exit 1, budget_exhausted.
TEST(Route, TooFewStrokesExitsOneWithBudgetExhausted) {
  const ProcessResult run =
      cueplan(route_command("two_stroke_speed_limit", "--max-strokes 1 --time 0.3 --json"));
  EXPECT_EQ(run.exit_code, 1) << run.out << run.err;
  const json j = parsed(run);
  EXPECT_EQ(j.value("status", ""), "budget_exhausted");
  EXPECT_TRUE(j["strokes"].empty());
}

// A ring of balls around the target: proven unreachable, exit 1.
TEST(Route, WalledOffTargetExitsOneAsUnreachable) {
  const fs::path file = scratch() / "ringed.yaml";
  write_text(file,
             "cue_ball: [0.9, 0.9]\ntarget: [2.7, 0.9]\nobstacles:\n"
             "  - [2.78, 0.9]\n  - [2.7566, 0.9566]\n  - [2.7, 0.98]\n  - [2.6434, 0.9566]\n"
             "  - [2.62, 0.9]\n  - [2.6434, 0.8434]\n  - [2.7, 0.82]\n  - [2.7566, 0.8434]\n");
  const ProcessResult run = cueplan("route '" + file.string() + "' --json");
  EXPECT_EQ(run.exit_code, 1) << run.out << run.err;
  const json j = parsed(run);
  EXPECT_EQ(j.value("status", ""), "unreachable");
  EXPECT_NE(j.value("message", "").find("wall it off"), std::string::npos);
}

struct BadInput {
  const char* name;
  const char* args;
  const char* message;  // part of the one line on stderr
};

class RouteBadInput : public testing::TestWithParam<BadInput> {};

TEST_P(RouteBadInput, ExitsTwoWithOneLineNamingTheProblem) {
  // A leading PROBLEM stands for a shipped route problem.
  const std::string given = GetParam().args;
  const std::string placeholder = "PROBLEM";
  std::string args = given;
  if (given.rfind(placeholder, 0) == 0) {
    args = "'";
    args.append(route_path("two_stroke_speed_limit")).append("'");
    args.append(given, placeholder.size(), std::string::npos);
  }
  const ProcessResult run = cueplan("route " + args);
  EXPECT_EQ(run.exit_code, 2) << run.out << run.err;
  EXPECT_EQ(run.out, "");
  EXPECT_EQ(count_of(run.err, "\n"), 1u) << run.err;
  EXPECT_NE(run.err.find(GetParam().message), std::string::npos) << run.err;
}

INSTANTIATE_TEST_SUITE_P(
    Route, RouteBadInput,
    testing::Values(BadInput{"UnknownPlanner", "PROBLEM --planner prm", "--planner"},
                    BadInput{"UnknownSampler", "PROBLEM --sampler smart", "--sampler"},
                    BadInput{"ZeroStrokes", "PROBLEM --max-strokes 0", "--max-strokes"},
                    BadInput{"NegativeTime", "PROBLEM --time -1", "--time"},
                    BadInput{"NegativeNoise", "PROBLEM --noise -1", "--noise"},
                    BadInput{"FewSteerEvaluations", "PROBLEM --steer-evaluations 3",
                             "--steer-evaluations"},
                    BadInput{"MissingProblemFile", "/nonexistent/problem.yaml",
                             "/nonexistent/problem.yaml"},
                    BadInput{"NoProblem", "--json", "PROBLEM"}),
    [](const testing::TestParamInfo<BadInput>& param) { return std::string(param.param.name); });

TEST(Route, HelpGivesUnitsAndDefaults) {
  const ProcessResult run = cueplan("route --help");
  EXPECT_EQ(run.exit_code, 0);
  for (const char* needle : {"--max-strokes", "--time", "SECONDS", "--planner", "sst", "rrt",
                             "kpiece1", "--sampler", "directed", "--json", "--svg", "m/s"})
    EXPECT_NE(run.out.find(needle), std::string::npos) << needle;
}

}  // namespace
}  // namespace cli_test
