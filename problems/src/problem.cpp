// What a problem asks for: a human summary, and the tests a shot and its outcome pass.
#include "cueplan/problems/problem.hpp"

#include "cueplan/problems/ball_names.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace cueplan::problems {
namespace {

using physics::FieldPath;
using physics::FieldStep;
using physics::invalid;
using physics::Validation;

const std::string* name_at(const FieldPath& path, size_t i) {
  return i < path.size() ? std::get_if<std::string>(&path.steps()[i]) : nullptr;
}
const int* index_at(const FieldPath& path, size_t i) {
  return i < path.size() ? std::get_if<int>(&path.steps()[i]) : nullptr;
}

// Problem::scene's fields as the file names them.
std::string scene_field(const FieldPath& path) {
  const std::string* head = name_at(path, 0);
  if (head == nullptr) return path.text();
  if (*head == "length" || *head == "width") return "table." + *head;
  if (*head == "ball_and_cushion") {
    const std::string* member = name_at(path, 1);
    if (member == nullptr) return "ball";
    if (*member == "mass" || *member == "radius") return "ball." + *member;
    if (*member == "mu_table") return "physics.mu_slide";  // one ball-cloth friction in the file
    return "physics." + *member;
  }
  if (*head == "cloth") return "physics." + path.drop_front(1).text();
  if (*head == "ball_contact") {
    const std::string* member = name_at(path, 1);
    if (member == nullptr) return "physics";
    if (*member == "mu_ball") return "physics.mu_ball";
    return "physics.ball_" + *member;  // ball_restitution, ball_model, ball_friction
  }
  if (*head == "pockets") {
    const int* index = index_at(path, 1);
    if (path.size() >= 3) {
      // A jawed pocket's shape is the corner's or the middle's; a capture circle's radius
      // is the one radius every pocket has.
      const std::string* member = name_at(path, 2);
      if (member != nullptr && *member != "radius" && *member != "centre" && index != nullptr)
        return fmt::format("table.pockets.{}.{}", *index == 1 || *index == 4 ? "middle" : "corner",
                           *member);
      return "table.pocket_radius";
    }
    if (index != nullptr && *index >= 0 && *index < 6)
      return fmt::format("the {} pocket", kPocketNames[*index]);
    return path.text();
  }
  return path.text();  // obstacles[2], balls.red, ...
}

}  // namespace

std::string file_field(const FieldPath& path) {
  const std::string* head = name_at(path, 0);
  if (head == nullptr) return path.text();
  if (*head == "scene") return scene_field(path.drop_front(1));
  if (*head == "limits") {
    const std::string* member = name_at(path, 1);
    if (member == nullptr) return "limits";
    if (*member == "speed_min") return "limits.speed[0]";
    if (*member == "speed_max") return "limits.speed[1]";
    if (*member == "spin_max") return "limits.spin";
    if (*member == "aim") return "limits.aim_deg";
    if (*member == "cushions_min") return "limits.cushions[0]";
    if (*member == "cushions_max") return "limits.cushions[1]";
    if (*member == "elevation_min_deg") return "limits.elevation_deg[0]";
    if (*member == "elevation_max_deg") return "limits.elevation_deg[1]";
    if (*member == "cushions_before_contact_min") return "limits.cushions_before_contact[0]";
    if (*member == "cushions_before_contact_max") return "limits.cushions_before_contact[1]";
    if (*member == "object_cushions_min") return "limits.object_cushions[0]";
    if (*member == "object_cushions_max") return "limits.object_cushions[1]";
  }
  return path.text();  // cue_ball, target, tolerance, max_strokes, time_budget_s, pot.ball,
                       // first_contact
}

std::string file_message(const physics::ValidationError& error) {
  return error.message(file_field(error.field), error.other ? file_field(*error.other) : "");
}

