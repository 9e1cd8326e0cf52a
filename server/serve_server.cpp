#include "serve_server.hpp"

#include <arpa/inet.h>
#include <httplib.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <exception>
#include <map>
#include <mutex>
#include <string_view>
#include <thread>
#include <utility>

#include "cueplan/physics/parallel.hpp"
#include "serve_assets.hpp"

namespace cueplan::server {
using namespace cueplan::api;  // the api's types and checks, as the server's own
namespace {

using nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

// Connection threads besides those of the workers and the queue: a browser keeps up to
// six connections open, and the page, /api/health and /api/examples must answer while
// every worker computes and the queue is full.
constexpr int kSpareConnections = 32;
constexpr int kListenBacklog = 128;
constexpr time_t kKeepAliveSeconds = 3;
constexpr time_t kSocketTimeoutSeconds = 10;
constexpr int kRetryWhenRefused = 1;  // s, a connection over its address's limit
// A refused request's unread body is drained (not kept) this long at most before the
// connection closes, so that the client reads the refusal instead of a reset.
constexpr auto kDrainTime = std::chrono::milliseconds(500);
constexpr size_t kDrainBytes = 4u << 20;

enum Endpoint { kSolve, kSimulate, kSpinmap, kRun, kEndpoints };
// First guesses of one request's computing time (s), before any has been measured.
constexpr double kFirstEstimate[kEndpoints] = {0.5, 0.05, 2.0, 5.0};

// The workers and the first-come queue in front of them. A request runs at once when a
// worker is free and nobody waits; otherwise it joins the queue, unless the queue is full
// or its expected wait (the estimated computing time of everything queued and half that
// of everything running, over the workers) exceeds the budget. A queued request waits
// at most the budget.
class SolveQueue {
 public:
  enum class Verdict { run, full, too_long, timed_out, stopping };
  struct Ticket {
    Verdict verdict = Verdict::run;
    double expected_wait_s = 0.0;
    double waited_s = 0.0;
    int retry_after_s = 1;
    double estimate_s = 0.0;  // give back to leave()
  };

  SolveQueue(int workers, int capacity, double budget_s)
      : workers_(workers), capacity_(capacity), budget_s_(budget_s) {
    std::copy(std::begin(kFirstEstimate), std::end(kFirstEstimate), estimate_);
  }

  Ticket enter(Endpoint endpoint) {
    const Clock::time_point arrived = Clock::now();
    std::unique_lock<std::mutex> lock(mutex_);
    Ticket t;
    t.estimate_s = estimate_[endpoint];
    if (stopping_) return refuse(t, Verdict::stopping, 1.0);
    if (busy_ < workers_ && waiting_.empty()) {
      ++busy_;
      running_s_ += t.estimate_s;
      return t;
    }
    t.expected_wait_s = (queued_s_ + t.estimate_s + 0.5 * running_s_) / workers_;
    if (static_cast<int>(waiting_.size()) >= capacity_)
      return refuse(t, Verdict::full, t.expected_wait_s);
    if (t.expected_wait_s > budget_s_)
      return refuse(t, Verdict::too_long, t.expected_wait_s - budget_s_);
    Waiter me{t.estimate_s};
    waiting_.push_back(&me);
    queued_s_ += t.estimate_s;
    const auto deadline = arrived + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(budget_s_));
    changed_.wait_until(lock, deadline, [&] { return me.granted || stopping_; });
    t.waited_s = std::chrono::duration<double>(Clock::now() - arrived).count();
    if (me.granted) return t;
    waiting_.erase(std::find(waiting_.begin(), waiting_.end(), &me));
    queued_s_ -= t.estimate_s;
    return refuse(t, stopping_ ? Verdict::stopping : Verdict::timed_out, 1.0);
  }

  // A request that ran: its worker goes to the first in the queue, or is free.
  void leave(Endpoint endpoint, const Ticket& t, double computed_s) {
    std::lock_guard<std::mutex> lock(mutex_);
    running_s_ -= t.estimate_s;
    estimate_[endpoint] = 0.8 * estimate_[endpoint] + 0.2 * computed_s;
    if (waiting_.empty()) {
      --busy_;
      return;
    }
    Waiter* next = waiting_.front();
    waiting_.pop_front();
    queued_s_ -= next->estimate_s;
    running_s_ += next->estimate_s;
    next->granted = true;
    changed_.notify_all();
  }

