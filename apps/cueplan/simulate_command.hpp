// `cueplan simulate PROBLEM`: one cue-ball shot (or a CSV batch of them) on a problem
// file's scene through physics::simulate, reported as text, JSON or CSV against the
// problem's target, and drawn to scale (SVG, PNG or PDF).
#pragma once

#include <cmath>
#include <cstdint>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cueplan/physics/shot.hpp"
#include "cueplan/physics/trace.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/problems/problem.hpp"
#include "cueplan/api/impact.hpp"
#include "cueplan/api/results.hpp"

namespace CLI {
class App;
}

namespace cueplan::physics {
class ImpactTable;
}

namespace cueplan::problems {
struct Problem;
}

namespace cueplan::cli {

// What the command line asked for, in the flags' units.
struct SimulateArgs {
  std::string problem_file;  // PROBLEM, a YAML problem file
  double speed = NAN;        // m/s, --speed
  double aim_deg = NAN;      // deg from +x, counter-clockwise, --aim
  double topspin_k = 0.0;    // --topspin-k, k_T; 0 is a centre-ball strike
  double sidespin_k = 0.0;   // --sidespin-k, k_S; > 0 right spin
  double elevation_deg = 0.0;  // --elevation-deg, the cue above the horizontal
  std::string method = kShotImpactMethod;
  double accuracy = physics::SimulationOptions{}.impact_accuracy;  // relative, per impact
  std::string table_cache;  // empty: default_table_cache_dir() (table_cache.hpp)
  int max_events = 200;
  bool json = false;
  std::string svg_file;  // empty: no drawing
  std::string batch_file;
  int threads = 0;     // batch (and table build) threads; 0: one per core
  int samples = 0;     // --samples: noisy strokes for the success estimate; 0: none
  double noise = 1.0;  // --noise: scale of planner::NoiseModel's deviations
  uint64_t seed = 1;   // --seed: of the noisy strokes
  double trace = NAN;  // --trace: s between samples of every ball's state; NAN: no trace
};

class SimulateCommand {
 public:
  // Registers `simulate` and its flags on `parent`; the flags write into this object,
  // so it must outlive the parse and stay where it is.
  explicit SimulateCommand(CLI::App& parent);
  SimulateCommand(const SimulateCommand&) = delete;
  SimulateCommand& operator=(const SimulateCommand&) = delete;

  bool selected() const;

  // Checks every flag, the problem file, the batch file and the --svg path without
  // doing any work or writing anything; returns kExitOk, or kExitUsage with its one line
  // written to `err`.
  int validate(std::ostream& err) const;

  // Runs the parsed command (validate() first); returns an ExitCode.
  int run(std::ostream& out, std::ostream& err) const;

 private:
  struct Inputs;  // everything run() needs, read and checked from the flags and files

  bool given(const char* flag) const;
  // All the checks of validate(); empty or the one-line reason to stop.
  std::string read_inputs(Inputs* inputs) const;

  // Stages of run(), in order; each returns empty or the one-line reason to stop.
  std::string read_options(physics::SimulationOptions* options) const;
  std::string read_shot(physics::Shot* shot) const;
  // With --method table: loads or builds the table for the scene's cushion and sets
  // options->table (and the accuracy, unless --accuracy was given). Notes go to `err`.
  // Returns an ExitCode: kExitOk, or the code to stop with (its line already written).
  int prepare_table(const problems::Problem& problem, physics::ImpactTable* table,
                    physics::SimulationOptions* options, std::ostream& err) const;

  CLI::App* command_ = nullptr;
  SimulateArgs args_;
};

// The success of the stroke under a player's noise (`cueplan simulate --samples N`).
}  // namespace cueplan::cli