Validation validate(const Problem& p) {
  if (Validation e = p.scene.validate()) return e->under({"scene"});
  // A pocket or ball a position meets is a field of the scene. The cue ball lies among
  // the object balls; the target need not be clear of them, which the shot may move.
  Validation place = p.scene.check_position(p.cue_ball, {"cue_ball"});
  if (!place && p.has_target) place = p.scene.check_rest_position(p.target, {"target"});
  if (place) {
    if (place->other) place->other = place->other->under({"scene"});
    return place;
  }
  if (!std::isfinite(p.tolerance) || !(p.tolerance > 0.0))
    return invalid({"tolerance"}, "must be positive and finite (m)", p.tolerance);
  const Limits& l = p.limits;
  if (!std::isfinite(l.speed_min) || !(l.speed_min > 0.0))
    return invalid({"limits", "speed_min"}, "must be positive and finite (m/s)", l.speed_min);
  if (!std::isfinite(l.speed_max) || !(l.speed_max > l.speed_min))
    return invalid({"limits", "speed_max"}, "must be finite and exceed the least speed (m/s)",
                   l.speed_max);
  if (!std::isfinite(l.spin_max) || !(l.spin_max > 0.0))
    return invalid({"limits", "spin_max"}, "must be positive and finite", l.spin_max);
  if (l.cushions_min < 0)
    return invalid({"limits", "cushions_min"}, "must not be negative", l.cushions_min);
  if (l.cushions_max < l.cushions_min)
    return invalid({"limits", "cushions_max"}, "must not be below the least count",
                   l.cushions_max);
  if (l.cushions_before_contact_min < 0)
    return invalid({"limits", "cushions_before_contact_min"}, "must not be negative",
                   l.cushions_before_contact_min);
  if (l.cushions_before_contact_max < l.cushions_before_contact_min)
    return invalid({"limits", "cushions_before_contact_max"}, "must not be below the least count",
                   l.cushions_before_contact_max);
  if (l.object_cushions_min < 0)
    return invalid({"limits", "object_cushions_min"}, "must not be negative", l.object_cushions_min);
  if (l.object_cushions_max < l.object_cushions_min)
    return invalid({"limits", "object_cushions_max"}, "must not be below the least count",
                   l.object_cushions_max);
  if (!std::isfinite(l.elevation_min_deg) || l.elevation_min_deg < 0.0)
    return invalid({"limits", "elevation_min_deg"}, "must be finite and not negative (deg)",
                   l.elevation_min_deg);
  if (!std::isfinite(l.elevation_max_deg) || l.elevation_max_deg < l.elevation_min_deg ||
      !(l.elevation_max_deg < 90.0))
    return invalid({"limits", "elevation_max_deg"},
                   "must be at least the least elevation and below 90 (deg)", l.elevation_max_deg);
  const AimLimit& a = l.aim;
  if (!std::isfinite(a.lo_deg) || !std::isfinite(a.hi_deg))
    return invalid({"limits", "aim"}, "must be finite (deg)",
                   std::isfinite(a.lo_deg) ? a.hi_deg : a.lo_deg);
  if (a.mode == AimMode::range && !(a.lo_deg < a.hi_deg && a.hi_deg <= a.lo_deg + 360.0))
    return invalid({"limits", "aim"},
                   fmt::format("range must satisfy lo < hi <= lo + 360 deg, got [{:.10g}, {:.10g}]",
                               a.lo_deg, a.hi_deg));
  if (p.max_strokes && (*p.max_strokes < 1 || *p.max_strokes > kMostStrokes))
    return invalid({"max_strokes"}, fmt::format("must lie in [1, {}]", kMostStrokes),
                   *p.max_strokes);
  if (p.time_budget_s && !(std::isfinite(*p.time_budget_s) && *p.time_budget_s > 0.0))
    return invalid({"time_budget_s"}, "must be positive and finite (s)", *p.time_budget_s);
  const auto is_ball = [&](const std::string& name) {
    for (const physics::ObjectBall& b : p.scene.balls)
      if (b.name == name) return true;
    return false;
  };
  if (p.pot) {
    if (!is_ball(p.pot->ball))
      return invalid({"pot", "ball"},
                     fmt::format("names no object ball on the table: \"{}\"", p.pot->ball));
    if (p.pot->pocket < 0 || p.pot->pocket >= static_cast<int>(p.scene.pockets.size()))
      return invalid({"pot", "pocket"},
                     p.scene.pockets.empty() ? "names a pocket, but the table has none"
                                             : "names no pocket of this table",
                     p.pot->pocket);
  }
  if (p.first_contact && !is_ball(*p.first_contact) && !is_contact_class(*p.first_contact))
    return invalid({"first_contact"},
                   fmt::format("names no object ball on the table and no class of balls: \"{}\"",
                               *p.first_contact));
  if (p.first_contact && p.pot && is_contact_class(*p.first_contact) &&
      !contact_allowed(*p.first_contact, p.pot->ball, p.scene.balls))
    return invalid({"first_contact"},
                   fmt::format("{} does not allow a first contact on the pot's ball {}",
                               *p.first_contact, p.pot->ball));
  if (!p.has_target && !p.pot && !p.first_contact)
    return invalid({"target"}, "is required unless the problem has a pot or a first_contact");
  if (!p.next.empty() && !p.pot)
    return invalid({"next"}, "needs a pot: the next pot is played after this stroke's pot");
  if (p.next.size() > static_cast<size_t>(kMostNextPots))
    return invalid({"next"}, fmt::format("may list at most {} pots", kMostNextPots),
                   static_cast<int>(p.next.size()));
  for (size_t i = 0; i < p.next.size(); ++i) {
    const NextPot& n = p.next[i];
    // The file's path: next.ball for a single pot, next[i].ball in a list.
    const physics::FieldPath at = p.next.size() == 1 && !p.next_is_list
                                      ? physics::FieldPath{"next"}
                                      : physics::FieldPath{"next", static_cast<int>(i)};
    if (!is_ball(n.ball))
      return invalid(at / "ball", fmt::format("names no object ball on the table: \"{}\"", n.ball));
    if (p.pot && n.ball == p.pot->ball)
      return invalid(at / "ball",
                     fmt::format("names the pot's own ball \"{}\", which this stroke pots", n.ball));
    for (size_t j = 0; j < i; ++j)
      if (p.next[j].ball == n.ball)
        return invalid(at / "ball", fmt::format("names \"{}\" a second time", n.ball));
    if (n.pocket < 0 || n.pocket >= static_cast<int>(p.scene.pockets.size()))
      return invalid(at / "pocket",
                     p.scene.pockets.empty() ? "names a pocket, but the table has none"
                                             : "names no pocket of this table",
                     n.pocket);
  }
  if (!p.obstacle_names.empty() && p.obstacle_names.size() != p.scene.obstacles.size())
    return invalid({"obstacles"}, "names some obstacles but not all");
  return {};
}

