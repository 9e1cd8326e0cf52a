// Tests of `cueplan run`, run as a separate process: the planned sequence in words, the
// JSON keys the issue names, the pattern drawing, and errors that name the flag or the
// layout's field. Few runs under the noise: the suite runs on 2 cores.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.hpp"

namespace cli_test {

const char* const kScratchName = "cueplan_run_test_";

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string run_path(const std::string& stem) {
  return std::string(CUEPLAN_PROBLEMS_DIR) + "/runs/" + stem + ".yaml";
}

json parsed(const ProcessResult& run) {
  try {
    return json::parse(run.out);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not JSON (" << e.what() << "):\n" << run.out << run.err;
    return json::object();
  }
}

TEST(Run, TextListsTheSequenceAndTheStatistics) {
  const ProcessResult run = cueplan("run '" + run_path("nine_ball_four") + "' --samples 4 --threads 2");
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  for (const char* needle : {"game            nine_ball", "shot 1          6 into ", "    stroke      ",
                             "    P(pot)      ", "    position    cue ball to (", "plan            clears the table",
                             "P(run-out)      ", " of 4 runs", "mean potted     ", "time            "})
    EXPECT_NE(run.out.find(needle), std::string::npos) << needle << "\n" << run.out;
}

TEST(Run, JsonHasTheIssuesKeysAndADrawing) {
  const fs::path svg = scratch() / "run.svg";
  const ProcessResult run = cueplan("run '" + run_path("snooker_colours") +
                                    "' --samples 3 --threads 2 --lookahead 1 --json --svg '" + svg.string() + "'");
  ASSERT_TRUE(run.exit_code == 0 || run.exit_code == 1) << run.out << run.err;
  const json j = parsed(run);
  for (const char* key : {"plan", "runout", "mean_potted", "mean_break", "deaths", "policy", "game"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j.value("policy", ""), "planner");
  EXPECT_EQ(j.value("game", ""), "snooker");
  for (const char* key : {"p", "low", "high", "samples"}) EXPECT_TRUE(j["runout"].contains(key)) << key;
  EXPECT_EQ(j["runout"]["samples"].get<int>(), 3);
  ASSERT_TRUE(j["plan"].is_array());
  ASSERT_FALSE(j["plan"].empty());
  EXPECT_EQ(j["plan"][0]["ball"], "yellow");  // the colours in order
  for (const json& s : j["plan"])
    for (const char* key : {"ball", "pocket", "shot", "success"}) EXPECT_TRUE(s.contains(key)) << key;
  EXPECT_EQ(run.exit_code == 0, j["plan_clears"].get<bool>());
  const std::string picture = read_text(svg);
  EXPECT_NE(picture.find("<svg"), std::string::npos);
}

TEST(Run, GreedyPolicyAndGameFlag) {
  const ProcessResult run = cueplan("run '" + run_path("any_order_three") +
                                    "' --game any_order --policy greedy --samples 0 --json");
  ASSERT_TRUE(run.exit_code == 0 || run.exit_code == 1) << run.out << run.err;
  const json j = parsed(run);
  EXPECT_EQ(j.value("policy", ""), "greedy");
  EXPECT_EQ(j["runout"]["samples"].get<int>(), 0);
}

TEST(Run, BadFlagsAreNamed) {
  const std::string layout = "'" + run_path("nine_ball_four") + "'";
  struct Case {
    std::string args, needle;
  };
  for (const Case& c : {Case{"--game ten_ball", "--game must be any_order, nine_ball, eight_ball or snooker"},
                        Case{"--policy best", "--policy must be planner or greedy"},
                        Case{"--lookahead 0", "--lookahead must be 1 to 5"},
                        Case{"--samples -1", "--samples must be 0 to 100000"},
                        Case{"--png x.svg", "--png must name a .png file"},
                        Case{"--game snooker", "balls.6: is not a snooker ball"}}) {
    const ProcessResult run = cueplan("run " + layout + " " + c.args);
    EXPECT_EQ(run.exit_code, 2) << c.args;
    EXPECT_NE(run.err.find(c.needle), std::string::npos) << c.args << ": " << run.err;
    EXPECT_EQ(run.out, "");
  }
}

TEST(Run, BadLayoutFieldsAreNamed) {
  const fs::path with_pot = scratch() / "with_pot.yaml";
  write_text(with_pot, "name: x\nballs:\n  red: [1.0, 0.5]\ncue_ball: [0.5, 0.5]\npot: {ball: red, pocket: top_left}\n");
  ProcessResult run = cueplan("run '" + with_pot.string() + "'");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("with_pot.yaml:5: pot: a layout has no pot"), std::string::npos) << run.err;
  const fs::path bad_game = scratch() / "bad_game.yaml";
  write_text(bad_game, "name: x\ngame: pool\nballs:\n  red: [1.0, 0.5]\ncue_ball: [0.5, 0.5]\n");
  run = cueplan("run '" + bad_game.string() + "'");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("bad_game.yaml:2: game: must be any_order"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace cli_test
