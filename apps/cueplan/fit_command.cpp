#include "fit_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cueplan/draw/table.hpp"
#include "cueplan/parallel.hpp"
#include "cueplan/problems/presets.hpp"
#include "cueplan/problems/problem.hpp"
#include "cueplan/api/exit_codes.hpp"
#include "cueplan/api/output_file.hpp"
#include "cueplan/api/words.hpp"

namespace cueplan::cli {
namespace {

namespace phys = cueplan::physics;
namespace plan = cueplan::planner;
using nlohmann::ordered_json;

constexpr const char* kCommandName = "cueplan fit";

std::string read_all(const std::string& path, std::string* error) {
  std::ostringstream text;
  if (path == "-") {
    text << std::cin.rdbuf();
    return text.str();
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    *error = path + ": cannot open";
    return {};
  }
  text << in.rdbuf();
  return text.str();
}

ordered_json point_json(phys::Vec2 p) { return ordered_json::array({p.x, p.y}); }

// The problem file that `cueplan simulate` takes to replay a fit.
ordered_json problem_json(const plan::ShotData& d, const phys::Scene& scene,
                          const phys::ShotResult& r) {
  ordered_json j;
  j["name"] = "shot " + d.id;
  j["table"] = {{"preset", "carom"}, {"length", scene.length}, {"width", scene.width}};
  j["ball"] = {{"radius", scene.radius()}, {"mass", scene.ball_and_cushion.mass}};
  j["physics"] = physics_json(scene);
  j["cue_ball"] = point_json(d.cue_start);
  ordered_json balls = ordered_json::object();
  for (const phys::ObjectBall& b : scene.balls) balls[b.name] = point_json(b.position);
  j["balls"] = balls;
  j["target"] = point_json(r.balls.empty() ? d.cue_start : r.balls[0].final_position);
  return j;
}

ordered_json shot_json(const plan::StrokeFit& f) {
  return {{"speed", f.shot.speed},
          {"aim_deg", f.shot.aim_deg},
          {"topspin_k", f.shot.topspin_k},
          {"sidespin_k", f.shot.sidespin_k},
          {"elevation_deg", f.shot.elevation_deg},
          {"strike_offset_s", f.offset_s},
          {"words", tip_offset_words(f.shot)}};
}

std::string stroke_words(const plan::StrokeFit& f) {
  std::string words = fmt::format("{:.3f} m/s at {:.2f} deg, {}", f.shot.speed, f.shot.aim_deg,
                                  tip_offset_words(f.shot));
  // The cue's elevation, where the fit raised it.
  if (f.shot.elevation_deg >= 0.05) words += fmt::format(", cue raised {:.1f} deg", f.shot.elevation_deg);
  return words;
}

// The recorded samples over the simulated paths.
draw::Picture fit_picture(const plan::ShotData& d, const phys::Scene& scene,
                          const phys::ShotResult& r, const plan::StrokeFit& before,
                          const plan::StrokeFit& f) {
  draw::TableScene ts;
  ts.scene = scene;
  ts.markings = draw::TableMarkings::diamonds;
  ts.title = fmt::format("shot {}: cue-ball RMSE {:.1f} cm (first guess {:.1f} cm)", d.id,
                         100.0 * f.rmse_cue_m, 100.0 * before.rmse_cue_m);
  ts.caption = {"fitted stroke: " + stroke_words(f),
                "dots: recorded samples (per ball); lines: the simulation of the fitted stroke"};
  const draw::Colour colours[3] = {draw::Colour::hex("#ffffff"), draw::Colour::hex("#e6c619"),
                                   draw::Colour::hex("#d62728")};
  const draw::Colour dots[3] = {draw::Colour::hex("#333333"), draw::Colour::hex("#b8860b"),
                                draw::Colour::hex("#8b0000")};
  for (size_t k = 0; k < d.p.size(); ++k) {
    draw::DrawnBall b;
    b.name = k == 0 ? "cue ball " + d.names[k] : "ball " + d.names[k];
    b.colour = colours[k % 3];
    b.start = d.p[k].front();
    if (k < r.balls.size() && !r.balls[k].path.empty()) {
      draw::DrawnPath p;
      p.segments = r.balls[k].path;
      p.events = r.balls[k].events;
      if (k > 0) p.colour = colours[k % 3];
      b.paths.push_back(std::move(p));
    }
    ts.balls.push_back(std::move(b));
    for (const phys::Vec2& q : d.p[k]) ts.dots.push_back({q, dots[k % 3], 1.8, std::nullopt});
  }
  ts.dots_legend = "recorded";
  return draw::table_picture(ts);
}

}  // namespace

std::string carom_table(const std::string& physics_file, phys::Scene* scene) {
  *scene = problems::carom_scene();
  if (physics_file.empty()) return {};
  std::string error;
  const std::string text = read_all(physics_file, &error);
  if (!error.empty()) return "--physics: " + error;
  return problems::apply_physics_block(text, physics_file, scene);
}

ordered_json physics_json(const phys::Scene& s) {
  ordered_json j = {{"mu_slide", s.cloth.mu_slide},
          {"mu_roll", s.cloth.mu_roll},
          {"mu_spin", s.cloth.mu_spin},
          {"mu_cushion", s.ball_and_cushion.mu_cushion},
          {"restitution", s.ball_and_cushion.restitution},
          {"cushion_height", s.ball_and_cushion.cushion_height},
          {"cushion_model", phys::to_string(s.ball_and_cushion.model)},
          {"gravity", s.cloth.gravity},
          {"mu_ball", s.ball_contact.mu_ball},
          {"ball_restitution", s.ball_contact.restitution},
          {"ball_model", phys::to_string(s.ball_contact.model)},
          {"ball_friction", phys::to_string(s.ball_contact.friction)}};
  // The compliant cushion's own parameter, where it is the model.
  if (s.ball_and_cushion.model == phys::CushionModel::stronge_compliant)
    j["eta_squared"] = s.ball_and_cushion.eta_squared;
  return j;
}

void add_stroke_search_flags(CLI::App& c, StrokeSearchArgs* a) {
  c.add_option("--max-elevation", a->max_elevation_deg,
               "The cue's elevation in the stroke search, in [0, DEG] (swerve with side); 0 keeps "
               "the cue level")
      ->type_name("DEG")
      ->capture_default_str();
  c.add_option("--spin-starts", a->spin_starts,
               "Restarts of the local search with the spins reset round the spin circle (more: "
               "fewer shots caught in a wrong spin's minimum, longer fits)")
      ->capture_default_str();
  c.add_option("--global-evaluations", a->global_evaluations,
               "Simulations of each of the two global stages (CRS2) of a stroke's search")
      ->capture_default_str();
  c.add_option("--local-evaluations", a->local_evaluations,
               "Simulations of the local stages (BOBYQA) of a stroke's search")
      ->capture_default_str();
  c.add_option("--restarts", a->restarts,
               "Whole searches per stroke, each with its own random draws; the best is kept "
               "(more: fewer shots caught in a wrong minimum, proportionally longer fits)")
      ->capture_default_str();
  c.add_flag("--no-horizon", a->no_horizon,
             "Follow every simulation to rest, even when a score compares only the first "
             "seconds of the samples (the same scores unless a simulation fails after the window; slower: for comparison)");
  c.add_option("--huber-delta", a->huber_delta,
               "Residuals beyond this distance (m) count linearly in the objective, so that "
               "a few tracking glitches do not drag the fit")
      ->type_name("M")
      ->capture_default_str();
}

std::string check_stroke_search(const StrokeSearchArgs& a) {
  if (!std::isfinite(a.max_elevation_deg) || a.max_elevation_deg < 0.0 ||
      a.max_elevation_deg > 60.0)
    return "--max-elevation must be in [0, 60] deg";
  if (a.spin_starts < 0 || a.spin_starts > 1000) return "--spin-starts must be in [0, 1000]";
  if (a.global_evaluations < 10 || a.global_evaluations > 1000000)
    return "--global-evaluations must be in [10, 1000000]";
  if (a.local_evaluations < 10 || a.local_evaluations > 1000000)
    return "--local-evaluations must be in [10, 1000000]";
  if (a.restarts < 1 || a.restarts > 100) return "--restarts must be in [1, 100]";
  if (!std::isfinite(a.huber_delta) || a.huber_delta <= 0.0 || a.huber_delta > 10.0)
    return "--huber-delta must be in (0, 10] m";
  return {};
}

void apply_stroke_search(const StrokeSearchArgs& a, plan::FitOptions* o) {
  o->max_elevation_deg = a.max_elevation_deg;
  o->spin_starts = a.spin_starts;
  o->global_evaluations = a.global_evaluations;
  o->local_evaluations = a.local_evaluations;
  o->huber_delta = a.huber_delta;
  o->restarts = a.restarts;
  o->horizon = !a.no_horizon;
}

std::vector<plan::ShotData> read_tracks(const std::string& path, const phys::Scene& table,
                                        const plan::TrackFrame& frame, const std::string& command,
                                        std::ostream& err, int* bad) {
  std::vector<plan::ShotData> shots;
  *bad = 0;
  std::string error;
  const std::string text = read_all(path, &error);
  if (!error.empty()) {
    err << command << ": " << error << '\n';
    *bad = -1;
    return shots;
  }
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const plan::TrackRead read = plan::parse_track(line, number);
    if (!read.error.empty()) {
      err << command << ": " << path << ":" << number << ": " << read.error << "; skipped\n";
      ++*bad;
      continue;
    }
    plan::ShotDataRead data = plan::prepare_shot(*read.track, table, frame);
    if (!data.error.empty()) {
      err << command << ": " << path << ":" << number << ": " << data.error << "; skipped\n";
      ++*bad;
      continue;
    }
    shots.push_back(std::move(*data.data));
  }
  if (shots.empty() && *bad == 0) {
    err << command << ": " << path << ": no shots\n";
    *bad = 1;
  }
  return shots;
}

