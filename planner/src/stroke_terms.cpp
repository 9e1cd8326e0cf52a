// Names of the planner's methods and statuses, the noise model's checks, and the
// stroke in a player's terms.
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "cueplan/planner/planner.hpp"

namespace cueplan::planner {
namespace {

// A "tip" of offset is a quarter of the ball's radius, so the miscue limit (half the
// radius, PHYSICS.md) is two tips. Amounts are rounded to the nearest quarter tip.
std::string tips(double offset_over_radius) {
  const double quarters = std::round(std::abs(offset_over_radius) * 4.0 * 4.0);
  const int whole = static_cast<int>(quarters) / 4;
  const int part = static_cast<int>(quarters) % 4;
  static constexpr const char* kParts[] = {"", "a quarter", "half", "three quarters"};
  std::string words;
  if (whole == 0) {
    words = std::string(kParts[part]) + " of a tip";
    if (part == 2) words = "half a tip";
  } else {
    words = whole == 1 ? "one" : std::to_string(whole);
    if (part == 2)
      words += " and a half";
    else if (part != 0)
      words += std::string(" and ") + kParts[part];
    words += whole == 1 && part == 0 ? " tip" : " tips";
  }
  return words;
}

}  // namespace

const char* to_string(GlobalMethod method) {
  switch (method) {
    case GlobalMethod::direct_l: return "direct_l";
    case GlobalMethod::crs2: return "crs2";
    case GlobalMethod::mlsl: return "mlsl";
    case GlobalMethod::isres: return "isres";
    case GlobalMethod::ompl_kpiece1: return "ompl_kpiece1";
  }
  return "unknown";
}

const char* to_string(LocalMethod method) {
  switch (method) {
    case LocalMethod::bobyqa: return "bobyqa";
    case LocalMethod::sbplx: return "sbplx";
    case LocalMethod::cobyla: return "cobyla";
    case LocalMethod::neldermead: return "neldermead";
  }
  return "unknown";
}

const char* to_string(PlanStatus status) {
  switch (status) {
    case PlanStatus::solved: return "solved";
    case PlanStatus::no_solution_found: return "no_solution_found";
    case PlanStatus::budget_exhausted: return "budget_exhausted";
    case PlanStatus::unreachable: return "unreachable";
    case PlanStatus::invalid_input: return "invalid_input";
  }
  return "unknown";
}

bool parse_global_method(const std::string& name, GlobalMethod* method) {
  for (GlobalMethod m : {GlobalMethod::direct_l, GlobalMethod::crs2, GlobalMethod::mlsl,
                         GlobalMethod::isres, GlobalMethod::ompl_kpiece1}) {
    if (name == to_string(m)) {
      *method = m;
      return true;
    }
  }
  return false;
}

bool parse_local_method(const std::string& name, LocalMethod* method) {
  for (LocalMethod m : {LocalMethod::bobyqa, LocalMethod::sbplx, LocalMethod::cobyla,
                        LocalMethod::neldermead}) {
    if (name == to_string(m)) {
      *method = m;
      return true;
    }
  }
  return false;
}

physics::Validation NoiseModel::validate() const {
  using physics::invalid;
  if (!std::isfinite(aim_deg) || aim_deg < 0.0)
    return invalid({"aim_deg"}, "must be finite and not negative (deg)", aim_deg);
  if (!std::isfinite(speed) || speed < 0.0)
    return invalid({"speed"}, "must be finite and not negative (m/s)", speed);
  if (!std::isfinite(tip_offset) || tip_offset < 0.0)
    return invalid({"tip_offset"}, "must be finite and not negative (m)", tip_offset);
  if (!std::isfinite(tip_offset_relative) || tip_offset_relative < 0.0)
    return invalid({"tip_offset_relative"}, "must be finite and not negative", tip_offset_relative);
  if (!std::isfinite(squirt_judgement) || squirt_judgement < 0.0)
    return invalid({"squirt_judgement"}, "must be finite and not negative", squirt_judgement);
  if (!std::isfinite(bridge_length) || bridge_length < 0.0)
    return invalid({"bridge_length"}, "must be finite and not negative (m)", bridge_length);
  if (!std::isfinite(scale) || scale < 0.0)
    return invalid({"scale"}, "must be finite and not negative", scale);
  return {};
}

TipOffset tip_offset(const physics::Shot& shot) {
  return {shot.sidespin_k / physics::kSpinPerTipOffset, shot.topspin_k / physics::kSpinPerTipOffset};
}

std::string describe_stroke(const physics::Shot& shot) {
  const TipOffset t = tip_offset(shot);
  const double eighth = 1.0 / 32.0;  // below half a quarter tip reads as centre
  std::string side, height;
  if (std::abs(t.right) < eighth)
    side = "no side";
  else
    side = tips(t.right) + (t.right > 0 ? " of right" : " of left");
  if (std::abs(t.up) < eighth)
    height = "centre ball";
  else
    height = tips(t.up) + (t.up > 0 ? " above centre" : " below centre");
  return side + ", " + height + ", at " + fmt::format("{:.2f} m/s", shot.speed);
}

}  // namespace cueplan::planner
