#include "cueplan/api/rebound_inputs.hpp"

#include <fmt/format.h>

#include <cmath>
#include <exception>
#include <utility>

#include "cueplan/api/field_names.hpp"
#include "cueplan/api/table_cache.hpp"

namespace cueplan::api {
namespace {

std::string describe(const char* name, const char* rule, double value) {
  return physics::invalid({}, rule, value).message(name);
}

}  // namespace

std::string check_incidence(double speed, double angle_deg, double topspin, double sidespin,
                            const IncidenceNames& names) {
  if (!std::isfinite(speed) || !(speed > 0.0))
    return describe(names.speed, "must be positive and finite (m/s)", speed);
  if (!std::isfinite(angle_deg) || !(angle_deg > 0.0) || !(angle_deg < 180.0))
    return describe(names.angle, "must lie in (0, 180) degrees", angle_deg);
  if (!std::isfinite(topspin)) return describe(names.topspin, "must be finite", topspin);
  if (!std::isfinite(sidespin)) return describe(names.sidespin, "must be finite", sidespin);
  return {};
}

std::string check_params(const physics::CushionParams& params) {
  const physics::Validation e = params.validate();
  return e ? message_in(*e, kCushionFlags) : std::string();
}

std::string check_options(const physics::ImpactOptions& options) {
  const physics::Validation e = options.validate();
  return e ? message_in(*e, kCushionFlags) : std::string();
}

std::optional<physics::ImpactTable> acquire_table(const physics::CushionParams& params,
                                                  const std::string& cache_dir, int threads,
                                                  std::string* note, std::string* error) {
  physics::ImpactTableOptions options;
  options.threads = threads;
  try {
    physics::ImpactTable table = load_or_build_table(params, options, cache_dir, note);
    if (table.empty()) {
      *error = "cannot build the impact table: " + *note;
      return std::nullopt;
    }
    // What the build measured, so a user can judge the surrogate.
    const physics::ImpactTableError& measured = table.measured_error();
    *note += fmt::format(
        "; {:.3g} % of {} cells answer with the exact method (by default at tolerance {:.3g}); "
        "elsewhere max error {:.3g} of V0 in speed, {:.3g} deg in angle",
        100.0 * table.fallback_fraction(), static_cast<long long>(measured.cells),
        table.fallback_tolerance(), measured.max_speed_relative, measured.max_angle_deg);
    return table;
  } catch (const std::exception& e) {
    *error = std::string("cannot build the impact table: ") + e.what();
    return std::nullopt;
  }
}

}  // namespace cueplan::api
