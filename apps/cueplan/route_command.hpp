// `cueplan route PROBLEM`: a short sequence of strokes that brings the cue ball to rest
// on the target when one stroke cannot (planner::plan_route on OMPL's SST, RRT or
// KPIECE1), reported stroke by stroke in a player's terms, as JSON, and drawn (SVG, PNG or PDF).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>

#include "cueplan/planner/route.hpp"
#include "cueplan/problems/problem.hpp"
#include "cueplan/api/results.hpp"

namespace CLI {
class App;
}

namespace cueplan::cli {

// What the command line asked for, in the flags' units.
struct RouteArgs {
  std::string problem_file;  // PROBLEM, a YAML problem file
  int max_strokes = 0;       // 0: the file's max_strokes, else 3
  double time_s = 0.0;       // 0: the file's time_budget_s, else 5
  std::string planner = "sst";
  std::string sampler = "directed";
  uint64_t seed = 1;
  double noise = 1.0;  // multiplies every deviation of the NoiseModel
  int samples = 200;   // noisy strokes per reported success probability
  int steer_evaluations = 300;
  bool first = false;  // stop at the first route
  bool json = false;
  std::string svg_file;  // empty: no drawing
};

class RouteCommand {
 public:
  // Registers `route` and its flags on `parent`; the flags write into this object, so it
  // must outlive the parse and stay where it is.
  explicit RouteCommand(CLI::App& parent);
  RouteCommand(const RouteCommand&) = delete;
  RouteCommand& operator=(const RouteCommand&) = delete;

  bool selected() const;

  // Runs the parsed command; returns an ExitCode: 0 a route found, 1 unreachable or no
  // route within the budget, 2 bad input.
  int run(std::ostream& out, std::ostream& err) const;

  // Checks the flags and reads the problem without planning; returns kExitOk or
  // kExitUsage (with one line on `err`).
  int validate(std::ostream& err) const;

 private:
  // The flags and the problem file read into options; kExitOk or kExitUsage.
  int read(std::ostream& err, problems::Problem* problem, planner::RouteOptions* options) const;

  CLI::App* command_ = nullptr;
  RouteArgs args_;
};

// What `cueplan route --json` prints for a route (svg_file: the drawing written, or empty).
}  // namespace cueplan::cli
