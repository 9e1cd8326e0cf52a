#include "solve_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <ostream>
#include <vector>

#include "cueplan/draw/table.hpp"
#include "cueplan/physics/impact_table.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/planner/position.hpp"
#include "cueplan/problems/problem.hpp"
#include "cueplan/problems/stroke_ranges.hpp"
#include "cueplan/api/exit_codes.hpp"
#include "search_flags.hpp"
#include "cueplan/api/output_file.hpp"
#include "cueplan/api/shot_report.hpp"
#include "cueplan/api/words.hpp"

namespace cueplan::cli {
using namespace cueplan::batch;  // batch streaming (batch/)
namespace {

namespace phys = cueplan::physics;
namespace plan = cueplan::planner;
namespace prob = cueplan::problems;
using nlohmann::ordered_json;

constexpr const char* kCommandName = "cueplan solve";
constexpr double kSpinPerTipOffset = 2.5;  // k = 2.5 d / R (PHYSICS.md, "Cue strike")

// Tip offsets as fractions of R, with their direction in words.
std::string tip_offset_text(const phys::Shot& shot, const prob::Limits& limits) {
  return tip_offset_words(shot) +
         " (fractions of the ball radius; the spin "
         "limit is " +
         fmt::format("{:.3g}", limits.spin_max / kSpinPerTipOffset) + " R)";
}

std::string miss_text(const prob::Problem& problem, const plan::PlannedShot& p) {
  if (!problem.has_target)
    return problem.is_escape() ? "none: an escape has no target" : "none: a pure pot has no target";
  if (!std::isfinite(p.miss_distance)) return "none: the ball did not come to rest on the table";
  const bool inside = p.miss_distance <= problem.tolerance;
  return fmt::format("{:.3g} mm", 1000.0 * p.miss_distance) + " (tolerance " +
         number(1000.0 * problem.tolerance, "mm") +
         "): " + (inside ? "inside the target zone" : "outside the target zone");
}

std::string success_text(const plan::PlannerOptions& options, const plan::Success& success) {
  if (options.robustness_samples == 0) return "not estimated (--samples 0)";
  const plan::Estimate& e = success.both;
  std::string text = estimate_text(e) + " of " + std::to_string(e.samples) +
                     " noisy strokes succeed" + pot_success_words(success) +
                     " (noise: " + noise_text(options.noise) + ")";
  if (e.samples < options.robustness_samples)
    text += fmt::format("; cut short at {} of {} strokes by the time budget or by the "
                        "ranking, which stops sampling strokes that are measurably worse",
                        e.samples, options.robustness_samples);
  return text;
}

// "yes" when the stroke meets every condition and some noisy stroke succeeded too;
// "exact" when it lands only as struck, no noisy stroke having succeeded.
const char* solves_text(const plan::PlannedShot& p) {
  if (!p.solves) return "no";
  return p.success.both.samples > 0 && p.success.both.successes == 0 ? "exact" : "yes";
}

// ---------------------------------------------------------------------------
// Text

void write_text(std::ostream& out, const prob::Problem& problem,
                const plan::PlannerOptions& options, const plan::PlanResult& r,
                const std::string& svg_file) {
  const auto line = [&](std::string_view label, const std::string& text) {
    report_line(out, label, text);
  };
  const plan::PlannedShot& b = r.best;
  const phys::Shot& s = b.shot;
  const double spin_unit = s.speed / problem.scene.radius();  // rad/s per unit of k

  line("problem", problem.name + "  (" + problem.source + ")");
  line("status", plan::to_string(r.status));
  line("summary", r.message);
  line("shot", "V = " + number(s.speed, "m/s") + " at aim " + number(s.aim_deg, "deg") +
                   ", k_T = " + number(s.topspin_k) + " (w_T = " +
                   number(s.topspin_k * spin_unit, "rad/s") + "), k_S = " + number(s.sidespin_k) +
                   " (w_S = " + number(s.sidespin_k * spin_unit, "rad/s") + ")");
  line("stroke", plan::describe_stroke(s));
  line("tip offset", tip_offset_text(s, problem.limits));
  if (s.elevation_deg > 0.0) line("elevation", number(s.elevation_deg, "deg"));
  if (const std::string w = squirt_words(problem.scene, s); !w.empty()) line("squirt", w);
  line("landing", landing_text(b));
  if (b.pot)
    for (const auto& [label, text] : pot_lines(*b.pot)) line(label, text);
  if (problem.has_target)
    line("target", "x = " + number(problem.target.x, "m") + ", y = " +
                       number(problem.target.y, "m") + ", tolerance " +
                       number(problem.tolerance, "m"));
  else if (!problem.next.empty())
    line("target", "none: position for the next pot, the cue ball may stop anywhere");
  else
    line("target", problem.is_escape()
                       ? "none: an escape, a legal hit is all it asks (the cue ball stays on the table)"
                       : "none: a pure pot, the cue ball may stop anywhere");
  if (b.next)
    for (const auto& [label, text] : next_lines(*b.next)) line(label, text);
  line("miss distance", miss_text(problem, b));
  line("success", success_text(options, b.success));
  line("route", route_text(problem.scene, b.route));
  if (!b.route_words.empty()) line("route in words", b.route_words);
  if (b.opponent_pot)
    line("leave", fmt::format("the easiest pot left to the opponent: {:.0f} % (leave: safe)",
                              100.0 * *b.opponent_pot));
  line("family", b.family);
  for (const std::string& why : r.ruled_out) line("ruled out", why);
  const std::vector<ConstraintRow> rows = constraints(problem, b, options.enforce_rigid_limit);
  int broken = 0;
  for (const ConstraintRow& c : rows) broken += std::string(c.state) == "broken" ? 1 : 0;
  line("constraints", broken == 0 ? "all met" : std::to_string(broken) + " broken");
  for (const ConstraintRow& c : rows) {
    std::string buf;
    buf = fmt::format("    {:<13} {:<8}", c.name, c.state);
    out << buf << c.detail << '\n';
  }
  line("evaluations", std::to_string(r.evaluations) + " shot simulations (" +
                          std::to_string(r.local_searches) + " local searches, " +
                          std::to_string(r.converged_searches) + " converged)");
  line("time", fmt::format("{:.3g} s", r.time_s));
  line("search",
       std::string(plan::to_string(options.global)) + " then " + plan::to_string(options.local) +
           " from " + std::to_string(options.local_starts) + " starts; budget " +
           std::to_string(options.max_evaluations) + " simulations or " +
           number(options.max_time_s, "s") + "; seed " + std::to_string(options.seed) + "; " +
           std::to_string(options.threads) + (options.threads == 1 ? " thread" : " threads") +
           (options.robust ? "; robust (maximises the success probability)" : ""));
  line("method", "search " + method_text(options.simulation, problem.scene) +
                     "; reported outcome " + phys::to_string(b.impact_method));
  if (!svg_file.empty()) line("drawing", svg_file);

  line("alternatives", r.alternatives.empty() ? std::string("none")
                                              : std::to_string(r.alternatives.size()) +
                                                    " (other families, best first)");
  if (r.alternatives.empty()) return;
  std::string buf;
  buf = fmt::format("  {:>2} {:>8} {:>10} {:>7} {:>7} {:>10} {:>15}  {:<6} {:<28} {}", "#",
                    "V (m/s)", "aim (deg)", "k_T", "k_S", "miss (mm)", "success (95 %)", "solves",
                    "route", "stroke");
  out << buf << '\n';
  for (size_t i = 0; i < r.alternatives.size(); ++i) {
    const plan::PlannedShot& a = r.alternatives[i];
    const std::string miss =
        std::isfinite(a.miss_distance) ? fmt::format("{:.3g}", 1000.0 * a.miss_distance) : "-";
    const plan::Estimate& e = a.success.both;
    const std::string success =
        e.samples == 0 ? "-"
                       : fmt::format("{:.1f} % ({:.0f}-{:.0f})", 100.0 * e.p, 100.0 * e.low,
                                     100.0 * e.high);
    std::string route = route_text(problem.scene, a.route);
    if (a.outcome != phys::ShotStatus::rest)
      route += std::string(", ") + phys::to_string(a.outcome);
    buf = fmt::format("  {:2} {:8.4f} {:10.3f} {:7.3f} {:7.3f} {:>10} {:>15}  {:<6} {:<28} {}",
                      i + 1, a.shot.speed, a.shot.aim_deg, a.shot.topspin_k, a.shot.sidespin_k,
                      miss, success, solves_text(a), route, plan::describe_stroke(a.shot));
    out << buf << '\n';
  }
  for (const plan::PlannedShot& a : r.alternatives)
    if (std::string(solves_text(a)) == "exact") {
      out << "  (solves exact: the stroke lands as given, but none of its noisy strokes "
             "succeeded)\n";
      break;
    }
}

// ---------------------------------------------------------------------------
// JSON


// ---------------------------------------------------------------------------
// The drawing: the best path in full, the alternatives faint.

// The stroke simulated as the reported outcome was: with the method that gave it.
phys::ShotResult drawn_result(const prob::Problem& problem, const plan::PlannedShot& p,
                              const phys::SimulationOptions& search) {
  phys::SimulationOptions options = search;
  options.record_path = true;
  if (p.impact_method != phys::ImpactMethod::table &&
      search.impact_method == phys::ImpactMethod::table) {
    options.impact_method = phys::ImpactMethod::exact;
    options.impact_accuracy = 1e-9;
  }
  return phys::simulate(problem.scene, problem.cue_ball, p.shot, options);
}

draw::DrawnPath path_of(const prob::Problem& problem, const plan::PlannedShot& p,
                        const phys::SimulationOptions& search, bool faint) {
  const phys::ShotResult r = drawn_result(problem, p, search);
  return {r.path, r.events, faint};
}

draw::TableScene drawing_of(const prob::Problem& problem, const plan::PlannerOptions& options,
                            const plan::PlanResult& r) {
  const plan::PlannedShot& b = r.best;
  draw::TableScene d = draw::problem_table(problem);
  if (r.position_field && r.position_field->best_value() > 0.0) {
    // Position play: the next pot's zone, outlined over the cloth (cueplan zone shades it).
    const plan::PositionField& f = *r.position_field;
    draw::TableField zone;
    zone.cell = f.cell();
    zone.columns = f.columns();
    zone.rows = f.rows();
    for (int j = 0; j < zone.rows; ++j)
      for (int i = 0; i < zone.columns; ++i) zone.values.push_back(f.cell_value(i, j));
    zone.shade = false;
    zone.outline_level = f.zone_threshold();
    zone.outline_legend = fmt::format("zone for the {}: P(next pot) within 10 points of the best",
                                      problem.next.front().ball);
    d.field = std::move(zone);
  }
  for (const plan::PlannedShot& a : r.alternatives)
    d.balls.front().paths.push_back(path_of(problem, a, options.simulation, true));
  d.balls.front().paths.push_back(path_of(problem, b, options.simulation, false));
  // The object balls where they stand, and how the best stroke moves them (the pot's
  // ball to its pocket).
  const phys::ShotResult best = drawn_result(problem, b, options.simulation);
  for (size_t k = 1; k < best.balls.size(); ++k) {
    const phys::BallOutcome& ball = best.balls[k];
    draw::DrawnBall drawn = draw::named_ball(ball.name, ball.start);
    if (!ball.path.empty()) drawn.paths.push_back({ball.path, ball.events, false});
    // problem_table drew it where it stands: give that one its path rather than a twin.
    auto same = std::find_if(d.balls.begin(), d.balls.end(),
                             [&](const draw::DrawnBall& shown) { return shown.name == ball.name; });
    if (same != d.balls.end()) {
      same->paths = std::move(drawn.paths);
      continue;
    }
    d.balls.push_back(std::move(drawn));
  }
  if (!r.alternatives.empty())
    d.faint_legend = std::to_string(r.alternatives.size()) +
                     (r.alternatives.size() == 1 ? " alternative stroke" : " alternative strokes");

  std::string buf;
  buf = fmt::format("{}: {}, aim {:.4g}\u00b0", problem.name.c_str(),
                plan::describe_stroke(b.shot).c_str(), b.shot.aim_deg);
  d.title = buf;
  buf = fmt::format("{}. V = {:.4g} m/s, aim {:.4g}\u00b0, k_{{T}} = {:.3g}, k_{{S}} = {:.3g} (tip {}).",
                r.status == plan::PlanStatus::solved ? "Solved"
                : r.status == plan::PlanStatus::no_solution_found
                    ? "No solution found; the nearest stroke"
                    : "Budget exhausted; the best stroke",
                b.shot.speed, b.shot.aim_deg, b.shot.topspin_k, b.shot.sidespin_k,
                tip_offset_words(b.shot).c_str());
  d.caption.push_back(buf);
  std::string outcome;
  if (std::isfinite(b.miss_distance) && problem.is_escape()) {
    outcome = "The cue ball comes to rest after " + route_text(problem.scene, b.route);
  } else if (!problem.has_target && b.outcome == phys::ShotStatus::rest) {
    outcome = fmt::format("Stops at x = {:.3f} m, y = {:.3f} m after {}", b.final_position.x,
                          b.final_position.y, route_text(problem.scene, b.route));
  } else if (std::isfinite(b.miss_distance)) {
    buf = fmt::format("Stops {:.3g} mm from the target after {}",
                  1000.0 * b.miss_distance, route_text(problem.scene, b.route).c_str());
    outcome = buf;
  } else {
    outcome = std::string("Ends ") + phys::to_string(b.outcome) + " after " +
              route_text(problem.scene, b.route);
  }
  if (options.robustness_samples > 0)
    outcome += "; " + fmt::format("{:.0f} %", 100.0 * b.success_probability) +
               " of noisy strokes succeed (noise \u00d7" + number(options.noise.scale) + ")";
  if (b.pot)
    outcome = fmt::format("{} {} in the {} pocket ({:.1f}\u00b0 cut, {} ball); ",
                          b.pot->made ? "Pots" : "Misses", b.pot->ball, b.pot->pocket_name,
                          b.pot->cut_deg, b.pot->thickness) +
              static_cast<char>(std::tolower(static_cast<unsigned char>(outcome.front()))) +
              outcome.substr(1);
  d.caption.push_back(outcome + ".");
  if (!b.route_words.empty()) {
    std::string words = b.route_words;
    words.front() = static_cast<char>(std::toupper(static_cast<unsigned char>(words.front())));
    d.caption.push_back(words + ".");
  }
  if (!r.alternatives.empty())
    d.caption.push_back(
        "Faint grey: the alternatives (other routes or spins), listed by cueplan solve.");
  return d;
}

}  // namespace

SolveCommand::SolveCommand(CLI::App& parent) {
  command_ = parent.add_subcommand(
      "solve",
      "Plan the stroke - speed, aim, topspin, sidespin - that leaves the cue ball on a "
      "problem's target, and report it in a player's terms with its chance of success and "
      "its alternatives.");
  CLI::App& c = *command_;
  CLI::Option* problem =
      c.add_option("PROBLEM", args_.problem_file,
                   "Problem file (YAML, problems/README.md): table, cue ball, target, limits. "
                   "Required unless --batch is given.")
          ->type_name("FILE.yaml");

  add_planner_flags(c, &args_.planner, "Search");
  c.add_option("--threads", args_.threads,
               "Threads for the independent local starts (and a table build); 0: one per core. "
               "The answer does not depend on it while the evaluation budget ends the search")
      ->type_name("N")
      ->capture_default_str()
      ->group("Search");
  add_impact_flags(c, &args_.impact, "Cushion impacts");

  const char* output = "Output";
  CLI::Option* json = c.add_flag("--json", args_.json,
             "Print one JSON object instead of text: status, message, shot {speed, aim_deg, "
             "topspin_k, sidespin_k}, final_position, miss_distance, success_probability, "
             "success {pot (pot problems), position, next (with next), both: {p, low, high, "
             "samples}}, pot {ball, pocket, cut_deg, thickness, throw_deg, margin_m, "
             "aim_margin_deg, ...}, next {ball, pocket, p, cut_deg, distance_m, zone_area_m2, "
             "in_zone, ...} (with next), failure, "
             "evaluations, time_s, alternatives (same shape), constraints, ...")
      ->group(output);
  CLI::Option* svg =
      c.add_option("--svg", args_.svg_file,
                   "Also draw the plan: the table, the target zone, the best stroke's path and "
                   "the alternatives' paths dimmed; SVG, PNG or PDF by the file's extension")
          ->type_name("FILE.svg|.png|.pdf")
          ->group(output);
  add_solve_batch_flags(c, &args_.batch, problem, json, svg);

  c.footer(
      "Status: solved (exit 0); no_solution_found - the search converged everywhere it "
      "looked without reaching the target, a strong hint but no proof - budget_exhausted, or "
      "unreachable - no direct, kick or bank route within the limits, every family screened or "
      "off the cushions on its mirror lines (exit 1; the ruled-out families are listed); bad "
      "input exits 2.\n"
      "Example: cueplan solve problems/one_rail_position.yaml --seed 7 --svg plan.svg");
}

bool SolveCommand::selected() const { return command_->parsed(); }

struct SolveCommand::Inputs {
  phys::SimulationOptions simulation;
  plan::PlannerOptions options;
  prob::LoadResult loaded;
};

std::string SolveCommand::read_inputs(Inputs* inputs) const {
  // Flags first, then the output path and the problem: whole-input errors come before
  // any table is built.
  if (std::string why = read_impact_options(args_.impact, &inputs->simulation); !why.empty())
    return why;
  if (std::string why = read_planner_options(args_.planner, args_.threads, inputs->simulation,
                                             &inputs->options);
      !why.empty())
    return why;
  if (!args_.svg_file.empty())
    if (std::string why = check_picture_file("--svg", args_.svg_file); !why.empty()) return why;
  if (args_.problem_file.empty()) return "PROBLEM is required (a problem file) unless --batch is given";
  inputs->loaded = prob::load_problem(args_.problem_file);
  return inputs->loaded.error;
}

namespace {

// The batch's request from the command's flags.
SolveBatchRequest batch_request(const SolveArgs& args) {
  return {args.planner, args.impact, args.threads};
}

}  // namespace

int SolveCommand::validate(std::ostream& err) const {
  if (command_->count("--batch") > 0)
    return validate_solve_batch(args_.batch, batch_request(args_), command_->count("--accuracy") > 0, err);
  Inputs inputs;
  const std::string why = read_inputs(&inputs);
  return why.empty() ? kExitOk : usage_error(err, kCommandName, why);
}

int SolveCommand::run(std::ostream& out, std::ostream& err) const {
  if (command_->count("--batch") > 0)
    return run_solve_batch(args_.batch, batch_request(args_), command_->count("--accuracy") > 0, out, err);
  const auto started = std::chrono::steady_clock::now();
  const auto usage = [&](const std::string& why) { return usage_error(err, kCommandName, why); };

  Inputs inputs;
  if (std::string why = read_inputs(&inputs); !why.empty()) return usage(why);
  for (const std::string& warning : prob::problem_warnings(*inputs.loaded.problem))
    err << kCommandName << ": warning: " << warning << '\n';
  phys::SimulationOptions& simulation = inputs.simulation;
  plan::PlannerOptions& options = inputs.options;
  const prob::Problem& problem = *inputs.loaded.problem;

  phys::ImpactTable table;
  bool built = false;  // a first build of the table is not charged to --max-time
  if (simulation.impact_method == phys::ImpactMethod::table) {
    const int code = prepare_impact_table(kCommandName, problem.scene, args_.impact.table_cache,
                                          args_.threads, command_->count("--accuracy") > 0, &table,
                                          &simulation, err, &built);
    if (code != kExitOk) return code;
    options.simulation = simulation;
  }

  // --max-time bounds the whole command: the plan gets what reading the inputs and
  // loading the table left of it.
  plan::PlannerOptions budgeted = options;
  if (!built) {
    const double spent =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    budgeted.max_time_s = std::max(1e-6, options.max_time_s - spent);
    if (spent > 0.5 * options.max_time_s)
      err << kCommandName << ": reading the problem and loading the impact table took "
          << fmt::format("{:.3g} s of the {:.3g} s --max-time budget; the plan has {:.3g} s",
                         spent, options.max_time_s, budgeted.max_time_s)
          << '\n';
  }
  const plan::PlanResult result = plan::plan(problem, budgeted);
  if (result.status == plan::PlanStatus::invalid_input) return usage(result.message);

  // The drawing first: if it cannot be written, nothing else is printed.
  if (!args_.svg_file.empty()) {
    const draw::Picture picture = draw::table_picture(drawing_of(problem, options, result));
    if (std::string why = write_picture(args_.svg_file, picture); !why.empty())
      return usage("--svg: " + why);
  }
  if (args_.json)
    out << solve_json(problem, options, result, args_.svg_file).dump(2) << '\n';
  else
    write_text(out, problem, options, result, args_.svg_file);
  if (!out) return kExitFailed;
  return result.status == plan::PlanStatus::solved ? kExitOk : kExitFailed;
}

}  // namespace cueplan::cli