  // Every waiting request is refused; new ones too.
  void stop() {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    changed_.notify_all();
  }

  int busy() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return busy_;
  }
  int queued() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return static_cast<int>(waiting_.size());
  }
  int workers() const { return workers_; }
  int capacity() const { return capacity_; }
  double budget_s() const { return budget_s_; }

 private:
  struct Waiter {
    double estimate_s;
    bool granted = false;
  };
  static Ticket refuse(Ticket t, Verdict why, double retry_s) {
    t.verdict = why;
    t.retry_after_s = std::clamp(static_cast<int>(std::ceil(retry_s)), 1, 3600);
    return t;
  }

  const int workers_;
  const int capacity_;
  const double budget_s_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Waiter*> waiting_;
  int busy_ = 0;
  double queued_s_ = 0.0;   // estimated computing time of the queue
  double running_s_ = 0.0;  // estimated computing time of the running requests
  double estimate_[kEndpoints];
  bool stopping_ = false;
};

// Open connections per client address.
class ClientCounts {
 public:
  explicit ClientCounts(int limit) : limit_(limit) {}
  bool take(const std::string& address) {
    std::lock_guard<std::mutex> lock(mutex_);
    int& n = open_[address];
    if (limit_ > 0 && n >= limit_) {
      if (n == 0) open_.erase(address);
      return false;
    }
    ++n;
    return true;
  }
  void give_back(const std::string& address) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (--open_[address] <= 0) open_.erase(address);
  }
  int limit() const { return limit_; }

 private:
  const int limit_;
  std::mutex mutex_;
  std::map<std::string, int> open_;
};

std::string reason_phrase(int status) {
  switch (status) {
    case 408: return "Request Timeout";
    case 413: return "Payload Too Large";
    case 431: return "Request Header Fields Too Large";
    case 503: return "Service Unavailable";
    default: return "Error";
  }
}

// A connection's socket as httplib reads and writes requests through it, with the
// guards httplib's own stream lacks: one deadline for a request's headers and body
// together (a byte now and then does not keep a request alive), and limits on the bytes
// of the headers and of the body as they arrive, chunked or not. Past any of them the
// stream answers the request itself (408, 431, 413, with Connection: close) and reads
// and writes nothing more. It lives as long as the connection, so bytes of a next
// request read ahead are kept.
class GuardedStream final : public httplib::Stream {
 public:
  struct Limits {
    std::chrono::milliseconds deadline;
    std::chrono::milliseconds read_timeout;
    size_t header_bytes;
    size_t body_bytes;  // raw, with chunk framing
    size_t max_body;    // as the client is told
  };

  GuardedStream(socket_t sock, Limits limits) : sock_(sock), limits_(limits) {}

