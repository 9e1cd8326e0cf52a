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
#include "cueplan/api/exit_codes.hpp"
#include "cueplan/api/impact.hpp"
#include "cueplan/api/output_file.hpp"
#include "cueplan/api/options.hpp"
#include "cueplan/api/shot_report.hpp"
#include "cueplan/api/words.hpp"
#include "simulate_batch.hpp"

namespace cueplan::cli {
using namespace cueplan::batch;  // batch streaming (batch/)
namespace {

namespace phys = cueplan::physics;
namespace prob = cueplan::problems;

constexpr const char* kCommandName = "cueplan simulate";

}  // namespace

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
    write_simulate_text(out, problem, shot, options, result, args_.svg_file, success);
  }
  const bool outcome = result.status == phys::ShotStatus::rest ||
                       result.status == phys::ShotStatus::pocketed ||
                       result.status == phys::ShotStatus::hit_obstacle;
  return outcome ? kExitOk : kExitFailed;
}

}  // namespace cueplan::cli
