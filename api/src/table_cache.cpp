#include "cueplan/api/table_cache.hpp"

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <system_error>

namespace cueplan::api {

std::string default_table_cache_dir() {
  auto set = [](const char* name) -> const char* {
    const char* value = std::getenv(name);
    return value != nullptr && *value != '\0' ? value : nullptr;
  };
  if (const char* dir = set("CUEPLAN_CACHE_DIR")) return dir;
  if (const char* dir = set("XDG_CACHE_HOME")) return std::string(dir) + "/cueplan";
  if (const char* dir = set("HOME")) return std::string(dir) + "/.cache/cueplan";
  std::error_code ec;
  const std::filesystem::path temp = std::filesystem::temp_directory_path(ec);
  return ((ec ? std::filesystem::path("/tmp") : temp) / "cueplan").string();
}

physics::ImpactTable load_or_build_table(const physics::CushionParams& params,
                                         const physics::ImpactTableOptions& options,
                                         const std::string& cache_dir, std::string* note) {
  using physics::ImpactTable;
  auto say = [note](std::string text) {
    if (note) *note = std::move(text);
  };
  if (cache_dir.empty()) {
    ImpactTable t = ImpactTable::build(params, options);
    say(t.empty() ? "impact table not built: invalid params or options"
                  : "built impact table (no cache directory)");
    return t;
  }
  const std::filesystem::path path =
      std::filesystem::path(cache_dir) / ImpactTable::cache_file_name(params, options);
  std::error_code ec;
  const bool existed = std::filesystem::exists(path, ec);
  std::optional<ImpactTable> cached = ImpactTable::load(path.string());
  if (cached && cached->covers(params) && cached->built_with(options)) {
    say("loaded impact table " + path.string());
    return std::move(*cached);
  }
  ImpactTable t = ImpactTable::build(params, options);
  if (t.empty()) {
    say("impact table not built: invalid params or options");
    return t;
  }
  std::filesystem::create_directories(cache_dir, ec);
  const bool saved = t.save(path.string());
  say(std::string(existed ? "rebuilt impact table (the cached file was unusable)"
                          : "built impact table") +
      (saved ? ", saved to " : ", could not save to ") + path.string());
  return t;
}

}  // namespace cueplan::api
