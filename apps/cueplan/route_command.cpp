#include "route_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <ostream>
#include <vector>

#include "cueplan/draw/table.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/planner/route.hpp"
#include "cueplan/problems/problem.hpp"
#include "cueplan/problems/stroke_ranges.hpp"
#include "cueplan/api/exit_codes.hpp"
#include "cueplan/api/field_names.hpp"
#include "cueplan/api/output_file.hpp"
#include "cueplan/api/options.hpp"
#include "cueplan/api/shot_report.hpp"
#include "cueplan/api/words.hpp"

namespace cueplan::cli {
namespace {

namespace phys = cueplan::physics;
namespace plan = cueplan::planner;
namespace prob = cueplan::problems;
using nlohmann::ordered_json;

constexpr const char* kCommandName = "cueplan route";
constexpr int kDefaultMaxStrokes = 3;
constexpr double kDefaultTimeS = 5.0;

std::string position_text(phys::Vec2 p) {
  return "x = " + number(p.x, "m") + ", y = " + number(p.y, "m");
}

std::string strokes_text(int n) { return std::to_string(n) + (n == 1 ? " stroke" : " strokes"); }

std::string success_text(const plan::RouteOptions& o, const plan::RouteStroke& s, bool last) {
  if (o.robustness_samples == 0) return "not estimated (--samples 0)";
  return fmt::format("{:.1f} %", 100.0 * s.planned.success_probability) + " of " +
         std::to_string(o.robustness_samples) + " noisy strokes stop " +
         (last ? "in the target zone (within " + number(1000.0 * s.zone_radius, "mm") +
                     " of the target)"
               : "within " + number(1000.0 * s.zone_radius, "mm") + " of this landing");
}

// ---------------------------------------------------------------------------
// Text

void write_text(std::ostream& out, const prob::Problem& problem, const plan::RouteOptions& o,
                const plan::RouteResult& r, const std::string& svg_file) {
  const auto line = [&](std::string_view label, const std::string& text) {
    report_line(out, label, text);
  };
  line("problem", problem.name + "  (" + problem.source + ")");
  line("status", plan::to_string(r.status));
  line("summary", r.message);
  line("start", position_text(problem.cue_ball));
  line("target", position_text(problem.target) + ", tolerance " + number(problem.tolerance, "m"));
  line("strokes", std::to_string(r.strokes.size()) + " (at most " + std::to_string(o.max_strokes) +
                      ")");
  for (size_t i = 0; i < r.strokes.size(); ++i) {
    const plan::RouteStroke& s = r.strokes[i];
    const phys::Shot& shot = s.planned.shot;
    const bool last = i + 1 == r.strokes.size();
    line("stroke " + std::to_string(i + 1),
         plan::describe_stroke(shot) + ", aim " + number(shot.aim_deg, "deg"));
    line("    shot", "V = " + number(shot.speed, "m/s") + " at aim " + number(shot.aim_deg, "deg") +
                         ", k_T = " + number(shot.topspin_k) + ", k_S = " + number(shot.sidespin_k));
    line("    from", position_text(s.start));
    line("    landing", landing_text(s.planned));
    line("    cushions", route_text(problem.scene, s.planned.route));
    if (last)
      line("    miss", fmt::format("{:.3g} mm", 1000.0 * s.planned.miss_distance) + " from the target");
    line("    success", success_text(o, s, last));
  }
  if (r.status == plan::RouteStatus::solved && o.robustness_samples > 0)
    line("route success",
         fmt::format("{:.1f} %", 100.0 * r.route_success_probability) +
             " (product of the strokes' success probabilities; noise: " + noise_text(o.noise) + ")");
  line("time", fmt::format("{:.3g} s", r.time_s) +
                   (r.time_to_first_solution_s >= 0.0
                        ? " (first route after " + fmt::format("{:.3g} s", r.time_to_first_solution_s) + ")"
                        : std::string()));
  line("search", std::string(plan::to_string(o.planner)) + " with the " +
                     plan::to_string(o.sampler) + " sampler; " + std::to_string(r.propagations) +
                     " strokes propagated, " + std::to_string(r.steerings) + " steerings, " +
                     std::to_string(r.evaluations) + " shot simulations, " +
                     std::to_string(r.tree_states) + " states in the tree; budget " +
                     number(o.max_time_s, "s") + (o.stop_at_first_solution ? " (first route)" : "") +
                     "; seed " + std::to_string(o.seed));
  if (!svg_file.empty()) line("drawing", svg_file);
}

// ---------------------------------------------------------------------------
// JSON


// ---------------------------------------------------------------------------
// The drawing: every stroke's path in order, numbered.

draw::TableScene drawing_of(const prob::Problem& problem, const plan::RouteOptions& o,
                            const plan::RouteResult& r) {
  draw::TableScene d = draw::problem_table(problem);
  phys::SimulationOptions exact;  // as the route was verified: exact, 1e-9
  exact.record_path = true;
  for (const plan::RouteStroke& s : r.strokes) {
    const phys::ShotResult sim = phys::simulate(problem.scene, s.start, s.planned.shot, exact);
    const int stroke = static_cast<int>(d.balls.front().paths.size()) + 1;
    d.balls.front().paths.push_back({sim.path, sim.events, false, stroke});
  }
  d.title = problem.name + ": " +
            (r.status == plan::RouteStatus::solved ? "route of " + strokes_text(static_cast<int>(r.strokes.size()))
                                                   : std::string(plan::to_string(r.status)));
  for (size_t i = 0; i < r.strokes.size(); ++i) {
    const phys::Shot& s = r.strokes[i].planned.shot;
    std::string buf;
    buf = fmt::format("{}. V = {:.3g} m/s, aim {:.4g}\u00b0, k_{{T}} = {:.3g}, k_{{S}} = {:.3g}",
                  i + 1, s.speed, s.aim_deg, s.topspin_k, s.sidespin_k);
    std::string text = buf;
    if (o.robustness_samples > 0)
      text += "; " + fmt::format("{:.0f} %", 100.0 * r.strokes[i].planned.success_probability) +
              " of noisy strokes succeed";
    d.caption.push_back(text + ".");
  }
  if (r.strokes.empty()) d.caption.push_back(r.message);
  else if (r.strokes.size() > 1)
    d.caption.push_back(
        "Each stroke starts where the one before it stops (the ghosts where each comes to rest).");
  return d;
}

}  // namespace

RouteCommand::RouteCommand(CLI::App& parent) {
  command_ = parent.add_subcommand(
      "route",
      "Plan a short sequence of strokes that leaves the cue ball on a problem's target when "
      "one stroke cannot (blocked lines, a speed limit, fragile single strokes), on OMPL's "
      "kinodynamic planners, and report each stroke in a player's terms.");
  CLI::App& c = *command_;
  c.add_option("PROBLEM", args_.problem_file,
               "Problem file (YAML, problems/README.md): table, cue ball, target, limits; may "
               "set max_strokes and time_budget_s")
      ->required()
      ->type_name("FILE.yaml");
  const char* search = "Search";
  c.add_option("--max-strokes", args_.max_strokes,
               "Most strokes in the route, 1-100 (default: the file's max_strokes, else 3)")
      ->type_name("K")
      ->group(search);
  c.add_option("--time", args_.time_s,
               "Search budget in seconds (default: the file's time_budget_s, else 5). SST "
               "keeps improving its route until the budget ends unless --first is given")
      ->type_name("SECONDS")
      ->group(search);
  c.add_option("--planner", args_.planner, "OMPL control planner: sst, rrt or kpiece1")
      ->type_name("NAME")
      ->capture_default_str()
      ->group(search);
  c.add_option("--sampler", args_.sampler,
               "How strokes are chosen: directed (each stroke steers toward a sampled point "
               "through the one-stroke planner) or random (uniform strokes within the limits)")
      ->type_name("NAME")
      ->capture_default_str()
      ->group(search);
  c.add_flag("--first", args_.first, "Stop at the first route found (SST; RRT and KPIECE1 always do)")
      ->group(search);
  c.add_option("--seed", args_.seed, "Seed of every random choice")
      ->type_name("N")
      ->capture_default_str()
      ->group(search);
  c.add_option("--steer-evaluations", args_.steer_evaluations,
               "Shot simulations per directed steering, >= 10")
      ->type_name("N")
      ->capture_default_str()
      ->group(search);
  c.add_option("--noise", args_.noise,
               "Scale of the player's execution noise (Gaussian: aim 0.125 deg, speed 0.075 m/s, "
               "tip offset 0.5 mm each way, times this), >= 0; 0 is a perfect cue")
      ->type_name("X")
      ->capture_default_str()
      ->group(search);
  c.add_option("--samples", args_.samples,
               "Noisy strokes per reported success probability (0: not estimated)")
      ->type_name("N")
      ->capture_default_str()
      ->group(search);
  const char* output = "Output";
  c.add_flag("--json", args_.json,
             "Print one JSON object instead of text: status, message, strokes (each like solve's "
             "shot, with start and final_position in m and success_probability), time_s, ...")
      ->group(output);
  c.add_option("--svg", args_.svg_file,
               "Also draw the route: the table, the target zone and every stroke's path, "
               "numbered; SVG, PNG or PDF by the file's extension")
      ->type_name("FILE.svg|.png|.pdf")
      ->group(output);
  c.footer(
      "Status: solved (exit 0); unreachable - proven: obstacle balls or pockets wall the "
      "target off - or budget_exhausted - no route within the budget (exit 1); bad input "
      "exits 2.\n"
      "Example: cueplan route problems/routes/two_stroke_blocked.yaml --max-strokes 2 --svg "
      "route.svg");
}

bool RouteCommand::selected() const { return command_->parsed(); }

int RouteCommand::read(std::ostream& err, prob::Problem* problem_out,
                       plan::RouteOptions* options) const {
  const auto usage = [&](const std::string& why) { return usage_error(err, kCommandName, why); };
  plan::RouteOptions& o = *options;
  if (!plan::parse_route_planner(args_.planner, &o.planner))
    return usage("--planner must be sst, rrt or kpiece1, got '" + args_.planner + "'");
  if (!plan::parse_route_sampler(args_.sampler, &o.sampler))
    return usage("--sampler must be directed or random, got '" + args_.sampler + "'");
  // The flags alone first (RouteOptions::validate checks them), so that a bad flag is
  // named before the problem file is read.
  o.max_strokes = command_->count("--max-strokes") > 0 ? args_.max_strokes : kDefaultMaxStrokes;
  o.max_time_s = command_->count("--time") > 0 ? args_.time_s : kDefaultTimeS;
  o.stop_at_first_solution = args_.first;
  o.seed = args_.seed;
  o.noise.scale = args_.noise;
  o.robustness_samples = args_.samples;
  o.steer_evaluations = args_.steer_evaluations;
  const FieldName flags[] = {{{"max_strokes"}, "--max-strokes"},
                             {{"max_time_s"}, "--time"},
                             {{"noise", "scale"}, "--noise"},
                             {{"robustness_samples"}, "--samples"},
                             {{"steer_evaluations"}, "--steer-evaluations"}};
  if (physics::Validation e = o.validate()) return usage(message_in(*e, flags));
  if (!args_.svg_file.empty())
    if (std::string why = check_picture_file("--svg", args_.svg_file); !why.empty())
      return usage(why);
  const prob::LoadResult loaded = prob::load_problem(args_.problem_file);
  if (!loaded.ok()) return usage(loaded.error);
  const prob::Problem& problem = *loaded.problem;

  // The file's budgets where no flag overrides them (the loader checked them).
  if (command_->count("--max-strokes") == 0 && problem.max_strokes) o.max_strokes = *problem.max_strokes;
  if (command_->count("--time") == 0 && problem.time_budget_s) o.max_time_s = *problem.time_budget_s;
  *problem_out = problem;
  return kExitOk;
}

int RouteCommand::validate(std::ostream& err) const {
  prob::Problem problem;
  plan::RouteOptions o;
  return read(err, &problem, &o);
}

int RouteCommand::run(std::ostream& out, std::ostream& err) const {
  const auto usage = [&](const std::string& why) { return usage_error(err, kCommandName, why); };
  prob::Problem problem;
  plan::RouteOptions o;
  if (const int code = read(err, &problem, &o); code != kExitOk) return code;
  for (const std::string& warning : prob::problem_warnings(problem))
    err << kCommandName << ": warning: " << warning << '\n';

  const plan::RouteResult result = plan::plan_route(problem, o);
  if (result.status == plan::RouteStatus::invalid_input) return usage(result.message);

  if (!args_.svg_file.empty()) {
    const draw::Picture picture = draw::table_picture(drawing_of(problem, o, result));
    if (std::string why = write_picture(args_.svg_file, picture); !why.empty())
      return usage("--svg: " + why);
  }
  if (args_.json)
    out << route_json(problem, o, result, args_.svg_file).dump(2) << '\n';
  else
    write_text(out, problem, o, result, args_.svg_file);
  if (!out) return kExitFailed;
  return result.status == plan::RouteStatus::solved ? kExitOk : kExitFailed;
}

}  // namespace cueplan::cli
