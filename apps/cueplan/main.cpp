// cueplan: the command line over the cueplan libraries. Each subcommand lives in its
// own file; this shell parses, reports parse errors in one line and dispatches.
#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

#include "exit_codes.hpp"
#include "figures_command.hpp"
#include "rebound_command.hpp"
#include "simulate_command.hpp"
#include "solve_command.hpp"
#include "spinmap_command.hpp"

namespace {

// CLI11's message as one line, prefixed with the subcommand it concerns.
std::string parse_error_line(const CLI::App& app, const CLI::ParseError& error) {
  std::string prefix = "cueplan";
  for (const CLI::App* sub : app.get_subcommands()) prefix += " " + sub->get_name();
  std::string message = error.what();
  for (char& c : message)
    if (c == '\n') c = ' ';
  while (!message.empty() && message.back() == ' ') message.pop_back();
  return prefix + ": " + message;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace cueplan::cli;

  CLI::App app{
      "cueplan: cue-sports shot planning on the Mathavan-Jackson-Parkin (2010) "
      "ball-cushion impact model.",
      "cueplan"};
  app.set_version_flag("--version", std::string("cueplan ") + CUEPLAN_VERSION);
  app.require_subcommand(1);
  app.footer(
      "Run 'cueplan <command> --help' for a command's flags, units and defaults.\n"
      "Exit codes: 0 done, 1 no usable result, 2 bad command line or input.");

  ReboundCommand rebound(app);
  SimulateCommand simulate(app);
  FiguresCommand figures(app);
  SolveCommand solve(app);
  SpinmapCommand spinmap(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& done) {  // --help or --version
    return app.exit(done);
  } catch (const CLI::ParseError& error) {
    // CLI11 reports an unknown command as a missing one; name it instead.
    if (app.get_subcommands().empty() && argc > 1 && argv[1][0] != '-') {
      std::cerr << "cueplan: unknown command '" << argv[1]
                << "'; the commands are rebound, simulate, solve, spinmap and figures\n";
      return kExitUsage;
    }
    std::cerr << parse_error_line(app, error) << '\n';
    return kExitUsage;
  }

  if (rebound.selected()) return rebound.run(std::cout, std::cerr);
  if (simulate.selected()) return simulate.run(std::cout, std::cerr);
  if (figures.selected()) return figures.run(std::cout, std::cerr);
  if (solve.selected()) return solve.run(std::cout, std::cerr);
  if (spinmap.selected()) return spinmap.run(std::cout, std::cerr);
  return kExitUsage;  // unreachable: a subcommand is required
}
