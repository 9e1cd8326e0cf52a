#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "cueplan/physics/impact_table.hpp"
#include "cueplan/physics/shot.hpp"
#include "polynomial_roots.hpp"

namespace cueplan::physics {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kNever = std::numeric_limits<double>::infinity();
// An approach speed below this fraction of the ball's speed at a cushion that the cloth's
// friction presses it into is the end of a run of ever smaller bounces: the ball is
// pressed against the cushion.
constexpr double kRoundingApproach = 1e-12;

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double norm(Vec2 a) { return std::hypot(a.x, a.y); }

std::string describe(const std::string& field, const char* rule, double value) {
  char buf[320];
  std::snprintf(buf, sizeof buf, "%s %s, got %.10g", field.c_str(), rule, value);
  return buf;
}

// The four cushions: outward normal n (from the ball into the cushion) and the
// value of n . p at which the ball's centre touches the cushion.
struct CushionLine {
  Vec2 normal;
  double contact;  // n . p at contact
};

std::array<CushionLine, 4> cushion_lines(const Scene& s) {
  const double off = s.contact_offset();
  return {{{{0.0, -1.0}, -off},
           {{1.0, 0.0}, s.length - off},
           {{0.0, 1.0}, s.width - off},
           {{-1.0, 0.0}, -off}}};
}

// The ball on the cloth.
struct Ball {
  Vec2 p;  // m
  Vec2 v;  // m/s
  Vec3 w;  // rad/s
};

// Rates of the cloth model (PHYSICS.md, "Ball on the cloth").
struct ClothModel {
  double radius;
  double slide_decel;  // mu_s g
  double roll_decel;   // mu_r g
  double spin_decel;   // 5 mu_sp g / (2R), for w_z
  double slide_spin;   // 5 mu_s g / (2R), for the horizontal spin while sliding

  explicit ClothModel(const Scene& s)
      : radius(s.radius()),
        slide_decel(s.cloth.mu_slide * s.cloth.gravity),
        roll_decel(s.cloth.mu_roll * s.cloth.gravity),
        spin_decel(2.5 * s.cloth.mu_spin * s.cloth.gravity / s.radius()),
        slide_spin(2.5 * s.cloth.mu_slide * s.cloth.gravity / s.radius()) {}

  // Velocity of the contact point with the cloth: v + w x (-R z).
  Vec2 slip(const Ball& b) const { return {b.v.x - radius * b.w.y, b.v.y + radius * b.w.x}; }
};

// A piece of motion with constant acceleration, from a state until its motion changes.
struct Piece {
  Motion motion = Motion::resting;
  Vec2 accel;
  Vec2 spin_rate;           // d(w_x, w_y)/dt while sliding
  double duration = kNever;  // until slide to roll, or rest
};

Piece piece_from(const ClothModel& m, const Ball& b) {
  Piece piece;
  const Vec2 u = m.slip(b);
  const double us = norm(u);
  const double speed = norm(b.v);
  const double scale = speed + m.radius * std::hypot(b.w.x, b.w.y);
  if (us > 1e-12 * scale && us > 0.0) {
    // Sliding: friction against the slip, which keeps its direction and shrinks
    // at 7/2 mu_s g.
    const Vec2 d = (1.0 / us) * u;
    piece.motion = Motion::sliding;
    piece.accel = -m.slide_decel * d;
    piece.spin_rate = {-m.slide_spin * d.y, m.slide_spin * d.x};
    piece.duration = 2.0 * us / (7.0 * m.slide_decel);
  } else if (speed > 0.0) {
    piece.motion = Motion::rolling;
    piece.accel = (-m.roll_decel / speed) * b.v;
    piece.duration = speed / m.roll_decel;
  }
  return piece;
}

void advance(const ClothModel& m, const Piece& piece, double dt, Ball* b) {
  b->p = b->p + dt * b->v + (0.5 * dt * dt) * piece.accel;
  b->v = b->v + dt * piece.accel;
  if (piece.motion == Motion::sliding) {
    b->w.x += piece.spin_rate.x * dt;
    b->w.y += piece.spin_rate.y * dt;
  } else {
    b->w.x = -b->v.y / m.radius;
    b->w.y = b->v.x / m.radius;
  }
  // Sidespin decays toward zero in every phase.
  const double drop = m.spin_decel * dt;
  b->w.z = b->w.z > 0.0 ? std::max(0.0, b->w.z - drop) : std::min(0.0, b->w.z + drop);
}

// Position coefficients of a piece: p(t) = a0 + a1 t + a2 t^2.
struct Quadratic {
  Vec2 a0, a1, a2;
};

// First time in [0, horizon] at which the centre enters the circle (c, r), or kNever.
// The path's bounding box is tested first, which rules out most circles cheaply.
double entry_time(const Quadratic& q, double horizon, Vec2 c, double r) {
  auto range = [&](double p0, double v, double a2, double* lo, double* hi) {
    const double end = p0 + v * horizon + a2 * horizon * horizon;
    *lo = std::min(p0, end);
    *hi = std::max(p0, end);
    if (a2 != 0.0) {
      const double t = -v / (2.0 * a2);
      if (t > 0.0 && t < horizon) {
        const double mid = p0 + v * t + a2 * t * t;
        *lo = std::min(*lo, mid);
        *hi = std::max(*hi, mid);
      }
    }
  };
  double xlo, xhi, ylo, yhi;
  range(q.a0.x, q.a1.x, q.a2.x, &xlo, &xhi);
  range(q.a0.y, q.a1.y, q.a2.y, &ylo, &yhi);
  if (c.x + r < xlo || c.x - r > xhi || c.y + r < ylo || c.y - r > yhi) return kNever;

  // |d(t)|^2 - r^2 with d = (a0 - c) + a1 t + a2 t^2: a quartic in t.
  const Vec2 d0 = q.a0 - c;
  const double coeff[5] = {dot(d0, d0) - r * r, 2.0 * dot(d0, q.a1),
                           dot(q.a1, q.a1) + 2.0 * dot(d0, q.a2), 2.0 * dot(q.a1, q.a2),
                           dot(q.a2, q.a2)};
  if (coeff[0] <= 0.0) return coeff[1] < 0.0 || coeff[0] < 0.0 ? 0.0 : kNever;
  double roots[detail::kMaxDegree];
  const int n = detail::roots_in(coeff, 4, 0.0, horizon, roots);
  return n > 0 ? roots[0] : kNever;
}

// Upper bound on how far the ball can still travel (sliding, then rolling to rest).
double reach(const ClothModel& m, const Ball& b) {
  const double slide_time = 2.0 * norm(m.slip(b)) / (7.0 * m.slide_decel);
  const double top_speed = norm(b.v) + m.slide_decel * slide_time;
  return top_speed * slide_time + top_speed * top_speed / (2.0 * m.roll_decel);
}

}  // namespace

