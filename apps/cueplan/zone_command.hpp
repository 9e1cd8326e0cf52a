// `cueplan zone PROBLEM --out FILE`: position play as a coaching diagram. For a problem
// with `next`, the table shaded by P(next pot) from every cue-ball position (the
// planner's PositionField), the zone (within 10 percentage points of the best) outlined,
// the planned stroke's path and landing, and where a player's noisy strokes leave the
// cue ball as a cloud of dots.
#pragma once

#include <iosfwd>
#include <string>

#include "cueplan/api/impact.hpp"
#include "cueplan/api/options.hpp"

namespace CLI {
class App;
}

namespace cueplan::cli {

struct ZoneArgs {
  std::string problem_file;  // PROBLEM
  std::string out_file;      // --out, .svg, .png or .pdf
  bool field_only = false;   // --field-only: no stroke planned, the field and zone alone
  int cloud = 200;           // --cloud: noisy strokes drawn as landings (0: none)
  int threads = 0;
  ImpactArgs impact;
  PlannerArgs planner;
  bool json = false;
};

class ZoneCommand {
 public:
  // Registers `zone` and its flags on `parent`; the flags write into this object, so it
  // must outlive the parse and stay where it is.
  explicit ZoneCommand(CLI::App& parent);
  ZoneCommand(const ZoneCommand&) = delete;
  ZoneCommand& operator=(const ZoneCommand&) = delete;

  bool selected() const;
  // Checks the flags, the problem file and the --out path without doing any work.
  int validate(std::ostream& err) const;
  // Draws the picture; 0 written, 1 not, 2 bad input.
  int run(std::ostream& out, std::ostream& err) const;

 private:
  struct Inputs;
  std::string read_inputs(Inputs* inputs) const;
  bool given(const char* flag) const;

  CLI::App* command_ = nullptr;
  ZoneArgs args_;
};

}  // namespace cueplan::cli
