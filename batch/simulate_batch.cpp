#include "simulate_batch.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <memory>

#include "cueplan/parallel.hpp"
#include "cueplan/problems/stroke_ranges.hpp"
#include "csv.hpp"
#include "cueplan/api/field_names.hpp"

namespace cueplan::batch {
using namespace cueplan::api;  // the api's types and checks, as batch streaming's own
namespace {

namespace phys = cueplan::physics;

constexpr size_t kInputColumns = 4;
constexpr size_t kResultColumns = 8;  // final_x .. reaches_target

constexpr size_t kColumnsAfterMessage = 2;  // first_contact, pocketed_balls

BatchOutcome failed(std::string status, std::string message) {
  return {std::move(status), std::move(message), std::vector<std::string>(kResultColumns),
          std::vector<std::string>(kColumnsAfterMessage)};
}

// The object balls pocketed, NAME:POCKET joined by ';'.
std::string pocketed_balls(const problems::Problem& problem, const phys::ShotResult& r) {
  std::string cell;
  for (size_t k = 1; k < r.balls.size(); ++k)
    if (r.balls[k].pocketed)
      cell += (cell.empty() ? "" : ";") + r.balls[k].name + ":" +
              problems::pocket_name(problem.scene, r.balls[k].pocket);
  return cell;
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
  if (r.rigid_limit_exceeded)
    add(fmt::format("a cushion normal speed of {:.4g} m/s exceeded the rigid-cushion limit of "
                    "{:.4g} m/s",
                    r.max_cushion_normal_speed, problem.scene.ball_and_cushion.rigid_speed_limit));
  return message;
}

BatchOutcome simulate_row(const BatchRow& row, const problems::Problem& problem,
                          const phys::CompiledScene& scene, const phys::SimulationOptions& options) {
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

  const phys::ShotResult r = phys::simulate(scene, problem.cue_ball, shot, options);
  if (r.status == phys::ShotStatus::invalid_input)
    return failed("invalid_input", where + r.message);
  BatchOutcome outcome{phys::to_string(r.status), row_message(problem, shot, r), {}};
  if (!outcome.message.empty()) outcome.message = where + outcome.message;
  outcome.results = {format_number(r.final_position.x),
                     format_number(r.final_position.y),
                     std::to_string(r.cushion_hits),
                     r.status == phys::ShotStatus::pocketed ? "1" : "0",
                     r.status == phys::ShotStatus::hit_obstacle ? "1" : "0",
                     format_number(r.duration),
                     format_number(problems::miss_distance(problem, r)),
                     problems::reaches_target(problem, r) ? "1" : "0"};
  outcome.after_message = {
      r.first_contact > 0 ? r.balls[static_cast<size_t>(r.first_contact)].name : "",
      pocketed_balls(problem, r)};
  return outcome;
}

}  // namespace

BatchJob shot_batch_job(const problems::Problem& problem, const phys::SimulationOptions& options,
                        int threads) {
  phys::SimulationOptions row_options = options;
  row_options.record_path = false;  // only the outcome is written
  auto scene = std::make_shared<const phys::CompiledScene>(problem.scene);
  BatchJob job;
  job.command = "cueplan simulate";
  job.header = std::string(kShotBatchHeader) + ',' + kShotBatchResultHeader;
  job.input_columns = kInputColumns;
  job.block_rows = 64;  // a shot takes far longer than an impact
  job.threads = threads;
  job.failed = [](const std::string& status) {
    return status != phys::to_string(phys::ShotStatus::rest) &&
           status != phys::to_string(phys::ShotStatus::pocketed) &&
           status != phys::to_string(phys::ShotStatus::hit_obstacle);
  };
  job.compute = [&problem, scene, row_options](std::span<const BatchRow> rows,
                                               std::span<BatchOutcome> outcomes) {
    for (size_t i = 0; i < rows.size(); ++i)
      outcomes[i] = simulate_row(rows[i], problem, *scene, row_options);
  };
  return job;
}

}  // namespace cueplan::batch
