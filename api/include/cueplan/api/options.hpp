// The planner's options as every face asks for them (the command line's flags, the
// server's request options, a batch's lines), and the one validator that reads them into
// planner::PlannerOptions: its errors are InputErrors naming the field as the caller does.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "cueplan/api/errors.hpp"
#include "cueplan/api/field_names.hpp"

#include "cueplan/planner/planner.hpp"

namespace cueplan::api {

// What the command line asked of the planner, in the flags' units; the defaults are
// PlannerOptions' own.
struct PlannerArgs {
  std::string global = planner::to_string(planner::PlannerOptions{}.global);
  std::string local = planner::to_string(planner::PlannerOptions{}.local);
  int max_evaluations = planner::PlannerOptions{}.max_evaluations;
  double max_time_s = planner::PlannerOptions{}.max_time_s;
  int starts = planner::PlannerOptions{}.local_starts;
  uint64_t seed = planner::PlannerOptions{}.seed;
  double noise = 1.0;  // multiplies every deviation of the NoiseModel
  double tip_offset_relative = planner::NoiseModel{}.tip_offset_relative;  // --tip-offset-relative
  double squirt_judgement = planner::NoiseModel{}.squirt_judgement;        // --squirt-judgement
  double bridge_length = planner::NoiseModel{}.bridge_length;              // --bridge-length
  bool robust = false;
  int samples = planner::PlannerOptions{}.robustness_samples;
  bool enforce_rigid_limit = false;
  int alternatives = planner::PlannerOptions{}.max_alternatives;
};

// The planner's options read from `args`, with `threads` (0: one per core) and
// `simulation`. Throws InputError when one is not usable, its field and message naming
// the option by `names` (PlannerOptions' fields: {"max_time_s"}, {"noise", "scale"},
// {"robust"}, {"robustness_samples"}, ...; planner_flag_names() for the flags).
planner::PlannerOptions planner_options(const PlannerArgs& args, int threads,
                                        const physics::SimulationOptions& simulation,
                                        std::span<const FieldName> names);

// The command line's form of planner_options: empty when the flags are usable: then *options holds them, `threads` (0: one per
// core) and `simulation`. Otherwise one line naming the flag.
std::string read_planner_options(const PlannerArgs& args, int threads,
                                 const physics::SimulationOptions& simulation,
                                 planner::PlannerOptions* options);

// PlannerOptions' fields and the flags that set them, by which read_planner_options
// names its errors ({"max_time_s"} -> "--max-time", {"noise", "scale"} -> "--noise", ...).
std::span<const FieldName> planner_flag_names();

// The planner's noise model in words, e.g. "aim 0.125 deg, speed 0.075 m/s, tip 0.5 mm
// (standard deviations, --noise 1)".
std::string noise_text(const planner::NoiseModel& noise);

}  // namespace cueplan::api

// The faces (command line, server, batch) name these as their own.
namespace cueplan::cli {
using api::PlannerArgs;
using api::read_planner_options;
using api::planner_options;
using api::InputError;
using api::planner_flag_names;
using api::noise_text;
}  // namespace cueplan::cli