  // Waits up to `idle` for a next request (false: none came, or the server stops).
  bool wait_for_request(std::chrono::milliseconds idle, const std::atomic<socket_t>& server) {
    if (dead_) return false;
    if (start_ < end_) return true;
    const Clock::time_point until = Clock::now() + idle;
    while (server != INVALID_SOCKET) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now());
      if (left.count() <= 0) return false;
      pollfd p{sock_, POLLIN, 0};
      const int ready = ::poll(&p, 1, static_cast<int>(std::min<long>(left.count(), 100)));
      if (ready < 0 && errno != EINTR) return false;
      if (ready > 0) return true;
    }
    return false;
  }

  // A request begins: its deadline starts now.
  void begin_request() {
    deadline_ = Clock::now() + limits_.deadline;
    in_body_ = false;
    counted_ = 0;
  }
  // Its headers are read; its body begins.
  void begin_body() {
    in_body_ = true;
    counted_ = 0;
  }
  // True once the connection is to close: a refusal, or a response that said so.
  bool closing() const { return dead_ || close_after_; }
  bool refused() const { return refused_; }

  // Answers the request with `status` and a JSON error, and ends the connection.
  void refuse(int status, const std::string& message, int retry_after_s = 0) {
    if (dead_) return;
    const std::string body =
        ordered_json({{"error", message}, {"field", nullptr}}).dump();
    std::string head = fmt::format(
        "HTTP/1.1 {} {}\r\nContent-Type: application/json\r\nContent-Length: {}\r\n"
        "Connection: close\r\nCache-Control: no-store\r\nX-Content-Type-Options: nosniff\r\n",
        status, reason_phrase(status), body.size());
    if (retry_after_s > 0) head += fmt::format("Retry-After: {}\r\n", retry_after_s);
    head += "\r\n" + body;
    send_all(head.data(), head.size());
    dead_ = true;
    refused_ = true;
  }

  bool is_readable() const override {
    if (dead_) return false;
    if (start_ < end_) return true;
    pollfd p{sock_, POLLIN, 0};
    return ::poll(&p, 1, 0) > 0;
  }
  bool is_writable() const override {
    if (dead_) return false;
    pollfd p{sock_, POLLOUT, 0};
    return ::poll(&p, 1, static_cast<int>(limits_.read_timeout.count())) > 0;
  }

  ssize_t read(char* ptr, size_t size) override {
    if (dead_) return -1;
    if (start_ == end_) {
      if (!fill()) return -1;
      if (start_ == end_) return 0;  // the client closed
    }
    const size_t n = std::min(size, end_ - start_);
    std::copy(buffer_ + start_, buffer_ + start_ + n, ptr);
    start_ += n;
    counted_ += n;
    if (!in_body_ && counted_ > limits_.header_bytes) {
      refuse(431, fmt::format("the request's headers are larger than this server takes ({} "
                              "bytes)",
                              limits_.header_bytes));
      return -1;
    }
    if (in_body_ && counted_ > limits_.body_bytes) {
      refuse(413, fmt::format("the request body is larger than this server takes ({} bytes)",
                              limits_.max_body));
      return -1;
    }
    return static_cast<ssize_t>(n);
  }

  ssize_t write(const char* ptr, size_t size) override {
    if (dead_) return -1;
    const std::string_view text(ptr, size);
    if (text.rfind("HTTP/1.1 ", 0) == 0 && text.find("\r\nConnection: close\r\n") != text.npos)
      close_after_ = true;
    const ssize_t n = ::send(sock_, ptr, size, MSG_NOSIGNAL);
    return n;
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    address_of(&::getpeername, ip, port);
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    address_of(&::getsockname, ip, port);
  }
  socket_t socket() const override { return sock_; }

  // Reads and drops what the client still sends, briefly, then the caller closes: the
  // client then reads the answer rather than a reset.
  void drain() {
    ::shutdown(sock_, SHUT_WR);
    const Clock::time_point until = Clock::now() + kDrainTime;
    char scratch[16384];
    for (size_t total = 0; total < kDrainBytes;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now());
      if (left.count() <= 0) return;
      pollfd p{sock_, POLLIN, 0};
      if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) return;
      const ssize_t n = ::recv(sock_, scratch, sizeof scratch, 0);
      if (n <= 0) return;
      total += static_cast<size_t>(n);
    }
  }

 private:
  using AddressOf = int (*)(int, sockaddr*, socklen_t*);
  void address_of(AddressOf get, std::string& ip, int& port) const {
    sockaddr_storage a{};
    socklen_t len = sizeof a;
    ip.clear();
    port = 0;
    if (get(sock_, reinterpret_cast<sockaddr*>(&a), &len) != 0) return;
    char text[INET6_ADDRSTRLEN] = {};
    if (a.ss_family == AF_INET) {
      const auto* v4 = reinterpret_cast<const sockaddr_in*>(&a);
      ::inet_ntop(AF_INET, &v4->sin_addr, text, sizeof text);
      port = ntohs(v4->sin_port);
    } else if (a.ss_family == AF_INET6) {
      const auto* v6 = reinterpret_cast<const sockaddr_in6*>(&a);
      ::inet_ntop(AF_INET6, &v6->sin6_addr, text, sizeof text);
      port = ntohs(v6->sin6_port);
    }
    ip = text;
  }

  // Reads what has arrived, waiting no longer than the request's deadline allows.
  bool fill() {
    for (;;) {
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline_ - Clock::now());
      if (left.count() <= 0) {
        refuse(408, fmt::format("the request did not arrive in time: its headers and body must "
                                "arrive within {} s",
                                static_cast<double>(limits_.deadline.count()) / 1000.0));
        return false;
      }
      pollfd p{sock_, POLLIN, 0};
      const int ready =
          ::poll(&p, 1, static_cast<int>(std::min(left, limits_.read_timeout).count()));
      if (ready < 0 && errno == EINTR) continue;
      if (ready < 0) return false;
      if (ready == 0) {
        if (left <= limits_.read_timeout) continue;  // the deadline answers
        refuse(408, "the request stalled: nothing arrived for " +
                        std::to_string(limits_.read_timeout.count() / 1000) + " s");
        return false;
      }
      const ssize_t n = ::recv(sock_, buffer_, sizeof buffer_, 0);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) return false;
      start_ = 0;
      end_ = static_cast<size_t>(n);
      return true;
    }
  }

  void send_all(const char* data, size_t size) {
    while (size > 0) {
      const ssize_t n = ::send(sock_, data, size, MSG_NOSIGNAL);
      if (n <= 0) return;
      data += n;
      size -= static_cast<size_t>(n);
    }
  }

  socket_t sock_;
  Limits limits_;
  Clock::time_point deadline_ = Clock::now();
  char buffer_[4096];
  size_t start_ = 0, end_ = 0;
  size_t counted_ = 0;
  bool in_body_ = false;
  bool dead_ = false;
  bool refused_ = false;
  bool close_after_ = false;
};

