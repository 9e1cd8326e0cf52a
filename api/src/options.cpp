#include "planner_flags.hpp"
#include "field_names.hpp"
#include "shot_words.hpp"

#include <CLI/CLI.hpp>

#include "cueplan/physics/parallel.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace cueplan::cli {
namespace {

namespace plan = cueplan::planner;

// PlannerOptions' fields and the flags that set them.
const std::initializer_list<FieldName> kPlannerFlags = {
    {{"max_evaluations"}, "--max-evaluations"},
    {{"max_time_s"}, "--max-time"},
    {{"local_starts"}, "--starts"},
    {{"threads"}, "--threads"},
    {{"noise", "scale"}, "--noise"},
    {{"noise", "tip_offset_relative"}, "--tip-offset-relative"},
    {{"noise", "squirt_judgement"}, "--squirt-judgement"},
    {{"noise", "bridge_length"}, "--bridge-length"},
    {{"robustness_samples"}, "--samples"},
    {{"max_alternatives"}, "--alternatives"},
    {{"simulation", "impact_accuracy"}, "--accuracy"},
    {{"global"}, "--global"},
    {{"local"}, "--local"},
};

}  // namespace

void add_planner_flags(CLI::App& c, PlannerArgs* args, const char* group) {
  c.add_option("--global", args->global,
               "Global search (NLopt): direct_l (DIRECT-L), crs2 (controlled random search), "
               "mlsl (multi-level single linkage) or isres (evolution strategy); or (OMPL) "
               "ompl_kpiece1 (a KPIECE1 tree of strokes spread by where they land)")
      ->type_name("direct_l|crs2|mlsl|isres|ompl_kpiece1")
      ->capture_default_str()
      ->group(group);
  c.add_option("--local", args->local,
               "Local polish (NLopt, derivative-free): bobyqa, sbplx (Subplex), cobyla or "
               "neldermead")
      ->type_name("bobyqa|sbplx|cobyla|neldermead")
      ->capture_default_str()
      ->group(group);
  c.add_option("--max-evaluations", args->max_evaluations,
               "Budget: shot simulations for the search, global and local together, >= 10")
      ->type_name("N")
      ->capture_default_str()
      ->group(group);
  c.add_option("--max-time", args->max_time_s,
               "Budget: wall-clock time for the whole command (s), > 0: loading the impact "
               "table (not a first build), the search (up to 75 % of it), the exact "
               "verification and the Monte Carlo (an estimate the clock cuts short counts the "
               "strokes it played). A plan the clock ends is no longer reproducible from its "
               "seed")
      ->type_name("S")
      ->capture_default_str()
      ->group(group);
  c.add_option("--starts", args->starts, "Distinct global candidates polished locally, >= 1")
      ->type_name("N")
      ->capture_default_str()
      ->group(group);
  c.add_option("--seed", args->seed,
               "Seed of every random choice: the same seed and options give the same answer")
      ->type_name("N")
      ->capture_default_str()
      ->group(group);
  c.add_option("--noise", args->noise,
               "Scale of the player's execution noise (Gaussian: aim 0.125 deg, speed "
               "0.075 m/s, tip offset 0.5 mm each way plus --tip-offset-relative of the "
               "offset, squirt misjudged by --squirt-judgement of it; all times this), >= 0; "
               "0 is a perfect cue")
      ->type_name("X")
      ->capture_default_str()
      ->group(group);
  c.add_option("--tip-offset-relative", args->tip_offset_relative,
               "Execution noise: the tip offset's deviation each way grows by this fraction of "
               "the offset intended that way (docs/squirt.md), >= 0")
      ->type_name("F")
      ->capture_default_str()
      ->group(group);
  c.add_option("--squirt-judgement", args->squirt_judgement,
               "Execution noise: the player's allowance for squirt errs by this fraction of "
               "the squirt (an aim deviation; docs/squirt.md), >= 0")
      ->type_name("F")
      ->capture_default_str()
      ->group(group);
  c.add_option("--bridge-length", args->bridge_length,
               "Execution noise: a sideways tip error turns the cue about the bridge this far "
               "behind the tip (m; docs/squirt.md), >= 0; 0 shifts the cue without turning it")
      ->type_name("M")
      ->capture_default_str()
      ->group(group);
  c.add_flag("--robust", args->robust,
             "Maximise the success probability under the noise rather than the nominal miss")
      ->group(group);
  c.add_option("--samples", args->samples,
               "Noisy strokes simulated per success probability (Monte Carlo), >= 0; 0 skips it "
               "(>= 1 with --robust)")
      ->type_name("N")
      ->capture_default_str()
      ->group(group);
  c.add_flag("--enforce-rigid-limit", args->enforce_rigid_limit,
             "Reject strokes that meet a cushion faster than " +
                 number(physics::CushionParams{}.rigid_speed_limit, "m/s") +
                 " along its normal, where the rigid-cushion model is not trusted (otherwise "
                 "such strokes are only flagged)")
      ->group(group);
  c.add_option("--alternatives", args->alternatives,
               "Distinct solutions (other cushion routes, draw or follow, left or right) reported "
               "besides the best, >= 0")
      ->type_name("N")
      ->capture_default_str()
      ->group(group);
}

