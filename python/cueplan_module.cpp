// The Python module `cueplan`: the command line's computations as functions that return
// the command line's own `--json` objects as dicts.
//
//   rebound(speed, angle, **flags)      cueplan rebound --json     (flags: topspin_k=1, ...)
//   collide(speed, cut, **flags)        cueplan collide --json
//   simulate(problem, stroke, **opts)   cueplan simulate --json    (opts: method, accuracy,
//                                                                   max_events)
//   solve(problem, **opts)              cueplan solve --json       (opts: seed, max_time,
//                                                                   max_evaluations, ...)
//   spin_map(problem, speed=None, aim_deg=None, grid=None, **opts)
//                                       cueplan spinmap --json, plus `cells`
//   read_problem(path)                  a problem file's fields as a dict
//
// rebound and collide run the commands themselves (cli_main.hpp), their flags named by
// the keywords (topspin_k=1 is --topspin-k 1); simulate, solve and spin_map are the JSON
// API of `cueplan serve` (serve_api.hpp), whose options are the flags' names without the
// dashes. Either way the dicts are built by the commands' functions (rebound_json,
// collide's JSON, simulate_json, solve_json, spinmap_json), so their keys are the
// command line's. A problem is a dict of the problem file's fields or the path of a YAML
// file. `path` (a ball's path segments) and `cells` (the spin map's grid) come as dicts
// of numpy columns: t0 (n,), p0 (n, 2), ... Bad input raises cueplan.InputError (a
// ValueError) whose message and `field` name the argument. The GIL is released while
// C++ computes, so Python threads run in parallel.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_main.hpp"
#include "cueplan/problems/problem.hpp"
#include "serve_api.hpp"
#include "serve_problems.hpp"
#include "serve_tables.hpp"
#include "cueplan/api/table_cache.hpp"

namespace py = pybind11;

namespace {

namespace cli = cueplan::cli;
namespace prob = cueplan::problems;
using nlohmann::ordered_json;

// A bad argument: raised in Python as cueplan.InputError with its `field`.
struct InputError {
  std::string message;
  std::string field;
};

// cueplan.InputError, made when the module is imported; the module holds the reference.
PyObject* input_error_type = nullptr;

[[noreturn]] void raise_input_error(const InputError& e) {
  py::object error = py::reinterpret_borrow<py::object>(input_error_type)(e.message);
  error.attr("field") = e.field.empty() ? py::none() : py::object(py::str(e.field));
  PyErr_SetObject(input_error_type, error.ptr());
  throw py::error_already_set();
}

// ---------------------------------------------------------------------------
// Python values to JSON and back

ordered_json to_json(py::handle value, const std::string& where) {
  if (value.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) {
    try {
      return value.cast<int64_t>();
    } catch (const py::cast_error&) {
      try {
        return value.cast<uint64_t>();
      } catch (const py::cast_error&) {
        raise_input_error({where + " is too large a whole number: " + py::repr(value).cast<std::string>(), where});
      }
    }
  }
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::dict>(value)) {
    ordered_json object = ordered_json::object();
    for (const auto& [key, item] : value.cast<py::dict>()) {
      if (!py::isinstance<py::str>(key))
        raise_input_error({where + " must have string keys, got " + py::repr(key).cast<std::string>(), where});
      const std::string name = key.cast<std::string>();
      object[name] = to_json(item, where.empty() ? name : where + "." + name);
    }
    return object;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    ordered_json array = ordered_json::array();
    size_t i = 0;
    for (py::handle item : value) array.push_back(to_json(item, where + "[" + std::to_string(i++) + "]"));
    return array;
  }
  if (py::hasattr(value, "tolist")) return to_json(value.attr("tolist")(), where);  // numpy
  raise_input_error({where + " must be a number, string, bool, list or dict, got " +
                         py::repr(py::type::of(value)).cast<std::string>(),
                     where});
}

py::object to_python(const ordered_json& j, const std::string& key);

