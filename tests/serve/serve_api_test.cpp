// Tests of `cueplan serve`'s API against a server started inside the test on a free
// port (port 0), over HTTP with cpp-httplib's client: every endpoint, its answers held
// against the command line's `--json` for the same problem and options, bad input
// answered 400 with the field named (numeric extremes too), oversize bodies 413 (chunked
// ones while they are read), the queue in front of the workers and its 503s, sixteen and
// sixty-four concurrent solves, slow and greedy clients, wrong methods; and the command
// itself as a process: its address, Ctrl-C. Everything runs on loopback.
#include <gtest/gtest.h>
#include <httplib.h>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <iostream>
#include <cmath>
#include <filesystem>
#include <functional>
#include <latch>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "cli/cli_test_support.hpp"
#include "cueplan/problems/problem.hpp"
#include "serve_api.hpp"
#include "serve_problems.hpp"
#include "serve_server.hpp"
#include "serve_tables.hpp"
#include "support/physics_checks.hpp"

extern char** environ;

namespace cli_test {

const char* const kScratchName = "cueplan_serve_test_";

namespace {

namespace fs = std::filesystem;
namespace prob = cueplan::problems;
using cueplan::server::Api;
using cueplan::server::ApiReply;
using cueplan::server::ImpactTableStore;
using cueplan::server::ServerOptions;
using cueplan::server::WebServer;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

// ---------------------------------------------------------------------------
// A server inside the test

// Serves on a free loopback port from its own thread until destroyed.
class TestServer {
 public:
  explicit TestServer(ServerOptions options = defaults()) : server_(std::move(options)) {
    const std::string why = server_.bind();
    EXPECT_EQ(why, "");
    thread_ = std::thread([this] { server_.run(); });
  }
  ~TestServer() {
    server_.stop();
    thread_.join();
  }
  // Exact impacts (no table to wait for), a scratch table cache, two workers.
  static ServerOptions defaults() {
    ServerOptions o;
    o.port = 0;
    o.workers = 2;
    o.default_method = "exact";
    o.tables.cache_dir = (scratch() / "cache").string();
    o.tables.options = cueplan::physics::test::tiny_table_options();
    return o;
  }
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", server_.port());
    c.set_read_timeout(120);
    c.set_connection_timeout(10);
    return c;
  }
  int port() const { return server_.port(); }
  WebServer& server() { return server_; }

