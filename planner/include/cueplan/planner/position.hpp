// Position play: how good a cue-ball position is for the next pot.
//
// A PositionField answers, for any point of the table, P(next pot): the chance that a
// player with the planner's execution noise (NoiseModel) pots the next ball into its
// pocket from a cue ball there, with the simple stroke at the ghost ball. It is a
// closed-form estimate, not a search (docs/position.md derives it and checks it against
// the planner's own P(pot) from `solve`; tests/planner/position_test.cpp holds that
// comparison):
//   the object ball must leave within the pocket's angular half-width w (its opening as
//   seen along the ball's path, from the jaws or the capture circle, over the distance to
//   the pocket); an error delta of the cue ball's direction turns the object ball's by
//   g delta, g = |D / (2 R cos(cut)) - 1| (D the cue ball's distance to the object ball);
//   with sigma the cue ball's direction deviation of the noise model (aim, and sideways
//   tip errors through squirt and the cue's pivot at the bridge) and sigma_t the throw's,
//       P = 2 Phi(w / sqrt((g sigma)^2 + sigma_t^2)) - 1;
//   zero when the next ball is screened (a ball within 2R of the cue ball's path to the
//   ghost ball or of the object ball's path to the pocket) or the cut is beyond
//   kMostCut; lower when the cue ball lies near a cushion and the cue must come over it
//   (elevated cueing), and when it is too close to the next ball to cue.
// With a list of next pots, one step of look-ahead: a position is worth
//   value = P(first) x max P(second) over where the cue ball can be sent from it,
// those points sampled along the directions a stun, follow or draw stroke can take after
// the first pot (straight, no cushion), up to the first cushion or ball.
//
// value() is computed exactly at every call (a few microseconds); the field also keeps
// the values on a grid of cells (2 cm) for what needs the whole table: the best value,
// the zone (where value is within kZoneWidth of the best) and pictures. The grid costs
// a few milliseconds; a field built with FieldGrid::lazy fills it only when something
// asks for it (the run-out planner asks thousands of fields for a few points each).
//
// Immutable once built (a lazy grid is filled once, under std::call_once): share it
// between threads. No globals, no hidden statics.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::planner {

// The zone: where value is within this of the best (10 percentage points).
inline constexpr double kZoneWidth = 0.10;
// Cuts beyond this (deg) are not played.
inline constexpr double kMostCut = 80.0;
// The difference allowed between the field's P(next pot) and the planner's P(pot) from
// `solve` at the validation positions (tests/planner/position_test.cpp; 0.064 measured,
// docs/position.md): what the reported success.next's interval allows for the estimate.
inline constexpr double kFieldError = 0.10;

// The next pot from one cue-ball position, in a player's terms.
struct NextShot {
  double p = 0.0;            // P(pot) estimate, [0, 1]
  double cut_deg = 0.0;      // between the cue ball's path and the object ball's (0: full ball)
  int cut_side = 0;          // +1 the object ball leaves to the left of the cue ball's path, -1 right
  std::string thickness;     // full, 3/4, half, 1/4 or thin (as PotReport::thickness)
  double cue_distance_m = 0.0;     // cue ball to the object ball's centre
  double object_distance_m = 0.0;  // object ball to the pocket's aim point
  std::string screened_by;   // the ball in the way ("red", "obstacle 2"); empty when clear
  bool impossible_cut = false;     // cut beyond kMostCut, or no ghost ball to reach
  bool near_cushion = false;       // the cue must come over a cushion: P lowered
  bool too_close = false;          // within a few cm of the object ball: P lowered
  bool valid_position = true;      // false off the table, in a pocket or inside a ball
};

// When the grid of cells is filled: in the constructor, or at the first call that needs
// it (best_value, best, zone_area_m2, in_zone, zone_threshold, cell_value; with a list
// of next pots value() and next_shot() need the second pot's grid, filled on their first
// call). Either way every answer is the same.
enum class FieldGrid { eager, lazy };

class PositionField {
 public:
  // `layout`: the table and the balls as they will be for the next shot (the cue ball is
  // not among them); `next`: the pots in order (1 to problems::kMostNextPots), balls of
  // layout.balls and pockets of layout.pockets; `cell_m`: the grid's cell (m, > 0).
  PositionField(const physics::Scene& layout, std::vector<problems::NextPot> next,
                const NoiseModel& noise, double cell_m = 0.02, FieldGrid grid = FieldGrid::eager);

  // The field of a problem with `next`: its scene without the pot's ball (this stroke
  // pots it). The problem must have been validated and have a next pot.
  static PositionField for_problem(const problems::Problem& problem, const NoiseModel& noise,
                                   double cell_m = 0.02, FieldGrid grid = FieldGrid::eager);

