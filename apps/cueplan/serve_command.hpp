// `cueplan serve`: a local web server with the teaching page "what spin lands here?"
// and the JSON API behind it (serve_server.hpp, serve_api.hpp). It prints the address
// to open and serves until Ctrl-C (SIGINT) or SIGTERM, letting the requests being
// computed finish.
#pragma once

#include <iosfwd>
#include <string>

namespace CLI {
class App;
}

namespace cueplan::cli {

// What the command line asked for, in the flags' units.
struct ServeArgs {
  std::string host = "127.0.0.1";
  int port = 8080;   // 0: any free port
  int threads = 0;   // requests computed at once; 0: one per core
  int queue = 64;    // requests that may wait for a worker
  std::string wait_budget = "20s";       // the longest a request waits for a worker
  std::string request_deadline = "10s";  // to receive a request's headers and body
  int client_connections = 64;           // open connections per client address; 0: no limit
  std::string method = "table";  // the impact method of searches that name none
  std::string table_cache;       // empty: default_table_cache_dir()
  double max_time_s = 20.0;      // the longest planner search a request may ask for (s)
  int max_grid = 61;             // the finest spin map a request may ask for
  bool quiet = false;            // no line per request
};

class ServeCommand {
 public:
  // Registers `serve` and its flags on `parent`; the flags write into this object, so it
  // must outlive the parse and stay where it is.
  explicit ServeCommand(CLI::App& parent);
  ServeCommand(const ServeCommand&) = delete;
  ServeCommand& operator=(const ServeCommand&) = delete;

  bool selected() const;

  // Checks every flag without binding or writing anything; returns kExitOk, or
  // kExitUsage with its one line written to `err`.
  int validate(std::ostream& err) const;

  // Serves until a signal; returns kExitOk after a clean stop, kExitFailed when it could
  // not listen, kExitUsage for bad flags.
  int run(std::ostream& out, std::ostream& err) const;

 private:
  std::string check() const;  // empty or the one-line reason to stop

  CLI::App* command_ = nullptr;
  ServeArgs args_;
};

}  // namespace cueplan::cli
