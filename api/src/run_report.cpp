// `run`'s result as JSON.
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

ordered_json run_json(const prob::Layout& layout, const prob::GameState& start,
                      const plan::RunoutOptions& o, const plan::RunoutResult& r) {
  const prob::Problem& problem = layout.problem;
  ordered_json j;
  j["layout"] = {{"name", problem.name}, {"source", problem.source}};
  j["game"] = prob::to_string(start.game);
  if (start.game == prob::Game::eight_ball) j["group"] = prob::to_string(start.group);
  j["policy"] = plan::to_string(o.policy);
  j["lookahead"] = o.lookahead;
  ordered_json shots = ordered_json::array();
  for (const plan::RunShot& s : r.plan.shots) {
    const plan::TipOffset tip = plan::tip_offset(s.shot);
    ordered_json shot;
    shot["ball"] = s.ball;
    shot["pocket"] = s.pocket_name;
    shot["shot"] = {{"speed", s.shot.speed},
                    {"aim_deg", s.shot.aim_deg},
                    {"topspin_k", s.shot.topspin_k},
                    {"sidespin_k", s.shot.sidespin_k},
                    {"elevation_deg", s.shot.elevation_deg},
                    {"stroke", plan::describe_stroke(s.shot)},
                    {"tip_offset", {{"right", tip.right}, {"up", tip.up}}}};
    shot["success"] = estimate_json(s.pot);
    shot["start"] = point_json(s.cue_from);
    shot["final_position"] = point_json(s.cue_to);
    shot["next"] = s.next_ball.empty() ? ordered_json() : ordered_json(s.next_ball);
    shot["verdict"] = s.verdict;
    shot["route"] = s.route;
    shot["route_words"] = s.route_words;
    shot["score"] = s.score;
    shots.push_back(shot);
  }
  j["plan"] = shots;
  j["plan_clears"] = r.plan.cleared;
  j["plan_ended"] = r.plan.cleared ? ordered_json() : ordered_json(r.plan.ended);
  j["runout"] = estimate_json(r.runout);
  j["mean_potted"] = r.mean_potted;
  if (start.game == prob::Game::snooker) j["mean_break"] = r.mean_score;
  ordered_json deaths = ordered_json::array();
  for (const plan::RunDeath& d : r.deaths)
    deaths.push_back({{"shot", d.shot}, {"reason", d.reason}, {"count", d.count}});
  j["deaths"] = deaths;
  j["seed"] = o.seed;
  j["time_s"] = r.time_s;
  j["first_decision_s"] = r.decision_time_s;
  j["units"] = {{"start", "m"}, {"final_position", "m"}, {"speed", "m/s"},
                {"aim_deg", "deg from +x, counter-clockwise"},
                {"success", "P(pot and stay at the table) under the noise, 0..1"},
                {"runout", "fraction of runs played under the noise that clear, 95 % Wilson interval"}};
  return j;
}

}  // namespace cueplan::api
