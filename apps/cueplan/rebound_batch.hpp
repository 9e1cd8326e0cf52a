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

#include "batch_csv.hpp"
#include "cueplan/physics/cushion_impact.hpp"

namespace cueplan::cli {

// The header an input file starts with (read it with read_batch_csv).
inline constexpr const char* kBatchInputHeader = "speed,angle_deg,topspin_k,sidespin_k";

// Resolves every row (from `threads` threads, 0: one per core) and writes the output
// CSV, header included, to `out`.
void write_batch(const BatchInput& input, const physics::CushionParams& params,
                 const physics::ImpactOptions& options, int threads, std::ostream& out);

}  // namespace cueplan::cli
