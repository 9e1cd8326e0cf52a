// `cueplan run LAYOUT`: a run-out under a game's rules (planner/runout.hpp): the
// sequence of pots the policy plays, each stroke in a player's words, and how often the
// run clears the table under the execution noise; text, JSON, and a pattern-play
// drawing (each shot's cue-ball path numbered).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>

#include "cueplan/planner/runout.hpp"
#include "cueplan/problems/game.hpp"
#include "cueplan/api/results.hpp"

namespace CLI {
class App;
}

namespace cueplan::cli {

struct RunArgs {
  std::string layout_file;
  std::string game;      // empty: the file's game, else any_order
  int lookahead = 2;
  std::string policy = "planner";
  int samples = 100;
  uint64_t seed = 1;
  int threads = 0;
  double noise = 1.0;
  bool json = false;
  std::string svg_file;
  std::string png_file;
};

class RunCommand {
 public:
  explicit RunCommand(CLI::App& parent);
  RunCommand(const RunCommand&) = delete;
  RunCommand& operator=(const RunCommand&) = delete;

  bool selected() const;
  // 0: the planned run clears the table; 1: it does not; 2: bad input.
  int run(std::ostream& out, std::ostream& err) const;
  int validate(std::ostream& err) const;

 private:
  int read(std::ostream& err, problems::Layout* layout, problems::GameState* start,
           planner::RunoutOptions* options) const;

  CLI::App* command_ = nullptr;
  RunArgs args_;
};

// What `cueplan run --json` prints: plan [{ball, pocket, shot, success, ...}], runout
// {p, low, high, samples}, mean_potted, mean_break (snooker), deaths, policy, ...
}  // namespace cueplan::cli
