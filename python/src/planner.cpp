// cueplan._core's planner: plan one problem, plan many over threads, and the spin map.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <string>
#include <vector>

#include "core.hpp"
#include "cueplan/api/errors.hpp"
#include "cueplan/api/field_names.hpp"
#include "cueplan/api/options.hpp"
#include "cueplan/parallel.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/planner/spin_map.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::python {
namespace {

namespace phys = cueplan::physics;
namespace prob = cueplan::problems;
namespace plan = cueplan::planner;

// PlannerOptions' members as the Python keywords name them.
std::string keyword_of(const phys::FieldPath& path) {
  const std::string text = path.text();
  if (text == "max_time_s") return "max_time";
  if (text == "local_starts") return "starts";
  if (text == "robustness_samples") return "samples";
  if (text == "noise.scale") return "noise";
  if (text == "max_alternatives") return "alternatives";
  if (text == "global") return "global_method";
  if (text == "local") return "local_method";
  if (text == "simulation.impact_accuracy") return "accuracy";
  if (text == "simulation.max_events") return "max_events";
  return text;
}

[[noreturn]] void raise_option(const phys::ValidationError& e) {
  const std::string field = keyword_of(e.field);
  throw InputError(e.message(field), field);
}

// A plan's or spin map's error: the problem's fields as the file names them (validate()
// names them as Problem's members), the options' as the keywords.
[[noreturn]] void raise_result(const std::optional<phys::ValidationError>& e, const std::string& message) {
  if (!e) throw InputError(message, "");
  static const char* problem_members[] = {"scene", "cue_ball", "target", "tolerance", "limits",
                                          "pot", "first_contact", "next", "max_strokes", "time_budget_s"};
  const auto& steps = e->field.steps();
  if (!steps.empty() && std::holds_alternative<std::string>(steps[0]))
    for (const char* member : problem_members)
      if (std::get<std::string>(steps[0]) == member)
        throw InputError(prob::file_message(*e), prob::file_field(e->field));
  raise_option(*e);
}

struct Options {
  plan::PlannerOptions planner;
};

// PlannerOptions' fields as the Python keywords name them: how the api's validator
// names its errors here.
const std::initializer_list<api::FieldName> kKeywordNames = {
    {{"global"}, "global_method"},
    {{"local"}, "local_method"},
    {{"max_evaluations"}, "max_evaluations"},
    {{"max_time_s"}, "max_time"},
    {{"local_starts"}, "starts"},
    {{"seed"}, "seed"},
    {{"threads"}, "threads"},
    {{"noise", "scale"}, "noise"},
    {{"robust"}, "robust"},
    {{"robustness_samples"}, "samples"},
    {{"enforce_rigid_limit"}, "enforce_rigid_limit"},
    {{"max_alternatives"}, "alternatives"},
    {{"simulation", "impact_method"}, "method"},
    {{"simulation", "impact_accuracy"}, "accuracy"},
    {{"simulation", "max_events"}, "max_events"},
};

// The keywords checked by the api's one options validator (the command line's and the
// server's), its typed error raised as InputError with its field.
Options planner_options(uint64_t seed, int max_evaluations, double max_time, int starts, int samples,
                        double noise, bool robust, int alternatives, const std::string& global_method,
                        const std::string& local_method, bool enforce_rigid_limit, int threads) {
  api::PlannerArgs args;
  args.global = global_method;
  args.local = local_method;
  args.max_evaluations = max_evaluations;
  args.max_time_s = max_time;
  args.starts = starts;
  args.seed = seed;
  args.noise = noise;
  args.robust = robust;
  args.samples = samples;
  args.enforce_rigid_limit = enforce_rigid_limit;
  args.alternatives = alternatives;
  Options o;
  try {
    o.planner = api::planner_options(args, threads, phys::SimulationOptions{}, kKeywordNames);
  } catch (const api::InputError& e) {
    throw InputError(e.what(), e.field());
  }
  return o;
}

py::dict estimate(const plan::Estimate& e) {
  py::dict d;
  d["p"] = e.p;
  d["low"] = e.low;
  d["high"] = e.high;
  d["samples"] = e.samples;
  d["successes"] = e.successes;
  return d;
}

py::dict planned_shot(const prob::Problem& problem, const plan::PlannedShot& s) {
  py::dict d;
  d["speed"] = s.shot.speed;
  d["aim_deg"] = s.shot.aim_deg;
  d["topspin_k"] = s.shot.topspin_k;
  d["sidespin_k"] = s.shot.sidespin_k;
  d["elevation_deg"] = s.shot.elevation_deg;
  d["stroke_words"] = plan::describe_stroke(s.shot);
  d["outcome"] = phys::to_string(s.outcome);
  d["final_position"] = py::make_tuple(s.final_position.x, s.final_position.y);
  d["miss_distance"] = s.miss_distance;
  d["cushion_hits"] = s.cushion_hits;
  d["route"] = s.route;
  d["within_limits"] = s.within_limits;
  d["rigid_limit_exceeded"] = s.rigid_limit_exceeded;
  d["max_cushion_normal_speed"] = s.max_cushion_normal_speed;
  py::dict success;
  success["pot"] = s.success.pot ? py::object(estimate(*s.success.pot)) : py::object(py::none());
  success["position"] = estimate(s.success.position);
  success["both"] = estimate(s.success.both);
  success["next"] = s.success.next ? py::object(estimate(*s.success.next)) : py::object(py::none());
  d["success"] = success;
  d["success_probability"] = s.success_probability;
  d["family"] = s.family;
  d["solves"] = s.solves;
  d["violations"] = s.violations;
  d["failure"] = prob::to_string(s.failure);
  d["failure_reason"] = s.failure_reason;
  if (s.pot) {
    py::dict pot;
    pot["ball"] = s.pot->ball;
    pot["pocket"] = s.pot->pocket_name;
    pot["made"] = s.pot->made;
    pot["cut_deg"] = s.pot->cut_deg;
    pot["thickness"] = s.pot->thickness;
    pot["throw_deg"] = s.pot->throw_deg;
    pot["margin_m"] = s.pot->margin_m;
    pot["aim_margin_deg"] = s.pot->aim_margin_deg;
    d["pot"] = pot;
  } else {
    d["pot"] = py::none();
  }
  d["route_words"] = s.route_words;
  d["impact_method"] = phys::to_string(s.impact_method);
  (void)problem;
  return d;
}

py::dict plan_dict(const prob::Problem& problem, const plan::PlanResult& r) {
  py::dict d;
  d["name"] = problem.name;
  d["status"] = plan::to_string(r.status);
  d["message"] = r.message;
  d["best"] = planned_shot(problem, r.best);
  py::list alternatives;
  for (const auto& a : r.alternatives) alternatives.append(planned_shot(problem, a));
  d["alternatives"] = alternatives;
  d["evaluations"] = r.evaluations;
  d["time_s"] = r.time_s;
  d["local_searches"] = r.local_searches;
  d["converged_searches"] = r.converged_searches;
  d["ruled_out"] = r.ruled_out;
  return d;
}

plan::PlannerOptions with_simulation(const Options& options, const std::string& method,
                                     std::optional<double> accuracy, int max_events, const TableHandle* table) {
  plan::PlannerOptions p = options.planner;
  p.simulation = simulation_options(method, accuracy, max_events, table);
  if (const phys::Validation e = p.validate()) raise_option(*e);
  return p;
}

py::dict plan_one(const prob::Problem& problem, const Options& options, const std::string& method,
                  std::optional<double> accuracy, int max_events, const TableHandle* table) {
  const plan::PlannerOptions p = with_simulation(options, method, accuracy, max_events, table);
  plan::PlanResult r;
  {
    py::gil_scoped_release release;
    r = plan::plan(problem, p);
  }
  if (r.status == plan::PlanStatus::invalid_input) raise_result(r.error, r.message);
  return plan_dict(problem, r);
}

// Every problem planned, `threads` at a time (each plan on one thread); the results in
// the problems' order, the same for any thread count. A problem the planner refuses
// comes back with status invalid_input and its message, not as an exception. methods
// and tables: each problem's (a han_2005 cushion needs no table).
py::list plan_many(const std::vector<std::shared_ptr<prob::Problem>>& problems, const Options& options,
                   const std::vector<std::string>& methods, std::optional<double> accuracy, int max_events,
                   const std::vector<const TableHandle*>& tables, int threads) {
  if (tables.size() != problems.size() || methods.size() != problems.size())
    throw std::invalid_argument("one method and one table (or None) a problem");
  if (threads < 0)
    throw InputError(phys::invalid({}, "must be 0 (one per core) or more", threads).message("threads"), "threads");
  std::vector<plan::PlannerOptions> each;
  for (size_t i = 0; i < problems.size(); ++i) {
    each.push_back(with_simulation(options, methods[i], accuracy, max_events, tables[i]));
    each.back().threads = 1;
  }
  std::vector<plan::PlanResult> results(problems.size());
  {
    py::gil_scoped_release release;
    parallel_for(problems.size(), thread_count(threads, problems.size()),
                 [&](size_t i, unsigned) { results[i] = plan::plan(*problems[i], each[i]); });
  }
  py::list out;
  for (size_t i = 0; i < problems.size(); ++i) out.append(plan_dict(*problems[i], results[i]));
  return out;
}

py::dict spin_map(const prob::Problem& problem, double speed, double aim_deg, int grid, double spin_max,
                  int threads, const std::string& method, std::optional<double> accuracy, int max_events,
                  const TableHandle* table) {
  plan::SpinMapOptions options;
  options.grid = grid;
  options.spin_max = spin_max;
  options.threads = static_cast<int>(thread_count(threads));
  options.simulation = simulation_options(method, accuracy, max_events, table);
  if (threads < 0)
    throw InputError(phys::invalid({}, "must be 0 (one per core) or more", threads).message("threads"), "threads");
  if (const phys::Validation e = options.validate()) raise_option(*e);
  plan::SpinMap map;
  {
    py::gil_scoped_release release;
    map = plan::spin_map(problem, speed, aim_deg, options);
  }
  if (map.error || (map.points.empty() && !map.message.empty())) raise_result(map.error, map.message);
  const auto n = static_cast<py::ssize_t>(map.points.size());
  py::array_t<double> topspin(n), sidespin(n), x(n), y(n), miss(n), aim(n);
  py::array_t<bool> lands(n), pots(n);
  py::array_t<int32_t> cushions(n);
  py::list outcome;
  for (py::ssize_t i = 0; i < n; ++i) {
    const plan::SpinMapPoint& p = map.points[static_cast<size_t>(i)];
    topspin.mutable_at(i) = p.topspin_k;
    sidespin.mutable_at(i) = p.sidespin_k;
    x.mutable_at(i) = p.final_position.x;
    y.mutable_at(i) = p.final_position.y;
    miss.mutable_at(i) = p.miss_distance;
    aim.mutable_at(i) = p.aim_deg;
    lands.mutable_at(i) = p.lands;
    pots.mutable_at(i) = p.pots;
    cushions.mutable_at(i) = p.cushion_hits;
    outcome.append(phys::to_string(p.outcome));
  }
  py::dict cells;
  cells["topspin_k"] = topspin;
  cells["sidespin_k"] = sidespin;
  cells["final_x"] = x;
  cells["final_y"] = y;
  cells["miss_distance"] = miss;
  cells["cushion_hits"] = cushions;
  cells["lands"] = lands;
  cells["aim_deg"] = aim;
  cells["pots"] = pots;
  cells["outcome"] = outcome;
  py::dict d;
  d["speed"] = map.speed;
  d["aim_deg"] = map.aim_deg;
  d["spin_max"] = map.spin_max;
  d["grid"] = map.grid;
  d["landing"] = map.landing;
  d["not_potting"] = map.not_potting;
  d["cells"] = cells;
  return d;
}

}  // namespace

void bind_planner(py::module_& m) {
  py::class_<Options>(m, "PlannerOptions", "Checked planner options (planner/planner.hpp).");
  m.def("planner_options", &planner_options, py::arg("seed"), py::arg("max_evaluations"), py::arg("max_time"),
        py::arg("starts"), py::arg("samples"), py::arg("noise"), py::arg("robust"), py::arg("alternatives"),
        py::arg("global_method"), py::arg("local_method"), py::arg("enforce_rigid_limit"), py::arg("threads"));
  m.def("plan", &plan_one, py::arg("problem"), py::arg("options"), py::arg("method"),
        py::arg("accuracy").none(true), py::arg("max_events"), py::arg("table").none(true));
  m.def("plan_many", &plan_many, py::arg("problems"), py::arg("options"), py::arg("methods"),
        py::arg("accuracy").none(true), py::arg("max_events"), py::arg("tables"), py::arg("threads"));
  m.def("spin_map", &spin_map, py::arg("problem"), py::arg("speed"), py::arg("aim_deg"), py::arg("grid"),
        py::arg("spin_max"), py::arg("threads"), py::arg("method"), py::arg("accuracy").none(true),
        py::arg("max_events"), py::arg("table").none(true));
}

}  // namespace cueplan::python
