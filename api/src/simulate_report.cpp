// One simulated shot reported: in words, as JSON, and its trace (CSV, JSON).
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

std::string point(phys::Vec2 p) { return "(" + number(p.x) + ", " + number(p.y) + ") m"; }

double speed_of(const phys::ShotEvent& e) { return std::hypot(e.velocity.x, e.velocity.y); }

// How the ball moves after an event: the piece of its path that starts there, if any.
const char* motion_after(const phys::BallOutcome& ball, const phys::ShotEvent& e) {
  for (const phys::PathSegment& s : ball.path)
    if (s.t0 == e.time) return phys::to_string(s.motion);
  return "-";
}

// The name of ball k of a result (0: the cue ball).
const std::string& ball_name(const phys::ShotResult& r, int k) {
  return r.balls.at(static_cast<size_t>(k)).name;
}

}  // namespace

// The first ball the cue ball struck, by name, or none.
std::string first_contact_name(const phys::ShotResult& r) {
  return r.first_contact > 0 ? ball_name(r, r.first_contact) : std::string();
}

namespace {

std::string event_detail(const prob::Problem& problem, const phys::ShotResult& r,
                         const phys::ShotEvent& e) {
  const phys::Scene& scene = problem.scene;
  switch (e.type) {
    case phys::EventType::ball_contact:
      return "ball " + ball_name(r, e.other) + ", approach " + number(e.normal_speed, "m/s") +
             ", impulse " + number(e.impulse, "N s");
    case phys::EventType::cushion: {
      std::string text = "cushion " + cushion_name(scene, e.cushion) + ", normal speed " +
                         number(e.normal_speed, "m/s");
      if (e.normal_speed > scene.ball_and_cushion.rigid_speed_limit)
        text += " (above the rigid-cushion limit)";
      return text;
    }
    case phys::EventType::jaw: {
      static constexpr const char* kParts[] = {"left point", "left facing", "right facing",
                                               "right point"};
      const std::string part = e.cushion >= 0 && e.cushion < 4 ? kParts[e.cushion] : "jaw";
      return "pocket " + std::to_string(e.index) + " (" + prob::pocket_name(scene, e.index) +
             ") " + part + ", normal speed " + number(e.normal_speed, "m/s");
    }
    case phys::EventType::pocket:
      return "pocket " + std::to_string(e.index) + " (" + prob::pocket_name(scene, e.index) +
             ") at " + point(scene.pockets.at(static_cast<size_t>(e.index)).centre);
    case phys::EventType::obstacle:
      return "obstacles[" + std::to_string(e.index) + "] at " +
             point(scene.obstacles.at(static_cast<size_t>(e.index)));
    case phys::EventType::spin_stop:
      return "sidespin spent";
    default:
      return {};
  }
}

std::string status_text(const phys::ShotResult& r) {
  std::string text = phys::to_string(r.status);
  switch (r.status) {
    case phys::ShotStatus::rest:
      return text + " (came to rest on the table)";
    case phys::ShotStatus::pocketed:
      return text + " (entered pocket " + std::to_string(r.events.back().index) + ")";
    case phys::ShotStatus::hit_obstacle:
      // The ball that touched it: its last event is the contact.
      for (const phys::BallOutcome& b : r.balls)
        if (!b.events.empty() && b.events.back().type == phys::EventType::obstacle)
          return text + " (" + (b.name == phys::kCueBallName ? "" : b.name + " ") +
                 "touched obstacles[" + std::to_string(b.events.back().index) + "])";
      return text;
    default:
      return text + ": " + r.message;
  }
}

std::string rigid_limit_warning(const prob::Problem& problem, const phys::ShotResult& r) {
  return "warning: a cushion normal speed of " + number(r.max_cushion_normal_speed, "m/s") +
         " exceeded the rigid-cushion limit of " +
         number(problem.scene.ball_and_cushion.rigid_speed_limit, "m/s") +
         "; the model trusts a rigid cushion only below it";
}


}  // namespace

