// What `cueplan collide` computes for one cue shot at an object ball, in both of its
// forms, and `cueplan collide --batch FILE.csv`: many shots from a CSV file, one output
// row each.
//
// Input:  header `speed,cut_deg,topspin_k,sidespin_k`, then one shot per line (V m/s,
//         cut deg, k_T, k_S); blank lines are skipped.
// Output: the input columns, then for the cue ball and then the object ball the velocity
//         (m/s) and spin (rad/s) just after the collision, the velocity at which it rolls
//         again, that speed and its direction (deg from +x); then throw_deg, status and a
//         quoted message. A bad row gets status parse_error or invalid_input and empty
//         result cells; the others are unaffected. Rows come out in input order,
//         identical for any thread count, each chunk as soon as it is resolved.
#pragma once

#include <string>

#include "batch_csv.hpp"
#include "cueplan/physics/ball_collision.hpp"

namespace cueplan::batch {

inline constexpr const char* kCollideBatchHeader = "speed,cut_deg,topspin_k,sidespin_k";
inline constexpr const char* kCollideBatchResultHeader =
    "cue_vx,cue_vy,cue_wx,cue_wy,cue_wz,cue_rolling_vx,cue_rolling_vy,cue_rolling_speed,"
    "cue_rolling_angle_deg,object_vx,object_vy,object_wx,object_wy,object_wz,object_rolling_vx,"
    "object_rolling_vy,object_rolling_speed,object_rolling_angle_deg,throw_deg,status,message";

// How the caller spells a shot's inputs in its messages (flags or CSV columns).
struct CutNames {
  const char* speed;
  const char* cut;
};

// Empty when the shot is a collision the model takes (V > 0 and |cut| < 90 deg, both
// finite); otherwise one line naming the input. Spins are the caller's to check.
std::string check_cut(double speed, double cut_deg, const CutNames& names);

// One ball as the command reports it, in the table frame of the shot (x along the cue
// ball's line, z up).
struct BallReport {
  physics::Vec3 velocity;  // m/s, just after the collision
  physics::Vec3 spin;      // rad/s
  physics::Vec3 rolling;   // m/s, once it rolls again on the cloth (closed form)
  double rolling_speed = 0.0;
  double rolling_angle_deg = 0.0;  // direction of `rolling` from +x
};

struct CutOutcome {
  physics::CollisionResult result;  // in the table frame
  BallReport cue, object;
  // The object ball's direction just after the collision against the line of centres
  // (deg, counter-clockwise; a cut to the right is thrown counter-clockwise, thinner).
  double throw_deg = 0.0;
};

// The cue ball, moving along +x at `speed` (m/s) with `spin` (rad/s, table frame), cuts
// an object ball at rest by `cut_deg` (physics::cut_shot).
CutOutcome collide_cut(const physics::BallBallParams& params,
                       const physics::CollisionOptions& options, double speed, double cut_deg,
                       physics::Vec3 spin);

// A library field (mu_ball, paper_steps, ...) as its flag (--mu-ball, --steps, ...).
std::string flag_of(const physics::FieldPath& field);
// A library error in the flags' words.
std::string flag_message(const physics::ValidationError& error);

// The batch of collisions: chunks of rows resolved from `threads` threads (0: one
// per core); rows whose status is not ok fail. `params` and `options` must outlive the
// job.
BatchJob collide_batch_job(const physics::BallBallParams& params,
                           const physics::CollisionOptions& options, int threads);

}  // namespace cueplan::batch
