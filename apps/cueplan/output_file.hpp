// Files the command line writes: each appears complete or not at all.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace cueplan::cli {

// Creates `dir` (and its parents) if missing. Empty when the directory exists
// afterwards; otherwise one line saying why not.
std::string ensure_directory(const std::filesystem::path& dir);

// Writes `contents` to a temporary file beside `path` and renames it over `path`, so
// a reader never sees a half-written file. Empty on success; otherwise one line.
std::string write_file_atomically(const std::filesystem::path& path, std::string_view contents);

}  // namespace cueplan::cli
