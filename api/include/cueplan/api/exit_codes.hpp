// Exit codes shared by every cueplan subcommand.
#pragma once

#include <ostream>
#include <string_view>

namespace cueplan::api {

enum ExitCode : int {
  kExitOk = 0,      // done; a result flagged only (e.g. above the rigid limit) is still ok
  kExitFailed = 1,  // the input was fine but the physics could not give a usable answer
  kExitUsage = 2,   // bad command line or input file; one line on stderr says which
};

// Prints the one usage line "COMMAND: WHY" and returns kExitUsage.
inline int usage_error(std::ostream& err, std::string_view command, std::string_view why) {
  err << command << ": " << why << '\n';
  return kExitUsage;
}

}  // namespace cueplan::api

// The faces (command line, server, batch) name these as their own.
namespace cueplan::cli {
using api::ExitCode;
using api::kExitOk;
using api::kExitFailed;
using api::kExitUsage;
using api::usage_error;
}  // namespace cueplan::cli
