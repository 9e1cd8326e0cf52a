// The scene, the stroke and their checks; names of the simulator's enums.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "ball_motion.hpp"
#include "scene_geometry.hpp"
#include "cueplan/physics/impact_table.hpp"
#include "cueplan/physics/shot.hpp"

namespace cueplan::physics {

using detail::dot;
using detail::norm;
using detail::operator+;
using detail::operator-;
using detail::operator*;

double Scene::contact_offset() const { return radius() * ball_and_cushion.cos_theta(); }

BallBallParams Scene::ball_ball_params() const {
  BallBallParams p;
  p.mass = ball_and_cushion.mass;
  p.radius = ball_and_cushion.radius;
  p.mu_ball = ball_contact.mu_ball;
  p.restitution = ball_contact.restitution;
  p.mu_table = cloth.mu_slide;
  p.model = ball_contact.model;
  p.friction = ball_contact.friction;
  return p;
}

Vec2 PathSegment::at(double t) const {
  const double dt = t - t0;
  return {p0.x + v0.x * dt + 0.5 * accel.x * dt * dt, p0.y + v0.y * dt + 0.5 * accel.y * dt * dt};
}

namespace {

// Two balls closer than 2R (a hair of rounding allowed: touching is fine).
bool overlap(Vec2 a, Vec2 b, double radius) { return norm(a - b) < 2.0 * radius * (1.0 - 1e-9); }

// A rule of the collision parameters on the scene's own fields: mass, radius and cloth
// friction are the scene's, the rest is ball_contact.
FieldPath scene_field_of_collision(const FieldPath& field) {
  if (field == FieldPath{"mu_table"}) return {"cloth", "mu_slide"};
  if (field == FieldPath{"mass"} || field == FieldPath{"radius"})
    return field.under({"ball_and_cushion"});
  return field.under({"ball_contact"});
}

// Where a ball may lie: on the cloth, out of the pockets, clear of the obstacles and,
// with `object_balls`, of the object balls other than `self` (an index into balls, or -1).
Validation place_error(const Scene& s, Vec2 p, const FieldPath& what, bool object_balls, int self) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y))
    return invalid(what, "must be finite (m)", std::isfinite(p.x) ? p.y : p.x);
  const double off = s.contact_offset();
  // A jawed pocket holds a ball whose centre is in its hole; one in its mouth beyond
  // the cushion lines is in the jaws.
  for (size_t i = 0; i < s.pockets.size(); ++i) {
    const Pocket& k = s.pockets[i];
    if (!k.jaws) continue;
    const bool in_hole = norm(p - k.jaws->hole_centre) < k.jaws->shape.hole_radius;
    const Vec2 d = p - k.jaws->mouth_centre;
    const bool in_mouth = dot(d, k.jaws->inward) > -off &&
                          norm(d) < k.jaws->shape.mouth + k.jaws->shape.shelf;
    const bool off_table = p.x < off || p.x > s.length - off || p.y < off || p.y > s.width - off;
    const double reach = k.jaws->shape.point_radius + off;
    const bool on_point = norm(p - k.jaws->point_centre[0]) < reach * (1.0 - 1e-9) ||
                          norm(p - k.jaws->point_centre[1]) < reach * (1.0 - 1e-9);
    if (in_hole || ((off_table && in_mouth) || on_point)) {
      ValidationError e = invalid(what, in_hole ? "lies inside {other}" : "lies in the jaws of {other}");
      e.other = FieldPath{"pockets", static_cast<int>(i)};
      return e;
    }
  }
  if (p.x < off || p.x > s.length - off || p.y < off || p.y > s.width - off)
    return invalid(what, fmt::format("({:.4g}, {:.4g}) lies off the table: its centre must be "
                                     "within [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] m",
                                     p.x, p.y, off, s.length - off, off, s.width - off));
  for (size_t i = 0; i < s.pockets.size(); ++i) {
    if (!s.pockets[i].jaws && norm(p - s.pockets[i].centre) < s.pockets[i].radius) {
      ValidationError e = invalid(what, "lies inside {other}");
      e.other = FieldPath{"pockets", static_cast<int>(i)};
      return e;
    }
  }
  for (size_t i = 0; i < s.obstacles.size(); ++i) {
    if (overlap(p, s.obstacles[i], s.radius())) {
      ValidationError e = invalid(what, "overlaps {other}");
      e.other = FieldPath{"obstacles", static_cast<int>(i)};
      return e;
    }
  }
  for (size_t i = 0; object_balls && i < s.balls.size(); ++i) {
    if (static_cast<int>(i) != self && overlap(p, s.balls[i].position, s.radius())) {
      ValidationError e = invalid(what, "overlaps {other}");
      e.other = FieldPath{"balls", s.balls[i].name};
      return e;
    }
  }
  return {};
}