// httplib's server with each connection served through a GuardedStream, and a bounded
// number of connections per client address.
class GuardedServer final : public httplib::Server {
 public:
  GuardedServer(GuardedStream::Limits limits, int client_connections)
      : limits_(limits), clients_(client_connections) {}

  // Raises the listen backlog (httplib listens with 5) once the socket is bound.
  bool raise_backlog() { return ::listen(svr_sock_, kListenBacklog) == 0; }

 private:
  bool process_and_close_socket(socket_t sock) override {
    GuardedStream strm(sock, limits_);
    std::string peer;
    int peer_port = 0;
    strm.get_remote_ip_and_port(peer, peer_port);
    bool ret = false;
    if (!clients_.take(peer)) {
      strm.refuse(503,
                  fmt::format("too many connections from {}: this server takes {} at once from "
                              "one address",
                              peer, clients_.limit()),
                  kRetryWhenRefused);
    } else {
      for (size_t left = keep_alive_max_count_; left > 0; --left) {
        if (!strm.wait_for_request(std::chrono::seconds(keep_alive_timeout_sec_), svr_sock_))
          break;
        strm.begin_request();
        bool connection_closed = false;
        ret = process_request(strm, left == 1, connection_closed,
                              [&strm](httplib::Request&) { strm.begin_body(); });
        if (!ret || connection_closed || strm.closing()) break;
      }
      clients_.give_back(peer);
    }
    if (strm.closing()) strm.drain();
    ::shutdown(sock, SHUT_RDWR);
    ::close(sock);
    return ret;
  }

