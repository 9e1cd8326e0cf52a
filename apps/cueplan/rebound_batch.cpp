#include "rebound_batch.hpp"

#include <fstream>
#include <optional>
#include <ostream>

#include "csv.hpp"
#include "parallel.hpp"
#include "rebound_inputs.hpp"

namespace cueplan::cli {
namespace {

constexpr size_t kInputColumns = 4;
constexpr size_t kResultColumns = 7;  // rebound_speed .. wz

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

struct RowOutcome {
  std::string status;
  std::string message;
  std::vector<std::string> results;  // kResultColumns cells, empty on failure
};

RowOutcome failed(std::string status, std::string message) {
  return {std::move(status), std::move(message), std::vector<std::string>(kResultColumns)};
}

RowOutcome solve_row(const BatchRow& row, const physics::CushionParams& params,
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
  RowOutcome outcome{physics::to_string(r.status), r.message, {}};
  for (double x : {r.rebound_speed, r.rebound_angle_deg, v.x, v.y, w.x, w.y, w.z})
    outcome.results.push_back(format_number(x));
  return outcome;
}

}  // namespace

BatchInput read_batch(const std::string& path) {
  BatchInput input;
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
      if (header != kBatchInputHeader) {
        input.error = "--batch: " + path + " must start with the header '" + kBatchInputHeader +
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
                  std::string(kBatchInputHeader) + "'";
  return input;
}

void write_batch(const BatchInput& input, const physics::CushionParams& params,
                 const physics::ImpactOptions& options, int threads, std::ostream& out) {
  std::vector<RowOutcome> outcomes(input.rows.size());
  parallel_for(input.rows.size(), thread_count(threads, input.rows.size()),
               [&](size_t i) { outcomes[i] = solve_row(input.rows[i], params, options); });

  out << kBatchInputHeader << ",rebound_speed,rebound_angle_deg,vx,vy,wx,wy,wz,status,message\n";
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
