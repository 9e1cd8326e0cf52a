// `cueplan solve PROBLEM`: the inverse problem through planner::plan - the stroke
// (speed, aim, topspin, sidespin) whose cue ball stops on the target - reported in a
// player's terms as text or JSON, with its distinct alternatives, and drawn as SVG.
#pragma once

#include <iosfwd>
#include <string>

#include "impact_setup.hpp"
#include "planner_flags.hpp"

namespace CLI {
class App;
}

namespace cueplan::cli {

// What the command line asked for, in the flags' units.
struct SolveArgs {
  std::string problem_file;  // PROBLEM, a YAML problem file
  PlannerArgs planner;
  ImpactArgs impact;  // --method (default table), --accuracy, --table-cache
  int threads = 0;    // independent starts in parallel (and the table build); 0: one per core
  bool json = false;
  std::string svg_file;  // empty: no drawing
};

class SolveCommand {
 public:
  // Registers `solve` and its flags on `parent`; the flags write into this object, so it
  // must outlive the parse and stay where it is.
  explicit SolveCommand(CLI::App& parent);
  SolveCommand(const SolveCommand&) = delete;
  SolveCommand& operator=(const SolveCommand&) = delete;

  bool selected() const;

  // Runs the parsed command; returns an ExitCode: 0 solved, 1 unreachable or budget
  // exhausted (the best found is still reported), 2 bad input.
  int run(std::ostream& out, std::ostream& err) const;

 private:
  CLI::App* command_ = nullptr;
  SolveArgs args_;
};

}  // namespace cueplan::cli
