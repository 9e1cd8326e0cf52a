// A shot-planning problem: the table and its physics (a physics::Scene), where the cue
// ball lies, where it should come to rest, and the limits a planner searches within.
//
// Problems are written as YAML files; problems/README.md is the format reference.
// Loading never throws and never aborts: a bad file comes back as an error that names
// the file, the line and the field, so a command line can print it and exit with 2.
//
// SI units throughout (m, kg, m/s), except angles, which are in degrees as in the files.
// No globals or hidden state: every function here is safe to call from many threads.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"

namespace cueplan::problems {

// Defaults of the fields a file may leave out (problems/README.md lists them all).
inline constexpr double kDefaultPocketRadius = physics::kDefaultPocketRadius;  // m
inline constexpr double kDefaultTolerance = 0.02;  // m, radius of the landing zone
// The most strokes a route may take (max_strokes).
inline constexpr int kMostStrokes = 100;

// The cue's aim phi (deg from +x, counter-clockwise), as the planner may choose it.
enum class AimMode {
  free,   // any direction
  fixed,  // exactly lo_deg (== hi_deg)
  range,  // lo_deg <= phi <= hi_deg, modulo 360; lo_deg < hi_deg <= lo_deg + 360
};

struct AimLimit {
  AimMode mode = AimMode::free;
  double lo_deg = 0.0;
  double hi_deg = 0.0;
};

// The planner's search space and the constraints on an acceptable shot.
struct Limits {
  double speed_min = 0.2;  // m/s, cue-ball speed V just after the strike; > 0
  double speed_max = 4.5;  // m/s; > speed_min
  double spin_max = physics::kMiscueSpin;  // max sqrt(k_T^2 + k_S^2); > 0
  AimLimit aim;            // free unless the file says otherwise
  int cushions_min = 1;    // cushion contacts allowed before the ball rests; >= 0
  int cushions_max = 3;    // >= cushions_min
  // The cue's elevation (deg): 0 <= min <= max < 90. [0, 0], a level cue, unless the file
  // says otherwise; the planner plays the least elevation allowed.
  double elevation_min_deg = 0.0;
  double elevation_max_deg = 0.0;
  // Kicks and banks: the cushions the cue ball may meet before its first ball contact,
  // and those the pot's ball may meet before it drops (0 <= min <= max). A kick or an
  // escape off up to three cushions, a bank or double off up to two, by default.
  int cushions_before_contact_min = 0;
  int cushions_before_contact_max = 3;
  int object_cushions_min = 0;
  int object_cushions_max = 2;
};

// An object ball into a pocket: what a pot-and-position shot is to do.
struct Pot {
  std::string ball;  // an object ball's name (Scene::balls)
  int pocket = -1;   // index into Scene::pockets; the file names it (kPocketNames)
};

// A pot to be played after this stroke (the position play's next ball): an object ball
// into a pocket, from wherever this stroke leaves the cue ball.
struct NextPot {
  std::string ball;  // an object ball's name (Scene::balls), not the pot's ball
  int pocket = -1;   // index into Scene::pockets
};
// The most next pots a problem may list (`next` in the file).
inline constexpr int kMostNextPots = 3;

struct Problem {
  std::string name;    // the file's `name`, or the stem of its file name
  std::string source;  // file path, or the source name given to parse_problem
  physics::Scene scene;    // with the object balls (`balls`) and obstacles
  physics::Vec2 cue_ball;  // m, table frame; checked with Scene::check_position
  physics::Vec2 target;    // m, where the cue ball should come to rest; checked with
                           // Scene::check_rest_position (object balls may move away)
  // False for a pure pot (a file with `pot` and no `target`) or an escape (a file with
  // `first_contact` and neither `pot` nor `target`: a legal hit is all it asks): the cue
  // ball may come to rest anywhere, and `target` is unused.
  bool has_target = true;
  double tolerance = kDefaultTolerance;  // m, radius of the landing zone; > 0
  Limits limits;
  // For a route of several strokes (planner/route.hpp, `cueplan route`): the most
  // strokes allowed (a whole number in [1, 100]) and the planning time budget (s, > 0).
  // Empty when the file leaves them out; commands then use their own defaults.
  std::optional<int> max_strokes;
  std::optional<double> time_budget_s;
  // For pot-and-position planning: the pot the shot is to make, and the object ball the
  // cue ball must strike first (required_first_contact() gives the default, the pot's ball).
  std::optional<Pot> pot;
  // A ball's name or a class of balls (ball_names.hpp: any_red, lowest, solids, stripes,
  // any_colour): a first contact on any other ball is a foul.
  std::optional<std::string> first_contact;
  // Position play (`next`): the pots to be played after this one, in order (at most
  // kMostNextPots; empty: none). The stroke is judged by how well it leaves the cue ball
  // for the first (planner/position.hpp); with a pot only. Without a target the pot is
  // the only condition and the next pot ranks the strokes.
  std::vector<NextPot> next;
  bool next_is_list = false;  // the file wrote `next` as a list (how errors name its fields)
  // Names of the obstacles (`obstacles` written as a mapping), in Scene::obstacles'
  // order; empty when the file lists them as points.
  std::vector<std::string> obstacle_names;
  // `leave: safe`: an escape should also leave the opponent no easy pot from where the
  // cue ball stops (the planner ranks escapes by it after the legal hit).
  bool leave_safe = false;

