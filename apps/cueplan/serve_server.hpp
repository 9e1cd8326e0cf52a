// The HTTP side of `cueplan serve` (cpp-httplib): the page's files from the binary, the
// JSON API of serve_api.hpp, and what keeps a server well behaved - a bounded pool of
// workers (a request that finds them all busy gets 503 at once, it does not queue), a
// request body limit (413), JSON errors for every failure, POSTs only as
// application/json, and on loopback only requests addressed to a loopback name (so a
// web page elsewhere cannot drive it through DNS rebinding). Nothing a request says
// names a file on the server.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "serve_api.hpp"
#include "serve_tables.hpp"

namespace cueplan::cli {

struct ServerOptions {
  std::string host = "127.0.0.1";  // the address to listen on
  int port = 8080;                 // 0: any free port (port() tells which)
  int workers = 0;                 // requests computed at once; 0: one per core
  size_t max_body_bytes = 256 * 1024;
  ApiLimits limits;
  std::string default_method = "table";  // solve's and spinmap's when a request names none
  ImpactTableStore::Settings tables;
  bool preload_tables = true;  // queue the shipped problems' tables at start (with "table")
  // One line per request and per table note, from the server's threads; may be empty.
  std::function<void(const std::string&)> log;
};

class WebServer {
 public:
  explicit WebServer(ServerOptions options);
  ~WebServer();  // stops the server and waits for its threads
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  // Binds the listening socket: empty, or why not (the address is taken, say).
  std::string bind();
  // Serves until stop(); false when it could not listen. Call after bind().
  bool run();
  // From any thread: stops accepting; requests being computed finish first, then run()
  // returns.
  void stop();

  int port() const;         // after bind()
  std::string url() const;  // "http://127.0.0.1:8080/"
  int workers() const;
  ImpactTableStore& tables();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// True for a name or address of this machine's loopback: localhost, 127.x.y.z, ::1.
bool is_loopback(const std::string& host);

}  // namespace cueplan::cli
