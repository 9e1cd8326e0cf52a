#include <fmt/format.h>

#include <algorithm>
#include <cmath>
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

Validation Scene::validate() const {
  if (Validation e = ball_and_cushion.validate()) return e->under({"ball_and_cushion"});
  if (!std::isfinite(length) || !(length > 0.0))
    return invalid({"length"}, "must be positive and finite (m)", length);
  if (!std::isfinite(width) || !(width > 0.0))
    return invalid({"width"}, "must be positive and finite (m)", width);
  const double off = contact_offset();
  if (!(length > 2.0 * off) || !(width > 2.0 * off)) {
    // The shorter side is the one that leaves no room; the ball's radius sets the room
    // it needs, so it is the rule's other field.
    const bool length_short = !(length > 2.0 * off);
    ValidationError e = invalid({length_short ? "length" : "width"},
                                fmt::format("must leave room for a ball: more than 2 R cos(theta) "
                                            "= {:.4g} m ({{other}} R = {:.4g} m)",
                                            2.0 * off, radius()),
                                length_short ? length : width);
    e.other = FieldPath{"ball_and_cushion", "radius"};
    return e;
  }
  if (!std::isfinite(cloth.mu_roll) || !(cloth.mu_roll > 0.0))
    return invalid({"cloth", "mu_roll"},
                   "must be positive and finite: without rolling resistance a ball never stops",
                   cloth.mu_roll);
  if (!std::isfinite(cloth.mu_slide) || !(cloth.mu_slide > 0.0))
    return invalid({"cloth", "mu_slide"},
                   "must be positive and finite: without sliding friction a ball never rolls",
                   cloth.mu_slide);
  if (!std::isfinite(cloth.mu_spin) || cloth.mu_spin < 0.0)
    return invalid({"cloth", "mu_spin"}, "must be finite and not negative", cloth.mu_spin);
  if (!std::isfinite(cloth.gravity) || !(cloth.gravity > 0.0))
    return invalid({"cloth", "gravity"}, "must be positive and finite (m/s^2)", cloth.gravity);
  for (size_t i = 0; i < pockets.size(); ++i) {
    const Pocket& k = pockets[i];
    const int index = static_cast<int>(i);
    if (!std::isfinite(k.centre.x) || !std::isfinite(k.centre.y))
      return invalid({"pockets", index, "centre"}, "must be finite (m)",
                     std::isfinite(k.centre.x) ? k.centre.y : k.centre.x);
    if (!std::isfinite(k.radius) || !(k.radius > 0.0))
      return invalid({"pockets", index, "radius"}, "must be positive and finite (m)", k.radius);
  }
  const double r = radius();
  for (size_t i = 0; i < obstacles.size(); ++i) {
    const FieldPath name{"obstacles", static_cast<int>(i)};
    const Vec2 o = obstacles[i];
    if (!std::isfinite(o.x) || !std::isfinite(o.y))
      return invalid(name, "must be finite (m)", std::isfinite(o.x) ? o.y : o.x);
    if (o.x < off || o.x > length - off || o.y < off || o.y > width - off)
      return invalid(name, fmt::format("lies off the table (its centre must be at least {} m "
                                       "inside every cushion nose)",
                                       std::to_string(off)));
    for (size_t j = 0; j < i; ++j) {
      if (norm(o - obstacles[j]) < 2.0 * r * (1.0 - 1e-9)) {
        ValidationError e = invalid(name, "overlaps {other}");
        e.other = FieldPath{"obstacles", static_cast<int>(j)};
        return e;
      }
    }
  }
  return {};
}

Validation Scene::check_position(Vec2 p, const FieldPath& what) const {
  if (!std::isfinite(p.x) || !std::isfinite(p.y))
    return invalid(what, "must be finite (m)", std::isfinite(p.x) ? p.y : p.x);
  const double off = contact_offset();
  if (p.x < off || p.x > length - off || p.y < off || p.y > width - off)
    return invalid(what, fmt::format("({:.4g}, {:.4g}) lies off the table: its centre must be "
                                     "within [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] m",
                                     p.x, p.y, off, length - off, off, width - off));
  for (size_t i = 0; i < pockets.size(); ++i) {
    if (norm(p - pockets[i].centre) < pockets[i].radius) {
      ValidationError e = invalid(what, "lies inside {other}");
      e.other = FieldPath{"pockets", static_cast<int>(i)};
      return e;
    }
  }
  for (size_t i = 0; i < obstacles.size(); ++i) {
    if (norm(p - obstacles[i]) < 2.0 * radius() * (1.0 - 1e-9)) {
      ValidationError e = invalid(what, "overlaps {other}");
      e.other = FieldPath{"obstacles", static_cast<int>(i)};
      return e;
    }
  }
  return {};
}