 private:
  WebServer server_;
  std::thread thread_;
};

struct Answer {
  int status = 0;
  json body;
  std::string raw;
  std::string retry_after;
};

Answer answer_of(const httplib::Result& r) {
  Answer a;
  if (!r) {
    ADD_FAILURE() << "no answer: " << httplib::to_string(r.error());
    return a;
  }
  a.status = r->status;
  a.raw = r->body;
  a.retry_after = r->get_header_value("Retry-After");
  a.body = json::parse(r->body, nullptr, false);
  return a;
}

Answer post(const TestServer& server, const std::string& path, const std::string& body,
            const std::string& type = "application/json") {
  httplib::Client c = server.client();
  return answer_of(c.Post(path, body, type));
}
Answer post(const TestServer& server, const std::string& path, const json& body) {
  return post(server, path, body.dump());
}
Answer get(const TestServer& server, const std::string& path) {
  httplib::Client c = server.client();
  return answer_of(c.Get(path));
}

// A shipped problem as /api/examples gives it.
json example_problem(const TestServer& server, const std::string& file) {
  const Answer a = get(server, "/api/examples");
  for (const json& e : a.body["examples"])
    if (e["file"] == file) return e["problem"];
  ADD_FAILURE() << "no example " << file;
  return json::object();
}

// The command line's --json for the same work, with what depends on where and when it
// ran taken out: the time, the problem's source (a path or "request"), the picture.
json comparable(json j) {
  for (const char* key : {"time_s", "out", "format"}) j.erase(key);
  if (j.contains("problem")) j["problem"].erase("source");
  return j;
}

json cli_json(const std::string& args, const std::string& tag) {
  const ProcessResult run = cueplan(args, tag);
  EXPECT_LE(run.exit_code, 1) << args << "\n" << run.err;
  json j = json::parse(run.out, nullptr, false);
  EXPECT_FALSE(j.is_discarded()) << run.out << run.err;
  return j;
}

// A quick, reproducible search, as the request's options and as the command's flags.
json quick_options(uint64_t seed) {
  return {{"method", "exact"},
          {"max_evaluations", 1500},
          {"samples", 50},
          {"alternatives", 3},
          {"seed", seed}};
}
std::string quick_flags(uint64_t seed) {
  return "--method exact --max-evaluations 1500 --samples 50 --alternatives 3 --seed " +
         std::to_string(seed);
}

void expect_error(const Answer& a, int status, const std::optional<std::string>& field,
                  const std::string& words) {
  EXPECT_EQ(a.status, status) << a.raw;
  ASSERT_TRUE(a.body.is_object()) << a.raw;
  ASSERT_TRUE(a.body.contains("error")) << a.raw;
  if (field)
    EXPECT_EQ(a.body["field"], *field) << a.raw;
  else
    EXPECT_TRUE(a.body["field"].is_null()) << a.raw;
  EXPECT_NE(a.body["error"].get<std::string>().find(words), std::string::npos) << a.raw;
}

const json kSmallProblem = {{"cue_ball", {0.8, 0.5}}, {"target", {2.6, 1.2}}};

// Two problems hold the same numbers (both read from the same decimal text, so exactly).
void expect_same_problem(const prob::Problem& a, const prob::Problem& b) {
  const cueplan::physics::Scene &s = a.scene, &t = b.scene;
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(s.length, t.length);
  EXPECT_EQ(s.width, t.width);
  const cueplan::physics::CushionParams &p = s.ball_and_cushion, &q = t.ball_and_cushion;
  for (auto [x, y] : {std::pair{p.mass, q.mass}, {p.radius, q.radius}, {p.cushion_height, q.cushion_height},
                      {p.mu_cushion, q.mu_cushion}, {p.mu_table, q.mu_table},
                      {p.restitution, q.restitution}, {s.cloth.mu_slide, t.cloth.mu_slide},
                      {s.cloth.mu_roll, t.cloth.mu_roll}, {s.cloth.mu_spin, t.cloth.mu_spin},
                      {s.cloth.gravity, t.cloth.gravity}, {a.cue_ball.x, b.cue_ball.x},
                      {a.cue_ball.y, b.cue_ball.y}, {a.target.x, b.target.x}, {a.target.y, b.target.y},
                      {a.tolerance, b.tolerance}, {a.limits.speed_min, b.limits.speed_min},
                      {a.limits.speed_max, b.limits.speed_max}, {a.limits.spin_max, b.limits.spin_max},
                      {a.limits.aim.lo_deg, b.limits.aim.lo_deg}, {a.limits.aim.hi_deg, b.limits.aim.hi_deg}})
    EXPECT_EQ(x, y);
  EXPECT_EQ(a.limits.aim.mode, b.limits.aim.mode);
  EXPECT_EQ(a.limits.cushions_min, b.limits.cushions_min);
  EXPECT_EQ(a.limits.cushions_max, b.limits.cushions_max);
  ASSERT_EQ(s.pockets.size(), t.pockets.size());
  for (size_t i = 0; i < s.pockets.size(); ++i) {
    EXPECT_EQ(s.pockets[i].centre.x, t.pockets[i].centre.x);
    EXPECT_EQ(s.pockets[i].centre.y, t.pockets[i].centre.y);
    EXPECT_EQ(s.pockets[i].radius, t.pockets[i].radius);
  }
  ASSERT_EQ(s.obstacles.size(), t.obstacles.size());
  for (size_t i = 0; i < s.obstacles.size(); ++i) {
    EXPECT_EQ(s.obstacles[i].x, t.obstacles[i].x);
    EXPECT_EQ(s.obstacles[i].y, t.obstacles[i].y);
  }
  ASSERT_EQ(s.balls.size(), t.balls.size());
  for (size_t i = 0; i < s.balls.size(); ++i) {
    EXPECT_EQ(s.balls[i].name, t.balls[i].name);
    EXPECT_EQ(s.balls[i].position.x, t.balls[i].position.x);
    EXPECT_EQ(s.balls[i].position.y, t.balls[i].position.y);
  }
  EXPECT_EQ(a.pot.has_value(), b.pot.has_value());
  if (a.pot && b.pot) {
    EXPECT_EQ(a.pot->ball, b.pot->ball);
    EXPECT_EQ(a.pot->pocket, b.pot->pocket);
  }
  EXPECT_EQ(a.first_contact, b.first_contact);
  EXPECT_EQ(a.max_strokes, b.max_strokes);
  EXPECT_EQ(a.time_budget_s, b.time_budget_s);
}

// ---------------------------------------------------------------------------
// Endpoints

TEST(ServeHealth, SaysTheServerIsUpWithItsWorkersAndLimits) {
  TestServer server;
  const Answer a = get(server, "/api/health");
  ASSERT_EQ(a.status, 200) << a.raw;
  EXPECT_EQ(a.body["status"], "ok");
  EXPECT_EQ(a.body["workers"], 2);
  EXPECT_EQ(a.body["busy"], 0);
  EXPECT_EQ(a.body["default_method"], "exact");
  EXPECT_EQ(a.body["impact_tables_ready"], true);
  EXPECT_EQ(a.body["limits"]["max_body_bytes"], 256 * 1024);
  EXPECT_EQ(a.body["limits"]["max_grid"], 61);
}

TEST(ServeExamples, AreTheShippedProblemsAndLoadAsTheirFilesDo) {
  TestServer server;
  const Answer a = get(server, "/api/examples");
  ASSERT_EQ(a.status, 200);
  std::vector<std::string> files;
  for (const char* dir : {"", "pots"})
    for (const auto& entry : fs::directory_iterator(fs::path(CUEPLAN_PROBLEMS_DIR) / dir))
      if (entry.path().extension() == ".yaml")
        files.push_back((fs::path(dir) / entry.path().filename()).string());
  ASSERT_EQ(a.body["examples"].size(), files.size());
  // Read in the reply's order, as the page does: the order of object balls is theirs
  // on the table (it numbers them for the simulator's tie order).
  const nlohmann::ordered_json in_order = nlohmann::ordered_json::parse(a.raw);
  size_t index = 0;
  for (const json& e : a.body["examples"]) {
    const std::string file = e["file"];
    SCOPED_TRACE(file);
    const nlohmann::ordered_json& problem_fields = in_order["examples"][index++]["problem"];
    // The JSON problem, read as a request's, is the file's problem field for field.
    EXPECT_NE(std::find(files.begin(), files.end(), file), files.end());
    const prob::LoadResult from_file =
        prob::load_problem((fs::path(CUEPLAN_PROBLEMS_DIR) / file).string());
    ASSERT_TRUE(from_file.ok()) << from_file.error;
    const cueplan::server::ProblemFromJson from_json =
        cueplan::server::problem_from_json(problem_fields, "problem");
    ASSERT_TRUE(from_json.problem) << from_json.error.message;
    expect_same_problem(*from_json.problem, *from_file.problem);
    EXPECT_EQ(e["name"], from_file.problem->name);
    // The scene to draw is the loaded problem's.
    const prob::Problem& p = *from_file.problem;
    EXPECT_DOUBLE_EQ(e["scene"]["length"].get<double>(), p.scene.length);
    EXPECT_DOUBLE_EQ(e["scene"]["width"].get<double>(), p.scene.width);
    EXPECT_DOUBLE_EQ(e["scene"]["ball_radius"].get<double>(), p.scene.radius());
    EXPECT_EQ(e["scene"]["pockets"].size(), p.scene.pockets.size());
    EXPECT_DOUBLE_EQ(e["scene"]["cue_ball"][0].get<double>(), p.cue_ball.x);
    EXPECT_DOUBLE_EQ(e["scene"]["target"][1].get<double>(), p.target.y);
    EXPECT_DOUBLE_EQ(e["scene"]["tolerance"].get<double>(), p.tolerance);
    EXPECT_EQ(e["scene"]["limits"]["cushions"][0], p.limits.cushions_min);
    const std::string kind = e["scene"]["kind"];
    EXPECT_EQ(kind, p.scene.pockets.empty() ? "carom" : p.scene.length > 3.0 ? "snooker" : "pool");
  }
}

TEST(ServeSolve, AnswersAsTheCommandLineDoes) {
  TestServer server;
  const json problem = example_problem(server, "one_rail_position.yaml");
  const Answer a = post(server, "/api/solve", json{{"problem", problem}, {"options", quick_options(3)}});
  ASSERT_EQ(a.status, 200) << a.raw;
  EXPECT_EQ(a.body["status"], "solved");
  const json cli = cli_json("solve '" + problem_path("one_rail_position") + "' " + quick_flags(3) +
                                " --json",
                            "");
  EXPECT_EQ(comparable(a.body), comparable(cli));
  EXPECT_EQ(a.body["problem"]["source"], "request");
}

TEST(ServeSolve, PositionPlayAlsoGivesTheNextPotsFieldAsTheZoneCommandHasIt) {
  TestServer server;
  const json problem = example_problem(server, "pots/red_then_black.yaml");
  const Answer a = post(server, "/api/solve", json{{"problem", problem}, {"options", quick_options(3)}});
  ASSERT_EQ(a.status, 200) << a.raw;
  ASSERT_TRUE(a.body.contains("zone")) << a.raw.substr(0, 400);
  const json& z = a.body["zone"];
  EXPECT_EQ(z["ball"], "black");
  EXPECT_EQ(z["pocket"], "bottom_right");
  const int columns = z["columns"], rows = z["rows"];
  const double cell = z["cell"];
  ASSERT_EQ(z["values"].size(), static_cast<size_t>(columns) * rows);
  // The grid covers the cloth (3.569 x 1.778 m) in its cells.
  EXPECT_NEAR(columns * cell, 3.569, cell);
  EXPECT_NEAR(rows * cell, 1.778, cell);
  // The zone is where the value is within 10 points of the best, its area the cells'; the
  // best, the area and where it is are `cueplan zone`'s, and the plan's own report.
  const double threshold = z["threshold"], best = z["best_p"];
  EXPECT_NEAR(threshold, best - 0.1, 1e-12);
  int inside = 0;
  double largest = 0.0;
  for (const json& v : z["values"]) {
    const double value = v;
    ASSERT_GE(value, 0.0);
    ASSERT_LE(value, 1.0);
    largest = std::max(largest, value);
    inside += value >= threshold - 5e-4;  // the values are rounded to 0.001
  }
  EXPECT_NEAR(largest, best, 5e-4);
  EXPECT_NEAR(inside * cell * cell, z["area_m2"].get<double>(), 0.05 * z["area_m2"].get<double>());
  EXPECT_EQ(z["area_m2"], a.body["next"]["zone_area_m2"]);
  const json zone = cli_json("zone '" + problem_path("pots/red_then_black") + "' --json --method exact --out " +
                                 (std::filesystem::temp_directory_path() / "serve_zone_test.svg").string(),
                             "");
  EXPECT_EQ(z["best"], zone["best"]);
  EXPECT_EQ(z["best_p"], zone["best_p"]);
  EXPECT_EQ(z["area_m2"], zone["zone_area_m2"]);
  // The rest of the answer is solve's.
  json rest = a.body;
  rest.erase("zone");
  const json cli = cli_json("solve '" + problem_path("pots/red_then_black") + "' " + quick_flags(3) + " --json", "");
  EXPECT_EQ(comparable(rest), comparable(cli));
  // A problem without `next` has no zone.
  const Answer plain = post(server, "/api/solve", json{{"problem", example_problem(server, "one_rail_position.yaml")},
                                                       {"options", quick_options(3)}});
  EXPECT_FALSE(plain.body.contains("zone"));
}

TEST(ServeSolve, ClampsTheSearchTimeToTheServersAndSaysSo) {
  ServerOptions options = TestServer::defaults();
  options.limits.max_time_s = 3.0;
  TestServer server(options);
  json opts = quick_options(1);
  opts["max_time"] = 1000;
  const Answer a = post(server, "/api/solve", json{{"problem", kSmallProblem}, {"options", opts}});
  ASSERT_EQ(a.status, 200) << a.raw;
  EXPECT_EQ(a.body["options"]["max_time_s"], 3.0);
  EXPECT_NE(a.body["note"].get<std::string>().find("clamped"), std::string::npos);
}

TEST(ServeSimulate, AnswersAsTheCommandLineDoes) {
  TestServer server;
  // The witness of one_rail_position.yaml (problems/README.md): it lands.
  const json stroke = {{"speed", 1.002}, {"aim_deg", -60.36}, {"topspin_k", 0.8}, {"sidespin_k", 0}};
  const Answer a = post(server, "/api/simulate",
                        json{{"problem", example_problem(server, "one_rail_position.yaml")},
                             {"stroke", stroke}});
  ASSERT_EQ(a.status, 200) << a.raw;
  EXPECT_EQ(a.body["status"], "rest");
  EXPECT_EQ(a.body["reaches_target"], true);
  EXPECT_FALSE(a.body["path"].empty());
  const json cli = cli_json("simulate '" + problem_path("one_rail_position") +
                                "' --speed 1.002 --aim -60.36 --topspin-k 0.8 --sidespin-k 0 --json",
                            "");
  EXPECT_EQ(comparable(a.body), comparable(cli));
}

// A run-out from a shipped pot problem's balls (its pot and target set aside): the plan's
// keys as `cueplan run --json` gives them, each shot with simulate's JSON for its paths,
// starting where the shot before it left the cue ball; bad fields named.
TEST(ServeRun, PlansARunFromTheProblemsBallsWithEachShotsPaths) {
  TestServer server;
  const json problem = example_problem(server, "pots/cut_middle_pocket.yaml");
  const Answer a = post(server, "/api/run",
                        json{{"problem", problem}, {"options", {{"samples", 3}, {"lookahead", 1}}}});
  ASSERT_EQ(a.status, 200) << a.raw;
  for (const char* key : {"plan", "runout", "mean_potted", "deaths", "policy"})
    EXPECT_TRUE(a.body.contains(key)) << key;
  EXPECT_EQ(a.body["game"], "any_order");
  EXPECT_EQ(a.body["runout"]["samples"], 3);
  ASSERT_FALSE(a.body["plan"].empty()) << a.raw;
  json start = problem["cue_ball"];
  for (const json& shot : a.body["plan"]) {
    ASSERT_TRUE(shot.contains("simulation")) << shot.dump();
    EXPECT_FALSE(shot["simulation"]["path"].empty());
    EXPECT_NEAR(shot["start"][0].get<double>(), start[0].get<double>(), 1e-9);
    EXPECT_NEAR(shot["simulation"]["final_position"][0].get<double>(), shot["final_position"][0].get<double>(), 1e-9);
    start = shot["final_position"];
  }

  const Answer bad_game = post(server, "/api/run", json{{"problem", problem}, {"game", "ten_ball"}});
  EXPECT_EQ(bad_game.status, 400);
  EXPECT_EQ(bad_game.body["field"], "game");
  const Answer bad_samples = post(server, "/api/run", json{{"problem", problem}, {"options", {{"samples", 100000}}}});
  EXPECT_EQ(bad_samples.status, 400);
  EXPECT_EQ(bad_samples.body["field"], "options.samples");
  const Answer not_pool = post(server, "/api/run", json{{"problem", problem}, {"game", "nine_ball"}});
  EXPECT_EQ(not_pool.status, 400);
  EXPECT_NE(not_pool.body["field"].get<std::string>().rfind("problem.balls.", 0), std::string::npos) << not_pool.raw;
}

TEST(ServeSpinmap, AnswersAsTheCommandLineDoesWithEveryCell) {
  TestServer server;
  const json request = {{"problem", example_problem(server, "one_rail_position.yaml")},
                        {"speed", 1.002},
                        {"aim_deg", -60.36},
                        {"grid", 21},
                        {"options", {{"method", "exact"}}}};
  const Answer a = post(server, "/api/spinmap", request);
  ASSERT_EQ(a.status, 200) << a.raw;
  const json cells = a.body["cells"];
  json without_cells = a.body;
  without_cells.erase("cells");
  const json cli = cli_json("spinmap '" + problem_path("one_rail_position") +
                                "' --speed 1.002 --aim -60.36 --grid 21 --method exact --json --out '" +
                                (scratch() / "map.svg").string() + "'",
                            "");
  EXPECT_EQ(comparable(without_cells), comparable(cli));
  // Every grid spin, the landing ones among them as the summary lists them.
  ASSERT_EQ(cells.size(), a.body["points"].get<size_t>());
  size_t landing = 0;
  for (const json& c : cells) landing += c["lands"].get<bool>() ? 1 : 0;
  EXPECT_EQ(landing, a.body["landing"].get<size_t>());
  size_t listed = 0;
  for (const json& c : cells) {
    if (!c["lands"].get<bool>()) continue;
    const json& l = a.body["landing_spins"][listed++];
    EXPECT_EQ(c["topspin_k"], l["topspin_k"]);
    EXPECT_EQ(c["sidespin_k"], l["sidespin_k"]);
    EXPECT_EQ(c["kind"], "at_rest_allowed_cushions");
  }
  json counted = json::object();
  for (const json& c : cells) counted[c["kind"].get<std::string>()] = counted.value(c["kind"], 0) + 1;
  for (const auto& [kind, n] : a.body["outcomes"].items())
    EXPECT_EQ(counted.value(kind, 0), n.get<int>()) << kind;
}

TEST(ServeSpinmap, WithoutSpeedAndAimMapsThePlannersStroke) {
  TestServer server;
  const Answer a = post(server, "/api/spinmap",
                        json{{"problem", example_problem(server, "one_rail_position.yaml")},
                             {"grid", 11},
                             {"options", quick_options(5)}});
  ASSERT_EQ(a.status, 200) << a.raw;
  EXPECT_EQ(a.body["stroke_source"], "planner");
  EXPECT_EQ(a.body["speed"], a.body["planner"]["shot"]["speed"]);
  EXPECT_EQ(a.body["aim_deg"], a.body["planner"]["shot"]["aim_deg"]);
}

TEST(ServePage, IsServedFromTheBinaryAndNothingElseIs) {
  TestServer server;
  httplib::Client c = server.client();
  const httplib::Result page = c.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_EQ(page->get_header_value("Content-Type"), "text/html; charset=utf-8");
  EXPECT_NE(page->body.find("What spin lands here?"), std::string::npos);
  EXPECT_NE(page->get_header_value("Content-Security-Policy").find("default-src 'self'"),
            std::string::npos);
  const httplib::Result script = c.Get("/app.js");
  ASSERT_TRUE(script);
  EXPECT_EQ(script->status, 200);
  EXPECT_EQ(script->get_header_value("Content-Type"), "text/javascript; charset=utf-8");
  // No file of the server's disk, by any spelling of a path.
  for (const char* path : {"/../../etc/passwd", "/%2e%2e/%2e%2e/etc/passwd", "/web/index.html",
                           "/etc/passwd", "/problems/one_rail_position.yaml", "/api/nothing",
                           "/index.html/", "//etc/passwd"}) {
    const Answer a = get(server, path);
    EXPECT_EQ(a.status, 404) << path << ": " << a.raw;
    EXPECT_TRUE(a.body.is_object() && a.body.contains("error")) << path << ": " << a.raw;
  }
}

// ---------------------------------------------------------------------------
// Bad input

TEST(ServeBadInput, MalformedJsonIsA400ForTheBody) {
  TestServer server;
  for (const char* body : {"{\"problem\": ", "", "not json", "{\"a\": 1,}", "\xff\xfe"})
    for (const char* path : {"/api/solve", "/api/simulate", "/api/spinmap"}) {
      SCOPED_TRACE(std::string(path) + " " + body);
      expect_error(post(server, path, std::string(body)), 400, std::nullopt, "not JSON");
    }
  expect_error(post(server, "/api/solve", std::string("[1, 2]")), 400, std::nullopt, "JSON object");
}

TEST(ServeBadInput, UnknownFieldsAreNamed) {
  TestServer server;
  json with_typo = kSmallProblem;
  with_typo["tabel"] = {{"length", 3}};
  expect_error(post(server, "/api/solve", json{{"problem", with_typo}}), 400, "problem.tabel",
               "did you mean table");
  json nested = kSmallProblem;
  nested["table"] = {{"lenght", 3}};
  expect_error(post(server, "/api/solve", json{{"problem", nested}}), 400, "problem.table.lenght",
               "unknown key");
  expect_error(post(server, "/api/solve", json{{"problem", kSmallProblem}, {"seed", 1}}), 400, "seed",
               "unknown field 'seed'");
  expect_error(post(server, "/api/solve", json{{"problem", kSmallProblem}, {"options", {{"threads", 4}}}}),
               400, "options.threads", "the options are");
  expect_error(post(server, "/api/simulate",
                    json{{"problem", kSmallProblem},
                         {"stroke", {{"speed", 1}, {"aim_deg", 0}, {"spin", 1}}}}),
               400, "stroke.spin", "unknown field");
  expect_error(post(server, "/api/spinmap", json{{"problem", kSmallProblem}, {"options", {{"max_events", 5}}}}),
               400, "options.max_events", "unknown field");
}

TEST(ServeBadInput, BadValuesNameTheirField) {
  TestServer server;
  const auto solve = [&](json problem, json options = json::object()) {
    return post(server, "/api/solve", json{{"problem", problem}, {"options", options}});
  };
  json p = kSmallProblem;
  p["table"] = {{"length", -1}};
  expect_error(solve(p), 400, "problem.table.length", "must be positive");
  p = kSmallProblem;
  p["cue_ball"] = {1.0, 0.01};  // across the bottom cushion, away from the pockets
  expect_error(solve(p), 400, "problem.cue_ball", "off the table");
  p = kSmallProblem;
  p["limits"] = {{"speed", {3, 1}}};
  expect_error(solve(p), 400, "problem.limits.speed", "min must be below max");
  p = kSmallProblem;
  p["tolerance"] = "0.02";
  expect_error(solve(p), 400, "problem.tolerance", "must be a number");
  expect_error(solve(kSmallProblem, {{"max_time", -1}}), 400, "options.max_time", "positive");
  expect_error(solve(kSmallProblem, {{"seed", "x"}}), 400, "options.seed", "whole number");
  expect_error(solve(kSmallProblem, {{"seed", -1}}), 400, "options.seed", "whole number");
  expect_error(solve(kSmallProblem, {{"samples", 2.5}}), 400, "options.samples", "whole number");
  expect_error(solve(kSmallProblem, {{"samples", 100000}}), 400, "options.samples", "at most 2000");
  expect_error(solve(kSmallProblem, {{"robust", true}, {"samples", 0}}), 400, "options.samples",
               "options.robust");
  expect_error(solve(kSmallProblem, {{"global", "anneal"}}), 400, "options.global", "must be one of");
  expect_error(solve(kSmallProblem, {{"method", "fast"}}), 400, "options.method", "must be one of");
  expect_error(solve(kSmallProblem, {{"accuracy", 1}}), 400, "options.accuracy", "[1e-12, 0.1]");
  expect_error(post(server, "/api/solve", json{{"options", json::object()}}), 400, "problem",
               "problem is required");
  expect_error(post(server, "/api/solve", json{{"problem", 5}}), 400, "problem", "must be an object");
  expect_error(post(server, "/api/solve", json{{"problem", kSmallProblem}, {"options", 5}}), 400,
               "options", "must be an object");
  // A problem nested deeper than any file is refused before it is written out.
  const std::string deep = std::string(5000, '[') + "1" + std::string(5000, ']');
  expect_error(post(server, "/api/solve",
                    "{\"problem\": {\"cue_ball\": [0.8, 0.5], \"target\": [2.6, 1.2], \"obstacles\": " +
                        deep + "}}"),
               400, "problem", "deeper");

  const auto simulate = [&](json stroke) {
    return post(server, "/api/simulate", json{{"problem", kSmallProblem}, {"stroke", stroke}});
  };
  expect_error(simulate({{"aim_deg", 0}}), 400, "stroke.speed", "required");
  expect_error(simulate({{"speed", 0}, {"aim_deg", 0}}), 400, "stroke.speed", "stroke.speed");
  expect_error(simulate({{"speed", 1}, {"aim_deg", "north"}}), 400, "stroke.aim_deg", "number");
  expect_error(post(server, "/api/simulate", json{{"problem", kSmallProblem}}), 400, "stroke", "required");
  expect_error(post(server, "/api/simulate",
                    json{{"problem", kSmallProblem},
                         {"stroke", {{"speed", 1}, {"aim_deg", 0}}},
                         {"options", {{"max_events", 5000}}}}),
               400, "options.max_events", "at most 1000");

  const auto spinmap = [&](json extra) {
    json request = {{"problem", kSmallProblem}};
    request.update(extra);
    return post(server, "/api/spinmap", request);
  };
  expect_error(spinmap({{"speed", 1}}), 400, "aim_deg", "required with speed");
  expect_error(spinmap({{"speed", -1}, {"aim_deg", 0}}), 400, "speed", "above 0");
  expect_error(spinmap({{"speed", 1}, {"aim_deg", 0}, {"grid", 62}}), 400, "grid", "3 to 61");
  expect_error(spinmap({{"speed", 1}, {"aim_deg", 0}, {"grid", 2}}), 400, "grid", "3 to 61");
  // How forgiving each spin is: samples 1..200, a bounded total, cells in range.
  const json stroke = {{"speed", 1}, {"aim_deg", 0}, {"grid", 9}, {"success", true}};
  const auto with = [&](json extra) {
    json r = stroke;
    r.update(extra);
    return spinmap(r);
  };
  expect_error(with({{"success", "yes"}}), 400, "success", "true or false");
  expect_error(with({{"samples", 0}}), 400, "samples", "1 to 200");
  expect_error(with({{"samples", 201}}), 400, "samples", "1 to 200");
  expect_error(with({{"samples", 1.5}}), 400, "samples", "whole number");
  expect_error(with({{"success_from", -1}}), 400, "success_from", "0 to");
  expect_error(with({{"success_from", 49}}), 400, "success_from", "0 to 48");
  expect_error(with({{"success_count", 0}}), 400, "success_count", "at least 1");
  expect_error(spinmap({{"speed", 1}, {"aim_deg", 0}, {"grid", 61}, {"success", true},
                        {"samples", 200}}),
               400, "success_count", "at most 40000");
  expect_error(spinmap({{"speed", 1}, {"aim_deg", 0}, {"samples", 10}}), 400, "samples",
               "only with success");
  expect_error(with({{"options", {{"noise", -1}}}}), 400, "options.noise", "0 to 10");
}

// The success under noise asked for in two parts is the success asked for at once, and
// at noise 0 it is 1 exactly where the cell lands.
TEST(ServeSpinmap, SuccessInPartsIsTheWholeAndZeroNoiseIsTheOutcome) {
  TestServer server;
  json request = {{"problem", example_problem(server, "one_rail_position.yaml")},
                  {"speed", 1.002},
                  {"aim_deg", -60.36},
                  {"grid", 7},
                  {"success", true},
                  {"samples", 8},
                  {"options", {{"method", "exact"}, {"seed", 3}}}};
  const Answer whole = post(server, "/api/spinmap", request);
  ASSERT_EQ(whole.status, 200) << whole.raw;
  const json& cells = whole.body["cells"];
  ASSERT_EQ(cells.size(), 29u);
  EXPECT_EQ(whole.body["success"]["samples"], 8);
  EXPECT_EQ(whole.body["success"]["complete"], true);
  request["success_from"] = 0;
  request["success_count"] = 10;
  const Answer first = post(server, "/api/spinmap", request);
  request["success_from"] = 10;
  request["success_count"] = 100;
  const Answer rest = post(server, "/api/spinmap", request);
  ASSERT_EQ(first.status, 200) << first.raw;
  ASSERT_EQ(rest.status, 200) << rest.raw;
  EXPECT_EQ(rest.body["success"]["count"], 19);
  for (size_t i = 0; i < cells.size(); ++i) {
    const json& part = i < 10 ? first.body["cells"][i] : rest.body["cells"][i];
    EXPECT_EQ(part["success"], cells[i]["success"]) << i;
    EXPECT_EQ((i < 10 ? rest : first).body["cells"][i].contains("success"), false) << i;
  }
  request.erase("success_from");
  request.erase("success_count");
  request["options"]["noise"] = 0;
  const Answer exact = post(server, "/api/spinmap", request);
  ASSERT_EQ(exact.status, 200) << exact.raw;
  for (const json& c : exact.body["cells"])
    EXPECT_EQ(c["success"].get<double>(), c["lands"].get<bool>() ? 1.0 : 0.0);
}

TEST(ServeBadInput, OversizeBodiesAre413) {
  ServerOptions options = TestServer::defaults();
  options.max_body_bytes = 4096;
  TestServer server(options);
  const std::string big = "{\"problem\": {\"name\": \"" + std::string(5000, 'x') + "\"}}";
  const Answer a = post(server, "/api/solve", big);
  expect_error(a, 413, std::nullopt, "larger than this server takes (4096 bytes)");
  // A body within the limit is read.
  const Answer ok = post(server, "/api/solve", std::string("{\"problem\": 1}"));
  EXPECT_EQ(ok.status, 400);
}

TEST(ServeBadInput, OnlyJsonPostsAddressedToLocalhostAreTaken) {
  TestServer server;
  expect_error(post(server, "/api/solve", json{{"problem", kSmallProblem}}.dump(), "text/plain"), 415,
               std::nullopt, "Content-Type: application/json");
  httplib::Client c = server.client();
  const Answer a = answer_of(c.Get("/api/health", {{"Host", "attacker.example:80"}}));
  expect_error(a, 403, std::nullopt, "addressed to localhost");
  const Answer named = answer_of(c.Get("/api/health", {{"Host", "localhost:" + std::to_string(server.port())}}));
  EXPECT_EQ(named.status, 200);
}

// ---------------------------------------------------------------------------
// Concurrency

// Sixteen different shipped problems, each with the command line's answer to a quick
// search (computed once for the tests that need it).
struct ExpectedSolve {
  std::string file;  // as /api/examples names it
  uint64_t seed;
  json answer;
};
const std::vector<ExpectedSolve>& sixteen_problems() {
  static const std::vector<ExpectedSolve> kSixteen = [] {
    const std::vector<std::string> stems = {
        "one_rail_position",        "two_rail_position",        "three_rail_position",
        "near_pocket",              "pool_table",               "blocked_direct_route",
        "paper_figure8_rolling",    "paper_figure9_topspin",    "paper_figure10_sidespin",
        "pots/cut_middle_pocket",   "pots/long_pot",            "pots/only_draw",
        "pots/straight_pot_corner", "pots/pool_straight_follow", "pots/plant_two_balls",
        "pots/two_cushion_position"};
    std::vector<ExpectedSolve> list;
    uint64_t seed = 3;
    for (const std::string& stem : stems) {
      ExpectedSolve e{stem + ".yaml", seed++, {}};
      e.answer = cli_json("solve '" + problem_path(stem) + "' " + quick_flags(e.seed) +
                              " --max-time 600 --json",
                          "sixteen" + std::to_string(e.seed));
      list.push_back(std::move(e));
    }
    return list;
  }();
  return kSixteen;
}

// `copies` of each of the sixteen problems' searches sent at once (one connection each)
// to a server with two workers: every one must be answered 200 with the command line's
// answer.
void expect_all_answered_correctly(int copies, ServerOptions options) {
  options.workers = 2;
  // On two busy cores a search may take a second: a clock long enough that the
  // evaluation budget, not the time, ends each one, as the seed's answer needs
  // (planner.hpp), and a wait budget that lets the last in the queue wait its turn.
  options.limits.max_time_s = 600;
  options.wait_budget_s = 600;
  TestServer server(options);
  const std::vector<ExpectedSolve>& expected = sixteen_problems();
  struct Job {
    const ExpectedSolve* expected;
    std::string body;
    Answer answer;
  };
  std::vector<Job> jobs;
  for (int copy = 0; copy < copies; ++copy)
    for (const ExpectedSolve& e : expected) {
      json search = quick_options(e.seed);
      search["max_time"] = 600;
      jobs.push_back({&e, json{{"problem", example_problem(server, e.file)}, {"options", search}}.dump(), {}});
    }
  std::latch go(static_cast<std::ptrdiff_t>(jobs.size()));
  std::vector<std::thread> threads;
  const Clock::time_point started = Clock::now();
  for (Job& job : jobs)
    threads.emplace_back([&] {
      httplib::Client c = server.client();
      c.set_read_timeout(600);
      go.arrive_and_wait();
      job.answer = answer_of(c.Post("/api/solve", job.body, "application/json"));
    });
  for (std::thread& t : threads) t.join();
  const double seconds = std::chrono::duration<double>(Clock::now() - started).count();
  int right = 0;
  for (const Job& job : jobs) {
    SCOPED_TRACE(job.expected->file + " seed " + std::to_string(job.expected->seed));
    ASSERT_EQ(job.answer.status, 200) << job.answer.raw;
    EXPECT_EQ(comparable(job.answer.body), comparable(job.expected->answer));
    right += comparable(job.answer.body) == comparable(job.expected->answer);
  }
  std::cout << "[ measured ] " << jobs.size() << " concurrent solves on 2 workers: " << right
            << " answered 200 as the command line answers, in " << seconds << " s\n";
}

TEST(ServeConcurrency, SixteenSolvesOfDifferentProblemsAtOnceAreAllAnsweredCorrectly) {
  expect_all_answered_correctly(1, TestServer::defaults());
}

TEST(ServeLoad, SixtyFourSolvesAtOnceAreAllAnsweredCorrectly) {
  expect_all_answered_correctly(4, TestServer::defaults());
}

// A long search (about 3 s: the clock ends the search, then 11 strokes' success
// probabilities of 1000 noisy strokes each) that holds a worker.
const json kLongSearch = {{"problem", kSmallProblem},
                          {"options",
                           {{"method", "exact"}, {"max_evaluations", 200000}, {"max_time", 2},
                            {"samples", 1000}, {"alternatives", 10}, {"starts", 32}}}};
const json kQuickSimulate = {{"problem", kSmallProblem}, {"stroke", {{"speed", 1}, {"aim_deg", 0}}}};

// Starts the long search on its own thread and returns once the server says it computes.
std::thread hold_the_worker(TestServer& server, Answer* first, Clock::time_point* done) {
  std::thread holder([&server, first, done] {
    *first = post(server, "/api/solve", kLongSearch);
    *done = Clock::now();
  });
  const Clock::time_point deadline = Clock::now() + std::chrono::seconds(10);
  while (get(server, "/api/health").body["busy"] != 1 && Clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_EQ(get(server, "/api/health").body["busy"], 1);
  return holder;
}

TEST(ServeQueue, ARequestThatFindsTheWorkersBusyWaitsItsTurn) {
  ServerOptions options = TestServer::defaults();
  options.workers = 1;
  options.limits.max_time_s = 2.0;
  TestServer server(options);
  Answer first;
  Clock::time_point first_done;
  std::thread holder = hold_the_worker(server, &first, &first_done);
  Answer second;
  std::string second_timing;
  std::thread waiter([&] {
    httplib::Client c = server.client();
    const httplib::Result r = c.Post("/api/simulate", kQuickSimulate.dump(), "application/json");
    if (r) second_timing = r->get_header_value("Server-Timing");
    second = answer_of(r);
  });
  const Clock::time_point deadline = Clock::now() + std::chrono::seconds(10);
  while (get(server, "/api/health").body["queued"] != 1 && Clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(get(server, "/api/health").body["queued"], 1);
  const Clock::time_point queued_at = Clock::now();
  // The page and the health check still answer while the worker computes.
  EXPECT_EQ(get(server, "/").status, 200);
  holder.join();
  waiter.join();
  EXPECT_EQ(first.status, 200) << first.raw;
  EXPECT_EQ(second.status, 200) << second.raw;
  // It waited in the queue until the long search (a 2 s search clock) gave up its worker.
  std::smatch waited;
  ASSERT_TRUE(std::regex_search(second_timing, waited, std::regex(R"(queue;dur=([0-9.]+))")))
      << second_timing;
  const double queued_ms = std::stod(waited[1]);
  std::cout << "[ measured ] a request queued behind a 2 s search waited " << queued_ms
            << " ms, then was answered 200\n";
  // It waited at least from when it was seen queued until the long search's answer came
  // back (less a margin for that answer's trip to the client).
  const double held_ms = std::chrono::duration<double, std::milli>(first_done - queued_at).count();
  EXPECT_GT(held_ms, 100.0);
  EXPECT_GT(queued_ms, held_ms - 100.0);
  EXPECT_EQ(get(server, "/api/health").body["busy"], 0);
  EXPECT_EQ(get(server, "/api/health").body["queued"], 0);
}

TEST(ServeQueue, AFullQueueOrAWaitBeyondTheBudgetIs503WithRetryAfter) {
  {
    ServerOptions options = TestServer::defaults();
    options.workers = 1;
    options.queue = 0;
    options.limits.max_time_s = 2.0;
    TestServer server(options);
    Answer first;
    Clock::time_point first_done;
    std::thread holder = hold_the_worker(server, &first, &first_done);
    const Clock::time_point asked = Clock::now();
    const Answer second = post(server, "/api/simulate", kQuickSimulate);
    const double waited = std::chrono::duration<double>(Clock::now() - asked).count();
    expect_error(second, 503, std::nullopt, "queue of 0 requests is full");
    EXPECT_GE(std::stoi(second.retry_after), 1);
    EXPECT_EQ(second.body["retry_after_s"], std::stoi(second.retry_after));
    EXPECT_LT(waited, 0.5) << "a full queue answers at once";
    holder.join();
    EXPECT_EQ(first.status, 200) << first.raw;
  }
  {
    // A budget shorter than half the running search's estimate (0.25 s of 0.5 s).
    ServerOptions options = TestServer::defaults();
    options.workers = 1;
    options.wait_budget_s = 0.1;
    options.limits.max_time_s = 2.0;
    TestServer server(options);
    Answer first;
    Clock::time_point first_done;
    std::thread holder = hold_the_worker(server, &first, &first_done);
    const Clock::time_point asked = Clock::now();
    const Answer second = post(server, "/api/simulate", kQuickSimulate);
    const double waited = std::chrono::duration<double>(Clock::now() - asked).count();
    expect_error(second, 503, std::nullopt, "exceeds its wait budget of 0.1 s");
    EXPECT_GE(std::stoi(second.retry_after), 1);
    EXPECT_LT(waited, 0.5) << "an expected wait beyond the budget answers at once";
    holder.join();
  }
}

// ---------------------------------------------------------------------------
// Slow, hostile and odd clients, on loopback

// A TCP connection to the server from `source` (another loopback address stands for
// another client); -1 when it cannot connect.
int connect_to(int port, const char* source = "127.0.0.1") {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in from{};
  from.sin_family = AF_INET;
  ::inet_pton(AF_INET, source, &from.sin_addr);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&from), sizeof from) != 0) {
    ::close(fd);
    return -1;
  }
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<uint16_t>(port));
  ::inet_pton(AF_INET, "127.0.0.1", &to.sin_addr);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&to), sizeof to) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

