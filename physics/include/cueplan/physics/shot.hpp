// From a cue strike to every ball at rest, event by event (shared/PHYSICS.md, "Ball on
// the cloth" and "Several balls on the table").
//
// Between events each ball slides or rolls on the cloth with constant acceleration, so
// its position is a quadratic in time and every event - slide to roll, sidespin stop,
// stop, cushion contact, pocket capture, contact with an obstacle ball, contact with
// another ball - is a root of a polynomial, solved rather than stepped to. At a cushion
// contact the state is turned into that cushion's frame, resolved by the impact library
// and turned back; a contact of two balls is resolved by the ball-ball collision library
// (ball_collision.hpp) along their line of centres.
//
// The object balls lie at rest until struck. An object ball that drops into a pocket
// leaves the table and the shot goes on; so does the cue ball's: a pocketed cue ball
// ends its own motion, not the simulation of the others, which move on to rest (the
// result reports the cue ball pocketed). A contact of any ball with an obstacle ends
// the shot.
//
// Pure functions of their arguments: no globals, safe from many threads.
#pragma once

#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cueplan/physics/ball_collision.hpp"
#include "cueplan/physics/cushion_impact.hpp"
#include "cueplan/physics/validation.hpp"

namespace cueplan::physics {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

// Cloth friction and gravity (SI; defaults from PHYSICS.md). mu_slide is the same
// ball-cloth friction as the impact model's CushionParams::mu_table; problem files set
// both from one field, and only tests of limits (a frictionless impact on real cloth)
// set them apart.
struct ClothParams {
  double mu_slide = 0.212;  // ball-cloth sliding friction
  double mu_roll = 0.01;    // rolling resistance
  double mu_spin = 0.0117;  // spinning (sidespin) friction (PHYSICS.md: 10.9 rad/s^2 for snooker)
  double gravity = 9.81;    // m/s^2
};

// The cue, as the squirt model sees it (PHYSICS.md, "Squirt and swerve"): Alciatore's
// TP A-31 treats the cue's tip end as a free mass `end_mass` during the ~1 ms contact, so
// a tip offset to the side pushes the ball off the cue's line by an angle that grows with
// end_mass / ball mass. Presets in docs/squirt.md.
struct CueParams {
  double end_mass = 0.012;  // kg, effective end mass (the snooker cue's; see snooker_cue())

  // Empty when usable; otherwise the broken rule, {"end_mass"}.
  Validation validate() const;
};
// A snooker cue (ash shaft, brass ferrule, 9.5 mm tip): end mass 12 g, squirt 2.3 deg at
// a tip offset of R/4 with the snooker ball.
CueParams snooker_cue();
// A standard maple pool shaft: end mass 10 g, squirt 1.7 deg at R/4 with the pool ball.
CueParams pool_cue();

// The squirt angle (deg) of a stroke with sidespin k_S (tip offset b = k_S R / 2.5), by
// TP A-31: tan s = (5/2)(b/R) sqrt(1 - (b/R)^2) / (1 + m_ball/m_end + (5/2)(1 - (b/R)^2)).
// Signed as a turn seen from above: positive (counter-clockwise, to the left of the cue's
// line) for right side (k_S > 0), negative for left side, 0 at centre. |b| is clamped to R.
double squirt_angle_deg(const CueParams& cue, double ball_mass, double radius, double sidespin_k);

// The end mass (kg) whose squirt at a tip offset of R/4 is `squirt_deg` with a ball of
// `ball_mass`: squirt_angle_deg inverted. Empty when squirt_deg <= 0 or when no cue
// squirts that much (even a rigid tip, end mass -> infinity, squirts less).
std::optional<double> end_mass_for_squirt(double ball_mass, double squirt_deg);

// Capture radius of a standard pocket (m): a ball whose centre comes this close to the
// pocket's point drops.
inline constexpr double kDefaultPocketRadius = 0.045;

// The shape of a jawed pocket (PHYSICS.md, "Jawed pockets"); metres and degrees.
//
// The mouth is measured between the two UNROUNDED nose corners: the points where each
// cushion's nose line meets its facing line (as WPA/BCA measure it, "from tip to tip of
// the opposing cushion noses where direction changes into the pocket"). The rounding of
// radius point_radius is tangent to both lines, so the rounded noses stand slightly
// back from those corners. Each facing leaves its corner at wall_angle_deg to the
// pocket's centre line, turned toward the centre line: the facings converge into the
// pocket (the throat is narrower than the mouth; the pocket opens outward toward the
// table), as on WPA tables, whose "pocket angle" of 142 deg (corner) between the cushion
// nose and the facing is a wall angle of 45 - 38 = 7 deg, and 104 deg (side) one of
// 90 - 76 = 14 deg.
struct PocketShape {
  double mouth = 0.0;           // m, between the unrounded nose corners
  double wall_angle_deg = 0.0;  // deg, each facing to the centre line (converging)
  double shelf = 0.0;           // m, from the mouth line to the hole's edge, on the centre line
  double hole_radius = 0.0;     // m
  double point_radius = 0.0;    // m, rounding of each nose