std::vector<Pocket> standard_pockets(double length, double width, double radius) {
  return {{{0.0, 0.0}, radius},   {{length / 2, 0.0}, radius},   {{length, 0.0}, radius},
          {{0.0, width}, radius}, {{length / 2, width}, radius}, {{length, width}, radius}};
}

Scene snooker_scene() {
  Scene s;
  s.pockets = standard_pockets(s.length, s.width, kDefaultPocketRadius);
  return s;
}

Validation Shot::validate() const {
  if (!std::isfinite(speed) || !(speed > 0.0))
    return invalid({"speed"}, "must be positive and finite (m/s)", speed);
  if (!std::isfinite(aim_deg)) return invalid({"aim_deg"}, "must be finite (deg)", aim_deg);
  if (!std::isfinite(topspin_k)) return invalid({"topspin_k"}, "must be finite", topspin_k);
  if (!std::isfinite(sidespin_k)) return invalid({"sidespin_k"}, "must be finite", sidespin_k);
  return {};
}

CompiledScene::CompiledScene(Scene scene) : scene_(std::move(scene)), error_(scene_.validate()) {}

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

namespace {

// The stroke's own inputs, checked on every call (the scene was checked when compiled).
Validation check_stroke(const Scene& scene, Vec2 cue_ball, const Shot& shot,
                        const SimulationOptions& options) {
  if (Validation e = scene.check_position(cue_ball, {"cue_ball"})) return e;
  if (Validation e = shot.validate()) return e->under({"shot"});
  if (options.max_events < 1)
    return invalid({"max_events"}, "must be at least 1", options.max_events);
  return {};
}

// What ends the current piece of motion, and when.
struct NextEvent {
  EventType type = EventType::rest;
  double after = kNever;  // s from now
  int which = -1;         // cushion, pocket or obstacle index
};

// One shot from the strike to rest, as stages run in order for every piece of motion:
//   1. next_event - the piece's own end (slide to roll, rest), the sidespin stop, then
//                   the first contact before either (cushion, pocket, obstacle);
//   2. advance    - the ball moves along the piece to that event (path recorded);
//   3. resolve    - the event changes the ball's state (a cushion through the impact
//                   model) and is logged; pockets, obstacles and failures end the shot.
class ShotRun {
 public:
  ShotRun(const Scene& scene, const SimulationOptions& options, ShotResult* result)
      : scene_(scene), options_(options), cloth_(scene), lines_(cushion_lines(scene)),
        result_(result) {
    // The cheapest impact method that meets the accuracy asked for: the table where its
    // measured error does, else an exact method at a tolerance that does. Over the
    // uniform domain `exact` (also the table's fallback) errs by at most about 5
    // tolerances, `extrapolation` by about 100 (bench/README.md): a tenth and a
    // hundredth of the accuracy.
    impact_.method = chosen_impact_method(scene, options);
    const double tolerances = impact_.method == ImpactMethod::extrapolation ? 100.0 : 10.0;
    impact_.tolerance = std::clamp(options.impact_accuracy / tolerances, 1e-14, 1e-3);
    if (impact_.method == ImpactMethod::table) {
      impact_.table = options.table;
      impact_.table_fallback_tolerance = impact_.tolerance;  // the accuracy asked for, as above
    }
    result_->impact_method = impact_.method;
  }

  // Cue strike: speed along the aim, topspin about the horizontal axis perpendicular
  // to the motion (natural-roll sense), sidespin about z.
  void strike(Vec2 cue_ball, const Shot& shot) {
    const double phi = shot.aim_deg * kDegree;
    b_.p = cue_ball;
    b_.v = {shot.speed * std::cos(phi), shot.speed * std::sin(phi)};
    const double wt = shot.topspin_k * shot.speed / cloth_.radius;
    b_.w = {-wt * std::sin(phi), wt * std::cos(phi), shot.sidespin_k * shot.speed / cloth_.radius};
    result_->events.reserve(16);
    log(EventType::strike, -1, -1, 0.0);
    check_cushions_ = cushions_in_reach();
    result_->status = ShotStatus::rest;
  }

