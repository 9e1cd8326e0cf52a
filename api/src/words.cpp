#include "cueplan/api/words.hpp"

#include <fmt/format.h>

#include <cmath>

#include "cueplan/physics/impact_table.hpp"
#include "cueplan/planner/planner.hpp"

namespace cueplan::api {
namespace {

namespace phys = cueplan::physics;

}  // namespace

std::string cushion_name(const phys::Scene& scene, int cushion) {
  switch (cushion) {
    case 0:
      return "y = 0";
    case 1:
      return "x = " + number(scene.length);
    case 2:
      return "y = " + number(scene.width);
    case 3:
      return "x = 0";
    default:
      return "?";
  }
}

std::string route_text(const phys::Scene& scene, const std::vector<int>& route) {
  if (route.empty()) return "no cushion";
  std::string text =
      std::to_string(route.size()) + (route.size() == 1 ? " cushion: " : " cushions: ");
  for (size_t i = 0; i < route.size(); ++i)
    text += (i == 0 ? "" : ", ") + cushion_name(scene, route[i]);
  return text;
}

std::string method_text(const phys::SimulationOptions& options, const phys::Scene& scene) {
  switch (phys::chosen_impact_method(scene, options)) {
    case phys::ImpactMethod::paper:
      return fmt::format("paper (the paper's fixed-step scheme, {} impulse steps per cushion "
                         "impact)",
                         phys::ImpactOptions{}.paper_steps);
    case phys::ImpactMethod::table:
      return fmt::format(
          "table (measured error {:.3g} of the speed, within the impact accuracy {:.3g}; the "
          "exact method in the {:.3g} % of cells where interpolation is inaccurate)",
          options.table->measured_error().max_state_relative, options.impact_accuracy,
          100.0 * options.table->fallback_fraction());
    case phys::ImpactMethod::extrapolation:
      return "extrapolation (impact accuracy " + number(options.impact_accuracy) + " of the speed)";
    case phys::ImpactMethod::closed_form:
      return "closed_form (the han_2005 cushion model: one impulse per impact)";
    case phys::ImpactMethod::exact:
      break;
  }
  return "exact (impact accuracy " + number(options.impact_accuracy) + " of the speed)";
}

void report_line(std::ostream& out, std::string_view label, const std::string& text) {
  out << fmt::format("{:<16}", label) << text << '\n';
}

std::string number(double value, const char* unit) {
  std::string s = fmt::format("{:.6g}", value);
  if (unit) s += std::string(" ") + unit;
  return s;
}

std::string tip_offset_words(const phys::Shot& shot) {
  const planner::TipOffset t = planner::tip_offset(shot);
  return fmt::format("{:.3f} R {} of centre, {:.3f} R {} centre", std::abs(t.right),
                     t.right < 0.0 ? "left" : "right", std::abs(t.up), t.up < 0.0 ? "below" : "above");
}

double squirt_deg(const phys::Scene& scene, const phys::Shot& shot) {
  return phys::squirt_angle_deg(scene.cue, scene.ball_and_cushion.mass, scene.radius(),
                                shot.sidespin_k);
}

std::string squirt_words(const phys::Scene& scene, const phys::Shot& shot) {
  if (shot.sidespin_k == 0.0) return {};
  const double s = squirt_deg(scene, shot);
  std::string text = fmt::format("the cue ball leaves {:.2f} deg {} of the cue's line",
                                 std::abs(s), s > 0.0 ? "left" : "right");
  if (shot.elevation_deg > 0.0)
    text += fmt::format(", then swerves {} while it slides", shot.sidespin_k > 0.0 ? "right" : "left");
  return text;
}

std::string cushions_allowed(const problems::Limits& limits) {
  return limits.cushions_min == limits.cushions_max
             ? std::to_string(limits.cushions_min)
             : std::to_string(limits.cushions_min) + " to " + std::to_string(limits.cushions_max);
}

}  // namespace cueplan::api