  // Empty when a ball of `ball_radius` can enter and drop; otherwise the first broken
  // rule, fields named as these members: a mouth narrower than a ball (2R), a negative
  // shelf, a wall angle outside [0, 90), facings that cross before the hole, a negative
  // point radius, a hole too small to close the channel between the facings.
  Validation validate(double ball_radius) const;
};

// A jawed pocket's geometry in the table frame, derived from its shape by
// jawed_pockets(). "Left" and "right" are as seen from the table looking into the
// pocket along `inward`. The parts a ball can strike are numbered
// 0 left point, 1 left facing, 2 right facing, 3 right point (ShotEvent::cushion of a
// jaw event).
struct PocketJaws {
  PocketShape shape;
  Vec2 inward;             // unit, the centre line's direction into the pocket
  Vec2 mouth_centre;       // m, middle of the mouth line
  Vec2 corner[2];          // m, the unrounded nose corners: [0] left, [1] right
  Vec2 point_centre[2];    // m, centres of the rounded noses
  Vec2 facing_start[2];    // m, where each facing leaves its point's rounding
  Vec2 facing_dir[2];      // unit, along each facing into the pocket
  double facing_length[2] = {0.0, 0.0};  // m, from facing_start to the hole's centre depth
  Vec2 hole_centre;        // m
  int cushion[2] = {-1, -1};      // the cushion (ShotEvent::cushion numbering) each point ends
  Vec2 nose_tangent[2];    // m, where each cushion's straight nose ends at the point's rounding
};

// A pocket. Without jaws it is a capture circle (the `standard` pockets): a ball whose
// centre enters the circle (centre, radius) is pocketed. With jaws, a ball is pocketed
// when its centre enters the hole and meets the points and facings before that;
// `centre` is then the middle of the mouth line (where the planner aims an object ball)
// and `radius` the effective capture radius the planner's heuristics use: half the
// mouth, so that the circle spans the mouth from corner to corner (generous by about a
// ball's radius, the right side to err on for screens that rule pots out).
struct Pocket {
  Vec2 centre;          // m, table frame
  double radius = 0.0;  // m, capture circle (no jaws) or effective capture radius (jaws)
  std::optional<PocketJaws> jaws;
};

// An object ball, at rest where the shot starts; the same radius and mass as the cue ball.
struct ObjectBall {
  std::string name;  // unique on the table, not empty, not "cue" (the cue ball's name)
  Vec2 position;     // m, table frame
};

// The name ShotResult::balls gives the cue ball.
inline constexpr const char* kCueBallName = "cue";

// How two balls collide (PHYSICS.md, "Ball-ball collision"): the scene's part of
// BallBallParams. Mass, radius and the cloth friction are the scene's own
// (ball_and_cushion.mass, .radius, cloth.mu_slide), so they cannot disagree.
struct BallContact {
  double mu_ball = 0.05;      // ball-ball sliding friction mu_b
  double restitution = 0.89;  // e_b, in (0, 1]
  BallModel model = BallModel::mathavan_2014;
  BallFriction friction = BallFriction::constant;  // for frictional_inelastic
};

// The table and everything on it when the shot starts.
struct Scene {
  double length = 3.569;  // m between the cushion noses x = 0 and x = length
  double width = 1.778;   // m between y = 0 and y = width
  CushionParams ball_and_cushion;  // ball mass and radius, cushion height, mu_w, mu_s, e
  ClothParams cloth;
  std::vector<Pocket> pockets;
  std::vector<Vec2> obstacles;    // balls nothing may touch (same radius): a contact ends the shot
  std::vector<ObjectBall> balls;  // object balls the shot may strike
  BallContact ball_contact;
  CueParams cue;  // the cue's end mass: how far side squirts the cue ball

