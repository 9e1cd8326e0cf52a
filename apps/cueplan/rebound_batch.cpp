#include "rebound_batch.hpp"

#include <optional>
#include <ostream>

#include "cueplan/physics/parallel.hpp"
#include "csv.hpp"
#include "rebound_inputs.hpp"

namespace cueplan::cli {
namespace {

constexpr size_t kInputColumns = 4;
constexpr size_t kResultColumns = 7;  // rebound_speed .. wz

BatchOutcome failed(std::string status, std::string message) {
  return {std::move(status), std::move(message), std::vector<std::string>(kResultColumns)};
}

BatchOutcome solve_row(const BatchRow& row, const physics::CushionParams& params,
                       const physics::ImpactOptions& options) {
  const std::string where = "line " + std::to_string(row.line) + ": ";
  if (row.fields.size() != kInputColumns)
    return failed("parse_error",
                  where + "expected 4 columns, got " + std::to_string(row.fields.size()));
  double value[kInputColumns];
  for (size_t c = 0; c < kInputColumns; ++c) {
    const std::optional<double> number = parse_number(row.fields[c]);
    if (!number) {
      const char* names[] = {kColumnNames.speed, kColumnNames.angle, kColumnNames.topspin,
                             kColumnNames.sidespin};
      return failed("parse_error",
                    where + names[c] + " is not a number: '" + trimmed(row.fields[c]) + "'");
    }
    value[c] = *number;
  }
  const auto [speed, angle_deg, topspin_k, sidespin_k] = value;
  if (std::string why = check_incidence(speed, angle_deg, topspin_k, sidespin_k, kColumnNames);
      !why.empty())
    return failed("invalid_input", where + why);

  const physics::BallState incoming =
      physics::incoming_state_k(speed, angle_deg, topspin_k, sidespin_k, params.radius);
  const physics::ImpactResult r = physics::resolve_impact(params, incoming, options);
  if (!physics::usable(r.status)) return failed(physics::to_string(r.status), where + r.message);
  const physics::Vec3& v = r.outgoing.velocity;
  const physics::Vec3& w = r.outgoing.spin;
  BatchOutcome outcome{physics::to_string(r.status), r.message, {}};
  for (double x : {r.rebound_speed, r.rebound_angle_deg, v.x, v.y, w.x, w.y, w.z})
    outcome.results.push_back(format_number(x));
  return outcome;
}

}  // namespace

void write_batch(const BatchInput& input, const physics::CushionParams& params,
                 const physics::ImpactOptions& options, int threads, std::ostream& out) {
  std::vector<BatchOutcome> outcomes(input.rows.size());
  physics::parallel_for(input.rows.size(), physics::thread_count(threads, input.rows.size()),
                        [&](size_t i, unsigned) { outcomes[i] = solve_row(input.rows[i], params, options); });

  out << kBatchInputHeader << ",rebound_speed,rebound_angle_deg,vx,vy,wx,wy,wz,status,message\n";
  write_batch_rows(input, kInputColumns, std::move(outcomes), out);
}

}  // namespace cueplan::cli
