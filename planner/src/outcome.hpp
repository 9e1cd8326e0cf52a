// What the planner makes of one simulated stroke: the score it minimises, the
// family (route and spin) it belongs to, and the constraints it breaks.
#pragma once

#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::planner::detail {

// Penalties (in metres, added to a miss distance) that steer the search toward
// feasible strokes while keeping the objective continuous within a route.
inline constexpr double kEndedEarlyPenalty = 1.0;   // pocketed or touched an obstacle
inline constexpr double kCushionPenalty = 0.5;      // per cushion outside [min, max]
inline constexpr double kRigidPenalty = 0.5;        // cushion normal speed above the rigid limit
inline constexpr double kRigidPenaltyPerSpeed = 1.0;  // m per m/s of excess
inline constexpr double kFailedPenalty = 100.0;     // no result (invalid, event limit, impact)
inline constexpr double kPotPenalty = 1.0;          // the pot is not made (or is made foully)

// A tip offset under half a quarter tip (1/32 R) reads as centre, as in describe_stroke().
inline constexpr double kCentreK = physics::kSpinPerTipOffset / 32.0;

// The objective of the nominal search: the miss distance (m) when the stroke stops on
// the table after an allowed number of cushions, plus penalties otherwise.
double shot_score(const problems::Problem& problem, const physics::ShotResult& result,
                  bool enforce_rigid_limit);

// What shot_score adds for a pot (or first contact) the stroke does not make: 2
// kPotPenalty for the wrong first contact, kPotPenalty plus the pot's ball's distance
// from its pocket (at most 1 m) when it does not drop there, kPotPenalty when another
// ball drops too; 0 without a pot or first_contact.
double pot_penalty(const problems::Problem& problem, const physics::ShotResult& result);

// The event cap of the search: enough for any stroke that meets at most one cushion
// more than allowed (a cushion adds at most three events, the rest of a stroke four),
// so that a stroke running on around the table is cut short and scored by
// shot_score as meeting too many cushions.
int search_event_cap(const problems::Problem& problem, int max_events);

// The cushions met, in order (ShotEvent::cushion).
std::vector<int> route_of(const physics::ShotResult& result);

// Which family a stroke belongs to: its route and the signs of its spins, with a
// band around zero for stun and no side. Two strokes with equal keys are "the same
// way" of playing the shot.
using FamilyKey = Family;
FamilyKey family_key(const physics::Shot& shot, const physics::ShotResult& result);

// The constraints a described stroke breaks, in words; empty when it breaks none.
std::string violations(const problems::Problem& problem, const physics::Shot& shot,
                       const physics::ShotResult& result, bool enforce_rigid_limit);

// The stroke and its simulated outcome as a PlannedShot (success_probability left 0);
// `solves` counts the rigid-cushion limit only when it is enforced.
PlannedShot describe_outcome(const problems::Problem& problem, const physics::Shot& shot,
                             const physics::ShotResult& result, bool enforce_rigid_limit);

}  // namespace cueplan::planner::detail
