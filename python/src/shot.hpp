// The objects cueplan._core's parts share: a simulated stroke with its problem.
#pragma once

#include <memory>

#include "core.hpp"
#include "cueplan/physics/shot.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::python {

// A stroke simulated on a problem's table; keeps the problem (its scene) for the
// trajectory and the verdict.
struct ShotHandle {
  std::shared_ptr<const problems::Problem> problem;
  physics::Shot stroke;
  physics::ShotResult result;
};

// Simulates `stroke` on the problem's table with the GIL released; raises InputError
// for a bad stroke ("stroke.speed", ...).
ShotHandle simulate_stroke(const problems::Problem& problem, const physics::Shot& stroke,
                           const physics::SimulationOptions& options);

}  // namespace cueplan::python
