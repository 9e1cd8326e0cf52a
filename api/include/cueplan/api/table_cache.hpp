// Where the command line keeps impact tables between runs, and how it reuses them.
// (The physics library builds, saves and loads tables; the cache is the caller's.)
#pragma once

#include <string>

#include "cueplan/physics/impact_table.hpp"

namespace cueplan::api {

// Where tables are cached by default: $CUEPLAN_CACHE_DIR, else
// $XDG_CACHE_HOME/cueplan, else $HOME/.cache/cueplan, else a temporary directory.
std::string default_table_cache_dir();

// Loads a table for these parameters and options from `cache_dir`, or builds it and
// saves it there (creating the directory); with an empty `cache_dir` it only builds.
// `note`, when given, says which happened. An empty table means invalid input.
physics::ImpactTable load_or_build_table(const physics::CushionParams& params,
                                         const physics::ImpactTableOptions& options,
                                         const std::string& cache_dir, std::string* note = nullptr);

}  // namespace cueplan::api

// The faces (command line, server, batch) name these as their own.
namespace cueplan::cli {
using api::default_table_cache_dir;
using api::load_or_build_table;
}  // namespace cueplan::cli
