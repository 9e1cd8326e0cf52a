// libFuzzer target: the cueplan command line (cli_main.hpp) in validate mode, which
// parses and checks every flag and input file but runs nothing and writes nothing.
//
// The input is split into arguments at newlines and NUL bytes: "simulate\nPROBLEM\n
// --speed\n1" is `cueplan simulate PROBLEM --speed 1`. Every input must keep the
// command line's contract:
//   - the exit code is 0, 1 or 2;
//   - with exit code 2 (and 1), stderr holds exactly one line;
//   - nothing is written: the working directory, a scratch directory holding only a
//     link `problems` to the shipped problem files, gains no entry.
// A broken promise aborts, which libFuzzer reports as a crash with the input saved.
//
// Arguments naming /dev, /proc or /sys are skipped: reading /dev/zero or /dev/stdin as
// a problem file would block or never end, as it would for any program reading a file.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "cli_main.hpp"

namespace {

namespace fs = std::filesystem;

[[noreturn]] void broken(const char* promise, const std::vector<std::string>& args,
                         const std::string& detail) {
  std::fprintf(stderr, "cli_fuzzer: %s\n  cueplan", promise);
  for (const std::string& arg : args) std::fprintf(stderr, " '%s'", arg.c_str());
  std::fprintf(stderr, "\n  %s\n", detail.c_str());
  std::abort();
}

fs::path& scratch_dir() {
  static fs::path dir;
  return dir;
}

void remove_scratch() {
  std::error_code ignored;
  if (!scratch_dir().empty()) fs::remove_all(scratch_dir(), ignored);
}

std::size_t entries_in(const fs::path& dir) {
  std::error_code ec;
  std::size_t count = 0;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) ++count;
  return count;
}

bool reaches_devices(std::string_view arg) {
  for (const std::string_view root : {"/dev", "/proc", "/sys"})
    if (arg.find(root) != std::string_view::npos) return true;
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  char name[] = "/tmp/cueplan-cli-fuzz.XXXXXX";
  if (::mkdtemp(name) == nullptr) {
    std::perror("cli_fuzzer: mkdtemp");
    std::abort();
  }
  scratch_dir() = name;
  std::atexit(remove_scratch);
  std::error_code ec;
  fs::create_directory_symlink(CUEPLAN_PROBLEMS_DIR, scratch_dir() / "problems", ec);
  if (!ec) fs::current_path(scratch_dir(), ec);
  if (ec) {
    std::fprintf(stderr, "cli_fuzzer: cannot set up %s: %s\n", name, ec.message().c_str());
    std::abort();
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr std::size_t kMostArguments = 64;
  std::vector<std::string> args;
  std::string arg;
  for (std::size_t i = 0; i <= size; ++i) {
    if (i == size || data[i] == '\n' || data[i] == '\0') {
      args.push_back(arg);
      arg.clear();
      if (args.size() > kMostArguments) return -1;  // not worth keeping
    } else {
      arg += static_cast<char>(data[i]);
    }
  }
  for (const std::string& a : args)
    if (reaches_devices(a)) return -1;

  std::vector<const char*> argv{"cueplan"};
  for (const std::string& a : args) argv.push_back(a.c_str());
  argv.push_back(nullptr);

  const std::size_t entries_before = entries_in(scratch_dir());
  std::ostringstream out, err;
  const int code = cueplan::cli::run_cli(static_cast<int>(argv.size() - 1), argv.data(), out,
                                         err, cueplan::cli::CliMode::validate);
  const std::string errors = err.str();
  if (code != 0 && code != 1 && code != 2)
    broken("the exit code is 0, 1 or 2", args, "exit code " + std::to_string(code));
  if (code != 0) {
    const std::size_t newline = errors.find('\n');
    if (errors.empty() || newline != errors.size() - 1)
      broken("a failure writes exactly one line to stderr", args, errors);
  }
  if (entries_in(scratch_dir()) != entries_before)
    broken("validation writes no file", args, "the working directory gained an entry");
  return 0;
}
