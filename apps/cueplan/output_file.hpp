// Files the command line writes: each appears complete or not at all.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace cueplan::cli {

// Creates `dir` (and its parents) if missing. Empty when the directory exists
// afterwards; otherwise one line saying why not.
std::string ensure_directory(const std::filesystem::path& dir);

// Whether a file could be written at `path` without creating anything: empty when its
// directory exists and is writable and `path` is not a directory; otherwise one line.
// Commands check their output paths with it before any work, so that a bad path fails
// fast and leaves nothing behind.
std::string check_output_file(const std::filesystem::path& path);

// Writes `contents` to a temporary file beside `path` and renames it over `path`, so
// a reader never sees a half-written file. Empty on success; otherwise one line.
std::string write_file_atomically(const std::filesystem::path& path, std::string_view contents);

}  // namespace cueplan::cli
