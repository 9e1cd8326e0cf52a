#include "spinmap_command.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>

#include "cueplan/draw/spin_map.hpp"
#include "cueplan/physics/impact_table.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/planner/spin_map.hpp"
#include "cueplan/problems/problem.hpp"
#include "cueplan/problems/stroke_ranges.hpp"
#include "cueplan/api/exit_codes.hpp"
#include "search_flags.hpp"
#include "cueplan/api/output_file.hpp"
#include "cueplan/physics/parallel.hpp"
#include "cueplan/api/words.hpp"

namespace cueplan::cli {
namespace {

namespace phys = cueplan::physics;
namespace plan = cueplan::planner;
namespace prob = cueplan::problems;
using nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

constexpr const char* kCommandName = "cueplan spinmap";
constexpr double kSpinPerTipOffset = 2.5;  // k = 2.5 d / R (PHYSICS.md, "Cue strike")
constexpr int kSamplePathsPerSide = 5;     // faint paths: about 5 x 5 spins of the grid

using draw::classify;
using draw::format_of;
using draw::SpinCellKind;
using PictureFormat = draw::Format;

// A progress bar on a terminal's stderr, drawn once the work has taken a moment and
// redrawn as the fraction grows; nothing at all when stderr is not a terminal.
class ProgressBar {
 public:
  ProgressBar(std::ostream& err, std::string label)
      : err_(err),
        label_(std::move(label)),
        enabled_(::isatty(STDERR_FILENO) == 1),
        started_(Clock::now()) {}
  ~ProgressBar() { finish(); }

  void update(double fraction) {
    if (!enabled_) return;
    if (!drawn_ && Clock::now() - started_ < std::chrono::milliseconds(300)) return;
    const int percent = static_cast<int>(std::floor(100.0 * std::clamp(fraction, 0.0, 1.0)));
    if (drawn_ && percent == shown_) return;
    constexpr int kWidth = 32;
    const int filled = percent * kWidth / 100;
    err_ << '\r' << label_ << " [" << std::string(static_cast<size_t>(filled), '#')
         << std::string(static_cast<size_t>(kWidth - filled), '.') << "] " << percent << " %"
         << std::flush;
    drawn_ = true;
    shown_ = percent;
  }

  void finish() {
    if (drawn_) err_ << '\n' << std::flush;
    drawn_ = false;
    enabled_ = false;
  }

