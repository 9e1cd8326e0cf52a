// `cueplan figures`: redraws figures 8, 9, 10 and 12 of Mathavan, Jackson & Parkin
// (2010) as SVG files, each with a CSV of the plotted numbers beside it.
#pragma once

#include <iosfwd>
#include <string>

namespace CLI {
class App;
}

namespace cueplan::cli {

struct FiguresArgs {
  std::string out_dir;          // created if missing
  double alpha_step_deg = 0.5;  // spacing of the incidence angles over (0, 90]
};

class FiguresCommand {
 public:
  // Registers `figures` and its flags on `parent`; the flags write into this object.
  explicit FiguresCommand(CLI::App& parent);
  FiguresCommand(const FiguresCommand&) = delete;
  FiguresCommand& operator=(const FiguresCommand&) = delete;

  bool selected() const;

  // Runs the parsed command; returns an ExitCode.
  int run(std::ostream& out, std::ostream& err) const;

 private:
  CLI::App* command_ = nullptr;
  FiguresArgs args_;
};

}  // namespace cueplan::cli
