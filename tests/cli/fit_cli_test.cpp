// Tests of `cueplan fit`, run as a separate process: it recovers the strokes of shots
// simulated on the carom preset and sampled like the tracker (irregular ~50 Hz, ~1 cm
// noise); bad shots are named and skipped while the rest are fitted; its JSON keys; and
// its `problem` replays its `tracks` through `cueplan simulate`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_support.hpp"
#include "cueplan/physics/shot.hpp"
#include "cueplan/planner/fit.hpp"
#include "cueplan/problems/presets.hpp"
#include "cueplan/problems/problem.hpp"

namespace cli_test {

const char* const kScratchName = "cueplan_fit_test_";

namespace {

namespace phys = cueplan::physics;
namespace plan = cueplan::planner;
namespace prob = cueplan::problems;
using nlohmann::json;

struct Truth {
  phys::Shot shot;
  double offset_s;
};

// Strokes near natural roll (k_T -> 1) slide for a few samples only: their speed and
// topspin trade off within the noise (the rolling speed V (5 + 2 k_T) / 7 is what the
// samples pin), so the strokes here keep |k_T| <= 0.5.

// A shot simulated on the carom preset and tracked: irregular sampling (20 ms +- 6 ms,
// sparser once a ball rolls slowly), Gaussian noise of 1 cm on each coordinate, the
// strike `offset_s` after t = 0; in the file's frame and units.
json tracked_shot(int id, const std::vector<phys::Vec2>& start, const Truth& truth,
                  std::mt19937& rng, const phys::Scene& table = prob::carom_scene()) {
  phys::Scene scene = table;
  for (size_t k = 1; k < start.size(); ++k)
    scene.balls.push_back({"b" + std::to_string(k), start[k]});
  phys::SimulationOptions o;
  o.max_events = 400;
  const phys::ShotResult r = phys::simulate(scene, start[0], truth.shot, o);
  EXPECT_EQ(r.status, phys::ShotStatus::rest) << r.message;
  const plan::TrackFrame frame;
  std::normal_distribution<double> noise(0.0, 0.01);
  std::uniform_real_distribution<double> jitter(-0.006, 0.006);
  json balls = json::object();
  for (size_t k = 0; k < r.balls.size(); ++k) {
    const phys::BallOutcome& b = r.balls[k];
    json t = json::array(), x = json::array(), y = json::array();
    auto sample = [&](double time, phys::Vec2 p, bool noisy) {
      if (noisy) p = {p.x + noise(rng), p.y + noise(rng)};
      const phys::Vec2 f = frame.to_file(p);
      t.push_back(time);
      x.push_back(f.x);
      y.push_back(f.y);
    };
    sample(0.0, b.start, false);
    if (b.path.empty()) {  // never struck: start and end only
      sample(r.duration + 0.5, b.start, false);
    } else {
      const double end = b.path.back().t1 + truth.offset_s;
      // A ball at rest is not sampled (the format's rule): an object ball from when it
      // is struck.
      const double from = b.path.front().t0 + truth.offset_s;
      for (double time = 0.02 + jitter(rng); time < end; time += 0.02 + jitter(rng)) {
        if (time < from) continue;
        const double ts = time - truth.offset_s;
        phys::Vec2 p = b.start;
        if (ts > 0)
          for (const phys::PathSegment& s : b.path)
            if (ts >= s.t0 && ts <= s.t1) p = s.at(ts);
        sample(time, p, true);
        if (time > 3.0) time += 0.04;  // slow rolls are sampled more sparsely
      }
      sample(end + 0.2, b.final_position, true);
    }
    balls[std::to_string(k + 1)] = {{"t", t}, {"x", x}, {"y", y}};
  }
  return {{"id", id}, {"balls", balls}};
}

struct FitRun {
  std::vector<Truth> truths;
  ProcessResult result;
  std::vector<json> lines;
};

// Three good shots and five bad lines, fitted once for every test here.
const FitRun& fitted() {
  static const FitRun run = [] {
    FitRun r;
    std::mt19937 rng(7);
    r.truths = {{{3.2, 20.0, 0.4, -0.3}, 0.008},
                {{2.6, 155.0, -0.5, 0.6}, 0.013},
                {{4.1, -70.0, 0.3, 0.5}, 0.004}};  // side enough to show in the path (see below)
    const std::vector<std::vector<phys::Vec2>> starts = {
        {{0.5, 0.4}, {1.6, 0.9}, {2.2, 0.3}},
        {{2.3, 0.5}, {0.8, 1.1}, {1.4, 0.25}},
        {{1.2, 1.2}, {1.6, 0.5}, {0.4, 0.3}}};
    std::ostringstream file;
    file << tracked_shot(1, starts[0], r.truths[0], rng).dump() << '\n';
    file << "this is not JSON\n";
    file << R"({"id": 11, "balls": {"1": {"t": [], "x": [], "y": []}, "2": {"t": [0, 1], "x": [0, 0], "y": [0, 0]}}})" << '\n';
    file << tracked_shot(2, starts[1], r.truths[1], rng).dump() << '\n';
    file << R"({"id": 12, "balls": {"1": {"t": [0, 0.02, 0.04], "x": [0, 0.1, 0.2], "y": [0, 0, 0]}, "2": {"t": [0, 1], "x": [0.5, null], "y": [0, 0]}}})" << '\n';
    file << R"({"id": 13, "balls": {"1": {"t": [0, 0.02, 0.04], "x": [0, 0.1, 0.2], "y": [0, 0, 0]}, "2": {"t": [0, 1], "x": [0.02, 0.02], "y": [0, 0]}}})" << '\n';
    file << R"({"id": 14, "balls": {"1": {"t": [0, 0.04, 0.02], "x": [0, 0.1, 0.2], "y": [0, 0, 0]}, "2": {"t": [0, 1], "x": [0.5, 0.5], "y": [0, 0]}}})" << '\n';
    file << tracked_shot(3, starts[2], r.truths[2], rng).dump() << '\n';
    write_text(scratch() / "tracks.jsonl", file.str());
    // CUEPLAN_FIT_TEST_KEEP=PATH keeps a copy of the tracks, to rerun `cueplan fit` by hand.
    if (const char* keep = std::getenv("CUEPLAN_FIT_TEST_KEEP")) write_text(keep, file.str());
    r.result = cueplan("fit " + (scratch() / "tracks.jsonl").string() + " --json --png " +
                       (scratch() / "pictures").string());
    for (const std::string& line : lines_of(r.result.out))
      if (!line.empty()) r.lines.push_back(json::parse(line));
    return r;
  }();
  return run;
}

double angle_diff(double a, double b) { return std::remainder(a - b, 360.0); }

TEST(FitCli, RecoversSimulatedStrokes) {
  const FitRun& r = fitted();
  ASSERT_EQ(r.lines.size(), 3u) << r.result.err;
  for (size_t i = 0; i < 3; ++i) {
    const json& j = r.lines[i];
    const Truth& t = r.truths[i];
    EXPECT_EQ(j["id"], static_cast<int>(i + 1));
    const double speed = j["shot"]["speed"], aim = j["shot"]["aim_deg"];
    EXPECT_LT(std::fabs(speed / t.shot.speed - 1.0), 0.01)
        << "shot " << i + 1 << ": speed " << speed << " vs " << t.shot.speed;
    // The data fix the direction the cue ball leaves in: the cue's aim plus the squirt of
    // its side (PHYSICS.md, "Squirt and swerve"). The cue's aim itself is that less the
    // squirt of the fitted side, as uncertain as the side is where the shot barely shows
    // it; it is held to the squirt of a quarter of the side's range. The launch is held to
    // 0.4 deg: with the cue's elevation in the search the data do not fix it better, as the
    // swerve of a slightly raised cue bends the path as a slightly other aim would. Shot 2,
    // refitted with 6, 10 and 20 restarts: elevation 2.1, 1.2, 0.6 deg, launch 0.32, 0.18,
    // 0.09 deg off, RMSE 14.210, 14.199, 14.198 mm (1 cm noise a coordinate): fits apart by
    // 0.01 mm of RMSE, which rounding in the simulation moves between.
    const phys::Scene table = prob::carom_scene();
    const auto squirt = [&](double k) {
      return phys::squirt_angle_deg(table.cue, table.ball_and_cushion.mass, table.radius(), k);
    };
    const double fitted_launch = aim + squirt(j["shot"]["sidespin_k"].get<double>());
    const double true_launch = t.shot.aim_deg + squirt(t.shot.sidespin_k);
    EXPECT_LT(std::fabs(angle_diff(fitted_launch, true_launch)), 0.4)
        << "shot " << i + 1 << ": the cue ball leaves at " << fitted_launch << " vs " << true_launch;
    EXPECT_LT(std::fabs(angle_diff(aim, t.shot.aim_deg)), std::fabs(squirt(0.3125)))
        << "shot " << i + 1 << ": aim " << aim << " vs " << t.shot.aim_deg;
    // The noise alone is 1 cm per coordinate: 1.4 cm RMS in the plane.
    EXPECT_LT(j["rmse_cue_m"].get<double>(), 0.02) << "shot " << i + 1;
    EXPECT_GT(j["rmse_cue_m"].get<double>(), 0.008) << "shot " << i + 1;
  }
}

// The stroke search's flags reach the search: a smaller search spends fewer simulations
// (the JSON's shot.simulations), --max-elevation puts the cue's elevation into it within
// its bound, and a bad value is refused naming the flag.
TEST(FitCli, StrokeSearchFlags) {
  std::mt19937 rng(3);
  const auto tracks = scratch() / "search_flags.jsonl";
  write_text(tracks, tracked_shot(5, {{0.5, 0.4}, {1.6, 0.9}, {2.2, 0.3}},
                                  {{3.0, 25.0, 0.3, -0.2}, 0.006}, rng).dump() + "\n");
  const auto simulations = [&](const std::string& flags, double* elevation) -> long {
    const ProcessResult run = cueplan("fit " + tracks.string() + " --json --threads 1 " + flags);
    EXPECT_EQ(run.exit_code, 0) << flags << ": " << run.err;
    const std::vector<std::string> lines = lines_of(run.out);
    if (lines.empty() || lines[0].empty()) return -1;
    const json j = json::parse(lines[0]);
    if (elevation) *elevation = j["shot"]["elevation_deg"];
    EXPECT_LT(j["rmse_cue_m"].get<double>(), 0.03) << flags;
    return j["shot"]["simulations"];
  };
  double level = -1, raised = -1, by_default = -1;
  const long full = simulations("", &by_default);
  const long small = simulations(
      "--restarts 1 --spin-starts 0 --global-evaluations 300 --local-evaluations 200 "
      "--max-elevation 0", &level);
  const long elevated = simulations("--spin-starts 2 --max-elevation 15", &raised);
  std::cout << "simulations: default " << full << ", small " << small << ", elevation " << elevated
            << " (elevation " << raised << " deg)\n";
  EXPECT_EQ(level, 0.0);  // --max-elevation 0: a level cue
  EXPECT_GE(by_default, 0.0);
  EXPECT_LE(by_default, 20.0);  // the default search's bound
  EXPECT_GT(full, 2 * 2 * 2400);  // restarts of two global stages of 2400 each, and more
  EXPECT_LT(small, 2 * 300 + 200 * 5);
  EXPECT_GT(small, 300);
  EXPECT_GE(raised, 0.0);
  EXPECT_LE(raised, 15.0);
  for (const char* bad : {"--spin-starts -1", "--global-evaluations 5", "--local-evaluations nan",
                          "--max-elevation 75", "--restarts 0", "--huber-delta -0.01"}) {
    const ProcessResult run = cueplan("fit " + tracks.string() + " " + bad);
    EXPECT_EQ(run.exit_code, 2) << bad;
    const std::string flag = std::string(bad).substr(0, std::string(bad).find(' '));
    EXPECT_NE(run.err.find(flag), std::string::npos) << bad << ": " << run.err;
  }
  const ProcessResult cal = cueplan("calibrate " + tracks.string() + " --spin-starts -3");
  EXPECT_EQ(cal.exit_code, 2);
  EXPECT_NE(cal.err.find("--spin-starts"), std::string::npos) << cal.err;
}

TEST(FitCli, BadShotsAreNamedAndSkipped) {
  const FitRun& r = fitted();
  EXPECT_EQ(r.result.exit_code, 2);
  const std::string& err = r.result.err;
  EXPECT_NE(err.find(":2: line 2: not JSON"), std::string::npos) << err;
  EXPECT_NE(err.find("shot 11, ball 1: no samples"), std::string::npos) << err;
  EXPECT_NE(err.find("shot 12, ball 2: x[1] is null, not a number"), std::string::npos) << err;
  EXPECT_NE(err.find("shot 13, ball 2: overlaps ball 1 at the start"), std::string::npos) << err;
  EXPECT_NE(err.find("shot 14, ball 1: times out of order"), std::string::npos) << err;
  EXPECT_NE(err.find("5 shot(s) skipped"), std::string::npos) << err;
  EXPECT_EQ(r.lines.size(), 3u);
  for (int id = 1; id <= 3; ++id)
    EXPECT_TRUE(std::filesystem::exists(scratch() / "pictures" / ("shot_" + std::to_string(id) + ".png")));
}

TEST(FitCli, JsonKeysAndProblemReplaysTracks) {
  const FitRun& r = fitted();
  ASSERT_FALSE(r.lines.empty());
  std::vector<std::string> keys_seen;
  for (const auto& [key, value] : r.lines[0].items()) keys_seen.push_back(key);
  std::sort(keys_seen.begin(), keys_seen.end());
  EXPECT_EQ(keys_seen, (std::vector<std::string>{"id", "physics", "problem", "rmse_all_m",
                                                 "rmse_cue_m", "shot", "tracks"}));
  const json& j = r.lines[1];
  write_text(scratch() / "problem.json", j["problem"].dump());
  const json& s = j["shot"];
  const ProcessResult sim = cueplan(
      "simulate " + (scratch() / "problem.json").string() + " --json --max-events 400" +
          " --speed " + s["speed"].dump() + " --aim " + s["aim_deg"].dump() + " --topspin-k " +
          s["topspin_k"].dump() + " --sidespin-k " + s["sidespin_k"].dump() +
          " --elevation-deg " + s["elevation_deg"].dump(),
      "replay");
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const json out = json::parse(sim.out);
  const double offset = s["strike_offset_s"];
  const plan::TrackFrame frame;
  // Ball order in simulate's JSON: the cue ball (the first to move), then the problem's balls.
  const json& balls = out["balls"];
  ASSERT_EQ(balls.size(), 3u);
  std::vector<std::string> keys;
  for (const auto& [key, value] : j["tracks"].items()) keys.push_back(key);
  // The problem names the object balls "ball<key>" after the file's keys.
  std::vector<std::string> order;
  for (const auto& [name, value] : j["problem"]["balls"].items()) order.push_back(name.substr(4));
  std::string cue;
  for (const std::string& k : keys)
    if (std::find(order.begin(), order.end(), k) == order.end()) cue = k;
  order.insert(order.begin(), cue);
  double worst = 0;
  int compared = 0;
  for (size_t k = 0; k < 3; ++k) {
    const json& track = j["tracks"][order[k]];
    const json& path = balls[k]["path"];
    // Where it starts: the problem's cue_ball, then its balls in order.
    const json& start = k == 0 ? j["problem"]["cue_ball"] : j["problem"]["balls"]["ball" + order[k]];
    const double sx = start[0], sy = start[1];
    const double fx = balls[k]["final_position"][0], fy = balls[k]["final_position"][1];
    for (size_t i = 0; i < track["t"].size(); ++i) {
      const double ts = track["t"][i].get<double>() - offset;
      phys::Vec2 p{sx, sy};
      if (ts > 0) {
        p = {fx, fy};
        for (const json& seg : path)
          if (ts >= seg["t0"].get<double>() && ts <= seg["t1"].get<double>()) {
            const double dt = ts - seg["t0"].get<double>();
            p = {seg["p0"][0].get<double>() + seg["v0"][0].get<double>() * dt +
                     0.5 * seg["accel"][0].get<double>() * dt * dt,
                 seg["p0"][1].get<double>() + seg["v0"][1].get<double>() * dt +
                     0.5 * seg["accel"][1].get<double>() * dt * dt};
            break;
          }
      }
      const phys::Vec2 f = frame.to_file(p);
      worst = std::max({worst, std::fabs(f.x - track["x"][i].get<double>()),
                        std::fabs(f.y - track["y"][i].get<double>())});
      ++compared;
    }
  }
  EXPECT_GT(compared, 100);
  EXPECT_LT(worst, 1e-6) << "file units";
}

TEST(FitCli, CaromPresetAndPhysicsOverrides) {
  const prob::LoadResult a = prob::parse_problem(
      "table: carom\ncue_ball: [0.5, 0.5]\ntarget: [1.0, 1.0]\n", "<carom>");
  ASSERT_TRUE(a.ok()) << a.error;
  EXPECT_DOUBLE_EQ(a.problem->scene.length, 2.84);
  EXPECT_DOUBLE_EQ(a.problem->scene.width, 1.42);
  EXPECT_TRUE(a.problem->scene.pockets.empty());
  EXPECT_DOUBLE_EQ(a.problem->scene.radius(), 0.03075);
  EXPECT_DOUBLE_EQ(a.problem->scene.ball_and_cushion.mass, 0.21);
  EXPECT_DOUBLE_EQ(a.problem->scene.ball_and_cushion.cushion_height, 0.037);
  const prob::LoadResult b = prob::parse_problem(
      "table: {preset: carom, length: 2.5}\nphysics: {mu_roll: 0.004, cushion_height: 0.036}\n"
      "cue_ball: [0.5, 0.5]\ntarget: [1.0, 1.0]\n",
      "<carom>");
  ASSERT_TRUE(b.ok()) << b.error;
  EXPECT_DOUBLE_EQ(b.problem->scene.length, 2.5);
  EXPECT_DOUBLE_EQ(b.problem->scene.cloth.mu_roll, 0.004);
  EXPECT_DOUBLE_EQ(b.problem->scene.ball_and_cushion.cushion_height, 0.036);
  const prob::LoadResult c =
      prob::parse_problem("table: snooker9\ncue_ball: [0.5, 0.5]\ntarget: [1.0, 1.0]\n", "<t>");
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error.find("table: must be one of carom"), std::string::npos) << c.error;
  phys::Scene s = prob::carom_scene();
  EXPECT_EQ(prob::apply_physics_block("physics: {mu_roll: 0.0043}\n", "<p>", &s), "");
  EXPECT_DOUBLE_EQ(s.cloth.mu_roll, 0.0043);
  EXPECT_NE(prob::apply_physics_block("physics: {mu_rol: 0.0043}\n", "<p>", &s).find("mu_rol"),
            std::string::npos);
}

// The rolling resistance measured from the final rolls of tracked shots (1 cm noise,
// the tracker's sampling) simulated on a cloth with mu_roll 0.0065: the median over the
// balls' last straight rolls is within 10 % of it.
TEST(CalibrateCli, FinalRollsMeasureTheRollingResistance) {
  phys::Scene cloth = prob::carom_scene();
  cloth.cloth.mu_roll = 0.0065;
  std::mt19937 rng(5);
  const std::vector<std::vector<phys::Vec2>> starts = {
      {{0.5, 0.4}, {1.6, 0.9}, {2.2, 0.3}}, {{2.3, 0.5}, {0.8, 1.1}, {1.4, 0.25}},
      {{1.2, 1.2}, {1.6, 0.5}, {0.4, 0.3}}, {{0.4, 0.7}, {2.0, 1.0}, {2.5, 0.4}}};
  const std::vector<Truth> truths = {{{2.4, 20.0, 0.4, -0.3}, 0.008},
                                     {{2.0, 155.0, -0.2, 0.3}, 0.01},
                                     {{2.8, -70.0, 0.3, 0.2}, 0.004},
                                     {{1.8, 5.0, 0.5, 0.0}, 0.006}};
  std::vector<plan::ShotData> shots;
  for (size_t i = 0; i < starts.size(); ++i) {
    const json line = tracked_shot(static_cast<int>(i + 1), starts[i], truths[i], rng, cloth);
    const plan::TrackRead read = plan::parse_track(line.dump(), static_cast<int>(i + 1));
    ASSERT_TRUE(read.error.empty()) << read.error;
    plan::ShotDataRead data = plan::prepare_shot(*read.track, prob::carom_scene(), plan::TrackFrame{});
    ASSERT_TRUE(data.error.empty()) << data.error;
    shots.push_back(std::move(*data.data));
  }
  const plan::RollingMeasurement m = plan::measure_rolling_resistance(shots, {0, 1, 2, 3});
  std::cout << "mu_roll from " << m.rolls << " final rolls: " << m.mu_roll << " (quartiles "
            << m.quartiles[0] << ", " << m.quartiles[1] << "; simulated with 0.0065)\n";
  EXPECT_GE(m.rolls, 3);
  EXPECT_NEAR(m.mu_roll, 0.0065, 0.00065);
  // No rolls, no measurement.
  EXPECT_EQ(plan::measure_rolling_resistance(shots, {}).rolls, 0);
  EXPECT_TRUE(std::isnan(plan::measure_rolling_resistance(shots, {}).mu_roll));
}

// `calibrate` moves a constant the shots were simulated with back toward its true value:
// three shots rolled on a cloth with mu_roll 0.0065 (the preset's is 0.005), calibrated
// from the preset. With the stronge_compliant cushion it also fits eta_squared.
TEST(CalibrateCli, RecoversTheRollingResistanceAndFitsEtaSquaredForTheCompliantCushion) {
  phys::Scene truth_table = prob::carom_scene();
  truth_table.cloth.mu_roll = 0.0065;
  std::mt19937 rng(11);
  std::ostringstream file;
  file << tracked_shot(1, {{0.5, 0.4}, {1.6, 0.9}, {2.2, 0.3}}, {{2.4, 20.0, 0.4, -0.3}, 0.008}, rng,
                       truth_table).dump() << '\n';
  file << tracked_shot(2, {{2.3, 0.5}, {0.8, 1.1}, {1.4, 0.25}}, {{2.0, 155.0, -0.2, 0.3}, 0.01}, rng,
                       truth_table).dump() << '\n';
  file << tracked_shot(3, {{1.2, 1.2}, {1.6, 0.5}, {0.4, 0.3}}, {{2.8, -70.0, 0.3, 0.2}, 0.004}, rng,
                       truth_table).dump() << '\n';
  const auto tracks = scratch() / "calibrate_tracks.jsonl";
  write_text(tracks, file.str());
  const std::string common = " --folds 1 --rounds 1 --evaluations 40 --refit-evaluations 20 --threads 2";
  const ProcessResult run = cueplan("calibrate " + tracks.string() + common + " --out " +
                                    (scratch() / "calibrated.yaml").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  double start = 0, fitted = 0;
  std::istringstream table(run.out);
  std::string line;
  bool found = false;
  while (std::getline(table, line)) {
    std::istringstream row(line);
    std::string name;
    if (row >> name && name == "mu_roll" && (row >> start >> fitted)) found = true;
  }
  ASSERT_TRUE(found) << run.out;
  std::cout << "calibrate: mu_roll " << start << " -> " << fitted << " (simulated with 0.0065)\n"
            << run.out.substr(0, run.out.find("per shot"));
  EXPECT_DOUBLE_EQ(start, 0.005);
  EXPECT_LT(std::fabs(fitted - 0.0065), std::fabs(start - 0.0065) / 2) << run.out;
  EXPECT_EQ(run.out.find("eta_squared"), std::string::npos) << run.out;

  write_text(scratch() / "stronge.yaml", "physics: {cushion_model: stronge_compliant, eta_squared: 1.5}\n");
  const ProcessResult compliant =
      cueplan("calibrate " + tracks.string() + common + " --physics " +
              (scratch() / "stronge.yaml").string() + " --out " + (scratch() / "stronge_out.yaml").string());
  ASSERT_EQ(compliant.exit_code, 0) << compliant.err;
  std::cout << compliant.out.substr(0, compliant.out.find("per shot"));
  EXPECT_NE(compliant.out.find("\neta_squared "), std::string::npos) << compliant.out;
  const std::string written = read_text(scratch() / "stronge_out.yaml");
  EXPECT_NE(written.find("eta_squared:"), std::string::npos) << written;
  EXPECT_NE(written.find("cushion_model: \"stronge_compliant\""), std::string::npos) << written;
}

}  // namespace
}  // namespace cli_test
