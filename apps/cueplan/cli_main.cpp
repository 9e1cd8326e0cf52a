#include "cli_main.hpp"

#include <CLI/CLI.hpp>
#include <exception>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "calibrate_command.hpp"
#include "collide_command.hpp"
#include "cueplan/api/exit_codes.hpp"
#include "figures_command.hpp"
#include "fit_command.hpp"
#include "merge_command.hpp"
#include "rebound_command.hpp"
#include "route_command.hpp"
#include "run_command.hpp"
#include "serve_command.hpp"
#include "simulate_command.hpp"
#include "solve_command.hpp"
#include "spinmap_command.hpp"
#include "zone_command.hpp"

namespace cueplan::cli {
namespace {

// One registered command, seen through the three calls the shell makes.
struct CommandEntry {
  std::function<bool()> selected;
  std::function<int(std::ostream& err)> validate;
  std::function<int(std::ostream& out, std::ostream& err)> run;
};

template <class Command>
CommandEntry entry(const Command& command) {
  CommandEntry e;
  e.selected = [&command] { return command.selected(); };
  e.run = [&command](std::ostream& out, std::ostream& err) { return command.run(out, err); };
  e.validate = [&command](std::ostream& err) {
    if constexpr (requires { command.validate(err); })
      return command.validate(err);
    else
      return static_cast<int>(kExitOk);  // a command without checks of its own
  };
  return e;
}

// Text as one line: newlines become spaces, trailing spaces go.
std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

// CLI11's message as one line, prefixed with the subcommand it concerns.
std::string parse_error_line(const CLI::App& app, const CLI::Error& error) {
  std::string prefix = "cueplan";
  for (const CLI::App* sub : app.get_subcommands()) prefix += " " + sub->get_name();
  return prefix + ": " + one_line(error.what());
}

// "a, b and c"
std::string listed(const std::vector<std::string>& names) {
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) text += i + 1 == names.size() ? " and " : ", ";
    text += names[i];
  }
  return text;
}

int parse_and_dispatch(int argc, const char* const* argv, std::ostream& out, std::ostream& err,
                       CliMode mode) {
  CLI::App app{
      "cueplan: cue-sports shot planning on the Mathavan-Jackson-Parkin (2010) "
      "ball-cushion impact model.",
      "cueplan"};
  app.set_version_flag("--version", std::string("cueplan ") + CUEPLAN_VERSION);
  app.require_subcommand(1);
  app.footer(
      "Run 'cueplan <command> --help' for a command's flags, units and defaults.\n"
      "Exit codes: 0 done, 1 no usable result, 2 bad command line or input.");

  // Every command is registered here and nowhere else: construct it on `app` (its flags
  // bind into it, so it lives until the end of this function) and list it in `commands`.
  ReboundCommand rebound(app);
  CollideCommand collide(app);
  SimulateCommand simulate(app);
  FiguresCommand figures(app);
  SolveCommand solve(app);
  SpinmapCommand spinmap(app);
  ZoneCommand zone(app);
  RouteCommand route(app);
  RunCommand run(app);
  ServeCommand serve(app);
  MergeCommand merge(app);
  FitCommand fit(app);
  CalibrateCommand calibrate(app);
  const std::vector<CommandEntry> commands = {
      entry(rebound), entry(collide), entry(simulate), entry(figures), entry(solve),
      entry(spinmap), entry(route),   entry(serve),    entry(merge),   entry(fit),
      entry(calibrate), entry(run), entry(zone)};

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& done) {  // --help or --version
    return app.exit(done, out, err);
  } catch (const CLI::ParseError& error) {
    // CLI11 reports an unknown command as a missing one; name it instead.
    if (app.get_subcommands().empty() && argc > 1 && argv[1][0] != '-') {
      std::vector<std::string> names;
      for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
      err << "cueplan: unknown command '" << one_line(argv[1]) << "'; the commands are "
          << listed(names) << '\n';
      return kExitUsage;
    }
    err << parse_error_line(app, error) << '\n';
    return kExitUsage;
  }

  for (const CommandEntry& command : commands) {
    if (!command.selected()) continue;
    return mode == CliMode::validate ? command.validate(err) : command.run(out, err);
  }
  return kExitUsage;  // unreachable: a subcommand is required
}

}  // namespace

int run_cli(int argc, const char* const* argv, std::ostream& out, std::ostream& err,
            CliMode mode) {
  // CLI11 throws more than ParseError for some inputs (e.g. its own construction errors),
  // and a command may run out of memory: nothing escapes, each becomes one line.
  try {
    return parse_and_dispatch(argc, argv, out, err, mode);
  } catch (const CLI::Error& error) {
    err << "cueplan: " << one_line(error.what()) << '\n';
    return kExitUsage;
  } catch (const std::exception& error) {
    err << "cueplan: " << one_line(error.what()) << '\n';
    return kExitFailed;
  } catch (...) {
    err << "cueplan: unknown error\n";
    return kExitFailed;
  }
}

}  // namespace cueplan::cli