bool send_text(int fd, const std::string& text) {
  return ::send(fd, text.data(), text.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(text.size());
}

// What the server sends within `wait` (until it closes or goes quiet that long).
std::string receive(int fd, std::chrono::milliseconds wait) {
  std::string got;
  char buffer[4096];
  for (;;) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(wait.count())) <= 0) break;
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) break;
    got.append(buffer, static_cast<size_t>(n));
  }
  return got;
}

double health_ms(const TestServer& server) {
  const Clock::time_point asked = Clock::now();
  const Answer a = get(server, "/api/health");
  EXPECT_EQ(a.status, 200) << a.raw;
  return std::chrono::duration<double, std::milli>(Clock::now() - asked).count();
}

TEST(ServeAbuse, TwentySlowHeaderClientsDoNotStopHealthAnswering) {
  ServerOptions options = TestServer::defaults();
  options.request_deadline_s = 2.0;
  TestServer server(options);
  // Each sends its headers a byte at a time, 20 bytes a second.
  const std::string headers = "GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: " +
                              std::string(200, 'a') + "\r\n\r\n";
  std::vector<int> slow;
  for (int i = 0; i < 20; ++i) {
    const int fd = connect_to(server.port());
    ASSERT_GE(fd, 0);
    slow.push_back(fd);
  }
  std::atomic<bool> done{false};
  std::thread dribble([&] {
    for (size_t at = 0; at < headers.size() && !done; ++at) {
      for (int fd : slow) send_text(fd, headers.substr(at, 1));
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  double worst = 0.0;
  for (int i = 0; i < 10; ++i) {
    worst = std::max(worst, health_ms(server));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  std::cout << "[ measured ] /api/health with 20 slow-header clients: slowest of 10 answers "
            << worst << " ms\n";
  EXPECT_LT(worst, 100.0);
  // Past the deadline each slow client has been answered 408 and its connection closed.
  for (int fd : slow) {
    const std::string got = receive(fd, std::chrono::milliseconds(3000));
    EXPECT_EQ(got.rfind("HTTP/1.1 408", 0), 0u) << got;
    EXPECT_NE(got.find("within 2 s"), std::string::npos) << got;
  }
  done = true;
  dribble.join();
  for (int fd : slow) ::close(fd);
}

TEST(ServeAbuse, ConnectionsPerClientAddressAreLimited) {
  ServerOptions options = TestServer::defaults();
  options.client_connections = 3;
  TestServer server(options);
  std::vector<int> held;
  for (int i = 0; i < 3; ++i) held.push_back(connect_to(server.port(), "127.0.0.2"));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const int extra = connect_to(server.port(), "127.0.0.2");
  ASSERT_GE(extra, 0);
  const std::string got = receive(extra, std::chrono::milliseconds(2000));
  EXPECT_EQ(got.rfind("HTTP/1.1 503", 0), 0u) << got;
  EXPECT_NE(got.find("Retry-After: 1"), std::string::npos) << got;
  EXPECT_NE(got.find("too many connections from 127.0.0.2"), std::string::npos) << got;
  // Another address is served meanwhile.
  EXPECT_EQ(get(server, "/api/health").status, 200);
  ::close(extra);
  for (int fd : held) ::close(fd);
}

TEST(ServeAbuse, AChunkedBodyBeyondTheLimitIs413WhileItIsRead) {
  TestServer server;  // 256 KiB
  const int fd = connect_to(server.port());
  ASSERT_GE(fd, 0);
  ASSERT_TRUE(send_text(fd, "POST /api/solve HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: "
                            "application/json\r\nTransfer-Encoding: chunked\r\n\r\n"));
  // 320 KiB of a 1 MiB body, in 16 KiB chunks; then the client waits. A server that
  // buffered the body whole would wait for the rest; this one answers now.
  const std::string chunk = "4000\r\n" + std::string(16384, ' ') + "\r\n";
  size_t sent = 0;
  while (sent < 320 * 1024 && send_text(fd, chunk)) sent += 16384;
  const std::string got = receive(fd, std::chrono::milliseconds(3000));
  std::cout << "[ measured ] chunked body: answered after " << sent / 1024 << " KiB of 1024 KiB: "
            << got.substr(0, got.find('\r')) << "\n";
  EXPECT_EQ(got.rfind("HTTP/1.1 413", 0), 0u) << got.substr(0, 300);
  EXPECT_NE(got.find("larger than this server takes (262144 bytes)"), std::string::npos) << got;
  EXPECT_NE(got.find("Connection: close"), std::string::npos) << got;
  // The rest cannot be sent into a closed connection forever: the server is gone.
  while (sent < 1024 * 1024 && send_text(fd, chunk)) sent += 16384;
  ::close(fd);
  EXPECT_EQ(get(server, "/api/health").status, 200);
}

TEST(ServeAbuse, AnAnnouncedBodyBeyondTheLimitIs413BeforeItIsSent) {
  TestServer server;
  const int fd = connect_to(server.port());
  ASSERT_GE(fd, 0);
  ASSERT_TRUE(send_text(fd, "POST /api/solve HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: "
                            "application/json\r\nContent-Length: 52428800\r\n\r\n"));
  const std::string got = receive(fd, std::chrono::milliseconds(2000));
  EXPECT_EQ(got.rfind("HTTP/1.1 413", 0), 0u) << got;
  ::close(fd);
}

TEST(ServeAbuse, NumericExtremesAre400NamingTheField) {
  TestServer server;
  const std::string problem = json(kSmallProblem).dump();
  const auto simulate = [&](const std::string& stroke) {
    return post(server, "/api/simulate", "{\"problem\": " + problem + ", \"stroke\": " + stroke + "}");
  };
  int answered = 0;
  const auto expect_400 = [&](const Answer& a, const std::optional<std::string>& field,
                              const std::string& words) {
    expect_error(a, 400, field, words);
    answered += a.status == 400;
  };
  expect_400(simulate(R"({"speed": 1e400, "aim_deg": 0})"), "stroke.speed", "out of range");
  expect_400(simulate(R"({"speed": -1e400, "aim_deg": 0})"), "stroke.speed", "out of range");
  expect_400(simulate(R"({"speed": 1, "aim_deg": 0, "topspin_k": 1e400})"), "stroke.topspin_k",
             "out of range");
  expect_400(simulate(R"({"speed": -0, "aim_deg": 0})"), "stroke.speed", "positive");
  expect_400(simulate(R"({"speed": -0.0, "aim_deg": 0})"), "stroke.speed", "positive");
  expect_400(simulate(R"({"speed": NaN, "aim_deg": 0})"), std::nullopt, "not JSON");
  expect_400(simulate(R"({"speed": "NaN", "aim_deg": 0})"), "stroke.speed", "must be a number");
  expect_400(simulate(R"({"speed": Infinity, "aim_deg": 0})"), std::nullopt, "not JSON");
  expect_400(simulate(R"({"speed": 1e308, "aim_deg": 0})"), "stroke.speed", "at most 20 m/s");
  expect_400(simulate(R"({"speed": 25, "aim_deg": 0})"), "stroke.speed", "at most 20 m/s");
  expect_400(simulate(R"({"speed": 1, "aim_deg": 1e308})"), "stroke.aim_deg", "-360 to 360");
  expect_400(simulate(R"({"speed": 1, "aim_deg": 0, "topspin_k": 1e9})"), "stroke.topspin_k",
             "miscues");
  expect_400(simulate(R"({"speed": 1, "aim_deg": 0, "topspin_k": 1, "sidespin_k": 0.9})"),
             "stroke.topspin_k", "0.54 ball radii");
  expect_400(simulate(R"({"speed": 1, "aim_deg": 0, "sidespin_k": -1e308})"), "stroke.sidespin_k",
             "miscues");
  const auto spinmap = [&](const std::string& rest) {
    return post(server, "/api/spinmap", "{\"problem\": " + problem + ", " + rest + "}");
  };
  expect_400(spinmap(R"("speed": 1e308, "aim_deg": 0)"), "speed", "at most 20 m/s");
  expect_400(spinmap(R"("speed": 1, "aim_deg": 1e400)"), "aim_deg", "out of range");
  expect_400(spinmap(R"("speed": 1, "aim_deg": 0, "grid": 1e400)"), "grid", "out of range");
  expect_400(spinmap(R"("speed": 1, "aim_deg": 0, "grid": 1e308)"), "grid", "whole number");
  const auto solve = [&](const std::string& body) { return post(server, "/api/solve", body); };
  expect_400(solve("{\"problem\": " + problem + R"(, "options": {"samples": 1e400}})"),
             "options.samples", "out of range");
  expect_400(solve("{\"problem\": " + problem + R"(, "options": {"noise": 1e308}})"),
             "options.noise", "0 to 10");
  expect_400(solve(R"({"problem": {"cue_ball": [1e400, 0.5], "target": [2.6, 1.2]}})"),
             "problem.cue_ball", "out of range");
  json p = kSmallProblem;
  p["limits"] = {{"spin", 3}};
  expect_400(solve(json{{"problem", p}}.dump()), "problem.limits.spin", "miscues");
  p["limits"] = {{"speed", {0.2, 50}}};
  expect_400(solve(json{{"problem", p}}.dump()), "problem.limits.speed[1]", "at most 20 m/s");
  std::cout << "[ measured ] numeric extremes: " << answered << " of 23 answered 400 naming the field\n";

  // Implausible but possible: played, with a warning naming the field.
  p["limits"] = {{"speed", {0.2, 14}}};
  const Answer quick = post(server, "/api/solve",
                            json{{"problem", p}, {"options", {{"max_evaluations", 300}, {"samples", 0}}}});
  ASSERT_EQ(quick.status, 200) << quick.raw;
  ASSERT_TRUE(quick.body.contains("warnings")) << quick.raw;
  EXPECT_NE(quick.body["warnings"][0].get<std::string>().find("problem.limits.speed[1] 14 m/s is faster than a break shot"),
            std::string::npos)
      << quick.raw;
  const Answer fast = simulate(R"({"speed": 14, "aim_deg": 0})");
  ASSERT_EQ(fast.status, 200) << fast.raw;
  ASSERT_TRUE(fast.body.contains("warnings")) << fast.raw;
  EXPECT_NE(fast.body["warnings"][0].get<std::string>().find("stroke.speed 14 m/s is faster than a break shot"),
            std::string::npos)
      << fast.raw;
  EXPECT_FALSE(fast.body["final_position"].is_null()) << fast.raw;
}

TEST(ServeMethods, AWrongMethodIs405WithAllow) {
  TestServer server;
  httplib::Client c = server.client();
  const httplib::Result get_solve = c.Get("/api/solve");
  ASSERT_TRUE(get_solve);
  EXPECT_EQ(get_solve->status, 405);
  EXPECT_EQ(get_solve->get_header_value("Allow"), "POST, OPTIONS");
  expect_error(answer_of(get_solve), 405, std::nullopt, "use POST");
  const httplib::Result post_health = c.Post("/api/health", "{}", "application/json");
  ASSERT_TRUE(post_health);
  EXPECT_EQ(post_health->status, 405);
  EXPECT_EQ(post_health->get_header_value("Allow"), "GET, HEAD, OPTIONS");
  const httplib::Result delete_page = c.Delete("/");
  ASSERT_TRUE(delete_page);
  EXPECT_EQ(delete_page->status, 405);
  EXPECT_EQ(delete_page->get_header_value("Allow"), "GET, HEAD, OPTIONS");
  const httplib::Result options = c.Options("/api/spinmap");
  ASSERT_TRUE(options);
  EXPECT_EQ(options->status, 204);
  EXPECT_EQ(options->get_header_value("Allow"), "POST, OPTIONS");
  // Unknown paths stay 404, whatever the method.
  EXPECT_EQ(c.Get("/api/nothing")->status, 404);
}

// ---------------------------------------------------------------------------
// Impact tables

// An Api over a table store with a tiny table, as the server has one.
struct TableApi {
  explicit TableApi(size_t max_tables = 8) : store(settings(max_tables)) {
    std::string error;
    api = std::make_unique<Api>(cueplan::server::ApiLimits{}, "table", &store,
                                cueplan::server::shipped_examples(&error));
    EXPECT_EQ(error, "");
  }
  static ImpactTableStore::Settings settings(size_t max_tables) {
    ImpactTableStore::Settings s;
    s.cache_dir = (scratch() / ("tables" + std::to_string(max_tables))).string();
    s.options = cueplan::physics::test::tiny_table_options();
    s.max_tables = max_tables;
    return s;
  }
  void wait_until_made() {
    const Clock::time_point deadline = Clock::now() + std::chrono::seconds(60);
    while (store.working() && Clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_FALSE(store.working());
  }
  ImpactTableStore store;
  std::unique_ptr<Api> api;
};

TEST(ServeImpactTables, ASearchBeforeItsTableIsMadeIsAskedToComeBackThenUsesIt) {
  TableApi t;
  const std::string body =
      json{{"problem", kSmallProblem}, {"options", {{"max_evaluations", 300}, {"samples", 10}}}}.dump();
  // The first request for a cushion queues its table: 503, with when to ask again.
  const ApiReply early = t.api->solve(body);
  EXPECT_EQ(early.status, 503) << early.body.dump();
  EXPECT_EQ(early.retry_after_s, 5);
  EXPECT_EQ(early.body["field"], "options.method");
  EXPECT_NE(early.body["error"].get<std::string>().find("not ready yet"), std::string::npos);
  t.wait_until_made();
  const ApiReply later = t.api->solve(body);
  ASSERT_EQ(later.status, 200) << later.body.dump();
  EXPECT_EQ(later.body["options"]["method"], "table");
  const ApiReply health = t.api->health(1, 0);
  EXPECT_EQ(health.body["impact_tables_ready"], true);
  ASSERT_EQ(health.body["impact_tables"].size(), 1u);
  EXPECT_EQ(health.body["impact_tables"][0]["state"], "ready");
  // exact needs no table.
  const ApiReply exact = t.api->simulate(
      json{{"problem", kSmallProblem}, {"stroke", {{"speed", 1}, {"aim_deg", 0}}}}.dump());
  EXPECT_EQ(exact.status, 200);
}

TEST(ServeImpactTables, ACushionBeyondTheStoresRoomIsRefusedByName) {
  TableApi t(1);
  const auto solve = [&](const json& problem) {
    return t.api->solve(json{{"problem", problem}, {"options", {{"max_evaluations", 300}}}}.dump());
  };
  EXPECT_EQ(solve(kSmallProblem).status, 503);  // the one table it keeps
  json other = kSmallProblem;
  other["physics"] = {{"mu_cushion", 0.2}};
  const ApiReply refused = solve(other);
  EXPECT_EQ(refused.status, 400) << refused.body.dump();
  EXPECT_EQ(refused.body["field"], "options.method");
  EXPECT_NE(refused.body["error"].get<std::string>().find("at most 1 cushions"), std::string::npos);
  t.wait_until_made();
}

// ---------------------------------------------------------------------------
// The command as a process

// `cueplan serve ARGS` with its stdout and stderr on pipes.
class ServeProcess {
 public:
  explicit ServeProcess(const std::vector<std::string>& args) {
    int out[2], err[2];
    EXPECT_EQ(::pipe(out), 0);
    EXPECT_EQ(::pipe(err), 0);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, out[1], 1);
    posix_spawn_file_actions_adddup2(&actions, err[1], 2);
    posix_spawn_file_actions_addclose(&actions, out[0]);
    posix_spawn_file_actions_addclose(&actions, err[0]);
    std::vector<std::string> words = {CUEPLAN_BINARY, "serve"};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    EXPECT_EQ(posix_spawn(&pid_, CUEPLAN_BINARY, &actions, nullptr, argv.data(), environ), 0);
    posix_spawn_file_actions_destroy(&actions);
    ::close(out[1]);
    ::close(err[1]);
    out_ = out[0];
    err_ = err[0];
  }
  ~ServeProcess() {
    if (pid_ > 0 && !exited_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    ::close(out_);
    ::close(err_);
  }
  // The first line on stdout, within `seconds`.
  std::string first_line(double seconds) {
    std::string line;
    const auto deadline = Clock::now() + std::chrono::duration<double>(seconds);
    while (Clock::now() < deadline) {
      pollfd p{out_, POLLIN, 0};
      if (::poll(&p, 1, 50) <= 0) continue;
      char c = 0;
      if (::read(out_, &c, 1) != 1) break;
      if (c == '\n') return line;
      line += c;
    }
    return line;
  }
  // Waits up to `seconds` for the exit; its code, or -1 if it did not exit.
  int wait(double seconds) {
    const auto deadline = Clock::now() + std::chrono::duration<double>(seconds);
    while (Clock::now() < deadline) {
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        exited_ = true;
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return -1;
  }
  std::string rest_of_stderr() {
    std::string text;
    char buf[4096];
    for (ssize_t n; (n = ::read(err_, buf, sizeof buf)) > 0;) text.append(buf, static_cast<size_t>(n));
    return text;
  }
  pid_t pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
  int out_ = -1, err_ = -1;
  bool exited_ = false;
};

int port_in(const std::string& line) {
  std::smatch m;
  return std::regex_search(line, m, std::regex(R"(http://127\.0\.0\.1:(\d+)/)")) ? std::stoi(m[1]) : 0;
}

TEST(ServeCommand, PrintsItsAddressAndStopsCleanlyOnCtrlCAfterTheRequestInFlight) {
  ServeProcess serve({"--port", "0", "--method", "exact", "--threads", "1", "--max-time", "1.5",
                      "--table-cache", (scratch() / "cache").string()});
  const std::string line = serve.first_line(20);
  const int port = port_in(line);
  ASSERT_GT(port, 0) << line;
  EXPECT_NE(line.find("in a browser"), std::string::npos) << line;
  httplib::Client c("127.0.0.1", port);
  c.set_read_timeout(30);
  ASSERT_EQ(answer_of(c.Get("/api/health")).status, 200);
  // A search the clock ends is running when Ctrl-C comes: it is answered, then the
  // server stops.
  Answer in_flight;
  std::thread request([&] {
    httplib::Client mine("127.0.0.1", port);
    mine.set_read_timeout(30);
    in_flight = answer_of(mine.Post(
        "/api/solve",
        json{{"problem", kSmallProblem},
             {"options", {{"max_evaluations", 200000}, {"max_time", 1.5}, {"samples", 10}}}}
            .dump(),
        "application/json"));
  });
  const Clock::time_point deadline = Clock::now() + std::chrono::seconds(10);
  while (answer_of(c.Get("/api/health")).body["busy"] != 1 && Clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_EQ(::kill(serve.pid(), SIGINT), 0);
  request.join();
  EXPECT_EQ(in_flight.status, 200) << in_flight.raw;
  EXPECT_EQ(serve.wait(15), 0);
  const std::string err = serve.rest_of_stderr();
  EXPECT_NE(err.find("stopping (SIGINT)"), std::string::npos) << err;
  EXPECT_NE(err.find("cueplan serve: stopped"), std::string::npos) << err;
  // Nobody listens any more.
  httplib::Client after("127.0.0.1", port);
  after.set_connection_timeout(1);
  EXPECT_FALSE(after.Get("/api/health"));
}

TEST(ServeCommand, StopsOnSigtermAndWhileATableIsStillBeingBuilt) {
  // A fresh cache: the real table for the snooker cushion starts building at once and
  // takes far longer than this test waits.
  ServeProcess serve({"--port", "0", "--table-cache", (scratch() / "empty-cache").string()});
  const int port = port_in(serve.first_line(20));
  ASSERT_GT(port, 0);
  httplib::Client c("127.0.0.1", port);
  const Answer health = answer_of(c.Get("/api/health"));
  ASSERT_EQ(health.status, 200);
  EXPECT_EQ(health.body["impact_tables_ready"], false);
  ASSERT_EQ(::kill(serve.pid(), SIGTERM), 0);
  EXPECT_EQ(serve.wait(10), 0);
  const std::string err = serve.rest_of_stderr();
  EXPECT_NE(err.find("stopping (SIGTERM)"), std::string::npos) << err;
  EXPECT_NE(err.find("still being made"), std::string::npos) << err;
}

TEST(ServeCommand, ATakenPortAndBadFlagsAreReported) {
  TestServer server;
  // (As a process that may be ended: were the port shared, it would serve for ever.)
  ServeProcess taken({"--method", "exact", "--port", std::to_string(server.port())});
  EXPECT_EQ(taken.wait(20), 1);
  const std::string err = taken.rest_of_stderr();
  EXPECT_NE(err.find("cannot listen on 127.0.0.1 port"), std::string::npos) << err;
  for (const auto& [flags, words] :
       std::vector<std::pair<std::string, std::string>>{{"--port 70000", "--port must be 0 to 65535"},
                                                        {"--threads -1", "--threads"},
                                                        {"--method paper", "--method must be table or exact"},
                                                        {"--max-time 0", "--max-time"},
                                                        {"--max-grid 2", "--max-grid"}}) {
    const ProcessResult run = cueplan("serve " + flags, flags);
    EXPECT_EQ(run.exit_code, 2) << flags;
    EXPECT_EQ(lines_of(run.err).size(), 1u) << run.err;
    EXPECT_NE(run.err.find(words), std::string::npos) << run.err;
  }
}

}  // namespace
}  // namespace cli_test