  GuardedStream::Limits limits_;
  ClientCounts clients_;
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
    case 408: return "the request did not arrive in time";
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

namespace {

// The methods each known path answers; empty for a path the server does not know.
const char* allowed_methods(const std::string& path) {
  if (path == "/api/health" || path == "/api/examples") return "GET, HEAD";
  if (path == "/api/solve" || path == "/api/simulate" || path == "/api/spinmap" || path == "/api/run")
    return "POST";
  if (path == "/") return "GET, HEAD";
  for (const EmbeddedFile& f : web_assets())
    if (path.size() > 1 && f.name == std::string_view(path).substr(1)) return "GET, HEAD";
  return "";
}

bool allows(std::string_view allowed, const std::string& method) {
  for (size_t at = 0; at < allowed.size();) {
    const size_t comma = std::min(allowed.find(',', at), allowed.size());
    if (allowed.substr(at, comma - at) == method) return true;
    at = comma + 2;
  }
  return false;
}

// A refusal sent before the body is read: the connection closes after it.
httplib::Server::HandlerResponse refuse_early(httplib::Response& res, const ApiReply& reply) {
  send(res, reply);
  res.set_header("Connection", "close");
  return httplib::Server::HandlerResponse::Handled;
}

}  // namespace

struct WebServer::Impl {
  explicit Impl(ServerOptions o)
      : options(std::move(o)),
        queue(static_cast<int>(physics::thread_count(options.workers)), std::max(options.queue, 0),
              options.wait_budget_s),
        tables(options.tables),
        api(options.limits, options.default_method, &tables, shipped_examples(&examples_error)),
        http(GuardedStream::Limits{
                 std::chrono::milliseconds(
                     static_cast<long>(std::llround(options.request_deadline_s * 1000.0))),
                 std::chrono::milliseconds(kSocketTimeoutSeconds * 1000),
                 options.max_header_bytes,
                 // Chunk framing on top of the body: a chunk-size line per chunk.
                 options.max_body_bytes + options.max_body_bytes / 4 + 4096,
                 options.max_body_bytes},
             options.client_connections) {}

  void log(const std::string& line) const {
    if (options.log) options.log(line);
  }

  // A POST endpoint that computes: it reads the body (at most max_body_bytes, counted as
  // it arrives), then waits its turn for a worker, or is answered 503 when it cannot.
  httplib::Server::HandlerWithContentReader compute(
      Endpoint which, ApiReply (Api::*endpoint)(std::string_view) const) {
    return [this, which, endpoint](const httplib::Request&, httplib::Response& res,
                                   const httplib::ContentReader& read) {
      std::string body;
      bool too_large = false;
      const bool complete = read([&](const char* data, size_t size) {
        if (body.size() + size > options.max_body_bytes) {
          too_large = true;
          return false;
        }
        body.append(data, size);
        return true;
      });
      if (too_large || res.status == 413) {
        send(res, error_reply(413, reason_of(413, options.max_body_bytes)));
        res.set_header("Connection", "close");
        return;
      }
      if (!complete) {
        send(res, error_reply(400, "the request body could not be read"));
        res.set_header("Connection", "close");
        return;
      }

      const SolveQueue::Ticket ticket = queue.enter(which);
      if (ticket.verdict != SolveQueue::Verdict::run) {
        std::string why;
        switch (ticket.verdict) {
          case SolveQueue::Verdict::full:
            why = fmt::format("the server is busy: its queue of {} requests is full", queue.capacity());
            break;
          case SolveQueue::Verdict::too_long:
            why = fmt::format("the server is busy: the expected wait, {:.1f} s, exceeds its wait "
                              "budget of {:g} s",
                              ticket.expected_wait_s, queue.budget_s());
            break;
          case SolveQueue::Verdict::timed_out:
            why = fmt::format("the server is busy: no worker came free within its wait budget "
                              "of {:g} s",
                              queue.budget_s());
            break;
          default: why = "the server is stopping"; break;
        }
        ApiReply busy = error_reply(503, why + fmt::format("; ask again in {} s", ticket.retry_after_s));
        busy.retry_after_s = ticket.retry_after_s;
        busy.body["retry_after_s"] = ticket.retry_after_s;
        send(res, busy);
        return;
      }
      const Clock::time_point started = Clock::now();
      struct Leave {
        SolveQueue& q;
        Endpoint which;
        const SolveQueue::Ticket& t;
        Clock::time_point started;
        ~Leave() {
          q.leave(which, t, std::chrono::duration<double>(Clock::now() - started).count());
        }
      } leave{queue, which, ticket, started};
      send(res, (api.*endpoint)(body));
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - started).count();
      res.set_header("Server-Timing", fmt::format("compute;dur={:.1f}, queue;dur={:.1f}", ms,
                                                  ticket.waited_s * 1000.0));
    };
  }

