// The topspin and sidespin flags of the commands that strike one ball (`rebound`,
// `collide`): each spin as k = w R / V (--topspin-k, --sidespin-k) or in rad/s
// (--topspin, --sidespin), and the spins they give.
#pragma once

#include <string>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace cueplan::cli {

// What the flags asked for, in their units.
struct SpinArgs {
  double topspin_k = 1.0;   // --topspin-k, k_T = w_T R / V (1: natural roll)
  double sidespin_k = 0.0;  // --sidespin-k, k_S = w_S R / V
  double topspin = 0.0;     // rad/s, --topspin (replaces --topspin-k when given)
  double sidespin = 0.0;    // rad/s, --sidespin (replaces --sidespin-k when given)
};

struct SpinFlags {
  CLI::Option* topspin_k = nullptr;
  CLI::Option* sidespin_k = nullptr;
  CLI::Option* topspin = nullptr;
  CLI::Option* sidespin = nullptr;
};

// Registers the four flags on `command` in `group`; they write into *args, which must
// outlive the parse. The help writes the ball's speed as `speed` ("V0", "V") and says
// about which axis topspin turns with `topspin_axis` (may be empty).
SpinFlags add_spin_flags(CLI::App& command, SpinArgs* args, const char* group, const char* speed,
                         const char* topspin_axis);

// Topspin w_T and sidespin w_S (rad/s) for a ball struck at `speed` (m/s) with radius
// `radius` (m), from whichever flag of each pair was given. Empty, or one line naming the
// flag whose value is not finite.
std::string read_spins(const CLI::App& command, const SpinArgs& args, double speed, double radius,
                       double* topspin, double* sidespin);

}  // namespace cueplan::cli
