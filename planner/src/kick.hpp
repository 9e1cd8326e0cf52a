// Kicks, banks and escapes: routes by cushion sequence.
//
// A route family is the number of cushions the cue ball meets before its first contact
// (a kick; an escape from a snooker) and, for a pot, the number the object ball meets
// before its pocket (a bank, a double). Each family's routes are seeded by the mirror
// image construction: the point the cue ball must reach is reflected across the
// cushions' centre lines (the noses inset by the contact offset R cos(theta)), last
// cushion first, and the aim is the line to the last image; a bank reflects the pocket
// the same way. A route is clear when every straight leg keeps two radii from every other
// ball and every bounce falls on a cushion's straight nose, out of the pocket mouths.
//
// On the exact model spin and speed bend a kick off its mirror line (the cue ball leaves
// a cushion sliding, and its side changes the rebound). So each route is played on a
// small grid of speeds and spins, and for each the aim is solved by a 1-D root on the
// simulator: the signed offset at which the cue ball's last leg passes the ball it is
// to strike (then, for a pot, the pot's ball's last leg against its pocket's centre).
//
// Pure functions of their arguments: safe from any thread.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::planner::detail {

struct Task;

// One route: the cue ball off `cue_cushions` (ShotEvent::cushion numbering) to strike
// `ball`, passing its centre at `offset_m` (> 0: the centre to the left of the cue ball's
// last leg; 0: full ball); for a pot, the pot's ball off `object_cushions` to its pocket.
struct KickRoute {
  std::vector<int> cue_cushions;
  std::vector<physics::Vec2> cue_bounces;  // where the centre meets each cushion line
  int ball = 0;                            // index into ShotResult::balls (1: Scene::balls[0])
  std::string ball_name;
  double offset_m = 0.0;
  std::vector<int> object_cushions;
  std::vector<physics::Vec2> object_bounces;
  double seed_aim_deg = 0.0;   // the mirror line's aim (deg, wrapped)
  double cue_length = 0.0;     // m, the cue ball's path to the contact
  double object_length = 0.0;  // m, the pot's ball's path to its pocket
  double cut_deg = 0.0;        // a pot: the cut the route asks for
  // The mirror line is screened by another ball (its bounces fall on the noses): the
  // cushion's rebound (a rolling ball's angle is not the mirror's) and side bend the
  // path off the mirror line, which may clear the screen.
  bool screened = false;
};

// The families a problem's limits allow, each with its clear routes or why it has none.
struct KickFamilies {
  std::vector<KickRoute> routes;       // every clear route, cheapest family first
  std::vector<std::string> ruled_out;  // "one cushion: ..." for each family with no clear route
  // Cushion routes whose mirror lines only other balls screen, cheapest first: tried
  // once the clear routes have failed.
  std::vector<KickRoute> screened;
  int families = 0;                    // families the limits allow (those searched)
};

// The name of a family: "direct", "one cushion", "two cushions", ...; a pot's object
// cushions after it: "one cushion, then a double off one cushion".
std::string family_name(int cue_cushions, int object_cushions, bool pot);

// The routes of the families the limits allow (cushions_before_contact and, for a pot,
// object_cushions). `direct`: whether the family with no cushions at all is included
// (the normal search plans direct pots).
KickFamilies kick_families(const problems::Problem& problem, bool direct);

// Strokes along `route` that solve the problem (problems::check_stroke), at most
// `keep`: the route played at each speed and spin of its grid, cheapest first, with the
// aim solved on `simulation`. Stops at `deadline`; *simulations counts what it cost.
std::vector<physics::Shot> solve_kick(const Task& task, const KickRoute& route,
                                      const physics::SimulationOptions& simulation,
                                      std::chrono::steady_clock::time_point deadline, int keep,
                                      int* simulations);

// A combination: the cue ball strikes problem.first_contact directly, which drives the
// pot's ball into its pocket. The cue ball's path to its ghost ball, the first ball's to
// the pot's ball's ghost ball and that ball's to its pocket must be clear (two radii from
// every other ball), the cue ball's cut at most 60 deg and the first ball's 45 deg: then
// the three legs' length (the cost a route is ranked by), else empty.
std::optional<double> combination_length(const problems::Problem& problem);

// Strokes that play that combination (problems::check_stroke: the first contact and the
// pot), at most `keep`: a few speeds and spins, the aim solved on `simulation` so that
// the pot's ball's path passes its pocket's centre. *simulations counts what it cost.
std::vector<physics::Shot> solve_combination(const Task& task, const physics::SimulationOptions& simulation,
                                             int keep, int* simulations);

// The route a stroke took, in a player's words: "one cushion off the top cushion,
// right-hand side, to hit the red full; the red doubles off the bottom cushion into the
// top middle pocket". Empty when the problem names no ball to strike.
std::string route_words(const problems::Problem& problem, const physics::Shot& shot,
                        const physics::ShotResult& result);

// What an escape leaves the opponent (`leave: safe`): the chance of the easiest direct
// pot from where the cue ball stops, over every object ball left on the table and every
// pocket whose lines (cue ball to ghost ball, ball to pocket) are two radii clear. A
// simple estimate: the cue ball's aim may err by the object ball's angular margin at the
// pocket (its capture radius over its distance) scaled by 2R cos(cut) over the cue
// ball's distance, against a Gaussian aim error of `aim_sigma_deg`; cuts beyond 75 deg
// count as no pot. 0 when the cue ball is not at rest on the table.
double easiest_pot(const problems::Problem& problem, const physics::ShotResult& result,
                   double aim_sigma_deg);

}  // namespace cueplan::planner::detail
