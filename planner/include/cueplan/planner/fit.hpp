// Recorded shots: the stroke whose simulation best matches a tracked shot (`cueplan fit`)
// and the table constants that best match many of them (`cueplan calibrate`).
//
// A track is one line of the shared format (data/carom_tracks/README.md): per ball, times
// (s) and centres in the tracker's units, origin at the table's centre. Positions are
// turned into metres in the table frame (origin at a corner, shared/PHYSICS.md) by
// TrackFrame, and back again for output.
//
// Pure functions of their arguments: no globals, safe from many threads.
#pragma once

#include <array>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"

namespace cueplan::planner {

// One ball's samples, as the file gives them (its units, its frame).
struct TrackedBall {
  std::string name;  // the file's key ("1", "2", "3")
  std::vector<double> t, x, y;
};

// One recorded shot. `id` is the file's id as JSON text (a number or a quoted string).
struct Track {
  std::string id;
  std::vector<TrackedBall> balls;
};

// A line of the file read, or why it cannot be (naming the id and the ball when known).
struct TrackRead {
  std::optional<Track> track;
  std::string id;     // the id when the line has one, else "line N"
  std::string error;  // empty on success
};
TrackRead parse_track(const std::string& json_line, int line_number);

// The tracker's frame and units: metres = file units x scale, origin moved from the
// table's centre to the corner of the cushion noses x = 0, y = 0.
struct TrackFrame {
  double scale = 0.03075 / 0.03275;  // m per file unit (the README's mapping)
  double length = 2.84;              // m, the table's cushion-to-cushion length
  double width = 1.42;
  physics::Vec2 to_table(double x, double y) const {
    return {x * scale + 0.5 * length, y * scale + 0.5 * width};
  }
  physics::Vec2 to_file(physics::Vec2 p) const {
    return {(p.x - 0.5 * length) / scale, (p.y - 0.5 * width) / scale};
  }
};

// A track ready to fit: the cue ball (the ball that moves first) first, then the
// object balls, each with its samples in metres in the table frame.
struct ShotData {
  std::string id;
  std::vector<std::string> names;  // the file's keys, cue ball first
  std::vector<std::vector<double>> t;
  std::vector<std::vector<physics::Vec2>> p;  // m, table frame
  physics::Scene scene;                       // the table with the object balls placed
  physics::Vec2 cue_start;
  // The strike lies in [strike_lo, strike_lo + FitOptions::max_offset_s + strike_extra]
  // (s on the file's clock): [0, max_offset_s] when the cue ball's samples start at the
  // usual rate; when its first moving sample comes after a gap, the window ends there.
  double strike_lo = 0.0;
  double strike_extra = 0.0;
  // Samples of the cue ball before any other ball moves (for the first guess).
  double first_other_motion = 0.0;
};
struct ShotDataRead {
  std::optional<ShotData> data;
  std::string error;  // "shot ID, ball NAME: what is wrong"
};
// Checks the samples (none, NaN or infinite, times out of order, a ball off the table,
// balls overlapping at the start) and places the balls on `table` (its object balls are
// replaced). Balls within 1 cm of touching or of a cushion are nudged to be legal.
ShotDataRead prepare_shot(const Track& track, const physics::Scene& table,
                          const TrackFrame& frame);

struct FitOptions {
  bool all_balls = false;        // objective over every ball's samples, not only the cue ball's
  double huber_delta = 0.03;     // m: residuals beyond it count linearly (tracking glitches)
  double max_offset_s = 0.02;    // the strike lies in [0, max_offset_s] after the file's t = 0
  int global_evaluations = 2400;  // each of the two NLopt global stages (CRS2) over the box
                                  // round the first guess
  int local_evaluations = 600;    // NLopt local stage (BOBYQA) from the best point so far
  double aim_span_deg = 8.0;      // the box: first-guess aim +- this
  double speed_span = 0.35;      // and first-guess speed x [1 - span, 1 + span]
  double spin_max = 1.25;        // |k_T|, |k_S| <= this
  int max_events = 400;
  // Extra starts of the local stage with the spins reset to two rings round (0, 0) (radii
  // spin_start_radius and spin_start_radius_outer, starts alternating between them and,
  // in pairs, between the two global stages' answers), speed, aim and strike kept; each
  // runs spin_start_evaluations BOBYQA evaluations on each of three windows.
  int spin_starts = 8;
  double spin_start_radius = 0.7;
  double spin_start_radius_outer = 1.05;
  int spin_start_evaluations = 100;
  // Whole searches (both global stages, the continuation, the spin starts) with their own
  // random draws and turned spin rings, each later one's first global box centred on a
  // stroke the one before found (its last spin start's answer); the best on every
  // sample is kept.
  int restarts = 6;
  // A score on a window of the samples follows the simulation only to the window's last
  // sample (SimulationOptions::max_time); false follows every one to rest (the same
  // scores, slower: for comparison).
  bool horizon = true;
  // The cue's elevation (deg): > 0 adds it to the search, in [0, max_elevation_deg]
  // (swerve: a stroke with side and elevation curves while it slides); 0 keeps the cue
  // level. 20 deg covers an ordinary raised butt, short of masse.
  double max_elevation_deg = 20.0;
};

// A stroke and the strike time, and how well they match the recorded shot.
struct StrokeFit {
  physics::Shot shot;
  double offset_s = 0.0;  // strike time after the file's t = 0 (in ShotData's window)
  double loss = 0.0;      // mean Huber loss over the objective's samples (m^2)
  double rmse_cue_m = 0.0;
  double rmse_all_m = 0.0;
  int evaluations = 0;
  bool simulated = false;  // false: the simulation failed (rmse are +inf)
};

// The stroke from the first moving samples: direction and speed of a straight-line fit,
// the speed corrected for the sliding deceleration since the strike; spins zero.
StrokeFit kinematic_guess(const ShotData& data, const FitOptions& options);

// Scores one stroke (fills loss, rmse_*, simulated).
StrokeFit evaluate_stroke(const physics::CompiledScene& scene, const ShotData& data,
                          const physics::Shot& shot, double offset_s, const FitOptions& options);

// Global then local search for the stroke. With `start`, only the local stage runs from it
// (a refit after the constants changed).
StrokeFit fit_stroke(const physics::CompiledScene& scene, const ShotData& data,
                     const FitOptions& options, const StrokeFit* start = nullptr);

// Where the simulation puts every ball at each of its recorded times (m, table frame),
// in ShotData's ball order; empty when the simulation fails. With a finite max_time (s
// after the strike) the shot is followed only that long (positions after it are where
// the balls were then).
std::vector<std::vector<physics::Vec2>> simulated_positions(
    const physics::CompiledScene& scene, const ShotData& data, const StrokeFit& fit,
    physics::ShotResult* result = nullptr, int max_events = 400,
    double max_time = std::numeric_limits<double>::infinity());

// ---- Calibration ----

// The shared constants calibrate fits, in the order of kConstantNames, read from and
// written to a scene.
inline constexpr int kConstantCount = 8;
inline constexpr const char* kConstantNames[kConstantCount] = {
    "mu_slide", "mu_roll",     "mu_spin", "mu_cushion", "restitution", "cushion_height",
    "mu_ball",  "ball_restitution"};  // the physics: block's field names
// With the stronge_compliant cushion a ninth constant follows them: "eta_squared", the
// cushion's normal over tangential contact stiffness (kept within the model's valid
// 0.875-3.5; docs/cushion_models.md).
inline constexpr const char* kEtaSquaredName = "eta_squared";
// The names of the constants calibrate fits for `scene`'s cushion model.
std::vector<std::string> constant_names(const physics::Scene& scene);
// 8 values, or 9 with the stronge_compliant cushion (constant_names' order).
std::vector<double> constants_of(const physics::Scene& scene);
// Writes c (8 values, or 9: the ninth is eta_squared) into the scene.
void set_constants(const std::vector<double>& c, physics::Scene* scene);
// Bounds the search keeps to, for `count` constants (8 or 9).
std::vector<double> constant_lower_bounds(size_t count = kConstantCount);
std::vector<double> constant_upper_bounds(size_t count = kConstantCount);

// The rolling resistance measured from recorded final rolls: on each ball's last straight
// stretch (past its first half second, when a ball may still slide), a quadratic fit of
// the distance against time gives the deceleration mu_roll g. The median over every ball
// of `which` (indices into shots) with a roll of >= 0.8 s and 12 samples.
struct RollingMeasurement {
  double mu_roll = std::numeric_limits<double>::quiet_NaN();
  int rolls = 0;                         // balls measured
  std::array<double, 2> quartiles{};     // of the per-ball values
};
RollingMeasurement measure_rolling_resistance(const std::vector<ShotData>& shots,
                                              const std::vector<size_t>& which);

struct CalibrationOptions {
  int folds = 5;
  // mu_roll starts from measure_rolling_resistance on each fold's training shots (when
  // it has >= 5 rolls) instead of the starting constants' value.
  bool measure_rolling = true;
  int rounds = 2;                  // alternations of constants and strokes
  int constant_evaluations = 120;  // NLopt local stage per round
  // Each evaluation of the constants refits every stroke with this many local
  // evaluations (strokes and constants are strongly coupled - speed and cloth friction,
  // above all - so constants with strokes held fixed barely move).
  int refit_evaluations = 40;
  // The constants' search's first step, as a fraction of each constant's range
  // (constant_lower_bounds .. constant_upper_bounds).
  double constant_step = 0.05;
  int threads = 0;                 // 0: one per core
  FitOptions fit;
};

struct ConstantReport {
  std::string name;
  double value = 0.0;      // fitted on every shot
  double fold_spread = 0;  // standard deviation across the folds' values
  double half_width = 0;   // change that raises the all-shot loss by 1 % (the other
                           // constants fixed, the strokes refitted)
  bool constrained = false;
};

struct CalibrationResult {
  std::vector<std::string> ids;              // every shot used, in input order
  std::vector<double> rmse_before_m;         // cue-ball RMSE with the starting constants
  std::vector<double> rmse_heldout_m;        // with the constants of the fold that left it out
  std::vector<int> fold_of;                  // each shot's fold
  std::vector<std::vector<double>> fold_constants;
  std::vector<double> constants;             // fitted on every shot
  std::vector<double> rmse_all_shots_m;      // every shot, with `constants`
  std::vector<ConstantReport> report;
  // measure_rolling: the measured mu_roll and the rolls behind it, for each fold and then
  // for all shots (NaN, 0 when none).
  std::vector<double> measured_mu_roll;
  std::vector<int> measured_rolls;
};

// k-fold calibration of the shared constants on `shots` (all with the same table), each
// shot's stroke refitted inside; `progress` gets lines for people.
CalibrationResult calibrate(const std::vector<ShotData>& shots, const physics::Scene& start,
                            const CalibrationOptions& options,
                            const std::function<void(const std::string&)>& progress = {});

}  // namespace cueplan::planner
