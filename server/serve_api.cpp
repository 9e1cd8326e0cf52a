#include "serve_api.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/planner/position.hpp"
#include "cueplan/planner/runout.hpp"
#include "cueplan/problems/game.hpp"
#include "cueplan/planner/spin_map.hpp"
#include "cueplan/problems/stroke_ranges.hpp"
#include "cueplan/api/field_names.hpp"
#include "cueplan/api/impact.hpp"
#include "cueplan/api/options.hpp"
#include "cueplan/api/request_options.hpp"
#include "cueplan/api/results.hpp"
#include "cueplan/api/stroke.hpp"

namespace cueplan::server {
using namespace cueplan::api;  // the api's types and checks, as the server's own
namespace {

using api::InputError;
using api::SearchInputs;
using api::SearchLimits;
using api::json_number;
using api::json_whole;
using api::json_seed;
using api::json_bool;
using api::json_text;
using api::json_at_most;
using api::check_request_option_keys;
using api::request_option_names;
using api::search_simulation;
using api::search_planner_options;

namespace phys = cueplan::physics;
namespace plan = cueplan::planner;
namespace prob = cueplan::problems;
using nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

constexpr int kRetryWhileTableIsMade = 5;  // s
const int kDefaultGrid = kDefaultSpinmapGrid;

// A request that stops short: the reply to send.
struct Stop {
  ApiReply reply;
};

Stop bad(const std::string& field, const std::string& message) {
  return {error_reply(400, message, field)};
}

std::string listed(std::initializer_list<const char*> keys) {
  std::string text;
  for (const char* k : keys) text += (text.empty() ? "" : ", ") + std::string(k);
  return text;
}

std::string dotted(const std::string& prefix, const std::string& key) {
  return prefix.empty() ? key : prefix + "." + key;
}

// The body as a JSON object. A number beyond a double's range (1e400) is refused naming
// the field it was given for, as any other bad value.
ordered_json parse_body(std::string_view body) {
  ordered_json j;
  std::vector<std::string> path;  // the keys down to the value being read
  std::string last_key;
  const auto track = [&](int /*depth*/, ordered_json::parse_event_t event, ordered_json& parsed) {
    using E = ordered_json::parse_event_t;
    if (event == E::key) last_key = parsed.get<std::string>();
    if (event == E::object_start) {
      path.push_back(last_key);
      last_key.clear();
    }
    if (event == E::object_end && !path.empty()) path.pop_back();
    if (event == E::value || event == E::object_end || event == E::array_end) last_key.clear();
    return true;
  };
  try {
    j = ordered_json::parse(body, track);
  } catch (const ordered_json::parse_error& e) {
    std::string what = e.what();
    // "[json.exception.parse_error.101] parse error at line 1, ..." without the tag.
    if (const size_t tag = what.find("] "); what.rfind("[json.exception", 0) == 0 &&
                                             tag != std::string::npos)
      what.erase(0, tag + 2);
    throw bad("", "the request body is not JSON: " + what);
  } catch (const ordered_json::exception& e) {
    // out_of_range.406: "number overflow parsing '1e400'".
    std::string field;
    for (const std::string& key : path)
      if (!key.empty()) field += (field.empty() ? "" : ".") + key;
    if (!last_key.empty()) field += (field.empty() ? "" : ".") + last_key;
    std::string what = e.what();
    if (const size_t tag = what.find("] "); tag != std::string::npos) what.erase(0, tag + 2);
    throw bad(field, (field.empty() ? std::string("a number") : field) +
                         " is out of range (" + what + "); numbers must lie within a double's "
                         "range and mean something physical");
  }
  if (!j.is_object())
    throw bad("", "the request body must be a JSON object, such as {\"problem\": {...}}");
  return j;
}

// Every key of `object` is one of `keys`; otherwise the first that is not.
void check_keys(const ordered_json& object, std::initializer_list<const char*> keys,
                const std::string& prefix) {
  for (const auto& [key, value] : object.items())
    if (std::none_of(keys.begin(), keys.end(), [&](const char* k) { return key == k; }))
      throw bad(dotted(prefix, key), "unknown field '" + dotted(prefix, key) + "'; " +
                                         (prefix.empty() ? "the request's" : prefix + "'s") +
                                         " fields are " + listed(keys));
}

// Typed reads of one field; each names the field when the value has the wrong type.
const ordered_json* member(const ordered_json& object, const char* key) {
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

double read_number(const ordered_json& v, const std::string& field, const char* unit) {
  return json_number(v, field, unit);
}
int read_whole(const ordered_json& v, const std::string& field) { return json_whole(v, field); }
uint64_t read_seed(const ordered_json& v, const std::string& field) { return json_seed(v, field); }
bool read_bool(const ordered_json& v, const std::string& field) { return json_bool(v, field); }
std::string read_text(const ordered_json& v, const std::string& field) { return json_text(v, field); }
void at_most(int value, int most, const std::string& field) { json_at_most(value, most, field); }

const ordered_json& options_of(const ordered_json& request) {
  static const ordered_json kNone = ordered_json::object();
  const ordered_json* options = member(request, "options");
  if (options == nullptr) return kNone;
  if (!options->is_object())
    throw bad("options", "options must be an object, such as {\"seed\": 7}, got " + options->dump());
  return *options;
}

// A reply's `warnings`: what is implausible in the problem's limits and the stroke.
void add_warnings(ApiReply& reply, const prob::Problem& problem,
                  const std::vector<std::string>& more = {}) {
  std::vector<std::string> all;
  for (const std::string& w : prob::problem_warnings(problem)) all.push_back("problem." + w);
  all.insert(all.end(), more.begin(), more.end());
  if (!all.empty()) reply.body["warnings"] = all;
}

prob::Problem read_problem(const ordered_json& request) {
  const ordered_json* value = member(request, "problem");
  if (value == nullptr)
    throw bad("problem", "problem is required: the problem file's fields as an object, such as "
                         "{\"cue_ball\": [0.8, 0.5], \"target\": [2.6, 1.2]}");
  ProblemFromJson loaded = problem_from_json(*value, "problem");
  if (!loaded.problem) throw bad(loaded.error.field, loaded.error.message);
  return std::move(*loaded.problem);
}

// The planner's and the impact method's options of a request: the api's reader
// (cueplan/api/request_options.hpp), under this server's limits.
SearchInputs read_search_options(const ordered_json& options, const std::string& default_method,
                                 const ApiLimits& limits) {
  const SearchLimits bounds{limits.max_time_s, limits.max_evaluations, limits.max_starts,
                            limits.max_samples, limits.max_alternatives};
  return api::read_search_options(options, default_method, bounds);
}

phys::SimulationOptions read_impact(const ImpactArgs& impact) {
  SearchInputs in;
  in.impact = impact;
  return search_simulation(in);
}

plan::PlannerOptions read_planner(const SearchInputs& in,
                                  const phys::SimulationOptions& simulation) {
  // One thread a request: the server's concurrency is its worker pool. The answer does
  // not depend on it (planner.hpp) while the evaluation budget ends the search.
  return search_planner_options(in, 1, simulation);
}

// A library's field (planner options, spin map options, the shot, the problem) as the
// request names it.
std::string request_field(const phys::FieldPath& path) {
  // The options', as the request names them.
  if (const std::string option = name_of(path, request_option_names()); option != path.text()) return option;
  static const std::initializer_list<FieldName> kNames = {
      {{"max_events"}, "options.max_events"},
      {{"speed"}, "speed"},
      {{"aim_deg"}, "aim_deg"},
      {{"grid"}, "grid"},
      {{"shot", "speed"}, "stroke.speed"},
      {{"shot", "aim_deg"}, "stroke.aim_deg"},
      {{"shot", "topspin_k"}, "stroke.topspin_k"},
      {{"shot", "sidespin_k"}, "stroke.sidespin_k"},
  };
  const std::string named = name_of(path, kNames);
  if (named != path.text()) return named;
  static const char* kProblemFields[] = {"scene", "cue_ball", "target", "tolerance", "limits"};
  const auto* head = path.empty() ? nullptr : std::get_if<std::string>(&path.steps()[0]);
  if (head && std::find(std::begin(kProblemFields), std::end(kProblemFields), *head) !=
                  std::end(kProblemFields))
    return "problem." + prob::file_field(path);
  return path.text();
}

Stop library_error(const std::optional<phys::ValidationError>& error, const std::string& message) {
  if (!error) return bad("", message);
  const std::string field = request_field(error->field);
  return bad(field, error->message(field, error->other ? request_field(*error->other) : ""));
}

ordered_json time_note(const SearchInputs& in, const ApiLimits& limits) {
  return in.time_clamped ? ordered_json(fmt::format("options.max_time was clamped to this "
                                                    "server's maximum, {:g} s",
                                                    limits.max_time_s))
                         : ordered_json();
}

}  // namespace

ApiReply error_reply(int status, const std::string& message, const std::string& field) {
  ApiReply r;
  r.status = status;
  r.body = {{"error", message}, {"field", field.empty() ? ordered_json() : ordered_json(field)}};
  return r;
}

Api::Api(ApiLimits limits, std::string default_method, ImpactTableStore* tables,
         std::vector<Example> examples)
    : limits_(limits),
      default_method_(std::move(default_method)),
      tables_(tables),
      examples_(std::move(examples)) {}

namespace {

// With the table method: the store's table for the problem's cushion, set in
// *simulation (and kept alive by *keep); or the reply when there is none yet.
void attach_table(ImpactTableStore& tables, const prob::Problem& problem, bool accuracy_given,
                  phys::SimulationOptions* simulation,
                  std::shared_ptr<const phys::ImpactTable>* keep) {
  if (simulation->impact_method != phys::ImpactMethod::table) return;
  const ImpactTableStore::Lookup found = tables.find(problem.scene.ball_and_cushion);
  if (found.state == ImpactTableStore::State::ready) {
    *keep = found.table;
    use_impact_table(**keep, problem.scene, accuracy_given, simulation);
    return;
  }
  const std::string instead = "; or ask for \"options\": {\"method\": \"exact\"}";
  if (found.refused) throw bad("options.method", found.message + instead);
  if (found.state == ImpactTableStore::State::failed)
    throw Stop{error_reply(500, "the impact table for this problem's cushion: " + found.message +
                                    instead,
                           "options.method")};
  Stop wait{error_reply(503,
                        "the impact table for this problem's cushion is not ready yet (" +
                            found.message + "); ask again in a few seconds" + instead,
                        "options.method")};
  wait.reply.body["impact_table"] = to_string(found.state);
  wait.reply.body["retry_after_s"] = kRetryWhileTableIsMade;
  wait.reply.retry_after_s = kRetryWhileTableIsMade;
  throw wait;
}

// Runs one endpoint: a Stop thrown anywhere inside becomes its reply.
template <class Body>
ApiReply answer(Body&& body) {
  try {
    return body();
  } catch (const Stop& stop) {
    return stop.reply;
  } catch (const InputError& e) {  // the api's readers and validator: the field it names
    return error_reply(400, e.what(), e.field());
  }
}

}  // namespace

namespace {

// Position play: the next pot's field over the cloth, for the page to shade (as `cueplan
// zone` draws it): P(next pot), with a list the look-ahead's worth, in each cell of the
// field's grid, rounded to 0.001; row-major from y = 0, cell (i, j) centred at
// ((i + 0.5) cell, (j + 0.5) cell); the zone is where the value is at least `threshold`.
ordered_json zone_json(const prob::Problem& problem, const plan::PositionField& f) {
  ordered_json values = ordered_json::array();
  for (int j = 0; j < f.rows(); ++j)
    for (int i = 0; i < f.columns(); ++i) values.push_back(std::round(1000.0 * f.cell_value(i, j)) / 1000.0);
  const prob::NextPot& next = problem.next.front();
  return {{"ball", next.ball},
          {"pocket", prob::pocket_name(problem.scene, next.pocket)},
          {"cell", f.cell()},
          {"columns", f.columns()},
          {"rows", f.rows()},
          {"values", values},
          {"threshold", f.zone_threshold()},
          {"best_p", f.best_value()},
          {"best", {f.best().x, f.best().y}},
          {"area_m2", f.zone_area_m2()}};
}

}  // namespace

ApiReply Api::solve(std::string_view body) const {
  return answer([&] {
    const ordered_json request = parse_body(body);
    check_keys(request, {"problem", "options"}, "");
    const SearchInputs in = read_search_options(options_of(request), default_method_, limits_);
    phys::SimulationOptions simulation = read_impact(in.impact);
    plan::PlannerOptions options = read_planner(in, simulation);
    const prob::Problem problem = read_problem(request);

    std::shared_ptr<const phys::ImpactTable> table;
    attach_table(*tables_, problem, in.accuracy_given, &simulation, &table);
    options.simulation = simulation;

    const plan::PlanResult result = plan::plan(problem, options);
    if (result.status == plan::PlanStatus::invalid_input)
      throw library_error(result.error, result.message);
    ApiReply reply;
    reply.body = solve_json(problem, options, result, "");
    if (result.position_field && !problem.next.empty())
      reply.body["zone"] = zone_json(problem, *result.position_field);
    if (in.time_clamped) reply.body["note"] = time_note(in, limits_);
    add_warnings(reply, problem);
    return reply;
  });
}

ApiReply Api::simulate(std::string_view body) const {
  return answer([&] {
    const ordered_json request = parse_body(body);
    check_keys(request, {"problem", "stroke", "options"}, "");
    const ordered_json& options = options_of(request);
    check_request_option_keys(options, {"method", "accuracy", "max_events"});
    ImpactArgs impact;
    impact.method = kShotImpactMethod;
    phys::SimulationOptions simulation;
    bool accuracy_given = false;
    for (const auto& [key, v] : options.items()) {
      const std::string field = "options." + key;
      if (key == "method") impact.method = read_text(v, field);
      if (key == "accuracy") {
        impact.accuracy = read_number(v, field, nullptr);
        accuracy_given = true;
      }
      if (key == "max_events") {
        simulation.max_events = read_whole(v, field);
        if (simulation.max_events < 1)
          throw bad(field, field + " must be at least 1, got " + v.dump());
        at_most(simulation.max_events, limits_.max_events, field);
      }
    }
    const int max_events = simulation.max_events;
    impact_options(impact, request_option_names(), &simulation);
    simulation.max_events = max_events;

    const ordered_json* stroke = member(request, "stroke");
    if (stroke == nullptr || !stroke->is_object())
      throw bad("stroke", "stroke is required: an object {speed (m/s), aim_deg (deg from +x), "
                          "topspin_k, sidespin_k, elevation_deg}");
    check_keys(*stroke, {"speed", "aim_deg", "topspin_k", "sidespin_k", "elevation_deg"},
               "stroke");
    phys::Shot shot{NAN, NAN, 0.0, 0.0};
    for (const char* required : {"speed", "aim_deg"})
      if (member(*stroke, required) == nullptr)
        throw bad(std::string("stroke.") + required,
                  std::string("stroke.") + required + " is required (" +
                      (std::string(required) == "speed" ? "m/s" : "deg from +x") + ")");
    shot.speed = read_number(stroke->at("speed"), "stroke.speed", "m/s");
    shot.aim_deg = read_number(stroke->at("aim_deg"), "stroke.aim_deg", "deg");
    if (const ordered_json* k = member(*stroke, "topspin_k"))
      shot.topspin_k = read_number(*k, "stroke.topspin_k", nullptr);
    if (const ordered_json* k = member(*stroke, "sidespin_k"))
      shot.sidespin_k = read_number(*k, "stroke.sidespin_k", nullptr);
    if (const ordered_json* e = member(*stroke, "elevation_deg"))
      shot.elevation_deg = read_number(*e, "stroke.elevation_deg", "deg");
    constexpr ShotNames kStrokeNames = {"stroke.speed", "stroke.aim_deg", "stroke.topspin_k",
                                        "stroke.sidespin_k", "stroke.elevation_deg"};
    if (std::string why = check_shot_inputs(shot, kStrokeNames); !why.empty()) {
      std::string field = "stroke";
      for (const char* name : {kStrokeNames.speed, kStrokeNames.aim, kStrokeNames.topspin,
                               kStrokeNames.sidespin, kStrokeNames.elevation})
        if (why.rfind(std::string(name) + " ", 0) == 0) field = name;
      throw bad(field, why);
    }
    const std::vector<std::string> warnings = shot_warnings(shot, kStrokeNames);
    const prob::Problem problem = read_problem(request);

    std::shared_ptr<const phys::ImpactTable> table;
    attach_table(*tables_, problem, accuracy_given, &simulation, &table);
    const phys::ShotResult result =
        phys::simulate(problem.scene, problem.cue_ball, shot, simulation);
    if (result.status == phys::ShotStatus::invalid_input)
      throw library_error(result.error, result.message);
    ApiReply reply;
    reply.body = simulate_json(problem, shot, simulation, result, "");
    add_warnings(reply, problem, warnings);
    return reply;
  });
}

namespace {

// The spins a grid holds inside its disc (the spin map's points): (i, j) with
// (2i - n + 1)^2 + (2j - n + 1)^2 <= (n - 1)^2.
size_t disc_point_count(int grid) {
  size_t count = 0;
  const long n = grid;
  for (long i = 0; i < n; ++i)
    for (long j = 0; j < n; ++j) {
      const long a = 2 * i - (n - 1), b = 2 * j - (n - 1);
      count += a * a + b * b <= (n - 1) * (n - 1);
    }
  return count;
}

}  // namespace

ApiReply Api::spinmap(std::string_view body) const {
  const Clock::time_point started = Clock::now();
  return answer([&] {
    const ordered_json request = parse_body(body);
    check_keys(request,
               {"problem", "speed", "aim_deg", "grid", "options", "success", "samples",
                "success_from", "success_count"},
               "");
    const ordered_json* speed = member(request, "speed");
    const ordered_json* aim = member(request, "aim_deg");
    if ((speed == nullptr) != (aim == nullptr))
      throw bad(speed ? "aim_deg" : "speed",
                std::string(speed ? "aim_deg" : "speed") + " is required with " +
                    (speed ? "speed" : "aim_deg") +
                    ": give both, or neither to use the planner's best stroke");
    const bool stroke_given = speed != nullptr;
    double v = NAN, aim_deg = NAN;
    if (stroke_given) {
      v = read_number(*speed, "speed", "m/s");
      aim_deg = read_number(*aim, "aim_deg", "deg");
      const prob::StrokeRangeCheck ranges = prob::check_stroke_ranges(
          phys::Shot{v, aim_deg, 0.0, 0.0}, {"speed", "aim_deg", nullptr, nullptr, nullptr});
      if (!ranges.ok()) throw bad(ranges.field, ranges.error);
    }
    int grid = kDefaultGrid;
    if (const ordered_json* g = member(request, "grid")) {
      grid = read_whole(*g, "grid");
      if (grid < 3 || grid > limits_.max_grid)
        throw bad("grid", fmt::format("grid must be 3 to {} points across the disc on this "
                                      "server, got {}",
                                      limits_.max_grid, grid));
    }
    const SearchInputs in = read_search_options(options_of(request), default_method_, limits_);
    // How forgiving each spin is, on request: `samples` noisy strokes for each of the
    // cells [success_from, success_from + success_count) in the map's order.
    bool success = false;
    if (const ordered_json* f = member(request, "success")) success = read_bool(*f, "success");
    for (const char* key : {"samples", "success_from", "success_count"})
      if (!success && member(request, key))
        throw bad(key, std::string(key) + " is given only with success: true");
    int samples = kDefaultSuccessSamples;
    size_t success_from = 0, success_count = 0;
    if (success) {
      if (const ordered_json* n = member(request, "samples")) {
        samples = read_whole(*n, "samples");
        if (samples < 1 || samples > limits_.max_success_samples)
          throw bad("samples", fmt::format("samples must be 1 to {} noisy strokes a spin on this "
                                           "server, got {}",
                                           limits_.max_success_samples, samples));
      }
      const size_t cells = disc_point_count(grid);
      if (const ordered_json* n = member(request, "success_from")) {
        const int from = read_whole(*n, "success_from");
        if (from < 0 || static_cast<size_t>(from) >= cells)
          throw bad("success_from", fmt::format("success_from must be 0 to {} (the grid's {} "
                                                "spins), got {}",
                                                cells - 1, cells, from));
        success_from = static_cast<size_t>(from);
      }
      success_count = cells - success_from;
      if (const ordered_json* n = member(request, "success_count")) {
        const int count = read_whole(*n, "success_count");
        if (count < 1) throw bad("success_count", fmt::format("success_count must be at least 1, got {}", count));
        success_count = std::min(success_count, static_cast<size_t>(count));
      }
      if (static_cast<double>(samples) * static_cast<double>(success_count) >
          limits_.max_success_strokes)
        throw bad("success_count",
                  fmt::format("samples x success_count must be at most {} noisy strokes in one "
                              "request on this server, got {} x {}: ask for the cells in parts",
                              limits_.max_success_strokes, samples, success_count));
      if (!std::isfinite(in.planner.noise) || in.planner.noise < 0.0 || in.planner.noise > 10.0)
        throw bad("options.noise",
                  fmt::format("options.noise must be 0 to 10 (times a club player's scatter), "
                              "got {}",
                              in.planner.noise));
    }
    phys::SimulationOptions simulation = read_impact(in.impact);
    plan::PlannerOptions planner_options;
    if (!stroke_given) planner_options = read_planner(in, simulation);
    const prob::Problem problem = read_problem(request);

    std::shared_ptr<const phys::ImpactTable> table;
    attach_table(*tables_, problem, in.accuracy_given, &simulation, &table);
    planner_options.simulation = simulation;

    StrokeSource source;
    if (!stroke_given) {
      source.planned = true;
      source.plan = plan::plan(problem, planner_options);
      if (source.plan.status == plan::PlanStatus::invalid_input)
        throw library_error(source.plan.error, source.plan.message);
      v = source.plan.best.shot.speed;
      aim_deg = source.plan.best.shot.aim_deg;
    }
    plan::SpinMapOptions map_options;
    map_options.grid = grid;
    map_options.threads = 1;  // as solve: the worker pool is the server's concurrency
    map_options.simulation = simulation;
    if (success) {
      map_options.success_samples = samples;
      map_options.success_first = success_from;
      map_options.success_count = success_count;
      map_options.noise.scale = in.planner.noise;
      map_options.seed = in.planner.seed;
      map_options.deadline = started + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(limits_.max_time_s));
    }
    const plan::SpinMap map = plan::spin_map(problem, v, aim_deg, map_options);
    if (!map.message.empty()) throw library_error(map.error, map.message);
    if (map.points.empty()) throw Stop{error_reply(422, "no spin lies within the disc", "grid")};

    const double seconds = std::chrono::duration<double>(Clock::now() - started).count();
    ApiReply reply;
    reply.body = spinmap_json(problem, map, source, simulation, "", seconds);
    reply.body["cells"] = spinmap_cells_json(problem, map);
    if (success) {
      reply.body["success"]["from"] = success_from;
      reply.body["success"]["count"] = success_count;
      reply.body["success"]["noise"] = in.planner.noise;
      reply.body["success"]["seed"] = in.planner.seed;
    }
    if (in.time_clamped && !stroke_given) reply.body["note"] = time_note(in, limits_);
    add_warnings(reply, problem,
                 prob::check_stroke_ranges(phys::Shot{v, aim_deg, 0.0, 0.0},
                                           {"speed", "aim_deg", nullptr, nullptr, nullptr})
                     .warnings);
    return reply;
  });
}

ApiReply Api::examples() const {
  ordered_json list = ordered_json::array();
  for (const Example& e : examples_)
    list.push_back({{"name", e.name},
                    {"file", e.file},
                    {"problem", e.problem},
                    {"scene", scene_json(e.loaded)}});
  ApiReply reply;
  reply.body = {{"examples", list}};
  return reply;
}

ApiReply Api::health(int workers, int busy) const {
  ApiReply reply;
  ordered_json tables = tables_->json();
  bool ready = default_method_ != "table" || !tables.empty();
  for (const ordered_json& t : tables) ready = ready && t["state"] == "ready";
  reply.body = {{"status", "ok"},
                {"version", CUEPLAN_VERSION},
                {"workers", workers},
                {"busy", busy},
                {"default_method", default_method_},
                {"impact_tables_ready", ready},
                {"impact_tables", tables},
                {"limits",
                 {{"max_time_s", limits_.max_time_s},
                  {"max_evaluations", limits_.max_evaluations},
                  {"max_starts", limits_.max_starts},
                  {"max_samples", limits_.max_samples},
                  {"max_alternatives", limits_.max_alternatives},
                  {"max_grid", limits_.max_grid},
                  {"max_success_samples", limits_.max_success_samples},
                  {"max_success_strokes", limits_.max_success_strokes},
                  {"max_events", limits_.max_events}}}};
  return reply;
}

namespace {

// Runs under the noise one /api/run request may ask for (each re-plans every shot).
constexpr int kMostRunSamples = 200;

}  // namespace

ApiReply Api::run(std::string_view body) const {
  return answer([&] {
    const ordered_json request = parse_body(body);
    check_keys(request, {"problem", "game", "group", "options"}, "");
    const ordered_json& options = options_of(request);
    check_keys(options, {"lookahead", "policy", "samples", "seed", "noise"}, "options");
    plan::RunoutOptions o;
    o.samples = 20;
    for (const auto& [key, v] : options.items()) {
      const std::string field = "options." + key;
      if (key == "lookahead") {
        o.lookahead = read_whole(v, field);
        if (o.lookahead < 1 || o.lookahead > 5) throw bad(field, field + " must be 1 to 5, got " + v.dump());
      }
      if (key == "policy" && !plan::parse_run_policy(read_text(v, field), &o.policy))
        throw bad(field, field + " must be planner or greedy, got " + v.dump());
      if (key == "samples") {
        o.samples = read_whole(v, field);
        if (o.samples < 0) throw bad(field, field + " must be at least 0, got " + v.dump());
        at_most(o.samples, kMostRunSamples, field);
      }
      if (key == "seed") o.seed = read_seed(v, field);
      if (key == "noise") {
        o.noise.scale = read_number(v, field, nullptr);
        if (!(o.noise.scale >= 0.0)) throw bad(field, field + " must be at least 0, got " + v.dump());
      }
    }
    prob::Game game = prob::Game::any_order;
    if (const ordered_json* g = member(request, "game"))
      if (!prob::parse_game(read_text(*g, "game"), &game))
        throw bad("game", "game must be any_order, nine_ball, eight_ball or snooker, got " + g->dump());
    std::optional<prob::Group> group;
    if (const ordered_json* g = member(request, "group")) {
      prob::Group gr;
      if (!prob::parse_group(read_text(*g, "group"), &gr))
        throw bad("group", "group must be solids or stripes, got " + g->dump());
      if (game != prob::Game::eight_ball) throw bad("group", "group is for eight_ball only");
      group = gr;
    }
    // The problem's table and balls; the run chooses its own pots and positions.
    const ordered_json* value = member(request, "problem");
    if (value == nullptr || !value->is_object())
      throw bad("problem", "problem is required: the layout's fields as an object (balls, cue_ball, ...)");
    ordered_json layout = *value;
    for (const char* key : {"pot", "target", "first_contact", "tolerance"}) layout.erase(key);
    if (layout.contains("cue_ball")) layout["target"] = layout["cue_ball"];
    ProblemFromJson loaded = problem_from_json(layout, "problem");
    if (!loaded.problem) throw bad(loaded.error.field, loaded.error.message);
    prob::Problem problem = std::move(*loaded.problem);
    problem.has_target = false;
    if (problem.scene.balls.empty()) throw bad("problem.balls", "problem.balls: a run needs at least one object ball");
    if (std::string why = prob::check_game_balls(problem.scene.balls, game); !why.empty())
      throw bad("problem." + why.substr(0, why.find(':')), "problem." + why);

    const prob::GameState start = prob::initial_state(game, group);
    o.threads = 0;
    const plan::RunoutResult result = plan::plan_runout(problem, start, o);
    prob::Layout shown{problem, game, group};
    ApiReply reply;
    reply.body = run_json(shown, start, o, result);
    // Each shot as simulate's JSON, from where the balls stood: the page draws its paths.
    phys::SimulationOptions simulation;
    phys::Scene scene = problem.scene;
    prob::GameState state = start;
    phys::Vec2 cue = problem.cue_ball;
    for (size_t i = 0; i < result.plan.shots.size(); ++i) {
      const plan::RunShot& s = result.plan.shots[i];
      prob::Problem at = problem;
      at.scene = scene;
      at.cue_ball = cue;
      at.target = cue;
      const phys::ShotResult sim = phys::simulate(scene, cue, s.shot, simulation);
      reply.body["plan"][i]["simulation"] = simulate_json(at, s.shot, simulation, sim, "");
      const prob::ShotJudgement j = prob::judge_stroke(state, scene, {s.ball, s.pocket}, sim);
      if (!j.continues) break;
      state = j.next;
      scene.balls = j.balls;
      cue = sim.final_position;
    }
    return reply;
  });
}

}  // namespace cueplan::server
