// `solve`'s result as JSON.
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

nlohmann::ordered_json solve_json(const prob::Problem& problem,
                const plan::PlannerOptions& options, const plan::PlanResult& r,
                const std::string& svg_file) {
  ordered_json j;
  j["problem"] = {{"name", problem.name}, {"source", problem.source}};
  j["status"] = plan::to_string(r.status);
  j["message"] = r.message;
  const ordered_json best = planned_json(problem, r.best, options.enforce_rigid_limit);
  for (const auto& [key, value] : best.items()) j[key] = value;
  j["evaluations"] = r.evaluations;
  j["time_s"] = r.time_s;
  j["local_searches"] = r.local_searches;
  j["converged_searches"] = r.converged_searches;
  ordered_json alternatives = ordered_json::array();
  for (const plan::PlannedShot& a : r.alternatives)
    alternatives.push_back(planned_json(problem, a, options.enforce_rigid_limit));
  j["alternatives"] = alternatives;
  // Kicks, banks and escapes: the best stroke's route in words, each alternative's in its
  // entry, and the route families with no clear route.
  j["route_words"] = r.best.route_words;
  for (size_t i = 0; i < r.alternatives.size(); ++i)
    j["alternatives"][i]["route_words"] = r.alternatives[i].route_words;
  j["ruled_out"] = r.ruled_out;
  if (r.best.opponent_pot) j["opponent_pot"] = *r.best.opponent_pot;
  j["target"] = problem.has_target ? point_json(problem.target) : ordered_json();
  j["tolerance"] = problem.tolerance;
  j["cue_ball"] = point_json(problem.cue_ball);
  j["options"] = {{"global", plan::to_string(options.global)},
                  {"local", plan::to_string(options.local)},
                  {"max_evaluations", options.max_evaluations},
                  {"max_time_s", options.max_time_s},
                  {"starts", options.local_starts},
                  {"seed", options.seed},
                  {"robust", options.robust},
                  {"noise",
                   {{"scale", options.noise.scale},
                    {"aim_deg", options.noise.aim_deg},
                    {"speed", options.noise.speed},
                    {"tip_offset", options.noise.tip_offset},
                    {"tip_offset_relative", options.noise.tip_offset_relative},
                    {"squirt_judgement", options.noise.squirt_judgement},
                    {"bridge_length", options.noise.bridge_length}}},
                  {"samples", options.robustness_samples},
                  {"enforce_rigid_limit", options.enforce_rigid_limit},
                  {"alternatives", options.max_alternatives},
                  {"method", phys::to_string(options.simulation.impact_method)},
                  {"impact_accuracy", options.simulation.impact_accuracy}};
  if (!svg_file.empty()) j["svg"] = svg_file;
  j["units"] = {{"frame",
                 "table: origin where the cushion noses x = 0 and y = 0 meet, x along the "
                 "length, y along the width"},
                {"speed", "m/s"},
                {"aim_deg", "deg from +x, counter-clockwise"},
                {"topspin_k", "k_T = w_T R / V (1: natural roll, < 0: draw)"},
                {"sidespin_k", "k_S = w_S R / V, > 0 right spin"},
                {"tip_offset", "d / R, the cue tip's offset from centre (k = 2.5 d / R)"},
                {"final_position", "m"},
                {"miss_distance", "m"},
                {"success_probability", "fraction of noisy strokes, 0..1 (= success.both.p)"},
                {"success",
                 "fractions of noisy strokes, 0..1: p with its 95 % Wilson interval [low, high] "
                 "over `samples` strokes; position is given the pot (all strokes without one); "
                 "next (problems with next): the mean P(next pot) from the landings of the "
                 "strokes that pot, its interval widened by the position field's allowance"},
                {"next", "position play: ball, pocket, p (P(next pot) from the landing), cut_deg, "
                         "distance_m (m, cue ball to the next ball), zone_area_m2 (m^2), in_zone"},
                {"time_s", "s"},
                {"max_cushion_normal_speed", "m/s"},
                {"noise", "standard deviations: aim deg, speed m/s, tip_offset m"}};
  return j;
}

}  // namespace cueplan::api