// Object balls: a name each (not empty, not the cue ball's, not repeated), then a place.
Validation balls_error(const Scene& s) {
  for (size_t i = 0; i < s.balls.size(); ++i) {
    const std::string& name = s.balls[i].name;
    const FieldPath name_field{"balls", static_cast<int>(i), "name"};
    if (name.empty()) return invalid(name_field, "must not be empty");
    if (name == kCueBallName)
      return invalid(name_field,
                     fmt::format("must not be \"{}\": that is the cue ball's name", kCueBallName));
    for (size_t j = 0; j < i; ++j) {
      if (s.balls[j].name == name) {
        ValidationError e =
            invalid(name_field, fmt::format("repeats the name \"{}\" of {{other}}", name));
        e.other = FieldPath{"balls", static_cast<int>(j), "name"};
        return e;
      }
    }
  }
  for (size_t i = 0; i < s.balls.size(); ++i)
    if (Validation e = place_error(s, s.balls[i].position, {"balls", s.balls[i].name}, true,
                                   static_cast<int>(i)))
      return e;
  return {};
}

}  // namespace

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
  if (Validation e = cue.validate()) return e->under({"cue"});
  if (Validation e = ball_ball_params().validate()) {
    e->field = scene_field_of_collision(e->field);
    if (e->other) e->other = scene_field_of_collision(*e->other);
    return e;
  }
  for (size_t i = 0; i < pockets.size(); ++i) {
    const Pocket& k = pockets[i];
    const int index = static_cast<int>(i);
    if (!std::isfinite(k.centre.x) || !std::isfinite(k.centre.y))
      return invalid({"pockets", index, "centre"}, "must be finite (m)",
                     std::isfinite(k.centre.x) ? k.centre.y : k.centre.x);
    if (!std::isfinite(k.radius) || !(k.radius > 0.0))
      return invalid({"pockets", index, "radius"}, "must be positive and finite (m)", k.radius);
    if (k.jaws)
      if (Validation e = k.jaws->shape.validate(radius())) return e->under({"pockets", index});
  }
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
      if (overlap(o, obstacles[j], radius())) {
        ValidationError e = invalid(name, "overlaps {other}");
        e.other = FieldPath{"obstacles", static_cast<int>(j)};
        return e;
      }
    }
  }
  return balls_error(*this);
}

Validation Scene::check_position(Vec2 p, const FieldPath& what) const {
  return place_error(*this, p, what, true, -1);
}

Validation Scene::check_rest_position(Vec2 p, const FieldPath& what) const {
  return place_error(*this, p, what, false, -1);
}

std::vector<Pocket> standard_pockets(double length, double width, double radius) {
  return {{{0.0, 0.0}, radius, {}},   {{length / 2, 0.0}, radius, {}},
          {{length, 0.0}, radius, {}},  {{0.0, width}, radius, {}},
          {{length / 2, width}, radius, {}}, {{length, width}, radius, {}}};
}

