// `cueplan rebound --batch FILE.csv`: many impacts from a CSV file, one output row each.
//
// Input:  header `speed,angle_deg,topspin_k,sidespin_k`, then one impact per line
//         (V0 m/s, alpha deg, k_T, k_S); blank lines are skipped.
// Output: the input columns, then rebound_speed (m/s), rebound_angle_deg, vx, vy (m/s),
//         wx, wy, wz (rad/s, cushion frame), status and a quoted message. A bad row gets
//         status parse_error or invalid_input and empty result cells; the others are
//         unaffected. Rows come out in input order, identical for any thread count,
//         each chunk of rows as soon as it is resolved (batch_csv.hpp).
#pragma once

#include "batch_csv.hpp"
#include "cueplan/physics/cushion_impact.hpp"

namespace cueplan::batch {

// The header an input file starts with (read it with BatchReader).
inline constexpr const char* kBatchInputHeader = "speed,angle_deg,topspin_k,sidespin_k";

// The batch of impacts: each chunk's valid rows resolved together (from `threads`
// threads, 0: one per core); rows without a usable result (parse_error, invalid_input,
// step_limit) fail. `params` and `options` must outlive the job.
BatchJob rebound_batch_job(const physics::CushionParams& params,
                           const physics::ImpactOptions& options, int threads);

}  // namespace cueplan::batch
