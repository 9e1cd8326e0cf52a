#include "cueplan/api/impact.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <ostream>

#include "cueplan/api/exit_codes.hpp"
#include "cueplan/api/field_names.hpp"
#include "cueplan/api/output_file.hpp"
#include "cueplan/api/rebound_inputs.hpp"
#include "cueplan/api/words.hpp"
#include "cueplan/api/table_cache.hpp"

namespace cueplan::api {
namespace {

namespace phys = cueplan::physics;

}  // namespace

void impact_options(const ImpactArgs& args, std::span<const FieldName> names,
                    phys::SimulationOptions* options) {
  if (!phys::parse_method(args.method, &options->impact_method)) {
    const std::string name = name_of({"simulation", "impact_method"}, names);
    throw InputError(name, name + " must be one of table, exact, extrapolation, paper, got '" +
                               args.method + "'");
  }
  if (!std::isfinite(args.accuracy) || !(args.accuracy >= 1e-12) || !(args.accuracy <= 0.1)) {
    const std::string name = name_of({"simulation", "impact_accuracy"}, names);
    throw InputError(name, name + " must lie in [1e-12, 0.1], got " + number(args.accuracy));
  }
  options->impact_accuracy = args.accuracy;
}

std::string read_impact_options(const ImpactArgs& args, phys::SimulationOptions* options) {
  static const std::initializer_list<FieldName> kFlags = {
      {{"simulation", "impact_method"}, "--method"},
      {{"simulation", "impact_accuracy"}, "--accuracy"},
  };
  try {
    impact_options(args, kFlags, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

int prepare_impact_table(const char* command, const phys::Scene& scene,
                         const std::string& table_cache, int threads, bool accuracy_given,
                         phys::ImpactTable* table, phys::SimulationOptions* options,
                         std::ostream& err, bool* built) {
  const phys::CushionParams& params = scene.ball_and_cushion;
  // The table is the Mathavan model's; a han_2005 scene's impacts are closed forms.
  if (params.model != phys::CushionModel::mathavan_2010) {
    if (built) *built = false;
    return kExitOk;
  }
  const std::string cache_dir = table_cache.empty() ? default_table_cache_dir() : table_cache;
  if (std::string why = ensure_directory(cache_dir); !why.empty()) {
    err << command << ": --table-cache: " << why << '\n';
    return kExitUsage;
  }
  // A first build takes a while: say so before it starts, not only after.
  const std::filesystem::path file =
      std::filesystem::path(cache_dir) / phys::ImpactTable::cache_file_name(params, {});
  std::error_code ec;
  const bool first_build = !std::filesystem::exists(file, ec);
  if (built) *built = first_build;
  if (first_build)
    err << command << ": building the impact table for this cushion (once; about 30 s on "
        << "2 cores), to be cached in " << cache_dir << '\n';
  std::string note;
  std::string error;
  std::optional<phys::ImpactTable> acquired =
      acquire_table(params, cache_dir, threads, &note, &error);
  if (!acquired) {
    err << command << ": " << error << '\n';
    return kExitFailed;
  }
  if (!note.empty()) err << command << ": " << note << '\n';
  *table = std::move(*acquired);
  if (std::string note_on_method = use_impact_table(*table, scene, accuracy_given, options);
      !note_on_method.empty())
    err << command << ": " << note_on_method << '\n';
  return kExitOk;
}

std::string use_impact_table(const phys::ImpactTable& table, const phys::Scene& scene,
                             bool accuracy_given, phys::SimulationOptions* options) {
  options->table = &table;
  // Asked for the table without an accuracy: the table's own measured error is it.
  const double measured = table.measured_error().max_state_relative;
  if (!accuracy_given) options->impact_accuracy = std::max(options->impact_accuracy, measured);
  if (phys::chosen_impact_method(scene, *options) != phys::ImpactMethod::table)
    return "the table's measured error " + number(measured) + " is above --accuracy " +
           number(options->impact_accuracy) + "; cushion impacts use the exact method";
  return {};
}

}  // namespace cueplan::api