namespace {

constexpr double kInch = 0.0254;
constexpr double kDegree = std::numbers::pi / 180.0;

Vec2 unit(Vec2 v) { return (1.0 / norm(v)) * v; }

// One jawed pocket from its unrounded nose corners (left, right as seen from the table),
// the cushions they end and each cushion's nose direction toward the pocket.
Pocket jawed_pocket(const PocketShape& shape, Vec2 inward, Vec2 left_corner, Vec2 right_corner,
                    int left_cushion, int right_cushion, Vec2 left_nose, Vec2 right_nose) {
  PocketJaws j;
  j.shape = shape;
  j.inward = inward;
  j.corner[0] = left_corner;
  j.corner[1] = right_corner;
  j.mouth_centre = 0.5 * (left_corner + right_corner);
  j.cushion[0] = left_cushion;
  j.cushion[1] = right_cushion;
  const Vec2 left{-inward.y, inward.x};  // toward the left corner
  const double a = shape.wall_angle_deg * kDegree;
  // Facings converge: each is turned from the centre line toward it.
  const Vec2 facing[2] = {std::cos(a) * inward - std::sin(a) * left,
                          std::cos(a) * inward + std::sin(a) * left};
  const Vec2 nose[2] = {left_nose, right_nose};
  const double hole_depth = shape.shelf + shape.hole_radius;  // of the hole's centre
  for (int side = 0; side < 2; ++side) {
    // The rounding sits in the rubber's wedge between the nose (back along -nose) and
    // the facing; its angle phi is the "pocket angle" (142 deg for a WPA corner).
    const Vec2 back = -1.0 * nose[side];
    const double phi = std::acos(std::clamp(dot(back, facing[side]), -1.0, 1.0));
    const double r = shape.point_radius;
    const double along = r / std::tan(0.5 * phi);  // corner to each tangent point
    const Vec2 bisector = unit(back + facing[side]);
    j.point_centre[side] = j.corner[side] + (r / std::sin(0.5 * phi)) * bisector;
    j.nose_tangent[side] = j.corner[side] + along * back;
    j.facing_start[side] = j.corner[side] + along * facing[side];
    j.facing_dir[side] = facing[side];
    // To the depth of the hole's centre: past it every centre the channel admits lies in
    // the hole (PocketShape::validate), so a ball never meets the facing beyond.
    j.facing_length[side] = std::max(0.0, hole_depth / std::cos(a) - along);
  }
  j.hole_centre = j.mouth_centre + hole_depth * inward;
  Pocket p;
  p.centre = j.mouth_centre;
  p.radius = 0.5 * shape.mouth;
  p.jaws = j;
  return p;
}

}  // namespace

Validation PocketShape::validate(double ball_radius) const {
  for (const auto& [name, value] :
       {std::pair{"mouth", mouth}, {"wall_angle_deg", wall_angle_deg}, {"shelf", shelf},
        {"hole_radius", hole_radius}, {"point_radius", point_radius}})
    if (!std::isfinite(value)) return invalid({name}, "must be finite", value);
  if (!(mouth > 2.0 * ball_radius))
    return invalid({"mouth"},
                   fmt::format("{:.4g} m is narrower than a ball ({:.4g} m)", mouth, 2.0 * ball_radius));
  if (wall_angle_deg < 0.0 || !(wall_angle_deg < 90.0))
    return invalid({"wall_angle_deg"},
                   "must be in [0, 90) deg: the facings converge into the pocket at that angle "
                   "to its centre line",
                   wall_angle_deg);
  if (shelf < 0.0) return invalid({"shelf"}, "must not be negative (m)", shelf);
  if (point_radius < 0.0) return invalid({"point_radius"}, "must not be negative (m)", point_radius);
  if (!(hole_radius > ball_radius))
    return invalid({"hole_radius"},
                   fmt::format("{:.4g} m must exceed the ball's radius ({:.4g} m)", hole_radius,
                               ball_radius),
                   hole_radius);
  const double a = wall_angle_deg * kDegree;
  const double hole_depth = shelf + hole_radius;
  // The facings cross (mouth / 2) / tan(a) beyond the mouth line.
  if (a > 0.0 && 0.5 * mouth / std::tan(a) <= hole_depth)
    return invalid({"wall_angle_deg"},
                   fmt::format("{:.4g} deg makes the facings cross {:.4g} m beyond the mouth, "
                               "before the hole's centre ({:.4g} m)",
                               wall_angle_deg, 0.5 * mouth / std::tan(a), hole_depth),
                   wall_angle_deg);
  // At the hole's centre depth every centre the channel admits must lie in the hole, so
  // that no ball passes it: the channel's half-width there, between the facings
  // themselves (a bound that holds for any cushion height), is at most the hole's radius.
  const double channel = 0.5 * mouth - hole_depth * std::tan(a);
  if (channel > hole_radius)
    return invalid({"hole_radius"},
                   fmt::format("{:.4g} m does not close the channel between the facings "
                               "({:.4g} m either side of the centre line at the hole's centre)",
                               hole_radius, channel),
                   hole_radius);
  return {};
}

