// `cueplan calibrate TRACKS.jsonl`: the table's shared constants (cloth, cushion, balls)
// fitted across recorded shots with each shot's stroke refitted inside, k-fold
// cross-validated (planner::calibrate), written as a physics: block.
#pragma once

#include <iosfwd>
#include <string>

#include "fit_command.hpp"

namespace CLI {
class App;
}

namespace cueplan::cli {

struct CalibrateArgs {
  std::string tracks_file;
  int folds = 5;
  int rounds = 2;
  int evaluations = 120;
  int refit_evaluations = 40;
  std::string out_file;
  std::string physics_file;
  int threads = 0;
  StrokeSearchArgs search;
  bool keep_mu_roll = false;
  double constant_step = planner::CalibrationOptions{}.constant_step;
};

class CalibrateCommand {
 public:
  explicit CalibrateCommand(CLI::App& parent);
  CalibrateCommand(const CalibrateCommand&) = delete;
  CalibrateCommand& operator=(const CalibrateCommand&) = delete;
  bool selected() const;
  int validate(std::ostream& err) const;
  int run(std::ostream& out, std::ostream& err) const;

 private:
  CLI::App* command_ = nullptr;
  CalibrateArgs args_;
};

}  // namespace cueplan::cli