std::string Problem::required_first_contact() const {
  // A class that allows the pot's ball: the pot's ball is the one to strike.
  if (first_contact && pot && is_contact_class(*first_contact)) return pot->ball;
  if (first_contact) return *first_contact;
  return pot ? pot->ball : std::string();
}

namespace {

// True when `phi` lies in [lo, hi] (deg) up to whole turns.
bool aim_within(double phi, double lo, double hi) {
  constexpr double kSlack = 1e-9;  // deg
  const double turns = std::floor((phi - lo) / 360.0);
  const double shifted = phi - 360.0 * turns;  // in [lo, lo + 360)
  return shifted <= hi + kSlack || shifted >= lo + 360.0 - kSlack;
}

std::string describe_aim(const AimLimit& aim) {
  switch (aim.mode) {
    case AimMode::free: return "aim free";
    case AimMode::fixed: return fmt::format("aim {:.6g} deg", aim.lo_deg);
    case AimMode::range: return fmt::format("aim {:.6g} to {:.6g} deg", aim.lo_deg, aim.hi_deg);
  }
  return "aim ?";
}

}  // namespace

std::string describe(const Problem& p) {
  const physics::Scene& s = p.scene;
  const physics::CushionParams& b = s.ball_and_cushion;
  std::string text = p.name + "  (" + p.source + ")\n";
  text += fmt::format("  table {:.4g} x {:.4g} m, ", s.length, s.width);
  if (s.pockets.empty()) {
    text += "no pockets";
  } else if (const auto& jaws = s.pockets.front().jaws) {
    const physics::PocketShape& c = jaws->shape;
    text += fmt::format("{} jawed pockets (corner mouth {:.4g} mm, facings {:.3g} deg, shelf {:.3g} mm, "
                        "hole radius {:.4g} mm",
                        s.pockets.size(), 1e3 * c.mouth, c.wall_angle_deg, 1e3 * c.shelf,
                        1e3 * c.hole_radius);
    if (s.pockets.size() == 6 && s.pockets[1].jaws)
      text += fmt::format("; middle mouth {:.4g} mm", 1e3 * s.pockets[1].jaws->shape.mouth);
    text += ")";
  } else {
    text += fmt::format("{} pockets (capture radius {:.4g} mm)", s.pockets.size(),
                        1e3 * s.pockets.front().radius);
  }
  text += fmt::format("; ball R {:.5g} mm, {:.4g} g\n", 1e3 * b.radius, 1e3 * b.mass);
  text += fmt::format("  cloth mu_s {:.4g}, mu_r {:.4g}, mu_sp {:.4g}, g {:.4g} m/s^2; cushion mu_w {:.4g}, e {:.4g}, "
      "h {:.5g} mm\n",
      s.cloth.mu_slide, s.cloth.mu_roll, s.cloth.mu_spin, s.cloth.gravity, b.mu_cushion,
      b.restitution, 1e3 * b.cushion_height);
  text += fmt::format("  cue ball ({:.4f}, {:.4f}) m -> target ({:.4f}, {:.4f}) m within {:.4g} mm", p.cue_ball.x,
                 p.cue_ball.y, p.target.x, p.target.y, 1e3 * p.tolerance);
  if (!s.obstacles.empty())
    text += fmt::format("; {} obstacle{}", s.obstacles.size(), s.obstacles.size() == 1 ? "" : "s");
  if (!s.balls.empty()) {
    std::string names;
    for (const physics::ObjectBall& ball : s.balls)
      names += (names.empty() ? "" : ", ") + ball.name;
    text +=
        fmt::format("\n  object ball{} {} (ball-ball {}, mu_b {:.4g}, e_b {:.4g})",
                    s.balls.size() == 1 ? "" : "s", names, physics::to_string(s.ball_contact.model),
                    s.ball_contact.mu_ball, s.ball_contact.restitution);
  }
  if (p.pot) text += fmt::format("\n  pot {} into {}", p.pot->ball, pocket_name(s, p.pot->pocket));
  for (size_t i = 0; i < p.next.size(); ++i)
    text += fmt::format("\n  {} {} into {}", i == 0 ? "then" : "and then", p.next[i].ball,
                        pocket_name(s, p.next[i].pocket));
  if (p.first_contact) text += fmt::format("; first contact {}", *p.first_contact);
  const Limits& l = p.limits;
  text += fmt::format("\n  limits: speed {:.4g}-{:.4g} m/s, spin <= {:.4g}, {}, ", l.speed_min, l.speed_max,
                 l.spin_max, describe_aim(l.aim).c_str());
  text += l.cushions_min == l.cushions_max
              ? fmt::format("{} cushion{}", l.cushions_min, l.cushions_min == 1 ? "" : "s")
              : fmt::format("{}-{} cushions", l.cushions_min, l.cushions_max);
  return text + "\n";
}

