// The OMPL global stage: KPIECE1 over the unit cube of strokes, with the landing
// position of each stroke as its projection.
//
// The tree's states are strokes (points of the search space's unit cube), each kept
// with where it lands and its score; a control is a small random step in the cube
// (Gaussian, with a scale drawn log-uniformly from 0.002 to 0.15 per step), so a
// propagation plays one perturbed stroke. KPIECE1 spreads the tree over a grid of
// landing positions (kLandingCell) and, with its goal bias, keeps extending the strokes
// that landed nearest the target. Strokes that end on a ball, in a pocket or fail are
// invalid states: the tree grows only from strokes that come to rest. The tree starts
// from a seeded uniform sample of the cube that takes half the budget (measured in
// bench/README.md, "Obstacle fields"), and the search stops early once a stroke lands
// within goal_score.
#pragma once

#include <cstdint>
#include <functional>

#include "cueplan/physics/shot.hpp"

namespace cueplan::planner::detail {

// One stroke's outcome as the stage needs it.
struct Landing {
  double score = 0.0;     // the planner's nominal score (m); lower is better
  physics::Vec2 position;  // m, where the ball stopped
  bool at_rest = false;    // on the table, not pocketed, no obstacle, no failure
};
// Simulates the stroke at a point of the unit cube (and counts it).
using LandingProbe = std::function<Landing(const double* u)>;

struct LandingSearch {
  int dimension = 4;
  int aim_coordinate = -1;     // index of a free aim's coordinate (wraps round); < 0: none
  int max_evaluations = 1000;  // probe calls, starts included
  double max_time_s = 1.0;     // wall clock
  double goal_score = 0.0;     // stop once a stroke scores at most this
  double table_length = 3.569, table_width = 1.778;  // m, the landing grid's extent
  uint64_t seed = 1;
};

// Runs the search; every stroke it plays goes through `probe`, at most
// max_evaluations of them. Deterministic for a seed when the evaluations end it.
void explore_landings(const LandingSearch& settings, const LandingProbe& probe);

}  // namespace cueplan::planner::detail
