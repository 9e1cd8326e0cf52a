// Helpers shared by the command-line tests: run `cueplan` as a separate process and
// collect what it printed, keep its output files in a scratch directory, and read the
// text and CSV it writes.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cueplan/problems/problem.hpp"

namespace cli_test {

// The name each test program gives its scratch directory (the process id is appended);
// a test file defines it once.
extern const char* const kScratchName;

// This test program's scratch directory, created on first use and removed at exit.
const std::filesystem::path& scratch();

std::string read_text(const std::filesystem::path& path);
void write_text(const std::filesystem::path& path, const std::string& text);

struct ProcessResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// Runs `cueplan <args>` through the shell (args are shell words) and collects its exit
// code, stdout and stderr; `tag` keeps the output files of several runs in one test apart.
ProcessResult cueplan(const std::string& args, const std::string& tag = "");

std::vector<std::string> lines_of(const std::string& text);

// Splits a CSV line; quoted fields (the message column) keep their commas.
std::vector<std::string> csv_fields(const std::string& line);

// A CSV text as rows of named cells.
std::vector<std::map<std::string, std::string>> csv_rows(const std::string& text);

// How many times `needle` stands in `text`, overlaps included.
std::size_t count_of(const std::string& text, const std::string& needle);

// The path of a shipped problem file, by its stem.
std::string problem_path(const std::string& stem);

// A shipped problem, loaded; a load failure fails the calling test.
cueplan::problems::Problem shipped(const std::string& stem);

}  // namespace cli_test
