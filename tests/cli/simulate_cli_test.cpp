// Tests of `cueplan simulate`, run as a separate process the way a user runs it: what it
// prints and draws, its exit codes, and that its numbers are the simulator's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_test_support.hpp"
#include "cueplan/physics/shot.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/problems/problem.hpp"

// The test files share their helpers (cli_test_support.hpp) by living in its namespace.
namespace cli_test {

const char* const kScratchName = "cueplan_simulate_test_";

namespace {

namespace fs = std::filesystem;
namespace phys = cueplan::physics;
namespace prob = cueplan::problems;
using nlohmann::json;

// The simulator called directly, with the command's defaults (exact method, accuracy
// 1e-9, 200 events).
phys::ShotResult library_shot(const prob::Problem& p, const phys::Shot& shot,
                              const phys::SimulationOptions& options = {}) {
  return phys::simulate(p.scene, p.cue_ball, shot, options);
}

std::string g6(double value, const char* unit) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g %s", value, unit);
  return buf;
}

// The header of `simulate --batch`'s output.
constexpr const char* kBatchHeader =
    "speed,aim_deg,topspin_k,sidespin_k,final_x,final_y,cushion_hits,pocketed,hit_obstacle,"
    "duration,miss_distance,reaches_target,status,message,first_contact,pocketed_balls";

// The shot the one-rail problem file records as solving it.
constexpr const char* kOneRailShot = "--speed 1.002 --aim -60.36 --topspin-k 0.8 --sidespin-k 0";
const phys::Shot kOneRail{1.002, -60.36, 0.8, 0.0};

std::string one_rail_command(const std::string& extra = {}) {
  return "simulate '" + problem_path("one_rail_position") + "' " + kOneRailShot +
         (extra.empty() ? "" : " " + extra);
}

// ---------------------------------------------------------------------------
// text and JSON

TEST(Simulate, SpelledOutCommandPrintsFinalPositionAndEventsWithUnits) {
  const ProcessResult run = cueplan(one_rail_command());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "");
  const phys::ShotResult expected = library_shot(shipped("one_rail_position"), kOneRail);
  ASSERT_EQ(expected.status, phys::ShotStatus::rest);
  for (const std::string& needle :
       {std::string("one-rail position"), std::string("final position"),
        "x = " + g6(expected.final_position.x, "m"), "y = " + g6(expected.final_position.y, "m"),
        g6(expected.duration, "s"), std::string("cushion hits    1"),
        std::string("status          rest"), std::string("pocketed        no"),
        std::string("hit obstacle    no"), std::string("miss distance"),
        std::string("inside the target zone"), std::string("tolerance 0.02 m"),
        std::string("t (s)"), std::string("x (m)"), std::string("v (m/s)"), std::string("m/s"),
        std::string("exact")})
    EXPECT_NE(run.out.find(needle), std::string::npos) << "missing '" << needle << "' in\n"
                                                       << run.out;
  // One table row per event, in order, named as the library names them.
  const std::vector<std::string> lines = lines_of(run.out);
  size_t row = 0;
  for (const std::string& line : lines) {
    if (row < expected.events.size() &&
        line.find(std::string(" ") + phys::to_string(expected.events[row].type) + " ") !=
            std::string::npos &&
        line.rfind("  ", 0) == 0)
      ++row;
  }
  EXPECT_EQ(row, expected.events.size()) << run.out;
  EXPECT_NE(run.out.find("cushion y = 0, normal speed"), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("warning"), std::string::npos);
}