// Rows of objects (path segments, spin-map cells) as columns: numbers as a numpy array,
// pairs and triples of numbers as an (n, k) one, anything else as a list.
py::dict columns(const ordered_json& rows) {
  std::vector<std::string> keys;
  for (const ordered_json& row : rows)
    for (const auto& [key, value] : row.items())
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  py::dict out;
  const size_t n = rows.size();
  for (const std::string& key : keys) {
    bool numbers = true, integers = true, booleans = true, vectors = true;
    size_t width = 0;
    for (const ordered_json& row : rows) {
      const auto it = row.find(key);
      const bool present = it != row.end();
      numbers = numbers && present && it->is_number();
      integers = integers && present && it->is_number_integer();
      booleans = booleans && present && it->is_boolean();
      bool vector = present && it->is_array() && !it->empty();
      if (vector) {
        for (const ordered_json& x : *it) vector = vector && x.is_number();
        if (width == 0) width = it->size();
        vector = vector && it->size() == width;
      }
      vectors = vectors && vector;
    }
    if (numbers && integers) {
      py::array_t<int64_t> a(static_cast<py::ssize_t>(n));
      for (size_t i = 0; i < n; ++i) a.mutable_at(i) = rows[i][key].get<int64_t>();
      out[py::str(key)] = a;
    } else if (numbers) {
      py::array_t<double> a(static_cast<py::ssize_t>(n));
      for (size_t i = 0; i < n; ++i) a.mutable_at(i) = rows[i][key].get<double>();
      out[py::str(key)] = a;
    } else if (booleans) {
      py::array_t<bool> a(static_cast<py::ssize_t>(n));
      for (size_t i = 0; i < n; ++i) a.mutable_at(i) = rows[i][key].get<bool>();
      out[py::str(key)] = a;
    } else if (vectors) {
      py::array_t<double> a({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(width)});
      for (size_t i = 0; i < n; ++i)
        for (size_t k = 0; k < width; ++k) a.mutable_at(i, k) = rows[i][key][k].get<double>();
      out[py::str(key)] = a;
    } else {
      py::list list;
      for (const ordered_json& row : rows) {
        const auto it = row.find(key);
        list.append(it == row.end() ? py::none() : to_python(*it, key));
      }
      out[py::str(key)] = list;
    }
  }
  return out;
}

py::object to_python(const ordered_json& j, const std::string& key) {
  switch (j.type()) {
    case ordered_json::value_t::null: return py::none();
    case ordered_json::value_t::boolean: return py::bool_(j.get<bool>());
    case ordered_json::value_t::number_integer: return py::int_(j.get<int64_t>());
    case ordered_json::value_t::number_unsigned: return py::int_(j.get<uint64_t>());
    case ordered_json::value_t::number_float: return py::float_(j.get<double>());
    case ordered_json::value_t::string: return py::str(j.get<std::string>());
    case ordered_json::value_t::object: {
      py::dict d;
      for (const auto& [k, v] : j.items()) d[py::str(k)] = to_python(v, k);
      return d;
    }
    case ordered_json::value_t::array: {
      if (key == "path" || key == "cells") {
        bool rows = true;
        for (const ordered_json& x : j) rows = rows && x.is_object();
        if (rows) return columns(j);
      }
      py::list list;
      for (const ordered_json& x : j) list.append(to_python(x, ""));
      return list;
    }
    default: return py::none();
  }
}

// ---------------------------------------------------------------------------
// rebound and collide: the commands themselves

// A flag's name as the keyword that sets it: --topspin-k is topspin_k.
std::string keyword_of_flags(const std::string& text) {
  static const std::regex flag("--([a-z][a-z0-9]*(?:-[a-z0-9]+)*)");
  std::string out;
  auto begin = std::sregex_iterator(text.begin(), text.end(), flag);
  size_t last = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    out += text.substr(last, static_cast<size_t>(it->position()) - last);
    std::string name = (*it)[1].str();
    std::replace(name.begin(), name.end(), '-', '_');
    out += name;
    last = static_cast<size_t>(it->position() + it->length());
  }
  return out + text.substr(last);
}

