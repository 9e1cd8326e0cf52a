// How the command line's reports name cushions, cushion routes and the impact method a
// simulation used, so that every command says them the same way.
#pragma once

#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"

namespace cueplan::cli {

// A cushion by its nose line (ShotEvent::cushion numbers them): "y = 0", "x = 3.569",
// "y = 1.778", "x = 0".
std::string cushion_name(const physics::Scene& scene, int cushion);

// Cushions in the order met, e.g. "2 cushions: y = 0, x = 3.569"; "no cushion" when empty.
std::string route_text(const physics::Scene& scene, const std::vector<int>& route);

// The impact method simulate() uses with these options (its own rule,
// physics::chosen_impact_method), with what it promises, e.g.
// "exact (impact accuracy 1e-09 of the speed)".
std::string method_text(const physics::SimulationOptions& options, const physics::Scene& scene);

}  // namespace cueplan::cli
