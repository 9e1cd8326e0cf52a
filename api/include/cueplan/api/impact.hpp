// The cushion-impact flags of the commands that simulate many shots on a problem's
// scene (--method, --accuracy, --table-cache) and the impact table they may need.
#pragma once

#include <iosfwd>
#include <span>
#include <string>

#include "cueplan/physics/impact_table.hpp"
#include "cueplan/physics/shot.hpp"
#include "cueplan/api/errors.hpp"
#include "cueplan/api/field_names.hpp"

namespace cueplan::api {

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

// The impact method and accuracy of `args` set on *options. Throws InputError when one
// is not usable, naming it by `names` ({"simulation", "impact_method"},
// {"simulation", "impact_accuracy"}).
void impact_options(const ImpactArgs& args, std::span<const FieldName> names,
                    physics::SimulationOptions* options);

// The command line's form: empty when the flags are usable (then *options has the method and accuracy);
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

}  // namespace cueplan::api

// The faces (command line, server, batch) name these as their own.
namespace cueplan::cli {
using api::kShotImpactMethod;
using api::kSearchImpactMethod;
using api::ImpactArgs;
using api::read_impact_options;
using api::impact_options;
using api::prepare_impact_table;
using api::use_impact_table;
}  // namespace cueplan::cli
