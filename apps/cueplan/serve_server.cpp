#include "serve_server.hpp"

#include <httplib.h>

#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <string_view>
#include <thread>
#include <utility>

#include "cueplan/physics/parallel.hpp"
#include "serve_assets.hpp"

namespace cueplan::cli {
namespace {

using nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

// Connections served besides the workers' own: a browser keeps up to six open, and the
// page, /api/health and /api/examples must answer while every worker computes.
constexpr int kSpareConnections = 8;
constexpr time_t kKeepAliveSeconds = 3;
constexpr time_t kSocketTimeoutSeconds = 10;
constexpr int kRetryWhenBusy = 1;  // s

// The pool's free workers; a request takes one or is turned away, it never waits.
class WorkerSlots {
 public:
  explicit WorkerSlots(int size) : size_(size) {}
  bool try_take() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (busy_ >= size_) return false;
    ++busy_;
    return true;
  }
  void give_back() {
    std::lock_guard<std::mutex> lock(mutex_);
    --busy_;
  }
  int busy() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return busy_;
  }
  int size() const { return size_; }

 private:
  const int size_;
  mutable std::mutex mutex_;
  int busy_ = 0;
};

const char* mime_type(std::string_view name) {
  const auto ends = [&](std::string_view ext) {
    return name.size() >= ext.size() && name.substr(name.size() - ext.size()) == ext;
  };
  if (ends(".html")) return "text/html; charset=utf-8";
  if (ends(".js")) return "text/javascript; charset=utf-8";
  if (ends(".css")) return "text/css; charset=utf-8";
  if (ends(".svg")) return "image/svg+xml";
  if (ends(".png")) return "image/png";
  return "application/octet-stream";
}

void send(httplib::Response& res, const ApiReply& reply) {
  res.status = reply.status;
  if (reply.retry_after_s) res.set_header("Retry-After", std::to_string(*reply.retry_after_s));
  res.set_content(reply.body.dump(-1, ' ', false, ordered_json::error_handler_t::replace),
                  "application/json");
}

// The host part of a Host header: "localhost:8080" -> "localhost", "[::1]:80" -> "::1".
std::string host_name(const std::string& header) {
  if (!header.empty() && header.front() == '[') {
    const size_t close = header.find(']');
    return close == std::string::npos ? header : header.substr(1, close - 1);
  }
  return header.substr(0, header.find(':'));
}

std::string reason_of(int status, size_t max_body) {
  switch (status) {
    case 400: return "bad request: the HTTP request could not be read";
    case 404: return "no such page or endpoint";
    case 405: return "method not allowed";
    case 413:
      return fmt::format("the request body is larger than this server takes ({} bytes)", max_body);
    case 414: return "the request's address is too long";
    default: return fmt::format("HTTP status {}", status);
  }
}

}  // namespace

bool is_loopback(const std::string& host) {
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

struct WebServer::Impl {
  explicit Impl(ServerOptions o)
      : options(std::move(o)),
        slots(static_cast<int>(physics::thread_count(options.workers))),
        tables(options.tables),
        api(options.limits, options.default_method, &tables, shipped_examples(&examples_error)) {}

  void log(const std::string& line) const {
    if (options.log) options.log(line);
  }

  // A POST endpoint that computes: it takes a worker or answers 503 at once.
  httplib::Server::Handler compute(ApiReply (Api::*endpoint)(std::string_view) const) {
    return [this, endpoint](const httplib::Request& req, httplib::Response& res) {
      if (!slots.try_take()) {
        ApiReply busy = error_reply(
            503, fmt::format("the server is busy: all {} of its workers are computing; ask again "
                             "in a moment",
                             slots.size()));
        busy.retry_after_s = kRetryWhenBusy;
        send(res, busy);
        return;
      }
      struct GiveBack {
        WorkerSlots& s;
        ~GiveBack() { s.give_back(); }
      } give_back{slots};
      const Clock::time_point started = Clock::now();
      send(res, (api.*endpoint)(req.body));
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - started).count();
      res.set_header("Server-Timing", fmt::format("compute;dur={:.1f}", ms));
    };
  }

  void routes() {
    using httplib::Request;
    using httplib::Response;
    http.Get("/api/health", [this](const Request&, Response& res) {
      ApiReply reply = api.health(slots.size(), slots.busy());
      reply.body["limits"]["max_body_bytes"] = options.max_body_bytes;
      send(res, reply);
    });
    http.Get("/api/examples", [this](const Request&, Response& res) { send(res, api.examples()); });
    http.Post("/api/solve", compute(&Api::solve));
    http.Post("/api/simulate", compute(&Api::simulate));
    http.Post("/api/spinmap", compute(&Api::spinmap));
    // The page: only the files carried in the binary, by exact name.
    http.Get("/[^/]*", [](const Request& req, Response& res) {
      const std::string name = req.path == "/" ? "index.html" : req.path.substr(1);
      for (const EmbeddedFile& f : web_assets())
        if (f.name == name) {
          res.set_content(std::string(f.bytes), mime_type(f.name));
          return;
        }
      res.status = 404;
    });

    http.set_pre_routing_handler([this](const Request& req, Response& res) {
      // On loopback, only requests addressed to a loopback name.
      if (is_loopback(options.host) && !is_loopback(host_name(req.get_header_value("Host")))) {
        send(res, error_reply(403, "this server answers only requests addressed to localhost "
                                   "or 127.0.0.1 (Host: " +
                                       req.get_header_value("Host") + ")"));
        res.set_header("Connection", "close");
        return httplib::Server::HandlerResponse::Handled;
      }
      // POSTs carry JSON: a form on another site cannot send that without asking first.
      if (req.method == "POST" &&
          req.get_header_value("Content-Type").rfind("application/json", 0) != 0) {
        send(res, error_reply(415, "POST requests must be JSON, with Content-Type: "
                                   "application/json"));
        res.set_header("Connection", "close");
        return httplib::Server::HandlerResponse::Handled;
      }
      return httplib::Server::HandlerResponse::Unhandled;
    });
    // Every failure httplib answers itself (404, 413, ...) gets a JSON body too.
    http.set_error_handler(httplib::Server::HandlerWithResponse(
        [this](const Request&, Response& res) {
          if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
          const int status = res.status;
          send(res, error_reply(status, reason_of(status, options.max_body_bytes)));
          return httplib::Server::HandlerResponse::Handled;
        }));
    http.set_exception_handler([](const Request&, Response& res, std::exception_ptr ep) {
      std::string what = "unknown error";
      try {
        if (ep) std::rethrow_exception(ep);
      } catch (const std::exception& e) {
        what = e.what();
      } catch (...) {
      }
      send(res, error_reply(500, "internal error: " + what));
    });
    http.set_logger([this](const Request& req, const Response& res) {
      const std::string timing = res.get_header_value("Server-Timing");
      log(req.method + " " + req.path + " " + std::to_string(res.status) +
          (timing.empty() ? "" : " (" + timing.substr(timing.find('=') + 1) + " ms)"));
    });
  }

  ServerOptions options;
  WorkerSlots slots;
  ImpactTableStore tables;
  std::string examples_error;  // set by shipped_examples, before `api` (declared after it)
  Api api;
  httplib::Server http;
  int port = 0;
  std::atomic<bool> stop_requested{false};
  std::atomic<bool> listening_phase{false};
};

