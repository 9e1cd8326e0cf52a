// Tests of `cueplan solve` and `cueplan spinmap`, run as separate processes the way a
// user runs them: what they print and draw, their exit codes, that the shots they
// report are the simulator's, and that a seed fixes the answer. Every run uses the
// exact impact method and a small budget, so nothing waits for an impact table.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_test_support.hpp"
#include "cueplan/physics/shot.hpp"
#include "cueplan/problems/problem.hpp"

// The test files share their helpers (cli_test_support.hpp) by living in its namespace.
namespace cli_test {

const char* const kScratchName = "cueplan_solve_test_";

namespace {

namespace fs = std::filesystem;
namespace phys = cueplan::physics;
namespace prob = cueplan::problems;
using nlohmann::json;

// A quick, reproducible search: exact impacts, a small budget, a fixed seed.
constexpr const char* kQuick =
    "--method exact --max-evaluations 1500 --samples 50 --alternatives 3 --seed 11";

std::string solve_command(const std::string& stem, const std::string& extra = {}) {
  return "solve '" + problem_path(stem) + "' " + kQuick + (extra.empty() ? "" : " " + extra);
}

// A JSON number as text that reads back to the same double.
std::string fmt_exact(const json& number) { return json(number.get<double>()).dump(); }

json parsed(const ProcessResult& run) {
  try {
    return json::parse(run.out);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not JSON (" << e.what() << "):\n" << run.out << run.err;
    return json::object();
  }
}

// ---------------------------------------------------------------------------
// solve

TEST(Solve, TextGivesTheShotInPlayersTermsWithUnits) {
  const ProcessResult run = cueplan(solve_command("one_rail_position"));
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_EQ(run.err, "");
  for (const char* needle : {"one-rail position",
                             "status          solved",
                             "shot            V = ",
                             " m/s at aim ",
                             " deg, k_T = ",
                             ", k_S = ",
                             "stroke          ",
                             " tip",
                             "tip offset      ",
                             " R ",
                             "of the ball radius",
                             "landing         x = ",
                             " m, y = ",
                             "miss distance   ",
                             " mm",
                             "inside the target zone",
                             "success         ",
                             " %",
                             "route           1 cushion: ",
                             "family          ",
                             "constraints     all met",
                             "    speed         ok",
                             "    spin          ok",
                             "    aim           ok",
                             "    cushions      ok",
                             "    pocket        ok",
                             "    obstacle      ok",
                             "    rigid limit   ok",
                             "evaluations     ",
                             " shot simulations",
                             "time            ",
                             "alternatives    "})
    EXPECT_NE(run.out.find(needle), std::string::npos) << "missing '" << needle << "' in\n"
                                                       << run.out;
  // The route names cushions as simulate does.
  const std::string route = run.out.substr(run.out.find("route "));
  EXPECT_TRUE(
      route.find("y = 0") != std::string::npos || route.find("x = 3.569") != std::string::npos ||
      route.find("y = 1.778") != std::string::npos || route.find("x = 0") != std::string::npos)
      << route;
}

TEST(Solve, JsonHasEveryFieldAndTheShotsAreTheSimulators) {
  const ProcessResult run = cueplan(solve_command("one_rail_position", "--json"));
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const json j = parsed(run);
  for (const char* key : {"status", "message", "shot", "final_position", "miss_distance",
                          "success_probability", "evaluations", "time_s", "alternatives", "route",
                          "family", "constraints", "stroke", "tip_offset"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j.value("status", ""), "solved");
  EXPECT_GT(j.value("evaluations", 0), 0);
  EXPECT_GE(j.value("time_s", -1.0), 0.0);
  ASSERT_TRUE(j["alternatives"].is_array());

  const prob::Problem problem = shipped("one_rail_position");
  std::vector<json> shots = {j};
  for (const json& a : j["alternatives"]) shots.push_back(a);
  for (const json& s : shots) {
    for (const char* key : {"speed", "aim_deg", "topspin_k", "sidespin_k"})
      ASSERT_TRUE(s["shot"].contains(key)) << key;
    for (const char* key : {"final_position", "miss_distance", "success_probability"})
      EXPECT_TRUE(s.contains(key)) << key;
    const double p = s["success_probability"].get<double>();
    EXPECT_GE(p, 0.0);
    EXPECT_LE(p, 1.0);
    // An independent simulation of the reported stroke stops where the report says.
    const phys::Shot shot{s["shot"]["speed"].get<double>(), s["shot"]["aim_deg"].get<double>(),
                          s["shot"]["topspin_k"].get<double>(),
                          s["shot"]["sidespin_k"].get<double>()};
    const phys::ShotResult r = phys::simulate(problem.scene, problem.cue_ball, shot);
    EXPECT_NEAR(r.final_position.x, s["final_position"][0].get<double>(), 1e-9);
    EXPECT_NEAR(r.final_position.y, s["final_position"][1].get<double>(), 1e-9);
    if (r.status == phys::ShotStatus::rest) {
      EXPECT_NEAR(prob::miss_distance(problem, r), s["miss_distance"].get<double>(), 1e-9);
    }
  }
  // Solved: the best stroke lands within the tolerance and within the limits.
  EXPECT_LE(j["miss_distance"].get<double>(), problem.tolerance);
  const phys::Shot best{j["shot"]["speed"].get<double>(), j["shot"]["aim_deg"].get<double>(),
                        j["shot"]["topspin_k"].get<double>(),
                        j["shot"]["sidespin_k"].get<double>()};
  EXPECT_EQ(prob::check_shot(problem.limits, best), "");
}

// Every shot's success comes as {position, both}, each {p, low, high, samples}, with
// no pot in a problem without one; both equals position and success_probability is
// both.p; and the best stroke's estimate is what `cueplan simulate --samples` gives
// for it with the same samples and the seed solve draws its noise from whatever its
// --seed (planner::kReferenceSeed, 0x636f616368).
TEST(Solve, JsonSuccessHasIntervalsAndIsWhatSimulateEstimates) {
  const ProcessResult run = cueplan(solve_command("one_rail_position", "--json"));
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const json j = parsed(run);
  std::vector<json> shots = {j};
  for (const json& a : j["alternatives"]) shots.push_back(a);
  for (const json& s : shots) {
    ASSERT_TRUE(s.contains("success")) << s.dump();
    const json& success = s["success"];
    EXPECT_FALSE(success.contains("pot"));
    for (const char* part : {"position", "both"}) {
      const json& e = success[part];
      for (const char* key : {"p", "low", "high", "samples"}) EXPECT_TRUE(e.contains(key)) << key;
      EXPECT_LE(e["low"].get<double>(), e["p"].get<double>());
      EXPECT_GE(e["high"].get<double>(), e["p"].get<double>());
      EXPECT_GT(e["samples"].get<int>(), 0);
      EXPECT_LE(e["samples"].get<int>(), 50);
    }
    EXPECT_EQ(success["both"], success["position"]);
    EXPECT_EQ(s["success_probability"].get<double>(), success["both"]["p"].get<double>());
    EXPECT_GE(j["success"]["both"]["high"].get<double>(), success["both"]["low"].get<double>());
  }
  const json& shot = j["shot"];
  const ProcessResult sim = cueplan(
      "simulate '" + problem_path("one_rail_position") + "' --method exact --speed " +
          fmt_exact(shot["speed"]) + " --aim " + fmt_exact(shot["aim_deg"]) + " --topspin-k " +
          fmt_exact(shot["topspin_k"]) + " --sidespin-k " + fmt_exact(shot["sidespin_k"]) +
          " --samples 50 --seed 427070415720 --json",
      "sim");
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  EXPECT_EQ(parsed(sim)["success"], j["success"]);
}

TEST(Solve, SameSeedGivesTheSameJson) {
  // Everything but the wall-clock time; with the evaluation budget ending the search,
  // the thread count does not matter either.
  const auto without_time = [](json j) {
    j.erase("time_s");
    return j.dump();
  };
  const ProcessResult a = cueplan(solve_command("two_rail_position", "--json --threads 1"), "a");
  const ProcessResult b = cueplan(solve_command("two_rail_position", "--json --threads 1"), "b");
  const ProcessResult c = cueplan(solve_command("two_rail_position", "--json --threads 2"), "c");
  ASSERT_NE(a.exit_code, 2) << a.err;
  EXPECT_EQ(without_time(parsed(a)), without_time(parsed(b)));
  EXPECT_EQ(without_time(parsed(a)), without_time(parsed(c)));
}

// The picture's content (the best path, the alternatives faint) is checked on the same
// scenes in tests/draw; here, what the command writes and says.
TEST(Solve, SvgTitleGivesTheStrokeAndItsTipInPlayersWords) {
  const fs::path svg = scratch() / "plan.svg";
  const ProcessResult run =
      cueplan(solve_command("one_rail_position", "--json --svg '" + svg.string() + "'"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = parsed(run);
  const std::string text = read_text(svg);
  ASSERT_EQ(text.rfind("<?xml", 0), 0u) << "no SVG written";
  EXPECT_NE(text.find("</svg>"), std::string::npos);
  const size_t title = text.find("<title>one-rail position: ");
  ASSERT_NE(title, std::string::npos);
  EXPECT_NE(text.find("m/s", title), std::string::npos) << "the title gives the stroke";
  // The plan's first line says where the tip meets the ball as the text report does:
  // "below centre" for draw, never a signed "R up".
  const double up = j["shot"]["topspin_k"].get<double>() / 2.5;
  EXPECT_NE(text.find(up < 0.0 ? " R below centre" : " R above centre"), std::string::npos);
  EXPECT_EQ(text.find(" R up"), std::string::npos);
  if (!j["alternatives"].empty()) {
    EXPECT_NE(text.find("Faint grey: the alternatives"), std::string::npos) << "in the description";
  }
  EXPECT_EQ(j.value("svg", ""), svg.string());
}

TEST(Solve, SvgFlagWithAPngNameWritesAPng) {
  const fs::path png = scratch() / "plan.png";
  const ProcessResult run = cueplan(solve_command("one_rail_position", "--svg '" + png.string() + "'"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(read_text(png).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_NE(run.out.find("drawing         " + png.string()), std::string::npos);
}

TEST(Solve, TargetOutOfReachStillReportsAndExitsOne) {
  // The cue ball can barely move: the far target is out of reach.
  const fs::path file = scratch() / "out_of_reach.yaml";
  write_text(file,
             "name: out of reach\n"
             "cue_ball: [0.5, 0.5]\n"
             "target: [3.0, 1.5]\n"
             "limits:\n"
             "  speed: [0.2, 0.25]\n"
             "  cushions: [0, 3]\n");
  const ProcessResult run = cueplan("solve '" + file.string() + "' " + kQuick);
  EXPECT_EQ(run.exit_code, 1) << run.out << run.err;
  EXPECT_NE(run.out.find("status"), std::string::npos);
  EXPECT_TRUE(run.out.find("no_solution_found") != std::string::npos ||
              run.out.find("budget_exhausted") != std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("miss distance"), std::string::npos) << "the nearest stroke is shown";
}

struct BadInput {
  const char* name;
  const char* args;  // after the command; {one_rail} stands for the problem file
  const char* what;  // the thing the one-line message must name
};

// gtest prints a parameter with PrintTo: the case name instead of its bytes.
void PrintTo(const BadInput& input, std::ostream* os) { *os << input.name; }

std::string expand(const std::string& args) {
  const std::string key = "{one_rail}";
  const size_t at = args.find(key);
  if (at == std::string::npos) return args;
  return args.substr(0, at) + "'" + problem_path("one_rail_position") + "'" +
         args.substr(at + key.size());
}

class SolveBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(SolveBadInput, ExitsTwoWithOneLineNamingIt) {
  const ProcessResult run = cueplan(expand(GetParam().args));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.out, "");
  const std::vector<std::string> lines = lines_of(run.err);
  ASSERT_EQ(lines.size(), 1u) << run.err;
  EXPECT_EQ(lines[0].rfind("cueplan", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find(GetParam().what), std::string::npos) << lines[0];
}

INSTANTIATE_TEST_SUITE_P(
    Cli, SolveBadInput,
    ::testing::Values(
        BadInput{"UnknownGlobal", "solve {one_rail} --method exact --global simplex", "--global"},
        BadInput{"UnknownLocal", "solve {one_rail} --method exact --local newton", "--local"},
        BadInput{"NegativeNoise", "solve {one_rail} --method exact --noise -1", "--noise"},
        BadInput{"ZeroEvaluations", "solve {one_rail} --method exact --max-evaluations 0",
                 "--max-evaluations"},
        BadInput{"ZeroTime", "solve {one_rail} --method exact --max-time 0", "--max-time"},
        BadInput{"ZeroStarts", "solve {one_rail} --method exact --starts 0", "--starts"},
        BadInput{"NegativeSamples", "solve {one_rail} --method exact --samples -1", "--samples"},
        BadInput{"NegativeThreads", "solve {one_rail} --method exact --threads -1", "--threads"},
        BadInput{"UnknownMethod", "solve {one_rail} --method magic", "--method"},
        BadInput{"NoProblem", "solve --method exact", "PROBLEM"},
        BadInput{"MissingProblemFile", "solve /nonexistent/problem.yaml --method exact",
                 "/nonexistent/problem.yaml"},
        BadInput{"UnwritableSvg",
                 "solve {one_rail} --method exact --max-evaluations 200 --svg /nonexistent/d/x.svg",
                 "--svg"},
        BadInput{"SpinmapWithoutOut", "spinmap {one_rail} --speed 1 --aim 0", "--out"},
        BadInput{"SpinmapJpeg", "spinmap {one_rail} --speed 1 --aim 0 --out x.jpg", "--out"},
        BadInput{"SpinmapSpeedWithoutAim", "spinmap {one_rail} --speed 1 --out x.svg", "--aim"},
        BadInput{"SpinmapAimWithoutSpeed", "spinmap {one_rail} --aim 0 --out x.svg", "--speed"},
        BadInput{"SpinmapZeroSpeed", "spinmap {one_rail} --speed 0 --aim 0 --out x.svg", "--speed"},
        BadInput{"SpinmapTinyGrid", "spinmap {one_rail} --speed 1 --aim 0 --grid 2 --out x.svg",
                 "--grid"},
        BadInput{"SpinmapSuccessNoSamples",
                 "spinmap {one_rail} --speed 1 --aim 0 --success --samples 0 --out x.svg",
                 "--samples"},
        BadInput{"SpinmapSuccessTooManySamples",
                 "spinmap {one_rail} --speed 1 --aim 0 --success --samples 20000 --out x.svg",
                 "--samples"}),
    [](const ::testing::TestParamInfo<BadInput>& param) { return std::string(param.param.name); });

// ---------------------------------------------------------------------------
// spinmap

// Grid points inside the disc: (i, j) with (2i - n + 1)^2 + (2j - n + 1)^2 <= (n - 1)^2.
size_t disc_points(int n) {
  size_t count = 0;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) {
      const long a = 2L * i - (n - 1);
      const long b = 2L * k - (n - 1);
      if (a * a + b * b <= static_cast<long>(n - 1) * (n - 1)) ++count;
    }
  return count;
}

constexpr const char* kOneRailStroke = "--speed 1.002 --aim -60.36 --method exact";

TEST(Spinmap, SvgHasOneCellPerSpinAndOutlinesTheLandingOnes) {
  const fs::path svg = scratch() / "map.svg";
  const ProcessResult run =
      cueplan("spinmap '" + problem_path("one_rail_position") + "' " + kOneRailStroke +
              " --grid 17 --json --out '" + svg.string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_EQ(run.err, "") << "no progress bar unless stderr is a terminal";
  // The cells (one per spin), the dots and the outline are checked on the same map in
  // tests/draw; here, that the file is the SVG the command says it wrote.
  const std::string text = read_text(svg);
  ASSERT_EQ(text.rfind("<?xml", 0), 0u) << "no SVG written";
  EXPECT_NE(text.find("<title>What spin lands here? one-rail position"), std::string::npos);

  const json j = parsed(run);
  EXPECT_EQ(j.value("points", 0), static_cast<int>(disc_points(17)));
  EXPECT_EQ(j.value("stroke_source", ""), "given");
  EXPECT_EQ(static_cast<int>(j["landing_spins"].size()), j.value("landing", -1));
  // The recorded solution's topspin (k_T 0.8) lies between grid rows; the row at 0.78
  // still lands, so the outline is there.
  EXPECT_GT(j.value("landing", 0), 0);
  EXPECT_EQ(j.value("format", ""), "svg");
  const prob::Problem problem = shipped("one_rail_position");
  for (const json& p : j["landing_spins"]) {
    const phys::ShotResult r = phys::simulate(
        problem.scene, problem.cue_ball,
        {1.002, -60.36, p["topspin_k"].get<double>(), p["sidespin_k"].get<double>()});
    EXPECT_TRUE(prob::reaches_target(problem, r));
  }
}

// --success: every cell gets the fraction of its noisy strokes that solve the problem,
// and a cell's value is what `simulate --samples` estimates for that cell's stroke with
// the same seed (the same noise draws); half a club player's scatter, so that some spins
// succeed sometimes.
TEST(Spinmap, SuccessShadesEveryCellAndAgreesWithSimulate) {
  const fs::path svg = scratch() / "success.svg";
  const ProcessResult run =
      cueplan("spinmap '" + problem_path("one_rail_position") + "' " + kOneRailStroke +
              " --grid 7 --success --samples 12 --seed 11 --noise 0.5 --json --out '" + svg.string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  // The picture's text is drawn as glyphs; its description says what the cells show.
  EXPECT_NE(read_text(svg).find("success under noise (12 noisy strokes)"), std::string::npos);
  const json j = parsed(run);
  EXPECT_EQ(j.at("success").at("samples"), 12);
  EXPECT_EQ(j.at("success").at("complete"), true);
  ASSERT_EQ(j.at("cells").size(), disc_points(7));
  const json* best = nullptr;
  for (const json& c : j.at("cells")) {
    const double p = c.at("success").get<double>();
    EXPECT_GE(p, 0.0);
    EXPECT_LE(p, 1.0);
    EXPECT_DOUBLE_EQ(p * 12.0, std::round(p * 12.0)) << "a count of 12 strokes";
    if (!best || p > (*best)["success"].get<double>()) best = &c;
  }
  ASSERT_NE(best, nullptr);
  EXPECT_GT((*best)["success"].get<double>(), 0.0) << "some spin succeeds sometimes";
  const ProcessResult sim = cueplan(
      "simulate '" + problem_path("one_rail_position") + "' --method exact --speed 1.002 --aim " +
          fmt_exact((*best)["aim_deg"]) + " --topspin-k " + fmt_exact((*best)["topspin_k"]) +
          " --sidespin-k " + fmt_exact((*best)["sidespin_k"]) + " --samples 12 --seed 11 --noise 0.5 --json",
      "sim");
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  EXPECT_EQ(parsed(sim).at("success").at("both").at("p").get<double>(),
            (*best)["success"].get<double>());
  // Without --success, no cell list and no success.
  const ProcessResult plain =
      cueplan("spinmap '" + problem_path("one_rail_position") + "' " + kOneRailStroke +
              " --grid 7 --json --out '" + svg.string() + "'");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_FALSE(parsed(plain).contains("success"));
  EXPECT_FALSE(parsed(plain).contains("cells"));
}

TEST(Spinmap, PngHasAValidSignatureAndSize) {
  const fs::path png = scratch() / "map.png";
  const ProcessResult run = cueplan("spinmap '" + problem_path("one_rail_position") + "' " +
                                    kOneRailStroke + " --grid 9 --out '" + png.string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const std::string bytes = read_text(png);
  ASSERT_GT(bytes.size(), 33u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(bytes.substr(12, 4), "IHDR");
  const auto be32 = [&](size_t at) {
    return (static_cast<unsigned char>(bytes[at]) << 24) |
           (static_cast<unsigned char>(bytes[at + 1]) << 16) |
           (static_cast<unsigned char>(bytes[at + 2]) << 8) |
           static_cast<unsigned char>(bytes[at + 3]);
  };
  EXPECT_GT(be32(16), 800u) << "width: the disc and the table side by side";
  EXPECT_GT(be32(20), 400u) << "height";
  EXPECT_EQ(bytes.substr(bytes.size() - 8, 4), "IEND");
  EXPECT_NE(run.out.find("picture"), std::string::npos);
}

TEST(Spinmap, WithoutSpeedAndAimUsesThePlannersStroke) {
  const fs::path svg = scratch() / "planned.svg";
  const std::string search = "--method exact --max-evaluations 1500 --samples 20 --seed 11";
  const ProcessResult map = cueplan("spinmap '" + problem_path("one_rail_position") + "' " +
                                        search + " --grid 7 --json --out '" + svg.string() + "'",
                                    "map");
  ASSERT_EQ(map.exit_code, 0) << map.out << map.err;
  const ProcessResult plan =
      cueplan("solve '" + problem_path("one_rail_position") + "' " + search + " --json", "plan");
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  const json m = parsed(map);
  const json p = parsed(plan);
  EXPECT_EQ(m.value("stroke_source", ""), "planner");
  EXPECT_EQ(m["speed"].get<double>(), p["shot"]["speed"].get<double>());
  EXPECT_EQ(m["aim_deg"].get<double>(), p["shot"]["aim_deg"].get<double>());
  EXPECT_NE(read_text(svg).find("the planner's best stroke"), std::string::npos) << "in the description";
}

// A pot problem's JSON: the pot in a player's terms and the success split into the pot,
// the position given the pot and both, for the answer and each alternative; the stroke
// replayed by `simulate` pots as reported, and `simulate --samples` splits it alike.
TEST(SolvePotJson, ReportsThePotAndItsSuccessSplit) {
  const ProcessResult run = cueplan(solve_command("pots/cut_middle_pocket", "--json"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = parsed(run);
  std::vector<json> shots{j};
  for (const json& a : j.at("alternatives")) shots.push_back(a);
  for (const json& s : shots) {
    const json& pot = s.at("pot");
    EXPECT_EQ(pot.at("ball"), "red");
    EXPECT_EQ(pot.at("pocket"), "bottom_middle");
    for (const char* key : {"cut_deg", "throw_deg", "margin_m", "aim_margin_deg"})
      EXPECT_TRUE(pot.at(key).is_number()) << key;
    const std::string thickness = pot.at("thickness");
    EXPECT_TRUE(thickness == "full" || thickness == "3/4" || thickness == "half" ||
                thickness == "1/4" || thickness == "thin")
        << thickness;
    const json& success = s.at("success");
    for (const char* part : {"pot", "position", "both"})
      for (const char* key : {"p", "low", "high", "samples"})
        EXPECT_TRUE(success.at(part).at(key).is_number()) << part << "." << key;
    EXPECT_EQ(s.at("success_probability"), success.at("both").at("p"));
    EXPECT_LE(success.at("both").at("p").get<double>(), success.at("pot").at("p").get<double>());
  }
  EXPECT_TRUE(j.at("pot").at("made").get<bool>());
  EXPECT_EQ(j.at("failure").at("condition"), "none");

  // Replayed: the red drops in its pocket, and the estimate is split the same way.
  const json& shot = j.at("shot");
  const std::string stroke = " --speed " + fmt_exact(shot.at("speed")) + " --aim " +
                             fmt_exact(shot.at("aim_deg")) + " --topspin-k " +
                             fmt_exact(shot.at("topspin_k")) + " --sidespin-k " +
                             fmt_exact(shot.at("sidespin_k"));
  const ProcessResult sim = cueplan("simulate '" + problem_path("pots/cut_middle_pocket") + "'" +
                                    stroke + " --samples 40 --json");
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const json k = json::parse(sim.out);
  EXPECT_EQ(k.at("failure").at("condition"), "none");
  EXPECT_TRUE(k.at("reaches_target").get<bool>());
  bool red_in = false;
  for (const json& b : k.at("balls"))
    if (b.at("name") == "red") red_in = b.at("pocketed").get<bool>() && b.at("pocket") == "bottom_middle";
  EXPECT_TRUE(red_in);
  EXPECT_EQ(k.at("success").at("pot").at("samples"), 40);
  EXPECT_EQ(k.at("success").at("position").at("samples").get<int>(),
            static_cast<int>(std::lround(k.at("success").at("pot").at("p").get<double>() * 40)));
}

// A screened pot with no kick or bank allowed: status unreachable, the reason in the
// message and in ruled_out, exit 1.
TEST(SolvePotJson, AScreenedPotIsUnreachable) {
  const std::string file = (scratch() / "screened.yaml").string();
  write_text(file,
             "balls: {red: [1.0, 1.0], blue: [0.6, 0.6]}\npot: {ball: red, pocket: bottom_left}\n"
             "cue_ball: [1.5, 1.3]\nlimits: {cushions_before_contact: 0, object_cushions: 0}\n");
  const ProcessResult run = cueplan("solve '" + file + "' " + kQuick + " --json");
  EXPECT_EQ(run.exit_code, 1) << run.err;
  const json j = parsed(run);
  EXPECT_EQ(j.at("status"), "unreachable");
  EXPECT_NE(j.at("message").get<std::string>().find("screened by blue"), std::string::npos)
      << j.at("message");
  ASSERT_EQ(j.at("ruled_out").size(), 1u);
  EXPECT_EQ(j.at("ruled_out")[0].get<std::string>().rfind("direct: ", 0), 0u);
}

// An escape: a legal hit off a cushion, the route in words in the text and the JSON, and
// the direct line ruled out by the ball that screens it.
TEST(SolvePotJson, AnEscapeReportsItsRouteAndWhatWasRuledOut) {
  const std::string file = (scratch() / "escape.yaml").string();
  write_text(file,
             "balls: {red: [2.6, 1.18], blue: [1.7845, 0.889]}\nfirst_contact: any_red\n"
             "cue_ball: [1.0, 0.6]\n");
  const ProcessResult run = cueplan("solve '" + file + "' " + kQuick + " --json");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  const json j = parsed(run);
  EXPECT_EQ(j.at("status"), "solved");
  EXPECT_NE(j.at("route_words").get<std::string>().find("one cushion off the"), std::string::npos)
      << j.at("route_words");
  EXPECT_NE(j.at("route_words").get<std::string>().find("to hit the red"), std::string::npos);
  ASSERT_GE(j.at("ruled_out").size(), 1u);
  EXPECT_NE(j.at("ruled_out")[0].get<std::string>().find("screened by blue"), std::string::npos);
  const ProcessResult text = cueplan("solve '" + file + "' " + kQuick);
  EXPECT_NE(text.out.find("route in words  one cushion off the"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("ruled out       direct: "), std::string::npos) << text.out;
}

}  // namespace
}  // namespace cli_test