TargetReport target_report(const prob::Problem& problem, const phys::Shot& shot,
                           const phys::ShotResult& r) {
  TargetReport t;
  t.miss = prob::miss_distance(problem, r);
  t.in_zone = t.miss <= problem.tolerance;
  t.reaches = prob::reaches_target(problem, r);
  t.limits = prob::check_shot(problem.limits, shot);
  t.verdict = prob::check_stroke(problem, shot, r);
  return t;
}

namespace {

// One ball's events as a table under `label`.
void write_events(std::ostream& out, const prob::Problem& problem, const phys::ShotResult& r,
                  const phys::BallOutcome& ball, const std::string& label) {
  report_line(out, label,
              std::to_string(ball.events.size()) + " (speed and motion just after each event)");
  out << fmt::format("  {:>3}  {:<14} {:>9} {:>9} {:>9} {:>11}  {:<8} {}\n", "#", "event", "t (s)",
                     "x (m)", "y (m)", "v (m/s)", "then", "detail");
  for (size_t i = 0; i < ball.events.size(); ++i) {
    const phys::ShotEvent& e = ball.events[i];
    std::string row = fmt::format("  {:3}  {:<14} {:9.4f} {:9.4f} {:9.4f} {:11.4f}  {:<8} ", i,
                                  phys::to_string(e.type), e.time, e.position.x, e.position.y,
                                  speed_of(e), motion_after(ball, e)) +
                      event_detail(problem, r, e);
    while (!row.empty() && row.back() == ' ') row.pop_back();
    out << row << '\n';
  }
}

void write_text(std::ostream& out, const prob::Problem& problem, const phys::Shot& shot,
                const phys::SimulationOptions& options, const phys::ShotResult& r,
                const std::string& svg_file, const std::optional<SimulatedSuccess>& success) {
  const auto line = [&](std::string_view label, const std::string& text) {
    report_line(out, label, text);
  };
  const phys::Scene& scene = problem.scene;
  const double spin_unit = shot.speed / scene.radius();  // rad/s per unit of k
  const TargetReport target = target_report(problem, shot, r);

  line("problem", problem.name + "  (" + problem.source + ")");
  line("shot", "V = " + number(shot.speed, "m/s") + " at aim " + number(shot.aim_deg, "deg") +
                   ", k_T = " + number(shot.topspin_k) +
                   " (w_T = " + number(shot.topspin_k * spin_unit, "rad/s") +
                   "), k_S = " + number(shot.sidespin_k) +
                   " (w_S = " + number(shot.sidespin_k * spin_unit, "rad/s") + ")" +
                   (shot.elevation_deg > 0.0
                        ? ", cue elevated " + number(shot.elevation_deg, "deg")
                        : std::string()));
  if (const std::string s = squirt_words(scene, shot); !s.empty()) line("squirt", s);
  line("cue ball",
       "x = " + number(problem.cue_ball.x, "m") + ", y = " + number(problem.cue_ball.y, "m"));
  line("status", status_text(r));
  line("final position",
       "x = " + number(r.final_position.x, "m") + ", y = " + number(r.final_position.y, "m"));
  line("duration", number(r.duration, "s"));
  line("cushion hits", std::to_string(r.cushion_hits));
  line("pocketed", r.status == phys::ShotStatus::pocketed ? "yes" : "no");
  line("hit obstacle", r.status == phys::ShotStatus::hit_obstacle ? "yes" : "no");
  if (!problem.has_target) {
    line("target", "none: a pure pot, the cue ball may stop anywhere");
  } else {
    line("target", "x = " + number(problem.target.x, "m") + ", y = " + number(problem.target.y, "m") +
                       ", tolerance " + number(problem.tolerance, "m"));
    if (std::isfinite(target.miss))
      line("miss distance",
           number(target.miss, "m") +
               (target.in_zone ? ": inside the target zone" : ": outside the target zone"));
    else
      line("miss distance", "none: the ball did not come to rest on the table");
  }
  if (problem.pot || problem.first_contact)
    line("solves problem",
         target.verdict.solves()
             ? "yes: " + (problem.pot ? problem.pot->ball + " drops in the " +
                                            prob::pocket_name(scene, problem.pot->pocket) +
                                            " pocket cleanly"
                                      : "the cue ball strikes " + *problem.first_contact + " first") +
                   (problem.has_target ? ", and the cue ball rests in the target zone" : "")
             : "no: " + target.verdict.reason);
  else
    line("solves problem",
         std::string(target.reaches ? "yes" : "no") + ": " +
             (target.in_zone ? "at rest in the target zone" : "not at rest in the target zone") +
             " after " + std::to_string(r.cushion_hits) + " cushion" +
             (r.cushion_hits == 1 ? "" : "s") + " (the problem allows " +
             cushions_allowed(problem.limits) + ")");
  line("limits", target.limits.empty() ? "the shot lies within the problem's limits"
                                       : "outside the problem's limits: " + target.limits);
  if (success) {
    const planner::Success& s = success->success;
    line("success", estimate_text(s.both) + " of " + std::to_string(s.both.samples) +
                        " noisy strokes solve the problem" + pot_success_words(s) +
                        " (noise: " + noise_text(success->noise) +
                        "; seed " + std::to_string(success->seed) + ")");
  }
  line("method", method_text(options, scene));
  if (r.cushion_hits > 0)
    line("cushion speed", "max normal speed " + number(r.max_cushion_normal_speed, "m/s") +
                              " (rigid-cushion limit " +
                              number(scene.ball_and_cushion.rigid_speed_limit, "m/s") + ")");
  if (!svg_file.empty()) line("drawing", svg_file);

  if (r.balls.size() > 1) {
    line("first contact", r.first_contact > 0 ? first_contact_name(r) : "none");
    line("balls", std::to_string(r.balls.size()) + " (the cue ball first)");
    out << fmt::format("  {:<12} {:>9} {:>9}  {:<22} {:>8} {:>6}\n", "ball", "x (m)", "y (m)",
                       "pocketed", "cushions", "events");
    for (const phys::BallOutcome& b : r.balls) {
      const std::string pocketed =
          b.pocketed ? "yes, " + prob::pocket_name(scene, b.pocket) : std::string("no");
      out << fmt::format("  {:<12} {:9.4f} {:9.4f}  {:<22} {:>8} {:>6}\n", b.name,
                         b.final_position.x, b.final_position.y, pocketed, b.cushion_hits,
                         b.events.size());
    }
  }
  for (size_t k = 0; k < r.balls.size(); ++k) {
    const phys::BallOutcome& ball = r.balls[k];
    if (k > 0 && ball.events.empty()) continue;
    write_events(out, problem, r, ball, k == 0 ? "events" : "events of " + ball.name);
  }
  if (r.rigid_limit_exceeded) out << rigid_limit_warning(problem, r) << '\n';
}

nlohmann::ordered_json vec(phys::Vec2 v) { return {v.x, v.y}; }

// One ball's events as JSON.
nlohmann::ordered_json events_json(const phys::Scene& scene, const phys::ShotResult& r,
                                   const phys::BallOutcome& ball) {
  nlohmann::ordered_json events = nlohmann::ordered_json::array();
  for (const phys::ShotEvent& e : ball.events) {
    nlohmann::ordered_json j;
    j["type"] = phys::to_string(e.type);
    j["time"] = e.time;
    j["position"] = vec(e.position);
    j["velocity"] = vec(e.velocity);
    j["speed"] = speed_of(e);
    j["spin"] = {e.spin.x, e.spin.y, e.spin.z};
    j["motion_after"] = motion_after(ball, e);
    if (e.type == phys::EventType::cushion) {
      j["cushion"] = e.cushion;
      j["cushion_line"] = cushion_name(scene, e.cushion);
      j["normal_speed"] = e.normal_speed;
    }
    if (e.type == phys::EventType::pocket) j["pocket"] = e.index;
    if (e.type == phys::EventType::jaw) {
      j["pocket"] = e.index;
      j["jaw_part"] = e.cushion;  // 0 left point, 1 left facing, 2 right facing, 3 right point
      j["normal_speed"] = e.normal_speed;
    }
    if (e.type == phys::EventType::obstacle) j["obstacle"] = e.index;
    if (e.type == phys::EventType::ball_contact) {
      j["ball"] = ball_name(r, e.other);
      j["approach_speed"] = e.normal_speed;
      j["impulse"] = e.impulse;
    }
    events.push_back(std::move(j));
  }
  return events;
}

nlohmann::ordered_json path_json(const std::vector<phys::PathSegment>& path) {
  nlohmann::ordered_json segments = nlohmann::ordered_json::array();
  for (const phys::PathSegment& s : path)
    segments.push_back({{"t0", s.t0},
                        {"t1", s.t1},
                        {"p0", vec(s.p0)},
                        {"v0", vec(s.v0)},
                        {"accel", vec(s.accel)},
                        {"motion", phys::to_string(s.motion)}});
  return segments;
}

}  // namespace