// A keyword's value as the flag's text (floats as Python writes them: shortest exact).
std::string flag_text(py::handle value) {
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value) ||
      py::hasattr(value, "tolist")) {
    py::object items = py::hasattr(value, "tolist") ? value.attr("tolist")() : py::reinterpret_borrow<py::object>(value);
    if (py::isinstance<py::list>(items) || py::isinstance<py::tuple>(items)) {
      std::string text;
      for (py::handle x : items) text += (text.empty() ? "" : ",") + flag_text(x);
      return text;
    }
    return flag_text(items);
  }
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  return py::repr(value).cast<std::string>();
}

py::object run_command(const char* command, std::vector<const char*> positional_names,
                       const py::args& args, const py::kwargs& kwargs) {
  std::vector<std::string> argv = {"cueplan", command, "--json"};
  if (args.size() > positional_names.size())
    raise_input_error({std::string(command) + " takes at most " +
                           std::to_string(positional_names.size()) +
                           " arguments by position; give the others by name",
                       ""});
  const auto add = [&](const std::string& name, py::handle value) {
    for (const char* refused : {"json", "batch", "threads", "help", "version"})
      if (name == refused)
        raise_input_error({name + " is a command-line flag only; the module returns one dict", name});
    if (value.is_none()) return;
    std::string flag = "--" + name;
    std::replace(flag.begin(), flag.end(), '_', '-');
    if (py::isinstance<py::bool_>(value)) {
      if (value.cast<bool>()) argv.push_back(flag);
      return;
    }
    argv.push_back(flag);
    argv.push_back(flag_text(value));
  };
  for (size_t i = 0; i < args.size(); ++i) add(positional_names[i], args[i]);
  for (const auto& [key, value] : kwargs) add(key.cast<std::string>(), value);

  std::ostringstream out, err;
  int code = 0;
  {
    py::gil_scoped_release release;
    std::vector<const char*> pointers;
    for (const std::string& a : argv) pointers.push_back(a.c_str());
    code = cli::run_cli(static_cast<int>(pointers.size()), pointers.data(), out, err);
  }
  if (code == 2) {
    std::string why = err.str();
    const std::string prefix = std::string("cueplan ") + command + ": ";
    if (why.rfind(prefix, 0) == 0) why.erase(0, prefix.size());
    while (!why.empty() && why.back() == '\n') why.pop_back();
    std::smatch m;
    const std::string named = keyword_of_flags(why);
    std::string field;
    if (std::regex_search(why, m, std::regex("--([a-z][a-z0-9-]*)"))) field = keyword_of_flags(m[0].str());
    raise_input_error({named, field});
  }
  ordered_json j;
  try {
    j = ordered_json::parse(out.str());
  } catch (const ordered_json::parse_error&) {
    throw std::runtime_error(std::string("cueplan ") + command + " gave no result: " + err.str());
  }
  return to_python(j, "");
}

// ---------------------------------------------------------------------------
// simulate, solve, spin_map: the JSON API

struct Engine {
  static cli::ImpactTableStore::Settings store_settings() {
    cli::ImpactTableStore::Settings s;
    s.cache_dir = cli::default_table_cache_dir();
    s.max_tables = 64;
    return s;
  }
  static cli::ApiLimits no_limits() {
    cli::ApiLimits l;
    const int most = std::numeric_limits<int>::max();
    l.max_time_s = std::numeric_limits<double>::infinity();
    l.max_evaluations = most;
    l.max_starts = most;
    l.max_samples = most;
    l.max_alternatives = most;
    l.max_grid = 1001;
    l.max_events = most;
    return l;
  }

  cli::ImpactTableStore tables{store_settings()};
  cli::Api api{no_limits(), "table", &tables, {}};
};

Engine& engine() {
  static Engine e;  // made on first use, shared by every thread (the Api is thread-safe)
  return e;
}

// A problem argument: a dict of the problem file's fields, or a YAML file's path.
struct ProblemArgument {
  ordered_json fields;
  std::string path;  // when given as a file
};

