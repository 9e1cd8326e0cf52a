// A spin map reported: in words and as JSON.
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

constexpr double kSpinPerTipOffset = 2.5;  // k = 2.5 d / R (PHYSICS.md, "Cue strike")

using draw::classify;
using draw::format_of;
using draw::SpinCellKind;
using PictureFormat = draw::Format;

// The spins that land, as ranges of k and of tip offset.
struct LandingRange {
  double kt_min = INFINITY, kt_max = -INFINITY, ks_min = INFINITY, ks_max = -INFINITY;
};

LandingRange landing_range(const plan::SpinMap& map) {
  LandingRange r;
  for (const plan::SpinMapPoint& p : map.points) {
    if (!p.lands) continue;
    r.kt_min = std::min(r.kt_min, p.topspin_k);
    r.kt_max = std::max(r.kt_max, p.topspin_k);
    r.ks_min = std::min(r.ks_min, p.sidespin_k);
    r.ks_max = std::max(r.ks_max, p.sidespin_k);
  }
  return r;
}

// The spin that stops nearest the target after an allowed number of cushions, if any.
const plan::SpinMapPoint* nearest(const plan::SpinMap& map, const prob::Limits& limits) {
  const plan::SpinMapPoint* best = nullptr;
  for (const plan::SpinMapPoint& p : map.points)
    if (classify(p, limits) == SpinCellKind::distance &&
        (!best || p.miss_distance < best->miss_distance))
      best = &p;
  return best;
}

std::string tip_words(double right, double up) {
  return fmt::format("{:.3f}", std::abs(right)) + " R " + (right < 0.0 ? "left" : "right") + ", " +
         fmt::format("{:.3f}", std::abs(up)) + " R " + (up < 0.0 ? "below" : "above");
}

// A range of tip offsets along one axis in words, e.g. "from 0.1 R left to 0.2 R right of
// centre" or "0.24 R to 0.31 R above centre".
std::string offset_range(double lo, double hi, const char* negative, const char* positive,
                         const char* centre) {
  const auto side = [&](double v) { return v < 0.0 ? negative : positive; };
  const auto amount = [](double v) { return fmt::format("{:.3g}", std::abs(v)) + " R"; };
  if (lo == hi) return amount(lo) + " " + side(lo) + centre;
  if ((lo < 0.0) == (hi < 0.0) || lo == 0.0) {
    const double near = lo < 0.0 ? hi : lo;
    const double far = lo < 0.0 ? lo : hi;
    return amount(near) + " to " + amount(far) + " " + side(far) + centre;
  }
  return "from " + amount(lo) + " " + side(lo) + " to " + amount(hi) + " " + side(hi) + centre;
}

struct Counts {
  int kinds[6] = {0, 0, 0, 0, 0, 0};
  int of(SpinCellKind k) const { return kinds[static_cast<int>(k)]; }
};

Counts counts_of(const plan::SpinMap& map, const prob::Limits& limits) {
  Counts c;
  for (const plan::SpinMapPoint& p : map.points) ++c.kinds[static_cast<int>(classify(p, limits))];
  return c;
}

std::string source_text(const StrokeSource& source) {
  if (!source.planned) return "given by --speed and --aim";
  const phys::Shot& s = source.plan.best.shot;
  return "from the planner's best stroke (no --speed and --aim given; " +
         std::string(plan::to_string(source.plan.status)) + ", with k_T = " + number(s.topspin_k) +
         ", k_S = " + number(s.sidespin_k) + ": " + plan::describe_stroke(s) + ")";
}

