// The planner's search space: a stroke as a point of the unit cube [0, 1]^n.
//
// Coordinates, in order: speed (always), aim (unless the problem fixes it) and the
// two tip-offset coordinates of the spin disc. The disc sqrt(k_T^2 + k_S^2) <=
// spin_max is reached from the square [-1, 1]^2 by the area-preserving concentric map
// of Shirley and Chiu (1997), so a box-bounded optimiser respects the miscue limit
// exactly and a uniform sample of the cube is uniform over the disc. A free aim spans
// one turn centred on `aim_centre_deg`, so a local search can be centred on its start
// and never meets the seam. With a held sidespin the spin is one coordinate: the
// topspin, across the chord of the disc at that sidespin.
#pragma once

#include <optional>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::planner::detail {

// Square [-1, 1]^2 -> disc of radius 1 (x: first coordinate), and back.
void square_to_disc(double a, double b, double* x, double* y);
void disc_to_square(double x, double y, double* a, double* b);

// Wraps an angle in degrees into [-180, 180).
double wrap_degrees(double deg);

class SearchSpace {
 public:
  // `aim_centre_deg` matters for a free aim only: the searched turn is centred there.
  // `held_sidespin_k` (|k_S| <= spin_max) fixes the sidespin and leaves the topspin
  // searched within the spin limit.
  // `aim_solved`: the aim is no coordinate (a pot's aim is solved for each stroke,
  // PotAim); shot() leaves it at 0 for the caller to set, and a last coordinate says
  // where across the pocket the pot's ball is sent (pot_offset()).
  explicit SearchSpace(const problems::Limits& limits, double aim_centre_deg = 0.0,
                       std::optional<double> held_sidespin_k = std::nullopt,
                       bool aim_solved = false);

  int dimension() const {
    return (aim_searched_ ? 2 : 1) + (held_sidespin_ ? 1 : 2) + (aim_solved_ ? 1 : 0);
  }
  bool aim_searched() const { return aim_searched_; }

  // The stroke at a point of the unit cube (coordinates are clamped into [0, 1]).
  // A free aim comes back wrapped into [-180, 180).
  physics::Shot shot(const double* u) const;
  // The point of the cube for a stroke within the limits (the inverse of shot()).
  std::vector<double> point(const physics::Shot& shot, double pot_offset = 0.0) const;
  // With a solved aim: where across the pocket the pot's ball is sent, in [-1, 1] of
  // the reach the aim solver allows (PotAim::lateral_reach); 0 otherwise.
  double pot_offset(const double* u) const;

 private:
  problems::Limits limits_;
  double aim_lo_ = 0.0, aim_hi_ = 0.0;  // deg, the searched interval
  bool aim_searched_ = true;
  bool aim_solved_ = false;
  std::optional<double> held_sidespin_;
  double topspin_reach_ = 0.0;  // with a held sidespin: |k_T| within the spin limit
};

}  // namespace cueplan::planner::detail
