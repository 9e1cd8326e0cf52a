#include "simulate_batch.hpp"

#include <cmath>
#include <cstdio>
#include <optional>
#include <ostream>

#include "csv.hpp"
#include "parallel.hpp"

namespace cueplan::cli {
namespace {

namespace phys = cueplan::physics;

constexpr size_t kInputColumns = 4;
constexpr size_t kResultColumns = 8;  // final_x .. reaches_target

std::string describe(const char* name, const char* rule, double value) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s %s, got %.10g", name, rule, value);
  return buf;
}

BatchOutcome failed(std::string status, std::string message) {
  return {std::move(status), std::move(message), std::vector<std::string>(kResultColumns)};
}

// What a good row's message says: why the simulator stopped early, a shot outside the
// problem's limits, a cushion met faster than the rigid model is trusted for.
std::string row_message(const problems::Problem& problem, const phys::Shot& shot,
                        const phys::ShotResult& r) {
  std::string message = r.message;
  const auto add = [&](const std::string& note) {
    if (!message.empty()) message += "; ";
    message += note;
  };
  if (std::string why = problems::check_shot(problem.limits, shot); !why.empty())
    add("outside the problem's limits: " + why);
  if (r.rigid_limit_exceeded) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "a cushion normal speed of %.4g m/s exceeded the rigid-cushion limit of %.4g m/s",
                  r.max_cushion_normal_speed, problem.scene.ball_and_cushion.rigid_speed_limit);
    add(buf);
  }
  return message;
}

BatchOutcome simulate_row(const BatchRow& row, const problems::Problem& problem,
                          const phys::SimulationOptions& options) {
  const std::string where = "line " + std::to_string(row.line) + ": ";
  if (row.fields.size() != kInputColumns)
    return failed("parse_error",
                  where + "expected 4 columns, got " + std::to_string(row.fields.size()));
  double value[kInputColumns];
  for (size_t c = 0; c < kInputColumns; ++c) {
    const std::optional<double> number = parse_number(row.fields[c]);
    if (!number) {
      const char* names[] = {kShotColumnNames.speed, kShotColumnNames.aim, kShotColumnNames.topspin,
                             kShotColumnNames.sidespin};
      return failed("parse_error",
                    where + names[c] + " is not a number: '" + trimmed(row.fields[c]) + "'");
    }
    value[c] = *number;
  }
  const phys::Shot shot{value[0], value[1], value[2], value[3]};
  if (std::string why = check_shot_inputs(shot, kShotColumnNames); !why.empty())
    return failed("invalid_input", where + why);

  const phys::ShotResult r = phys::simulate(problem.scene, problem.cue_ball, shot, options);
  if (r.status == phys::ShotStatus::invalid_input)
    return failed("invalid_input", where + r.message);
  BatchOutcome outcome{phys::to_string(r.status), row_message(problem, shot, r), {}};
  if (!outcome.message.empty()) outcome.message = where + outcome.message;
  outcome.results = {format_number(r.final_position.x),
                     format_number(r.final_position.y),
                     std::to_string(r.cushion_hits),
                     r.pocketed ? "1" : "0",
                     r.hit_obstacle ? "1" : "0",
                     format_number(r.duration),
                     format_number(problems::miss_distance(problem, r)),
                     problems::reaches_target(problem, r) ? "1" : "0"};
  return outcome;
}

}  // namespace

std::string check_shot_inputs(const phys::Shot& shot, const ShotNames& names) {
  if (!std::isfinite(shot.speed) || !(shot.speed > 0.0))
    return describe(names.speed, "must be positive and finite (m/s)", shot.speed);
  if (!std::isfinite(shot.aim_deg))
    return describe(names.aim, "must be finite (deg)", shot.aim_deg);
  if (!std::isfinite(shot.topspin_k))
    return describe(names.topspin, "must be finite", shot.topspin_k);
  if (!std::isfinite(shot.sidespin_k))
    return describe(names.sidespin, "must be finite", shot.sidespin_k);
  return {};
}

void write_shot_batch(const BatchInput& input, const problems::Problem& problem,
                      const phys::SimulationOptions& options, int threads, std::ostream& out) {
  phys::SimulationOptions row_options = options;
  row_options.record_path = false;  // only the outcome is written
  std::vector<BatchOutcome> outcomes(input.rows.size());
  parallel_for(input.rows.size(), thread_count(threads, input.rows.size()),
               [&](size_t i) { outcomes[i] = simulate_row(input.rows[i], problem, row_options); });

  out << kShotBatchHeader << ',' << kShotBatchResultHeader << '\n';
  write_batch_rows(input, kInputColumns, std::move(outcomes), out);
}

}  // namespace cueplan::cli
