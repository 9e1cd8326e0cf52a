// Tests of the `cueplan` command line, run as a separate process the way a user runs
// it: what it prints, its exit codes, and that its numbers are the library's.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "cli_test_support.hpp"
#include "cueplan/physics/cushion_impact.hpp"

// The test files share their helpers (cli_test_support.hpp) by living in its namespace.
namespace cli_test {

const char* const kScratchName = "cueplan_cli_test_";

namespace {

namespace fs = std::filesystem;
namespace phys = cueplan::physics;
using nlohmann::json;

phys::ImpactResult library_rebound(const phys::CushionParams& params, double speed,
                                   double angle_deg, double topspin_k, double sidespin_k,
                                   const phys::ImpactOptions& options = {}) {
  return phys::resolve_impact(
      params, phys::incoming_state_k(speed, angle_deg, topspin_k, sidespin_k, params.radius),
      options);
}

// ---------------------------------------------------------------------------
// rebound: text, JSON, physics

TEST(Rebound, SpelledOutCommandPrintsSpeedAndAngleWithUnits) {
  const ProcessResult run = cueplan("rebound --speed 1 --angle 45 --topspin-k 1 --sidespin-k 0");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "");
  const phys::ImpactResult expected = library_rebound({}, 1.0, 45.0, 1.0, 0.0);
  char speed[64];
  char angle[64];
  std::snprintf(speed, sizeof speed, "%.6g m/s", expected.rebound_speed);
  std::snprintf(angle, sizeof angle, "%.6g deg", expected.rebound_angle_deg);
  for (const std::string& needle :
       {std::string("rebound speed"), std::string(speed), std::string("rebound angle"),
        std::string(angle), std::string("vx = "), std::string("rad/s"), std::string("status"),
        std::string("ok"), std::string("exact"), std::string("N s"), std::string(" J"),
        std::string("transitions")})
    EXPECT_NE(run.out.find(needle), std::string::npos) << "missing '" << needle << "' in\n"
                                                       << run.out;
  EXPECT_EQ(run.out.find("warning"), std::string::npos);
}

// CUEPLAN_SIMD caps the exact impact's kernels; a value the library does not know is
// ignored, and the command says so on stderr without changing the result.
TEST(Rebound, UnknownSimdCapIsReportedAndChangesNothing) {
  const std::string args = "rebound --speed 1.3 --angle 70 --topspin-k 0.4 --sidespin-k -1";
  const ProcessResult plain = cueplan(args, "plain");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  ASSERT_EQ(::setenv("CUEPLAN_SIMD", "sse2", 1), 0);
  const ProcessResult capped = cueplan(args, "sse2");
  ASSERT_EQ(::setenv("CUEPLAN_SIMD", "avx", 1), 0);
  const ProcessResult typo = cueplan(args, "typo");
  ::unsetenv("CUEPLAN_SIMD");
  EXPECT_EQ(capped.exit_code, 0);
  EXPECT_EQ(capped.err, "");
  EXPECT_EQ(capped.out, plain.out);  // every kernel build gives the same bits
  EXPECT_EQ(typo.exit_code, 0);
  EXPECT_EQ(typo.out, plain.out);
  EXPECT_EQ(typo.err,
            "cueplan: warning: CUEPLAN_SIMD='avx' is not one of sse2, avx2, avx512; ignored "
            "(the exact impact uses the widest instruction set the CPU has)\n");
}

TEST(Rebound, JsonEqualsTheLibraryResult) {
  const ProcessResult run =
      cueplan("rebound --speed 1 --angle 45 --topspin-k 1 --sidespin-k 0 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);
  const phys::ImpactResult expected = library_rebound({}, 1.0, 45.0, 1.0, 0.0);
  const double v_tol = 1e-12;  // m/s, for V0 = 1 m/s
  const double w_tol = v_tol / phys::CushionParams{}.radius;
  EXPECT_EQ(j.at("status"), "ok");
  EXPECT_EQ(j.at("method"), "exact");
  EXPECT_NEAR(j.at("rebound_speed").get<double>(), expected.rebound_speed, v_tol);
  EXPECT_NEAR(j.at("rebound_angle_deg").get<double>(), expected.rebound_angle_deg, 1e-10);
  ASSERT_EQ(j.at("velocity").size(), 2u);
  ASSERT_EQ(j.at("spin").size(), 3u);
  EXPECT_NEAR(j["velocity"][0].get<double>(), expected.outgoing.velocity.x, v_tol);
  EXPECT_NEAR(j["velocity"][1].get<double>(), expected.outgoing.velocity.y, v_tol);
  EXPECT_NEAR(j["spin"][0].get<double>(), expected.outgoing.spin.x, w_tol);
  EXPECT_NEAR(j["spin"][1].get<double>(), expected.outgoing.spin.y, w_tol);
  EXPECT_NEAR(j["spin"][2].get<double>(), expected.outgoing.spin.z, w_tol);
  EXPECT_NEAR(j.at("impulse_total").get<double>(), expected.impulse_total, 1e-14);
  EXPECT_EQ(j.at("transitions").size(), static_cast<size_t>(expected.transition_count));
  EXPECT_EQ(j.at("units").at("spin"), "rad/s");
  EXPECT_EQ(j.at("input").at("angle_deg"), 45.0);
}

TEST(Rebound, HanModelJsonEqualsTheLibraryResult) {
  const ProcessResult run = cueplan(
      "rebound --speed 1.4 --angle 60 --topspin-k 0.5 --sidespin-k -0.8 --cushion-model han_2005 "
      "--method table --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "");  // no table is built for the closed form
  const json j = json::parse(run.out);
  phys::CushionParams params;
  params.model = phys::CushionModel::han_2005;
  const phys::ImpactResult expected = phys::resolve_impact(
      params, phys::incoming_state_k(1.4, 60.0, 0.5, -0.8, params.radius));
  ASSERT_EQ(expected.status, phys::ImpactStatus::ok);
  EXPECT_EQ(j.at("cushion_model"), "han_2005");
  EXPECT_EQ(j.at("method"), "closed_form");
  EXPECT_EQ(j.at("input").at("cushion_model"), "han_2005");
  EXPECT_NEAR(j["velocity"][0].get<double>(), expected.outgoing.velocity.x, 1e-12);
  EXPECT_NEAR(j["velocity"][1].get<double>(), expected.outgoing.velocity.y, 1e-12);
  EXPECT_NEAR(j["spin"][2].get<double>(), expected.outgoing.spin.z, 1e-9);
  // The default model is still Mathavan's.
  const ProcessResult mathavan = cueplan("rebound --speed 1.4 --angle 60 --json");
  ASSERT_EQ(mathavan.exit_code, 0) << mathavan.err;
  EXPECT_EQ(json::parse(mathavan.out).at("cushion_model"), "mathavan_2010");
}

TEST(Rebound, StrongeModelJsonEqualsTheLibraryResult) {
  const ProcessResult run = cueplan(
      "rebound --speed 1.4 --angle 60 --topspin-k 0.5 --sidespin-k -0.8 --cushion-model "
      "stronge_compliant --eta-squared 2.2 --restitution 0.93 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);
  phys::CushionParams params;
  params.model = phys::CushionModel::stronge_compliant;
  params.eta_squared = 2.2;
  params.restitution = 0.93;
  const phys::ImpactResult expected = phys::resolve_impact(
      params, phys::incoming_state_k(1.4, 60.0, 0.5, -0.8, params.radius));
  ASSERT_EQ(expected.status, phys::ImpactStatus::ok);
  EXPECT_EQ(j.at("cushion_model"), "stronge_compliant");
  EXPECT_EQ(j.at("method"), "closed_form");
  EXPECT_NEAR(j["velocity"][0].get<double>(), expected.outgoing.velocity.x, 1e-12);
  EXPECT_NEAR(j["velocity"][1].get<double>(), expected.outgoing.velocity.y, 1e-12);
  EXPECT_NEAR(j["spin"][2].get<double>(), expected.outgoing.spin.z, 1e-9);
  // eta_squared reaches the model: near the perpendicular the slip sticks and reverses,
  // and another stiffness ratio gives another rebound (in gross slip, as above, it cannot).
  const auto near_perpendicular = [](const char* eta) {
    const ProcessResult r = cueplan(std::string("rebound --speed 1 --angle 80 --topspin-k 0 --sidespin-k 0.3 "
                                                "--cushion-model stronge_compliant --json --eta-squared ") + eta);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return json::parse(r.out);
  };
  EXPECT_GT(std::fabs(near_perpendicular("1.2")["velocity"][0].get<double>() -
                      near_perpendicular("3.2")["velocity"][0].get<double>()),
            1e-3);
}

// Every flag reaches the library: paper method, rad/s spins, a pool ball with its own
// mass, radius (cushion height following at 7R/5) and friction.
TEST(Rebound, FlagsReachTheLibrary) {
  const ProcessResult run = cueplan(
      "rebound --speed 1.7 --angle 120 --topspin -20 --sidespin 35 --method paper "
      "--steps 2000 --mass 0.17 --radius 0.028575 --mu-cushion 0.2 --mu-table 0.15 "
      "--restitution 0.9 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);
  phys::CushionParams params = phys::params_for_radius(0.028575);
  params.mass = 0.17;
  params.mu_cushion = 0.2;
  params.mu_table = 0.15;
  params.restitution = 0.9;
  phys::ImpactOptions options;
  options.method = phys::ImpactMethod::paper;
  options.paper_steps = 2000;
  const phys::ImpactResult expected =
      phys::resolve_impact(params, phys::incoming_state(1.7, 120.0, -20.0, 35.0), options);
  EXPECT_EQ(j.at("method"), "paper");
  EXPECT_NEAR(j.at("input").at("cushion_height").get<double>(), 1.4 * 0.028575, 1e-15);
  EXPECT_NEAR(j.at("rebound_speed").get<double>(), expected.rebound_speed, 1e-12);
  EXPECT_NEAR(j.at("rebound_angle_deg").get<double>(), expected.rebound_angle_deg, 1e-10);
  EXPECT_NEAR(j["spin"][2].get<double>(), expected.outgoing.spin.z, 1e-9);
  EXPECT_NEAR(j.at("impulse_total").get<double>(), expected.impulse_total, 1e-14);
}

// With no friction the impact only scales the normal velocity by -e (eq. 16b with a
// linear vy(P_I)) and leaves the tangential one alone.
TEST(Rebound, FrictionlessImpactReflects) {
  const double speed = 1.3;
  const double alpha = 35.0;
  const double e = 0.9;
  const ProcessResult run = cueplan(
      "rebound --speed 1.3 --angle 35 --topspin-k 0.4 --sidespin-k 1.5 "
      "--mu-cushion 0 --mu-table 0 --restitution 0.9 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);
  const double a = alpha * std::numbers::pi / 180.0;
  const double vx_in = speed * std::cos(a);
  const double vy_in = speed * std::sin(a);
  EXPECT_NEAR(j["velocity"][0].get<double>(), vx_in, 1e-10);
  EXPECT_NEAR(j["velocity"][1].get<double>(), -e * vy_in, 1e-10);
  EXPECT_NEAR(j.at("rebound_speed").get<double>(), std::hypot(vx_in, e * vy_in), 1e-10);
  EXPECT_NEAR(j.at("rebound_angle_deg").get<double>(),
              std::atan2(e * vy_in, vx_in) * 180.0 / std::numbers::pi, 1e-8);
}

TEST(Rebound, AboveTheRigidLimitIsSolvedAndFlagged) {
  const ProcessResult text = cueplan("rebound --speed 4 --angle 60");
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("rigid_limit_exceeded"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("warning: "), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("2.5 m/s"), std::string::npos) << text.out;

  const ProcessResult json_run = cueplan("rebound --speed 4 --angle 60 --json");
  ASSERT_EQ(json_run.exit_code, 0) << json_run.err;
  const json j = json::parse(json_run.out);
  EXPECT_EQ(j.at("status"), "rigid_limit_exceeded");
  EXPECT_TRUE(j.contains("warning"));
}

// ---------------------------------------------------------------------------
// rebound: bad input

struct BadInput {
  const char* name;
  const char* args;
  const char* flag;  // the flag the one-line message must name
};

// gtest prints a parameter with PrintTo: the case name instead of its bytes.
void PrintTo(const BadInput& input, std::ostream* os) { *os << input.name; }

class ReboundBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(ReboundBadInput, ExitsTwoWithOneLineNamingTheFlag) {
  const ProcessResult run = cueplan(GetParam().args);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.out, "");
  const std::vector<std::string> lines = lines_of(run.err);
  ASSERT_EQ(lines.size(), 1u) << run.err;
  EXPECT_EQ(lines[0].rfind("cueplan", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find(GetParam().flag), std::string::npos) << lines[0];
}

INSTANTIATE_TEST_SUITE_P(
    Cli, ReboundBadInput,
    ::testing::Values(
        BadInput{"ZeroSpeed", "rebound --speed 0 --angle 45", "--speed"},
        BadInput{"NegativeSpeed", "rebound --speed -1 --angle 45", "--speed"},
        BadInput{"NanSpeed", "rebound --speed nan --angle 45", "--speed"},
        BadInput{"WordForSpeed", "rebound --speed fast --angle 45", "--speed"},
        BadInput{"AngleAbove180", "rebound --speed 1 --angle 190", "--angle"},
        BadInput{"ZeroAngle", "rebound --speed 1 --angle 0", "--angle"},
        BadInput{"NanAngle", "rebound --speed 1 --angle nan", "--angle"},
        BadInput{"NanTopspinK", "rebound --speed 1 --angle 45 --topspin-k nan", "--topspin-k"},
        BadInput{"NegativeMass", "rebound --speed 1 --angle 45 --mass -0.1", "--mass"},
        BadInput{"ZeroRadius", "rebound --speed 1 --angle 45 --radius 0", "--radius"},
        BadInput{"NegativeCushionFriction", "rebound --speed 1 --angle 45 --mu-cushion -0.1",
                 "--mu-cushion"},
        BadInput{"NegativeTableFriction", "rebound --speed 1 --angle 45 --mu-table -0.2",
                 "--mu-table"},
        BadInput{"RestitutionAboveOne", "rebound --speed 1 --angle 45 --restitution 1.5",
                 "--restitution"},
        BadInput{"ZeroRestitution", "rebound --speed 1 --angle 45 --restitution 0",
                 "--restitution"},
        BadInput{"CushionBelowEquator", "rebound --speed 1 --angle 45 --cushion-height 0.02",
                 "--cushion-height"},
        BadInput{"UnknownMethod", "rebound --speed 1 --angle 45 --method magic", "--method"},
        BadInput{"UnknownCushionModel", "rebound --speed 1 --angle 45 --cushion-model han",
                 "--cushion-model"},
        BadInput{"StrongeEtaSquaredOutOfRange",
                 "rebound --speed 1 --angle 45 --cushion-model stronge_compliant --eta-squared 5",
                 "--eta-squared"},
        BadInput{"HanRestitutionTooLow",
                 "rebound --speed 1 --angle 45 --cushion-model han_2005 --restitution 0.1",
                 "--restitution"},
        BadInput{"NegativeSteps", "rebound --speed 1 --angle 45 --method paper --steps -5",
                 "--steps"},
        BadInput{"LooseTolerance", "rebound --speed 1 --angle 45 --tolerance 0.5", "--tolerance"},
        BadInput{"BothTopspinForms", "rebound --speed 1 --angle 45 --topspin 30 --topspin-k 1",
                 "--topspin"},
        BadInput{"MissingAngle", "rebound --speed 1", "--angle"},
        BadInput{"UnknownFlag", "rebound --speed 1 --angle 45 --spin 3", "--spin"},
        BadInput{"MissingValue", "rebound --speed 1 --angle", "--angle"},
        BadInput{"ThreadsWithoutBatch", "rebound --speed 1 --angle 45 --threads 2", "--threads"},
        BadInput{"MissingBatchFile", "rebound --batch /nonexistent/impacts.csv", "--batch"},
        BadInput{"NoCommand", "", "subcommand"},
        BadInput{"UnknownCommand", "bounce --speed 1", "bounce"},
        BadInput{"FiguresWithoutOut", "figures", "--out"},
        BadInput{"FiguresZeroAlphaStep", "figures --out /tmp --alpha-step 0", "--alpha-step"}),
    [](const ::testing::TestParamInfo<BadInput>& param) { return param.param.name; });

TEST(Rebound, AngleMessageIsTheDocumentedOne) {
  const ProcessResult run = cueplan("rebound --speed 1 --angle 190");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err, "cueplan rebound: --angle must lie in (0, 180) degrees, got 190\n");
}

// ---------------------------------------------------------------------------
// help and version

TEST(Help, TopLevelHelpListsTheCommands) {
  const ProcessResult run = cueplan("--help");
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_NE(run.out.find("rebound"), std::string::npos);
  EXPECT_NE(run.out.find("figures"), std::string::npos);
}

TEST(Help, ReboundHelpStatesEveryFlagWithUnitsAndDefaults) {
  const ProcessResult run = cueplan("rebound --help");
  EXPECT_EQ(run.exit_code, 0);
  for (const char* needle : {"--speed",
                             "--angle",
                             "--topspin-k",
                             "--sidespin-k",
                             "--topspin",
                             "--sidespin",
                             "--method",
                             "--steps",
                             "--tolerance",
                             "--mu-cushion",
                             "--mu-table",
                             "--restitution",
                             "--cushion-height",
                             "--mass",
                             "--radius",
                             "--json",
                             "--batch",
                             "--threads",
                             "--table-cache",
                             "m/s",
                             "deg",
                             "rad/s",
                             "(kg)",
                             "(m)",
                             "7R/5",
                             "5000",
                             "1e-12",
                             "0.98",
                             "0.14",
                             "0.212",
                             "0.1406",
                             "0.02625"})
    EXPECT_NE(run.out.find(needle), std::string::npos) << "missing " << needle;
}

TEST(Help, VersionPrintsTheVersion) {
  const ProcessResult run = cueplan("--version");
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_EQ(run.out.rfind("cueplan ", 0), 0u) << run.out;
}

// ---------------------------------------------------------------------------
// rebound --batch

constexpr const char* kBatchHeader =
    "speed,angle_deg,topspin_k,sidespin_k,rebound_speed,rebound_angle_deg,vx,vy,wx,wy,wz,"
    "status,message";

TEST(Batch, EveryRowComesOutAndBadRowsAloneFail) {
  const fs::path input = scratch() / "mixed.csv";
  write_text(input,
             "speed,angle_deg,topspin_k,sidespin_k\n"
             "1,45,1,0\n"
             "2,30,0.5,-1\n"
             "1,190,1,0\n"
             "1,fast,1,0\n"
             "1,45,1\n"
             "nan,45,1,0\n"
             "0.5,89,2,1\n");
  const ProcessResult run = cueplan("rebound --batch '" + input.string() + "'");
  EXPECT_EQ(run.exit_code, 1) << "some rows failed";
  EXPECT_EQ(run.err,
            "cueplan rebound: 7 rows: 2 invalid_input, 3 ok, 2 parse_error; 4 failed\n");
  EXPECT_EQ(lines_of(run.out).at(0), kBatchHeader);
  const auto rows = csv_rows(run.out);
  ASSERT_EQ(rows.size(), 7u);
  const std::vector<std::string> statuses = {
      "ok", "ok", "invalid_input", "parse_error", "parse_error", "invalid_input", "ok"};
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].at("status"), statuses[i]) << "row " << i;
    const bool good = statuses[i] == "ok";
    EXPECT_EQ(rows[i].at("rebound_speed").empty(), !good) << "row " << i;
    EXPECT_EQ(rows[i].at("message").empty(), good) << "row " << i;
  }
  EXPECT_NE(rows[2].at("message").find("angle_deg"), std::string::npos);

  const phys::ImpactResult second = library_rebound({}, 2.0, 30.0, 0.5, -1.0);
  EXPECT_NEAR(std::stod(rows[1].at("rebound_speed")), second.rebound_speed, 1e-12);
  EXPECT_NEAR(std::stod(rows[1].at("rebound_angle_deg")), second.rebound_angle_deg, 1e-10);
  EXPECT_NEAR(std::stod(rows[1].at("wz")), second.outgoing.spin.z, 1e-9);
}

TEST(Batch, OutputIsTheSameForAnyThreadCount) {
  const fs::path input = scratch() / "many.csv";
  std::string text = "speed,angle_deg,topspin_k,sidespin_k\n";
  for (int i = 0; i < 60; ++i)
    text += std::to_string(0.3 + 0.05 * i) + "," + std::to_string(2 + 2.9 * i) + "," +
            std::to_string(-1.0 + 0.05 * i) + "," + std::to_string(1.5 - 0.05 * i) + "\n";
  write_text(input, text);
  const ProcessResult one = cueplan("rebound --batch '" + input.string() + "' --threads 1");
  const ProcessResult two = cueplan("rebound --batch '" + input.string() + "' --threads 2");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_EQ(lines_of(one.out).size(), 61u);
  EXPECT_EQ(one.out, two.out);  // deliberate exact comparison: determinism
}

TEST(Batch, ReadsStandardInputAndSummarisesOnStderr) {
  const fs::path input = scratch() / "good.csv";
  write_text(input, "speed,angle_deg,topspin_k,sidespin_k\n1,45,1,0\n3,80,0,0\n");
  const ProcessResult file = cueplan("rebound --batch '" + input.string() + "'", "file");
  const ProcessResult piped = cueplan("rebound --batch - < '" + input.string() + "'", "stdin");
  ASSERT_EQ(piped.exit_code, 0) << piped.err;  // flagged (rigid limit) is not failed
  EXPECT_EQ(piped.err, "cueplan rebound: 2 rows: 1 ok, 1 rigid_limit_exceeded; none failed\n");
  EXPECT_EQ(piped.out, file.out);
  EXPECT_EQ(lines_of(piped.out).size(), 3u);
}

// Rows are read, resolved and written in blocks (8192 impacts): a file longer than a
// block gives the rows its two halves give.
TEST(Batch, BlocksDoNotChangeTheRows) {
  const std::string header = "speed,angle_deg,topspin_k,sidespin_k\n";
  std::string first, second;
  for (int i = 0; i < 9000; ++i)
    (i < 4000 ? first : second) += fmt::format("{},{},{},{}\n", 0.2 + 0.0003 * i,
                                               1 + 0.0197 * i, -1 + 0.0002 * i, 0.5);
  write_text(scratch() / "whole.csv", header + first + second);
  write_text(scratch() / "first.csv", header + first);
  write_text(scratch() / "second.csv", header + second);
  const std::string method = " --method paper --steps 20 --threads 2";
  const ProcessResult whole =
      cueplan("rebound --batch '" + (scratch() / "whole.csv").string() + "'" + method, "whole");
  const ProcessResult a =
      cueplan("rebound --batch '" + (scratch() / "first.csv").string() + "'" + method, "a");
  const ProcessResult b =
      cueplan("rebound --batch '" + (scratch() / "second.csv").string() + "'" + method, "b");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const std::vector<std::string> lines = lines_of(whole.out);
  ASSERT_EQ(lines.size(), 9001u);
  const std::string header_line = lines.front() + "\n";
  ASSERT_EQ(b.out.rfind(header_line, 0), 0u);
  EXPECT_EQ(whole.out, a.out + b.out.substr(header_line.size()));  // deliberate: determinism
}

TEST(Batch, WrongHeaderIsAWholeCommandError) {
  const fs::path input = scratch() / "wrong_header.csv";
  write_text(input, "v,alpha,kt,ks\n1,45,1,0\n");
  const ProcessResult run = cueplan("rebound --batch '" + input.string() + "'");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.out, "");
  EXPECT_EQ(lines_of(run.err).size(), 1u);
  EXPECT_NE(run.err.find("speed,angle_deg,topspin_k,sidespin_k"), std::string::npos);
}

// ---------------------------------------------------------------------------
// figures

TEST(Figures, WritesEveryFigureAndItsNumbers) {
  const fs::path dir = scratch() / "figures" / "nested";
  const ProcessResult run = cueplan("figures --out '" + dir.string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char* stem :
       {"fig08_rolling", "fig09_topspin", "fig10_sidespin", "fig12_slip_vs_impulse"}) {
    const std::string svg = read_text(dir / (std::string(stem) + ".svg"));
    EXPECT_EQ(svg.rfind("<?xml", 0), 0u) << stem;
    EXPECT_NE(svg.find("</svg>"), std::string::npos) << stem;
    EXPECT_FALSE(csv_rows(read_text(dir / (std::string(stem) + ".csv"))).empty()) << stem;
  }
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();

  // The paper's figure 8 result: a rolling ball's rebound angle depends on alpha only.
  std::map<std::string, std::vector<double>> angles_by_alpha;
  for (const auto& row : csv_rows(read_text(dir / "fig08_rolling.csv"))) {
    ASSERT_EQ(row.at("status"), "ok");
    angles_by_alpha[row.at("angle_deg")].push_back(std::stod(row.at("rebound_angle_deg")));
  }
  EXPECT_GT(angles_by_alpha.size(), 90u);
  for (const auto& [alpha, angles] : angles_by_alpha) {
    ASSERT_GE(angles.size(), 4u) << alpha;
    const auto [lo, hi] = std::minmax_element(angles.begin(), angles.end());
    EXPECT_LT(*hi - *lo, 1e-8) << "alpha " << alpha;
  }

  // The paper's figure 10 results: right spin can make the ball leave faster than it
  // came, and strong left spin near head-on sends it back toward where it came from.
  double fastest_right_spin = 0.0;
  double head_on_left_spin_angle = 0.0;
  for (const auto& row : csv_rows(read_text(dir / "fig10_sidespin.csv"))) {
    if (row.at("sidespin_k") == "2")
      fastest_right_spin = std::max(fastest_right_spin, std::stod(row.at("rebound_speed")));
    if (row.at("sidespin_k") == "-2" && row.at("angle_deg") == "90")
      head_on_left_spin_angle = std::stod(row.at("rebound_angle_deg"));
  }
  EXPECT_GT(fastest_right_spin, 1.0);  // V0 = 1 m/s
  EXPECT_GT(head_on_left_spin_angle, 90.0);

  // Figure 12 runs over the cushion impulse from zero upward.
  const auto slips = csv_rows(read_text(dir / "fig12_slip_vs_impulse.csv"));
  ASSERT_GT(slips.size(), 10u);
  EXPECT_EQ(std::stod(slips.front().at("impulse")), 0.0);
  for (size_t i = 1; i < slips.size(); ++i)
    EXPECT_GE(std::stod(slips[i].at("impulse")), std::stod(slips[i - 1].at("impulse")));
}

TEST(Figures, FormatFlagChoosesPdfOrPng) {
  for (const auto& [format, magic] : {std::pair<std::string, std::string>{"pdf", "%PDF-"},
                                      std::pair<std::string, std::string>{"png", "\x89PNG"}}) {
    const fs::path dir = scratch() / ("figures_" + format);
    const ProcessResult run =
        cueplan("figures --alpha-step 5 --format " + format + " --out '" + dir.string() + "'", format);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    for (const char* stem : {"fig08_rolling", "fig09_topspin", "fig10_sidespin", "fig12_slip_vs_impulse"}) {
      EXPECT_EQ(read_text(dir / (std::string(stem) + "." + format)).substr(0, magic.size()), magic) << stem;
      EXPECT_TRUE(fs::exists(dir / (std::string(stem) + ".csv"))) << stem;
      EXPECT_FALSE(fs::exists(dir / (std::string(stem) + ".svg"))) << stem;
    }
  }
}

TEST(Figures, UnwritableDirectoryExitsTwo) {
  const fs::path blocker = scratch() / "a_file";
  write_text(blocker, "not a directory\n");
  const ProcessResult run = cueplan("figures --out '" + (blocker / "figs").string() + "'");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(lines_of(run.err).size(), 1u) << run.err;
  EXPECT_NE(run.err.find("--out"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace cli_test
