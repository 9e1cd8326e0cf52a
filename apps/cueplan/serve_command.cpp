#include "serve_command.hpp"

#include <pthread.h>
#include <signal.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <ostream>
#include <stdexcept>
#include <string>
#include <thread>

#include "cueplan/physics/cushion_impact.hpp"
#include "cueplan/api/exit_codes.hpp"
#include "serve_server.hpp"
#include "cueplan/api/table_cache.hpp"

namespace cueplan::cli {
using namespace cueplan::server;  // the server (server/)
namespace {

constexpr const char* kCommandName = "cueplan serve";

// "20", "20s" or "2.5 s" as seconds; NaN for anything else.
double seconds(const std::string& text) {
  std::string t = text;
  while (!t.empty() && t.back() == ' ') t.pop_back();
  if (!t.empty() && t.back() == 's') t.pop_back();
  while (!t.empty() && t.back() == ' ') t.pop_back();
  if (t.empty()) return NAN;
  size_t used = 0;
  double value = NAN;
  try {
    value = std::stod(t, &used);
  } catch (const std::exception&) {
    return NAN;
  }
  return used == t.size() && std::isfinite(value) ? value : NAN;
}

}  // namespace

ServeCommand::ServeCommand(CLI::App& parent) {
  command_ = parent.add_subcommand(
      "serve",
      "Serve the teaching page - set up a shot on the table, plan it, and see every spin that "
      "lands on the target - and its JSON API on a local web server, until Ctrl-C.");
  CLI::App& c = *command_;
  c.add_option("--host", args_.host,
               "Address to listen on. The default, loopback, keeps the server to this machine; "
               "0.0.0.0 opens it to the network")
      ->type_name("ADDRESS")
      ->capture_default_str();
  c.add_option("--port", args_.port, "TCP port, 0 to 65535; 0 picks a free one (printed)")
      ->type_name("N")
      ->capture_default_str();
  c.add_option("--threads", args_.threads,
               "Requests computed at once (the worker pool; each request runs on one thread); "
               "0: one per core. A request that finds every worker busy waits in the queue")
      ->type_name("N")
      ->capture_default_str();
  c.add_option("--queue", args_.queue,
               "Requests that may wait for a worker, first come first served, 0 to 10000. A "
               "request is answered 503 with Retry-After only when the queue is full or its "
               "expected wait exceeds --wait-budget")
      ->type_name("N")
      ->capture_default_str();
  c.add_option("--wait-budget", args_.wait_budget,
               "The longest a request waits for a worker, in seconds (20 or 20s), 0 to 600")
      ->type_name("S")
      ->capture_default_str();
  c.add_option("--request-deadline", args_.request_deadline,
               "A request's headers and body must arrive within this many seconds (10 or 10s), "
               "0.1 to 600; a slower one is answered 408 and its connection closed")
      ->type_name("S")
      ->capture_default_str();
  c.add_option("--client-connections", args_.client_connections,
               "Connections one client address may hold open at once (a browser uses up to 6); "
               "0: no limit. Raise it when a class reaches the server through one address (NAT)")
      ->type_name("N")
      ->capture_default_str();
  c.add_option("--method", args_.method,
               "Cushion impacts of the searches (solve, spinmap) when a request names none: "
               "table (as cueplan solve; the shipped problems' tables are loaded from the cache, "
               "or built once in the background, about 30 s each on 2 cores) or exact")
      ->type_name("table|exact")
      ->capture_default_str();
  c.add_option("--table-cache", args_.table_cache,
               "Directory of the cached impact tables (default: $CUEPLAN_CACHE_DIR, else "
               "$XDG_CACHE_HOME/cueplan, else ~/.cache/cueplan)")
      ->type_name("DIR");
  c.add_option("--max-time", args_.max_time_s,
               "The longest planner search a request gets (s), > 0: a request's options.max_time "
               "is clamped to it")
      ->type_name("S")
      ->capture_default_str();
  c.add_option("--max-grid", args_.max_grid,
               "The finest spin map a request may ask for, 3 to 1001 points across the disc")
      ->type_name("N")
      ->capture_default_str();
  c.add_flag("--quiet", args_.quiet, "No line on stderr for each request");
  c.footer(
      "API (JSON in, JSON out; the answers are the commands' --json objects): POST /api/solve "
      "{problem, options}, POST /api/simulate {problem, stroke, options}, POST /api/spinmap "
      "{problem, speed, aim_deg, grid, options}, POST /api/run {problem, game, options}, GET "
      "/api/examples, GET /api/health. docs/commands/serve.md shows each.\n"
      "Exit codes: 0 stopped by Ctrl-C or SIGTERM, 1 could not listen, 2 bad flags.\n"
      "Example: cueplan serve --port 8080, then open http://127.0.0.1:8080/");
}

bool ServeCommand::selected() const { return command_->parsed(); }

std::string ServeCommand::check() const {
  if (args_.host.empty()) return "--host must name an address, such as 127.0.0.1";
  if (args_.port < 0 || args_.port > 65535)
    return "--port must be 0 to 65535, got " + std::to_string(args_.port);
  if (args_.threads < 0)
    return "--threads must be 0 (one per core) or more, got " + std::to_string(args_.threads);
  if (args_.queue < 0 || args_.queue > 10000)
    return "--queue must be 0 to 10000, got " + std::to_string(args_.queue);
  if (const double s = seconds(args_.wait_budget); !(s >= 0.0 && s <= 600.0))
    return "--wait-budget must be 0 to 600 seconds (20 or 20s), got '" + args_.wait_budget + "'";
  if (const double s = seconds(args_.request_deadline); !(s >= 0.1 && s <= 600.0))
    return "--request-deadline must be 0.1 to 600 seconds (10 or 10s), got '" +
           args_.request_deadline + "'";
  if (args_.client_connections < 0)
    return "--client-connections must be 0 (no limit) or more, got " +
           std::to_string(args_.client_connections);
  if (args_.method != "table" && args_.method != "exact")
    return "--method must be table or exact, got '" + args_.method + "'";
  if (!std::isfinite(args_.max_time_s) || !(args_.max_time_s > 0.0))
    return fmt::format("--max-time must be positive and finite (s), got {}", args_.max_time_s);
  if (args_.max_grid < 3 || args_.max_grid > 1001)
    return "--max-grid must be 3 to 1001, got " + std::to_string(args_.max_grid);
  return {};
}

int ServeCommand::validate(std::ostream& err) const {
  const std::string why = check();
  return why.empty() ? kExitOk : usage_error(err, kCommandName, why);
}

int ServeCommand::run(std::ostream& out, std::ostream& err) const {
  if (std::string why = check(); !why.empty()) return usage_error(err, kCommandName, why);

  // SIGINT and SIGTERM go to one thread that waits for them (every thread started from
  // here on inherits the mask), which stops the server; a second one ends the process.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  sigset_t previous;
  pthread_sigmask(SIG_BLOCK, &signals, &previous);

  std::mutex err_mutex;
  const auto note = [&](const std::string& line) {
    std::lock_guard<std::mutex> lock(err_mutex);
    err << kCommandName << ": " << line << std::endl;
  };

  ServerOptions options;
  options.host = args_.host;
  options.port = args_.port;
  options.workers = args_.threads;
  options.queue = args_.queue;
  options.wait_budget_s = seconds(args_.wait_budget);
  options.request_deadline_s = seconds(args_.request_deadline);
  options.client_connections = args_.client_connections;
  options.default_method = args_.method;
  options.limits.max_time_s = args_.max_time_s;
  options.limits.max_grid = args_.max_grid;
  options.tables.cache_dir =
      args_.table_cache.empty() ? default_table_cache_dir() : args_.table_cache;
  options.tables.on_note = note;
  if (!args_.quiet) options.log = note;

  int code = kExitOk;
  {
    WebServer server(options);
    if (std::string why = server.bind(); !why.empty()) {
      note(why);
      pthread_sigmask(SIG_SETMASK, &previous, nullptr);
      return kExitFailed;
    }
    out << kCommandName << ": open " << server.url() << " in a browser (Ctrl-C stops the server)"
        << std::endl;
    if (!is_loopback(args_.host))
      note("listening on " + args_.host + ": other machines can reach this server");
    note(fmt::format("{} worker{} and a queue of {} (wait budget {:g} s); searches use the {} "
                     "impact method{}",
                     server.workers(), server.workers() == 1 ? "" : "s", args_.queue,
                     seconds(args_.wait_budget), args_.method,
                     args_.method == "table"
                         ? " (tables load or build in the background; /api/health tells when "
                           "they are ready)"
                         : ""));

    std::atomic<bool> finished{false};
    std::thread waiter([&] {
      for (int received = 0;;) {
        int signal = 0;
        if (sigwait(&signals, &signal) != 0 || finished) return;
        if (++received == 1) {
          note(std::string("stopping (") + (signal == SIGINT ? "SIGINT" : "SIGTERM") +
               "): requests being computed finish first; a second signal ends it at once");
          server.stop();
        } else {
          note("stopped at once");
          std::_Exit(kExitFailed);
        }
      }
    });
    if (!server.run()) {
      note("the server stopped: it could not accept connections");
      code = kExitFailed;
    }
    finished = true;
    pthread_kill(waiter.native_handle(), SIGTERM);  // wakes the waiter if no signal came
    waiter.join();

    // A table build cannot be interrupted; rather than wait for it, leave now (the cache
    // is written through a temporary file and a rename, so nothing half-made is kept).
    if (server.tables().working()) {
      note("stopped (an impact table was still being made; it is made again at the next start)");
      out.flush();
      err.flush();
      std::_Exit(code);
    }
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  note("stopped");
  return code;
}

}  // namespace cueplan::cli
