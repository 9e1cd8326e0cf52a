// The search commands' flags (`solve`, `spinmap`, `zone`, and `simulate`'s impact
// flags): registered on a command and read into the api's requests (cueplan/api/options.hpp,
// cueplan/api/impact.hpp), which check them.
#pragma once

#include "cueplan/api/impact.hpp"
#include "cueplan/api/options.hpp"

namespace CLI {
class App;
}

namespace cueplan::cli {

// Registers the planner's flags on `command`, in `group`; they write into *args, which
// must outlive the parse.
void add_planner_flags(CLI::App& command, PlannerArgs* args, const char* group);

// Registers --method, --accuracy and --table-cache on `command`, in `group`; the flags
// write into *args, which must outlive the parse.
void add_impact_flags(CLI::App& command, ImpactArgs* args, const char* group);

}  // namespace cueplan::cli
