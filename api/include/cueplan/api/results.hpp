// Results to JSON, and the reports in words the faces share: one codec per result,
// used by the command line (--json and its text), the server's replies and Python.
#pragma once

#include <cmath>
#include <cstdint>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cueplan/physics/shot.hpp"
#include "cueplan/physics/trace.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/planner/route.hpp"
#include "cueplan/planner/runout.hpp"
#include "cueplan/planner/spin_map.hpp"
#include "cueplan/problems/game.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::api {

// `solve`: the plan, its best stroke and alternatives, the options and units.
nlohmann::ordered_json solve_json(const problems::Problem& problem,
                                  const planner::PlannerOptions& options,
                                  const planner::PlanResult& r, const std::string& svg_file);

// `route`: the strokes of a route and the search's counts.
nlohmann::ordered_json route_json(const problems::Problem& problem,
                                  const planner::RouteOptions& o, const planner::RouteResult& r,
                                  const std::string& svg_file);

// `run`: the planned run-out and its success under noise.
nlohmann::ordered_json run_json(const problems::Layout& layout, const problems::GameState& start,
                                const planner::RunoutOptions& options,
                                const planner::RunoutResult& result);

// `simulate`: one shot, and its success under noise when estimated.
struct SimulatedSuccess {
  planner::NoiseModel noise;
  uint64_t seed = 1;
  planner::Success success;  // its estimates' samples are N
};

// Everything the text and JSON reports say about the target.
struct TargetReport {
  double miss = 0.0;  // m; +inf when the ball did not come to rest on the table
  bool in_zone = false;
  bool reaches = false;
  std::string limits;  // empty when the shot lies within the problem's limits
  problems::Verdict verdict;  // every condition of the problem, the stroke's limits first
};
TargetReport target_report(const problems::Problem& problem, const physics::Shot& shot,
                           const physics::ShotResult& r);
// The first ball the cue ball struck, by name, or none.
std::string first_contact_name(const physics::ShotResult& r);

void write_simulate_text(std::ostream& out, const problems::Problem& problem,
                         const physics::Shot& shot, const physics::SimulationOptions& options,
                         const physics::ShotResult& r, const std::string& svg_file,
                         const std::optional<SimulatedSuccess>& success);
nlohmann::ordered_json simulate_json(const problems::Problem& problem, const physics::Shot& shot,
                                     const physics::SimulationOptions& options,
                                     const physics::ShotResult& r, const std::string& svg_file,
                                     const std::optional<SimulatedSuccess>& success = {});
void write_trace_csv(std::ostream& out, const physics::ShotTrace& trace,
                     const physics::ShotResult& r);
nlohmann::ordered_json trace_json(const physics::ShotTrace& trace, const physics::ShotResult& r,
                                  double interval);

// `spinmap`: where the stroke came from, the map in words and as JSON.
inline constexpr int kDefaultSpinmapGrid = 41;  // points across the disc's diameter
inline constexpr int kDefaultSuccessSamples = 24;
inline constexpr int kMaxSuccessSamples = 10000;

struct StrokeSource {
  bool planned = false;
  planner::PlanResult plan;  // when planned
};

void write_spinmap_text(std::ostream& out, const problems::Problem& problem,
                        const planner::SpinMap& map, const StrokeSource& source,
                        const physics::SimulationOptions& simulation, const std::string& file,
                        double seconds);
nlohmann::ordered_json spinmap_json(const problems::Problem& problem, const planner::SpinMap& map,
                                    const StrokeSource& source,
                                    const physics::SimulationOptions& simulation,
                                    const std::string& picture_file, double seconds);
nlohmann::ordered_json spinmap_cells_json(const problems::Problem& problem,
                                          const planner::SpinMap& map);

}  // namespace cueplan::api

// The faces (command line, server, batch) name these as their own.
namespace cueplan::cli {
using api::solve_json;
using api::route_json;
using api::run_json;
using api::SimulatedSuccess;
using api::TargetReport;
using api::target_report;
using api::first_contact_name;
using api::write_simulate_text;
using api::simulate_json;
using api::write_trace_csv;
using api::trace_json;
using api::kDefaultSpinmapGrid;
using api::kDefaultSuccessSamples;
using api::kMaxSuccessSamples;
using api::StrokeSource;
using api::write_spinmap_text;
using api::spinmap_json;
using api::spinmap_cells_json;
}  // namespace cueplan::cli