double Scene::contact_offset() const { return radius() * ball_and_cushion.cos_theta(); }

Vec2 PathSegment::at(double t) const {
  const double dt = t - t0;
  return {p0.x + v0.x * dt + 0.5 * accel.x * dt * dt, p0.y + v0.y * dt + 0.5 * accel.y * dt * dt};
}

std::string Scene::validate() const {
  if (std::string why = ball_and_cushion.validate(); !why.empty()) return why;
  if (!std::isfinite(length) || !(length > 0.0))
    return describe("table.length", "must be positive and finite (m)", length);
  if (!std::isfinite(width) || !(width > 0.0))
    return describe("table.width", "must be positive and finite (m)", width);
  const double off = contact_offset();
  if (!(length > 2.0 * off) || !(width > 2.0 * off))
    return describe("table.length", "and table.width must leave room for a ball (m)",
                    std::min(length, width));
  if (!std::isfinite(cloth.mu_roll) || !(cloth.mu_roll > 0.0))
    return describe("physics.mu_roll",
                    "must be positive and finite: without rolling resistance a ball never stops",
                    cloth.mu_roll);
  if (!std::isfinite(cloth.mu_slide) || !(cloth.mu_slide > 0.0))
    return describe("physics.mu_slide",
                    "must be positive and finite: without sliding friction a ball never rolls",
                    cloth.mu_slide);
  if (!std::isfinite(cloth.mu_spin) || cloth.mu_spin < 0.0)
    return describe("physics.mu_spin", "must be finite and not negative", cloth.mu_spin);
  if (!std::isfinite(cloth.gravity) || !(cloth.gravity > 0.0))
    return describe("physics.gravity", "must be positive and finite (m/s^2)", cloth.gravity);
  for (size_t i = 0; i < pockets.size(); ++i) {
    const Pocket& k = pockets[i];
    const std::string name = "pockets[" + std::to_string(i) + "]";
    if (!std::isfinite(k.centre.x) || !std::isfinite(k.centre.y))
      return describe(name + ".centre", "must be finite (m)", NAN);
    if (!std::isfinite(k.radius) || !(k.radius > 0.0))
      return describe(name + ".radius", "must be positive and finite (m)", k.radius);
  }
  const double r = radius();
  for (size_t i = 0; i < obstacles.size(); ++i) {
    const std::string name = "obstacles[" + std::to_string(i) + "]";
    const Vec2 o = obstacles[i];
    if (!std::isfinite(o.x) || !std::isfinite(o.y))
      return describe(name, "must be finite (m)", std::isfinite(o.x) ? o.y : o.x);
    if (o.x < off || o.x > length - off || o.y < off || o.y > width - off)
      return name + " lies off the table (its centre must be at least " +
             std::to_string(off) + " m inside every cushion nose)";
    for (size_t j = 0; j < i; ++j) {
      if (norm(o - obstacles[j]) < 2.0 * r * (1.0 - 1e-9))
        return name + " overlaps obstacles[" + std::to_string(j) + "]";
    }
  }
  return {};
}

