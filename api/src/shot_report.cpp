#include "cueplan/api/shot_report.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "cueplan/api/words.hpp"

namespace cueplan::api {

namespace phys = cueplan::physics;
namespace plan = cueplan::planner;
namespace prob = cueplan::problems;
using nlohmann::ordered_json;

namespace {

// An aim the problem allows, to judge the other limits on their own.
double allowed_aim(const prob::Limits& limits, double aim_deg) {
  return limits.aim.mode == prob::AimMode::free ? aim_deg : limits.aim.lo_deg;
}

}  // namespace

std::vector<ConstraintRow> constraints(const prob::Problem& problem, const plan::PlannedShot& p,
                                       bool enforce_rigid_limit) {
  const prob::Limits& l = problem.limits;
  const phys::Shot& s = p.shot;
  const double aim = allowed_aim(l, s.aim_deg);
  std::vector<ConstraintRow> rows;
  const auto row = [&](const char* name, bool ok, std::string detail) {
    rows.push_back({name, name, ok ? "ok" : "broken", std::move(detail)});
  };

  const std::string speed = prob::check_shot(l, {s.speed, aim, 0.0, 0.0});
  row("speed", speed.empty(),
      speed.empty() ? number(s.speed, "m/s") + " within [" + number(l.speed_min) + ", " +
                          number(l.speed_max) + "] m/s"
                    : speed);
  const std::string spin = prob::check_shot(l, {l.speed_min, aim, s.topspin_k, s.sidespin_k});
  row("spin", spin.empty(),
      spin.empty() ? "sqrt(k_T^2 + k_S^2) = " + number(std::hypot(s.topspin_k, s.sidespin_k)) +
                         " within " + number(l.spin_max)
                   : spin);
  const std::string aim_check = prob::check_shot(l, {l.speed_min, s.aim_deg, 0.0, 0.0});
  std::string aim_detail = aim_check;
  if (aim_check.empty())
    aim_detail = l.aim.mode == prob::AimMode::free
                     ? number(s.aim_deg, "deg") + " (any aim allowed)"
                     : number(s.aim_deg, "deg") + " within [" + number(l.aim.lo_deg) + ", " +
                           number(l.aim.hi_deg) + "] deg";
  row("aim", aim_check.empty(), aim_detail);
  const bool cushions_ok = p.cushion_hits >= l.cushions_min && p.cushion_hits <= l.cushions_max;
  row("cushions", cushions_ok,
      std::to_string(p.cushion_hits) + " (the problem allows " + cushions_allowed(l) + ")");
  const bool pocketed = p.outcome == phys::ShotStatus::pocketed;
  row("pocket", !pocketed, pocketed ? "the cue ball is pocketed" : "not pocketed");
  const bool touched = p.outcome == phys::ShotStatus::hit_obstacle;
  row("obstacle", !touched,
      touched                           ? "the cue ball touches an obstacle ball"
      : problem.scene.obstacles.empty() ? "no obstacle balls on this table"
                                        : "clears every obstacle ball");

  // A pot problem's own conditions: the first contact and the pot.
  using prob::Failure;
  if (const std::string first = problem.required_first_contact(); !first.empty()) {
    const bool ok = p.failure != Failure::first_contact;
    rows.push_back({"first contact", "first_contact", ok ? "ok" : "broken",
                    ok ? (p.failure == Failure::no_outcome || p.failure == Failure::obstacle ||
                                  p.failure == Failure::cue_ball_pocketed
                              ? "not judged: " + p.failure_reason
                              : "the cue ball strikes " + first + " first")
                       : p.failure_reason});
  }
  if (problem.pot) {
    const bool foul = p.failure == Failure::pot_missed || p.failure == Failure::wrong_pocket ||
                      p.failure == Failure::other_ball_pocketed;
    const bool made = p.pot ? p.pot->made && p.failure != Failure::other_ball_pocketed : !foul;
    const std::string pocket = prob::pocket_name(problem.scene, problem.pot->pocket);
    rows.push_back({"pot", "pot", made ? "ok" : "broken",
                    made ? problem.pot->ball + " drops in the " + pocket + " pocket, no other ball does"
                    : foul ? p.failure_reason
                           : problem.pot->ball + " does not drop in the " + pocket + " pocket"});
  }

  const double limit = problem.scene.ball_and_cushion.rigid_speed_limit;
  std::string rigid = "max cushion normal speed " + number(p.max_cushion_normal_speed, "m/s");
  if (!p.rigid_limit_exceeded) {
    rows.push_back({"rigid limit", "rigid_limit", "ok", rigid + ", below " + number(limit, "m/s")});
  } else if (enforce_rigid_limit) {
    rows.push_back(
        {"rigid limit", "rigid_limit", "broken",
         rigid + ", above " + number(limit, "m/s") + " (enforced by --enforce-rigid-limit)"});
  } else {
    rows.push_back({"rigid limit", "rigid_limit", "flagged",
                    rigid + ", above " + number(limit, "m/s") +
                        ": the rigid-cushion model is not trusted there (--enforce-rigid-limit "
                        "rejects such strokes)"});
  }
  return rows;
}

std::string landing_text(const plan::PlannedShot& p) {
  switch (p.outcome) {
    case phys::ShotStatus::rest:
      return "x = " + number(p.final_position.x, "m") + ", y = " + number(p.final_position.y, "m");
    case phys::ShotStatus::pocketed:
      return "none: pocketed at x = " + number(p.final_position.x, "m") +
             ", y = " + number(p.final_position.y, "m");
    case phys::ShotStatus::hit_obstacle:
      return "none: stopped against an obstacle ball at x = " + number(p.final_position.x, "m") +
             ", y = " + number(p.final_position.y, "m");
    default:
      return std::string("none: ") + phys::to_string(p.outcome);
  }
}

ordered_json point_json(phys::Vec2 v) { return {v.x, v.y}; }

std::string estimate_text(const plan::Estimate& e) {
  return fmt::format("{:.1f} % (95 % interval {:.1f}-{:.1f} %)", 100.0 * e.p, 100.0 * e.low,
                     100.0 * e.high);
}

ordered_json estimate_json(const plan::Estimate& e) {
  return {{"p", e.p}, {"low", e.low}, {"high", e.high}, {"samples", e.samples}};
}

ordered_json success_json(const plan::Success& s) {
  ordered_json j;
  if (s.pot) j["pot"] = estimate_json(*s.pot);
  j["position"] = estimate_json(s.position);
  if (s.next) j["next"] = estimate_json(*s.next);
  j["both"] = estimate_json(s.both);
  return j;
}

std::string pot_success_words(const plan::Success& s) {
  if (!s.pot) return {};
  if (s.next)
    return " (pot now and pot next); the pot alone " + estimate_text(*s.pot) +
           ", the next pot from where the cue ball stops " + estimate_text(*s.next) + " over " +
           std::to_string(s.next->samples) + " landings";
  return " (pot and position); the pot alone " + estimate_text(*s.pot) +
         ", the position given the pot " + estimate_text(s.position) + " of " +
         std::to_string(s.position.samples);
}

std::vector<std::pair<std::string, std::string>> pot_lines(const plan::PotReport& pot) {
  std::vector<std::pair<std::string, std::string>> lines;
  lines.emplace_back("pot", pot.ball + " into the " + pot.pocket_name + " pocket: " +
                                (pot.made ? "made" : "missed") +
                                (pot.striker.empty() || pot.striker == phys::kCueBallName
                                     ? std::string()
                                     : " (struck by " + pot.striker + ": a plant)"));
  if (pot.thickness.empty()) return lines;  // never struck
  const char* side = pot.cut_side > 0 ? "to the left" : pot.cut_side < 0 ? "to the right" : "straight on";
  lines.emplace_back("cut", fmt::format("{:.1f} deg, {} ball ({} leaves {} of the {}'s path)",
                                        pot.cut_deg, pot.thickness, pot.ball, side,
                                        pot.striker == phys::kCueBallName ? "cue ball" : pot.striker));
  const double allowance = pot.aim_allowance_deg;
  lines.emplace_back(
      "throw",
      fmt::format("{:.2f} deg {} (the model's: {} leaves that far {} of the line of centres); "
                  "the aim, {:.3f} deg {} of the ghost-ball line ({:.3f} deg), allows for it",
                  std::abs(pot.throw_deg), pot.throw_deg >= 0.0 ? "counter-clockwise" : "clockwise",
                  pot.ball, pot.throw_deg >= 0.0 ? "counter-clockwise" : "clockwise",
                  std::abs(allowance), allowance >= 0.0 ? "counter-clockwise" : "clockwise",
                  pot.ghost_aim_deg));
  if (pot.jaw_clearance_m)
    lines.emplace_back(
        "pot margin",
        *pot.jaw_clearance_m >= 0.0
            ? fmt::format("the {} clears the near ({}) jaw by {:.1f} mm{}", pot.ball,
                          pot.near_jaw, 1e3 * *pot.jaw_clearance_m,
                          pot.made ? fmt::format("; an aim error of {:.3f} deg rattles it or "
                                                 "misses",
                                                 pot.aim_margin_deg)
                                   : std::string())
            : fmt::format("the {}'s line meets the {} jaw ({:.1f} mm into it){}", pot.ball,
                          pot.near_jaw, -1e3 * *pot.jaw_clearance_m,
                          pot.made ? fmt::format("; it drops off the jaw, and an aim error of "
                                                 "{:.3f} deg would miss",
                                                 pot.aim_margin_deg)
                                   : std::string()));
  else if (pot.made)
    lines.emplace_back(
        "pot margin",
        fmt::format("{}'s centre passes {:.1f} mm inside the pocket's capture circle; an aim "
                    "error of {:.3f} deg would miss",
                    pot.ball, 1e3 * pot.margin_m, pot.aim_margin_deg));
  return lines;
}

std::vector<std::pair<std::string, std::string>> next_lines(const plan::NextReport& n) {
  std::vector<std::pair<std::string, std::string>> lines;
  lines.emplace_back("next", fmt::format("{} into the {} pocket: {} (P(next pot) {:.0f} % from there)",
                                         n.ball, n.pocket_name, n.words, 100.0 * n.p));
  lines.emplace_back(
      "zone", fmt::format("{:.0f} cm^2 where P(next pot) is within 10 points of the best ({:.0f} % "
                          "at x = {:.3f} m, y = {:.3f} m); the landing is {}",
                          1e4 * n.zone_area_m2, 100.0 * n.best_p, n.best.x, n.best.y,
                          n.in_zone ? "inside it" : "outside it"));
  return lines;
}

ordered_json next_json(const plan::NextReport& n) {
  ordered_json j;
  j["ball"] = n.ball;
  j["pocket"] = n.pocket_name;
  j["p"] = n.p;
  j["cut_deg"] = n.cut_deg;
  j["cut_side"] = n.cut_side > 0 ? "left" : n.cut_side < 0 ? "right" : "straight";
  j["thickness"] = n.thickness;
  j["distance_m"] = n.distance_m;
  j["screened_by"] = n.screened_by.empty() ? ordered_json() : ordered_json(n.screened_by);
  j["zone_area_m2"] = n.zone_area_m2;
  j["in_zone"] = n.in_zone;
  j["best_p"] = n.best_p;
  j["best"] = point_json(n.best);
  j["landing"] = point_json(n.landing);
  j["words"] = n.words;
  return j;
}

ordered_json pot_json(const plan::PotReport& pot) {
  ordered_json j;
  j["ball"] = pot.ball;
  j["pocket"] = pot.pocket_name;
  j["made"] = pot.made;
  j["striker"] = pot.striker;
  j["cut_deg"] = pot.cut_deg;
  j["cut_side"] = pot.cut_side > 0 ? "left" : pot.cut_side < 0 ? "right" : "straight";
  j["thickness"] = pot.thickness;
  j["throw_deg"] = pot.throw_deg;
  j["ghost_aim_deg"] = pot.ghost_aim_deg;
  j["aim_allowance_deg"] = pot.aim_allowance_deg;
  j["margin_m"] = pot.margin_m;
  j["aim_margin_deg"] = pot.aim_margin_deg;
  if (pot.jaw_clearance_m) {
    j["jaw_clearance_m"] = *pot.jaw_clearance_m;
    j["near_jaw"] = pot.near_jaw;
  }
  return j;
}

ordered_json planned_json(const prob::Problem& problem, const plan::PlannedShot& p,
                          bool enforce_rigid_limit) {
  ordered_json j;
  j["shot"] = {{"speed", p.shot.speed},
               {"aim_deg", p.shot.aim_deg},
               {"topspin_k", p.shot.topspin_k},
               {"sidespin_k", p.shot.sidespin_k},
               {"elevation_deg", p.shot.elevation_deg},
               {"squirt_deg", squirt_deg(problem.scene, p.shot)}};
  const plan::TipOffset t = plan::tip_offset(p.shot);
  j["tip_offset"] = {{"right", t.right}, {"up", t.up}};
  j["stroke"] = plan::describe_stroke(p.shot);
  j["outcome"] = phys::to_string(p.outcome);
  j["final_position"] = point_json(p.final_position);
  // null when the ball did not come to rest on the table (JSON has no infinity)
  j["miss_distance"] = std::isfinite(p.miss_distance) && problem.has_target
                           ? ordered_json(p.miss_distance)
                           : ordered_json();
  j["success_probability"] = p.success_probability;
  j["success"] = success_json(p.success);
  j["solves"] = p.solves;
  j["cushion_hits"] = p.cushion_hits;
  j["route"] = p.route;
  ordered_json names = ordered_json::array();
  for (int c : p.route) names.push_back(cushion_name(problem.scene, c));
  j["route_names"] = names;
  j["family"] = p.family;
  j["within_limits"] = p.within_limits;
  j["violations"] = p.violations;
  ordered_json rows = ordered_json::object();
  for (const ConstraintRow& c : constraints(problem, p, enforce_rigid_limit))
    rows[c.key] = {{"state", c.state}, {"detail", c.detail}};
  j["constraints"] = rows;
  j["max_cushion_normal_speed"] = p.max_cushion_normal_speed;
  j["rigid_limit_exceeded"] = p.rigid_limit_exceeded;
  j["impact_method"] = phys::to_string(p.impact_method);
  j["failure"] = {{"condition", prob::to_string(p.failure)}, {"reason", p.failure_reason}};
  if (p.pot) j["pot"] = pot_json(*p.pot);
  if (p.next) j["next"] = next_json(*p.next);
  return j;
}

}  // namespace cueplan::api