  void routes() {
    using httplib::Request;
    using httplib::Response;
    http.Get("/api/health", [this](const Request&, Response& res) {
      ApiReply reply = api.health(queue.workers(), queue.busy());
      reply.body["queued"] = queue.queued();
      reply.body["limits"]["queue"] = queue.capacity();
      reply.body["limits"]["wait_budget_s"] = queue.budget_s();
      reply.body["limits"]["request_deadline_s"] = options.request_deadline_s;
      reply.body["limits"]["client_connections"] = options.client_connections;
      reply.body["limits"]["max_body_bytes"] = options.max_body_bytes;
      send(res, reply);
    });
    http.Get("/api/examples", [this](const Request&, Response& res) { send(res, api.examples()); });
    http.Post("/api/solve", compute(kSolve, &Api::solve));
    http.Post("/api/simulate", compute(kSimulate, &Api::simulate));
    http.Post("/api/spinmap", compute(kSpinmap, &Api::spinmap));
    http.Post("/api/run", compute(kRun, &Api::run));
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
      if (is_loopback(options.host) && !is_loopback(host_name(req.get_header_value("Host"))))
        return refuse_early(res, error_reply(403, "this server answers only requests addressed "
                                                  "to localhost or 127.0.0.1 (Host: " +
                                                      req.get_header_value("Host") + ")"));
      // A known path asked with a method it does not answer: 405 and what it does.
      if (const std::string allowed = allowed_methods(req.path); !allowed.empty()) {
        if (req.method == "OPTIONS") {
          res.status = 204;
          res.set_header("Allow", allowed + ", OPTIONS");
          res.set_header("Connection", "close");
          return httplib::Server::HandlerResponse::Handled;
        }
        if (!allows(allowed, req.method)) {
          res.set_header("Allow", allowed + ", OPTIONS");
          return refuse_early(res, error_reply(405, req.method + " is not answered at " +
                                                        req.path + "; use " + allowed));
        }
      }
      // POSTs carry JSON: a form on another site cannot send that without asking first.
      if (req.method == "POST" &&
          req.get_header_value("Content-Type").rfind("application/json", 0) != 0)
        return refuse_early(res, error_reply(415, "POST requests must be JSON, with "
                                                  "Content-Type: application/json"));
      // A body announced larger than the limit is refused before it is read.
      if (req.has_header("Content-Length")) {
        const std::string length = req.get_header_value("Content-Length");
        const bool digits = !length.empty() && length.size() <= 18 &&
                            std::all_of(length.begin(), length.end(),
                                        [](char c) { return c >= '0' && c <= '9'; });
        if (!digits)
          return refuse_early(res, error_reply(400, "Content-Length must be a whole number of "
                                                    "bytes, got '" + length + "'"));
        if (std::stoull(length) > options.max_body_bytes)
          return refuse_early(res, error_reply(413, reason_of(413, options.max_body_bytes)));
      }
      return httplib::Server::HandlerResponse::Unhandled;
    });
    // A response that closes its connection does not also offer to keep it alive.
    http.set_post_routing_handler([](const Request&, Response& res) {
      if (res.get_header_value("Connection") == "close") res.headers.erase("Keep-Alive");
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
      std::string ms;
      if (const size_t at = timing.find("dur="); at != std::string::npos)
        ms = " (" + timing.substr(at + 4, timing.find(',', at) - at - 4) + " ms)";
      log(req.method + " " + req.path + " " + std::to_string(res.status) + ms);
    });
  }

  int connection_threads() const { return queue.workers() + queue.capacity() + kSpareConnections; }

  ServerOptions options;
  SolveQueue queue;
  ImpactTableStore tables;
  std::string examples_error;  // set by shipped_examples, before `api` (declared after it)
  Api api;
  GuardedServer http;
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
  const int connections = s.connection_threads();
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
  if (!s.http.raise_backlog())
    return fmt::format("cannot listen on {} port {} with a backlog of {}", s.options.host, s.port,
                       kListenBacklog);
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
  s.queue.stop();
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

int WebServer::workers() const { return impl_->queue.workers(); }

int WebServer::connection_threads() const { return impl_->connection_threads(); }

ImpactTableStore& WebServer::tables() { return impl_->tables; }

}  // namespace cueplan::server
