// NLopt runs: algorithms, bounds and stopping rules.
#include "nlopt_stage.hpp"

namespace cueplan::planner::detail {
namespace {

struct OptDeleter {
  void operator()(nlopt_opt o) const { nlopt_destroy(o); }
};
using Opt = std::unique_ptr<std::remove_pointer_t<nlopt_opt>, OptDeleter>;

// The objective with a budget of simulations: NLopt calls this, it calls the objective
// and stops the run once the simulations are spent.
struct Budgeted {
  nlopt_func f;
  void* data;
  nlopt_opt opt;
  const int* simulations;
  int max_simulations;
};
double budgeted_call(unsigned n, const double* x, double* grad, void* data) {
  Budgeted& b = *static_cast<Budgeted*>(data);
  const double value = b.f(n, x, grad, b.data);
  if (*b.simulations >= b.max_simulations) nlopt_force_stop(b.opt);
  return value;
}

}  // namespace

nlopt_algorithm nlopt_global(GlobalMethod method) {
  switch (method) {
    case GlobalMethod::direct_l: return NLOPT_GN_DIRECT_L;
    case GlobalMethod::crs2: return NLOPT_GN_CRS2_LM;
    case GlobalMethod::mlsl: return NLOPT_G_MLSL_LDS;
    case GlobalMethod::isres: return NLOPT_GN_ISRES;
    case GlobalMethod::ompl_kpiece1: break;  // not an NLopt method (ompl_stage.hpp)
  }
  return NLOPT_GN_CRS2_LM;
}

nlopt_algorithm nlopt_local(LocalMethod method) {
  switch (method) {
    case LocalMethod::bobyqa: return NLOPT_LN_BOBYQA;
    case LocalMethod::sbplx: return NLOPT_LN_SBPLX;
    case LocalMethod::cobyla: return NLOPT_LN_COBYLA;
    case LocalMethod::neldermead: return NLOPT_LN_NELDERMEAD;
  }
  return NLOPT_LN_SBPLX;
}

nlopt_result run_stage(const StageSettings& s, std::vector<double>* x, nlopt_func f, void* data) {
  const unsigned n = static_cast<unsigned>(x->size());
  Opt opt(nlopt_create(s.algorithm, n));
  if (!opt) return NLOPT_FAILURE;
  const std::vector<double> lower(n, 0.0), upper(n, 1.0);
  nlopt_set_lower_bounds(opt.get(), lower.data());
  nlopt_set_upper_bounds(opt.get(), upper.data());
  Budgeted budgeted{f, data, opt.get(), s.simulations, s.max_simulations};
  if (s.simulations != nullptr)
    nlopt_set_min_objective(opt.get(), &budgeted_call, &budgeted);
  else
    nlopt_set_min_objective(opt.get(), f, data);
  nlopt_set_maxeval(opt.get(), s.max_evaluations);
  if (s.max_time_s > 0.0) nlopt_set_maxtime(opt.get(), s.max_time_s);
  nlopt_set_stopval(opt.get(), s.stop_value);
  if (s.x_tolerance > 0.0) nlopt_set_xtol_abs1(opt.get(), s.x_tolerance);
  if (s.f_tolerance > 0.0) nlopt_set_ftol_abs(opt.get(), s.f_tolerance);
  if (s.initial_step > 0.0) nlopt_set_initial_step1(opt.get(), s.initial_step);
  if (s.algorithm == NLOPT_G_MLSL_LDS) {
    Opt inner(nlopt_create(s.inner, n));
    if (!inner) return NLOPT_FAILURE;
    nlopt_set_maxeval(inner.get(), s.inner_max_evaluations);
    if (s.inner_x_tolerance > 0.0) nlopt_set_xtol_abs1(inner.get(), s.inner_x_tolerance);
    if (s.inner_f_tolerance > 0.0) nlopt_set_ftol_abs(inner.get(), s.inner_f_tolerance);
    if (s.inner_step > 0.0) nlopt_set_initial_step1(inner.get(), s.inner_step);
    nlopt_set_local_optimizer(opt.get(), inner.get());  // NLopt keeps its own copy
  }
  for (double& u : *x) u = std::isfinite(u) ? std::fmin(1.0, std::fmax(0.0, u)) : 0.5;
  double value = 0.0;
  return nlopt_optimize(opt.get(), x->data(), &value);
}

bool converged(nlopt_result code) {
  return code == NLOPT_SUCCESS || code == NLOPT_STOPVAL_REACHED || code == NLOPT_FTOL_REACHED ||
         code == NLOPT_XTOL_REACHED || code == NLOPT_ROUNDOFF_LIMITED;
}
bool out_of_evaluations(nlopt_result code) {
  return code == NLOPT_MAXEVAL_REACHED || code == NLOPT_FORCED_STOP;
}
bool out_of_time(nlopt_result code) { return code == NLOPT_MAXTIME_REACHED; }

}  // namespace cueplan::planner::detail
