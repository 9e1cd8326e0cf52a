// Exit codes shared by every cueplan subcommand.
#pragma once

namespace cueplan::cli {

enum ExitCode : int {
  kExitOk = 0,      // done; a result flagged only (e.g. above the rigid limit) is still ok
  kExitFailed = 1,  // the input was fine but the physics could not give a usable answer
  kExitUsage = 2,   // bad command line or input file; one line on stderr says which
};

}  // namespace cueplan::cli
