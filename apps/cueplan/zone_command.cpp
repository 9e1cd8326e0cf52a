#include "zone_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>

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
namespace {

namespace phys = cueplan::physics;
namespace plan = cueplan::planner;
namespace prob = cueplan::problems;
using nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

constexpr const char* kCommandName = "cueplan zone";
constexpr int kMostCloud = 5000;

// The field as the table drawing takes it.
draw::TableField table_field(const plan::PositionField& f) {
  draw::TableField t;
  t.cell = f.cell();
  t.columns = f.columns();
  t.rows = f.rows();
  t.values.reserve(static_cast<size_t>(t.columns) * static_cast<size_t>(t.rows));
  for (int j = 0; j < t.rows; ++j)
    for (int i = 0; i < t.columns; ++i) t.values.push_back(f.cell_value(i, j));
  if (f.best_value() > 0.0) t.outline_level = f.zone_threshold();
  return t;
}

}  // namespace

ZoneCommand::ZoneCommand(CLI::App& parent) {
  command_ = parent.add_subcommand(
      "zone",
      "Position play as a coaching diagram: for a problem with `next`, the table shaded by "
      "P(next pot) from every cue-ball position, the zone where it is within 10 points of the "
      "best outlined, the planned stroke's path and landing, and the noisy strokes' landings.");
  CLI::App& c = *command_;
  c.add_option("PROBLEM", args_.problem_file,
               "Problem file (YAML, problems/README.md) with pot and next")
      ->required()
      ->type_name("FILE.yaml");
  c.add_option("--out", args_.out_file, "The picture to write: SVG, PNG or PDF, by the file's extension")
      ->required()
      ->type_name("FILE.svg|.png|.pdf");
  c.add_flag("--field-only", args_.field_only,
             "Draw the field and the zone alone: no stroke is planned");
  c.add_option("--cloud", args_.cloud,
               "Noisy strokes of the planned stroke drawn as landings (0: none; at most " +
                   std::to_string(kMostCloud) + ")")
      ->type_name("N")
      ->capture_default_str();
  c.add_option("--threads", args_.threads, "Threads for the planner (and a table build); 0: one per core")
      ->type_name("N")
      ->capture_default_str();
  add_impact_flags(c, &args_.impact, "Cushion impacts");
  add_planner_flags(c, &args_.planner, "Planner");
  c.add_flag("--json", args_.json,
             "Print a JSON summary instead of text: next {ball, pocket}, zone_area_m2, best, "
             "best_p, and with a plan: status, landing, p (P(next pot) there), in_zone, success, "
             "out")
      ->group("Output");
  c.footer(
      "Shade: P(next pot) from a cue ball there (viridis, clear where 0), the closed-form "
      "estimate of planner/position.hpp checked against the planner (docs/position.md). "
      "White outline: the zone. Dots: where noisy strokes stop (light: the pot made; dark: "
      "missed).\n"
      "Exit codes: 0 picture written, 1 it could not be had, 2 bad input.\n"
      "Example: cueplan zone problems/pots/red_then_black.yaml --out zone.png");
}

bool ZoneCommand::selected() const { return command_->parsed(); }

bool ZoneCommand::given(const char* flag) const { return command_->count(flag) > 0; }

struct ZoneCommand::Inputs {
  phys::SimulationOptions simulation;
  plan::PlannerOptions planner_options;
  prob::LoadResult loaded;
};

std::string ZoneCommand::read_inputs(Inputs* inputs) const {
  if (std::string why = check_picture_file("--out", args_.out_file); !why.empty()) return why;
  if (args_.cloud < 0 || args_.cloud > kMostCloud)
    return fmt::format("--cloud must be 0 to {} noisy strokes, got {}", kMostCloud, args_.cloud);
  if (args_.threads < 0)
    return "--threads must be 0 (one per core) or more, got " + std::to_string(args_.threads);
  if (std::string why = read_impact_options(args_.impact, &inputs->simulation); !why.empty())
    return why;
  if (std::string why = read_planner_options(args_.planner, args_.threads, inputs->simulation,
                                             &inputs->planner_options);
      !why.empty())
    return why;
  inputs->loaded = prob::load_problem(args_.problem_file);
  if (!inputs->loaded.ok()) return inputs->loaded.error;
  if (inputs->loaded.problem->next.empty())
    return args_.problem_file +
           ": next: missing; the zone is for the next pot (next: {ball: NAME, pocket: POCKET})";
  return {};
}

int ZoneCommand::validate(std::ostream& err) const {
  Inputs inputs;
  const std::string why = read_inputs(&inputs);
  return why.empty() ? kExitOk : usage_error(err, kCommandName, why);
}

