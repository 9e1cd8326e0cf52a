// cueplan._core's physics: cushion impacts and ball collisions over numpy columns (the
// batch path: resolve_impacts in SIMD lanes, rows spread over threads), one stroke
// simulated on a problem's table, and its trajectory sampled at a fixed interval.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "core.hpp"
#include "cueplan/parallel.hpp"
#include "cueplan/physics/ball_collision.hpp"
#include "cueplan/physics/cushion_impact.hpp"
#include "cueplan/physics/trace.hpp"
#include "cueplan/problems/problem.hpp"
#include "shot.hpp"

namespace cueplan::python {
namespace {

namespace phys = cueplan::physics;
using Column = py::array_t<double, py::array::c_style | py::array::forcecast>;

constexpr double kDegree = std::numbers::pi / 180.0;
// Rows per piece of work: enough for the SIMD lanes to stay full, small enough to
// spread over the threads (as the command line's batch).
constexpr size_t kChunk = 256;

// The options' field names as the Python keywords spell them.
std::string keyword_of(const phys::ValidationError& e) {
  const std::string text = e.field.text();
  if (text == "paper_steps") return "steps";
  return text;
}

[[noreturn]] void raise_option(const phys::ValidationError& e) {
  const std::string field = keyword_of(e);
  throw InputError(e.message(field), field);
}

// A bad row of a column: "angle[3] must lie in (0, 180) degrees, got 190" (or without
// the index for a single value).
[[noreturn]] void raise_row(const char* name, size_t row, bool scalar, const char* rule, double value) {
  const std::string label = scalar ? std::string(name) : std::string(name) + "[" + std::to_string(row) + "]";
  throw InputError(phys::invalid({}, rule, value).message(label), name);
}

struct Columns {
  size_t n = 0;
  std::vector<const double*> in;
};

Columns columns_of(std::initializer_list<const Column*> arrays) {
  Columns c;
  c.n = static_cast<size_t>((*arrays.begin())->size());
  for (const Column* a : arrays) {
    if (a->ndim() != 1 || static_cast<size_t>(a->size()) != c.n)
      throw std::invalid_argument("columns must be one-dimensional and of one length");
    c.in.push_back(a->data());
  }
  return c;
}

py::dict rebound(const Column& speed, const Column& angle, const Column& topspin_k,
                 const Column& sidespin_k, const phys::CushionParams& params, const std::string& method,
                 double tolerance, int steps, int max_steps, int lanes, int threads,
                 const TableHandle* table, bool scalar) {
  if (const phys::Validation e = params.validate()) raise_option(*e);
  phys::ImpactOptions options;
  if (!phys::parse_method(method, &options.method))
    throw InputError("method must be one of exact, extrapolation, paper, table, got '" + method + "'",
                     "method");
  options.tolerance = tolerance;
  options.paper_steps = steps;
  options.max_steps = max_steps;
  options.batch_lanes = lanes;
  if (options.method == phys::ImpactMethod::table) {
    if (table == nullptr || !table->table) throw InputError("method 'table' needs an impact table", "method");
    options.table = table->table.get();
  }
  if (const phys::Validation e = options.validate()) raise_option(*e);
  if (threads < 0) throw InputError(phys::invalid({}, "must be 0 (one per core) or more", threads).message("threads"), "threads");

  const Columns c = columns_of({&speed, &angle, &topspin_k, &sidespin_k});
  const size_t n = c.n;
  for (size_t i = 0; i < n; ++i) {
    const double v = c.in[0][i], a = c.in[1][i];
    if (!std::isfinite(v) || !(v > 0.0)) raise_row("speed", i, scalar, "must be positive and finite (m/s)", v);
    if (!std::isfinite(a) || !(a > 0.0) || !(a < 180.0))
      raise_row("angle", i, scalar, "must lie in (0, 180) degrees", a);
    if (!std::isfinite(c.in[2][i])) raise_row("topspin_k", i, scalar, "must be finite", c.in[2][i]);
    if (!std::isfinite(c.in[3][i])) raise_row("sidespin_k", i, scalar, "must be finite", c.in[3][i]);
  }

  const char* names[] = {"rebound_speed", "rebound_angle_deg", "vx", "vy", "wx", "wy", "wz",
                         "impulse_total", "work_total"};
  constexpr size_t kOut = 9;
  std::vector<py::array_t<double>> out;
  std::vector<double*> at;
  for (size_t k = 0; k < kOut; ++k) {
    out.emplace_back(static_cast<py::ssize_t>(n));
    at.push_back(out.back().mutable_data());
  }
  py::array_t<int8_t> status(static_cast<py::ssize_t>(n));
  int8_t* status_at = status.mutable_data();
  {
    py::gil_scoped_release release;
    const size_t chunks = (n + kChunk - 1) / kChunk;
    parallel_for(chunks, thread_count(threads, chunks), [&](size_t chunk, unsigned) {
      const size_t begin = chunk * kChunk, count = std::min(kChunk, n - begin);
      phys::BallState incoming[kChunk];
      phys::ImpactResult results[kChunk];
      for (size_t j = 0; j < count; ++j) {
        const size_t i = begin + j;
        incoming[j] = phys::incoming_state_k(c.in[0][i], c.in[1][i], c.in[2][i], c.in[3][i], params.radius);
      }
      phys::resolve_impacts(params, std::span<const phys::BallState>(incoming, count),
                            std::span<phys::ImpactResult>(results, count), options);
      for (size_t j = 0; j < count; ++j) {
        const size_t i = begin + j;
        const phys::ImpactResult& r = results[j];
        status_at[i] = static_cast<int8_t>(r.status);
        const bool ok = phys::usable(r.status);
        const double nan = std::nan("");
        const double values[kOut] = {r.rebound_speed, r.rebound_angle_deg, r.outgoing.velocity.x,
                                     r.outgoing.velocity.y, r.outgoing.spin.x, r.outgoing.spin.y,
                                     r.outgoing.spin.z, r.impulse_total, r.work_total};
        for (size_t k = 0; k < kOut; ++k) at[k][i] = ok ? values[k] : nan;
      }
    });
  }
  py::dict d;
  for (size_t k = 0; k < kOut; ++k) d[names[k]] = out[k];
  d["status"] = status;
  return d;
}

phys::BallBallParams ball_params(double mass, double radius, double mu_ball, double restitution,
                                 double mu_table, const std::string& model, const std::string& friction) {
  phys::BallBallParams p;
  p.mass = mass;
  p.radius = radius;
  p.mu_ball = mu_ball;
  p.restitution = restitution;
  p.mu_table = mu_table;
  if (!phys::parse_ball_model(model, &p.model))
    throw InputError("model must be mathavan_2014 or frictional_inelastic, got '" + model + "'", "model");
  if (!phys::parse_ball_friction(friction, &p.friction))
    throw InputError("friction must be constant or speed_dependent, got '" + friction + "'", "friction");
  if (const phys::Validation e = p.validate()) raise_option(*e);
  return p;
}

py::dict collide(const Column& speed, const Column& cut_deg, const Column& topspin_k,
                 const Column& sidespin_k, const phys::BallBallParams& params, const std::string& method,
                 double tolerance, int steps, int max_steps, int threads, bool scalar) {
  phys::CollisionOptions options;
  if (!phys::parse_collision_method(method, &options.method))
    throw InputError("method must be one of exact, paper, extrapolation, got '" + method + "'", "method");
  options.tolerance = tolerance;
  options.paper_steps = steps;
  options.max_steps = max_steps;
  if (const phys::Validation e = options.validate()) raise_option(*e);
  if (threads < 0) throw InputError(phys::invalid({}, "must be 0 (one per core) or more", threads).message("threads"), "threads");
  const Columns c = columns_of({&speed, &cut_deg, &topspin_k, &sidespin_k});
  const size_t n = c.n;
  for (size_t i = 0; i < n; ++i) {
    const double v = c.in[0][i], cut = c.in[1][i];
    if (!std::isfinite(v) || !(v > 0.0)) raise_row("speed", i, scalar, "must be positive and finite (m/s)", v);
    if (!std::isfinite(cut) || !(std::abs(cut) < 90.0))
      raise_row("cut", i, scalar, "must lie in (-90, 90) degrees: at 90 the cue ball only grazes", cut);
    if (!std::isfinite(c.in[2][i])) raise_row("topspin_k", i, scalar, "must be finite", c.in[2][i]);
    if (!std::isfinite(c.in[3][i])) raise_row("sidespin_k", i, scalar, "must be finite", c.in[3][i]);
  }
  const char* names[] = {"cue_vx", "cue_vy", "cue_wx", "cue_wy", "cue_wz", "cue_rolling_vx",
                         "cue_rolling_vy", "cue_rolling_speed", "cue_rolling_angle_deg",
                         "object_vx", "object_vy", "object_wx", "object_wy", "object_wz",
                         "object_rolling_vx", "object_rolling_vy", "object_rolling_speed",
                         "object_rolling_angle_deg", "throw_deg", "impulse_total"};
  constexpr size_t kOut = 20;
  std::vector<py::array_t<double>> out;
  std::vector<double*> at;
  for (size_t k = 0; k < kOut; ++k) {
    out.emplace_back(static_cast<py::ssize_t>(n));
    at.push_back(out.back().mutable_data());
  }
  py::array_t<int8_t> status(static_cast<py::ssize_t>(n));
  int8_t* status_at = status.mutable_data();
  {
    py::gil_scoped_release release;
    const size_t chunks = (n + kChunk - 1) / kChunk;
    parallel_for(chunks, thread_count(threads, chunks), [&](size_t chunk, unsigned) {
      const size_t begin = chunk * kChunk, end = std::min(n, begin + kChunk);
      for (size_t i = begin; i < end; ++i) {
        const double v = c.in[0][i], cut = c.in[1][i];
        const double unit = v / params.radius;  // rad/s per unit of k
        const phys::CutShot shot = phys::cut_shot(v, cut, {0.0, c.in[2][i] * unit, c.in[3][i] * unit},
                                                  params.radius);
        const phys::CollisionResult r = phys::resolve_table_collision(
            params, shot.cue_centre, shot.cue_ball, shot.object_centre, shot.object_ball, options);
        status_at[i] = static_cast<int8_t>(r.status);
        if (!phys::usable(r.status)) {
          for (size_t k = 0; k < kOut; ++k) at[k][i] = std::nan("");
          continue;
        }
        size_t k = 0;
        for (const phys::BallState* b : {&r.ball_i, &r.ball_j}) {
          const phys::Vec3 roll = phys::rolling_velocity(*b, params.radius);
          for (double x : {b->velocity.x, b->velocity.y, b->spin.x, b->spin.y, b->spin.z, roll.x, roll.y,
                           std::hypot(roll.x, roll.y), std::atan2(roll.y, roll.x) / kDegree})
            at[k++][i] = x;
        }
        double throw_deg = std::atan2(r.ball_j.velocity.y, r.ball_j.velocity.x) / kDegree + cut;
        while (throw_deg > 180.0) throw_deg -= 360.0;
        while (throw_deg <= -180.0) throw_deg += 360.0;
        at[k++][i] = throw_deg;
        at[k++][i] = r.impulse_total;
      }
    });
  }
  py::dict d;
  for (size_t k = 0; k < kOut; ++k) d[names[k]] = out[k];
  d["status"] = status;
  return d;
}

py::tuple xy(phys::Vec2 p) { return py::make_tuple(p.x, p.y); }

py::dict event_dict(const phys::ShotEvent& e, const std::vector<phys::BallOutcome>& balls) {
  py::dict d;
  d["time"] = e.time;
  d["ball"] = balls[static_cast<size_t>(e.ball)].name;
  d["type"] = phys::to_string(e.type);
  d["x"] = e.position.x;
  d["y"] = e.position.y;
  d["vx"] = e.velocity.x;
  d["vy"] = e.velocity.y;
  d["spin"] = py::make_tuple(e.spin.x, e.spin.y, e.spin.z);
  d["cushion"] = e.cushion >= 0 ? py::object(py::int_(e.cushion)) : py::object(py::none());
  d["index"] = e.index >= 0 ? py::object(py::int_(e.index)) : py::object(py::none());
  d["other"] = e.other >= 0 ? py::object(py::str(balls[static_cast<size_t>(e.other)].name))
                            : py::object(py::none());
  d["normal_speed"] = e.normal_speed;
  d["impulse"] = e.impulse;
  return d;
}

}  // namespace

ShotHandle simulate_stroke(const problems::Problem& problem, const phys::Shot& stroke,
                           const phys::SimulationOptions& options) {
  if (const phys::Validation e = stroke.validate()) raise_invalid(*e, "stroke.");
  ShotHandle shot;
  shot.problem = std::make_shared<const problems::Problem>(problem);
  shot.stroke = stroke;
  {
    py::gil_scoped_release release;
    shot.result = phys::simulate(problem.scene, problem.cue_ball, stroke, options);
  }
  if (shot.result.status == phys::ShotStatus::invalid_input) {
    if (shot.result.error) raise_invalid(*shot.result.error);
    throw InputError(shot.result.message, "");
  }
  return shot;
}

void bind_physics(py::module_& m) {
  py::class_<phys::CushionParams>(m, "CushionParams", "Ball-cushion impact parameters (SI units).")
      .def(py::init([](double mass, double radius, std::optional<double> cushion_height, double mu_cushion,
                       double mu_table, double restitution, double rigid_speed_limit, const std::string& model) {
             phys::CushionParams p = phys::params_for_radius(radius);
             p.mass = mass;
             if (cushion_height) p.cushion_height = *cushion_height;
             p.mu_cushion = mu_cushion;
             p.mu_table = mu_table;
             p.restitution = restitution;
             p.rigid_speed_limit = rigid_speed_limit;
             if (!phys::parse_cushion_model(model, &p.model))
               throw InputError("model must be mathavan_2010 or han_2005, got '" + model + "'", "model");
             if (const phys::Validation e = p.validate()) raise_option(*e);
             return p;
           }),
           py::arg("mass"), py::arg("radius"), py::arg("cushion_height"), py::arg("mu_cushion"),
           py::arg("mu_table"), py::arg("restitution"), py::arg("rigid_speed_limit"), py::arg("model"))
      .def_readonly("mass", &phys::CushionParams::mass)
      .def_readonly("radius", &phys::CushionParams::radius)
      .def_readonly("cushion_height", &phys::CushionParams::cushion_height)
      .def_readonly("mu_cushion", &phys::CushionParams::mu_cushion)
      .def_readonly("mu_table", &phys::CushionParams::mu_table)
      .def_readonly("restitution", &phys::CushionParams::restitution)
      .def_readonly("rigid_speed_limit", &phys::CushionParams::rigid_speed_limit)
      .def_property_readonly("model", [](const phys::CushionParams& p) { return phys::to_string(p.model); });

  py::class_<phys::BallBallParams>(m, "BallBallParams", "Ball-ball collision parameters (SI units).")
      .def(py::init(&ball_params), py::arg("mass"), py::arg("radius"), py::arg("mu_ball"),
           py::arg("restitution"), py::arg("mu_table"), py::arg("model"), py::arg("friction"));

  m.attr("IMPACT_STATUS") = py::make_tuple("ok", "rigid_limit_exceeded", "invalid_input", "step_limit");
  m.attr("COLLISION_STATUS") = py::make_tuple("ok", "invalid_input", "step_limit");
  m.def("rebound", &rebound, py::arg("speed"), py::arg("angle"), py::arg("topspin_k"),
        py::arg("sidespin_k"), py::arg("params"), py::arg("method"), py::arg("tolerance"),
        py::arg("steps"), py::arg("max_steps"), py::arg("lanes"), py::arg("threads"),
        py::arg("table").none(true), py::arg("scalar"));
  m.def("collide", &collide, py::arg("speed"), py::arg("cut"), py::arg("topspin_k"),
        py::arg("sidespin_k"), py::arg("params"), py::arg("method"), py::arg("tolerance"),
        py::arg("steps"), py::arg("max_steps"), py::arg("threads"), py::arg("scalar"));

  py::class_<ShotHandle>(m, "ShotResult", "A simulated stroke (physics::ShotResult) on its problem's table.")
      .def_property_readonly("status", [](const ShotHandle& s) { return phys::to_string(s.result.status); })
      .def_property_readonly("message", [](const ShotHandle& s) { return s.result.message; })
      .def_property_readonly("duration", [](const ShotHandle& s) { return s.result.duration; })
      .def_property_readonly("final_position", [](const ShotHandle& s) { return xy(s.result.final_position); })
      .def_property_readonly("cushion_hits", [](const ShotHandle& s) { return s.result.cushion_hits; })
      .def_property_readonly("impact_method",
                             [](const ShotHandle& s) { return phys::to_string(s.result.impact_method); })
      .def_property_readonly("stroke", [](const ShotHandle& s) {
        return py::make_tuple(s.stroke.speed, s.stroke.aim_deg, s.stroke.topspin_k, s.stroke.sidespin_k,
                              s.stroke.elevation_deg);
      })
      .def_property_readonly("ball_names", [](const ShotHandle& s) {
        py::list names;
        for (const auto& b : s.result.balls) names.append(b.name);
        return names;
      })
      .def_property_readonly("balls", [](const ShotHandle& s) {
        py::list balls;
        for (const auto& b : s.result.balls) {
          py::dict d;
          d["name"] = b.name;
          d["start"] = xy(b.start);
          d["final_position"] = xy(b.final_position);
          d["pocketed"] = b.pocketed;
          d["pocket"] = b.pocketed ? py::object(py::str(problems::pocket_name(s.problem->scene, b.pocket)))
                                   : py::object(py::none());
          d["cushion_hits"] = b.cushion_hits;
          d["jaw_hits"] = b.jaw_hits;
          d["events"] = b.events.size();
          balls.append(d);
        }
        return balls;
      })
      .def_property_readonly("events", [](const ShotHandle& s) {
        std::vector<const phys::ShotEvent*> all;
        for (const auto& b : s.result.balls)
          for (const auto& e : b.events) all.push_back(&e);
        std::stable_sort(all.begin(), all.end(), [](const phys::ShotEvent* a, const phys::ShotEvent* b) {
          return a->time < b->time;
        });
        py::list events;
        for (const phys::ShotEvent* e : all) events.append(event_dict(*e, s.result.balls));
        return events;
      })
      .def_property_readonly("verdict", [](const ShotHandle& s) {
        const problems::Verdict v = problems::check_stroke(*s.problem, s.stroke, s.result);
        py::dict d;
        d["failure"] = problems::to_string(v.failure);
        d["reason"] = v.reason;
        d["solves"] = v.solves();
        d["pot_made"] = s.problem->pot ? py::object(py::bool_(problems::makes_pot(*s.problem, s.result)))
                                       : py::object(py::none());
        d["miss_distance"] = problems::miss_distance(*s.problem, s.result);
        return d;
      })
      .def(
          "trajectory",
          [](const ShotHandle& s, double dt) {
            if (!std::isfinite(dt) || !(dt > 0.0))
              throw InputError(phys::invalid({}, "must be positive and finite (s)", dt).message("dt"), "dt");
            const auto& balls = s.result.balls;
            double end = 0.0;
            for (const auto& b : balls)
              if (!b.events.empty()) end = std::max(end, b.events.back().time);
            const double steps = std::floor(end / dt);
            if (steps * static_cast<double>(balls.size()) > static_cast<double>(phys::kMaxTraceSamples))
              throw InputError(phys::invalid({}, "is too small: the trajectory would exceed a million samples",
                                             dt).message("dt"),
                               "dt");
            std::vector<double> times;
            for (double k = 0; k <= steps; ++k) times.push_back(k * dt);
            for (const auto& b : balls)
              for (const auto& e : b.events) times.push_back(e.time);
            times.push_back(end);
            std::sort(times.begin(), times.end());
            times.erase(std::unique(times.begin(), times.end()), times.end());
            const auto rows = static_cast<py::ssize_t>(times.size());
            const auto cols = static_cast<py::ssize_t>(balls.size());
            py::array_t<double> t(rows), x({rows, cols}), y({rows, cols});
            std::copy(times.begin(), times.end(), t.mutable_data());
            double* xs = x.mutable_data();
            double* ys = y.mutable_data();
            {
              py::gil_scoped_release release;
              for (size_t b = 0; b < balls.size(); ++b) {
                double pocketed_at = INFINITY;
                for (const auto& e : balls[b].events)
                  if (e.type == phys::EventType::pocket) pocketed_at = e.time;
                for (size_t i = 0; i < times.size(); ++i) {
                  const size_t at = i * balls.size() + b;
                  if (times[i] > pocketed_at) {
                    xs[at] = ys[at] = std::nan("");
                    continue;
                  }
                  const phys::BallSample p =
                      phys::ball_state_at(s.result, s.problem->scene, static_cast<int>(b), times[i]);
                  xs[at] = p.position.x;
                  ys[at] = p.position.y;
                }
              }
            }
            return py::make_tuple(t, x, y);
          },
          py::arg("dt"));
}

}  // namespace cueplan::python