  double radius() const { return ball_and_cushion.radius; }
  // Distance from a cushion nose line at which the ball's centre meets it: R cos(theta).
  double contact_offset() const;
  // The collision parameters of two of this scene's balls.
  BallBallParams ball_ball_params() const;
  // Empty when usable; otherwise the first broken rule, fields named as the members
  // here: {"length"}, {"cloth", "mu_roll"}, {"ball_and_cushion", "mass"},
  // {"pockets", 2, "radius"}, {"obstacles", 1}, {"balls", "red"} (an object ball by its
  // name; {"balls", 2, "name"} for a bad name), {"ball_contact", "mu_ball"}. The
  // collision parameters' rules (BallBallParams::validate) come under "ball_contact",
  // except those on the mass, radius and cloth friction, which name the scene's fields.
  Validation validate() const;
  // Where a ball may rest: inside the cushions, not in a pocket, not on an obstacle or an
  // object ball (touching is fine). Empty when the position is fine; otherwise why not,
  // the field named `what` (a pocket or ball it meets is the error's `other`, named as in
  // validate()).
  Validation check_position(Vec2 position, const FieldPath& what) const;
  // Where a ball may come to rest after a shot: the same, but the object balls, which
  // the shot may have moved, do not count.
  Validation check_rest_position(Vec2 position, const FieldPath& what) const;
};

// Snooker table with the six standard pockets (capture radius kDefaultPocketRadius), in
// the order bottom left, bottom middle, bottom right, top left, top middle, top right.
Scene snooker_scene();
// The six standard pockets of a table: the corners and the middles of the long cushions
// y = 0 and y = width, in snooker_scene()'s order.
std::vector<Pocket> standard_pockets(double length, double width, double radius);
// The six jawed pockets of a table, in standard_pockets' order: the corners on the
// corner's bisector, the middles on the long cushions.
std::vector<Pocket> jawed_pockets(double length, double width, const PocketShape& corner,
                                  const PocketShape& middle);
// The corner and middle shapes of a named preset: "snooker" (WPBSA template) or "pool"
// (WPA specification); none for any other name (docs/pockets.md cites the numbers).
struct PocketPreset {
  PocketShape corner;
  PocketShape middle;
};
std::optional<PocketPreset> pocket_preset(std::string_view name);

namespace detail {
struct SceneGeometry;  // the simulator's own view of the scene's cushions and jaws
}

// A scene checked once, for the simulations that follow (in the spirit of MuJoCo's
// mjModel): simulate() takes it and checks nothing about the scene again.
class CompiledScene {
 public:
  // Checks `scene`; error() says what is wrong with it, if anything.
  explicit CompiledScene(Scene scene);

  const Scene& scene() const { return scene_; }
  // The broken rule when the scene is unusable (Scene::validate()'s); empty otherwise.
  const Validation& error() const { return error_; }
  bool ok() const { return !error_.has_value(); }
  // scene().ball_ball_params(), built once.
  const BallBallParams& ball_ball_params() const { return ball_ball_; }
  // The cushion lines, pocket mouths and jaws as the simulator meets them, built once
  // (empty for an unusable scene).
  const detail::SceneGeometry& geometry() const { return *geometry_; }