std::vector<Pocket> jawed_pockets(double length, double width, const PocketShape& corner,
                                  const PocketShape& middle) {
  const double c = corner.mouth / std::numbers::sqrt2;  // corner to each nose corner
  const double s = std::numbers::sqrt2 / 2.0;
  const double h = 0.5 * middle.mouth;
  // Cushions: 0 y = 0, 1 x = length, 2 y = width, 3 x = 0.
  return {
      jawed_pocket(corner, {-s, -s}, {c, 0.0}, {0.0, c}, 0, 3, {-1, 0}, {0, -1}),
      jawed_pocket(middle, {0, -1}, {length / 2 + h, 0.0}, {length / 2 - h, 0.0}, 0, 0, {-1, 0},
                   {1, 0}),
      jawed_pocket(corner, {s, -s}, {length, c}, {length - c, 0.0}, 1, 0, {0, -1}, {1, 0}),
      jawed_pocket(corner, {-s, s}, {0.0, width - c}, {c, width}, 3, 2, {0, 1}, {-1, 0}),
      jawed_pocket(middle, {0, 1}, {length / 2 - h, width}, {length / 2 + h, width}, 2, 2, {1, 0},
                   {-1, 0}),
      jawed_pocket(corner, {s, s}, {length - c, width}, {length, width - c}, 2, 1, {1, 0}, {0, 1}),
  };
}

std::optional<PocketPreset> pocket_preset(std::string_view name) {
  if (name == "pool") {
    // WPA equipment specifications: corner mouth 4.5-4.625 in, side 5-5.125 in; pocket
    // angles 142 deg (corner) and 104 deg (side); shelf corner 1-2.25 in, side
    // 0-0.375 in. Hole radius as in Alciatore's TP 3.6; point rounding a small 1/8 in.
    return PocketPreset{{4.5625 * kInch, 7.0, 1.625 * kInch, 2.75 * kInch, 0.125 * kInch},
                        {5.0625 * kInch, 14.0, 0.1875 * kInch, 2.75 * kInch, 0.125 * kInch}};
  }
  if (name == "snooker") {
    // Typical dimensions of pockets cut to the WPBSA templates (the templates themselves
    // are not published; docs/pockets.md says where these come from).
    return PocketPreset{{0.086, 4.0, 0.010, 0.045, 0.010}, {0.105, 10.0, 0.0, 0.050, 0.012}};
  }
  return std::nullopt;
}

Scene snooker_scene() {
  Scene s;
  s.pockets = standard_pockets(s.length, s.width, kDefaultPocketRadius);
  return s;
}

Validation CueParams::validate() const {
  if (!std::isfinite(end_mass) || !(end_mass > 0.0))
    return invalid({"end_mass"}, "must be positive and finite (kg)", end_mass);
  return {};
}

// End masses (TP A-31's m_e): chosen, not measured, so that the squirt at a tip offset of
// R/4 lies inside the 0.5-3 deg band of real cues (docs/squirt.md).
CueParams snooker_cue() { return CueParams{0.012}; }
CueParams pool_cue() { return CueParams{0.010}; }

