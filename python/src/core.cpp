// cueplan._core: the module's entry point, its error type, impact tables and the
// simulation options every computation shares (core.hpp).
#include "core.hpp"

#include <cmath>
#include <filesystem>
#include <system_error>

namespace cueplan::python {
namespace {

// cueplan.InputError, made when the module is imported and kept for the life of the
// interpreter (the module holds it as an attribute too).
PyObject* input_error_type = nullptr;

// Loads the table for `params` from `cache_dir` (the file ImpactTable::cache_file_name
// names), or builds it there when it is missing or unusable. "" for cache_dir: built
// and not kept.
TableHandle load_or_build_table(const physics::CushionParams& params, const std::string& cache_dir,
                                int threads) {
  if (const physics::Validation e = params.validate()) raise_invalid(*e);
  if (params.model != physics::CushionModel::mathavan_2010)
    throw InputError("the impact table is the mathavan_2010 model's; model " +
                         std::string(physics::to_string(params.model)) +
                         " resolves every impact in closed form",
                     "model");
  physics::ImpactTableOptions options;
  options.threads = threads;
  TableHandle handle;
  handle.file = physics::ImpactTable::cache_file_name(params, options);
  std::optional<physics::ImpactTable> table;
  {
    py::gil_scoped_release release;
    const std::filesystem::path path = std::filesystem::path(cache_dir) / handle.file;
    if (!cache_dir.empty()) {
      table = physics::ImpactTable::load(path.string());
      if (table && !(table->covers(params) && table->built_with(options))) table.reset();
    }
    if (!table) {
      table = physics::ImpactTable::build(params, options);
      if (!table->empty() && !cache_dir.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(cache_dir, ec);
        table->save(path.string());  // a cache: when it cannot be written, the table still serves
      }
    }
  }
  if (table->empty()) throw std::runtime_error("the impact table could not be built");
  handle.table = std::make_shared<const physics::ImpactTable>(std::move(*table));
  return handle;
}

}  // namespace

void raise_invalid(const physics::ValidationError& error, const std::string& prefix) {
  const std::string field = prefix + error.field.text();
  const std::string other = error.other ? prefix + error.other->text() : std::string();
  throw InputError(error.message(field, other), field);
}

physics::SimulationOptions simulation_options(const std::string& method,
                                              std::optional<double> accuracy, int max_events,
                                              const TableHandle* table) {
  physics::SimulationOptions options;
  if (!physics::parse_method(method, &options.impact_method))
    throw InputError("method must be one of table, exact, extrapolation, paper, got '" + method + "'",
                     "method");
  if (accuracy && (!std::isfinite(*accuracy) || !(*accuracy >= 1e-12) || !(*accuracy <= 0.1)))
    throw InputError(physics::invalid({}, "must lie in [1e-12, 0.1]", *accuracy).message("accuracy"),
                     "accuracy");
  if (max_events < 1)
    throw InputError(physics::invalid({}, "must be at least 1", max_events).message("max_events"),
                     "max_events");
  options.max_events = max_events;
  if (accuracy) options.impact_accuracy = *accuracy;
  if (options.impact_method == physics::ImpactMethod::table) {
    if (table == nullptr || !table->table)
      throw InputError("method 'table' needs an impact table", "method");
    options.table = table->table.get();
    // Without an accuracy the table's own measured error is it (as the command line does).
    const double measured = table->table->measured_error().max_state_relative;
    if (!accuracy) options.impact_accuracy = std::max(options.impact_accuracy, measured);
  }
  return options;
}

void bind_errors(py::module_& m) {
  input_error_type = PyErr_NewExceptionWithDoc(
      "cueplan.InputError",
      "Bad input. A ValueError whose message names the input and whose `field` is its name: "
      "a keyword (angle, mu_cushion, max_time), a problem file's field (table.length, "
      "cue_ball, limits.speed[1]) or a stroke's (stroke.speed).",
      PyExc_ValueError, nullptr);
  m.attr("InputError") = py::reinterpret_borrow<py::object>(input_error_type);
  // Raised from Python without one (InputError("...")), `field` reads None.
  m.attr("InputError").attr("field") = py::none();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      py::object error = py::reinterpret_borrow<py::object>(input_error_type)(e.message);
      error.attr("field") = e.field.empty() ? py::object(py::none()) : py::object(py::str(e.field));
      PyErr_SetObject(input_error_type, error.ptr());
    }
  });
}

}  // namespace cueplan::python

PYBIND11_MODULE(_core, m) {
  namespace cp = cueplan::python;
  namespace py = pybind11;
  m.doc() = "cueplan's C++ libraries (physics, problems, planner); use the package cueplan.";
  cp::bind_errors(m);

  py::class_<cp::TableHandle>(m, "ImpactTable",
                              "A precomputed surrogate of the cushion impact (physics/impact_table.hpp).")
      .def_property_readonly("file", [](const cp::TableHandle& t) { return t.file; })
      .def_property_readonly("measured_error", [](const cp::TableHandle& t) {
        const auto& e = t.table->measured_error();
        py::dict d;
        d["max_speed_relative"] = e.max_speed_relative;
        d["max_angle_deg"] = e.max_angle_deg;
        d["max_state_relative"] = e.max_state_relative;
        d["cells"] = e.cells;
        d["fallback_cells"] = e.fallback_cells;
        return d;
      });
  m.def("load_or_build_table", &cp::load_or_build_table, py::arg("params"), py::arg("cache_dir"),
        py::arg("threads") = 0);

  cp::bind_physics(m);
  cp::bind_problems(m);
  cp::bind_planner(m);
}
