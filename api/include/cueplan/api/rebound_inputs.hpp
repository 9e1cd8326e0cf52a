// Checks and set-up shared by the single and the batch forms of `cueplan rebound`.
#pragma once

#include <optional>
#include <string>

#include "cueplan/physics/cushion_impact.hpp"
#include "cueplan/physics/impact_table.hpp"

namespace cueplan::api {

// How the caller spells the inputs in its messages (flags or CSV columns).
struct IncidenceNames {
  const char* speed;
  const char* angle;
  const char* topspin;
  const char* sidespin;
};
inline constexpr IncidenceNames kFlagNames = {"--speed", "--angle", "--topspin", "--sidespin"};
inline constexpr IncidenceNames kColumnNames = {"speed", "angle_deg", "topspin_k", "sidespin_k"};

// Empty when (V0 m/s, alpha deg, spins) describe a ball moving into the cushion
// (V0 > 0, 0 < alpha < 180, all finite); otherwise one line naming the input.
std::string check_incidence(double speed, double angle_deg, double topspin, double sidespin,
                            const IncidenceNames& names);

// Empty when the parameters are usable (CushionParams::validate); otherwise its
// error with the fields named by their flags (--mu-table, ...).
std::string check_params(const physics::CushionParams& params);

// Empty when the options are usable (ImpactOptions::validate); otherwise its error
// with the fields named by their flags (--steps, --tolerance).
std::string check_options(const physics::ImpactOptions& options);

// Loads the impact table for `params` from `cache_dir` (which must exist) or builds
// and saves it there.
// On failure returns nullopt and sets *error; *note says what happened otherwise.
// `threads` only speeds the build (0: one per core).
std::optional<physics::ImpactTable> acquire_table(const physics::CushionParams& params,
                                                  const std::string& cache_dir, int threads,
                                                  std::string* note, std::string* error);

}  // namespace cueplan::api

// The faces (command line, server, batch) name these as their own.
namespace cueplan::cli {
using api::IncidenceNames;
using api::kFlagNames;
using api::kColumnNames;
using api::check_incidence;
using api::check_params;
using api::check_options;
using api::acquire_table;
}  // namespace cueplan::cli
