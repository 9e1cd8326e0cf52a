// Files the command line writes: each appears complete or not at all.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "cueplan/draw/picture.hpp"

namespace cueplan::api {

// Creates `dir` (and its parents) if missing. Empty when the directory exists
// afterwards; otherwise one line saying why not.
std::string ensure_directory(const std::filesystem::path& dir);

// Whether a file could be written at `path` without creating anything: empty when its
// directory exists and is writable and `path` is not a directory; otherwise one line.
// Commands check their output paths with it before any work, so that a bad path fails
// fast and leaves nothing behind.
std::string check_output_file(const std::filesystem::path& path);

// check_output_file for a picture named by `flag` (e.g. "--svg"), whose extension must
// choose its format (.svg, .png or .pdf): empty, or one line that names the flag, e.g.
// "--svg must name a .svg, .png or .pdf file, got 'plan.jpg'".
std::string check_picture_file(const std::string& flag, const std::filesystem::path& path);

// Encodes `picture` in the format of `path`'s extension and writes it atomically. Empty
// on success; otherwise one line (the caller names the flag).
std::string write_picture(const std::filesystem::path& path, const draw::Picture& picture);

// Writes `contents` to a temporary file beside `path` and renames it over `path`, so
// a reader never sees a half-written file. Empty on success; otherwise one line.
std::string write_file_atomically(const std::filesystem::path& path, std::string_view contents);

}  // namespace cueplan::api

// The faces (command line, server, batch) name these as their own.
namespace cueplan::cli {
using api::ensure_directory;
using api::check_output_file;
using api::check_picture_file;
using api::write_picture;
using api::write_file_atomically;
}  // namespace cueplan::cli
