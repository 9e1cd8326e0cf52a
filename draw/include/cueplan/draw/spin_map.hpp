// The spin map as a picture, "what spin lands here": on the left the tip-offset disc (tip
// right of centre along x, above centre along y, as fractions of the ball radius R), one
// cell per grid spin coloured by how far from the target that spin stops, the cells
// clipped to the spin-limit disc and the spins that land outlined; on the right the
// table with the target zone and every grid spin's rest position as a dot in the same
// colour, with the paths of a few spins. When the sampled strokes spend their sidespin
// before the first cushion the picture says so: left and right then change nothing.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cueplan/draw/picture.hpp"
#include "cueplan/draw/table.hpp"
#include "cueplan/planner/spin_map.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::draw {

// How one grid spin is shown.
enum class SpinCellKind {
  distance,        // at rest after an allowed number of cushions: coloured by the miss
  wrong_cushions,  // at rest, but after a number of cushions the problem does not allow
  pocketed,
  obstacle,   // stopped against an obstacle ball
  no_result,  // the simulation gave no outcome (event limit, impact failure)
  no_pot,     // a pot problem: no aim pots the ball with this spin
};
SpinCellKind classify(const planner::SpinMapPoint& point, const problems::Limits& limits);

// Log colour scale of the miss distance: the target tolerance (and less) at one end,
// `far_mm` (and more) at the other; viridis, near the target bright.
struct MissColourScale {
  double near_mm = 20.0;   // the problem's tolerance
  double far_mm = 2000.0;  // a 1-2-5 value at or above the largest coloured miss
  Colour colour(double miss_m) const;
  std::vector<double> ticks_mm() const;   // 1-2-5 values from near_mm to far_mm
  double position(double miss_mm) const;  // 0 at near_mm .. 1 at far_mm, clamped
};
MissColourScale miss_colour_scale(const planner::SpinMap& map, const problems::Problem& problem);

// Viridis (matplotlib) at t in [0, 1], linear between eleven tabulated colours.
Colour viridis(double t);

struct SpinMapScene {
  std::string title;
  std::vector<std::string> caption;
  problems::Problem problem;
  planner::SpinMap map;
  // Faint paths of a few grid spins; with their events, they tell whether sidespin
  // lasts to the first cushion.
  std::vector<DrawnPath> sample_paths;
  // A stroke to show in full (the planner's), with its spin marked on the disc.
  std::optional<DrawnPath> shot_path;
  std::optional<physics::Shot> marked_shot;
};

// Which grid spins get a faint path: about `per_side` of them along each axis.
std::vector<size_t> sparse_subset(const planner::SpinMap& map, int per_side);

// Whether sidespin is spent before the first cushion on every path that has some (a path
// that meets no cushion counts too: on the cloth side does not bend the path): the
// paths' strike events carry the spin, their spin_stop and cushion events the order.
// Empty when none spends its side before a cushion or some keep it to one; otherwise
// the sentence the picture shows.
std::string sidespin_note(const std::vector<DrawnPath>& paths);

Picture spin_map_picture(const SpinMapScene& scene);

}  // namespace cueplan::draw