 private:
  std::ostream& err_;
  std::string label_;
  bool enabled_;
  Clock::time_point started_;
  bool drawn_ = false;
  int shown_ = -1;
};

}  // namespace


namespace {

draw::SpinMapScene picture_of(const prob::Problem& problem, const plan::SpinMap& map,
                              const StrokeSource& source,
                              const phys::SimulationOptions& simulation) {
  draw::SpinMapScene picture;
  picture.problem = problem;
  picture.map = map;
  std::string buf;
  buf = fmt::format("What spin lands here? {}: V = {:.4g} m/s, aim {:.4g}\u00b0",
                problem.name.c_str(), map.speed, map.aim_deg);
  picture.title = buf;
  buf = problem.pot
            ? fmt::format("Each cell is one tip offset struck at this speed, its aim solved again to "
                          "keep the pot of {} (spin changes the throw), coloured by how far from the "
                          "target the cue ball stops; {} of {} spins land (outlined), {} cannot pot.",
                          problem.pot->ball, map.landing, map.points.size(), map.not_potting)
            : fmt::format("Each cell is one tip offset struck at this speed and aim, coloured by how far from "
                          "the target the cue ball stops; {} of {} spins land (outlined).",
                          map.landing, map.points.size());
  if (map.success_samples > 0) {
    // The cells show how forgiving each spin is instead.
    const std::string was = "coloured by how far from the target the cue ball stops";
    const size_t at = buf.find(was);
    if (at != std::string::npos)
      buf.replace(at, was.size(),
                  fmt::format("coloured by its success under noise ({} noisy strokes)",
                              map.success_samples));
  }
  picture.caption.push_back(buf);
  if (source.planned)
    picture.caption.push_back("Speed and aim are the planner's best stroke (" +
                              std::string(plan::to_string(source.plan.status)) +
                              "); its own spin is ringed, its path drawn in full.");
  else
    picture.caption.push_back(
        "Speed and aim as given. Tip offset d from centre gives spin k = 2.5 d/R.");

  // Faint paths of a few spins, and the planner's stroke in full.
  phys::SimulationOptions paths = simulation;
  paths.record_path = true;
  for (size_t i : draw::sparse_subset(map, kSamplePathsPerSide)) {
    const plan::SpinMapPoint& p = map.points[i];
    const phys::ShotResult r =
        phys::simulate(problem.scene, problem.cue_ball,
                       {map.speed, p.aim_deg, p.topspin_k, p.sidespin_k}, paths);
    picture.sample_paths.push_back({r.path, r.events, true});
  }
  if (source.planned) {
    // As the planner reported its outcome: with the exact method when it verified so.
    phys::SimulationOptions planned = paths;
    if (source.plan.best.impact_method != phys::ImpactMethod::table &&
        planned.impact_method == phys::ImpactMethod::table) {
      planned.impact_method = phys::ImpactMethod::exact;
      planned.impact_accuracy = 1e-9;
    }
    const phys::ShotResult r =
        phys::simulate(problem.scene, problem.cue_ball, source.plan.best.shot, planned);
    picture.shot_path = draw::DrawnPath{r.path, r.events, false};
    picture.marked_shot = source.plan.best.shot;
  }
  return picture;
}

}  // namespace

SpinmapCommand::SpinmapCommand(CLI::App& parent) {
  command_ = parent.add_subcommand(
      "spinmap",
      "What spin lands here? For one speed and aim, draw every spin over the tip-offset disc "
      "coloured by where the cue ball stops, the spins that land on the target outlined, and "
      "the table with each spin's rest position.");
  CLI::App& c = *command_;
  c.add_option("PROBLEM", args_.problem_file,
               "Problem file (YAML, problems/README.md): table, cue ball, target, limits")
      ->required()
      ->type_name("FILE.yaml");
  c.add_option("--out", args_.out_file, "The picture to write: SVG, PNG or PDF, by the file's extension")
      ->required()
      ->type_name("FILE.svg|.png|.pdf");

  const char* stroke = "Stroke";
  c.add_option("--speed", args_.speed,
               "Cue-ball speed V (m/s), > 0; with --aim. Without both, the planner's best stroke "
               "gives the speed and aim")
      ->type_name("m/s")
      ->group(stroke);
  c.add_option("--aim", args_.aim_deg, "Aim (deg from +x, counter-clockwise); with --speed")
      ->type_name("deg")
      ->group(stroke);
  c.add_option("--grid", args_.grid,
               "Spins across the disc's diameter, 3 to 1001 (odd keeps centre ball); the map "
               "simulates about 0.785 grid^2 strokes")
      ->type_name("N")
      ->capture_default_str()
      ->group(stroke);
  c.add_option("--threads", args_.threads,
               "Threads for the map (and the planner, a table build); 0: one per core. The map is "
               "the same for any count")
      ->type_name("N")
      ->capture_default_str()
      ->group(stroke);
  add_impact_flags(c, &args_.impact, "Cushion impacts");
  add_planner_flags(c, &args_.planner, "Planner (only without --speed and --aim)");
  c.add_flag("--success", args_.success,
             "How forgiving each spin is: shade the cells by the success under the execution "
             "noise (--samples noisy strokes a spin, default " +
                 std::to_string(kDefaultSuccessSamples) +
                 ", with --noise and --seed) rather than by where they stop")
      ->group(stroke);
  c.add_flag("--json", args_.json,
             "Print a JSON summary instead of text: speed, aim_deg, stroke_source, grid, points, "
             "landing, landing_spins, nearest, outcomes, out")
      ->group("Output");

  c.footer(
      "The disc: tip offset right of centre along x, above centre along y, as fractions of the "
      "ball radius R (k = 2.5 d/R); the dashed circle is the spin limit. Colour: distance from "
      "the target where the ball stops (log scale, mm); grey cells stop after a cushion count "
      "the problem does not allow, hatched ones are pocketed.\n"
      "Exit codes: 0 picture written, 1 it could not be had, 2 bad input.\n"
      "Example: cueplan spinmap problems/one_rail_position.yaml --speed 1.002 --aim -60.36 "
      "--out spin.svg");
}

bool SpinmapCommand::selected() const { return command_->parsed(); }

bool SpinmapCommand::given(const char* flag) const { return command_->count(flag) > 0; }

struct SpinmapCommand::Inputs {
  PictureFormat format = PictureFormat::svg;
  bool speed_given = false;  // --speed and --aim; otherwise the planner's stroke
  phys::SimulationOptions simulation;
  plan::PlannerOptions planner_options;
  prob::LoadResult loaded;
};

std::string SpinmapCommand::read_inputs(Inputs* inputs) const {
  // Flags first, then the output path and the problem: whole-input errors come before
  // any table is built.
  const std::optional<PictureFormat> format = format_of(args_.out_file);
  if (!format) return "--out must name a .svg, .png or .pdf file, got '" + args_.out_file + "'";
  inputs->format = *format;
  const bool speed_given = given("--speed");
  inputs->speed_given = speed_given;
  if (speed_given != given("--aim"))
    return std::string(speed_given ? "--aim" : "--speed") + " is required with " +
           (speed_given ? "--speed" : "--aim") +
           ": give both, or neither to use the planner's best stroke";
  if (speed_given && (!std::isfinite(args_.speed) || !(args_.speed > 0.0)))
    return "--speed must be finite and above 0 (m/s), got " + number(args_.speed);
  if (speed_given && !std::isfinite(args_.aim_deg))
    return "--aim must be finite (deg), got " + number(args_.aim_deg);
  if (args_.grid < 3 || args_.grid > 1001)
    return "--grid must be 3 to 1001 points across the disc, got " + std::to_string(args_.grid);
  if (args_.threads < 0)
    return "--threads must be 0 (one per core) or more, got " + std::to_string(args_.threads);
  if (std::string why = read_impact_options(args_.impact, &inputs->simulation); !why.empty())
    return why;
  if (args_.success && given("--samples") &&
      (args_.planner.samples < 1 || args_.planner.samples > kMaxSuccessSamples))
    return "--samples must be 1 to " + std::to_string(kMaxSuccessSamples) +
           " noisy strokes a spin with --success, got " + std::to_string(args_.planner.samples);
  if (args_.success && (!std::isfinite(args_.planner.noise) || args_.planner.noise < 0.0 ||
                        args_.planner.noise > 10.0))
    return "--noise must be 0 to 10 (times a club player's scatter), got " +
           number(args_.planner.noise);
  if (!speed_given)
    if (std::string why = read_planner_options(args_.planner, args_.threads, inputs->simulation,
                                               &inputs->planner_options);
        !why.empty())
      return why;
  if (std::string why = check_output_file(args_.out_file); !why.empty()) return "--out: " + why;
  inputs->loaded = prob::load_problem(args_.problem_file);
  return inputs->loaded.error;
}

int SpinmapCommand::validate(std::ostream& err) const {
  Inputs inputs;
  const std::string why = read_inputs(&inputs);
  return why.empty() ? kExitOk : usage_error(err, kCommandName, why);
}

int SpinmapCommand::run(std::ostream& out, std::ostream& err) const {
  const auto usage = [&](const std::string& why) { return usage_error(err, kCommandName, why); };
  const Clock::time_point started = Clock::now();

  Inputs inputs;
  if (std::string why = read_inputs(&inputs); !why.empty()) return usage(why);
  for (const std::string& warning : prob::problem_warnings(*inputs.loaded.problem))
    err << kCommandName << ": warning: " << warning << '\n';
  const PictureFormat format = inputs.format;
  const bool speed_given = inputs.speed_given;
  phys::SimulationOptions& simulation = inputs.simulation;
  plan::PlannerOptions& planner_options = inputs.planner_options;
  const prob::Problem& problem = *inputs.loaded.problem;

  phys::ImpactTable table;
  if (simulation.impact_method == phys::ImpactMethod::table) {
    const int code =
        prepare_impact_table(kCommandName, problem.scene, args_.impact.table_cache, args_.threads,
                             given("--accuracy"), &table, &simulation, err);
    if (code != kExitOk) return code;
    planner_options.simulation = simulation;
  }

  // The stroke: given, or the planner's best.
  StrokeSource source;
  double speed = args_.speed;
  double aim_deg = args_.aim_deg;
  if (!speed_given) {
    if (::isatty(STDERR_FILENO) == 1)
      err << kCommandName << ": no --speed and --aim: planning the stroke first (up to "
          << number(planner_options.max_time_s, "s") << ")\n";
    source.planned = true;
    source.plan = plan::plan(problem, planner_options);
    if (source.plan.status == plan::PlanStatus::invalid_input) return usage(source.plan.message);
    speed = source.plan.best.shot.speed;
    aim_deg = source.plan.best.shot.aim_deg;
  }

  plan::SpinMapOptions map_options;
  map_options.grid = args_.grid;
  map_options.threads = static_cast<int>(phys::thread_count(
      args_.threads, static_cast<size_t>(args_.grid) * static_cast<size_t>(args_.grid)));
  map_options.simulation = simulation;
  ProgressBar bar(err, std::string(kCommandName) + ": simulating " + std::to_string(args_.grid) +
                           " x " + std::to_string(args_.grid) + " spins");
  map_options.progress = [&bar](double fraction) { bar.update(fraction); };
  if (args_.success) {
    map_options.success_samples =
        given("--samples") ? args_.planner.samples : kDefaultSuccessSamples;
    map_options.noise.scale = args_.planner.noise;
    map_options.seed = args_.planner.seed;
  }
  const plan::SpinMap map = plan::spin_map(problem, speed, aim_deg, map_options);
  bar.finish();
  if (!map.message.empty()) return usage(map.message);
  if (map.points.empty()) {
    err << kCommandName << ": no spin lies within the disc\n";
    return kExitFailed;
  }

  const draw::Encoded picture =
      draw::encode(draw::spin_map_picture(picture_of(problem, map, source, simulation)), format);
  if (!picture.ok()) {
    err << kCommandName << ": " << picture.error << '\n';
    return kExitFailed;
  }
  if (std::string why = write_file_atomically(args_.out_file, picture.bytes); !why.empty())
    return usage("--out: " + why);

  const double seconds = std::chrono::duration<double>(Clock::now() - started).count();
  if (args_.json) {
    ordered_json j = spinmap_json(problem, map, source, simulation, args_.out_file, seconds);
    if (map.success_samples > 0) j["cells"] = spinmap_cells_json(problem, map);
    out << j.dump(2) << '\n';
  }
  else
    write_spinmap_text(out, problem, map, source, simulation, args_.out_file, seconds);
  return out ? kExitOk : kExitFailed;
}

}  // namespace cueplan::cli
