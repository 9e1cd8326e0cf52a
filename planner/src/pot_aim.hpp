// The pot's structure: for a given speed and spin, the aim that sends the pot's ball at
// its pocket is a 1-D root near the ghost-ball line, moved by the throw the collision
// gives the object ball (a few tenths of a degree of its direction, far less of the
// aim). PotAim finds that root by simulation, and describes a pot in a player's terms.
#pragma once

#include <optional>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::planner::detail {

struct Task;

// A pot problem's geometry, fixed once: the chain of balls the cue ball drives (the
// first contact, then the pot's ball when they differ: a plant), the pocket, and the
// ghost-ball aim. Immutable after construction, so one instance serves every thread.
// The squirt (deg, counter-clockwise) of `shot` with the problem's cue and ball.
double squirt_of(const problems::Problem& problem, const physics::Shot& shot);

class PotAim {
 public:
  // `problem` must have a pot (problems::validate checked it) and outlive this.
  explicit PotAim(const problems::Problem& problem);

  // The aim (deg, wrapped into [-180, 180)) of the ghost-ball line: the cue ball sent
  // straight to the position from which, with no throw, each ball of the chain leaves
  // along the line to the next ghost and the pot's ball to the pocket's centre.
  double ghost_aim_deg() const { return ghost_aim_deg_; }

  // The pot's ball's direction (deg) with no throw when the cue ball is aimed at
  // `aim_deg`, the balls meeting along straight lines; empty when a contact misses.
  std::optional<double> geometric_direction(double aim_deg) const;

  // The signed angle (deg, counter-clockwise) from the line of the pot's ball after it
  // was struck to the pocket's centre, as seen from where it was struck: the error the
  // aim root drives to zero; empty when the pot's ball was not struck. *margin_m, when
  // given, gets how far inside the capture circle the ball's centre passes (its
  // capture radius less the pocket centre's distance from the ball's line; negative
  // when it passes outside).
  // `lateral_m` moves the point aimed at across the pocket: that far (m) to the left
  // of its centre as seen from the pot's ball.
  std::optional<double> direction_error(const physics::ShotResult& result,
                                        double* margin_m = nullptr, double lateral_m = 0.0) const;
  // How far (m) to the left of the pocket's centre the pot's ball's line passes, as
  // seen from the ball; empty when it was not struck.
  std::optional<double> lateral_of(const physics::ShotResult& result) const;
  // The most lateral_m the search asks for: kPotWindow of the capture radius.
  double lateral_reach() const;

  struct Aimed {
    physics::Shot shot;          // with the aim found
    physics::ShotResult result;  // its simulation
    int simulations = 0;
    bool found = false;          // the pot's ball's line meets the pocket's centre
  };
  // The aim that pots with `shot`'s speed and spin (its aim is ignored): Newton steps
  // from the ghost-ball aim plus `offset_hint_deg` less the stroke's squirt (a nearby stroke's allowance for
  // throw), with the geometric gain as the slope, then regula falsi once the error
  // changes sign, until the pot's ball's line passes within kAimTolerance of the
  // pocket's centre. Not found when its line cannot be brought there (the cue ball
  // misses, or strikes another ball first).
  Aimed aim(const Task& task, const physics::Shot& shot,
            const physics::SimulationOptions& simulation, double offset_hint_deg = 0.0,
            double lateral_m = 0.0) const;

  const std::string& pot_ball() const { return pot_ball_; }

 private:
  const problems::Problem& problem_;
  std::string pot_ball_;
  int pot_index_ = 0;  // index into ShotResult::balls
  std::vector<physics::Vec2> chain_;  // centres of the balls the cue ball drives, in order
  physics::Vec2 pocket_;
  physics::Vec2 across_;  // unit, to the left of the line from the pot's ball to the pocket
  double capture_ = 0.0;
  double ghost_aim_deg_ = 0.0;
};

// What a pot looks like to a player (PlannedShot::pot), from the stroke's outcome:
// cut, thickness, throw, how the aim allows for it, the pot's margin in metres and in
// aim (found by simulating aims either side until the ball stays out).
PotReport pot_report(const Task& task, const PotAim& aim, const physics::Shot& shot,
                     const physics::ShotResult& result,
                     const physics::SimulationOptions& simulation, int* simulations);

// "full", "3/4", "half", "1/4" or "thin": the nearest fraction of the object ball the
// cue ball covers at contact, 1 - sin(cut), thin below 1/8.
const char* thickness_of(double cut_deg);

}  // namespace cueplan::planner::detail