void write_text(std::ostream& out, const prob::Problem& problem, const plan::SpinMap& map,
                const StrokeSource& source, const phys::SimulationOptions& simulation,
                const std::string& file, double seconds) {
  const auto line = [&](std::string_view label, const std::string& text) {
    report_line(out, label, text);
  };
  const prob::Limits& limits = problem.limits;
  line("problem", problem.name + "  (" + problem.source + ")");
  line("stroke", "V = " + number(map.speed, "m/s") + " at aim " + number(map.aim_deg, "deg") +
                     ", " + source_text(source));
  line("grid", std::to_string(map.grid) +
                   " points across the disc: " + std::to_string(map.points.size()) +
                   " spins with sqrt(k_T^2 + k_S^2) <= " + number(map.spin_max) +
                   " (tip offset up to " + number(map.spin_max / kSpinPerTipOffset) + " R)");
  line("landing", std::to_string(map.landing) + " of " + std::to_string(map.points.size()) +
                      " spins stop within " + number(1000.0 * problem.tolerance, "mm") +
                      " of the target after " + cushions_allowed(limits) +
                      (limits.cushions_max == 1 ? " cushion" : " cushions"));
  if (map.landing > 0) {
    const LandingRange r = landing_range(map);
    line("landing spins",
         "k_T " + fmt::format("{:.3g}", r.kt_min) + " to " + fmt::format("{:.3g}", r.kt_max) + ", k_S " +
             fmt::format("{:.3g}", r.ks_min) + " to " + fmt::format("{:.3g}", r.ks_max) + ": tip " +
             offset_range(r.ks_min / kSpinPerTipOffset, r.ks_max / kSpinPerTipOffset, "left",
                          "right", " of centre") +
             ", " +
             offset_range(r.kt_min / kSpinPerTipOffset, r.kt_max / kSpinPerTipOffset, "below",
                          "above", " centre"));
  }
  if (const plan::SpinMapPoint* p = nearest(map, limits))
    line("nearest", fmt::format("{:.3g} mm", 1000.0 * p->miss_distance) + " from the target with k_T = " +
                        number(p->topspin_k) + ", k_S = " + number(p->sidespin_k) + " (tip " +
                        tip_words(p->tip_right, p->tip_up) + " centre)");
  const Counts c = counts_of(map, limits);
  line("outcomes",
       std::to_string(c.of(SpinCellKind::distance)) + " at rest after " + cushions_allowed(limits) +
           (limits.cushions_max == 1 ? " cushion, " : " cushions, ") +
           std::to_string(c.of(SpinCellKind::wrong_cushions)) + " at rest after another number, " +
           std::to_string(c.of(SpinCellKind::pocketed)) + " pocketed, " +
           std::to_string(c.of(SpinCellKind::obstacle)) + " against an obstacle, " +
           std::to_string(c.of(SpinCellKind::no_result)) + " without an outcome" +
           (problem.pot ? ", " + std::to_string(c.of(SpinCellKind::no_pot)) + " for which no aim pots " +
                              problem.pot->ball + " (each spin's aim solved to keep the pot)"
                        : std::string()));
  if (map.success_samples > 0) {
    const plan::SpinMapPoint* best = nullptr;
    double sum = 0.0;
    for (const plan::SpinMapPoint& p : map.points) {
      if (!p.success) continue;
      sum += *p.success;
      if (!best || *p.success > *best->success) best = &p;
    }
    std::string text = std::to_string(map.success_samples) + " noisy strokes a spin: ";
    if (best)
      text += fmt::format("mean {:.0f} %, best {:.0f} % with k_T = ", 100.0 * sum / map.success_cells,
                          100.0 * *best->success) +
              number(best->topspin_k) + ", k_S = " + number(best->sidespin_k);
    else
      text += "none estimated";
    line("success", text);
  }
  line("method", method_text(simulation, problem.scene));
  line("picture", file);
  line("time", fmt::format("{:.3g} s", seconds));
}

ordered_json point_json(const plan::SpinMapPoint& p) {
  return {{"topspin_k", p.topspin_k},
          {"sidespin_k", p.sidespin_k},
          {"tip_right", p.tip_right},
          {"tip_up", p.tip_up},
          {"final_position", {p.final_position.x, p.final_position.y}},
          {"miss_distance",
           std::isfinite(p.miss_distance) ? ordered_json(p.miss_distance) : ordered_json()},
          {"cushion_hits", p.cushion_hits}};
}

// A point's JSON with its success under noise when it was estimated.
ordered_json point_json_with_success(const plan::SpinMapPoint& p) {
  ordered_json j = point_json(p);
  if (p.success) j["success"] = *p.success;
  return j;
}

// The outcome class of a grid spin by the name `outcomes` counts it under.
const char* outcome_key(SpinCellKind kind) {
  switch (kind) {
    case SpinCellKind::distance: return "at_rest_allowed_cushions";
    case SpinCellKind::wrong_cushions: return "at_rest_other_cushions";
    case SpinCellKind::pocketed: return "pocketed";
    case SpinCellKind::obstacle: return "hit_obstacle";
    case SpinCellKind::no_result: return "no_outcome";
    case SpinCellKind::no_pot: return "no_pot";
  }
  return "no_outcome";
}

}  // namespace

