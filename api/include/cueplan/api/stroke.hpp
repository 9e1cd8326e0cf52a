// A stroke's inputs checked as every face names them (flags, CSV columns, request fields).
#pragma once

#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"

namespace cueplan::api {

// How the caller spells a shot's inputs in its messages (flags or CSV columns).
struct ShotNames {
  const char* speed;
  const char* aim;
  const char* topspin;
  const char* sidespin;
  const char* elevation;
};
inline constexpr ShotNames kShotFlagNames = {"--speed", "--aim", "--topspin-k", "--sidespin-k",
                                             "--elevation-deg"};
// The batch has no elevation column: its strokes are level.
inline constexpr ShotNames kShotColumnNames = {"speed", "aim_deg", "topspin_k", "sidespin_k",
                                               "elevation_deg"};

// Empty when the shot can be simulated and a cue can play it (speed > 0 and at most
// problems::kMaxStrokeSpeed, the tip within the miscue limit, the aim within a turn,
// everything finite: problems/stroke_ranges.hpp); otherwise one line naming the input.
std::string check_shot_inputs(const physics::Shot& shot, const ShotNames& names);
// What is implausible about a shot that may be played (faster than a break shot), one
// line each naming the input.
std::vector<std::string> shot_warnings(const physics::Shot& shot, const ShotNames& names);

}  // namespace cueplan::api

// The faces (command line, server, batch) name these as their own.
namespace cueplan::cli {
using api::ShotNames;
using api::kShotFlagNames;
using api::kShotColumnNames;
using api::check_shot_inputs;
using api::shot_warnings;
}  // namespace cueplan::cli
