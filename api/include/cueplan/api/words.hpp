// How the command line's reports name cushions, cushion routes and the impact method a
// simulation used, so that every command says them the same way.
#pragma once

#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::api {

// A number as reports print it (6 significant digits), with its unit when given:
// "0.847614 m/s".
std::string number(double value, const char* unit = nullptr);

// One line of a text report: the label in a column of 16, then the text.
void report_line(std::ostream& out, std::string_view label, const std::string& text);

// Where the tip meets the cue ball, as fractions of its radius R, in words:
// "0.231 R right of centre, 0.100 R below centre".
std::string tip_offset_words(const physics::Shot& shot);

// The squirt of `shot` on `scene` (deg, counter-clockwise from the cue's line to the cue
// ball's: physics::squirt_angle_deg with the scene's cue and ball).
double squirt_deg(const physics::Scene& scene, const physics::Shot& shot);
// Where the cue ball goes for a stroke with side: "the cue ball leaves 1.2 deg left of
// the cue's line", and with an elevated cue "then swerves right while it slides". Empty
// for a centre-ball stroke.
std::string squirt_words(const physics::Scene& scene, const physics::Shot& shot);

// The cushion counts a problem allows: "1" or "1 to 3".
std::string cushions_allowed(const problems::Limits& limits);

// A cushion by its nose line (ShotEvent::cushion numbers them): "y = 0", "x = 3.569",
// "y = 1.778", "x = 0".
std::string cushion_name(const physics::Scene& scene, int cushion);

// Cushions in the order met, e.g. "2 cushions: y = 0, x = 3.569"; "no cushion" when empty.
std::string route_text(const physics::Scene& scene, const std::vector<int>& route);

// The impact method simulate() uses with these options (its own rule,
// physics::chosen_impact_method), with what it promises, e.g.
// "exact (impact accuracy 1e-09 of the speed)".
std::string method_text(const physics::SimulationOptions& options, const physics::Scene& scene);

}  // namespace cueplan::api

// The faces (command line, server, batch) name these as their own.
namespace cueplan::cli {
using api::number;
using api::report_line;
using api::tip_offset_words;
using api::squirt_deg;
using api::squirt_words;
using api::cushions_allowed;
using api::cushion_name;
using api::route_text;
using api::method_text;
}  // namespace cueplan::cli