std::string Scene::check_position(Vec2 p, const std::string& what) const {
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return what + " must be finite (m)";
  const double off = contact_offset();
  if (p.x < off || p.x > length - off || p.y < off || p.y > width - off) {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "%s (%.4g, %.4g) lies off the table: its centre must be within [%.4g, %.4g] "
                  "x [%.4g, %.4g] m",
                  what.c_str(), p.x, p.y, off, length - off, off, width - off);
    return buf;
  }
  for (size_t i = 0; i < pockets.size(); ++i) {
    if (norm(p - pockets[i].centre) < pockets[i].radius)
      return what + " lies inside pocket " + std::to_string(i);
  }
  for (size_t i = 0; i < obstacles.size(); ++i) {
    if (norm(p - obstacles[i]) < 2.0 * radius() * (1.0 - 1e-9))
      return what + " overlaps obstacles[" + std::to_string(i) + "]";
  }
  return {};
}

Scene snooker_scene() {
  Scene s;
  const double r = 0.045;
  s.pockets = {{{0.0, 0.0}, r},          {{s.length / 2, 0.0}, r}, {{s.length, 0.0}, r},
               {{0.0, s.width}, r},      {{s.length / 2, s.width}, r},
               {{s.length, s.width}, r}};
  return s;
}

const char* to_string(EventType type) {
  switch (type) {
    case EventType::strike: return "strike";
    case EventType::slide_to_roll: return "slide_to_roll";
    case EventType::spin_stop: return "spin_stop";
    case EventType::cushion: return "cushion";
    case EventType::pocket: return "pocket";
    case EventType::obstacle: return "obstacle";
    case EventType::rest: return "rest";
  }
  return "unknown";
}

const char* to_string(Motion motion) {
  switch (motion) {
    case Motion::sliding: return "sliding";
    case Motion::rolling: return "rolling";
    case Motion::resting: return "resting";
  }
  return "unknown";
}

const char* to_string(ShotStatus status) {
  switch (status) {
    case ShotStatus::rest: return "rest";
    case ShotStatus::pocketed: return "pocketed";
    case ShotStatus::hit_obstacle: return "hit_obstacle";
    case ShotStatus::invalid_input: return "invalid_input";
    case ShotStatus::event_limit: return "event_limit";
    case ShotStatus::impact_failed: return "impact_failed";
  }
  return "unknown";
}

ImpactMethod chosen_impact_method(const Scene& scene, const SimulationOptions& options) {
  if (options.impact_method == ImpactMethod::paper) return ImpactMethod::paper;
  if (options.impact_method == ImpactMethod::extrapolation) return ImpactMethod::extrapolation;
  if (options.impact_method == ImpactMethod::table && options.table != nullptr &&
      options.table->covers(scene.ball_and_cushion) &&
      options.table->measured_error().max_state_relative <= options.impact_accuracy)
    return ImpactMethod::table;
  return ImpactMethod::exact;
}

