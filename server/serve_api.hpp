// The JSON API of `cueplan serve`, apart from HTTP: each endpoint is a function from the
// request body to a status and a JSON body, so it can be tested and reasoned about
// without a socket. The answers are the command line's own `--json` objects
// (solve_json, simulate_json, spinmap_json), built by the same functions.
//
//   POST /api/solve     {problem, options?}                  -> cueplan solve --json, plus
//                                                               `zone` with `next`: the
//                                                               next pot's field, cell by cell
//   POST /api/simulate  {problem, stroke, options?}          -> cueplan simulate --json
//   POST /api/spinmap   {problem, speed?, aim_deg?, grid?, options?}
//                                                            -> cueplan spinmap --json, plus
//                                                               `cells`: every grid spin
//   POST /api/run       {problem, game?, group?, options?}    -> cueplan run --json, each
//                                                               plan shot with `simulation`
//                                                               (simulate's JSON, its paths)
//   GET  /api/examples  -> {examples: [{name, file, problem, scene}]}
//   GET  /api/health    -> {status, version, workers, busy, default_method, limits,
//                           impact_tables}
//
// `problem` is the problem file's fields as JSON (serve_problems.hpp). `options` are
// named as the command's flags without the dashes (max_time, max_evaluations, seed,
// samples, noise, method, ...); `stroke` is {speed, aim_deg, topspin_k, sidespin_k}.
// A bad request gets 400 and {"error": message, "field": "problem.table.length"} (the
// field as the request names it; null for the body as a whole); a search whose impact
// table is still being made gets 503 with `retry_after_s`.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "serve_problems.hpp"
#include "serve_tables.hpp"

namespace cueplan::server {
using namespace cueplan::api;  // the api's types and checks, as the server's own

// What one request may ask for. Beyond a bound a request gets 400 naming the field;
// max_time is clamped instead (the answer's options.max_time_s says what was used).
struct ApiLimits {
  double max_time_s = 20.0;       // solve's and spinmap's planner search time (s)
  int max_evaluations = 200000;   // planner shot simulations
  int max_starts = 32;
  int max_samples = 2000;         // Monte Carlo strokes per success probability
  int max_alternatives = 10;
  int max_grid = 61;              // spin map points across the disc (about 0.785 grid^2 shots)
  int max_events = 1000;          // simulate's event cap
  // The spin map's success under noise: noisy strokes per cell, and strokes in all (samples
  // times the cells asked for) in one request; a page asks for the cells in parts.
  int max_success_samples = 200;
  int max_success_strokes = 40000;
};

// An answer: the HTTP status and its JSON body.
struct ApiReply {
  int status = 200;
  nlohmann::ordered_json body;
  std::optional<int> retry_after_s;  // with 503: when to ask again
};

// A 4xx/5xx answer {"error": message, "field": field or null}.
ApiReply error_reply(int status, const std::string& message, const std::string& field = {});

class Api {
 public:
  // `default_method`: the impact method of solve and spinmap when a request names none
  // ("table" as the command line's, or "exact"). `tables` must outlive the Api.
  Api(ApiLimits limits, std::string default_method, ImpactTableStore* tables,
      std::vector<Example> examples);

  ApiReply solve(std::string_view body) const;
  ApiReply simulate(std::string_view body) const;
  ApiReply spinmap(std::string_view body) const;
  // A run-out from the problem's balls and cue ball (its pot and target ignored).
  ApiReply run(std::string_view body) const;
  ApiReply examples() const;
  // `workers`: requests computed at once; `busy`: of those, in use now.
  ApiReply health(int workers, int busy) const;

  const ApiLimits& limits() const { return limits_; }
  const std::vector<Example>& example_list() const { return examples_; }

 private:
  ApiLimits limits_;
  std::string default_method_;
  ImpactTableStore* tables_;
  std::vector<Example> examples_;
};

}  // namespace cueplan::server