FitCommand::FitCommand(CLI::App& parent) {
  command_ = parent.add_subcommand(
      "fit",
      "Reconstruct recorded shots: for each shot of a tracks file (data/carom_tracks format), "
      "the stroke (speed, aim, topspin, sidespin, strike time) whose simulation on the carom "
      "table best matches the tracked cue ball.");
  CLI::App& c = *command_;
  c.add_option("TRACKS", args_.tracks_file, "Tracks file, one shot a JSON line ('-': stdin)")
      ->required()
      ->type_name("TRACKS.jsonl");
  c.add_flag("--all-balls", args_.all_balls,
             "Match every ball's samples, not only the cue ball's");
  c.add_flag("--json", args_.json, "One JSON object per shot per line");
  c.add_option("--svg", args_.svg_dir, "Write one SVG picture per shot into DIR")->type_name("DIR");
  c.add_option("--png", args_.png_dir, "Write one PNG picture per shot into DIR")->type_name("DIR");
  c.add_option("--physics", args_.physics_file,
               "YAML/JSON file with a physics: block (as in problem files, e.g. from "
               "`cueplan calibrate --out`) applied to the carom table")
      ->type_name("FILE");
  c.add_option("--threads", args_.threads, "Threads (0: one per core)")->capture_default_str();
  add_stroke_search_flags(c, &args_.search);
}

