// `route`'s result as JSON.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cueplan/api/options.hpp"
#include "cueplan/api/results.hpp"
#include "cueplan/api/shot_report.hpp"
#include "cueplan/api/words.hpp"
#include "cueplan/draw/spin_map.hpp"
#include "cueplan/draw/table.hpp"
#include "cueplan/physics/shot.hpp"
#include "cueplan/physics/trace.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/planner/route.hpp"
#include "cueplan/planner/runout.hpp"
#include "cueplan/planner/spin_map.hpp"
#include "cueplan/problems/game.hpp"
#include "cueplan/problems/problem.hpp"
#include "cueplan/problems/stroke_ranges.hpp"

namespace cueplan::api {
namespace {

namespace phys = cueplan::physics;
namespace plan = cueplan::planner;
namespace prob = cueplan::problems;
using nlohmann::ordered_json;

}  // namespace

nlohmann::ordered_json route_json(const prob::Problem& problem, const plan::RouteOptions& o,
                const plan::RouteResult& r, const std::string& svg_file) {
  ordered_json j;
  j["problem"] = {{"name", problem.name}, {"source", problem.source}};
  j["status"] = plan::to_string(r.status);
  j["message"] = r.message;
  ordered_json strokes = ordered_json::array();
  for (const plan::RouteStroke& s : r.strokes) {
    ordered_json stroke;
    stroke["start"] = point_json(s.start);
    const ordered_json shot = planned_json(problem, s.planned, false);
    for (const auto& [key, value] : shot.items()) stroke[key] = value;
    stroke["zone"] = {{"centre", point_json(s.zone_centre)}, {"radius", s.zone_radius}};
    strokes.push_back(stroke);
  }
  j["strokes"] = strokes;
  j["route_success_probability"] = r.route_success_probability;
  j["time_s"] = r.time_s;
  j["time_to_first_solution_s"] =
      r.time_to_first_solution_s >= 0.0 ? ordered_json(r.time_to_first_solution_s) : ordered_json();
  j["propagations"] = r.propagations;
  j["steerings"] = r.steerings;
  j["evaluations"] = r.evaluations;
  j["tree_states"] = r.tree_states;
  j["cue_ball"] = point_json(problem.cue_ball);
  j["target"] = point_json(problem.target);
  j["tolerance"] = problem.tolerance;
  j["options"] = {{"planner", plan::to_string(o.planner)},
                  {"sampler", plan::to_string(o.sampler)},
                  {"max_strokes", o.max_strokes},
                  {"max_time_s", o.max_time_s},
                  {"first", o.stop_at_first_solution},
                  {"seed", o.seed},
                  {"steer_evaluations", o.steer_evaluations},
                  {"noise",
                   {{"scale", o.noise.scale},
                    {"aim_deg", o.noise.aim_deg},
                    {"speed", o.noise.speed},
                    {"tip_offset", o.noise.tip_offset},
                    {"tip_offset_relative", o.noise.tip_offset_relative},
                    {"squirt_judgement", o.noise.squirt_judgement},
                    {"bridge_length", o.noise.bridge_length}}},
                  {"samples", o.robustness_samples},
                  {"intermediate_zone_m", o.intermediate_zone_m}};
  if (!svg_file.empty()) j["svg"] = svg_file;
  j["units"] = {{"frame",
                 "table: origin where the cushion noses x = 0 and y = 0 meet, x along the "
                 "length, y along the width"},
                {"start", "m"},
                {"final_position", "m"},
                {"miss_distance", "m from the problem's target"},
                {"zone", "m: the circle each stroke's success_probability is judged by"},
                {"speed", "m/s"},
                {"aim_deg", "deg from +x, counter-clockwise"},
                {"success_probability", "fraction of noisy strokes, 0..1"},
                {"time_s", "s"}};
  return j;
}

}  // namespace cueplan::api