  // Runs the stages until the ball rests or the shot ends otherwise.
  void run() {
    for (;;) {
      if (static_cast<int>(result_->events.size()) > options_.max_events) {
        result_->status = ShotStatus::event_limit;
        result_->message =
            fmt::format("more than {} events before the ball came to rest", options_.max_events);
        break;
      }
      const Piece piece = piece_from(cloth_, b_);
      if (piece.motion == Motion::resting) {
        b_.v = {0.0, 0.0};
        log(EventType::rest, -1, -1, 0.0);
        break;
      }
      const NextEvent next = next_event(piece);
      advance(piece, next.after);
      resolve(next);
      if (next.type == EventType::rest || result_->status != ShotStatus::rest) break;
    }
    result_->final_position = b_.p;
    result_->duration = t_;
  }

 private:
  // Stage 1.
  NextEvent next_event(const Piece& piece) const {
    NextEvent next;
    next.after = piece.duration;
    next.type = piece.motion == Motion::sliding ? EventType::slide_to_roll : EventType::rest;
    const double spin_stop = b_.w.z != 0.0 ? std::abs(b_.w.z) / cloth_.spin_decel : kNever;
    if (spin_stop < next.after) {
      next.after = spin_stop;
      next.type = EventType::spin_stop;
    }
    const Quadratic q{b_.p, b_.v, 0.5 * piece.accel};
    if (check_cushions_) {
      for (int i = 0; i < 4; ++i) {
        const double hit = cushion_contact(q, i, next.after);
        if (hit < next.after) next = {EventType::cushion, hit, i};
      }
    }
    for (size_t i = 0; i < scene_.pockets.size(); ++i) {
      const double hit =
          entry_time(q, next.after, scene_.pockets[i].centre, scene_.pockets[i].radius);
      if (hit < next.after) next = {EventType::pocket, hit, static_cast<int>(i)};
    }
    for (size_t i = 0; i < scene_.obstacles.size(); ++i) {
      const double hit = entry_time(q, next.after, scene_.obstacles[i], 2.0 * cloth_.radius);
      if (hit < next.after) next = {EventType::obstacle, hit, static_cast<int>(i)};
    }
    return next;
  }

  // When within `horizon` the centre meets cushion i moving in; kNever if it does not.
  double cushion_contact(const Quadratic& q, int i, double horizon) const {
    const Vec2 n = lines_[i].normal;
    // n . p(t) - contact, negative on the table; contact when it rises to zero.
    double c[3] = {dot(n, q.a0) - lines_[i].contact, dot(n, q.a1), dot(n, q.a2)};
    if (c[0] >= 0.0) {
      // Touching (or rounding past): on the line, so that a ball leaving the cushion
      // is caught when friction on the cloth brings it back.
      c[0] = 0.0;
    }
    if (c[0] == 0.0 && (c[1] > 0.0 || (c[1] == 0.0 && c[2] > 0.0)))
      return 0.0;  // touching and moving in, or at rest across it and pressed in
    double roots[2];
    const int n_roots = detail::roots_in(c, 2, 0.0, horizon, roots);
    for (int k = 0; k < n_roots; ++k)
      if (c[1] + 2.0 * c[2] * roots[k] > 0.0) return roots[k];
    return kNever;
  }

  // Stage 2.
  void advance(const Piece& piece, double dt) {
    if (options_.record_path && dt > 0.0)
      result_->path.push_back({t_, t_ + dt, b_.p, b_.v, piece.accel, piece.motion});
    cueplan::physics::advance(cloth_, piece, dt, &b_);
    t_ += dt;
  }

  // Stage 3.
  void resolve(const NextEvent& next) {
    switch (next.type) {
      case EventType::slide_to_roll:
        b_.w.x = -b_.v.y / cloth_.radius;
        b_.w.y = b_.v.x / cloth_.radius;
        log(next.type, -1, -1, 0.0);
        break;
      case EventType::spin_stop:
        b_.w.z = 0.0;
        log(next.type, -1, -1, 0.0);
        break;
      case EventType::rest:
        b_.v = {0.0, 0.0};
        b_.w.x = b_.w.y = 0.0;
        log(next.type, -1, -1, 0.0);
        break;
      case EventType::cushion:
        rebound(next.which);
        break;
      case EventType::pocket:
        result_->status = ShotStatus::pocketed;
        log(next.type, -1, next.which, 0.0);
        break;
      case EventType::obstacle:
        result_->status = ShotStatus::hit_obstacle;
        log(next.type, -1, next.which, 0.0);
        break;
      case EventType::strike:
        break;
    }
  }