WebServer::WebServer(ServerOptions options) {
  // The table store reports through the server's log.
  auto log = options.log;
  if (!options.tables.on_note && log) options.tables.on_note = log;
  impl_ = std::make_unique<Impl>(std::move(options));
  Impl& s = *impl_;
  const int connections = s.slots.size() + kSpareConnections;
  s.http.new_task_queue = [connections] { return new httplib::ThreadPool(connections); };
  // SO_REUSEADDR only: a restarted server gets its port back at once, but (unlike
  // httplib's default, which adds SO_REUSEPORT) a second server cannot share a port that
  // one already listens on.
  s.http.set_socket_options([](socket_t sock) {
    int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  s.http.set_payload_max_length(s.options.max_body_bytes);
  s.http.set_keep_alive_timeout(kKeepAliveSeconds);
  s.http.set_read_timeout(kSocketTimeoutSeconds);
  s.http.set_write_timeout(kSocketTimeoutSeconds);
  s.http.set_default_headers(
      {{"X-Content-Type-Options", "nosniff"},
       {"Cache-Control", "no-store"},
       {"Referrer-Policy", "no-referrer"},
       {"Content-Security-Policy",
        "default-src 'self'; script-src 'self'; style-src 'self'; img-src 'self' data:; "
        "connect-src 'self'; frame-ancestors 'none'; base-uri 'none'; form-action 'none'"}});
  s.routes();
  if (s.options.default_method == "table" && s.options.preload_tables)
    for (const Example& e : s.api.example_list()) s.tables.find(e.loaded.scene.ball_and_cushion);
}

WebServer::~WebServer() { stop(); }

std::string WebServer::bind() {
  Impl& s = *impl_;
  if (!s.examples_error.empty()) return s.examples_error;
  if (s.options.port < 0 || s.options.port > 65535)
    return fmt::format("port {} is not a port number (0 to 65535)", s.options.port);
  if (s.options.port == 0) {
    s.port = s.http.bind_to_any_port(s.options.host);
    if (s.port <= 0) return "cannot listen on " + s.options.host + " (is it an address of this machine?)";
  } else {
    if (!s.http.bind_to_port(s.options.host, s.options.port))
      return fmt::format("cannot listen on {} port {} (is the port taken, or the address not "
                         "this machine's?)",
                         s.options.host, s.options.port);
    s.port = s.options.port;
  }
  return {};
}

bool WebServer::run() {
  Impl& s = *impl_;
  s.listening_phase = true;
  const bool ok = s.stop_requested ? true : s.http.listen_after_bind();
  s.listening_phase = false;
  return ok;
}

void WebServer::stop() {
  Impl& s = *impl_;
  s.stop_requested = true;
  // A stop that comes just as run() begins waits for the server to be listening, so it
  // is not lost.
  while (s.listening_phase && !s.http.is_running())
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  s.http.stop();
}

int WebServer::port() const { return impl_->port; }

std::string WebServer::url() const {
  std::string host = impl_->options.host;
  if (host == "0.0.0.0" || host == "::") host = "localhost";
  if (host.find(':') != std::string::npos) host = "[" + host + "]";
  return "http://" + host + ":" + std::to_string(impl_->port) + "/";
}

int WebServer::workers() const { return impl_->slots.size(); }

ImpactTableStore& WebServer::tables() { return impl_->tables; }

}  // namespace cueplan::cli