nlohmann::ordered_json simulate_json(const prob::Problem& problem, const phys::Shot& shot,
                                     const phys::SimulationOptions& options,
                                     const phys::ShotResult& r, const std::string& svg_file,
                                     const std::optional<SimulatedSuccess>& success) {
  using nlohmann::ordered_json;
  const phys::Scene& scene = problem.scene;
  const TargetReport target = target_report(problem, shot, r);

  ordered_json balls = ordered_json::array();
  for (const phys::BallOutcome& b : r.balls)
    balls.push_back(
        {{"name", b.name},
         {"final_position", vec(b.final_position)},
         {"pocketed", b.pocketed},
         {"pocket", b.pocketed ? ordered_json(prob::pocket_name(scene, b.pocket)) : ordered_json()},
         {"cushion_hits", b.cushion_hits},
         {"events", events_json(scene, r, b)},
         {"path", path_json(b.path)}});

  ordered_json j;
  j["problem"] = {{"name", problem.name}, {"source", problem.source}};
  j["shot"] = {{"speed", shot.speed},
               {"aim_deg", shot.aim_deg},
               {"topspin_k", shot.topspin_k},
               {"sidespin_k", shot.sidespin_k},
               {"elevation_deg", shot.elevation_deg},
               {"squirt_deg", squirt_deg(scene, shot)}};
  j["status"] = phys::to_string(r.status);
  j["message"] = r.message;
  if (r.rigid_limit_exceeded) j["warning"] = rigid_limit_warning(problem, r);
  j["final_position"] = vec(r.final_position);
  j["duration"] = r.duration;
  j["cushion_hits"] = r.cushion_hits;
  j["pocketed"] = r.status == phys::ShotStatus::pocketed;
  j["hit_obstacle"] = r.status == phys::ShotStatus::hit_obstacle;
  j["cue_ball"] = vec(problem.cue_ball);
  j["target"] = problem.has_target ? vec(problem.target) : ordered_json();
  j["tolerance"] = problem.tolerance;
  // null when the ball did not come to rest on the table (JSON has no infinity)
  j["miss_distance"] = std::isfinite(target.miss) ? ordered_json(target.miss) : ordered_json();
  j["in_target_zone"] = target.in_zone;
  j["reaches_target"] = target.reaches;
  j["within_limits"] = target.limits.empty();
  j["limits_message"] = target.limits;
  j["failure"] = {{"condition", prob::to_string(target.verdict.failure)},
                  {"reason", target.verdict.reason}};
  if (success) {
    j["success"] = success_json(success->success);
    const planner::NoiseModel& n = success->noise;
    j["noise"] = {{"scale", n.scale},
                  {"aim_deg", n.aim_deg},
                  {"speed", n.speed},
                  {"tip_offset", n.tip_offset},
                  {"tip_offset_relative", n.tip_offset_relative},
                  {"squirt_judgement", n.squirt_judgement},
                  {"bridge_length", n.bridge_length},
                  {"seed", success->seed}};
  }
  j["max_cushion_normal_speed"] = r.max_cushion_normal_speed;
  j["rigid_limit_exceeded"] = r.rigid_limit_exceeded;
  j["cushion_model"] = phys::to_string(r.cushion_model);
  j["method"] = phys::to_string(phys::chosen_impact_method(scene, options));
  j["method_requested"] = phys::to_string(options.impact_method);
  j["impact_accuracy"] = options.impact_accuracy;
  j["max_events"] = options.max_events;
  if (!svg_file.empty()) j["svg"] = svg_file;
  j["events"] = r.balls.empty() ? ordered_json::array() : events_json(scene, r, r.balls[0]);
  j["path"] = path_json(r.path);
  // Every ball, the cue ball first (its entry repeats the keys above).
  j["balls"] = balls;
  j["first_contact"] = r.first_contact > 0 ? ordered_json(first_contact_name(r)) : ordered_json();
  j["units"] = {{"frame",
                 "table: origin where the cushion noses x = 0 and y = 0 meet, x along the "
                 "length, y along the width"},
                {"position", "m"},
                {"time", "s"},
                {"duration", "s"},
                {"velocity", "m/s"},
                {"speed", "m/s"},
                {"spin", "rad/s"},
                {"accel", "m/s^2"},
                {"approach_speed", "m/s, along the line of centres"},
                {"impulse", "N s, normal"},
                {"aim_deg", "deg from +x, counter-clockwise"},
                {"topspin_k", "k_T = w_T R / V"},
                {"sidespin_k", "k_S = w_S R / V, > 0 right spin"},
                {"elevation_deg", "deg, the cue above the horizontal"},
                {"squirt_deg", "deg from the cue's line to the cue ball's, > 0 counter-clockwise"},
                {"tolerance", "m"},
                {"miss_distance", "m"},
                {"success", "fractions of noisy strokes, 0..1, with 95 % Wilson intervals"},
                {"noise", "standard deviations: aim deg, speed m/s, tip_offset m"},
                {"impact_accuracy", "relative to the speed"}};
  return j;
}