  // P(pot `ball` into `pocket`) from a cue ball at `cue`, the other balls as `layout`
  // has them (the field of that one pot, no grid): NextShot::p.
  static double pot_chance(const physics::Scene& layout, physics::Vec2 cue, std::string_view ball,
                           int pocket, const NoiseModel& noise);

  // The position's worth for position play: P(first next pot), times, with a list, the
  // best P(second) reachable from there. In [0, 1]; 0 where the cue ball cannot lie.
  double value(physics::Vec2 cue) const;
  // The `index`-th next pot (0: the first) from a cue ball at `cue`.
  NextShot next_shot(physics::Vec2 cue, size_t index = 0) const;

  // Over the grid's cells: the best value and where (a cell's centre).
  double best_value() const { return grid().best_value; }
  physics::Vec2 best() const { return grid().best; }
  // The zone: where value >= best_value() - kZoneWidth; its area (m^2, by cells).
  double zone_area_m2() const { return grid().zone_area_m2; }
  bool in_zone(physics::Vec2 cue) const { return value(cue) >= zone_threshold(); }
  double zone_threshold() const { return best_value() - kZoneWidth; }

  // The grid: columns along x, rows along y; cell (i, j) is centred at
  // ((i + 0.5) cell, (j + 0.5) cell); its value is value() there.
  int columns() const { return columns_; }
  int rows() const { return rows_; }
  double cell() const { return cell_; }
  double cell_value(int i, int j) const {
    return grid().values[static_cast<size_t>(j) * columns_ + i];
  }
  physics::Vec2 cell_centre(int i, int j) const { return {(i + 0.5) * cell_, (j + 0.5) * cell_}; }

  const std::vector<problems::NextPot>& next() const { return next_; }
  const physics::Scene& layout() const { return layout_; }
  // The cue ball's direction deviation (deg) the noise model gives a centre-ball stroke.
  double direction_sd_deg() const { return direction_sd_deg_; }

 private:
  // A next pot, ready to be evaluated from any cue position.
  struct Target {
    std::string ball;
    physics::Vec2 centre;       // the object ball
    physics::Vec2 aim;          // the pocket's aim point (its centre, or the mouth's middle)
    physics::Vec2 u;            // unit, object ball to aim
    physics::Vec2 ghost;        // the cue ball's centre at contact
    double distance = 0.0;      // object ball to aim (m)
    double half_angle = 0.0;    // rad: the directions that drop
    bool clear = true;          // the object ball's path is clear
    std::string screened_by;
  };
  // The grid, filled once (in the constructor, or lazily at the first call).
  struct Grid {
    std::vector<double> values;  // value() per cell
    double best_value = 0.0;
    physics::Vec2 best;
    double zone_area_m2 = 0.0;
  };
  struct Cells {
    std::once_flag second_once, grid_once;
    std::vector<double> second;  // P(second next pot) per cell (lists only)
    Grid grid;
  };
  const Grid& grid() const;
  const std::vector<double>& second() const;
  NextShot shot_from(physics::Vec2 cue, const Target& t) const;
  double reach_value(physics::Vec2 cue, const Target& first) const;
  double grid_value(const std::vector<double>& grid, physics::Vec2 p) const;
  bool cue_can_lie(physics::Vec2 cue) const;
  bool path_clear(physics::Vec2 a, physics::Vec2 b, const std::string& skip,
                  std::string* by) const;

  physics::Scene layout_;
  std::vector<problems::NextPot> next_;
  std::vector<Target> targets_;
  double radius_ = 0.0;
  double contact_offset_ = 0.0;
  double direction_sd_deg_ = 0.0;
  double cell_ = 0.02;
  int columns_ = 0, rows_ = 0;
  // Shared by copies of the field (they answer alike): filled under its once_flags.
  std::shared_ptr<Cells> cells_;
};

// Where a player's noisy strokes aimed at `shot` leave the cue ball: one entry per
// stroke that comes to rest on the table (miscues and pocketed cue balls left out),
// with whether it made the problem's pot cleanly; the same draws as estimate_success for
// the same seed. For pictures (the landing cloud of `cueplan zone`).
struct NoisyLanding {
  physics::Vec2 position;
  bool potted = false;
};
std::vector<NoisyLanding> noisy_landings(const problems::Problem& problem, const physics::Shot& shot,
                                         const NoiseModel& noise, int samples, uint64_t seed,
                                         const physics::SimulationOptions& simulation);

// Fields built once per problem and noise model and shared: the stroke search asks a
// field thousands of times, and solve, zone and the run-out planner may ask for the same
// problem's again. Thread-safe; a cache is an object the caller owns (no static cache).
class PositionCache {
 public:
  std::shared_ptr<const PositionField> get(const problems::Problem& problem,
                                           const NoiseModel& noise);
  size_t size() const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, std::shared_ptr<const PositionField>> fields_;
};

}  // namespace cueplan::planner
