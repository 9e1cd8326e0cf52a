// Position play on the command line, run as a user runs it: `cueplan solve` on a problem
// with `next` reports success {pot, next, both} with intervals and the next shot, and
// `cueplan zone` draws the field and its zone (PNG, SVG) and summarises it. Exact impacts
// and a small budget, so nothing waits for an impact table.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.hpp"

namespace cli_test {

const char* const kScratchName = "cueplan_zone_test_";

namespace {

using nlohmann::json;

constexpr const char* kQuick = "--method exact --max-evaluations 1500 --samples 60 --seed 3";

json parsed(const ProcessResult& run) {
  try {
    return json::parse(run.out);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not JSON (" << e.what() << "):\n" << run.out << run.err;
    return json::object();
  }
}

TEST(SolveNext, JsonHasPotNextAndBothWithIntervalsAndTheNextShot) {
  const ProcessResult run =
      cueplan("solve '" + problem_path("pots/red_then_black") + "' " + kQuick + " --json");
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  const json j = parsed(run);
  EXPECT_EQ(j.at("status"), "solved");
  const json& success = j.at("success");
  for (const char* part : {"pot", "next", "both"})
    for (const char* key : {"p", "low", "high", "samples"})
      EXPECT_TRUE(success.at(part).at(key).is_number()) << part << "." << key;
  for (const char* part : {"pot", "next", "both"}) {
    EXPECT_LE(success.at(part).at("low").get<double>(), success.at(part).at("p").get<double>());
    EXPECT_GE(success.at(part).at("high").get<double>(), success.at(part).at("p").get<double>());
  }
  const json& next = j.at("next");
  EXPECT_EQ(next.at("ball"), "black");
  EXPECT_EQ(next.at("pocket"), "bottom_right");
  for (const char* key : {"p", "cut_deg", "distance_m", "zone_area_m2"})
    EXPECT_TRUE(next.at(key).is_number()) << key;
  EXPECT_TRUE(next.at("in_zone").is_boolean());
  EXPECT_GT(next.at("zone_area_m2").get<double>(), 0.0);
  EXPECT_EQ(next.at("landing"), j.at("final_position"));
  for (const json& a : j.at("alternatives")) EXPECT_TRUE(a.contains("next"));
}

TEST(SolveNext, TextSaysWhatTheLandingLeavesInAPlayersWords) {
  const ProcessResult run = cueplan("solve '" + problem_path("pots/red_then_black") + "' " + kQuick);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("next            black into the bottom_right pocket: leaves "),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find(" on the black, "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("cm^2 where P(next pot) is within 10 points of the best"),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("(pot now and pot next)"), std::string::npos) << run.out;
}

TEST(Zone, WritesAPngAndSummarisesTheZoneAsJson) {
  const std::string png = (scratch() / "zone.png").string();
  const ProcessResult run = cueplan("zone '" + problem_path("pots/red_then_black") + "' " + kQuick +
                                    " --cloud 40 --json --out '" + png + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  const std::string bytes = read_text(png);
  ASSERT_GT(bytes.size(), 1000u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  const json j = parsed(run);
  for (const char* key : {"next", "zone_area_m2", "best", "best_p", "status", "landing", "p",
                          "in_zone", "success", "cloud", "out"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j.at("next").at("ball"), "black");
  EXPECT_GT(j.at("zone_area_m2").get<double>(), 0.0);
  EXPECT_LE(j.at("cloud").get<int>(), 40);
}

TEST(Zone, FieldOnlyWritesAnSvgWithoutPlanningAStroke) {
  const std::string svg = (scratch() / "zone.svg").string();
  const ProcessResult run = cueplan("zone '" + problem_path("pots/pool_two_ball_position") +
                                    "' --field-only --out '" + svg + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  const std::string text = read_text(svg);
  EXPECT_NE(text.find("<svg"), std::string::npos);
  EXPECT_NE(run.out.find("zone "), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("landing"), std::string::npos) << "no stroke planned:\n" << run.out;
}

TEST(Zone, AProblemWithoutNextIsABadInputNamingTheField) {
  const std::string png = (scratch() / "none.png").string();
  const ProcessResult run =
      cueplan("zone '" + problem_path("pots/cut_middle_pocket") + "' --out '" + png + "'");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("next: missing"), std::string::npos) << run.err;
  const ProcessResult bad = cueplan("zone '" + problem_path("pots/red_then_black") +
                                    "' --cloud -1 --out '" + png + "'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--cloud must be"), std::string::npos) << bad.err;
  const ProcessResult help = cueplan("zone --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("--field-only"), std::string::npos);
}

}  // namespace
}  // namespace cli_test
