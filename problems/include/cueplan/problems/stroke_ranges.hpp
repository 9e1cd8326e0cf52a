// What a cue can give a cue ball, in physical terms: the one range check of a stroke's
// numbers, shared by the command line's flags and CSV rows, `cueplan serve`'s requests
// and problem files' limits, so that nothing impossible reaches the physics.
//
// Refused (impossible):
//   speed      above kMaxStrokeSpeed (no cue gives a cue ball that much; the fastest
//              measured breaks are about 14 m/s), or not above 0;
//   spin       a tip offset beyond the miscue limit: the tip d from the ball's centre gives
//              k = (5/2) d / R (PHYSICS.md, "Cue strike"), and d <= R/2 bounds
//              sqrt(k_T^2 + k_S^2) by physics::kMiscueSpin = 1.25;
//   aim_deg    outside [-kMaxAimDeg, kMaxAimDeg] (an angle is one turn at most either way);
//   elevation  outside [0, 90] deg.
// Warned about (implausible): a speed above kBreakShotSpeed, faster than a break shot.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::problems {

inline constexpr double kMaxStrokeSpeed = 20.0;  // m/s
inline constexpr double kBreakShotSpeed = 12.0;  // m/s
inline constexpr double kMaxAimDeg = 360.0;      // deg
inline constexpr double kMaxElevationDeg = 90.0;  // deg

// The names a caller gives the numbers in its messages ("--speed", "stroke.speed",
// "limits.speed[1]"); a null name's check is skipped.
struct StrokeFieldNames {
  const char* speed = nullptr;
  const char* aim = nullptr;
  const char* topspin = nullptr;
  const char* sidespin = nullptr;
  const char* elevation = nullptr;
};

struct StrokeRangeCheck {
  std::string field;  // the field of the first refusal (one of the names); empty when none
  std::string error;  // "stroke.speed must be ... , got 1e+308"; empty when it may be played
  std::vector<std::string> warnings;  // "stroke.speed 14 m/s is faster than a break shot ..."
  bool ok() const { return error.empty(); }
};

// The checks above, in the order speed, aim, spin (the two together), elevation; also
// that every number is finite. `elevation_deg` is checked when given.
StrokeRangeCheck check_stroke_ranges(const physics::Shot& shot, const StrokeFieldNames& names,
                                     std::optional<double> elevation_deg = std::nullopt);

// One speed alone (a problem's speed limit, a spin map's speed).
StrokeRangeCheck check_speed_range(double speed, const char* name);
// One spin magnitude sqrt(k_T^2 + k_S^2) alone (a problem's spin limit).
StrokeRangeCheck check_spin_range(double spin, const char* name);

// What is implausible in a problem's limits (a top speed faster than a break shot), one
// line each naming the file's field: "limits.speed[1] 14 m/s is faster than ...". The
// loader refuses what is impossible; this is what it lets through with a warning.
std::vector<std::string> problem_warnings(const Problem& problem);

}  // namespace cueplan::problems