 private:
  Scene scene_;
  Validation error_;
  BallBallParams ball_ball_;
  std::shared_ptr<const detail::SceneGeometry> geometry_;  // immutable: copies share it
};

// A centred-impulse cue whose tip is d from the ball's centre gives spin k = (5/2) d / R
// (PHYSICS.md, "Cue strike"); the miscue limit d <= R/2 bounds sqrt(k_T^2 + k_S^2) by 1.25.
inline constexpr double kSpinPerTipOffset = 2.5;
inline constexpr double kMiscueSpin = 1.25;

// A stroke: speed V (m/s), the cue's direction aim phi (deg from +x), topspin k_T and
// sidespin k_S in the paper's dimensionless form (PHYSICS.md, "Cue strike"), and the
// cue's elevation above the horizontal. With side the cue ball leaves off the cue's line
// by the scene's squirt angle (squirt_angle_deg); with side and elevation it also swerves.
struct Shot {
  double speed = 1.0;
  double aim_deg = 0.0;
  double topspin_k = 0.0;
  double sidespin_k = 0.0;
  double elevation_deg = 0.0;  // 0 <= elevation < 90; 0: a level cue

  // Empty when it can be played (speed > 0, everything finite, 0 <= elevation_deg < 90);
  // otherwise the first broken rule, fields named as these members.
  Validation validate() const;
};

enum class EventType {
  strike,         // t = 0, the cue ball
  slide_to_roll,  // the contact point stops slipping on the cloth
  spin_stop,      // sidespin decays to zero
  cushion,        // cushion contact resolved by the impact model
  pocket,         // the centre entered a pocket's capture circle: the ball leaves the table
  obstacle,       // contact with an obstacle ball: the shot ends
  rest,           // the ball stops
  ball_contact,   // contact with another ball, resolved by the ball-ball collision model
  jaw,            // contact with a jawed pocket's point or facing, resolved by the cushion
                  // model in the contact's frame: index = the pocket, cushion = the part
                  // (0 left point, 1 left facing, 2 right facing, 3 right point, seen
                  // from the table); not counted in cushion_hits
};
const char* to_string(EventType type);

enum class Motion { sliding, rolling, resting };
const char* to_string(Motion motion);

// One event of one ball; position, velocity and spin are that ball's.
struct ShotEvent {
  EventType type = EventType::strike;
  double time = 0.0;  // s since the strike
  Vec2 position;      // m
  Vec2 velocity;      // m/s just after the event
  Vec3 spin;          // rad/s just after the event
  int cushion = -1;   // 0: y = 0, 1: x = length, 2: y = width, 3: x = 0 (cushion events);
                      // jaw events: the part of the pocket (see EventType::jaw)
  int index = -1;     // pocket or obstacle index (pocket, jaw and obstacle events)
  double normal_speed = 0.0;  // m/s into the cushion (cushion events); along the line
                              // of centres, how fast the balls approached (ball contacts)
  int ball = 0;       // whose event: index into ShotResult::balls (0: the cue ball)
  int other = -1;     // ball contacts: the other ball, index into ShotResult::balls
  double impulse = 0.0;  // N s, ball contacts: the collision's normal impulse
};

// One piece of path between events: p(t) = p0 + v0 (t - t0) + a (t - t0)^2 / 2.
struct PathSegment {
  double t0 = 0.0, t1 = 0.0;
  Vec2 p0, v0, accel;
  Motion motion = Motion::sliding;
  Vec2 at(double t) const;
};

// How the shot ended, said of the cue ball (the object balls' outcomes are in
// ShotResult::balls).
enum class ShotStatus {
  rest,            // the cue ball came to rest on the table (and so did every other ball)
  pocketed,        // the cue ball entered a pocket (the others moved on to rest)
  hit_obstacle,    // a ball (the cue ball or an object ball) touched an obstacle ball
  invalid_input,   // nothing simulated; message names the field
  event_limit,     // more events than SimulationOptions::max_events
  impact_failed,   // the impact model could not resolve a cushion contact, or friction
                   // presses a ball into a cushion it touches with no approach speed
                   // (sliding along a cushion is not modelled)
  collision_failed,  // the ball-ball collision model could not resolve a contact
  time_limit,      // SimulationOptions::max_time reached with a ball still moving: every
                   // ball's path and final_position stop at that time
};
const char* to_string(ShotStatus status);

struct SimulationOptions {
  // Impact method for cushion contacts of the mathavan_2010 model (the scene's
  // ball_and_cushion.model). With a table, the table answers where its measured error
  // meets `impact_accuracy`, and the exact method elsewhere. A han_2005 scene's impacts
  // are one closed form each: this, the accuracy and the table play no part in them. Ball-ball
  // contacts of the mathavan_2014 model are always resolved by its exact method, at a
  // tolerance that meets `impact_accuracy` as well.
  ImpactMethod impact_method = ImpactMethod::exact;
  double impact_accuracy = 1e-9;        // relative error wanted from each impact
  const ImpactTable* table = nullptr;   // used when impact_method is table
  // Bound on the events of all balls together: checked before each event, so a shot
  // stopped by it (event_limit) holds max_events + 1 events, or up to 4 more with
  // object balls (a contact logs one for each ball, balls stopping at one instant one
  // each).
  int max_events = 200;
  bool record_path = true;              // fill the path of ShotResult and of each ball
  // The shot is followed up to this time (s after the strike) only: a caller that needs
  // no more (a fit compared with the first second of a recording) skips the events after
  // it. A shot still moving then ends as time_limit.
  double max_time = std::numeric_limits<double>::infinity();
};

// The impact method simulate() uses for cushion contacts with these options: closed_form
// when the scene's cushion model is han_2005 (whatever the options ask for); otherwise the
// table where its measured error meets options.impact_accuracy, paper or
// extrapolation when asked for, else exact (at a tolerance that meets the accuracy).
ImpactMethod chosen_impact_method(const Scene& scene, const SimulationOptions& options);

// What became of one ball.
struct BallOutcome {
  std::string name;     // kCueBallName for the cue ball, else its ObjectBall::name
  Vec2 start;           // m, where it lay when the shot started
  Vec2 final_position;  // m, at rest, where it entered a pocket, or where the shot ended
  bool pocketed = false;
  int pocket = -1;      // when pocketed: index into Scene::pockets
  int cushion_hits = 0;  // rails only (jaw contacts are not counted)
  int jaw_hits = 0;      // contacts with pocket points and facings
  double max_cushion_normal_speed = 0.0;  // m/s, rails and jaws
  std::vector<ShotEvent> events;  // its own, in time order (none for a ball never struck)
  std::vector<PathSegment> path;  // its path, when record_path
};

// The outcome of a stroke. The top-level fields describe the cue ball (as they did
// before there were object balls); `balls` describes every ball, the cue ball first.
struct ShotResult {
  ShotStatus status = ShotStatus::invalid_input;
  std::string message;
  // invalid_input: the broken rule; fields named as Scene's members (see
  // Scene::validate), {"cue_ball"}, {"shot", "speed"} and the like, {"max_events"}.
  std::optional<ValidationError> error;
  Vec2 final_position;    // the cue ball's
  double duration = 0.0;  // s from the strike to the cue ball's rest (or its end event)
  int cushion_hits = 0;   // the cue ball's
  double max_cushion_normal_speed = 0.0;  // m/s, the cue ball's; above the rigid limit the
                                          // model is flagged
  bool rigid_limit_exceeded = false;      // the cue ball's cushions
  ImpactMethod impact_method = ImpactMethod::exact;  // chosen_impact_method()
  CushionModel cushion_model = CushionModel::mathavan_2010;  // the scene's, for the record
  int table_impacts = 0;  // cushion contacts (of every ball) the table answered (the rest
                          // fell back)
  std::vector<ShotEvent> events;  // the cue ball's (balls[0].events)
  std::vector<PathSegment> path;  // the cue ball's, when record_path (balls[0].path)
  // Every ball: balls[0] is the cue ball (named kCueBallName), balls[k] is
  // Scene::balls[k - 1]. Empty only with invalid_input.
  std::vector<BallOutcome> balls;
  int first_contact = -1;  // the first ball the cue ball touched (index into balls); -1: none
};

// Simulates one stroke of the cue ball from `cue_ball` on `scene`, which was checked
// when it was compiled (an unusable one gives invalid_input with its error), until
// every ball rests or leaves the table, or a ball touches an obstacle.
ShotResult simulate(const CompiledScene& scene, Vec2 cue_ball, const Shot& shot,
                    const SimulationOptions& options = {});
// The same for a scene checked on this call, for callers that simulate it once.
ShotResult simulate(const Scene& scene, Vec2 cue_ball, const Shot& shot,
                    const SimulationOptions& options = {});

}  // namespace cueplan::physics
