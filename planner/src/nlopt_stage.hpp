// One NLopt run over the unit cube, through the C interface: the objective is a
// plain callable, and nothing it throws crosses NLopt (a throw scores as a failed
// simulation).
#pragma once

#include <nlopt.h>

#include <cmath>
#include <memory>
#include <vector>

#include "cueplan/planner/planner.hpp"
#include "outcome.hpp"

namespace cueplan::planner::detail {

nlopt_algorithm nlopt_global(GlobalMethod method);
nlopt_algorithm nlopt_local(LocalMethod method);

struct StageSettings {
  nlopt_algorithm algorithm = NLOPT_LN_SBPLX;
  int max_evaluations = 100;
  double max_time_s = 0.0;         // <= 0: none
  double stop_value = -HUGE_VAL;   // stop once f <= this
  double x_tolerance = 0.0;        // absolute, in unit-cube coordinates
  double f_tolerance = 0.0;        // absolute, in the objective's units
  double initial_step = 0.0;       // unit-cube coordinates; 0: NLopt's choice
  // A budget in simulations rather than calls, for objectives whose calls cost several
  // (a pot's aim root): after a call that brings *simulations to max_simulations the
  // run is forced to stop (reported as out of evaluations). Null: calls only.
  const int* simulations = nullptr;
  int max_simulations = 0;
  // MLSL only: the local method inside it, with its own budget and tolerances per
  // local search.
  nlopt_algorithm inner = NLOPT_LN_SBPLX;
  int inner_max_evaluations = 0;
  double inner_x_tolerance = 1e-6;
  double inner_f_tolerance = 0.0;
  double inner_step = 0.0;
};

// The objective NLopt calls; `Objective` has `double operator()(const double* u)`.
template <class Objective>
double call_objective(unsigned, const double* u, double*, void* data) noexcept {
  try {
    const double f = (*static_cast<Objective*>(data))(u);
    return std::isfinite(f) ? f : kFailedPenalty;
  } catch (...) {
    return kFailedPenalty;
  }
}

// Minimises over [0, 1]^n from *x (updated to NLopt's answer); returns NLopt's code.
nlopt_result run_stage(const StageSettings& settings, std::vector<double>* x, nlopt_func f,
                       void* data);

template <class Objective>
nlopt_result run_stage(const StageSettings& settings, std::vector<double>* x, Objective* objective) {
  return run_stage(settings, x, &call_objective<Objective>, objective);
}

// True when NLopt stopped on its own tolerances (or the stop value), not on a budget
// or a failure.
bool converged(nlopt_result code);
bool out_of_evaluations(nlopt_result code);  // max_evaluations or max_simulations
bool out_of_time(nlopt_result code);

}  // namespace cueplan::planner::detail
