// `cueplan spinmap PROBLEM --out FILE`: the teaching tool, "what spin lands here". For
// one speed and aim (given, or the planner's best stroke), planner::spin_map simulates
// every spin on a grid over the tip-offset disc; the picture (SVG, PNG or PDF) shows each
// spin coloured by how far from the target it stops, the spins that land outlined,
// and beside it the table with every spin's rest position.
#pragma once

#include <cmath>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>

#include "cueplan/planner/planner.hpp"
#include "cueplan/planner/spin_map.hpp"
#include "cueplan/problems/problem.hpp"
#include "cueplan/api/impact.hpp"
#include "cueplan/api/options.hpp"
#include "cueplan/api/results.hpp"

namespace CLI {
class App;
}

namespace cueplan::cli {

// What the command line asked for, in the flags' units.
struct SpinmapArgs {
  std::string problem_file;  // PROBLEM, a YAML problem file
  std::string out_file;      // --out, .svg, .png or .pdf
  double speed = NAN;        // m/s, --speed (with --aim; neither: the planner's)
  double aim_deg = NAN;      // deg from +x, --aim
  int grid = kDefaultSpinmapGrid;  // points across the disc's diameter
  int threads = 0;           // 0: one per core
  ImpactArgs impact;
  PlannerArgs planner;  // used only without --speed and --aim
  bool json = false;
  bool success = false;  // --success: shade the cells by the success under noise
};

// Noisy strokes per spin with --success when --samples is not given, and the most.
class SpinmapCommand {
 public:
  // Registers `spinmap` and its flags on `parent`; the flags write into this object, so
  // it must outlive the parse and stay where it is.
  explicit SpinmapCommand(CLI::App& parent);
  SpinmapCommand(const SpinmapCommand&) = delete;
  SpinmapCommand& operator=(const SpinmapCommand&) = delete;

  bool selected() const;

  // Checks every flag, the problem file and the --out path without doing any work or
  // writing anything; returns kExitOk, or kExitUsage with its one line written to `err`.
  int validate(std::ostream& err) const;

  // Runs the parsed command (validate() first); returns an ExitCode: 0 when the picture
  // was written, 2 for bad input.
  int run(std::ostream& out, std::ostream& err) const;

 private:
  struct Inputs;  // everything run() needs, read and checked from the flags and file

  bool given(const char* flag) const;
  // All the checks of validate(); empty or the one-line reason to stop.
  std::string read_inputs(Inputs* inputs) const;

  CLI::App* command_ = nullptr;
  SpinmapArgs args_;
};

// Where a spin map's speed and aim came from: given, or the planner's best stroke.
}  // namespace cueplan::cli
