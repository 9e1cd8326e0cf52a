// `cueplan figures`: redraws figures 8, 9, 10 and 12 of Mathavan, Jackson & Parkin
// (2010) as SVG, PNG or PDF files, each with a CSV of the plotted numbers beside it.
#pragma once

#include <iosfwd>
#include <string>

namespace CLI {
class App;
}

namespace cueplan::cli {

struct FiguresArgs {
  std::string out_dir;          // created if missing
  std::string format = "svg";   // svg, png or pdf
  double alpha_step_deg = 0.5;  // spacing of the incidence angles over (0, 90]
};

class FiguresCommand {
 public:
  // Registers `figures` and its flags on `parent`; the flags write into this object.
  explicit FiguresCommand(CLI::App& parent);
  FiguresCommand(const FiguresCommand&) = delete;
  FiguresCommand& operator=(const FiguresCommand&) = delete;

  bool selected() const;

  // Checks the flags without computing or writing anything (the --out directory is not
  // created); returns kExitOk, or kExitUsage with its one line written to `err`.
  int validate(std::ostream& err) const;

  // Runs the parsed command (validate() first); returns an ExitCode.
  int run(std::ostream& out, std::ostream& err) const;

 private:
  // All the checks of validate(); empty or the one-line reason to stop.
  std::string check_flags() const;

  CLI::App* command_ = nullptr;
  FiguresArgs args_;
};

}  // namespace cueplan::cli
