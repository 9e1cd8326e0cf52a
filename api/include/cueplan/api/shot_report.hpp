// How the command line reports one planned stroke: its constraints one by one, where it
// lands, and its JSON object. Shared by `cueplan solve` (the best shot and its
// alternatives) and `cueplan route` (each stroke of a route).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::api {

// One constraint of the problem and whether the stroke meets it.
struct ConstraintRow {
  const char* name;   // speed, spin, aim, cushions, pocket, obstacle, rigid limit
  const char* key;    // the same as a JSON key: ..., rigid_limit
  const char* state;  // "ok", "broken" or "flagged" (rigid limit, not enforced)
  std::string detail;
};

// Every constraint of `problem` on the stroke `p`, each on its own row.
std::vector<ConstraintRow> constraints(const problems::Problem& problem,
                                       const planner::PlannedShot& p, bool enforce_rigid_limit);

// Where the stroke stops, in words with units: "x = 1.2 m, y = 0.4 m", or why it does not.
std::string landing_text(const planner::PlannedShot& p);

// [x, y] in m.
nlohmann::ordered_json point_json(physics::Vec2 v);

// A Monte Carlo estimate in words: "9.0 % (95 % interval 5.6-13.9 %)".
std::string estimate_text(const planner::Estimate& e);

// {p, low, high, samples}: an estimate as every command's JSON reports it.
nlohmann::ordered_json estimate_json(const planner::Estimate& e);
// {pot (pot problems only), position, both}, each an estimate_json.
nlohmann::ordered_json success_json(const planner::Success& s);
// For a pot problem, the pot and the position apart: " (pot and position); the pot alone
// P (95 % interval ...), the position given the pot P (...)"; empty without a pot.
std::string pot_success_words(const planner::Success& s);

// The pot of a planned stroke in a player's terms, as report lines (label, text): pot,
// cut, throw, pot margin.
std::vector<std::pair<std::string, std::string>> pot_lines(const planner::PotReport& pot);
// {ball, pocket, made, striker, cut_deg, cut_side, thickness, throw_deg, ghost_aim_deg,
// aim_allowance_deg, margin_m, aim_margin_deg}.
nlohmann::ordered_json pot_json(const planner::PotReport& pot);
// Position play: what the landing leaves for the next pot, as report lines (next, zone).
std::vector<std::pair<std::string, std::string>> next_lines(const planner::NextReport& next);
// {ball, pocket, p, cut_deg, cut_side, thickness, distance_m, screened_by, zone_area_m2,
// in_zone, best_p, best, landing, words}.
nlohmann::ordered_json next_json(const planner::NextReport& next);

// The stroke as `cueplan solve --json` reports a shot: shot {speed, aim_deg, topspin_k,
// sidespin_k, elevation_deg, squirt_deg}, tip_offset, stroke, outcome, final_position, miss_distance (null unless at
// rest on a problem with a target), success_probability, success, solves, cushion_hits,
// route, route_names, family, within_limits, violations, constraints,
// max_cushion_normal_speed, rigid_limit_exceeded, impact_method, failure {condition,
// reason}, and pot (pot_json) for a pot problem's stroke.
nlohmann::ordered_json planned_json(const problems::Problem& problem,
                                    const planner::PlannedShot& p, bool enforce_rigid_limit);

}  // namespace cueplan::api

// The faces (command line, server, batch) name these as their own.
namespace cueplan::cli {
using api::ConstraintRow;
using api::constraints;
using api::landing_text;
using api::point_json;
using api::estimate_text;
using api::estimate_json;
using api::success_json;
using api::pot_success_words;
using api::pot_lines;
using api::pot_json;
using api::next_lines;
using api::next_json;
using api::planned_json;
}  // namespace cueplan::cli
