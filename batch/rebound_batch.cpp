#include "rebound_batch.hpp"

#include <algorithm>
#include <optional>
#include <span>

#include "csv.hpp"
#include "cueplan/api/rebound_inputs.hpp"

namespace cueplan::batch {
using namespace cueplan::api;  // the api's types and checks, as batch streaming's own
namespace {

constexpr size_t kInputColumns = 4;
constexpr size_t kResultColumns = 7;  // rebound_speed .. wz

BatchOutcome failed(std::string status, std::string message) {
  return {std::move(status), std::move(message), std::vector<std::string>(kResultColumns)};
}

// A row's incoming state, or why it has none.
struct ParsedRow {
  std::optional<physics::BallState> incoming;
  BatchOutcome failure;
};

ParsedRow parse_row(const BatchRow& row, const physics::CushionParams& params) {
  const std::string where = "line " + std::to_string(row.line) + ": ";
  if (row.fields.size() != kInputColumns)
    return {std::nullopt, failed("parse_error", where + "expected 4 columns, got " +
                                                    std::to_string(row.fields.size()))};
  double value[kInputColumns];
  for (size_t c = 0; c < kInputColumns; ++c) {
    const std::optional<double> number = parse_number(row.fields[c]);
    if (!number) {
      const char* names[] = {kColumnNames.speed, kColumnNames.angle, kColumnNames.topspin,
                             kColumnNames.sidespin};
      return {std::nullopt, failed("parse_error", where + names[c] + " is not a number: '" +
                                                      trimmed(row.fields[c]) + "'")};
    }
    value[c] = *number;
  }
  const auto [speed, angle_deg, topspin_k, sidespin_k] = value;
  if (std::string why = check_incidence(speed, angle_deg, topspin_k, sidespin_k, kColumnNames);
      !why.empty())
    return {std::nullopt, failed("invalid_input", where + why)};
  return {physics::incoming_state_k(speed, angle_deg, topspin_k, sidespin_k, params.radius), {}};
}

BatchOutcome outcome_of(const BatchRow& row, const physics::ImpactResult& r) {
  if (!physics::usable(r.status))
    return failed(physics::to_string(r.status), "line " + std::to_string(row.line) + ": " + r.message);
  const physics::Vec3& v = r.outgoing.velocity;
  const physics::Vec3& w = r.outgoing.spin;
  BatchOutcome outcome{physics::to_string(r.status), r.message, {}};
  for (double x : {r.rebound_speed, r.rebound_angle_deg, v.x, v.y, w.x, w.y, w.z})
    outcome.results.push_back(format_number(x));
  return outcome;
}

// Impacts per piece of work: enough for the SIMD lanes of resolve_impacts to stay
// full, small enough to spread over the threads.
constexpr size_t kChunk = 256;

}  // namespace

BatchJob rebound_batch_job(const physics::CushionParams& params,
                           const physics::ImpactOptions& options, int threads) {
  BatchJob job;
  job.command = "cueplan rebound";
  job.header = std::string(kBatchInputHeader) +
               ",rebound_speed,rebound_angle_deg,vx,vy,wx,wy,wz,status,message";
  job.input_columns = kInputColumns;
  job.block_rows = 4 * kChunk;
  job.threads = threads;
  job.failed = [](const std::string& status) {
    return status != physics::to_string(physics::ImpactStatus::ok) &&
           status != physics::to_string(physics::ImpactStatus::rigid_limit_exceeded);
  };
  // A chunk's rows parsed in order; the valid ones resolved together, kChunk at a time
  // (resolve_impacts gives each impact what resolve_impact would: the output does not
  // depend on the thread count or the chunk size).
  job.compute = [&params, &options](std::span<const BatchRow> rows,
                                    std::span<BatchOutcome> outcomes) {
    std::vector<physics::BallState> incoming;
    std::vector<size_t> row_of;
    for (size_t i = 0; i < rows.size(); ++i) {
      ParsedRow parsed = parse_row(rows[i], params);
      if (parsed.incoming) {
        incoming.push_back(*parsed.incoming);
        row_of.push_back(i);
      } else {
        outcomes[i] = std::move(parsed.failure);
      }
    }
    std::vector<physics::ImpactResult> results(incoming.size());
    for (size_t begin = 0; begin < incoming.size(); begin += kChunk) {
      const size_t count = std::min(kChunk, incoming.size() - begin);
      physics::resolve_impacts(params, std::span(incoming).subspan(begin, count),
                               std::span(results).subspan(begin, count), options);
    }
    for (size_t j = 0; j < results.size(); ++j)
      outcomes[row_of[j]] = outcome_of(rows[row_of[j]], results[j]);
  };
  return job;
}

}  // namespace cueplan::batch
