// cueplan: the command line over the cueplan libraries. Each subcommand lives in its
// own file and is registered in cli_main.cpp, which parses, reports parse errors in
// one line and dispatches.
#include <iostream>

#include "cli_main.hpp"
#include "cueplan/planner/route.hpp"

int main(int argc, char** argv) {
  // The commands print their own reports; OMPL (route, solve --global ompl_kpiece1)
  // keeps to errors.
  cueplan::planner::quiet_ompl_messages();
  return cueplan::cli::run_cli(argc, argv, std::cout, std::cerr);
}