std::string read_planner_options(const PlannerArgs& args, int threads,
                                 const physics::SimulationOptions& simulation,
                                 plan::PlannerOptions* options) {
  if (!plan::parse_global_method(args.global, &options->global))
    return "--global must be one of direct_l, crs2, mlsl, isres, ompl_kpiece1, got '" + args.global + "'";
  if (!plan::parse_local_method(args.local, &options->local))
    return "--local must be one of bobyqa, sbplx, cobyla, neldermead, got '" + args.local + "'";
  if (args.max_evaluations < 1)
    return "--max-evaluations must be a positive number of shot simulations, got " +
           std::to_string(args.max_evaluations);
  if (!std::isfinite(args.max_time_s) || !(args.max_time_s > 0.0))
    return "--max-time must be positive and finite (s), got " + number(args.max_time_s);
  if (args.starts < 1) return "--starts must be at least 1, got " + std::to_string(args.starts);
  // Ten times a club player's scatter already sends strokes past what a cue can give.
  if (!std::isfinite(args.noise) || args.noise < 0.0 || args.noise > 10.0)
    return "--noise must be 0 to 10 (times a club player's scatter), got " + number(args.noise);
  if (args.samples < 0)
    return "--samples must not be negative, got " + std::to_string(args.samples);
  if (args.robust && args.samples < 1)
    return "--samples must be at least 1 with --robust, got " + std::to_string(args.samples);
  if (args.alternatives < 0)
    return "--alternatives must not be negative, got " + std::to_string(args.alternatives);
  if (threads < 0)
    return "--threads must be 0 (one per core) or more, got " + std::to_string(threads);

  options->max_evaluations = args.max_evaluations;
  options->max_time_s = args.max_time_s;
  options->local_starts = args.starts;
  options->seed = args.seed;
  options->threads = static_cast<int>(physics::thread_count(threads));
  options->noise.scale = args.noise;
  options->noise.tip_offset_relative = args.tip_offset_relative;
  options->noise.squirt_judgement = args.squirt_judgement;
  options->noise.bridge_length = args.bridge_length;
  options->robust = args.robust;
  options->robustness_samples = args.samples;
  options->enforce_rigid_limit = args.enforce_rigid_limit;
  options->max_alternatives = args.alternatives;
  options->simulation = simulation;
  const physics::Validation e = options->validate();
  return e ? message_in(*e, kPlannerFlags) : std::string();
}

std::span<const FieldName> planner_flag_names() { return kPlannerFlags; }

std::string noise_text(const plan::NoiseModel& noise) {
  return "aim " + number(noise.aim_deg * noise.scale) + " deg, speed " +
         number(noise.speed * noise.scale) + " m/s, tip offset " +
         number(1000.0 * noise.tip_offset * noise.scale) + " mm + " +
         number(100.0 * noise.tip_offset_relative * noise.scale) + " % of the offset, squirt " +
         number(100.0 * noise.squirt_judgement * noise.scale) +
         " % misjudged, cue pivoting " + number(1000.0 * noise.bridge_length) +
         " mm behind the tip (standard deviations; --noise " +
         number(noise.scale) + ")";
}

}  // namespace cueplan::cli