TEST(Simulate, JsonEqualsAnIndependentLibrarySimulation) {
  const ProcessResult run = cueplan(one_rail_command("--json"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);
  const prob::Problem problem = shipped("one_rail_position");
  const phys::ShotResult expected = library_shot(problem, kOneRail);

  // The same code on the same input: equal to the last bits (JSON keeps 17 digits).
  EXPECT_EQ(j.at("status"), "rest");
  EXPECT_DOUBLE_EQ(j.at("final_position")[0].get<double>(), expected.final_position.x);
  EXPECT_DOUBLE_EQ(j.at("final_position")[1].get<double>(), expected.final_position.y);
  EXPECT_DOUBLE_EQ(j.at("duration").get<double>(), expected.duration);
  EXPECT_EQ(j.at("cushion_hits").get<int>(), expected.cushion_hits);
  EXPECT_EQ(j.at("pocketed").get<bool>(), expected.status == phys::ShotStatus::pocketed);
  EXPECT_EQ(j.at("hit_obstacle").get<bool>(), expected.status == phys::ShotStatus::hit_obstacle);
  ASSERT_EQ(j.at("events").size(), expected.events.size());
  for (size_t i = 0; i < expected.events.size(); ++i) {
    const json& e = j["events"][i];
    EXPECT_EQ(e.at("type"), phys::to_string(expected.events[i].type)) << i;
    EXPECT_DOUBLE_EQ(e.at("time").get<double>(), expected.events[i].time) << i;
    EXPECT_DOUBLE_EQ(e.at("position")[0].get<double>(), expected.events[i].position.x) << i;
    EXPECT_DOUBLE_EQ(e.at("position")[1].get<double>(), expected.events[i].position.y) << i;
  }
  EXPECT_EQ(j.at("path").size(), expected.path.size());

  // Against the problem: the recorded shot solves it.
  EXPECT_EQ(j.at("problem").at("name"), problem.name);
  EXPECT_NEAR(j.at("miss_distance").get<double>(), prob::miss_distance(problem, expected), 1e-15);
  EXPECT_TRUE(j.at("in_target_zone").get<bool>());
  EXPECT_TRUE(j.at("reaches_target").get<bool>());
  EXPECT_TRUE(j.at("within_limits").get<bool>());
  EXPECT_EQ(j.at("method"), "exact");
  EXPECT_EQ(j.at("shot").at("aim_deg").get<double>(), -60.36);
  EXPECT_EQ(j.at("units").at("position"), "m");
}

// --samples N: the stroke's success under the planner's noise, with its 95 % Wilson
// interval, as the library estimates it for the same seed; without noise every stroke
// is the nominal one, which lands, so p = 1 and the lower bound is N / (N + z^2).
TEST(Simulate, SamplesEstimateTheSuccessWithItsInterval) {
  const prob::Problem problem = shipped("one_rail_position");
  const ProcessResult run = cueplan(one_rail_command("--samples 120 --seed 3 --json"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);
  const cueplan::planner::Success expected = cueplan::planner::estimate_success(
      problem, kOneRail, cueplan::planner::NoiseModel{}, 120, 3, phys::SimulationOptions{});
  const json& success = j.at("success");
  EXPECT_FALSE(success.contains("pot"));
  EXPECT_EQ(success.at("both"), success.at("position"));
  EXPECT_EQ(success.at("both").at("samples").get<int>(), 120);
  EXPECT_EQ(success.at("both").at("p").get<double>(), expected.both.p);
  EXPECT_EQ(success.at("both").at("low").get<double>(), expected.both.low);
  EXPECT_EQ(success.at("both").at("high").get<double>(), expected.both.high);
  EXPECT_GT(expected.both.p, 0.0);
  EXPECT_LT(expected.both.p, 1.0);
  EXPECT_EQ(j.at("noise").at("seed").get<int>(), 3);

  const ProcessResult still = cueplan(one_rail_command("--samples 40 --noise 0 --json"), "still");
  ASSERT_EQ(still.exit_code, 0) << still.err;
  const json still_json = json::parse(still.out);
  const json& perfect = still_json.at("success").at("both");
  const double z2 = 1.959963984540054 * 1.959963984540054;
  EXPECT_EQ(perfect.at("p").get<double>(), 1.0);
  EXPECT_NEAR(perfect.at("low").get<double>(), 40.0 / (40.0 + z2), 1e-12);
  EXPECT_EQ(perfect.at("high").get<double>(), 1.0);

  const ProcessResult text = cueplan(one_rail_command("--samples 120 --seed 3"), "text");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("success         "), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("(95 % interval "), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("of 120 noisy strokes solve the problem"), std::string::npos) << text.out;
}

// A table with object balls: a cut pots the red into the bottom-left corner, the yellow
// is never touched.
constexpr const char* kPotProblem =
    "name: cut into the corner\n"
    "balls: {red: [0.25, 0.25], yellow: [2.0, 1.2]}\n"
    "pot: {ball: red, pocket: bottom_left}\n"
    "cue_ball: [1.0, 0.5]\ntarget: [2.0, 1.0]\n";
constexpr const char* kPotShot = "--speed 2 --aim 196.63 --topspin-k 1";

TEST(SimulateBalls, JsonDescribesEveryBallAsTheLibraryDoes) {
  const fs::path file = scratch() / "pot.yaml";
  write_text(file, kPotProblem);
  const ProcessResult run =
      cueplan("simulate '" + file.string() + "' " + kPotShot + " --json", "pot_json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);
  const prob::LoadResult loaded = prob::load_problem(file.string());
  ASSERT_TRUE(loaded.ok()) << loaded.error;
  const phys::ShotResult expected = library_shot(*loaded.problem, {2.0, 196.63, 1.0, 0.0});
  ASSERT_EQ(expected.balls.size(), 3u);
  ASSERT_TRUE(expected.balls[1].pocketed);  // the case is what it says
  EXPECT_EQ(j.at("first_contact"), "red");
  const json& balls = j.at("balls");
  ASSERT_EQ(balls.size(), 3u);
  for (size_t k = 0; k < balls.size(); ++k) {
    const phys::BallOutcome& b = expected.balls[k];
    const json& e = balls[k];
    EXPECT_EQ(e.at("name"), b.name);
    EXPECT_DOUBLE_EQ(e.at("final_position")[0].get<double>(), b.final_position.x) << b.name;
    EXPECT_DOUBLE_EQ(e.at("final_position")[1].get<double>(), b.final_position.y) << b.name;
    EXPECT_EQ(e.at("pocketed").get<bool>(), b.pocketed) << b.name;
    EXPECT_EQ(e.at("cushion_hits").get<int>(), b.cushion_hits) << b.name;
    ASSERT_EQ(e.at("events").size(), b.events.size()) << b.name;
    for (size_t i = 0; i < b.events.size(); ++i)
      EXPECT_EQ(e["events"][i].at("type"), phys::to_string(b.events[i].type)) << b.name << i;
  }
  EXPECT_EQ(balls[0].at("name"), "cue");
  EXPECT_EQ(balls[1].at("pocket"), "bottom_left");
  EXPECT_TRUE(balls[0].at("pocket").is_null());
  EXPECT_EQ(balls[1].at("events")[0].at("type"), "ball_contact");
  EXPECT_EQ(balls[1].at("events")[0].at("ball"), "cue");
  EXPECT_GT(balls[1].at("events")[0].at("impulse").get<double>(), 0.0);
  // The top-level keys still describe the cue ball.
  EXPECT_EQ(j.at("events").size(), expected.events.size());
  EXPECT_DOUBLE_EQ(j.at("final_position")[0].get<double>(), expected.final_position.x);
  EXPECT_EQ(j.at("status"), "rest");
}

// ---------------------------------------------------------------------------
// --trace

constexpr const char* kTraceHeader =
    "t_s,ball,x_m,y_m,vx_mps,vy_mps,wx_radps,wy_radps,wz_radps,motion,event";

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> cells(1);
  for (char ch : line) {
    if (ch == ',')
      cells.emplace_back();
    else
      cells.back() += ch;
  }
  return cells;
}

TEST(SimulateTrace, CsvHasEveryBallOnTheGridAndAtItsEvents) {
  const fs::path file = scratch() / "pot_trace.yaml";
  write_text(file, kPotProblem);
  const ProcessResult run =
      cueplan("simulate '" + file.string() + "' " + kPotShot + " --trace 0.05", "pot_trace");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::vector<std::string> lines = lines_of(run.out);
  ASSERT_GT(lines.size(), 2u);
  EXPECT_EQ(lines[0], kTraceHeader);
  const prob::LoadResult loaded = prob::load_problem(file.string());
  ASSERT_TRUE(loaded.ok()) << loaded.error;
  const phys::ShotResult expected = library_shot(*loaded.problem, {2.0, 196.63, 1.0, 0.0});
  // Each ball's event rows are its events, in order, with their states.
  std::vector<size_t> next(expected.balls.size(), 0);
  size_t grid_rows = 0;
  double last_t = 0.0;
  for (size_t i = 1; i < lines.size(); ++i) {
    const std::vector<std::string> cells = split_csv(lines[i]);
    ASSERT_EQ(cells.size(), 11u) << lines[i];
    const double t = std::stod(cells[0]);
    EXPECT_GE(t, last_t);
    last_t = t;
    size_t k = 0;
    while (k < expected.balls.size() && expected.balls[k].name != cells[1]) ++k;
    ASSERT_LT(k, expected.balls.size()) << lines[i];
    if (cells[10].empty()) {
      ++grid_rows;
      EXPECT_NEAR(t / 0.05, std::round(t / 0.05), 1e-9) << lines[i];
      continue;
    }
    ASSERT_LT(next[k], expected.balls[k].events.size()) << lines[i];
    const phys::ShotEvent& e = expected.balls[k].events[next[k]++];
    EXPECT_EQ(cells[10], phys::to_string(e.type));
    EXPECT_NEAR(t, e.time, 1e-12);
    EXPECT_NEAR(std::stod(cells[2]), e.position.x, 1e-9);
    EXPECT_NEAR(std::stod(cells[3]), e.position.y, 1e-9);
    EXPECT_NEAR(std::stod(cells[4]), e.velocity.x, 1e-9);
    EXPECT_NEAR(std::stod(cells[5]), e.velocity.y, 1e-9);
    EXPECT_NEAR(std::stod(cells[8]), e.spin.z, 1e-9);
  }
  for (size_t k = 0; k < expected.balls.size(); ++k)
    EXPECT_EQ(next[k], expected.balls[k].events.size()) << expected.balls[k].name;
  EXPECT_GT(grid_rows, 3 * static_cast<size_t>(expected.duration / 0.05) / 2);
}

TEST(SimulateTrace, JsonReportCarriesTheTrace) {
  const ProcessResult run = cueplan(one_rail_command("--json --trace 0.1"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);
  EXPECT_EQ(j.at("status"), "rest");  // the report is still there
  EXPECT_EQ(j.at("cushion_model"), "mathavan_2010");
  const json& trace = j.at("trace");
  EXPECT_DOUBLE_EQ(trace.at("interval").get<double>(), 0.1);
  const phys::ShotResult expected = library_shot(shipped("one_rail_position"), kOneRail);
  size_t events = 0;
  for (const json& row : trace.at("samples")) {
    if (row.at("event").is_null()) continue;
    const phys::ShotEvent& e = expected.events.at(events++);
    EXPECT_EQ(row.at("event"), phys::to_string(e.type));
    EXPECT_NEAR(row.at("position")[0].get<double>(), e.position.x, 1e-9);
    EXPECT_NEAR(row.at("velocity")[1].get<double>(), e.velocity.y, 1e-9);
  }
  EXPECT_EQ(events, expected.events.size());
  EXPECT_EQ(trace.at("samples").size(),
            expected.events.size() + static_cast<size_t>(std::floor(expected.duration / 0.1)) + 1 -
                1 /* the strike replaces the grid row at t = 0 */);
}

TEST(SimulateCushionModel, HanSceneIsSimulatedAndNamed) {
  const fs::path file = scratch() / "han.yaml";
  write_text(file, "physics: {cushion_model: han_2005}\ncue_ball: [0.8, 0.5]\ntarget: [2.6, 1.2]\n");
  const ProcessResult run =
      cueplan("simulate '" + file.string() + "' --speed 1.5 --aim 30 --json --method table", "han");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "");  // no impact table is built for a closed-form model
  const json j = json::parse(run.out);
  EXPECT_EQ(j.at("cushion_model"), "han_2005");
  EXPECT_EQ(j.at("method"), "closed_form");
  const prob::LoadResult loaded = prob::load_problem(file.string());
  ASSERT_TRUE(loaded.ok()) << loaded.error;
  const phys::ShotResult expected = library_shot(*loaded.problem, {1.5, 30.0, 0.0, 0.0});
  EXPECT_DOUBLE_EQ(j.at("final_position")[0].get<double>(), expected.final_position.x);
  EXPECT_DOUBLE_EQ(j.at("final_position")[1].get<double>(), expected.final_position.y);
}

TEST(SimulateBalls, TextAndBatchNameTheFirstContactAndThePots) {
  const fs::path file = scratch() / "pot.yaml";
  write_text(file, kPotProblem);
  const ProcessResult text = cueplan("simulate '" + file.string() + "' " + kPotShot, "pot_text");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  for (const char* needle :
       {"first contact   red", "balls           3 (the cue ball first)", "yes, bottom_left",
        "events of red", "ball red, approach", "pocket 0 (bottom_left)"})
    EXPECT_NE(text.out.find(needle), std::string::npos) << needle << " not in\n" << text.out;
  EXPECT_EQ(text.out.find("events of yellow"), std::string::npos) << "yellow never moved";

  const fs::path input = scratch() / "pot_shots.csv";
  write_text(input, "speed,aim_deg,topspin_k,sidespin_k\n2,196.63,1,0\n1,90,0,0\n");
  const ProcessResult batch =
      cueplan("simulate '" + file.string() + "' --batch '" + input.string() + "'", "pot_batch");
  ASSERT_EQ(batch.exit_code, 0) << batch.err;
  EXPECT_EQ(lines_of(batch.out).at(0), kBatchHeader);
  const auto rows = csv_rows(batch.out);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("first_contact"), "red");
  EXPECT_EQ(rows[0].at("pocketed_balls"), "red:bottom_left");
  EXPECT_EQ(rows[1].at("first_contact"), "");
  EXPECT_EQ(rows[1].at("pocketed_balls"), "");
}

