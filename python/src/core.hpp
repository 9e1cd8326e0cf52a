// The module cueplan._core: the C++ libraries (physics, problems, planner) bound for
// the pure-Python package python/cueplan/, which gives them typed signatures, defaults
// and docstrings. Nothing here parses command-line flags or JSON requests: the module
// sits beside the command line, on the same libraries.
//
// Every long call releases the GIL (py::gil_scoped_release) once its arguments are
// converted, so Python threads run while C++ computes. Bad input raises
// cueplan.InputError (a ValueError) whose `field` is taken from the libraries' typed
// errors (physics::ValidationError's path, or the problem loader's field name).
#pragma once

#include <pybind11/pybind11.h>

#include <exception>
#include <memory>
#include <optional>
#include <string>

#include "cueplan/physics/impact_table.hpp"
#include "cueplan/physics/shot.hpp"
#include "cueplan/physics/validation.hpp"

namespace cueplan::python {

namespace py = pybind11;

// Raised by the bindings; translated to cueplan.InputError with `field`.
struct InputError : std::exception {
  InputError(std::string message_in, std::string field_in)
      : message(std::move(message_in)), field(std::move(field_in)) {}
  const char* what() const noexcept override { return message.c_str(); }
  std::string message;
  std::string field;
};

// A library's broken rule as an InputError: the field is the path's text with `prefix`
// before it ("stroke." for a Shot's members), the message names it the same way.
[[noreturn]] void raise_invalid(const physics::ValidationError& error, const std::string& prefix = {});

// An impact table shared by the Python objects that use it.
struct TableHandle {
  std::shared_ptr<const physics::ImpactTable> table;
  std::string file;  // its cache file's name
};

// Simulation options from the Python keywords: method (table, exact, extrapolation,
// paper), accuracy (None: 1e-9, or with a table its measured error when larger),
// max_events. Raises InputError naming the keyword.
physics::SimulationOptions simulation_options(const std::string& method,
                                              std::optional<double> accuracy, int max_events,
                                              const TableHandle* table);

void bind_errors(py::module_& m);
void bind_physics(py::module_& m);
void bind_problems(py::module_& m);
void bind_planner(py::module_& m);

}  // namespace cueplan::python
