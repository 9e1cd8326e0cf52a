// serve_colour_reference: the colours `cueplan spinmap` gives a spin map's cells, for the
// page test (serve_page_test.py) to hold the page's own colour scale against.
//
// stdin:  {"tolerance": m, "cells": [{"kind": ..., "miss_distance": m or null}, ...]}, the
//         cells as /api/spinmap gives them (kind: at_rest_allowed_cushions, ...).
// stdout: {"near_mm", "far_mm", "colours": ["#rrggbb", ...]}, one colour for each cell of
//         kind at_rest_allowed_cushions, in order, from cueplan/draw/spin_map.hpp's
//         miss_colour_scale and MissColourScale::colour.
#include <cmath>
#include <iostream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "cueplan/planner/spin_map.hpp"
#include "cueplan/problems/problem.hpp"
#include "cueplan/draw/spin_map.hpp"

int main() {
  namespace phys = cueplan::physics;
  using nlohmann::json;
  const std::string input((std::istreambuf_iterator<char>(std::cin)), std::istreambuf_iterator<char>());
  const json query = json::parse(input);

  // A problem that allows exactly one cushion: a cell's kind becomes an outcome and a
  // cushion count that classify() puts back in that kind.
  cueplan::problems::Problem problem;
  problem.tolerance = query.at("tolerance").get<double>();
  problem.limits.cushions_min = 1;
  problem.limits.cushions_max = 1;
  cueplan::planner::SpinMap map;
  for (const json& cell : query.at("cells")) {
    cueplan::planner::SpinMapPoint p;
    const std::string kind = cell.at("kind").get<std::string>();
    p.cushion_hits = kind == "at_rest_other_cushions" ? 0 : 1;
    p.outcome = kind == "pocketed"       ? phys::ShotStatus::pocketed
                : kind == "hit_obstacle" ? phys::ShotStatus::hit_obstacle
                : kind == "no_outcome"   ? phys::ShotStatus::event_limit
                                         : phys::ShotStatus::rest;
    p.miss_distance = cell.at("miss_distance").is_number() ? cell["miss_distance"].get<double>()
                                                           : INFINITY;
    map.points.push_back(p);
  }
  const cueplan::draw::MissColourScale scale = cueplan::draw::miss_colour_scale(map, problem);
  json colours = json::array();
  for (const cueplan::planner::SpinMapPoint& p : map.points)
    if (cueplan::draw::classify(p, problem.limits) == cueplan::draw::SpinCellKind::distance)
      colours.push_back(scale.colour(p.miss_distance).to_hex());
  std::cout << json{{"near_mm", scale.near_mm}, {"far_mm", scale.far_mm}, {"colours", colours}}
            << '\n';
  return 0;
}