bool FitCommand::selected() const { return command_->parsed(); }

int FitCommand::validate(std::ostream& err) const {
  phys::Scene scene;
  if (std::string why = carom_table(args_.physics_file, &scene); !why.empty())
    return usage_error(err, kCommandName, why);
  if (args_.threads < 0) return usage_error(err, kCommandName, "--threads must be >= 0");
  if (std::string why = check_stroke_search(args_.search); !why.empty())
    return usage_error(err, kCommandName, why);
  return kExitOk;
}

int FitCommand::run(std::ostream& out, std::ostream& err) const {
  if (const int code = validate(err); code != kExitOk) return code;
  phys::Scene table;
  carom_table(args_.physics_file, &table);
  for (const std::string* dir : {&args_.svg_dir, &args_.png_dir})
    if (!dir->empty())
      if (std::string why = ensure_directory(*dir); !why.empty())
        return usage_error(err, kCommandName, why);
  const plan::TrackFrame frame;
  int bad = 0;
  const std::vector<plan::ShotData> shots =
      read_tracks(args_.tracks_file, table, frame, kCommandName, err, &bad);
  if (bad < 0) return kExitUsage;

  plan::FitOptions options;
  options.all_balls = args_.all_balls;
  apply_stroke_search(args_.search, &options);
  struct Outcome {
    plan::StrokeFit before, after;
    double seconds = 0;
  };
  std::vector<Outcome> outcomes(shots.size());
  const unsigned threads = thread_count(args_.threads, shots.size());
  err << kCommandName << ": fitting " << shots.size() << " shots on " << threads << " threads\n";
  size_t reported = 0;
  parallel_for(
      shots.size(), threads,
      [&](size_t i, unsigned) {
        const auto start = std::chrono::steady_clock::now();
        const phys::CompiledScene scene(shots[i].scene);
        const plan::StrokeFit guess = plan::kinematic_guess(shots[i], options);
        outcomes[i].before =
            plan::evaluate_stroke(scene, shots[i], guess.shot, guess.offset_s, options);
        outcomes[i].after = plan::fit_stroke(scene, shots[i], options);
        outcomes[i].seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      },
      [&](size_t done) {
        if (done != reported && (done == shots.size() || done % 10 == 0)) {
          err << kCommandName << ": " << done << "/" << shots.size() << " shots fitted\n";
          reported = done;
        }
      },
      std::chrono::milliseconds(500));

  int failed = 0;
  if (!args_.json)
    out << fmt::format("{:>6}  {:>11}  {:>10}  {}\n", "id", "before (cm)", "after (cm)",
                       "stroke");
  for (size_t i = 0; i < shots.size(); ++i) {
    const plan::ShotData& d = shots[i];
    const Outcome& o = outcomes[i];
    const phys::CompiledScene scene(d.scene);
    phys::ShotResult r;
    const auto positions = plan::simulated_positions(scene, d, o.after, &r, options.max_events);
    if (positions.empty()) {
      err << kCommandName << ": shot " << d.id << ": no stroke could be simulated ("
          << phys::to_string(r.status) << ")\n";
      ++failed;
      continue;
    }
    if (args_.json) {
      ordered_json j;
      // The id as the file gives it (a number stays a number).
      j["id"] = nlohmann::json::parse(d.id, nullptr, false).is_discarded()
                    ? ordered_json(d.id)
                    : ordered_json::parse(d.id);
      j["shot"] = shot_json(o.after);
      // The first guess's error and the fit's time, beside the stroke.
      j["shot"]["first_guess_rmse_cue_m"] = o.before.rmse_cue_m;
      j["shot"]["fit_seconds"] = o.seconds;
      j["shot"]["simulations"] = o.after.evaluations;
      j["physics"] = physics_json(d.scene);
      j["rmse_cue_m"] = o.after.rmse_cue_m;
      j["rmse_all_m"] = o.after.rmse_all_m;
      ordered_json tracks = ordered_json::object();
      for (size_t k = 0; k < d.p.size(); ++k) {
        ordered_json b;
        ordered_json xs = ordered_json::array(), ys = ordered_json::array();
        for (const phys::Vec2& q : positions[k]) {
          const phys::Vec2 f = frame.to_file(q);
          xs.push_back(f.x);
          ys.push_back(f.y);
        }
        b["t"] = d.t[k];
        b["x"] = xs;
        b["y"] = ys;
        tracks[d.names[k]] = b;
      }
      j["tracks"] = tracks;
      j["problem"] = problem_json(d, d.scene, r);
      out << j.dump() << '\n';
    } else {
      out << fmt::format("{:>6}  {:>11.2f}  {:>10.2f}  {}\n", d.id, 100.0 * o.before.rmse_cue_m,
                         100.0 * o.after.rmse_cue_m, stroke_words(o.after));
    }
    for (const auto& [dir, ext] : {std::pair{&args_.svg_dir, ".svg"}, {&args_.png_dir, ".png"}}) {
      if (dir->empty()) continue;
      const std::filesystem::path file = std::filesystem::path(*dir) / ("shot_" + d.id + ext);
      if (std::string why = write_picture(file, fit_picture(d, d.scene, r, o.before, o.after));
          !why.empty()) {
        err << kCommandName << ": " << file.string() << ": " << why << '\n';
        ++failed;
      }
    }
  }
  if (bad > 0) {
    err << kCommandName << ": " << bad << " shot(s) skipped for bad input\n";
    return kExitUsage;
  }
  return failed > 0 ? kExitFailed : kExitOk;
}

}  // namespace cueplan::cli
