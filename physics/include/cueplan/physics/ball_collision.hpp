// Ball-ball collision on the cloth, as fixed by shared/PHYSICS.md "Ball-ball collision":
// the impulse-domain model of Mathavan, Jackson & Parkin (2014), with friction between
// the balls and between the ball pressed into the cloth and the cloth, and its
// closed-form alternative (one impulse, Alciatore's throw model). Two balls' velocity
// and spin and the line of centres in; both balls out, with a status.
//
// Everything here is a pure function of its arguments: no globals, no hidden state,
// safe to call from many threads at once.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "cueplan/physics/cushion_impact.hpp"
#include "cueplan/physics/validation.hpp"
#include "cueplan/physics/vec3.hpp"

namespace cueplan::physics {

enum class BallModel {
  mathavan_2014,         // friction between the balls and at the cloth over the normal impulse
  frictional_inelastic,  // one impulse, no cloth friction during the contact (closed form)
};

// Ball-ball friction of the closed form.
enum class BallFriction {
  constant,         // mu_ball
  speed_dependent,  // Alciatore's fit to measured throw: 0.00995 + 0.108 exp(-1.088 |slip|)
};

// How the mathavan_2014 model is resolved.
enum class CollisionMethod {
  exact,          // Taylor series in a regularised variable, landing on its events
  paper,          // the same equations in N fixed steps of the normal impulse
  extrapolation,  // adaptive extrapolation integrator in the normal impulse: a second,
                  // independent exact method (the `exact` before 2026-12-02)
};

const char* to_string(BallModel model);
const char* to_string(BallFriction friction);
const char* to_string(CollisionMethod method);
// Parse the names to_string gives; false (leaving *out alone) for anything else.
bool parse_ball_model(const std::string& name, BallModel* out);
bool parse_ball_friction(const std::string& name, BallFriction* out);
bool parse_collision_method(const std::string& name, CollisionMethod* out);

// Fixed parameters of a collision between two equal balls. SI units; defaults are the
// paper's (PHYSICS.md), with the cloth friction of the scene.
struct BallBallParams {
  double mass = 0.1406;       // kg, each ball
  double radius = 0.02625;    // m, each ball
  double mu_ball = 0.05;      // ball-ball sliding friction mu_b
  double restitution = 0.89;  // e_b, energetic coefficient of restitution, (0, 1]
  double mu_table = 0.212;    // ball-cloth sliding friction mu_s (the scene's mu_slide)
  BallModel model = BallModel::mathavan_2014;
  BallFriction friction = BallFriction::constant;  // for frictional_inelastic

  // Empty when usable; otherwise the broken rule, naming a member above (mu_ball, ...).
  // mathavan_2014 needs mu_ball mu_table < 2/7: then a cloth slip cannot stick during the
  // collision (it passes through zero, as the model assumes).
  Validation validate() const;
};

struct CollisionOptions {
  CollisionMethod method = CollisionMethod::exact;
  int paper_steps = 5000;    // paper: N, with dP = (1 + e_b) M a0 / (2 N)
  double tolerance = 1e-12;  // exact, extrapolation: local error per step, relative to the
                             // speed scale max(|v_i|, |v_j|); in [1e-15, 1e-2]
  int max_steps = 10000;     // exact, extrapolation: bound on the steps, >= 1