  // The ball the cue ball must strike first: first_contact, else the pot's ball; empty
  // when neither is given (any ball, or none).
  std::string required_first_contact() const;
  // An escape: a first contact asked for with no pot and no target.
  bool is_escape() const { return first_contact.has_value() && !pot && !has_target; }
};

// Empty when the problem can be planned; otherwise the first broken rule, fields named
// as the members of Problem: {"scene", "length"}, {"scene", "cloth", "mu_roll"},
// {"scene", "balls", "red"}, {"cue_ball"}, {"limits", "speed_max"}, {"pot", "ball"},
// {"first_contact"}, ... The one check of a problem: the loader runs it on every file,
// the planners on every problem they are given.
physics::Validation validate(const Problem& problem);

// A field of Problem (a path as validate() names it) as the problem file names it:
// {"scene", "length"} -> "table.length", {"scene", "ball_and_cushion", "mu_table"} ->
// "physics.mu_slide", {"scene", "ball_contact", "restitution"} ->
// "physics.ball_restitution", {"scene", "balls", "red"} -> "balls.red",
// {"limits", "speed_min"} -> "limits.speed[0]", a standard pocket {"scene", "pockets", 0}
// -> "the bottom_left pocket".
std::string file_field(const physics::FieldPath& path);
// The error in the file's words: "FIELD RULE, got VALUE".
std::string file_message(const physics::ValidationError& error);

// Names of the standard pockets in physics::standard_pockets' order: bottom_left (0, 0),
// bottom_middle (L/2, 0), bottom_right (L, 0), top_left (0, W), top_middle (L/2, W),
// top_right (L, W).
inline constexpr const char* kPocketNames[6] = {"bottom_left", "bottom_middle", "bottom_right",
                                                "top_left",    "top_middle",    "top_right"};

// Either a problem or one line saying what is wrong, never both.
//   "FILE:LINE: FIELD: message"  for a field (LINE counts from 1; FIELD is a path such as
//                                 table.length, limits.speed[1] or obstacles[2]);
//   "FILE:LINE: yaml: message"    for a YAML syntax error;
//   "FILE: message"               when the file cannot be read at all.
struct LoadResult {
  std::optional<Problem> problem;
  std::string error;
  // The field of the file the error is about (as in the message: "table.length",
  // "limits.speed[1]", "(document)", "yaml"; empty when the file cannot be read) and
  // its line (from 1; 0 when unknown), for callers that show them apart.
  std::string field;
  int line = 0;