std::string check_shot(const Limits& limits, const physics::Shot& shot) {
  constexpr double kSlack = 1e-12;  // relative, so bounds written in the file are inside
  if (!std::isfinite(shot.speed) || shot.speed < limits.speed_min * (1 - kSlack) ||
      shot.speed > limits.speed_max * (1 + kSlack))
    return fmt::format("speed {:.6g} m/s lies outside [{:.6g}, {:.6g}] m/s", shot.speed, limits.speed_min,
                  limits.speed_max);
  const double spin = std::hypot(shot.topspin_k, shot.sidespin_k);
  if (!std::isfinite(spin) || spin > limits.spin_max * (1 + kSlack))
    return fmt::format("spin sqrt(k_T^2 + k_S^2) = {:.6g} exceeds {:.6g}", spin, limits.spin_max);
  if (!(shot.elevation_deg >= limits.elevation_min_deg - kSlack &&
        shot.elevation_deg <= limits.elevation_max_deg + kSlack))
    return fmt::format("elevation {:.6g} deg lies outside [{:.6g}, {:.6g}] deg", shot.elevation_deg,
                       limits.elevation_min_deg, limits.elevation_max_deg);
  const AimLimit& aim = limits.aim;
  if (!std::isfinite(shot.aim_deg))
    return "aim must be finite";
  if (aim.mode != AimMode::free && !aim_within(shot.aim_deg, aim.lo_deg, aim.hi_deg))
    return fmt::format("aim {:.6g} deg lies outside [{:.6g}, {:.6g}] deg", shot.aim_deg, aim.lo_deg,
                  aim.hi_deg);
  return {};
}

double miss_distance(const Problem& problem, const physics::ShotResult& result) {
  if (result.status != physics::ShotStatus::rest)
    return std::numeric_limits<double>::infinity();
  if (!problem.has_target) return 0.0;
  return std::hypot(result.final_position.x - problem.target.x,
                    result.final_position.y - problem.target.y);
}

bool makes_pot(const Problem& problem, const physics::ShotResult& result) {
  if (!problem.pot) return false;
  for (const physics::BallOutcome& b : result.balls)
    if (b.name == problem.pot->ball) return b.pocketed && b.pocket == problem.pot->pocket;
  return false;
}

