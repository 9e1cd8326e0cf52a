// `cueplan simulate PROBLEM --batch FILE.csv`: many shots on one scene, one output row
// each, and the checks a shot's inputs pass in both forms of the command.
//
// Input:  header `speed,aim_deg,topspin_k,sidespin_k`, then one shot per line
//         (V m/s, aim deg from +x, k_T, k_S); blank lines are skipped.
// Output: the input columns, then final_x, final_y (m), cushion_hits, pocketed and
//         hit_obstacle (1 or 0), duration (s), miss_distance (m from the target; inf
//         unless the ball came to rest), reaches_target (1 or 0), status, a quoted
//         message, then first_contact (the object ball the cue ball struck first, or
//         empty) and pocketed_balls (the object balls pocketed, NAME:POCKET joined by ';',
//         in the order of the file's balls). A bad row gets status parse_error or
//         invalid_input and empty result cells; the others are unaffected. Rows come out
//         in input order, identical for any thread count, each chunk of rows as soon
//         as it is simulated (batch_csv.hpp).
#pragma once

#include <string>
#include <vector>

#include "batch_csv.hpp"
#include "cueplan/api/stroke.hpp"
#include "cueplan/physics/shot.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::batch {
using namespace cueplan::api;  // the api's types and checks, as batch streaming's own

// The header an input file starts with (read it with BatchReader).
inline constexpr const char* kShotBatchHeader = "speed,aim_deg,topspin_k,sidespin_k";
inline constexpr const char* kShotBatchResultHeader =
    "final_x,final_y,cushion_hits,pocketed,hit_obstacle,duration,miss_distance,reaches_target,"
    "status,message,first_contact,pocketed_balls";

// The batch of shots: chunks of rows simulated on the problem's scene (from
// `threads` threads, 0: one per core); rows without an outcome (parse_error,
// invalid_input, event_limit, impact_failed, collision_failed) fail. `problem` (and
// the table options point at) must outlive the job.
BatchJob shot_batch_job(const problems::Problem& problem,
                        const physics::SimulationOptions& options, int threads);

}  // namespace cueplan::batch
