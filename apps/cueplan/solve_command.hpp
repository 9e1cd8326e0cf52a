// `cueplan solve PROBLEM`: the inverse problem through planner::plan - the stroke
// (speed, aim, topspin, sidespin) whose cue ball stops on the target - reported in a
// player's terms as text or JSON, with its distinct alternatives, and drawn (SVG, PNG or PDF).
#pragma once

#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>

#include "cueplan/planner/planner.hpp"
#include "cueplan/problems/problem.hpp"
#include "cueplan/api/impact.hpp"
#include "cueplan/api/options.hpp"
#include "solve_batch.hpp"
#include "cueplan/api/results.hpp"

namespace CLI {
class App;
}

namespace cueplan::cli {

using batch::SolveBatchArgs;  // solve_batch.hpp

// What the command line asked for, in the flags' units.
struct SolveArgs {
  std::string problem_file;  // PROBLEM, a YAML problem file
  PlannerArgs planner;
  ImpactArgs impact;  // --method (default table), --accuracy, --table-cache
  int threads = 0;    // independent starts in parallel (and the table build); 0: one per core
  bool json = false;
  std::string svg_file;  // empty: no drawing
  SolveBatchArgs batch;  // --batch FILE.jsonl, --shard K/N (solve_batch.hpp)
};

class SolveCommand {
 public:
  // Registers `solve` and its flags on `parent`; the flags write into this object, so it
  // must outlive the parse and stay where it is.
  explicit SolveCommand(CLI::App& parent);
  SolveCommand(const SolveCommand&) = delete;
  SolveCommand& operator=(const SolveCommand&) = delete;

  bool selected() const;

  // Checks every flag, the problem file and the --svg path without doing any work or
  // writing anything; returns kExitOk, or kExitUsage with its one line written to `err`.
  int validate(std::ostream& err) const;

  // Runs the parsed command (validate() first); returns an ExitCode: 0 solved, 1
  // unreachable or budget exhausted (the best found is still reported), 2 bad input.
  int run(std::ostream& out, std::ostream& err) const;

 private:
  struct Inputs;  // everything run() needs, read and checked from the flags and file

  // All the checks of validate(); empty or the one-line reason to stop.
  std::string read_inputs(Inputs* inputs) const;

  CLI::App* command_ = nullptr;
  SolveArgs args_;
};

// What `cueplan solve --json` prints for a plan (svg_file: the drawing written, or empty).
}  // namespace cueplan::cli