  // Empty when usable; otherwise the broken rule, naming a member above.
  Validation validate() const;
};

enum class CollisionStatus {
  ok,
  invalid_input,  // nothing solved; error names the field
  step_limit,     // the integrator's work bound was reached; result unusable
};
const char* to_string(CollisionStatus status);
inline bool usable(CollisionStatus status) { return status == CollisionStatus::ok; }

// Where the friction changes during a mathavan_2014 collision (exact and extrapolation).
enum class CollisionEvent : unsigned char {
  balls_geared,          // the slip between the balls reached zero: no friction from here on
  cloth_i_through_zero,  // ball i, pressed into the cloth, had its cloth slip pass zero
  cloth_j_through_zero,  // the same for ball j
};
const char* to_string(CollisionEvent event);

struct CollisionTransition {
  CollisionEvent event = CollisionEvent::balls_geared;
  double impulse = 0.0;  // N s, normal impulse P at the event
};

constexpr int kMaxCollisionTransitions = 8;

struct CollisionResult {
  CollisionStatus status = CollisionStatus::invalid_input;
  std::string message;  // why, when the status is not ok
  // With invalid_input: the broken rule. Fields are named as the members of
  // BallBallParams ({"mu_ball"}), CollisionOptions ({"tolerance"}) and the arguments
  // ({"ball_i", "velocity", "x"}, {"centre_j"}).
  std::optional<ValidationError> error;
  BallModel model = BallModel::mathavan_2014;
  CollisionMethod method_used = CollisionMethod::exact;  // for mathavan_2014

  BallState ball_i;  // outgoing, in the frame of the input
  BallState ball_j;
  double impulse_compression = 0.0;  // N s, P when the normal approach stops (a = 0)
  double impulse_total = 0.0;        // N s, P when W = (1 - e_b^2) W_c
  double work_compression = 0.0;     // J, W_c = integral of a dP up to a = 0
  double work_total = 0.0;           // J, W at the end of the collision

  bool balls_slipping_at_start = true;    // b != 0 at first contact
  bool cloth_i_slipping_at_start = true;  // ball i's cloth slip c_i != 0 at first contact
  bool cloth_j_slipping_at_start = true;
  std::array<CollisionTransition, kMaxCollisionTransitions> transitions{};
  int transition_count = 0;

  int rhs_evaluations = 0;  // right-hand side calls (paper: steps): the work done
};

// Resolves one collision. Both states are in the collision frame (t, n, z) of
// PHYSICS.md, as the Vec3 components (x, y, z) = (t, n, z): n is the horizontal unit
// vector from ball i's centre to ball j's, t = n x z. Velocities have z = 0 and the balls
// must approach: ball_i.velocity.y > ball_j.velocity.y. Outgoing states in the same
// frame. Never throws for bad numbers: invalid input comes back as invalid_input.
CollisionResult resolve_collision(const BallBallParams& params, const BallState& ball_i,
                                  const BallState& ball_j, const CollisionOptions& options = {});

// The same in the table frame (x, y, z up): centres in m (z ignored; only the direction
// from centre_i to centre_j counts, so they need not be exactly 2R apart, but must
// differ), states and outgoing states in the table frame.
CollisionResult resolve_table_collision(const BallBallParams& params, Vec3 centre_i,
                                        const BallState& ball_i, Vec3 centre_j,
                                        const BallState& ball_j,
                                        const CollisionOptions& options = {});

// The velocity at which a ball sliding on the cloth starts to roll, nothing else
// intervening (PHYSICS.md, "Ball on the cloth"): friction acts along the contact-point
// velocity u = (v_x - R w_y, v_y + R w_x), which keeps its direction and shrinks at
// (7/2) mu_s g while v changes by -mu_s g along it, so v - (2/7) u stays constant and
// the ball rolls at v_roll = v - (2/7) u, whatever mu_s. Any frame with z up.
Vec3 rolling_velocity(const BallState& state, double radius);

// A cue shot at an object ball at rest, in the table frame: the cue ball, centred at the
// origin, moves along +x at `speed` (m/s) with spin `spin` (rad/s); the object ball's
// centre lies at 2R (cos c, -sin c) for the cut angle c = cut_deg (0: full ball; c > 0
// cuts it to the right; |c| < 90 for a contact).
struct CutShot {
  Vec3 cue_centre, object_centre;  // m
  BallState cue_ball, object_ball;
};
CutShot cut_shot(double speed, double cut_deg, Vec3 spin, double radius);

}  // namespace cueplan::physics
