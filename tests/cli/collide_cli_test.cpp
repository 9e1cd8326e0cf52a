// Tests of `cueplan collide`, run as a separate process the way a user runs it: what it
// prints, its JSON and batch output, its exit codes, and that its numbers are the
// library's and obey the facts of a cut shot.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "cli_test_support.hpp"
#include "cueplan/physics/ball_collision.hpp"

// The test files share their helpers (cli_test_support.hpp) by living in its namespace.
namespace cli_test {

const char* const kScratchName = "cueplan_collide_test_";

namespace {

namespace fs = std::filesystem;
namespace phys = cueplan::physics;
using nlohmann::json;

constexpr double kDeg = std::numbers::pi / 180.0;

// The library's answer for a cue ball along +x at `speed` with `spin` cutting an object
// ball at rest by `cut_deg`, in the table frame.
phys::CollisionResult library_cut(const phys::BallBallParams& p, double speed, double cut_deg,
                                  phys::Vec3 spin, const phys::CollisionOptions& options = {}) {
  const phys::CutShot s = phys::cut_shot(speed, cut_deg, spin, p.radius);
  return phys::resolve_table_collision(p, s.cue_centre, s.cue_ball, s.object_centre, s.object_ball,
                                       options);
}

void expect_ball(const json& j, const phys::BallState& expected, double radius, double tol,
                 const char* which) {
  ASSERT_EQ(j.at("velocity").size(), 2u) << which;
  ASSERT_EQ(j.at("spin").size(), 3u) << which;
  EXPECT_NEAR(j["velocity"][0].get<double>(), expected.velocity.x, tol) << which;
  EXPECT_NEAR(j["velocity"][1].get<double>(), expected.velocity.y, tol) << which;
  EXPECT_NEAR(j["spin"][0].get<double>(), expected.spin.x, tol / radius) << which;
  EXPECT_NEAR(j["spin"][1].get<double>(), expected.spin.y, tol / radius) << which;
  EXPECT_NEAR(j["spin"][2].get<double>(), expected.spin.z, tol / radius) << which;
  const phys::Vec3 rolling = phys::rolling_velocity(expected, radius);
  EXPECT_NEAR(j["rolling_velocity"][0].get<double>(), rolling.x, tol) << which;
  EXPECT_NEAR(j["rolling_velocity"][1].get<double>(), rolling.y, tol) << which;
  EXPECT_NEAR(j.at("rolling_speed").get<double>(), std::hypot(rolling.x, rolling.y), tol) << which;
  EXPECT_NEAR(j.at("rolling_angle_deg").get<double>(), std::atan2(rolling.y, rolling.x) / kDeg,
              1e-9)
      << which;
}

// ---------------------------------------------------------------------------
// text and JSON

TEST(Collide, SpelledOutCommandPrintsBothBallsWithUnits) {
  const ProcessResult run = cueplan("collide --speed 1 --cut 30 --topspin-k 1");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "");
  for (const char* needle :
       {"incoming", "cue ball", "object ball", "rolls at", "throw", "status", "ok",
        "mathavan_2014, exact", "m/s", "rad/s", "deg from +x", "N s", " J", "transitions", "frame"})
    EXPECT_NE(run.out.find(needle), std::string::npos) << "missing '" << needle << "' in\n"
                                                       << run.out;
}

TEST(Collide, JsonEqualsTheLibraryResult) {
  const ProcessResult run =
      cueplan("collide --speed 1.3 --cut -25 --topspin-k 0.5 --sidespin-k -0.7 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);
  const phys::BallBallParams p;
  const double unit = 1.3 / p.radius;
  const phys::CollisionResult expected = library_cut(p, 1.3, -25.0, {0.0, 0.5 * unit, -0.7 * unit});
  EXPECT_EQ(j.at("status"), "ok");
  EXPECT_EQ(j.at("model"), "mathavan_2014");
  expect_ball(j.at("cue_ball"), expected.ball_i, p.radius, 1e-12, "cue ball");
  expect_ball(j.at("object_ball"), expected.ball_j, p.radius, 1e-12, "object ball");
  const double line_of_centres = 25.0;  // deg: the object ball's centre at 2R (cos 25, sin 25)
  EXPECT_NEAR(
      j.at("throw_deg").get<double>(),
      std::atan2(expected.ball_j.velocity.y, expected.ball_j.velocity.x) / kDeg - line_of_centres,
      1e-9);
  EXPECT_NEAR(j.at("impulse_total").get<double>(), expected.impulse_total, 1e-14);
  EXPECT_EQ(j.at("rhs_evaluations").get<int>(), expected.rhs_evaluations);
  EXPECT_EQ(j.at("input").at("cut_deg"), -25.0);
  EXPECT_NEAR(j.at("input").at("sidespin_k").get<double>(), -0.7, 1e-12);
  EXPECT_EQ(j.at("units").at("rolling_angle_deg"), "deg from +x");
  for (const char* key :
       {"cue_ball", "object_ball", "throw_deg", "model", "status", "input", "units"})
    EXPECT_TRUE(j.contains(key)) << key;
}

// Every flag reaches the library: the closed form with speed-dependent friction, rad/s
// spins, a pool ball with its own mass, radius and friction; then the paper scheme.
TEST(Collide, FlagsReachTheLibrary) {
  const ProcessResult closed = cueplan(
      "collide --speed 2.1 --cut 40 --topspin 30 --sidespin -12 --model frictional_inelastic "
      "--ball-friction speed_dependent --mass 0.17 --radius 0.028575 --ball-restitution 0.93 "
      "--mu-table 0.2 --json");
  ASSERT_EQ(closed.exit_code, 0) << closed.err;
  phys::BallBallParams p;
  p.model = phys::BallModel::frictional_inelastic;
  p.friction = phys::BallFriction::speed_dependent;
  p.mass = 0.17;
  p.radius = 0.028575;
  p.restitution = 0.93;
  p.mu_table = 0.2;
  const json j = json::parse(closed.out);
  EXPECT_EQ(j.at("model"), "frictional_inelastic");
  EXPECT_EQ(j.at("input").at("ball_friction"), "speed_dependent");
  const phys::CollisionResult expected = library_cut(p, 2.1, 40.0, {0.0, 30.0, -12.0});
  expect_ball(j.at("cue_ball"), expected.ball_i, p.radius, 1e-12, "cue ball");
  expect_ball(j.at("object_ball"), expected.ball_j, p.radius, 1e-12, "object ball");

  const ProcessResult paper = cueplan(
      "collide --speed 1 --cut 10 --spin 3,-40,25 --method paper --steps 800 --mu-ball 0.07 "
      "--json");
  ASSERT_EQ(paper.exit_code, 0) << paper.err;
  phys::BallBallParams q;
  q.mu_ball = 0.07;
  phys::CollisionOptions o;
  o.method = phys::CollisionMethod::paper;
  o.paper_steps = 800;
  const json k = json::parse(paper.out);
  const phys::CollisionResult from_paper = library_cut(q, 1.0, 10.0, {3.0, -40.0, 25.0}, o);
  expect_ball(k.at("cue_ball"), from_paper.ball_i, q.radius, 1e-12, "cue ball");
  EXPECT_EQ(k.at("rhs_evaluations").get<int>(), from_paper.rhs_evaluations);
  EXPECT_EQ(k.at("input").at("method"), "paper");
}

// The 30-degree rule through the command: a rolling cue ball, half-ball hit, e_b = 1 and no
// ball friction rolls off at atan(sin c cos c / (sin^2 c + 2/5)) = 33.7 deg from its line
// (to the left of a cut to the right).
TEST(Collide, ThirtyDegreeRule) {
  const ProcessResult run =
      cueplan("collide --speed 1.5 --cut 30 --topspin-k 1 --mu-ball 0 --ball-restitution 1 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);
  const double s = std::sin(30.0 * kDeg), c = std::cos(30.0 * kDeg);
  EXPECT_NEAR(j.at("cue_ball").at("rolling_angle_deg").get<double>(),
              std::atan(s * c / (s * s + 0.4)) / kDeg, 1e-9);
  EXPECT_NEAR(j.at("object_ball").at("rolling_angle_deg").get<double>(), -30.0, 1e-9);
  EXPECT_NEAR(j.at("throw_deg").get<double>(), 0.0, 1e-9);
}

// A full-ball stun shot without ball friction and with e = 1 stops the cue ball dead; the
// object ball slides off at the cue ball's speed and rolls at 5/7 of it.
TEST(Collide, FullBallStunShotStopsTheCueBall) {
  const ProcessResult run =
      cueplan("collide --speed 2 --cut 0 --topspin-k 0 --mu-ball 0 --ball-restitution 1 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);
  EXPECT_NEAR(j["cue_ball"]["velocity"][0].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(j["cue_ball"]["rolling_speed"].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(j["object_ball"]["velocity"][0].get<double>(), 2.0, 1e-12);
  EXPECT_NEAR(j["object_ball"]["rolling_speed"].get<double>(), 2.0 * 5.0 / 7.0, 1e-12);
}

// ---------------------------------------------------------------------------
// bad input

struct BadInput {
  const char* name;
  const char* args;
  const char* flag;  // the flag the one-line message must name
};

void PrintTo(const BadInput& input, std::ostream* os) { *os << input.name; }

class CollideBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(CollideBadInput, ExitsTwoWithOneLineNamingTheFlag) {
  const ProcessResult run = cueplan(GetParam().args);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.out, "");
  const std::vector<std::string> lines = lines_of(run.err);
  ASSERT_EQ(lines.size(), 1u) << run.err;
  EXPECT_EQ(lines[0].rfind("cueplan collide", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find(GetParam().flag), std::string::npos) << lines[0];
}

INSTANTIATE_TEST_SUITE_P(
    Cli, CollideBadInput,
    ::testing::Values(
        BadInput{"ZeroSpeed", "collide --speed 0 --cut 30", "--speed"},
        BadInput{"NanSpeed", "collide --speed nan --cut 30", "--speed"},
        BadInput{"MissingSpeed", "collide --cut 30", "--speed"},
        BadInput{"MissingCut", "collide --speed 1", "--cut"},
        BadInput{"GrazingCut", "collide --speed 1 --cut 90", "--cut"},
        BadInput{"CutBeyondGrazing", "collide --speed 1 --cut -120", "--cut"},
        BadInput{"NanTopspinK", "collide --speed 1 --cut 30 --topspin-k nan", "--topspin-k"},
        BadInput{"InfiniteSidespin", "collide --speed 1 --cut 30 --sidespin inf", "--sidespin"},
        BadInput{"SpinWithTwoNumbers", "collide --speed 1 --cut 30 --spin 1,2", "--spin"},
        BadInput{"SpinNotANumber", "collide --speed 1 --cut 30 --spin 1,x,3", "--spin"},
        BadInput{"SpinWithTopspin", "collide --speed 1 --cut 30 --spin 1,2,3 --topspin-k 1",
                 "--spin"},
        BadInput{"BothTopspinForms", "collide --speed 1 --cut 30 --topspin 30 --topspin-k 1",
                 "--topspin"},
        BadInput{"UnknownModel", "collide --speed 1 --cut 30 --model mathavan_2010", "--model"},
        BadInput{"UnknownBallFriction", "collide --speed 1 --cut 30 --ball-friction fast",
                 "--ball-friction"},
        BadInput{"UnknownMethod", "collide --speed 1 --cut 30 --method table", "--method"},
        BadInput{"NoSteps", "collide --speed 1 --cut 30 --method paper --steps 0", "--steps"},
        BadInput{"LooseTolerance", "collide --speed 1 --cut 30 --tolerance 0.5", "--tolerance"},
        BadInput{"NegativeBallFriction", "collide --speed 1 --cut 30 --mu-ball -0.1", "--mu-ball"},
        BadInput{"BallFrictionTooLargeForTheCloth",
                 "collide --speed 1 --cut 30 --mu-ball 0.9 --mu-table 0.9", "--mu-table"},
        BadInput{"RestitutionAboveOne", "collide --speed 1 --cut 30 --ball-restitution 1.2",
                 "--ball-restitution"},
        BadInput{"NegativeClothFriction", "collide --speed 1 --cut 30 --mu-table -1", "--mu-table"},
        BadInput{"ZeroMass", "collide --speed 1 --cut 30 --mass 0", "--mass"},
        BadInput{"NegativeRadius", "collide --speed 1 --cut 30 --radius -0.02", "--radius"},
        BadInput{"ThreadsWithoutBatch", "collide --speed 1 --cut 30 --threads 2", "--threads"},
        BadInput{"BatchWithSpeed", "collide --batch x.csv --speed 1", "--speed"},
        BadInput{"MissingBatchFile", "collide --batch /nonexistent/shots.csv", "--batch"}),
    [](const ::testing::TestParamInfo<BadInput>& param) { return param.param.name; });

TEST(Collide, CutMessageIsTheDocumentedOne) {
  const ProcessResult run = cueplan("collide --speed 1 --cut 90");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err,
            "cueplan collide: --cut must lie in (-90, 90) degrees: at 90 the cue ball only grazes "
            "the object ball, got 90\n");
}

TEST(Collide, HelpStatesEveryFlagWithUnitsAndDefaults) {
  const ProcessResult run = cueplan("collide --help");
  EXPECT_EQ(run.exit_code, 0);
  for (const char* needle : {"--speed",
                             "--cut",
                             "--topspin-k",
                             "--sidespin-k",
                             "--topspin",
                             "--sidespin",
                             "--spin",
                             "--model",
                             "--ball-friction",
                             "--method",
                             "--steps",
                             "--tolerance",
                             "--mu-ball",
                             "--ball-restitution",
                             "--mu-table",
                             "--mass",
                             "--radius",
                             "--json",
                             "--batch",
                             "--threads",
                             "m/s",
                             "deg",
                             "rad/s",
                             "(kg)",
                             "(m)",
                             "mathavan_2014",
                             "0.89",
                             "0.05",
                             "0.212",
                             "0.1406",
                             "0.02625",
                             "5000",
                             "1e-12"})
    EXPECT_NE(run.out.find(needle), std::string::npos) << "missing " << needle;
}

// ---------------------------------------------------------------------------
// --batch

constexpr const char* kBatchHeader =
    "speed,cut_deg,topspin_k,sidespin_k,cue_vx,cue_vy,cue_wx,cue_wy,cue_wz,cue_rolling_vx,"
    "cue_rolling_vy,cue_rolling_speed,cue_rolling_angle_deg,object_vx,object_vy,object_wx,"
    "object_wy,object_wz,object_rolling_vx,object_rolling_vy,object_rolling_speed,"
    "object_rolling_angle_deg,throw_deg,status,message";

TEST(CollideBatch, EveryRowComesOutAndBadRowsAloneFail) {
  const fs::path input = scratch() / "mixed.csv";
  write_text(input,
             "speed,cut_deg,topspin_k,sidespin_k\n"
             "1,30,1,0\n"
             "2,-15,0.5,-1\n"
             "1,95,1,0\n"
             "1,thin,1,0\n"
             "1,30,1\n"
             "0,30,1,0\n"
             "1,30,nan,0\n"
             "0.5,5,-1,0.3\n");
  const ProcessResult run = cueplan("collide --batch '" + input.string() + "'");
  EXPECT_EQ(run.exit_code, 1) << "some rows failed";
  EXPECT_EQ(run.err, "cueplan collide: 8 rows: 3 invalid_input, 3 ok, 2 parse_error; 5 failed\n");
  EXPECT_EQ(lines_of(run.out).at(0), kBatchHeader);
  const auto rows = csv_rows(run.out);
  ASSERT_EQ(rows.size(), 8u);
  const std::vector<std::string> statuses = {
      "ok", "ok", "invalid_input", "parse_error", "parse_error", "invalid_input", "invalid_input",
      "ok"};
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].at("status"), statuses[i]) << "row " << i;
    const bool good = statuses[i] == "ok";
    EXPECT_EQ(rows[i].at("throw_deg").empty(), !good) << "row " << i;
    EXPECT_EQ(rows[i].at("message").empty(), good) << "row " << i;
  }
  EXPECT_NE(rows[2].at("message").find("cut_deg"), std::string::npos);
  EXPECT_NE(rows[5].at("message").find("speed"), std::string::npos);
  EXPECT_NE(rows[6].at("message").find("topspin_k"), std::string::npos);

  const phys::BallBallParams p;
  const double unit = 2.0 / p.radius;
  const phys::CollisionResult second = library_cut(p, 2.0, -15.0, {0.0, 0.5 * unit, -1.0 * unit});
  EXPECT_NEAR(std::stod(rows[1].at("object_vx")), second.ball_j.velocity.x, 1e-12);
  EXPECT_NEAR(std::stod(rows[1].at("cue_wz")), second.ball_i.spin.z, 1e-10);
  const phys::Vec3 rolling = phys::rolling_velocity(second.ball_i, p.radius);
  EXPECT_NEAR(std::stod(rows[1].at("cue_rolling_vy")), rolling.y, 1e-12);
}

TEST(CollideBatch, OutputIsTheSameForAnyThreadCount) {
  const fs::path input = scratch() / "many.csv";
  std::string text = "speed,cut_deg,topspin_k,sidespin_k\n";
  for (int i = 0; i < 40; ++i)
    text += std::to_string(0.3 + 0.07 * i) + "," + std::to_string(-80 + 4.1 * i) + "," +
            std::to_string(-1.0 + 0.05 * i) + "," + std::to_string(1.0 - 0.05 * i) + "\n";
  write_text(input, text);
  const ProcessResult one = cueplan("collide --batch '" + input.string() + "' --threads 1");
  const ProcessResult two = cueplan("collide --batch '" + input.string() + "' --threads 2");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_EQ(lines_of(one.out).size(), 41u);
  EXPECT_EQ(one.out, two.out);  // deliberate exact comparison: determinism
}

TEST(CollideBatch, WrongHeaderIsAWholeCommandError) {
  const fs::path input = scratch() / "wrong_header.csv";
  write_text(input, "speed,angle_deg,topspin_k,sidespin_k\n1,30,1,0\n");
  const ProcessResult run = cueplan("collide --batch '" + input.string() + "'");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.out, "");
  EXPECT_EQ(lines_of(run.err).size(), 1u);
  EXPECT_NE(run.err.find("speed,cut_deg,topspin_k,sidespin_k"), std::string::npos);
}

}  // namespace
}  // namespace cli_test