// The trace's CSV columns, units in their names.
constexpr const char* kTraceHeader =
    "t_s,ball,x_m,y_m,vx_mps,vy_mps,wx_radps,wy_radps,wz_radps,motion,event";

void write_trace_csv(std::ostream& out, const phys::ShotTrace& trace,
                     const phys::ShotResult& r) {
  out << kTraceHeader << '\n';
  std::string line;
  for (const phys::BallSample& s : trace.samples) {
    line.clear();
    // Shortest forms that read back to the same doubles.
    fmt::format_to(std::back_inserter(line), "{},{},{},{},{},{},",
                   s.time, r.balls[static_cast<size_t>(s.ball)].name, s.position.x, s.position.y,
                   s.velocity.x, s.velocity.y);
    fmt::format_to(std::back_inserter(line), "{},{},{},{},{}\n", s.spin.x,
                   s.spin.y, s.spin.z, phys::to_string(s.motion),
                   s.event ? phys::to_string(*s.event) : "");
    out << line;
  }
}

nlohmann::ordered_json trace_json(const phys::ShotTrace& trace, const phys::ShotResult& r,
                                  double interval) {
  using nlohmann::ordered_json;
  ordered_json rows = ordered_json::array();
  for (const phys::BallSample& s : trace.samples)
    rows.push_back({{"t", s.time},
                    {"ball", r.balls[static_cast<size_t>(s.ball)].name},
                    {"position", {s.position.x, s.position.y}},
                    {"velocity", {s.velocity.x, s.velocity.y}},
                    {"spin", {s.spin.x, s.spin.y, s.spin.z}},
                    {"motion", phys::to_string(s.motion)},
                    {"event", s.event ? ordered_json(phys::to_string(*s.event)) : ordered_json()}});
  return {{"interval", interval}, {"end_time", trace.end_time}, {"samples", rows}};
}

void write_simulate_text(std::ostream& out, const prob::Problem& problem, const phys::Shot& shot,
                         const phys::SimulationOptions& options, const phys::ShotResult& r,
                         const std::string& svg_file,
                         const std::optional<SimulatedSuccess>& success) {
  write_text(out, problem, shot, options, r, svg_file, success);
}

}  // namespace cueplan::api