std::string pocket_name(const physics::Scene& scene, int pocket) {
  const std::vector<physics::Pocket> standard =
      scene.pockets.empty()
          ? std::vector<physics::Pocket>{}
          : physics::standard_pockets(scene.length, scene.width, scene.pockets.front().radius);
  const bool named = scene.pockets.size() == standard.size() &&
                     std::equal(standard.begin(), standard.end(), scene.pockets.begin(),
                                [](const physics::Pocket& a, const physics::Pocket& b) {
                                  return a.centre.x == b.centre.x && a.centre.y == b.centre.y &&
                                         a.radius == b.radius;
                                });
  const bool jawed = scene.pockets.size() == 6 &&
                     std::all_of(scene.pockets.begin(), scene.pockets.end(),
                                 [](const physics::Pocket& p) { return p.jaws.has_value(); });
  if ((named || jawed) && pocket >= 0 && pocket < 6) return kPocketNames[pocket];
  return fmt::format("pocket {}", pocket);
}

int cushions_before_contact(const physics::ShotResult& result) {
  if (result.balls.empty()) return 0;
  int n = 0;
  for (const physics::ShotEvent& e : result.balls.front().events) {
    if (e.type == physics::EventType::ball_contact) break;
    if (e.type == physics::EventType::cushion) ++n;
  }
  return n;
}

bool reaches_target(const Problem& problem, const physics::ShotResult& result) {
  return outcome_failure(problem, result) == Failure::none;
}

const char* to_string(Failure failure) {
  switch (failure) {
    case Failure::none: return "none";
    case Failure::outside_limits: return "outside_limits";
    case Failure::no_outcome: return "no_outcome";
    case Failure::obstacle: return "obstacle";
    case Failure::cue_ball_pocketed: return "cue_ball_pocketed";
    case Failure::first_contact: return "first_contact";
    case Failure::pot_missed: return "pot_missed";
    case Failure::wrong_pocket: return "wrong_pocket";
    case Failure::other_ball_pocketed: return "other_ball_pocketed";
    case Failure::cushions: return "cushions";
    case Failure::off_target: return "off_target";
  }
  return "?";
}

