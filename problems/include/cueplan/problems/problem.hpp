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

#include "cueplan/physics/shot.hpp"

namespace cueplan::problems {

// Defaults of the fields a file may leave out (problems/README.md lists them all).
inline constexpr double kDefaultPocketRadius = 0.045;  // m, capture circle of a pocket
inline constexpr double kDefaultTolerance = 0.02;      // m, radius of the landing zone

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
  double spin_max = 1.25;  // max sqrt(k_T^2 + k_S^2), the miscue limit; > 0
  AimLimit aim;            // free unless the file says otherwise
  int cushions_min = 1;    // cushion contacts allowed before the ball rests; >= 0
  int cushions_max = 3;    // >= cushions_min
};

struct Problem {
  std::string name;    // the file's `name`, or the stem of its file name
  std::string source;  // file path, or the source name given to parse_problem
  physics::Scene scene;
  physics::Vec2 cue_ball;  // m, table frame; checked with Scene::check_position
  physics::Vec2 target;    // m, where the cue ball should come to rest; checked likewise
  double tolerance = kDefaultTolerance;  // m, radius of the landing zone; > 0
  Limits limits;
  // For a route of several strokes (planner/route.hpp, `cueplan route`): the most
  // strokes allowed (a whole number in [1, 100]) and the planning time budget (s, > 0).
  // Empty when the file leaves them out; commands then use their own defaults.
  std::optional<int> max_strokes;
  std::optional<double> time_budget_s;
};

// Either a problem or one line saying what is wrong, never both.
//   "FILE:LINE: FIELD: message"  for a field (LINE counts from 1; FIELD is a path such as
//                                 table.length, limits.speed[1] or obstacles[2]);
//   "FILE:LINE: yaml: message"    for a YAML syntax error;
//   "FILE: message"               when the file cannot be read at all.
struct LoadResult {
  std::optional<Problem> problem;
  std::string error;

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
// outcome, judged by reaches_target); otherwise which limit it breaks.
std::string check_shot(const Limits& limits, const physics::Shot& shot);

// Distance (m) from the target to where the cue ball came to rest; +infinity when the
// shot did not end at rest on the table (pocketed, hit an obstacle, failed).
double miss_distance(const Problem& problem, const physics::ShotResult& result);

// True when the outcome solves the problem: at rest within `tolerance` of the target
// after a number of cushion contacts within [cushions_min, cushions_max].
bool reaches_target(const Problem& problem, const physics::ShotResult& result);

}  // namespace cueplan::problems