ordered_json spinmap_json(const prob::Problem& problem, const plan::SpinMap& map,
                          const StrokeSource& source, const phys::SimulationOptions& simulation,
                          const std::string& picture_file, double seconds) {
  ordered_json j;
  j["problem"] = {{"name", problem.name}, {"source", problem.source}};
  j["speed"] = map.speed;
  j["aim_deg"] = map.aim_deg;
  j["stroke_source"] = source.planned ? "planner" : "given";
  if (source.planned) {
    const phys::Shot& s = source.plan.best.shot;
    j["planner"] = {{"status", plan::to_string(source.plan.status)},
                    {"message", source.plan.message},
                    {"shot",
                     {{"speed", s.speed},
                      {"aim_deg", s.aim_deg},
                      {"topspin_k", s.topspin_k},
                      {"sidespin_k", s.sidespin_k}}}};
  }
  j["grid"] = map.grid;
  j["spin_max"] = map.spin_max;
  j["points"] = map.points.size();
  j["landing"] = map.landing;
  ordered_json landing = ordered_json::array();
  for (const plan::SpinMapPoint& p : map.points)
    if (p.lands) landing.push_back(point_json_with_success(p));
  j["landing_spins"] = landing;
  const plan::SpinMapPoint* p = nearest(map, problem.limits);
  j["nearest"] = p ? point_json_with_success(*p) : ordered_json();
  if (map.success_samples > 0)
    j["success"] = {{"samples", map.success_samples},
                    {"cells", map.success_cells},
                    {"complete", map.success_complete},
                    {"unit", "fraction of the noisy strokes that solve the problem, 0..1"}};
  const Counts c = counts_of(map, problem.limits);
  j["outcomes"] = {{"at_rest_allowed_cushions", c.of(SpinCellKind::distance)},
                   {"at_rest_other_cushions", c.of(SpinCellKind::wrong_cushions)},
                   {"pocketed", c.of(SpinCellKind::pocketed)},
                   {"hit_obstacle", c.of(SpinCellKind::obstacle)},
                   {"no_outcome", c.of(SpinCellKind::no_result)}};
  if (problem.pot) {
    j["outcomes"]["no_pot"] = c.of(SpinCellKind::no_pot);
    j["pot_ball"] = problem.pot->ball;
  }
  j["target"] = {problem.target.x, problem.target.y};
  j["tolerance"] = problem.tolerance;
  j["method"] = phys::to_string(phys::chosen_impact_method(problem.scene, simulation));
  if (!picture_file.empty()) {
    j["out"] = picture_file;
    if (const std::optional<PictureFormat> format = format_of(picture_file))
      j["format"] = draw::to_string(*format);
  }
  j["time_s"] = seconds;
  j["units"] = {{"speed", "m/s"},
                {"aim_deg", "deg from +x, counter-clockwise"},
                {"topspin_k", "k_T = w_T R / V"},
                {"sidespin_k", "k_S = w_S R / V, > 0 right spin"},
                {"tip_right", "d / R, > 0 right of centre (k = 2.5 d / R)"},
                {"tip_up", "d / R, > 0 above centre"},
                {"final_position", "m, table frame"},
                {"miss_distance", "m"},
                {"tolerance", "m"},
                {"time_s", "s"}};
  return j;
}

ordered_json spinmap_cells_json(const prob::Problem& problem, const plan::SpinMap& map) {
  ordered_json cells = ordered_json::array();
  for (const plan::SpinMapPoint& p : map.points) {
    ordered_json cell = point_json_with_success(p);
    cell["outcome"] = phys::to_string(p.outcome);
    cell["kind"] = outcome_key(classify(p, problem.limits));
    cell["lands"] = p.lands;
    cell["aim_deg"] = p.aim_deg;
    cell["pots"] = p.pots;
    cells.push_back(std::move(cell));
  }
  return cells;
}

void write_spinmap_text(std::ostream& out, const prob::Problem& problem, const plan::SpinMap& map,
                        const StrokeSource& source, const phys::SimulationOptions& simulation,
                        const std::string& file, double seconds) {
  write_text(out, problem, map, source, simulation, file, seconds);
}

}  // namespace cueplan::api
