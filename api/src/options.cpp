#include "cueplan/api/options.hpp"
#include "cueplan/api/field_names.hpp"
#include "cueplan/api/words.hpp"

#include "cueplan/physics/parallel.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace cueplan::api {
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
    {{"robust"}, "--robust"},
    {{"simulation", "impact_method"}, "--method"},
};

}  // namespace

namespace {

// planner_options on *options (its other fields kept).
void fill_planner_options(const PlannerArgs& args, int threads,
                          const physics::SimulationOptions& simulation,
                          std::span<const FieldName> names, plan::PlannerOptions* out) {
  plan::PlannerOptions& options = *out;
  const auto name = [&](physics::FieldPath field) { return name_of(field, names); };
  const auto fail = [&](physics::FieldPath field, const std::string& rule) {
    const std::string n = name(field);
    return InputError(n, n + rule);
  };
  if (!plan::parse_global_method(args.global, &options.global))
    throw fail({"global"}, " must be one of direct_l, crs2, mlsl, isres, ompl_kpiece1, got '" +
                               args.global + "'");
  if (!plan::parse_local_method(args.local, &options.local))
    throw fail({"local"}, " must be one of bobyqa, sbplx, cobyla, neldermead, got '" + args.local +
                              "'");
  if (args.max_evaluations < 1)
    throw fail({"max_evaluations"}, " must be a positive number of shot simulations, got " +
                                        std::to_string(args.max_evaluations));
  if (!std::isfinite(args.max_time_s) || !(args.max_time_s > 0.0))
    throw fail({"max_time_s"}, " must be positive and finite (s), got " + number(args.max_time_s));
  if (args.starts < 1)
    throw fail({"local_starts"}, " must be at least 1, got " + std::to_string(args.starts));
  // Ten times a club player's scatter already sends strokes past what a cue can give.
  if (!std::isfinite(args.noise) || args.noise < 0.0 || args.noise > 10.0)
    throw fail({"noise", "scale"},
               " must be 0 to 10 (times a club player's scatter), got " + number(args.noise));
  if (args.samples < 0)
    throw fail({"robustness_samples"}, " must not be negative, got " + std::to_string(args.samples));
  if (args.robust && args.samples < 1)
    throw fail({"robustness_samples"}, " must be at least 1 with " + name({"robust"}) + ", got " +
                                           std::to_string(args.samples));
  if (args.alternatives < 0)
    throw fail({"max_alternatives"},
               " must not be negative, got " + std::to_string(args.alternatives));
  if (threads < 0)
    throw fail({"threads"}, " must be 0 (one per core) or more, got " + std::to_string(threads));

  options.max_evaluations = args.max_evaluations;
  options.max_time_s = args.max_time_s;
  options.local_starts = args.starts;
  options.seed = args.seed;
  options.threads = static_cast<int>(physics::thread_count(threads));
  options.noise.scale = args.noise;
  options.noise.tip_offset_relative = args.tip_offset_relative;
  options.noise.squirt_judgement = args.squirt_judgement;
  options.noise.bridge_length = args.bridge_length;
  options.robust = args.robust;
  options.robustness_samples = args.samples;
  options.enforce_rigid_limit = args.enforce_rigid_limit;
  options.max_alternatives = args.alternatives;
  options.simulation = simulation;
  if (const physics::Validation e = options.validate())
    throw InputError(name_of(e->field, names), message_in(*e, names));
}

}  // namespace

plan::PlannerOptions planner_options(const PlannerArgs& args, int threads,
                                     const physics::SimulationOptions& simulation,
                                     std::span<const FieldName> names) {
  plan::PlannerOptions options;
  fill_planner_options(args, threads, simulation, names, &options);
  return options;
}

std::string read_planner_options(const PlannerArgs& args, int threads,
                                 const physics::SimulationOptions& simulation,
                                 plan::PlannerOptions* options) {
  try {
    fill_planner_options(args, threads, simulation, kPlannerFlags, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
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

}  // namespace cueplan::api
