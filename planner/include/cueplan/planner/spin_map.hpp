// "What spin lands here?": for one speed and aim, where every spin within the miscue
// limit sends the cue ball, and which of those spins stop in the target zone.
//
// The spins form a square grid over the tip-offset disc (k_T, k_S with
// sqrt(k_T^2 + k_S^2) <= spin_max); each is simulated on the problem's scene. On a pot
// problem each spin's aim is solved again so that the pot is kept (spin changes the
// throw): from the given aim, sending the pot's ball where that aim sends it with a
// centre-ball stroke when that pots (else at the pocket's centre); a spin for which no
// aim pots is marked (pots false).
// A pure function of its arguments, deterministic for any number of threads.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::planner {

struct SpinMapOptions {
  int grid = 41;                 // points across the disc's diameter (odd keeps the centre)
  double spin_max = 0.0;         // disc radius in k; 0: the problem's limits.spin
  int threads = 1;
  physics::SimulationOptions simulation;
  // Called now and then with the fraction done (0..1), from the calling thread.
  std::function<void(double)> progress;
  // "How forgiving": when above 0, each cell's stroke (its speed, aim and spin) is also
  // played `success_samples` times with the execution noise `noise`, and the cell's
  // success is the fraction that solve the problem (check_outcome). Every cell uses the
  // same seeded draws (common random numbers): the map is deterministic for any number
  // of threads. At noise scale 0 every draw is the cell's own stroke, so success is 1
  // exactly where the cell lands and 0 elsewhere.
  int success_samples = 0;
  NoiseModel noise;
  uint64_t seed = 1;
  // Only the cells [success_first, success_first + success_count) get a success (the
  // map is computed whole): a caller can ask for the estimates in parts.
  size_t success_first = 0;
  size_t success_count = static_cast<size_t>(-1);
  // When it passes, no more cells are estimated (those not finished have no success)
  // and the map says it is incomplete.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  // Empty when usable; otherwise the first broken rule, fields named as these members.
  physics::Validation validate() const;
};

struct SpinMapPoint {
  double topspin_k = 0.0, sidespin_k = 0.0;
  double tip_right = 0.0, tip_up = 0.0;   // tip offset / R (d = k R / 2.5)
  physics::ShotStatus outcome = physics::ShotStatus::rest;
  physics::Vec2 final_position;            // m
  double miss_distance = 0.0;              // m; infinite unless at rest
  int cushion_hits = 0;
  bool lands = false;                      // solves the problem (problems::check_outcome)
  double aim_deg = 0.0;                    // the aim struck: the map's, or a pot's solved aim
  bool pots = true;                        // a pot problem: some aim pots with this spin
  // Asked for (SpinMapOptions::success_samples): the fraction of the noisy strokes
  // that solve the problem, 0..1; std::nullopt when not estimated.
  std::optional<double> success;
};

struct SpinMap {
  double speed = 0.0;    // m/s
  double aim_deg = 0.0;  // deg
  double spin_max = 0.0;
  int grid = 0;
  std::vector<SpinMapPoint> points;  // the grid points inside the disc, row by row
  int landing = 0;                   // how many land
  int not_potting = 0;               // a pot problem: spins for which no aim pots
  int success_samples = 0;           // noisy strokes per estimated cell (0: none asked)
  int success_cells = 0;             // cells given a success
  bool success_complete = true;      // false when the deadline stopped the estimates
  std::string message;               // set when the inputs were invalid (points empty)
  // The broken rule when the inputs were invalid: SpinMapOptions' members, {"speed"},
  // {"aim_deg"}, or the problem's (Problem's members, as problems::validate names them).
  std::optional<physics::ValidationError> error;
};

SpinMap spin_map(const problems::Problem& problem, double speed, double aim_deg,
                 const SpinMapOptions& options);

}  // namespace cueplan::planner