int ZoneCommand::run(std::ostream& out, std::ostream& err) const {
  const auto usage = [&](const std::string& why) { return usage_error(err, kCommandName, why); };
  const Clock::time_point started = Clock::now();
  Inputs inputs;
  if (std::string why = read_inputs(&inputs); !why.empty()) return usage(why);
  for (const std::string& warning : prob::problem_warnings(*inputs.loaded.problem))
    err << kCommandName << ": warning: " << warning << '\n';
  const prob::Problem& problem = *inputs.loaded.problem;
  phys::SimulationOptions& simulation = inputs.simulation;
  plan::PlannerOptions& options = inputs.planner_options;

  plan::PositionCache cache;
  options.position_cache = &cache;
  const std::shared_ptr<const plan::PositionField> field = cache.get(problem, options.noise);
  const prob::NextPot& next = problem.next.front();
  const std::string pocket = prob::pocket_name(problem.scene, next.pocket);

  draw::TableScene d = draw::problem_table(problem);
  d.field = table_field(*field);
  d.field->shade_legend = fmt::format("P(next pot: {} into the {}), 0-100 %", next.ball, pocket);
  d.field->outline_legend = fmt::format("zone: within 10 points of the best ({:.0f} %), {:.0f} cm\u00b2",
                                        100.0 * field->best_value(), 1e4 * field->zone_area_m2());
  d.title = fmt::format("{}: position for the {} into the {}", problem.name, next.ball, pocket);
  if (problem.next.size() > 1)
    d.caption.push_back(fmt::format(
        "Shaded by P({}) times the best P({}) reachable from there (one step of look-ahead).",
        next.ball, problem.next[1].ball));

  std::optional<plan::PlanResult> planned;
  std::vector<plan::NoisyLanding> cloud;
  if (!args_.field_only) {
    phys::ImpactTable table;
    if (simulation.impact_method == phys::ImpactMethod::table) {
      const int code = prepare_impact_table(kCommandName, problem.scene, args_.impact.table_cache,
                                            args_.threads, given("--accuracy"), &table, &simulation, err);
      if (code != kExitOk) return code;
      options.simulation = simulation;
    }
    planned = plan::plan(problem, options);
    if (planned->status == plan::PlanStatus::invalid_input) return usage(planned->message);
    const plan::PlannedShot& b = planned->best;
    phys::SimulationOptions drawn = simulation;
    drawn.record_path = true;
    if (b.impact_method != phys::ImpactMethod::table &&
        simulation.impact_method == phys::ImpactMethod::table) {
      drawn.impact_method = phys::ImpactMethod::exact;
      drawn.impact_accuracy = 1e-9;
    }
    const phys::ShotResult r = phys::simulate(problem.scene, problem.cue_ball, b.shot, drawn);
    d.balls.front().paths.push_back({r.path, r.events, false});
    for (size_t k = 1; k < r.balls.size(); ++k) {
      const phys::BallOutcome& ball = r.balls[k];
      for (draw::DrawnBall& shown : d.balls)
        if (shown.name == ball.name && !ball.path.empty())
          shown.paths.push_back({ball.path, ball.events, false});
    }
    if (args_.cloud > 0) {
      cloud = plan::noisy_landings(problem, b.shot, options.noise, args_.cloud, options.seed, simulation);
      for (const plan::NoisyLanding& l : cloud)
        d.dots.push_back({l.position,
                          l.potted ? draw::Colour::hex("#fbfbf5") : draw::Colour::hex("#404040"),
                          2.5, draw::Colour::hex("#202020")});
      d.dots_legend = fmt::format("where {} noisy strokes stop (white: the pot made, dark: missed)",
                                  args_.cloud);
    }
    std::string caption = fmt::format("{}: {}, aim {:.4g}\u00b0.", plan::to_string(planned->status),
                                      plan::describe_stroke(b.shot), b.shot.aim_deg);
    if (b.next)
      caption += fmt::format(" It {}; P(next pot) there {:.0f} %, {} the zone.", b.next->words,
                             100.0 * b.next->p, b.next->in_zone ? "inside" : "outside");
    d.caption.push_back(caption);
    if (b.success.next && b.success.pot)
      d.caption.push_back(fmt::format(
          "Under a player's noise: pot {:.0f} %, next pot from where it stops {:.0f} %, both {:.0f} %.",
          100.0 * b.success.pot->p, 100.0 * b.success.next->p, 100.0 * b.success.both.p));
  }

  if (std::string why = write_picture(args_.out_file, draw::table_picture(d)); !why.empty()) {
    err << kCommandName << ": --out: " << why << '\n';
    return kExitFailed;
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - started).count();
  if (args_.json) {
    ordered_json j;
    j["next"] = {{"ball", next.ball}, {"pocket", pocket}};
    j["zone_area_m2"] = field->zone_area_m2();
    j["best"] = {field->best().x, field->best().y};
    j["best_p"] = field->best_value();
    j["cell_m"] = field->cell();
    if (planned) {
      const plan::PlannedShot& b = planned->best;
      j["status"] = plan::to_string(planned->status);
      j["message"] = planned->message;
      j["landing"] = {b.final_position.x, b.final_position.y};
      if (b.next) {
        j["p"] = b.next->p;
        j["in_zone"] = b.next->in_zone;
        j["next_shot"] = next_json(*b.next);
      }
      j["success"] = success_json(b.success);
      j["cloud"] = static_cast<int>(cloud.size());
    }
    j["out"] = args_.out_file;
    j["time_s"] = seconds;
    out << j.dump(2) << '\n';
  } else {
    report_line(out, "problem", problem.name + "  (" + problem.source + ")");
    report_line(out, "next", fmt::format("{} into the {} pocket", next.ball, pocket));
    report_line(out, "zone",
                fmt::format("{:.0f} cm^2 where P(next pot) is within 10 points of the best "
                            "({:.0f} % at x = {:.3f} m, y = {:.3f} m)",
                            1e4 * field->zone_area_m2(), 100.0 * field->best_value(),
                            field->best().x, field->best().y));
    if (planned) {
      const plan::PlannedShot& b = planned->best;
      report_line(out, "status", plan::to_string(planned->status));
      report_line(out, "stroke", plan::describe_stroke(b.shot));
      report_line(out, "landing", landing_text(b));
      if (b.next)
        for (const auto& [label, text] : next_lines(*b.next)) report_line(out, label, text);
    }
    report_line(out, "picture", args_.out_file);
    report_line(out, "time", fmt::format("{:.3g} s", seconds));
  }
  if (planned && planned->status != plan::PlanStatus::solved) return kExitFailed;
  return out ? kExitOk : kExitFailed;
}

}  // namespace cueplan::cli