  // A cushion contact: into the cushion's frame (X = n x z, Y = n, Z = z), resolved by
  // the impact model, and back.
  void rebound(int which) {
    const Vec2 n = lines_[which].normal;
    const Vec2 x_axis{n.y, -n.x};
    BallState in;
    in.velocity = {dot(b_.v, x_axis), dot(b_.v, n), 0.0};
    in.spin = {b_.w.x * x_axis.x + b_.w.y * x_axis.y, b_.w.x * n.x + b_.w.y * n.y, b_.w.z};
    const bool pressed_in = dot(piece_from(cloth_, b_).accel, n) > 0.0;
    if (!(in.velocity.y > 0.0) ||
        (pressed_in &&
         in.velocity.y <= kRoundingApproach * std::hypot(in.velocity.x, in.velocity.y))) {
      // Friction on the cloth presses the ball into the cushion with no approach speed
      // left (a run of ever smaller bounces, each e times the last: the exact method
      // follows them down to far below the rounding of the speed, so the run is cut at
      // kRoundingApproach): sliding along a cushion is not modelled.
      result_->status = ShotStatus::impact_failed;
      result_->message = fmt::format(
          "cushion {}: the ball is pressed against it with no approach speed (sliding along a "
          "cushion is not modelled)",
          which);
      return;
    }
    const ImpactResult r = resolve_impact(scene_.ball_and_cushion, in, impact_);
    if (!usable(r.status)) {
      result_->status = ShotStatus::impact_failed;
      result_->message = fmt::format("cushion {}: {}", which, r.message);
      return;
    }
    b_.v = r.outgoing.velocity.x * x_axis + r.outgoing.velocity.y * n;
    const Vec2 wh = r.outgoing.spin.x * x_axis + r.outgoing.spin.y * n;
    b_.w = {wh.x, wh.y, r.outgoing.spin.z};
    // On the contact line exactly, so rounding never leaves it past the cushion.
    b_.p = b_.p + (lines_[which].contact - dot(n, b_.p)) * n;
    ++result_->cushion_hits;
    result_->max_cushion_normal_speed = std::max(result_->max_cushion_normal_speed, in.velocity.y);
    if (r.status == ImpactStatus::rigid_limit_exceeded) result_->rigid_limit_exceeded = true;
    if (r.method_used == ImpactMethod::table) ++result_->table_impacts;
    log(EventType::cushion, which, -1, in.velocity.y);
    check_cushions_ = cushions_in_reach();
  }

  void log(EventType type, int cushion, int index, double normal_speed) {
    ShotEvent e;
    e.type = type;
    e.time = t_;
    e.position = b_.p;
    e.velocity = b_.v;
    e.spin = b_.w;
    e.cushion = cushion;
    e.index = index;
    e.normal_speed = normal_speed;
    result_->events.push_back(e);
  }

  // Whether any cushion is still within reach; refreshed after every cushion.
  bool cushions_in_reach() const {
    const double d = reach(cloth_, b_);
    for (const CushionLine& c : lines_)
      if (c.contact - dot(c.normal, b_.p) <= d) return true;
    return false;
  }

  const Scene& scene_;
  const SimulationOptions& options_;
  const ClothModel cloth_;
  const std::array<CushionLine, 4> lines_;
  ImpactOptions impact_;
  ShotResult* result_;
  Ball b_;
  double t_ = 0.0;
  bool check_cushions_ = false;
};

ShotResult invalid_shot(ValidationError error) {
  ShotResult result;
  result.status = ShotStatus::invalid_input;
  result.message = error.message();
  result.error = std::move(error);
  return result;
}

}  // namespace

ShotResult simulate(const CompiledScene& compiled, Vec2 cue_ball, const Shot& shot,
                    const SimulationOptions& options) {
  if (compiled.error()) return invalid_shot(*compiled.error());
  const Scene& scene = compiled.scene();
  if (Validation e = check_stroke(scene, cue_ball, shot, options)) return invalid_shot(std::move(*e));
  ShotResult result;
  ShotRun run(scene, options, &result);
  run.strike(cue_ball, shot);
  run.run();
  return result;
}

ShotResult simulate(const Scene& scene, Vec2 cue_ball, const Shot& shot,
                    const SimulationOptions& options) {
  return simulate(CompiledScene(scene), cue_ball, shot, options);
}

}  // namespace cueplan::physics
