// The cushion-impact flags of the commands that simulate many shots on a problem's
// scene (--method, --accuracy, --table-cache) and the impact table they may need.
#pragma once

#include <iosfwd>
#include <string>

#include "cueplan/physics/impact_table.hpp"
#include "cueplan/physics/shot.hpp"

namespace CLI {
class App;
}

namespace cueplan::cli {

// The impact method of the commands that simulate one shot or a batch (rebound,
// simulate): the library's own default, exact.
inline const std::string kShotImpactMethod =
    physics::to_string(physics::SimulationOptions{}.impact_method);
// The impact method of the commands that search thousands of strokes (solve, spinmap):
// the table, the fast path (their reported strokes are verified exactly).
inline const std::string kSearchImpactMethod = physics::to_string(physics::ImpactMethod::table);

// The flags of the commands that search.
struct ImpactArgs {
  std::string method = kSearchImpactMethod;  // table, exact, extrapolation or paper
  double accuracy = physics::SimulationOptions{}.impact_accuracy;  // relative, per impact
  std::string table_cache;  // empty: default_table_cache_dir() (table_cache.hpp)
};

// Registers --method, --accuracy and --table-cache on `command`, in `group`; the flags
// write into *args, which must outlive the parse.
void add_impact_flags(CLI::App& command, ImpactArgs* args, const char* group);

// Empty when the flags are usable (then *options has the method and accuracy);
// otherwise one line naming the flag.
std::string read_impact_options(const ImpactArgs& args, physics::SimulationOptions* options);

// With the table method: loads the table for the scene's cushion from the cache
// directory, or builds and caches it (saying so on `err` before a first build), and
// points options->table at *table. Unless the accuracy was given, the table's own
// measured error becomes the accuracy. Notes go to `err`, each line led by `command`.
// Returns an ExitCode: kExitOk, or the code to stop with (its line already written).
// *built (when given) says whether the table had to be built, not loaded from the cache.
int prepare_impact_table(const char* command, const physics::Scene& scene,
                         const std::string& table_cache, int threads, bool accuracy_given,
                         physics::ImpactTable* table, physics::SimulationOptions* options,
                         std::ostream& err, bool* built = nullptr);

// Points options->table at `table` (which must outlive its use). Unless the accuracy
// was given, the table's own measured error becomes the accuracy. Returns a note when
// cushion impacts will still use the exact method (the table's measured error is above
// the accuracy asked for), else empty. prepare_impact_table ends with it.
std::string use_impact_table(const physics::ImpactTable& table, const physics::Scene& scene,
                             bool accuracy_given, physics::SimulationOptions* options);

}  // namespace cueplan::cli
