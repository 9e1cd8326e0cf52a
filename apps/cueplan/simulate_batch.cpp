#include "simulate_batch.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <ostream>

#include "csv.hpp"
#include "parallel.hpp"

namespace cueplan::cli {
namespace {

namespace phys = cueplan::physics;

constexpr size_t kInputColumns = 4;
constexpr size_t kResultColumns = 8;  // final_x .. reaches_target

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::string describe(const char* name, const char* rule, double value) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s %s, got %.10g", name, rule, value);
  return buf;
}

struct RowOutcome {
  std::string status;
  std::string message;
  std::vector<std::string> results;  // kResultColumns cells, empty on failure
};

RowOutcome failed(std::string status, std::string message) {
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

RowOutcome simulate_row(const ShotBatchRow& row, const problems::Problem& problem,
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
  RowOutcome outcome{phys::to_string(r.status), row_message(problem, shot, r), {}};
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

ShotBatchInput read_shot_batch(const std::string& path) {
  ShotBatchInput input;
  std::ifstream in(path);
  if (!in) {
    input.error = "--batch: cannot open " + path;
    return input;
  }
  std::string line;
  int line_number = 0;
  bool header_seen = false;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (trimmed(line).empty()) continue;
    if (!header_seen) {
      std::string header;
      for (const std::string& field : split_csv_line(line)) {
        if (!header.empty()) header += ',';
        header += trimmed(field);
      }
      if (header != kShotBatchHeader) {
        input.error = "--batch: " + path + " must start with the header '" + kShotBatchHeader +
                      "', got '" + line + "'";
        return input;
      }
      header_seen = true;
      continue;
    }
    input.rows.push_back({line_number, split_csv_line(line)});
  }
  if (in.bad())
    input.error = "--batch: error while reading " + path;
  else if (!header_seen)
    input.error = "--batch: " + path + " is empty; it needs the header '" +
                  std::string(kShotBatchHeader) + "'";
  return input;
}

void write_shot_batch(const ShotBatchInput& input, const problems::Problem& problem,
                      const phys::SimulationOptions& options, int threads, std::ostream& out) {
  phys::SimulationOptions row_options = options;
  row_options.record_path = false;  // only the outcome is written
  std::vector<RowOutcome> outcomes(input.rows.size());
  parallel_for(input.rows.size(), thread_count(threads, input.rows.size()),
               [&](size_t i) { outcomes[i] = simulate_row(input.rows[i], problem, row_options); });

  out << kShotBatchHeader << ',' << kShotBatchResultHeader << '\n';
  for (size_t i = 0; i < input.rows.size(); ++i) {
    std::vector<std::string> cells;
    for (size_t c = 0; c < kInputColumns; ++c)
      cells.push_back(c < input.rows[i].fields.size() ? trimmed(input.rows[i].fields[c]) : "");
    for (std::string& cell : outcomes[i].results) cells.push_back(std::move(cell));
    cells.push_back(outcomes[i].status);
    // The message is always quoted: it is free text.
    std::string line = csv_line(cells);
    line.pop_back();
    out << line << ',' << csv_quoted(outcomes[i].message) << '\n';
  }
}

}  // namespace cueplan::cli
