#include "simulate_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>

#include "cueplan/draw/table.hpp"
#include "cueplan/physics/impact_table.hpp"
#include "cueplan/problems/problem.hpp"
#include "cueplan/problems/stroke_ranges.hpp"
#include "exit_codes.hpp"
#include "impact_setup.hpp"
#include "output_file.hpp"
#include "planner_flags.hpp"
#include "shot_report.hpp"
#include "shot_words.hpp"
#include "simulate_batch.hpp"

namespace cueplan::cli {
namespace {

namespace phys = cueplan::physics;
namespace prob = cueplan::problems;

constexpr const char* kCommandName = "cueplan simulate";

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

// The first ball the cue ball struck, by name, or none.
std::string first_contact_name(const phys::ShotResult& r) {
  return r.first_contact > 0 ? ball_name(r, r.first_contact) : std::string();
}

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

// Everything the text and JSON reports say about the target.
struct TargetReport {
  double miss = 0.0;  // m; +inf when the ball did not come to rest on the table
  bool in_zone = false;
  bool reaches = false;
  std::string limits;  // empty when the shot lies within the problem's limits
  prob::Verdict verdict;  // every condition of the problem, the stroke's limits first
};

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

namespace {

// The title and caption of the drawing: the shot, then what came of it.
draw::TableScene drawing_of(const prob::Problem& problem, const phys::Shot& shot,
                            const phys::SimulationOptions& options, const phys::ShotResult& r) {
  draw::TableScene d = draw::problem_table(problem);
  d.balls.front().paths.push_back({r.path, r.events, false});
  // Each object ball that moved, along its own path in its colour (problem_table puts
  // them after the cue ball, by name).
  for (size_t k = 1; k < r.balls.size(); ++k) {
    const phys::BallOutcome& b = r.balls[k];
    if (b.path.empty()) continue;
    for (draw::DrawnBall& drawn : d.balls)
      if (drawn.name == b.name) drawn.paths.push_back({b.path, b.events, false, 0, drawn.colour});
  }

  std::string buf;
  buf = fmt::format("{}: V = {:.4g} m/s, aim {:.4g}\u00b0, k_{{T}} = {:.3g}, k_{{S}} = {:.3g}",
                problem.name.c_str(), shot.speed, shot.aim_deg, shot.topspin_k, shot.sidespin_k);
  d.title = buf;

  const TargetReport target = target_report(problem, shot, r);
  const std::string cushions =
      std::to_string(r.cushion_hits) + (r.cushion_hits == 1 ? " cushion" : " cushions");
  std::string outcome;
  switch (r.status) {
    case phys::ShotStatus::rest:
      buf = fmt::format("At rest at ({:.4f}, {:.4f}) m after {} and {:.3g} s; {:.4g} mm from the target "
                    "(tolerance {:.4g} mm): {} the target zone{}.",
                    r.final_position.x, r.final_position.y, cushions.c_str(), r.duration,
                    1000.0 * target.miss, 1000.0 * problem.tolerance,
                    target.in_zone ? "inside" : "outside",
                    target.reaches ? ", problem solved" : "");
      break;
    case phys::ShotStatus::pocketed:
    case phys::ShotStatus::hit_obstacle:
      buf = fmt::format("{} at ({:.4f}, {:.4f}) m after {} and {:.3g} s.",
                    r.status == phys::ShotStatus::pocketed ? "Pocketed" : "Hit an obstacle ball", r.final_position.x,
                    r.final_position.y, cushions.c_str(), r.duration);
      break;
    default:
      buf = fmt::format("Stopped ({}) after {}: {}", phys::to_string(r.status),
                    cushions.c_str(), r.message.c_str());
  }
  outcome = buf;
  if (r.first_contact > 0) {
    std::string pots;
    for (size_t k = 1; k < r.balls.size(); ++k)
      if (r.balls[k].pocketed)
        pots += fmt::format("{}{} in {}", pots.empty() ? "" : ", ", r.balls[k].name,
                            prob::pocket_name(problem.scene, r.balls[k].pocket));
    outcome += fmt::format(" First contact {}; {}.", first_contact_name(r),
                           pots.empty() ? "no object ball pocketed" : "pocketed " + pots);
  }
  if (r.rigid_limit_exceeded) outcome += " Rigid-cushion limit exceeded.";
  d.caption.push_back(outcome);

  const phys::CushionParams& b = problem.scene.ball_and_cushion;
  buf = fmt::format("Table {:.4g} \u00d7 {:.4g} m between the cushion noses, ball R = {:.4g} mm, "
                "cushion impacts: {}.",
                problem.scene.length, problem.scene.width, 1000.0 * b.radius,
                phys::to_string(phys::chosen_impact_method(problem.scene, options)));
  d.caption.push_back(buf);
  return d;
}

}  // namespace

SimulateCommand::SimulateCommand(CLI::App& parent) {
  command_ = parent.add_subcommand(
      "simulate",
      "Simulate one cue-ball shot on a problem file's table, from the strike until every ball "
      "rests, and report where the balls stop, every event and how far the cue ball lands "
      "from the target.");
  CLI::App& c = *command_;

  c.add_option("PROBLEM", args_.problem_file,
               "Problem file (YAML, problems/README.md): table, ball, cue ball, target")
      ->required()
      ->type_name("FILE.yaml");

  const char* stroke = "Shot";
  c.add_option("--speed", args_.speed,
               "Cue-ball speed V just after the strike (m/s), > 0. Required unless --batch is "
               "given.")
      ->type_name("m/s")
      ->group(stroke);
  c.add_option("--aim", args_.aim_deg,
               "Aim phi (deg from +x, counter-clockwise; +x runs along the table's length). "
               "Required unless --batch is given.")
      ->type_name("deg")
      ->group(stroke);
  c.add_option("--topspin-k", args_.topspin_k,
               "Topspin k_T = w_T R / V (0: centre-ball strike, the ball slides then rolls; "
               "1: natural roll; < 0: draw)")
      ->type_name("k_T")
      ->capture_default_str()
      ->group(stroke);
  c.add_option("--sidespin-k", args_.sidespin_k,
               "Sidespin k_S = w_S R / V (> 0: right spin, counter-clockwise seen from above)")
      ->type_name("k_S")
      ->capture_default_str()
      ->group(stroke);
  c.add_option("--elevation-deg", args_.elevation_deg,
               "The cue's elevation above the horizontal (deg, 0 <= e < 90): with side, the "
               "sliding cue ball swerves toward the side struck")
      ->type_name("deg")
      ->capture_default_str()
      ->group(stroke);

  const char* method = "Cushion impacts";
  c.add_option("--method", args_.method,
               "exact (Taylor-series integrator with stick/slip events), extrapolation (a "
               "second exact method, Gragg-Bulirsch-Stoer extrapolation), paper (the paper's "
               "fixed-step scheme, " + std::to_string(phys::ImpactOptions{}.paper_steps) +
                   " steps) or table (precomputed surrogate: the fast path for many shots; built "
                   "once, about 30 s on 2 cores, then loaded from the cache)")
      ->type_name("exact|extrapolation|paper|table")
      ->capture_default_str()
      ->group(method);
  c.add_option("--accuracy", args_.accuracy,
               "Relative error wanted from each cushion impact, in [1e-12, 0.1]. exact, "
               "extrapolation: their tolerance follows it; table: the table answers only if its "
               "measured error is within it (else exact does), and without this flag it is the "
               "table's measured error; paper: not used. Default 1e-09 (exact)")
      ->type_name("REL")
      ->group(method);
  c.add_option("--table-cache", args_.table_cache,
               "table: directory for the cached table (default: $CUEPLAN_CACHE_DIR, else "
               "$XDG_CACHE_HOME/cueplan, else ~/.cache/cueplan)")
      ->type_name("DIR")
      ->group(method);
  c.add_option("--max-events", args_.max_events,
               "Events (cushions, slide to roll, stops, ...) allowed before giving up, >= 1")
      ->type_name("N")
      ->capture_default_str()
      ->group(method);

  const char* output = "Output";
  auto* json =
      c.add_flag("--json", args_.json,
                 "Print one JSON object (SI units, table frame) instead of text: final_position, "
                 "cushion_hits, pocketed, hit_obstacle, events, duration, miss_distance, path "
                 "(the cue ball's), balls (every ball: name, final_position, pocketed, pocket, "
                 "cushion_hits, events, path), first_contact, ...")
          ->group(output);
  auto* svg = c.add_option("--svg", args_.svg_file,
                           "Also draw the table, pockets, obstacles, target zone and the ball's "
                           "path to scale, coloured by sliding and rolling, as a picture: SVG, "
                           "PNG or PDF by the file's extension")
                  ->type_name("FILE.svg|.png|.pdf")
                  ->group(output);
  auto* batch =
      c.add_option("--batch", args_.batch_file,
                   "Simulate every row of a CSV file with header "
                   "'speed,aim_deg,topspin_k,sidespin_k' (m/s, deg, k_T, k_S) and write CSV to "
                   "stdout: the input columns, then final_x,final_y (m),cushion_hits,pocketed,"
                   "hit_obstacle (1/0),duration (s),miss_distance (m; inf unless at rest),"
                   "reaches_target (1/0),status,message,first_contact (the object ball the cue "
                   "ball struck first),pocketed_balls (NAME:POCKET;...), each block of rows as "
                   "it is done; '-' reads standard input. A bad row gets its own error status "
                   "and the rest go on; a summary (rows, rows of each status) goes to stderr.")
          ->type_name("FILE.csv")
          ->group(output);
  const char* noise = "Success under a player's noise";
  auto* samples =
      c.add_option("--samples", args_.samples,
                   "Also estimate the stroke's success probability from N noisy strokes (the "
                   "planner's noise model), with its 95 % interval, >= 0; 0 skips it")
          ->type_name("N")
          ->capture_default_str()
          ->group(noise);
  c.add_option("--noise", args_.noise,
               "Scale of the noise (Gaussian: aim 0.125 deg, speed 0.075 m/s, tip offset 0.5 mm "
               "each way, times this), >= 0")
      ->type_name("X")
      ->capture_default_str()
      ->needs(samples)
      ->group(noise);
  c.add_option("--seed", args_.seed,
               "Seed of the noisy strokes: the same seed gives the same draws as cueplan solve's")
      ->type_name("N")
      ->capture_default_str()
      ->needs(samples)
      ->group(noise);
  auto* trace =
      c.add_option("--trace", args_.trace,
                   "Every ball's state every DT seconds (> 0) and at each of its events, "
                   "instead of the report: CSV with the header "
                   "t_s,ball,x_m,y_m,vx_mps,vy_mps,wx_radps,wy_radps,wz_radps,motion,event "
                   "(table frame; event empty between events); with --json, the report gains "
                   "`trace` {interval, end_time, samples: [{t, ball, position, velocity, spin, "
                   "motion, event}]}. At most " +
                       std::to_string(phys::kMaxTraceSamples) + " rows.")
          ->type_name("DT")
          ->group(output);
  c.add_option("--threads", args_.threads,
               "Batch: threads to spread the rows over (0: one per core); the output is the "
               "same for any count. Also used to build a table.")
      ->type_name("N")
      ->capture_default_str()
      ->needs(batch)
      ->group(output);
  batch->excludes(json);
  batch->excludes(svg);
  batch->excludes(samples);
  batch->excludes(trace);
  for (const char* flag : {"--speed", "--aim", "--topspin-k", "--sidespin-k", "--elevation-deg"})
    batch->excludes(c.get_option(flag));

  c.footer(
      "Frame: the origin is where the cushion noses x = 0 and y = 0 meet; x runs along the "
      "length, y along the width; cushions are named by their nose lines.\n"
      "Status (of the cue ball; the object balls' outcomes are listed with them): rest, "
      "pocketed, hit_obstacle (any ball touched an obstacle), event_limit (more than "
      "--max-events events of all balls), impact_failed or collision_failed. A cushion met "
      "faster than " +
      number(phys::CushionParams{}.rigid_speed_limit, "m/s") +
      " along its normal is solved but flagged: the rigid-cushion model is not trusted there.\n"
      "Exit codes: 0 simulated (at rest, pocketed or against an obstacle), 1 the simulation "
      "stopped without an outcome (event_limit, impact_failed, collision_failed; --batch: "
      "some row without one, or a bad row), 2 bad input (--batch: the command line, or a file "
      "that cannot be opened or has the wrong header).\n"
      "Example: cueplan simulate problems/one_rail_position.yaml --speed 1.002 --aim -60.36 "
      "--topspin-k 0.8 --sidespin-k 0");
}

bool SimulateCommand::selected() const { return command_->parsed(); }

bool SimulateCommand::given(const char* flag) const { return command_->count(flag) > 0; }

std::string SimulateCommand::read_options(phys::SimulationOptions* options) const {
  if (!phys::parse_method(args_.method, &options->impact_method))
    return "--method must be one of exact, extrapolation, paper, table, got '" + args_.method +
           "'";
  if (!std::isfinite(args_.accuracy) || !(args_.accuracy >= 1e-12) || !(args_.accuracy <= 0.1))
    return "--accuracy must lie in [1e-12, 0.1], got " + number(args_.accuracy);
  options->impact_accuracy = args_.accuracy;
  if (args_.max_events < 1)
    return "--max-events must be at least 1, got " + std::to_string(args_.max_events);
  options->max_events = args_.max_events;
  if (args_.threads < 0)
    return "--threads must be 0 (one per core) or more, got " + std::to_string(args_.threads);
  if (args_.samples < 0)
    return "--samples must not be negative, got " + std::to_string(args_.samples);
  if (!std::isfinite(args_.noise) || args_.noise < 0.0 || args_.noise > 10.0)
    return "--noise must be 0 to 10 (times a club player's scatter), got " + number(args_.noise);
  if (given("--trace") && (!std::isfinite(args_.trace) || !(args_.trace > 0.0)))
    return "--trace must be positive and finite (s between samples), got " + number(args_.trace);
  return {};
}

std::string SimulateCommand::read_shot(phys::Shot* shot) const {
  if (!given("--speed")) return "--speed is required (m/s) unless --batch is given";
  if (!given("--aim")) return "--aim is required (deg) unless --batch is given";
  *shot = {args_.speed, args_.aim_deg, args_.topspin_k, args_.sidespin_k};
  shot->elevation_deg = args_.elevation_deg;
  return check_shot_inputs(*shot, kShotFlagNames);
}

int SimulateCommand::prepare_table(const prob::Problem& problem, phys::ImpactTable* table,
                                   phys::SimulationOptions* options, std::ostream& err) const {
  return prepare_impact_table(kCommandName, problem.scene, args_.table_cache, args_.threads,
                              given("--accuracy"), table, options, err);
}

struct SimulateCommand::Inputs {
  phys::SimulationOptions options;
  bool batch = false;
  bool check_only = false;             // validate(): standard input is not read
  std::unique_ptr<BatchReader> reader;  // with --batch, past its header
  phys::Shot shot;                      // without
  prob::LoadResult loaded;
};

std::string SimulateCommand::read_inputs(Inputs* inputs) const {
  if (std::string why = read_options(&inputs->options); !why.empty()) return why;
  // The shot(s), the output path and the problem: whole-input errors come before any
  // table is built.
  inputs->batch = given("--batch");
  if (inputs->batch) {
    if (!(inputs->check_only && args_.batch_file == "-")) {
      inputs->reader = std::make_unique<BatchReader>(args_.batch_file, kShotBatchHeader);
      if (!inputs->reader->error().empty()) return inputs->reader->error();
    }
  } else if (std::string why = read_shot(&inputs->shot); !why.empty()) {
    return why;
  }
  if (!args_.svg_file.empty())
    if (std::string why = check_picture_file("--svg", args_.svg_file); !why.empty()) return why;
  inputs->loaded = prob::load_problem(args_.problem_file);
  return inputs->loaded.error;
}

int SimulateCommand::validate(std::ostream& err) const {
  Inputs inputs;
  inputs.check_only = true;
  const std::string why = read_inputs(&inputs);
  return why.empty() ? kExitOk : usage_error(err, kCommandName, why);
}

int SimulateCommand::run(std::ostream& out, std::ostream& err) const {
  const auto usage = [&](const std::string& why) { return usage_error(err, kCommandName, why); };

  Inputs inputs;
  if (std::string why = read_inputs(&inputs); !why.empty()) return usage(why);
  phys::SimulationOptions& options = inputs.options;
  const bool batch = inputs.batch;
  const phys::Shot& shot = inputs.shot;
  const prob::Problem& problem = *inputs.loaded.problem;

  phys::ImpactTable table;
  if (options.impact_method == phys::ImpactMethod::table)
    if (int code = prepare_table(problem, &table, &options, err); code != kExitOk) return code;

  if (batch) {
    return run_batch_command(*inputs.reader, shot_batch_job(problem, options, args_.threads),
                             out, err);
  }

  for (const std::string& warning : prob::problem_warnings(problem))
    err << kCommandName << ": warning: " << warning << '\n';
  for (const std::string& warning : shot_warnings(shot, kShotFlagNames))
    err << kCommandName << ": warning: " << warning << '\n';
  const phys::ShotResult result = phys::simulate(problem.scene, problem.cue_ball, shot, options);
  if (result.status == phys::ShotStatus::invalid_input) return usage(result.message);

  // The drawing first: if it cannot be written, nothing else is printed.
  if (!args_.svg_file.empty()) {
    const draw::Picture picture = draw::table_picture(drawing_of(problem, shot, options, result));
    if (std::string why = write_picture(args_.svg_file, picture); !why.empty())
      return usage("--svg: " + why);
  }
  std::optional<SimulatedSuccess> success;
  if (args_.samples > 0) {
    success.emplace();
    success->noise.scale = args_.noise;
    success->seed = args_.seed;
    success->success = planner::estimate_success(problem, shot, success->noise, args_.samples,
                                                 args_.seed, options);
  }
  std::optional<phys::ShotTrace> trace;
  if (given("--trace")) {
    trace = phys::trace_shot(result, problem.scene, args_.trace);
    if (trace->error) return usage(trace->error->message("--trace"));
  }
  if (args_.json) {
    nlohmann::ordered_json j = simulate_json(problem, shot, options, result, args_.svg_file, success);
    if (trace) j["trace"] = trace_json(*trace, result, args_.trace);
    out << j.dump(2) << '\n';
  } else if (trace) {
    write_trace_csv(out, *trace, result);
  } else {
    write_text(out, problem, shot, options, result, args_.svg_file, success);
  }
  const bool outcome = result.status == phys::ShotStatus::rest ||
                       result.status == phys::ShotStatus::pocketed ||
                       result.status == phys::ShotStatus::hit_obstacle;
  return outcome ? kExitOk : kExitFailed;
}

}  // namespace cueplan::cli
