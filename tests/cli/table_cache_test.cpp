// The command line's cache of impact tables: where it lives, and reuse of its files.
#include "cueplan/api/table_cache.hpp"

#include "support/physics_checks.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace cueplan::cli {
namespace {


TEST(TableCache, LoadOrBuildCachesAndRebuildsADamagedFile) {
  std::random_device random;
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("cueplan_table_cache_test_" + std::to_string(random()));
  const std::string cache = (dir / "cache").string();
  const physics::CushionParams params;
  const physics::ImpactTableOptions o = physics::test::tiny_table_options();
  std::string note;
  const physics::ImpactTable built = load_or_build_table(params, o, cache, &note);
  EXPECT_EQ(note.rfind("built impact table, saved to ", 0), 0u) << note;
  const std::filesystem::path file =
      std::filesystem::path(cache) / physics::ImpactTable::cache_file_name(params, o);
  ASSERT_TRUE(std::filesystem::exists(file));

  const physics::ImpactTable loaded = load_or_build_table(params, o, cache, &note);
  EXPECT_EQ(note.rfind("loaded impact table ", 0), 0u) << note;
  EXPECT_EQ(loaded.measured_error().fallback_cells, built.measured_error().fallback_cells);

  std::filesystem::resize_file(file, std::filesystem::file_size(file) / 2);
  const physics::ImpactTable rebuilt = load_or_build_table(params, o, cache, &note);
  EXPECT_EQ(note.rfind("rebuilt impact table", 0), 0u) << note;
  EXPECT_TRUE(physics::ImpactTable::load(file.string()).has_value());
  EXPECT_FALSE(rebuilt.empty());

  // A table of another shape is not taken for this one.
  physics::ImpactTableOptions other = o;
  other.sidespin_nodes += 2;
  load_or_build_table(params, other, cache, &note);
  EXPECT_EQ(note.rfind("built impact table, saved to ", 0), 0u) << note;
  std::filesystem::remove_all(dir);
}

TEST(TableCache, DefaultDirectoryFollowsTheEnvironment) {
  // Save and restore the variables this test changes.
  const char* names[] = {"CUEPLAN_CACHE_DIR", "XDG_CACHE_HOME", "HOME"};
  std::vector<std::pair<std::string, bool>> saved;
  for (const char* n : names) {
    const char* v = std::getenv(n);
    saved.emplace_back(v ? v : "", v != nullptr);
  }
  setenv("CUEPLAN_CACHE_DIR", "/a/cache", 1);
  setenv("XDG_CACHE_HOME", "/b", 1);
  setenv("HOME", "/c", 1);
  EXPECT_EQ(default_table_cache_dir(), "/a/cache");
  unsetenv("CUEPLAN_CACHE_DIR");
  EXPECT_EQ(default_table_cache_dir(), "/b/cueplan");
  setenv("XDG_CACHE_HOME", "", 1);
  EXPECT_EQ(default_table_cache_dir(), "/c/.cache/cueplan");
  unsetenv("HOME");
  unsetenv("XDG_CACHE_HOME");
  EXPECT_FALSE(default_table_cache_dir().empty());
  for (size_t i = 0; i < saved.size(); ++i) {
    if (saved[i].second)
      setenv(names[i], saved[i].first.c_str(), 1);
    else
      unsetenv(names[i]);
  }
}

}  // namespace
}  // namespace cueplan::cli
