#include "spin_flags.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>

namespace cueplan::cli {

SpinFlags add_spin_flags(CLI::App& c, SpinArgs* args, const char* group, const char* speed,
                         const char* topspin_axis) {
  SpinFlags f;
  f.topspin_k = c.add_option("--topspin-k", args->topspin_k,
                             fmt::format("Topspin k_T = w_T R / {}{} (1: natural roll, 0: stun, "
                                         "< 0: draw)",
                                         speed, topspin_axis))
                    ->type_name("k_T")
                    ->capture_default_str()
                    ->group(group);
  f.sidespin_k = c.add_option("--sidespin-k", args->sidespin_k,
                              fmt::format("Sidespin k_S = w_S R / {} (> 0: right spin)", speed))
                     ->type_name("k_S")
                     ->capture_default_str()
                     ->group(group);
  f.topspin = c.add_option("--topspin", args->topspin,
                           fmt::format("Topspin w_T (rad/s) instead of --topspin-k; {}/R is "
                                       "natural roll",
                                       speed))
                  ->type_name("rad/s")
                  ->excludes(f.topspin_k)
                  ->group(group);
  f.sidespin = c.add_option("--sidespin", args->sidespin,
                            "Sidespin w_S (rad/s) instead of --sidespin-k; > 0 is right spin")
                   ->type_name("rad/s")
                   ->excludes(f.sidespin_k)
                   ->group(group);
  return f;
}

std::string read_spins(const CLI::App& command, const SpinArgs& args, double speed, double radius,
                       double* topspin, double* sidespin) {
  // Each spin comes in rad/s or as k = w R / V, whichever flag was given.
  const bool topspin_rad = command.count("--topspin") > 0;
  const bool sidespin_rad = command.count("--sidespin") > 0;
  const double t = topspin_rad ? args.topspin : args.topspin_k;
  const double s = sidespin_rad ? args.sidespin : args.sidespin_k;
  if (!std::isfinite(t))
    return fmt::format("{} must be finite, got {}", topspin_rad ? "--topspin" : "--topspin-k", t);
  if (!std::isfinite(s))
    return fmt::format("{} must be finite, got {}", sidespin_rad ? "--sidespin" : "--sidespin-k",
                       s);
  const double unit = speed / radius;  // rad/s per unit of k
  *topspin = topspin_rad ? t : t * unit;
  *sidespin = sidespin_rad ? s : s * unit;
  return {};
}

}  // namespace cueplan::cli
