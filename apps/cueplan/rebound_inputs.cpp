#include "rebound_inputs.hpp"

#include <cmath>
#include <cstdio>
#include <exception>
#include <utility>

namespace cueplan::cli {
namespace {

std::string describe(const char* name, const char* rule, double value) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s %s, got %.10g", name, rule, value);
  return buf;
}

// Library field names and the flags that set them. Names with an underscore are
// unambiguous anywhere in a message; plain words only where the message starts.
constexpr std::pair<const char*, const char*> kFieldFlags[] = {
    {"cushion_height", "--cushion-height"},
    {"mu_cushion", "--mu-cushion"},
    {"mu_table", "--mu-table"},
    {"paper_steps", "--steps"},
    {"mass", "--mass"},
    {"radius", "--radius"},
    {"restitution", "--restitution"},
    {"tolerance", "--tolerance"},
};

bool is_word_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
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

std::string with_flag_names(std::string message) {
  for (const auto& [field, flag] : kFieldFlags) {
    const std::string name = field;
    const bool anywhere = name.find('_') != std::string::npos;
    for (size_t at = message.find(name); at != std::string::npos; at = message.find(name, at + 1)) {
      const size_t end = at + name.size();
      const bool whole_word = (at == 0 || !is_word_char(message[at - 1])) &&
                              (end == message.size() || !is_word_char(message[end]));
      if (!whole_word || (!anywhere && at != 0)) continue;
      message.replace(at, name.size(), flag);
    }
  }
  return message;
}

std::string check_params(const physics::CushionParams& params) {
  return with_flag_names(params.validate());
}

std::string check_options(const physics::ImpactOptions& options) {
  // The ranges resolve_impact accepts (cushion_impact.hpp).
  if (options.paper_steps < 1)
    return describe("--steps", "must be at least 1", options.paper_steps);
  if (!std::isfinite(options.tolerance) || !(options.tolerance >= 1e-15) ||
      !(options.tolerance <= 1e-2))
    return describe("--tolerance", "must lie in [1e-15, 1e-2]", options.tolerance);
  return {};
}

std::optional<physics::ImpactTable> acquire_table(const physics::CushionParams& params,
                                                  const std::string& cache_dir, int threads,
                                                  std::string* note, std::string* error) {
  physics::ImpactTableOptions options;
  options.threads = threads;
  try {
    physics::ImpactTable table =
        physics::ImpactTable::load_or_build(params, options, cache_dir, note);
    if (table.empty()) {
      *error = "cannot build the impact table: " + *note;
      return std::nullopt;
    }
    // What the build measured, so a user can judge the surrogate.
    const physics::ImpactTableError& measured = table.measured_error();
    char summary[256];
    std::snprintf(summary, sizeof summary,
                  "; %.3g %% of %lld cells answer with the exact method (by default at "
                  "tolerance %.3g); elsewhere max error %.3g of V0 in speed, %.3g deg in angle",
                  100.0 * table.fallback_fraction(), static_cast<long long>(measured.cells),
                  table.fallback_tolerance(), measured.max_speed_relative,
                  measured.max_angle_deg);
    *note += summary;
    return table;
  } catch (const std::exception& e) {
    *error = std::string("cannot build the impact table: ") + e.what();
    return std::nullopt;
  }
}

}  // namespace cueplan::cli
