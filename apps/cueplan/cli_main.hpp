// The whole command line as a function: parse argv, report a bad command line in one
// line, dispatch to the chosen command. main() is a call to run_cli; the command-line
// fuzzer (fuzz/) calls it too, without running anything.
#pragma once

#include <iosfwd>

namespace cueplan::cli {

enum class CliMode {
  run,       // parse, check, then do the work and write the outputs
  validate,  // parse and check every argument and input file, then stop: no work is
             // done and nothing is written or created (exit 0 when all is well)
};

// Returns an ExitCode (exit_codes.hpp). `out` receives results (and --help/--version);
// `err` receives diagnostics: with exit code 2, exactly one line. Never throws.
int run_cli(int argc, const char* const* argv, std::ostream& out, std::ostream& err,
            CliMode mode = CliMode::run);

}  // namespace cueplan::cli