// The paper scheme reaches the simulator too, and its answer is close to the exact one.
TEST(Simulate, PaperMethodIsTheLibrarysPaperMethod) {
  const ProcessResult run = cueplan(one_rail_command("--method paper --json"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);
  phys::SimulationOptions options;
  options.impact_method = phys::ImpactMethod::paper;
  const prob::Problem problem = shipped("one_rail_position");
  const phys::ShotResult paper = library_shot(problem, kOneRail, options);
  const phys::ShotResult exact = library_shot(problem, kOneRail);
  EXPECT_EQ(j.at("method"), "paper");
  EXPECT_DOUBLE_EQ(j.at("final_position")[0].get<double>(), paper.final_position.x);
  EXPECT_DOUBLE_EQ(j.at("final_position")[1].get<double>(), paper.final_position.y);
  EXPECT_NEAR(paper.final_position.x, exact.final_position.x, 0.01);  // m, first-order scheme
}

TEST(Simulate, PocketedShotReportsThePocket) {
  // Played straight at the middle pocket beyond the target, too fast to stop short.
  const std::string args =
      "simulate '" + problem_path("near_pocket") + "' --speed 0.7 --aim -56.84 --topspin-k 1";
  const ProcessResult text = cueplan(args);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("status          pocketed"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("pocketed        yes"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("did not come to rest"), std::string::npos) << text.out;

  const ProcessResult run = cueplan(args + " --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);
  EXPECT_EQ(j.at("status"), "pocketed");
  EXPECT_TRUE(j.at("pocketed").get<bool>());
  EXPECT_FALSE(j.at("hit_obstacle").get<bool>());
  EXPECT_TRUE(j.at("miss_distance").is_null());
  EXPECT_FALSE(j.at("reaches_target").get<bool>());
  EXPECT_EQ(j.at("events").back().at("type"), "pocket");
  EXPECT_EQ(j.at("events").back().at("pocket").get<int>(), 1);  // the bottom middle pocket
}

TEST(Simulate, ObstacleHitReportsTheObstacle) {
  // Straight at the wall of balls across the direct route.
  const std::string args =
      "simulate '" + problem_path("blocked_direct_route") + "' --speed 1.5 --aim 0";
  const ProcessResult text = cueplan(args);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("status          hit_obstacle"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("hit obstacle    yes"), std::string::npos) << text.out;

  const ProcessResult run = cueplan(args + " --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);
  EXPECT_EQ(j.at("status"), "hit_obstacle");
  EXPECT_TRUE(j.at("hit_obstacle").get<bool>());
  EXPECT_FALSE(j.at("pocketed").get<bool>());
  EXPECT_EQ(j.at("events").back().at("obstacle").get<int>(), 1);  // the middle ball of three
  // It stops touching that ball: centres 2R apart.
  const double gap = std::hypot(j["final_position"][0].get<double>() - 1.8,
                                j["final_position"][1].get<double>() - 0.9);
  EXPECT_NEAR(gap, 2.0 * 0.02625, 1e-9);
}

TEST(Simulate, AboveTheRigidLimitIsSimulatedAndFlagged) {
  const std::string args = "simulate '" + problem_path("one_rail_position") +
                           "' --speed 4.5 --aim -80 --topspin-k -1 --sidespin-k 0.5";
  const ProcessResult text = cueplan(args);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("warning: "), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("2.5 m/s"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("above the rigid-cushion limit"), std::string::npos) << text.out;

  const ProcessResult run = cueplan(args + " --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);
  EXPECT_TRUE(j.at("rigid_limit_exceeded").get<bool>());
  EXPECT_GT(j.at("max_cushion_normal_speed").get<double>(), 2.5);
  EXPECT_TRUE(j.contains("warning"));
}

TEST(Simulate, EventLimitStopsWithExitOne) {
  const ProcessResult run = cueplan(one_rail_command("--max-events 2 --json"));
  EXPECT_EQ(run.exit_code, 1);
  const json j = json::parse(run.out);
  EXPECT_EQ(j.at("status"), "event_limit");
  EXPECT_FALSE(j.at("message").get<std::string>().empty());
}

// A shot outside the problem's limits is simulated and said to be outside them.
TEST(Simulate, ShotOutsideTheProblemLimitsIsSimulatedAndNamed) {
  const ProcessResult run = cueplan("simulate '" + problem_path("one_rail_position") +
                                    "' --speed 6 --aim 30 --topspin-k 0.6 --sidespin-k 0.3");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("outside the problem's limits: speed"), std::string::npos) << run.out;
}

// What no cue can give is refused naming the flag; what few players can play is played
// with a warning (problems/stroke_ranges.hpp, the check the server and problem files use).
TEST(Simulate, StrokesBeyondWhatACueGivesAreRefusedAndImplausibleOnesWarned) {
  const std::string problem = "simulate '" + problem_path("one_rail_position") + "' --aim 30";
  const ProcessResult miscue = cueplan(problem + " --speed 1 --topspin-k 1 --sidespin-k 0.9");
  EXPECT_EQ(miscue.exit_code, 2);
  EXPECT_NE(miscue.err.find("--topspin-k 1 with --sidespin-k 0.9 gives spin"), std::string::npos)
      << miscue.err;
  EXPECT_NE(miscue.err.find("0.54 ball radii"), std::string::npos) << miscue.err;
  const ProcessResult too_fast = cueplan(problem + " --speed 1e308");
  EXPECT_EQ(too_fast.exit_code, 2);
  EXPECT_NE(too_fast.err.find("--speed must be at most 20 m/s"), std::string::npos) << too_fast.err;
  const ProcessResult fast = cueplan(problem + " --speed 14");
  EXPECT_LE(fast.exit_code, 1) << fast.err;
  EXPECT_NE(fast.err.find("warning: --speed 14 m/s is faster than a break shot"), std::string::npos)
      << fast.err;
}

// ---------------------------------------------------------------------------
// --svg

// What the drawing shows - pockets, contacts, the rest position, obstacles, an open
// table - is checked on the same scenes in tests/draw (cueplan::draw's marks); here, that
// the command writes it, whole, in the format its file name asks for.
TEST(SimulateSvg, WritesAnSvgDocumentTitledWithTheShot) {
  const fs::path file = scratch() / "one_rail.svg";
  const ProcessResult run = cueplan(one_rail_command("--svg '" + file.string() + "'"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find(file.string()), std::string::npos) << run.out;
  const std::string svg = read_text(file);
  // The root element is <svg>, after the XML declaration only.
  const size_t root = svg.find("<svg");
  ASSERT_NE(root, std::string::npos);
  EXPECT_TRUE(svg.rfind("<?xml", 0) == 0 || root == 0);
  EXPECT_EQ(svg.find('<', svg.find("?>") + 2), root);
  EXPECT_TRUE(svg.ends_with("</svg>\n") || svg.ends_with("</svg>")) << svg.substr(svg.size() - 20);
  const size_t title = svg.find("<title>");
  ASSERT_NE(title, std::string::npos);
  EXPECT_EQ(svg.find("one-rail position: V = 1.002 m/s"), title + 7) << "the title gives the shot";
  const phys::ShotResult expected = library_shot(shipped("one_rail_position"), kOneRail);
  EXPECT_NE(svg.find("after " + std::to_string(expected.cushion_hits) + " cushion"), std::string::npos)
      << "the description gives the outcome";
  for (const auto& entry : fs::directory_iterator(scratch()))
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
}

TEST(SimulateSvg, TheExtensionChoosesTheFormat) {
  const fs::path png = scratch() / "one_rail.png";
  const fs::path pdf = scratch() / "one_rail.PDF";
  ASSERT_EQ(cueplan(one_rail_command("--svg '" + png.string() + "'"), "png").exit_code, 0);
  ASSERT_EQ(cueplan(one_rail_command("--svg '" + pdf.string() + "'"), "pdf").exit_code, 0);
  EXPECT_EQ(read_text(png).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(read_text(pdf).substr(0, 5), "%PDF-");
  // Any other extension is refused before the shot is simulated.
  const fs::path jpg = scratch() / "one_rail.jpg";
  const ProcessResult run = cueplan(one_rail_command("--svg '" + jpg.string() + "'"), "jpg");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.out, "");
  EXPECT_NE(run.err.find("--svg must name a .svg, .png or .pdf file"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(jpg));
}

TEST(SimulateSvg, ObstacleAndOpenTablesAreDrawn) {
  const fs::path blocked = scratch() / "blocked.png";
  ASSERT_EQ(cueplan("simulate '" + problem_path("blocked_direct_route") +
                    "' --speed 1.5 --aim 0 --svg '" + blocked.string() + "'")
                .exit_code,
            0);
  EXPECT_EQ(read_text(blocked).substr(1, 3), "PNG");
  const fs::path carom = scratch() / "carom.svg";
  ASSERT_EQ(cueplan("simulate '" + problem_path("carom_three_cushion") +
                    "' --speed 1.75 --aim 119.1 --json --svg '" + carom.string() + "'")
                .exit_code,
            0);
  EXPECT_NE(read_text(carom).find("<title>carom three-cushion"), std::string::npos);
}

// ---------------------------------------------------------------------------
// --batch

TEST(SimulateBatch, EveryRowComesOutAndBadRowsAloneFail) {
  const fs::path input = scratch() / "shots.csv";
  write_text(input,
             "speed,aim_deg,topspin_k,sidespin_k\n"
             "1.002,-60.36,0.8,0\n"
             "1,fast,0,0\n"
             "-1,0,0,0\n"
             "\n"
             "1,30\n"
             "nan,0,0,0\n"
             "0.7,-56.84,1,0\n");
  const ProcessResult run =
      cueplan("simulate '" + problem_path("near_pocket") + "' --batch '" + input.string() + "'");
  EXPECT_EQ(run.exit_code, 1) << "some rows failed";
  EXPECT_EQ(run.err,
            "cueplan simulate: 6 rows: 2 invalid_input, 2 parse_error, 1 pocketed, 1 rest; 4 "
            "failed\n");
  EXPECT_EQ(lines_of(run.out).at(0), kBatchHeader);
  const auto rows = csv_rows(run.out);
  ASSERT_EQ(rows.size(), 6u);
  const std::vector<std::string> statuses = {"rest",        "parse_error",   "invalid_input",
                                             "parse_error", "invalid_input", "pocketed"};
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].at("status"), statuses[i]) << "row " << i;
    const bool simulated = statuses[i] == "rest" || statuses[i] == "pocketed";
    EXPECT_EQ(rows[i].at("final_x").empty(), !simulated) << "row " << i;
    EXPECT_EQ(rows[i].at("message").empty(), simulated) << "row " << i;
  }
  EXPECT_NE(rows[1].at("message").find("aim_deg"), std::string::npos);
  EXPECT_NE(rows[2].at("message").find("speed"), std::string::npos);
  EXPECT_NE(rows[3].at("message").find("line 6"), std::string::npos);  // blank line counted
  EXPECT_EQ(rows[1].at("aim_deg"), "fast");                            // input echoed

  const prob::Problem problem = shipped("near_pocket");
  const phys::ShotResult first = library_shot(problem, {1.002, -60.36, 0.8, 0.0});
  EXPECT_DOUBLE_EQ(std::stod(rows[0].at("final_x")), first.final_position.x);
  EXPECT_DOUBLE_EQ(std::stod(rows[0].at("final_y")), first.final_position.y);
  EXPECT_EQ(std::stoi(rows[0].at("cushion_hits")), first.cushion_hits);
  EXPECT_EQ(rows[0].at("pocketed"), "0");
  EXPECT_EQ(rows[5].at("pocketed"), "1");
  EXPECT_EQ(rows[5].at("hit_obstacle"), "0");
  EXPECT_EQ(rows[5].at("miss_distance"), "inf");
}

TEST(SimulateBatch, OutputIsTheSameForAnyThreadCount) {
  const fs::path input = scratch() / "many.csv";
  std::string text = "speed,aim_deg,topspin_k,sidespin_k\n";
  for (int i = 0; i < 40; ++i)
    text += std::to_string(0.4 + 0.1 * i) + "," + std::to_string(-170.0 + 9.0 * i) + "," +
            std::to_string(-0.9 + 0.045 * i) + "," + std::to_string(0.7 - 0.035 * i) + "\n";
  write_text(input, text);
  const std::string args =
      "simulate '" + problem_path("blocked_direct_route") + "' --batch '" + input.string() + "'";
  const ProcessResult one = cueplan(args + " --threads 1");
  const ProcessResult two = cueplan(args + " --threads 2");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_EQ(lines_of(one.out).size(), 41u);
  EXPECT_EQ(one.out, two.out);  // deliberate exact comparison: determinism
}

TEST(SimulateBatch, WrongHeaderIsAWholeCommandError) {
  const fs::path input = scratch() / "wrong_header.csv";
  write_text(input, "speed,angle_deg,topspin_k,sidespin_k\n1,45,1,0\n");
  const ProcessResult run = cueplan("simulate '" + problem_path("one_rail_position") +
                                    "' --batch '" + input.string() + "'");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.out, "");
  EXPECT_EQ(lines_of(run.err).size(), 1u);
  EXPECT_NE(run.err.find("speed,aim_deg,topspin_k,sidespin_k"), std::string::npos);
}

// ---------------------------------------------------------------------------
// bad input

struct BadInput {
  const char* name;
  const char* args;  // after `simulate`; {one_rail} and {malformed} stand for files
  const char* what;  // the thing the one-line message must name
};

// gtest prints a parameter with PrintTo: the case name instead of its bytes.
void PrintTo(const BadInput& input, std::ostream* os) { *os << input.name; }

// A problem file whose table length is negative, on its line 3.
std::string malformed_problem() {
  const fs::path file = scratch() / "malformed.yaml";
  write_text(file,
             "name: malformed\n"
             "table:\n"
             "  length: -2\n"
             "cue_ball: [0.5, 0.5]\n"
             "target: [1.0, 0.5]\n");
  return file.string();
}

std::string expand(std::string args) {
  const auto replace = [&](const std::string& key, const std::string& value) {
    for (size_t at = args.find(key); at != std::string::npos; at = args.find(key))
      args.replace(at, key.size(), "'" + value + "'");
  };
  replace("{one_rail}", problem_path("one_rail_position"));
  replace("{malformed}", malformed_problem());
  return args;
}

class SimulateBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(SimulateBadInput, ExitsTwoWithOneLineNamingIt) {
  const ProcessResult run = cueplan("simulate " + expand(GetParam().args));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.out, "");
  const std::vector<std::string> lines = lines_of(run.err);
  ASSERT_EQ(lines.size(), 1u) << run.err;
  EXPECT_EQ(lines[0].rfind("cueplan", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find(GetParam().what), std::string::npos) << lines[0];
}

INSTANTIATE_TEST_SUITE_P(
    Cli, SimulateBadInput,
    ::testing::Values(
        BadInput{"MissingProblemFile", "/nonexistent/problem.yaml --speed 1 --aim 0",
                 "/nonexistent/problem.yaml"},
        BadInput{"MalformedProblemFile", "{malformed} --speed 1 --aim 0",
                 "malformed.yaml:3: table.length"},
        BadInput{"NoProblem", "--speed 1 --aim 0", "PROBLEM"},
        BadInput{"NanSpeed", "{one_rail} --speed nan --aim 0", "--speed"},
        BadInput{"NegativeSpeed", "{one_rail} --speed -1 --aim 0", "--speed"},
        BadInput{"ZeroSpeed", "{one_rail} --speed 0 --aim 0", "--speed"},
        BadInput{"WordForSpeed", "{one_rail} --speed fast --aim 0", "--speed"},
        BadInput{"MissingSpeed", "{one_rail} --aim 0", "--speed"},
        BadInput{"MissingAim", "{one_rail} --speed 1", "--aim"},
        BadInput{"InfiniteAim", "{one_rail} --speed 1 --aim inf", "--aim"},
        BadInput{"NanTopspin", "{one_rail} --speed 1 --aim 0 --topspin-k nan", "--topspin-k"},
        BadInput{"NanSidespin", "{one_rail} --speed 1 --aim 0 --sidespin-k nan", "--sidespin-k"},
        BadInput{"UnknownMethod", "{one_rail} --speed 1 --aim 0 --method magic", "--method"},
        BadInput{"ZeroAccuracy", "{one_rail} --speed 1 --aim 0 --accuracy 0", "--accuracy"},
        BadInput{"LooseAccuracy", "{one_rail} --speed 1 --aim 0 --accuracy 0.5", "--accuracy"},
        BadInput{"ZeroMaxEvents", "{one_rail} --speed 1 --aim 0 --max-events 0", "--max-events"},
        BadInput{"ThreadsWithoutBatch", "{one_rail} --speed 1 --aim 0 --threads 2", "--threads"},
        BadInput{"BatchWithShotFlags", "{one_rail} --batch x.csv --speed 1", "--batch"},
        BadInput{"MissingBatchFile", "{one_rail} --batch /nonexistent/shots.csv", "--batch"},
        BadInput{"UnwritableSvg", "{one_rail} --speed 1 --aim 0 --svg /nonexistent/dir/x.svg",
                 "--svg"},
        BadInput{"UnknownFlag", "{one_rail} --speed 1 --aim 0 --angle 3", "--angle"},
        BadInput{"NegativeSamples", "{one_rail} --speed 1 --aim 0 --samples -1", "--samples"},
        BadInput{"NegativeNoise", "{one_rail} --speed 1 --aim 0 --samples 5 --noise -1",
                 "--noise"},
        BadInput{"NoiseWithoutSamples", "{one_rail} --speed 1 --aim 0 --noise 2", "--noise"},
        BadInput{"BatchWithSamples", "{one_rail} --batch x.csv --samples 5", "--batch"},
        BadInput{"ZeroTrace", "{one_rail} --speed 1 --aim 0 --trace 0", "--trace"},
        BadInput{"NegativeTrace", "{one_rail} --speed 1 --aim 0 --trace -0.01", "--trace"},
        BadInput{"NanTrace", "{one_rail} --speed 1 --aim 0 --trace nan", "--trace"},
        BadInput{"InfiniteTrace", "{one_rail} --speed 1 --aim 0 --trace inf", "--trace"},
        BadInput{"TraceOfTooManyRows", "{one_rail} --speed 1 --aim 0 --trace 1e-9",
                 "--trace gives"},
        BadInput{"BatchWithTrace", "{one_rail} --batch x.csv --trace 0.1", "--batch"}),
    [](const ::testing::TestParamInfo<BadInput>& param) { return param.param.name; });

TEST(SimulateBadInputMessage, SpeedMessageIsTheDocumentedOne) {
  const ProcessResult run =
      cueplan("simulate '" + problem_path("one_rail_position") + "' --speed -1 --aim 0");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err, "cueplan simulate: --speed must be positive and finite (m/s), got -1\n");
}

// ---------------------------------------------------------------------------
// help

TEST(SimulateHelp, StatesEveryFlagWithUnitsAndDefaults) {
  const ProcessResult run = cueplan("simulate --help");
  EXPECT_EQ(run.exit_code, 0);
  for (const char* needle : {"PROBLEM",
                             "--speed",
                             "--aim",
                             "--topspin-k",
                             "--sidespin-k",
                             "--method",
                             "--accuracy",
                             "--table-cache",
                             "--max-events",
                             "--json",
                             "--svg",
                             "--batch",
                             "--threads",
                             "m/s",
                             "deg",
                             "exact",
                             "paper",
                             "table",
                             "1e-09",
                             "200",
                             "centre-ball",
                             "speed,aim_deg,topspin_k,sidespin_k",
                             "final_x,final_y"})
    EXPECT_NE(run.out.find(needle), std::string::npos) << "missing " << needle;

  const ProcessResult top = cueplan("--help");
  EXPECT_NE(top.out.find("simulate"), std::string::npos);
}

}  // namespace
}  // namespace cli_test