namespace {

// A broken condition; its reason put in words only when `kExplain` (the planner's inner
// loops count outcomes by the thousand and never show why).
template <bool kExplain, class Reason>
Verdict broken(Failure failure, Reason&& reason) {
  if constexpr (kExplain) return {failure, std::string(reason())};
  else return {failure, {}};
}

std::string count_range(int lo, int hi) {
  return lo == hi ? fmt::format("{}", lo) : fmt::format("{}-{}", lo, hi);
}

const physics::BallOutcome* outcome_of(const physics::ShotResult& result, const std::string& name) {
  for (const physics::BallOutcome& b : result.balls)
    if (b.name == name) return &b;
  return nullptr;
}

// check_outcome's judgement; with `kExplain` false the reason is left empty.
template <bool kExplain>
Verdict judge_outcome(const Problem& problem, const physics::ShotResult& result) {
  using physics::ShotStatus;
  switch (result.status) {
    case ShotStatus::rest: break;
    case ShotStatus::pocketed:
      return broken<kExplain>(Failure::cue_ball_pocketed, [] { return "the cue ball is pocketed"; });
    case ShotStatus::hit_obstacle: {
      for (const physics::BallOutcome& b : result.balls)
        if (!b.events.empty() && b.events.back().type == physics::EventType::obstacle)
          return broken<kExplain>(Failure::obstacle, [&] {
            return fmt::format("{} touches obstacles[{}]",
                               b.name == physics::kCueBallName ? "the cue ball" : b.name,
                               b.events.back().index);
          });
      return broken<kExplain>(Failure::obstacle, [] { return "a ball touches an obstacle ball"; });
    }
    default:
      return broken<kExplain>(Failure::no_outcome, [&] {
        return fmt::format("no outcome ({}): {}", physics::to_string(result.status),
                           result.message);
      });
  }
  const std::string first = problem.required_first_contact();
  if (!first.empty()) {
    const int k = result.first_contact;
    if (k <= 0 || k >= static_cast<int>(result.balls.size()))
      return broken<kExplain>(Failure::first_contact, [&] {
        return fmt::format("the cue ball strikes no ball ({} first)", first);
      });
    const std::string& struck = result.balls[static_cast<size_t>(k)].name;
    if (is_contact_class(first)) {
      if (!contact_allowed(first, struck, problem.scene.balls))
        return broken<kExplain>(Failure::first_contact, [&] {
          return fmt::format("foul: first contact on {} ({} asked for)", struck, first);
        });
    } else if (struck != first) {
      return broken<kExplain>(Failure::first_contact, [&] {
        return fmt::format("the cue ball strikes {} first, not {}", struck, first);
      });
    }
    const int before = cushions_before_contact(result);
    const Limits& l = problem.limits;
    if (before < l.cushions_before_contact_min || before > l.cushions_before_contact_max)
      return broken<kExplain>(Failure::cushions, [&] {
        return fmt::format(
            "the cue ball meets {} cushion{} before it strikes {}, outside the allowed {}", before,
            before == 1 ? "" : "s", struck,
            count_range(l.cushions_before_contact_min, l.cushions_before_contact_max));
      });
  }
  if (problem.pot) {
    const Pot& pot = *problem.pot;
    const physics::BallOutcome* ball = outcome_of(result, pot.ball);
    if (ball != nullptr && !ball->pocketed && ball->jaw_hits > 0) {
      int jaw_pocket = -1;
      for (const physics::ShotEvent& e : ball->events)
        if (e.type == physics::EventType::jaw) jaw_pocket = e.index;
      return broken<kExplain>(Failure::pot_missed, [&] {
        return fmt::format(
            "{} rattled out of the jaws of the {} pocket (it stops at x = {:.4g} m, y = {:.4g} m)",
            pot.ball, pocket_name(problem.scene, jaw_pocket), ball->final_position.x,
            ball->final_position.y);
      });
    }
    if (ball == nullptr || !ball->pocketed)
      return broken<kExplain>(Failure::pot_missed, [&] {
        return fmt::format("{} does not drop (it stops at x = {:.4g} m, y = {:.4g} m)", pot.ball,
                           ball ? ball->final_position.x : 0.0,
                           ball ? ball->final_position.y : 0.0);
      });
    if (ball->pocket != pot.pocket)
      return broken<kExplain>(Failure::wrong_pocket, [&] {
        return fmt::format("{} drops in the {} pocket, not the {}", pot.ball,
                           pocket_name(problem.scene, ball->pocket),
                           pocket_name(problem.scene, pot.pocket));
      });
    const Limits& l = problem.limits;
    if (ball->cushion_hits < l.object_cushions_min || ball->cushion_hits > l.object_cushions_max)
      return broken<kExplain>(Failure::cushions, [&] {
        return fmt::format("{} meets {} cushion{} before it drops, outside the allowed {}",
                           pot.ball, ball->cushion_hits, ball->cushion_hits == 1 ? "" : "s",
                           count_range(l.object_cushions_min, l.object_cushions_max));
      });
    for (const physics::BallOutcome& b : result.balls)
      if (b.pocketed && b.name != pot.ball && b.name != physics::kCueBallName)
        return broken<kExplain>(Failure::other_ball_pocketed, [&] {
          return fmt::format("{} drops too (in the {} pocket)", b.name,
                             pocket_name(problem.scene, b.pocket));
        });
  }
  const Limits& l = problem.limits;
  if (result.cushion_hits < l.cushions_min || result.cushion_hits > l.cushions_max)
    return broken<kExplain>(Failure::cushions, [&] {
      return fmt::format("the cue ball meets {} cushion{}, outside the allowed {}",
                         result.cushion_hits, result.cushion_hits == 1 ? "" : "s",
                         count_range(l.cushions_min, l.cushions_max));
    });
  const double miss = miss_distance(problem, result);
  if (!(miss <= problem.tolerance))
    return broken<kExplain>(Failure::off_target, [&] {
      return fmt::format("the cue ball stops {:.3g} mm from the target (tolerance {:.3g} mm)",
                         1e3 * miss, 1e3 * problem.tolerance);
    });
  return {};
}

}  // namespace

Verdict check_outcome(const Problem& problem, const physics::ShotResult& result) {
  return judge_outcome<true>(problem, result);
}

Failure outcome_failure(const Problem& problem, const physics::ShotResult& result) {
  return judge_outcome<false>(problem, result).failure;
}

Verdict check_stroke(const Problem& problem, const physics::Shot& shot,
                     const physics::ShotResult& result) {
  if (std::string why = check_shot(problem.limits, shot); !why.empty())
    return {Failure::outside_limits, std::move(why)};
  return check_outcome(problem, result);
}

}  // namespace cueplan::problems
