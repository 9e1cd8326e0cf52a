// `cueplan rebound --batch FILE.csv`: many impacts from a CSV file, one output row each.
//
// Input:  header `speed,angle_deg,topspin_k,sidespin_k`, then one impact per line
//         (V0 m/s, alpha deg, k_T, k_S); blank lines are skipped.
// Output: the input columns, then rebound_speed (m/s), rebound_angle_deg, vx, vy (m/s),
//         wx, wy, wz (rad/s, cushion frame), status and a quoted message. A bad row gets
//         status parse_error or invalid_input and empty result cells; the others are
//         unaffected. Rows come out in input order, identical for any thread count.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "cueplan/physics/cushion_impact.hpp"

namespace cueplan::cli {

inline constexpr const char* kBatchInputHeader = "speed,angle_deg,topspin_k,sidespin_k";

// One line of the input file, as read.
struct BatchRow {
  int line = 0;                     // 1-based line number in the file
  std::vector<std::string> fields;  // the cells as written
};

// The input rows of a batch file, or why the whole file cannot be used.
struct BatchInput {
  std::vector<BatchRow> rows;
  std::string error;  // empty when the file was read and its header is right
};

BatchInput read_batch(const std::string& path);

// Resolves every row (from `threads` threads, 0: one per core) and writes the output
// CSV, header included, to `out`.
void write_batch(const BatchInput& input, const physics::CushionParams& params,
                 const physics::ImpactOptions& options, int threads, std::ostream& out);

}  // namespace cueplan::cli