ProblemArgument problem_argument(py::handle problem) {
  ProblemArgument a;
  if (py::isinstance<py::dict>(problem)) {
    a.fields = to_json(problem, "problem");
    return a;
  }
  if (!py::isinstance<py::str>(problem) && !py::hasattr(problem, "__fspath__"))
    raise_input_error({"problem must be a dict of the problem file's fields or a YAML file's path, got " +
                           py::repr(py::type::of(problem)).cast<std::string>(),
                       "problem"});
  a.path = py::module_::import("os").attr("fspath")(problem).cast<std::string>();
  const prob::LoadResult loaded = prob::load_problem(a.path);
  if (!loaded.ok())
    raise_input_error({loaded.error, loaded.field.empty() ? "problem" : "problem." + loaded.field});
  std::ifstream in(a.path);
  std::stringstream text;
  text << in.rdbuf();
  std::string why;
  std::optional<ordered_json> fields = cli::problem_yaml_to_json(text.str(), &why);
  if (!fields) raise_input_error({a.path + ": " + why, "problem"});
  a.fields = std::move(*fields);
  // Named as the command line names it: the file's name, or its stem.
  if (!a.fields.contains("name")) a.fields["name"] = loaded.problem->name;
  return a;
}

// Without the API's prefix for options: max_time, not options.max_time.
std::string in_keywords(std::string text) {
  for (size_t at = text.find("options."); at != std::string::npos; at = text.find("options.", at))
    text.erase(at, 8);
  return text;
}

using Endpoint = cli::ApiReply (cli::Api::*)(std::string_view) const;

py::object call_api(Endpoint endpoint, ordered_json request, const ProblemArgument& problem) {
  request["problem"] = problem.fields;
  const std::string body = request.dump();
  const ordered_json* options = request.contains("options") ? &request["options"] : nullptr;
  const bool table =
      !options || !options->contains("method") || (*options)["method"] == ordered_json("table");
  cli::ApiReply reply;
  {
    py::gil_scoped_release release;
    Engine& e = engine();
    // The table for the problem's cushion is waited for, not answered 503.
    if (table) {
      const cli::ProblemFromJson loaded = cli::problem_from_json(problem.fields, "problem");
      if (loaded.problem) e.tables.wait_for(loaded.problem->scene.ball_and_cushion);
    }
    reply = (e.api.*endpoint)(body);
  }
  if (reply.status == 400 || reply.status == 413 || reply.status == 422) {
    const ordered_json& field = reply.body["field"];
    raise_input_error({in_keywords(reply.body["error"].get<std::string>()),
                       field.is_string() ? in_keywords(field.get<std::string>()) : ""});
  }
  if (reply.status != 200)
    throw std::runtime_error(reply.body.value("error", std::string("the computation failed")));
  if (!problem.path.empty() && reply.body.contains("problem"))
    reply.body["problem"]["source"] = problem.path;
  return to_python(reply.body, "");
}

ordered_json options_of(const py::kwargs& kwargs) {
  ordered_json options = ordered_json::object();
  for (const auto& [key, value] : kwargs) {
    const std::string name = key.cast<std::string>();
    options[name] = to_json(value, name);
  }
  return options;
}

py::object simulate(py::handle problem, py::handle stroke, const py::kwargs& kwargs) {
  const ProblemArgument p = problem_argument(problem);
  ordered_json s;
  if (py::isinstance<py::dict>(stroke)) {
    s = to_json(stroke, "stroke");
  } else if (py::isinstance<py::list>(stroke) || py::isinstance<py::tuple>(stroke) ||
             py::hasattr(stroke, "tolist")) {
    const ordered_json values = to_json(stroke, "stroke");
    const char* names[] = {"speed", "aim_deg", "topspin_k", "sidespin_k"};
    if (!values.is_array() || values.size() < 2 || values.size() > 4)
      raise_input_error({"stroke must be {speed, aim_deg, topspin_k, sidespin_k} or 2 to 4 numbers "
                         "in that order",
                         "stroke"});
    s = ordered_json::object();
    for (size_t i = 0; i < values.size(); ++i) s[names[i]] = values[i];
  } else {
    raise_input_error({"stroke must be a dict {speed, aim_deg, topspin_k, sidespin_k} or a sequence",
                       "stroke"});
  }
  return call_api(&cli::Api::simulate, {{"stroke", s}, {"options", options_of(kwargs)}}, p);
}

