#include "collide_batch.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

#include "csv.hpp"
#include "cueplan/api/field_names.hpp"

namespace cueplan::batch {
using namespace cueplan::api;  // the api's types and checks, as batch streaming's own
namespace {

namespace phys = cueplan::physics;

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr size_t kInputColumns = 4;
constexpr size_t kResultColumns = 19;  // cue_vx .. throw_deg

// Library field names and the flags that set them.
// BallBallParams' and CollisionOptions' fields and the flags that set them.
const FieldName kCollideFlags[] = {
    {{"mass"}, "--mass"},
    {{"radius"}, "--radius"},
    {{"mu_ball"}, "--mu-ball"},
    {{"restitution"}, "--ball-restitution"},
    {{"mu_table"}, "--mu-table"},
    {{"model"}, "--model"},
    {{"friction"}, "--ball-friction"},
    {{"method"}, "--method"},
    {{"tolerance"}, "--tolerance"},
    {{"paper_steps"}, "--steps"},
};

double direction_deg(phys::Vec3 v) { return std::atan2(v.y, v.x) / kDegree; }

// An angle in (-180, 180].
double wrapped(double deg) {
  while (deg > 180.0) deg -= 360.0;
  while (deg <= -180.0) deg += 360.0;
  return deg;
}

BallReport report_of(const phys::BallState& state, double radius) {
  BallReport r;
  r.velocity = state.velocity;
  r.spin = state.spin;
  r.rolling = phys::rolling_velocity(state, radius);
  r.rolling_speed = std::hypot(r.rolling.x, r.rolling.y);
  r.rolling_angle_deg = direction_deg(r.rolling);
  return r;
}

BatchOutcome failed(std::string status, std::string message) {
  return {std::move(status), std::move(message), std::vector<std::string>(kResultColumns)};
}

constexpr CutNames kColumnNames = {"speed", "cut_deg"};

BatchOutcome solve_row(const BatchRow& row, const phys::BallBallParams& params,
                       const phys::CollisionOptions& options) {
  const std::string where = fmt::format("line {}: ", row.line);
  if (row.fields.size() != kInputColumns)
    return failed("parse_error", fmt::format("{}expected {} columns, got {}", where, kInputColumns,
                                             row.fields.size()));
  constexpr const char* kNames[] = {"speed", "cut_deg", "topspin_k", "sidespin_k"};
  double value[kInputColumns];
  for (size_t c = 0; c < kInputColumns; ++c) {
    const std::optional<double> number = parse_number(row.fields[c]);
    if (!number)
      return failed("parse_error", fmt::format("{}{} is not a number: '{}'", where, kNames[c],
                                               trimmed(row.fields[c])));
    value[c] = *number;
  }
  const auto [speed, cut_deg, topspin_k, sidespin_k] = value;
  std::string why = check_cut(speed, cut_deg, kColumnNames);
  for (size_t c : {2, 3})
    if (why.empty() && !std::isfinite(value[c]))
      why = fmt::format("{} must be finite, got {}", kNames[c], value[c]);
  if (!why.empty()) return failed("invalid_input", where + why);
  const double unit = speed / params.radius;  // rad/s per unit of k
  const phys::Vec3 spin = {0.0, topspin_k * unit, sidespin_k * unit};

  const CutOutcome o = collide_cut(params, options, speed, cut_deg, spin);
  if (!phys::usable(o.result.status))
    return failed(phys::to_string(o.result.status), where + o.result.message);
  BatchOutcome outcome{phys::to_string(o.result.status), o.result.message, {}};
  for (const BallReport* b : {&o.cue, &o.object})
    for (double x : {b->velocity.x, b->velocity.y, b->spin.x, b->spin.y, b->spin.z, b->rolling.x,
                     b->rolling.y, b->rolling_speed, b->rolling_angle_deg})
      outcome.results.push_back(format_number(x));
  outcome.results.push_back(format_number(o.throw_deg));
  return outcome;
}

}  // namespace

std::string check_cut(double speed, double cut_deg, const CutNames& names) {
  if (!std::isfinite(speed) || !(speed > 0.0))
    return fmt::format("{} must be positive and finite (m/s), got {:.10g}", names.speed, speed);
  if (!std::isfinite(cut_deg) || !(std::abs(cut_deg) < 90.0))
    return fmt::format(
        "{} must lie in (-90, 90) degrees: at 90 the cue ball only grazes the object ball, got "
        "{:.10g}",
        names.cut, cut_deg);
  return {};
}

CutOutcome collide_cut(const phys::BallBallParams& params, const phys::CollisionOptions& options,
                       double speed, double cut_deg, phys::Vec3 spin) {
  const phys::CutShot shot = phys::cut_shot(speed, cut_deg, spin, params.radius);
  CutOutcome o;
  o.result = phys::resolve_table_collision(params, shot.cue_centre, shot.cue_ball,
                                           shot.object_centre, shot.object_ball, options);
  if (o.result.status == phys::CollisionStatus::invalid_input) return o;
  o.cue = report_of(o.result.ball_i, params.radius);
  o.object = report_of(o.result.ball_j, params.radius);
  o.throw_deg = wrapped(direction_deg(o.result.ball_j.velocity) - (-cut_deg));
  return o;
}

std::string flag_message(const phys::ValidationError& error) {
  return message_in(error, kCollideFlags);
}

BatchJob collide_batch_job(const phys::BallBallParams& params,
                           const phys::CollisionOptions& options, int threads) {
  BatchJob job;
  job.command = "cueplan collide";
  job.header = std::string(kCollideBatchHeader) + ',' + kCollideBatchResultHeader;
  job.input_columns = kInputColumns;
  job.block_rows = 1024;
  job.threads = threads;
  job.failed = [](const std::string& status) {
    return status != phys::to_string(phys::CollisionStatus::ok);
  };
  job.compute = [&params, &options](std::span<const BatchRow> rows,
                                    std::span<BatchOutcome> outcomes) {
    for (size_t i = 0; i < rows.size(); ++i) outcomes[i] = solve_row(rows[i], params, options);
  };
  return job;
}

}  // namespace cueplan::batch