ShotResult simulate(const Scene& scene, Vec2 cue_ball, const Shot& shot,
                    const SimulationOptions& options) {
  ShotResult result;
  auto fail = [&](ShotStatus status, std::string why) {
    result.status = status;
    result.message = std::move(why);
    return result;
  };
  if (std::string why = scene.validate(); !why.empty())
    return fail(ShotStatus::invalid_input, why);
  if (std::string why = scene.check_position(cue_ball, "cue_ball"); !why.empty())
    return fail(ShotStatus::invalid_input, why);
  if (!std::isfinite(shot.speed) || !(shot.speed > 0.0))
    return fail(ShotStatus::invalid_input,
                describe("speed", "must be positive and finite (m/s)", shot.speed));
  if (!std::isfinite(shot.aim_deg))
    return fail(ShotStatus::invalid_input, describe("aim_deg", "must be finite", shot.aim_deg));
  if (!std::isfinite(shot.topspin_k))
    return fail(ShotStatus::invalid_input,
                describe("topspin_k", "must be finite", shot.topspin_k));
  if (!std::isfinite(shot.sidespin_k))
    return fail(ShotStatus::invalid_input,
                describe("sidespin_k", "must be finite", shot.sidespin_k));
  if (options.max_events < 1)
    return fail(ShotStatus::invalid_input,
                describe("max_events", "must be at least 1", options.max_events));

  const ClothModel cloth(scene);
  const CushionParams& params = scene.ball_and_cushion;
  const auto lines = cushion_lines(scene);

  // The cheapest impact method that meets the accuracy asked for: the table where its
  // measured error does, else an exact method at a tolerance that does. Over the
  // uniform domain `exact` (also the table's fallback) errs by at most about 5
  // tolerances, `extrapolation` by about 100 (bench/README.md): a tenth and a
  // hundredth of the accuracy.
  ImpactOptions impact;
  impact.method = chosen_impact_method(scene, options);
  const double tolerances = impact.method == ImpactMethod::extrapolation ? 100.0 : 10.0;
  impact.tolerance = std::clamp(options.impact_accuracy / tolerances, 1e-14, 1e-3);
  if (impact.method == ImpactMethod::table) {
    impact.table = options.table;
    impact.table_fallback_tolerance = impact.tolerance;  // the accuracy asked for, as above
  }
  result.impact_method = impact.method;

  // Cue strike: speed along the aim, topspin about the horizontal axis perpendicular
  // to the motion (natural-roll sense), sidespin about z.
  const double phi = shot.aim_deg * kDegree;
  Ball b;
  b.p = cue_ball;
  b.v = {shot.speed * std::cos(phi), shot.speed * std::sin(phi)};
  const double wt = shot.topspin_k * shot.speed / cloth.radius;
  b.w = {-wt * std::sin(phi), wt * std::cos(phi), shot.sidespin_k * shot.speed / cloth.radius};

  double t = 0.0;
  result.events.reserve(16);
  auto log = [&](EventType type, int cushion, int index, double normal_speed) {
    ShotEvent e;
    e.type = type;
    e.time = t;
    e.position = b.p;
    e.velocity = b.v;
    e.spin = b.w;
    e.cushion = cushion;
    e.index = index;
    e.normal_speed = normal_speed;
    result.events.push_back(e);
  };
  log(EventType::strike, -1, -1, 0.0);

  // Whether any cushion is still within reach; refreshed after every cushion.
  auto cushions_in_reach = [&] {
    const double d = reach(cloth, b);
    for (const CushionLine& c : lines)
      if (c.contact - dot(c.normal, b.p) <= d) return true;
    return false;
  };
  bool check_cushions = cushions_in_reach();

  result.status = ShotStatus::rest;
  for (;;) {
    if (static_cast<int>(result.events.size()) > options.max_events) {
      result.status = ShotStatus::event_limit;
      char buf[160];
      std::snprintf(buf, sizeof buf, "more than %d events before the ball came to rest",
                    options.max_events);
      result.message = buf;
      break;
    }
    const Piece piece = piece_from(cloth, b);
    if (piece.motion == Motion::resting) {
      b.v = {0.0, 0.0};
      log(EventType::rest, -1, -1, 0.0);
      break;
    }

    // The stages of one piece, in order: the motion's own end, the sidespin stop,
    // then the first contact (cushion, pocket, obstacle) before either.
    double horizon = piece.duration;
    EventType next = piece.motion == Motion::sliding ? EventType::slide_to_roll : EventType::rest;
    const double spin_stop = b.w.z != 0.0 ? std::abs(b.w.z) / cloth.spin_decel : kNever;
    if (spin_stop < horizon) {
      horizon = spin_stop;
      next = EventType::spin_stop;
    }
    const Quadratic q{b.p, b.v, 0.5 * piece.accel};
    int which = -1;
    if (check_cushions) {
      for (int i = 0; i < 4; ++i) {
        const Vec2 n = lines[i].normal;
        // n . p(t) - contact, negative on the table; contact when it rises to zero.
        double c[3] = {dot(n, q.a0) - lines[i].contact, dot(n, q.a1), dot(n, q.a2)};
        double hit = kNever;
        if (c[0] >= 0.0) {
          // Touching (or rounding past): on the line, so that a ball leaving the cushion
          // is caught when friction on the cloth brings it back.
          c[0] = 0.0;
        }
        if (c[0] == 0.0 && (c[1] > 0.0 || (c[1] == 0.0 && c[2] > 0.0))) {
          hit = 0.0;  // touching and moving in, or at rest across it and pressed in
        } else {
          double roots[2];
          const int n_roots = detail::roots_in(c, 2, 0.0, horizon, roots);
          for (int k = 0; k < n_roots; ++k) {
            if (c[1] + 2.0 * c[2] * roots[k] > 0.0) {
              hit = roots[k];
              break;
            }
          }
        }
        if (hit < horizon) {
          horizon = hit;
          next = EventType::cushion;
          which = i;
        }
      }
    }
    for (size_t i = 0; i < scene.pockets.size(); ++i) {
      const double hit = entry_time(q, horizon, scene.pockets[i].centre, scene.pockets[i].radius);
      if (hit < horizon) {
        horizon = hit;
        next = EventType::pocket;
        which = static_cast<int>(i);
      }
    }
    for (size_t i = 0; i < scene.obstacles.size(); ++i) {
      const double hit = entry_time(q, horizon, scene.obstacles[i], 2.0 * cloth.radius);
      if (hit < horizon) {
        horizon = hit;
        next = EventType::obstacle;
        which = static_cast<int>(i);
      }
    }

    if (options.record_path && horizon > 0.0)
      result.path.push_back({t, t + horizon, b.p, b.v, piece.accel, piece.motion});
    advance(cloth, piece, horizon, &b);
    t += horizon;

    switch (next) {
      case EventType::slide_to_roll:
        b.w.x = -b.v.y / cloth.radius;
        b.w.y = b.v.x / cloth.radius;
        log(next, -1, -1, 0.0);
        break;
      case EventType::spin_stop:
        b.w.z = 0.0;
        log(next, -1, -1, 0.0);
        break;
      case EventType::rest:
        b.v = {0.0, 0.0};
        b.w.x = b.w.y = 0.0;
        log(next, -1, -1, 0.0);
        break;
      case EventType::cushion: {
        // Into the cushion's frame (X = n x z, Y = n, Z = z), resolve, and back.
        const Vec2 n = lines[which].normal;
        const Vec2 x_axis{n.y, -n.x};
        BallState in;
        in.velocity = {dot(b.v, x_axis), dot(b.v, n), 0.0};
        in.spin = {b.w.x * x_axis.x + b.w.y * x_axis.y, b.w.x * n.x + b.w.y * n.y, b.w.z};
        const bool pressed_in = dot(piece_from(cloth, b).accel, n) > 0.0;
        if (!(in.velocity.y > 0.0) ||
            (pressed_in &&
             in.velocity.y <= kRoundingApproach * std::hypot(in.velocity.x, in.velocity.y))) {
          // Friction on the cloth presses the ball into the cushion with no approach
          // speed left (a run of ever smaller bounces, each e times the last: the exact
          // method follows them down to far below the rounding of the speed, so the
          // run is cut at kRoundingApproach): sliding along a cushion is not modelled.
          result.status = ShotStatus::impact_failed;
          result.message = "cushion " + std::to_string(which) +
                           ": the ball is pressed against it with no approach speed (sliding "
                           "along a cushion is not modelled)";
          break;
        }
        const ImpactResult r = resolve_impact(params, in, impact);
        if (!usable(r.status)) {
          result.status = ShotStatus::impact_failed;
          result.message = "cushion " + std::to_string(which) + ": " + r.message;
          break;
        }
        b.v = r.outgoing.velocity.x * x_axis + r.outgoing.velocity.y * n;
        const Vec2 wh = r.outgoing.spin.x * x_axis + r.outgoing.spin.y * n;
        b.w = {wh.x, wh.y, r.outgoing.spin.z};
        // On the contact line exactly, so rounding never leaves it past the cushion.
        b.p = b.p + (lines[which].contact - dot(n, b.p)) * n;
        ++result.cushion_hits;
        result.max_cushion_normal_speed = std::max(result.max_cushion_normal_speed,
                                                   in.velocity.y);
        if (r.status == ImpactStatus::rigid_limit_exceeded) result.rigid_limit_exceeded = true;
        if (r.method_used == ImpactMethod::table) ++result.table_impacts;
        log(next, which, -1, in.velocity.y);
        check_cushions = cushions_in_reach();
        break;
      }
      case EventType::pocket:
        result.status = ShotStatus::pocketed;
        result.pocketed = true;
        log(next, -1, which, 0.0);
        break;
      case EventType::obstacle:
        result.status = ShotStatus::hit_obstacle;
        result.hit_obstacle = true;
        log(next, -1, which, 0.0);
        break;
      case EventType::strike:
        break;
    }
    if (next == EventType::rest || result.status != ShotStatus::rest) break;
  }
  result.final_position = b.p;
  result.duration = t;
  return result;
}

}  // namespace cueplan::physics
