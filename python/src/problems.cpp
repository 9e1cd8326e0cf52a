// cueplan._core's problems: a problem loaded from a file or from YAML/JSON text by the
// problems library's loader (every default resolved, every field checked), its fields
// read back, and strokes simulated on its table.
#include <pybind11/stl.h>

#include <string>

#include "core.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/problems/problem.hpp"
#include "shot.hpp"

namespace cueplan::python {
namespace {

namespace phys = cueplan::physics;
namespace prob = cueplan::problems;
using ProblemPtr = std::shared_ptr<prob::Problem>;

ProblemPtr loaded(prob::LoadResult r) {
  if (!r.ok()) throw InputError(r.error, r.field.empty() ? "problem" : r.field);
  return std::make_shared<prob::Problem>(std::move(*r.problem));
}

ProblemPtr load_file(const std::string& path) {
  prob::LoadResult r;
  {
    py::gil_scoped_release release;
    r = prob::load_problem(path);
  }
  return loaded(std::move(r));
}

ProblemPtr parse_text(const std::string& text, const std::string& source) {
  prob::LoadResult r;
  {
    py::gil_scoped_release release;
    r = prob::parse_problem(text, source);
  }
  return loaded(std::move(r));
}

// A problem's broken rule in its file's words: field "table.length", "cue_ball", ...
[[noreturn]] void raise_problem(const phys::ValidationError& e) {
  throw InputError(prob::file_message(e), prob::file_field(e.field));
}

py::tuple xy(phys::Vec2 p) { return py::make_tuple(p.x, p.y); }

py::dict table_of(const prob::Problem& p) {
  const phys::Scene& s = p.scene;
  py::list pockets;
  for (size_t i = 0; i < s.pockets.size(); ++i) {
    py::dict d;
    d["name"] = prob::pocket_name(s, static_cast<int>(i));
    d["x"] = s.pockets[i].centre.x;
    d["y"] = s.pockets[i].centre.y;
    d["radius"] = s.pockets[i].radius;
    d["jawed"] = s.pockets[i].jaws.has_value();
    pockets.append(d);
  }
  py::dict t;
  t["length"] = s.length;
  t["width"] = s.width;
  t["cushion_height"] = s.ball_and_cushion.cushion_height;
  t["pockets"] = pockets;
  return t;
}

py::dict physics_of(const prob::Problem& p) {
  const phys::Scene& s = p.scene;
  py::dict d;
  d["mu_slide"] = s.cloth.mu_slide;
  d["mu_roll"] = s.cloth.mu_roll;
  d["mu_spin"] = s.cloth.mu_spin;
  d["gravity"] = s.cloth.gravity;
  d["mu_cushion"] = s.ball_and_cushion.mu_cushion;
  d["restitution"] = s.ball_and_cushion.restitution;
  d["cushion_height"] = s.ball_and_cushion.cushion_height;
  d["cushion_model"] = phys::to_string(s.ball_and_cushion.model);
  d["mu_ball"] = s.ball_contact.mu_ball;
  d["ball_restitution"] = s.ball_contact.restitution;
  d["ball_model"] = phys::to_string(s.ball_contact.model);
  d["ball_friction"] = phys::to_string(s.ball_contact.friction);
  d["cue_end_mass"] = s.cue.end_mass;
  return d;
}

py::dict limits_of(const prob::Problem& p) {
  const prob::Limits& l = p.limits;
  py::dict d;
  d["speed"] = py::make_tuple(l.speed_min, l.speed_max);
  d["spin"] = l.spin_max;
  switch (l.aim.mode) {
    case prob::AimMode::free: d["aim_deg"] = "free"; break;
    case prob::AimMode::fixed: d["aim_deg"] = l.aim.lo_deg; break;
    case prob::AimMode::range: d["aim_deg"] = py::make_tuple(l.aim.lo_deg, l.aim.hi_deg); break;
  }
  d["cushions"] = py::make_tuple(l.cushions_min, l.cushions_max);
  d["elevation_deg"] = py::make_tuple(l.elevation_min_deg, l.elevation_max_deg);
  d["cushions_before_contact"] = py::make_tuple(l.cushions_before_contact_min, l.cushions_before_contact_max);
  d["object_cushions"] = py::make_tuple(l.object_cushions_min, l.object_cushions_max);
  return d;
}

}  // namespace

void bind_problems(py::module_& m) {
  py::class_<prob::Problem, ProblemPtr>(m, "Problem", "A checked problem (problems/problem.hpp).")
      .def_readonly("name", &prob::Problem::name)
      .def_readonly("source", &prob::Problem::source)
      .def_property_readonly("table", &table_of)
      .def_property_readonly("physics", &physics_of)
      .def_property_readonly("limits", &limits_of)
      .def_property_readonly("ball", [](const prob::Problem& p) {
        py::dict d;
        d["radius"] = p.scene.ball_and_cushion.radius;
        d["mass"] = p.scene.ball_and_cushion.mass;
        return d;
      })
      .def_property_readonly("cue_ball", [](const prob::Problem& p) { return xy(p.cue_ball); })
      .def_property_readonly("target", [](const prob::Problem& p) {
        return p.has_target ? py::object(xy(p.target)) : py::object(py::none());
      })
      .def_readonly("tolerance", &prob::Problem::tolerance)
      .def_property_readonly("balls", [](const prob::Problem& p) {
        py::list balls;
        for (const auto& b : p.scene.balls) balls.append(py::make_tuple(b.name, b.position.x, b.position.y));
        return balls;
      })
      .def_property_readonly("obstacles", [](const prob::Problem& p) {
        py::list out;
        for (const auto& o : p.scene.obstacles) out.append(xy(o));
        return out;
      })
      .def_property_readonly("pot", [](const prob::Problem& p) -> py::object {
        if (!p.pot) return py::none();
        py::dict d;
        d["ball"] = p.pot->ball;
        d["pocket"] = prob::pocket_name(p.scene, p.pot->pocket);
        return d;
      })
      .def_property_readonly("first_contact", [](const prob::Problem& p) -> py::object {
        const std::string ball = p.required_first_contact();
        return ball.empty() ? py::object(py::none()) : py::object(py::str(ball));
      })
      .def_property_readonly("next", [](const prob::Problem& p) {
        py::list out;
        for (const auto& n : p.next) {
          py::dict d;
          d["ball"] = n.ball;
          d["pocket"] = prob::pocket_name(p.scene, n.pocket);
          out.append(d);
        }
        return out;
      })
      .def_property_readonly("cushion_params", [](const prob::Problem& p) { return p.scene.ball_and_cushion; })
      .def("describe", [](const prob::Problem& p) { return prob::describe(p); })
      .def(
          "with_positions",
          [](const prob::Problem& p, std::optional<std::pair<double, double>> cue_ball,
             std::optional<std::pair<double, double>> target) {
            auto copy = std::make_shared<prob::Problem>(p);
            if (cue_ball) copy->cue_ball = {cue_ball->first, cue_ball->second};
            if (target) {
              copy->target = {target->first, target->second};
              copy->has_target = true;
            }
            if (const phys::Validation e = prob::validate(*copy)) raise_problem(*e);
            return copy;
          },
          py::arg("cue_ball").none(true), py::arg("target").none(true));

  m.def("load_problem", &load_file, py::arg("path"));
  m.def("parse_problem", &parse_text, py::arg("text"), py::arg("source"));

  m.def(
      "simulate",
      [](const prob::Problem& p, double speed, double aim_deg, double topspin_k, double sidespin_k,
         double elevation_deg, const std::string& method, std::optional<double> accuracy, int max_events,
         const TableHandle* table) {
        const phys::SimulationOptions options = simulation_options(method, accuracy, max_events, table);
        phys::Shot stroke;
        stroke.speed = speed;
        stroke.aim_deg = aim_deg;
        stroke.topspin_k = topspin_k;
        stroke.sidespin_k = sidespin_k;
        stroke.elevation_deg = elevation_deg;
        return simulate_stroke(p, stroke, options);
      },
      py::arg("problem"), py::arg("speed"), py::arg("aim_deg"), py::arg("topspin_k"), py::arg("sidespin_k"),
      py::arg("elevation_deg"), py::arg("method"), py::arg("accuracy").none(true), py::arg("max_events"),
      py::arg("table").none(true));

  m.def("describe_stroke", [](double speed, double aim_deg, double topspin_k, double sidespin_k,
                              double elevation_deg) {
    phys::Shot s;
    s.speed = speed;
    s.aim_deg = aim_deg;
    s.topspin_k = topspin_k;
    s.sidespin_k = sidespin_k;
    s.elevation_deg = elevation_deg;
    return planner::describe_stroke(s);
  });
}

}  // namespace cueplan::python