py::object solve(py::handle problem, const py::kwargs& kwargs) {
  return call_api(&cli::Api::solve, {{"options", options_of(kwargs)}}, problem_argument(problem));
}

py::object spin_map(py::handle problem, py::handle speed, py::handle aim_deg, py::handle grid,
                    const py::kwargs& kwargs) {
  ordered_json request = {{"options", options_of(kwargs)}};
  if (!speed.is_none()) request["speed"] = to_json(speed, "speed");
  if (!aim_deg.is_none()) request["aim_deg"] = to_json(aim_deg, "aim_deg");
  if (!grid.is_none()) request["grid"] = to_json(grid, "grid");
  return call_api(&cli::Api::spinmap, request, problem_argument(problem));
}

}  // namespace

PYBIND11_MODULE(cueplan, m) {
  m.doc() =
      "cueplan: cue-sports shot planning on the Mathavan-Jackson-Parkin cushion-impact model. "
      "Each function returns the dict the command line's --json prints.";
  input_error_type =
      PyErr_NewExceptionWithDoc("cueplan.InputError",
                                "Bad input; the message names it, and `field` is its name "
                                "(problem.table.length, stroke.speed, max_time, angle, ...).",
                                PyExc_ValueError, nullptr);
  m.attr("InputError") = py::reinterpret_steal<py::object>(input_error_type);

  m.def(
      "read_problem",
      [](py::handle path) { return to_python(problem_argument(path).fields, ""); },
      py::arg("path"),
      "read_problem(path) -> dict: a YAML problem file's fields, checked by the loader (as "
      "the functions take a problem), with its `name`");
  m.def(
      "rebound",
      [](const py::args& args, const py::kwargs& kwargs) {
        return run_command("rebound", {"speed", "angle"}, args, kwargs);
      },
      "rebound(speed, angle, **flags) -> dict: `cueplan rebound --json`; flags by their "
      "names, topspin_k=1, sidespin_k=0, method='exact', mu_cushion=0.14, ...");
  m.def(
      "collide",
      [](const py::args& args, const py::kwargs& kwargs) {
        return run_command("collide", {"speed", "cut"}, args, kwargs);
      },
      "collide(speed, cut, **flags) -> dict: `cueplan collide --json`; flags by their names, "
      "topspin_k=1, spin=(wx, wy, wz), model='mathavan_2014', ...");
  m.def("simulate", &simulate, py::arg("problem"), py::arg("stroke"),
        "simulate(problem, stroke, **options) -> dict: `cueplan simulate --json`. problem: a "
        "dict of the problem file's fields or a YAML path; stroke: {speed, aim_deg, topspin_k, "
        "sidespin_k} or (speed, aim_deg[, topspin_k[, sidespin_k]]); options method, accuracy, "
        "max_events. `path` comes as numpy columns.");
  m.def("solve", &solve, py::arg("problem"),
        "solve(problem, **options) -> dict: `cueplan solve --json`; options as the flags: seed, "
        "max_time, max_evaluations, starts, samples, noise, robust, alternatives, global, "
        "local, method, accuracy, enforce_rigid_limit. One thread a call.");
  m.def("spin_map", &spin_map, py::arg("problem"), py::arg("speed") = py::none(),
        py::arg("aim_deg") = py::none(), py::arg("grid") = py::none(),
        "spin_map(problem, speed=None, aim_deg=None, grid=None, **options) -> dict: `cueplan "
        "spinmap --json` plus `cells`, the grid's spins as numpy columns (topspin_k, "
        "sidespin_k, final_position (n, 2), miss_distance, lands, ...). Without speed and aim, "
        "the planner's stroke (options as solve's).");
}