  bool ok() const { return problem.has_value(); }
};

// Reads and checks the problem file at `path`.
LoadResult load_problem(const std::string& path);

// The same for YAML text already in memory; `source_name` stands for the file in
// messages and in Problem::source (e.g. "<string>").
LoadResult parse_problem(const std::string& yaml_text, const std::string& source_name);

// A few lines for people: table, ball, positions, tolerance and limits with units.
std::string describe(const Problem& problem);

// Empty when `shot` lies within `limits` (speed, spin and aim; the cushion count is an
// outcome, judged by check_outcome); otherwise which limit it breaks.
std::string check_shot(const Limits& limits, const physics::Shot& shot);

// The conditions a stroke must meet to solve a problem, in the order they are judged;
// the first one broken is the reason it fails.
enum class Failure {
  none,                 // every condition met
  outside_limits,       // the stroke breaks a limit: speed, spin or aim (check_shot)
  no_outcome,           // the simulation gave no result (event limit, a failed impact)
  obstacle,             // a ball touched an obstacle ball
  cue_ball_pocketed,    // the cue ball dropped
  first_contact,        // the cue ball struck no ball, or another ball first
  pot_missed,           // the pot's ball did not drop
  wrong_pocket,         // it dropped, in another pocket
  other_ball_pocketed,  // a ball other than the pot's dropped
  cushions,             // the cue ball met too few or too many cushions
  off_target,           // the cue ball came to rest outside the tolerance of the target
};
// The condition's name: "none", "outside_limits", ..., "off_target".
const char* to_string(Failure failure);

// Every condition but the cue ball's rest on the target holds (see Verdict::pot_made).
inline bool pot_made(Failure failure) {
  return failure == Failure::none || failure == Failure::off_target;
}

// What a stroke's outcome made of a problem: the first condition broken, in words.
struct Verdict {
  Failure failure = Failure::none;
  std::string reason;  // the broken condition in words; empty when none is
  // Every condition but the cue ball's rest on the target holds: for a pot problem, the
  // pot is made cleanly (the ball in its pocket, first contact, no foul, cushions and
  // limits kept). P(pot) counts these strokes, P(position | pot) those of them that
  // also stop on the target.
  bool pot_made() const { return problems::pot_made(failure); }
  bool solves() const { return failure == Failure::none; }
};

// The conditions on the outcome alone (every condition but the stroke's limits):
//   the shot ended with every ball at rest (no obstacle touched, cue ball not pocketed);
//   the cue ball's first ball contact is required_first_contact(), when there is one (a
//   ball, or one of a class: "foul: first contact on X" otherwise), after
//   limits.cushions_before_contact cushions;
//   with a pot: its ball dropped in its pocket, after limits.object_cushions cushions,
//   and no other ball dropped;
//   the cue ball met limits.cushions_min..cushions_max cushions;
//   with a target: the cue ball rests within `tolerance` of it.
// Without a pot or first_contact these are the conditions of reaches_target.
Verdict check_outcome(const Problem& problem, const physics::ShotResult& result);
// check_outcome's failure alone, the reason not put in words: for loops that judge
// thousands of outcomes and only count them (the same conditions, in the same order).
Failure outcome_failure(const Problem& problem, const physics::ShotResult& result);
// The same with the stroke's limits judged first: whether `shot`, with the outcome
// `result`, solves the problem (the one judgement of planner, simulate and solve).
Verdict check_stroke(const Problem& problem, const physics::Shot& shot,
                     const physics::ShotResult& result);

// Why no direct pot exists, when that can be proved from the table's geometry alone:
// another ball (an object ball or an obstacle) screens the pot's ball from every line
// into its pocket's capture circle, or the cue ball from every straight path to a ghost
// ball that could send it there. Pots off cushions, kisses and plants are not judged.
struct PotScreen {
  std::string blocked;  // "the object ball's path" or "the cue ball's path"
  std::string by;       // the screening ball: an object ball's name or "obstacle N"
  std::string reason;   // "no direct pot: red's path to the bottom_left pocket is ..."
};
// Empty unless the problem has a direct pot (first contact the pot's ball) that is
// screened.
std::optional<PotScreen> screened_pot(const Problem& problem);

// Distance (m) from the target to where the cue ball came to rest; +infinity when the
// shot did not end at rest on the table (pocketed, hit an obstacle, failed); 0 at rest
// for a problem without a target (a pure pot).
double miss_distance(const Problem& problem, const physics::ShotResult& result);

// True when the outcome solves the problem (check_outcome finds no condition broken):
// without a pot or first_contact, at rest within `tolerance` of the target after a
// number of cushion contacts within [cushions_min, cushions_max].
bool reaches_target(const Problem& problem, const physics::ShotResult& result);

// The cushions (rails, not jaws) the cue ball meets before its first ball contact (all
// it meets when it strikes no ball).
int cushions_before_contact(const physics::ShotResult& result);
// True when the outcome makes the problem's pot (the ball in that pocket); false when
// the problem has none.
bool makes_pot(const Problem& problem, const physics::ShotResult& result);

// The pocket's name in problem files (kPocketNames) when the table has the standard
// pockets, else "pocket N".
std::string pocket_name(const physics::Scene& scene, int pocket);

}  // namespace cueplan::problems
