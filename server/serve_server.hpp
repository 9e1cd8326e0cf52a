// The HTTP side of `cueplan serve` (cpp-httplib): the page's files from the binary, the
// JSON API of serve_api.hpp, and what keeps a server well behaved when a class uses it:
// - a bounded pool of workers with a first-come queue in front of it: a request waits its
//   turn, and gets 503 with Retry-After only when the queue is full or its expected wait
//   exceeds the wait budget;
// - slow or hostile clients cannot starve the others: each request's headers and body
//   must arrive within an overall deadline (408), a client address holds a bounded number
//   of connections (503), there are many more connection threads than workers, and the
//   listen backlog is 128;
// - a body limit (413) counted while the body is read, chunked or not, so a large body is
//   refused without being held in memory; headers are limited too (431);
// - JSON errors for every failure, 405 with Allow for a wrong method, POSTs only as
//   application/json, and on loopback only requests addressed to a loopback name (so a
//   web page elsewhere cannot drive it through DNS rebinding). Nothing a request says
//   names a file on the server.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "serve_api.hpp"
#include "serve_tables.hpp"

namespace cueplan::server {
using namespace cueplan::api;  // the api's types and checks, as the server's own

struct ServerOptions {
  std::string host = "127.0.0.1";  // the address to listen on
  int port = 8080;                 // 0: any free port (port() tells which)
  int workers = 0;                 // requests computed at once; 0: one per core
  int queue = 64;                  // requests that may wait for a worker
  double wait_budget_s = 20.0;     // the longest a request waits for a worker (s)
  double request_deadline_s = 10.0;  // to receive one request's headers and body (s)
  int client_connections = 64;     // open connections per client address; 0: no limit
  size_t max_body_bytes = 256 * 1024;
  size_t max_header_bytes = 64 * 1024;
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
  int connection_threads() const;
  ImpactTableStore& tables();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// True for a name or address of this machine's loopback: localhost, 127.x.y.z, ::1.
bool is_loopback(const std::string& host);

}  // namespace cueplan::server