double squirt_angle_deg(const CueParams& cue, double ball_mass, double radius, double sidespin_k) {
  // Lateral tip offset over R: b / R = k_S / 2.5 (PHYSICS.md, "Cue strike").
  const double a = std::clamp(sidespin_k / kSpinPerTipOffset, -1.0, 1.0);
  (void)radius;  // the angle depends on b / R only
  const double c2 = 1.0 - a * a;
  // Alciatore TP A-31: the tip, a free end mass m_e, and the ball share the sideways
  // impulse while the tip's push along the contact normal sets the ball's speed.
  const double num = 2.5 * a * std::sqrt(c2);
  const double den = 1.0 + ball_mass / cue.end_mass + 2.5 * c2;
  return std::atan2(num, den) * 180.0 / std::numbers::pi;
}

std::optional<double> end_mass_for_squirt(double ball_mass, double squirt_deg) {
  if (!(squirt_deg > 0.0) || !std::isfinite(squirt_deg) || !(ball_mass > 0.0)) return {};
  const double a = 0.25, c2 = 1.0 - a * a;
  // tan s = 2.5 a sqrt(c2) / (1 + m_ball / m_end + 2.5 c2), solved for m_ball / m_end.
  const double ratio = 2.5 * a * std::sqrt(c2) / std::tan(squirt_deg * std::numbers::pi / 180.0) -
                       1.0 - 2.5 * c2;
  if (!(ratio > 0.0) || !std::isfinite(ratio)) return {};
  return ball_mass / ratio;
}

Validation Shot::validate() const {
  if (!std::isfinite(speed) || !(speed > 0.0))
    return invalid({"speed"}, "must be positive and finite (m/s)", speed);
  if (!std::isfinite(aim_deg)) return invalid({"aim_deg"}, "must be finite (deg)", aim_deg);
  if (!std::isfinite(topspin_k)) return invalid({"topspin_k"}, "must be finite", topspin_k);
  if (!std::isfinite(sidespin_k)) return invalid({"sidespin_k"}, "must be finite", sidespin_k);
  if (!std::isfinite(elevation_deg) || elevation_deg < 0.0 || !(elevation_deg < 90.0))
    return invalid({"elevation_deg"}, "must be at least 0 and below 90 (deg)", elevation_deg);
  return {};
}

CompiledScene::CompiledScene(Scene scene)
    : scene_(std::move(scene)),
      error_(scene_.validate()),
      ball_ball_(scene_.ball_ball_params()),
      geometry_(std::make_shared<const detail::SceneGeometry>(
          error_ ? detail::SceneGeometry{} : detail::scene_geometry(scene_))) {}

const char* to_string(EventType type) {
  switch (type) {
    case EventType::strike: return "strike";
    case EventType::slide_to_roll: return "slide_to_roll";
    case EventType::spin_stop: return "spin_stop";
    case EventType::cushion: return "cushion";
    case EventType::pocket: return "pocket";
    case EventType::obstacle: return "obstacle";
    case EventType::rest: return "rest";
    case EventType::ball_contact: return "ball_contact";
    case EventType::jaw: return "jaw";
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
    case ShotStatus::collision_failed: return "collision_failed";
    case ShotStatus::time_limit: return "time_limit";
  }
  return "unknown";
}

ImpactMethod chosen_impact_method(const Scene& scene, const SimulationOptions& options) {
  if (scene.ball_and_cushion.model == CushionModel::han_2005 ||
      scene.ball_and_cushion.model == CushionModel::stronge_compliant)
    return ImpactMethod::closed_form;
  if (options.impact_method == ImpactMethod::paper) return ImpactMethod::paper;
  if (options.impact_method == ImpactMethod::extrapolation) return ImpactMethod::extrapolation;
  if (options.impact_method == ImpactMethod::table && options.table != nullptr &&
      options.table->covers(scene.ball_and_cushion) &&
      options.table->measured_error().max_state_relative <= options.impact_accuracy)
    return ImpactMethod::table;
  return ImpactMethod::exact;
}

}  // namespace cueplan::physics
