// Problem files into a Problem: each section read in the order the format lists them,
// then the physics' own checks on the finished scene and positions (problems/README.md).
#include <fmt/format.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "cueplan/problems/ball_names.hpp"
#include "cueplan/problems/presets.hpp"
#include "cueplan/problems/problem.hpp"
#include "cueplan/problems/stroke_ranges.hpp"
#include "yaml_fields.hpp"

namespace cueplan::problems {
namespace {

using detail::Field;
using detail::FieldError;
using detail::Mapping;
using FieldLines = std::map<std::string, int>;  // path in the file -> line

constexpr const char* kDocument = "(document)";

// Line of `field`, or of the nearest enclosing field the file gives; else `fallback`.
int line_in_file(std::string field, const FieldLines& lines, int fallback) {
  while (!field.empty()) {
    if (const auto it = lines.find(field); it != lines.end()) return it->second;
    const std::size_t cut = field.find_last_of(".[");
    if (cut == std::string::npos) break;
    field.resize(cut);
  }
  return fallback;
}

// A broken rule of the finished problem (validate()) on the field of the file that
// sets the value, at its line.
[[noreturn]] void fail_on(const physics::ValidationError& error, const FieldLines& lines,
                          int fallback_line) {
  std::string field = file_field(error.field);
  std::string rule = error.rule_text(error.other ? file_field(*error.other) : "");
  // A table too small for the ball: when the file leaves that side at its default but
  // sets the radius, the radius is what it got wrong.
  const physics::FieldPath radius{"scene", "ball_and_cushion", "radius"};
  if (error.other == radius && !lines.contains(field) && lines.contains("ball.radius") &&
      error.value) {
    rule = fmt::format("leaves no room for the ball on the table: 2 R cos(theta) must be below "
                       "{} = {:.4g} m",
                       field, *error.value);
    field = "ball.radius";
  }
  throw FieldError{line_in_file(field, lines, fallback_line), field, rule};
}

std::string read_name(const Mapping& root, const std::string& source) {
  if (const std::optional<Field> field = root.find("name")) {
    std::string name = detail::text(*field);
    if (name.empty()) detail::fail(*field, "must not be empty");
    return name;
  }
  std::string stem = std::filesystem::path(source).stem().string();
  return stem.empty() ? std::string("problem") : stem;
}

// What table.pockets asks for; the jawed shapes are built once the ball's radius is
// known (read_ball), which their checks need.
struct PocketsSpec {
  enum class Kind { none, standard, jawed } kind = Kind::jawed;
  double pocket_radius = kDefaultPocketRadius;
  physics::PocketPreset shapes = *physics::pocket_preset("snooker");
  std::optional<Field> field;  // table.pockets, when the file gives it
  bool mapping = false;        // given as {corner: ..., middle: ...}
};

// One shape of table.pockets {corner: {...}, middle: {...}}: a key left out keeps the
// snooker preset's value.
physics::PocketShape read_pocket_shape(const Field& field, FieldLines& lines,
                                       physics::PocketShape shape) {
  const Mapping m(field, {"mouth", "wall_angle_deg", "shelf", "hole_radius", "point_radius"},
                  lines);
  if (auto f = m.find("mouth")) shape.mouth = detail::positive_number(*f);
  if (auto f = m.find("wall_angle_deg")) shape.wall_angle_deg = detail::number(*f);
  if (auto f = m.find("shelf")) shape.shelf = detail::number(*f);
  if (auto f = m.find("hole_radius")) shape.hole_radius = detail::positive_number(*f);
  if (auto f = m.find("point_radius")) shape.point_radius = detail::number(*f);
  return shape;
}

// table: length, width (m), pockets (none | standard | snooker | pool | carom | a mapping
// {corner: {mouth, wall_angle_deg, shelf, hole_radius, point_radius}, middle: {...}}),
// pocket_radius (m, the standard pockets' capture radius). Without `pockets` the table
// has the snooker preset's jawed pockets, or the standard capture circles when
// pocket_radius is given (files that set a radius keep their circles). Under a preset
// (`table: carom`, or `preset: carom` in the mapping; read_table_preset) the table has no
// pockets unless `pockets` says otherwise.
PocketsSpec read_table(const Mapping& root, FieldLines& lines, physics::Scene& scene,
                       bool preset) {
  PocketsSpec spec;
  if (preset) spec.kind = PocketsSpec::Kind::none;
  if (const std::optional<Field> table = root.find("table")) {
    if (table->value.IsScalar()) return spec;  // a preset's name: read_table_preset set it all
    const Mapping m(*table, {"preset", "length", "width", "pockets", "pocket_radius"}, lines);
    if (auto f = m.find("length")) scene.length = detail::positive_number(*f);
    if (auto f = m.find("width")) scene.width = detail::positive_number(*f);
    if (auto f = m.find("pocket_radius")) {
      spec.pocket_radius = detail::positive_number(*f);
      spec.kind = PocketsSpec::Kind::standard;
    }
    if (auto f = m.find("pockets")) {
      spec.field = *f;
      if (f->value.IsMap()) {
        const Mapping shapes(*f, {"corner", "middle"}, lines);
        spec.kind = PocketsSpec::Kind::jawed;
        spec.mapping = true;
        if (auto c = shapes.find("corner"))
          spec.shapes.corner = read_pocket_shape(*c, lines, spec.shapes.corner);
        if (auto c = shapes.find("middle"))
          spec.shapes.middle = read_pocket_shape(*c, lines, spec.shapes.middle);
      } else if (detail::is_word(*f, "none") || detail::is_word(*f, "carom")) {
        spec.kind = PocketsSpec::Kind::none;
      } else if (detail::is_word(*f, "standard")) {
        spec.kind = PocketsSpec::Kind::standard;
      } else if (detail::is_word(*f, "snooker") || detail::is_word(*f, "pool")) {
        spec.kind = PocketsSpec::Kind::jawed;
        spec.shapes = *physics::pocket_preset(detail::text(*f));
      } else {
        detail::fail(*f, "must be none, standard, snooker, pool, carom or a mapping {corner: "
                         "{...}, middle: {...}}, got " +
                             detail::describe_value(f->value));
      }
    }
  }
  return spec;
}

// The pockets table.pockets asked for, their shapes checked against the ball.
void build_pockets(const PocketsSpec& spec, const FieldLines& lines, physics::Scene& scene) {
  scene.pockets.clear();
  // Four corners and the middles of the long cushions y = 0 and y = width (kPocketNames).
  switch (spec.kind) {
    case PocketsSpec::Kind::none: return;
    case PocketsSpec::Kind::standard:
      scene.pockets = physics::standard_pockets(scene.length, scene.width, spec.pocket_radius);
      return;
    case PocketsSpec::Kind::jawed: break;
  }
  const double r = scene.radius();
  // A ball too big for the table is that rule's error (Scene::validate), not the pockets'.
  if (!(scene.length > 2.0 * r && scene.width > 2.0 * r)) return;
  for (const auto& [name, shape] :
       {std::pair{"corner", spec.shapes.corner}, std::pair{"middle", spec.shapes.middle}}) {
    const physics::Validation e = shape.validate(r);
    if (!e) continue;
    const std::string member = e->field.text();
    if (spec.mapping) {
      const std::string path = "table.pockets." + std::string(name) + "." + member;
      throw FieldError{line_in_file(path, lines, spec.field->line), path, e->rule_text()};
    }
    throw detail::FieldError{spec.field ? spec.field->line : 0, "table.pockets",
                             fmt::format("the {} pockets' {} {} (ball radius {:.4g} m)", name,
                                         member, e->rule_text(), r)};
  }
  scene.pockets =
      physics::jawed_pockets(scene.length, scene.width, spec.shapes.corner, spec.shapes.middle);
}

// table: carom, or table: {preset: carom, ...}: the match table and its constants
// (carom_scene()), before the file's own table, ball and physics fields override them.
// Returns whether a preset was applied.
bool read_table_preset(const Mapping& root, FieldLines& lines, physics::Scene& scene) {
  const std::optional<Field> table = root.find("table");
  if (!table) return false;
  std::optional<Field> name;
  if (table->value.IsScalar()) {
    name = *table;
  } else if (table->value.IsMap() && table->value["preset"]) {
    lines[table->path + ".preset"] = table->line;
    name = Field{table->value["preset"], table->path + ".preset", table->line};
  }
  if (!name) return false;
  if (!name->value.IsScalar())
    detail::fail(*name, "must be a preset's name (carom), got " + detail::describe_value(name->value));
  detail::one_of(*name, {"carom"});
  const std::vector<physics::ObjectBall> balls = scene.balls;
  scene = carom_scene();
  scene.balls = balls;
  return true;
}

// ball: radius (m), mass (kg). Keeps the rest of the cushion parameters at their defaults.
void read_ball(const Mapping& root, FieldLines& lines, physics::Scene& scene) {
  physics::CushionParams& ball = scene.ball_and_cushion;
  if (const std::optional<Field> field = root.find("ball")) {
    const Mapping m(*field, {"radius", "mass"}, lines);
    if (auto f = m.find("radius")) ball.radius = detail::positive_number(*f);
    if (auto f = m.find("mass")) ball.mass = detail::positive_number(*f);
  }
  // The cushion nose sits at 7R/5 unless physics.cushion_height says otherwise.
  ball.cushion_height = physics::params_for_radius(ball.radius).cushion_height;
}

// physics: cloth and cushion coefficients; mu_slide is both the cloth's sliding
// friction and the impact model's ball-table friction.
void read_physics(const Mapping& root, FieldLines& lines, physics::Scene& scene) {
  const std::optional<Field> field = root.find("physics");
  if (!field) return;
  const Mapping m(*field,
                  {"mu_slide", "mu_roll", "mu_spin", "mu_cushion", "restitution", "cushion_height",
                   "gravity", "mu_ball", "ball_restitution", "ball_model", "ball_friction",
                   "cushion_model", "eta_squared"},
                  lines);
  physics::CushionParams& cushion = scene.ball_and_cushion;
  physics::ClothParams& cloth = scene.cloth;
  if (auto f = m.find("mu_slide")) cloth.mu_slide = cushion.mu_table = detail::positive_number(*f);
  if (auto f = m.find("mu_roll")) cloth.mu_roll = detail::positive_number(*f);
  if (auto f = m.find("mu_spin")) cloth.mu_spin = detail::non_negative_number(*f);
  if (auto f = m.find("mu_cushion")) cushion.mu_cushion = detail::non_negative_number(*f);
  if (auto f = m.find("restitution")) cushion.restitution = detail::positive_number(*f);
  if (auto f = m.find("cushion_height")) cushion.cushion_height = detail::positive_number(*f);
  if (auto f = m.find("eta_squared")) cushion.eta_squared = detail::positive_number(*f);
  if (auto f = m.find("gravity")) cloth.gravity = detail::positive_number(*f);
  if (auto f = m.find("cushion_model")) {
    const std::string model =
        detail::one_of(*f, {"mathavan_2010", "han_2005", "stronge_compliant"});
    physics::parse_cushion_model(model, &cushion.model);
  }
  // Between the balls (the collision library checks the rest of their rules).
  physics::BallContact& contact = scene.ball_contact;
  if (auto f = m.find("mu_ball")) contact.mu_ball = detail::non_negative_number(*f);
  if (auto f = m.find("ball_restitution")) contact.restitution = detail::positive_number(*f);
  if (auto f = m.find("ball_model")) {
    const std::string model = detail::one_of(*f, {"mathavan_2014", "frictional_inelastic"});
    physics::parse_ball_model(model, &contact.model);
  }
  if (auto f = m.find("ball_friction")) {
    const std::string friction = detail::one_of(*f, {"constant", "speed_dependent"});
    physics::parse_ball_friction(friction, &contact.friction);
  }
}

// balls: a mapping from each object ball's name to its centre [x, y] (m), at rest.
void read_balls(const Mapping& root, FieldLines& lines, physics::Scene& scene) {
  const std::optional<Field> field = root.find("balls");
  if (!field) return;
  if (!field->value.IsMap())
    detail::fail(*field,
                 "must be a mapping from each object ball's name to its centre [x, y] in "
                 "m, got " +
                     detail::describe_value(field->value));
  const Mapping balls(*field, {}, lines);
  for (const auto& [name, position] : balls.entries()) {
    if (name == physics::kCueBallName)
      detail::fail(position, "names the cue ball (\"cue\"); an object ball needs another name");
    scene.balls.push_back({name, detail::point(position)});
  }
}

// The names of the object balls, for checking the fields that refer to them.
std::vector<std::string_view> ball_names(const physics::Scene& scene) {
  std::vector<std::string_view> names;
  for (const physics::ObjectBall& b : scene.balls) names.push_back(b.name);
  return names;
}

// A field that names one of the object balls.
std::string read_ball_name(const Field& field, const physics::Scene& scene) {
  if (scene.balls.empty())
    detail::fail(field, "names an object ball, but the file has no balls: " +
                            detail::describe_value(field.value));
  return detail::one_of(field, ball_names(scene), "the name of a ball in balls:");
}

// pot: {ball: NAME, pocket: POCKET} and first_contact: NAME, for pot-and-position planning.
void read_pot(const Mapping& root, FieldLines& lines, Problem& problem) {
  const physics::Scene& scene = problem.scene;
  if (const std::optional<Field> field = root.find("pot")) {
    const Mapping m(*field, {"ball", "pocket"}, lines);
    Pot pot;
    pot.ball = read_ball_name(m.require("ball", "the object ball to pot, a name in balls"), scene);
    const Field pocket = m.require("pocket", "the pocket to pot it in (bottom_left, ...)");
    const std::string name = detail::one_of(
        pocket, std::vector<std::string_view>(std::begin(kPocketNames), std::end(kPocketNames)));
    if (scene.pockets.empty())
      detail::fail(pocket, "names the " + name +
                               " pocket, but the table has none "
                               "(table.pockets: none)");
    pot.pocket = static_cast<int>(
        std::find(std::begin(kPocketNames), std::end(kPocketNames), std::string_view(name)) -
        std::begin(kPocketNames));
    problem.pot = pot;
  }
  if (const std::optional<Field> field = root.find("first_contact")) {
    // A class of balls (any_red, lowest, solids, stripes, any_colour) or one ball.
    if (field->value.IsScalar() && is_contact_class(field->value.Scalar())) {
      problem.first_contact = field->value.Scalar();
      const auto allowed = [&](const physics::ObjectBall& b) {
        return contact_allowed(*problem.first_contact, b.name, scene.balls);
      };
      if (std::none_of(scene.balls.begin(), scene.balls.end(), allowed))
        detail::fail(*field, "names the class " + *problem.first_contact +
                                 ", but no ball in balls belongs to it");
    } else {
      if (scene.balls.empty())
        detail::fail(*field, "names an object ball, but the file has no balls: " +
                                 detail::describe_value(field->value));
      std::vector<std::string_view> names = ball_names(scene);
      for (const char* c : kContactClasses) names.emplace_back(c);
      problem.first_contact =
          detail::one_of(*field, names, "the name of a ball in balls or a class of balls:");
    }
  }
}

// A pocket's name (kPocketNames) as its index; the table must have pockets.
int read_pocket(const Field& pocket, const physics::Scene& scene) {
  const std::string name = detail::one_of(
      pocket, std::vector<std::string_view>(std::begin(kPocketNames), std::end(kPocketNames)));
  if (scene.pockets.empty())
    detail::fail(pocket, "names the " + name + " pocket, but the table has none (table.pockets: none)");
  return static_cast<int>(
      std::find(std::begin(kPocketNames), std::end(kPocketNames), std::string_view(name)) -
      std::begin(kPocketNames));
}

// next: {ball: NAME, pocket: POCKET}, or a list of up to kMostNextPots of them: the pots
// to be played after this one, in order (position play). Needs `pot`.
void read_next(const Mapping& root, FieldLines& lines, Problem& problem) {
  const std::optional<Field> field = root.find("next");
  if (!field) return;
  const physics::Scene& scene = problem.scene;
  if (!problem.pot)
    detail::fail(*field, "needs a pot: the next pot is played after this stroke's pot (add pot:)");
  const auto one = [&](const Field& f) {
    if (!f.value.IsMap())
      detail::fail(f, "must be {ball: NAME, pocket: POCKET}, got " + detail::describe_value(f.value));
    const Mapping m(f, {"ball", "pocket"}, lines);
    NextPot n;
    n.ball = read_ball_name(m.require("ball", "the object ball to pot next, a name in balls"), scene);
    n.pocket = read_pocket(m.require("pocket", "the pocket to pot it in (bottom_left, ...)"), scene);
    problem.next.push_back(n);
  };
  if (field->value.IsSequence()) {
    problem.next_is_list = true;
    const std::vector<Field> items = detail::sequence(
        *field, 0, "a list of up to 3 pots {ball: NAME, pocket: POCKET}, in the order played");
    if (items.empty() || items.size() > static_cast<size_t>(kMostNextPots))
      detail::fail(*field, "must list 1 to 3 pots {ball: NAME, pocket: POCKET}, got " +
                               std::to_string(items.size()));
    for (const Field& item : items) {
      lines[item.path] = item.line;
      one(item);
    }
  } else {
    one(*field);
  }
}

void read_obstacles(const Mapping& root, Problem& problem, FieldLines& lines) {
  physics::Scene& scene = problem.scene;
  const std::optional<Field> field = root.find("obstacles");
  if (!field) return;
  // Named: a mapping from each obstacle's name to its centre, like balls.
  if (field->value.IsMap()) {
    const Mapping named(*field, {}, lines);
    for (const auto& [name, position] : named.entries()) {
      scene.obstacles.push_back(detail::point(position));
      problem.obstacle_names.push_back(name);
    }
    return;
  }
  for (const Field& obstacle : detail::sequence(*field, 0, "a list of points [x, y] in m")) {
    lines[obstacle.path] = obstacle.line;
    scene.obstacles.push_back(detail::point(obstacle));
  }
}

// cue: snooker | pool | {end_mass: kg} | {squirt_deg_at_half_tip: deg} (the squirt at a
// tip offset of R/4 with this problem's ball, turned into the equivalent end mass). Read
// after the ball, whose mass and radius the conversion needs.
void read_cue(const Mapping& root, FieldLines& lines, physics::Scene& scene) {
  scene.cue = physics::snooker_cue();
  const std::optional<Field> field = root.find("cue");
  if (!field) return;
  if (field->value.IsScalar()) {
    const std::string name = detail::one_of(*field, {"snooker", "pool"});
    scene.cue = name == "pool" ? physics::pool_cue() : physics::snooker_cue();
    return;
  }
  if (!field->value.IsMap())
    detail::fail(*field, "must be snooker, pool, {end_mass: KG} or {squirt_deg_at_half_tip: DEG}, "
                         "got " + detail::describe_value(field->value));
  const Mapping m(*field, {"end_mass", "squirt_deg_at_half_tip"}, lines);
  const std::optional<Field> mass = m.find("end_mass");
  const std::optional<Field> squirt = m.find("squirt_deg_at_half_tip");
  if (mass && squirt)
    detail::fail(*squirt, "give end_mass or squirt_deg_at_half_tip, not both");
  if (mass) {
    scene.cue.end_mass = detail::positive_number(*mass);
  } else if (squirt) {
    const double s = detail::positive_number(*squirt);
    const double m_ball = scene.ball_and_cushion.mass;
    const std::optional<double> end_mass = physics::end_mass_for_squirt(m_ball, s);
    if (!end_mass)
      detail::fail(*squirt, fmt::format("must be below {:.4g} deg: the squirt of a rigid cue at a "
                                        "tip offset of R/4",
                                        physics::squirt_angle_deg(physics::CueParams{1e300}, m_ball,
                                                                  1.0, 0.25 * physics::kSpinPerTipOffset)));
    scene.cue.end_mass = *end_mass;
  } else {
    detail::fail(*field, "needs end_mass (kg) or squirt_deg_at_half_tip (deg)");
  }
}

// A ball position [x, y]; where it may lie is checked with the whole problem.
physics::Vec2 read_position(const Mapping& root, std::string_view key, std::string_view meaning) {
  return detail::point(root.require(key, meaning));
}

// A count n (meaning [n, n]) or a range [lo, hi] of whole numbers, 0 <= lo <= hi <= 1000.
void read_count_range(const Mapping& m, const char* key, int* lo, int* hi) {
  const std::optional<Field> f = m.find(key);
  if (!f) return;
  constexpr int kMost = 1000;
  if (f->value.IsSequence()) {
    const auto bounds = detail::sequence(*f, 2, "a count n or a range [min, max]");
    *lo = detail::whole_number(bounds[0], 0, kMost);
    *hi = detail::whole_number(bounds[1], 0, kMost);
    if (*lo > *hi)
      detail::fail(*f, "min must not exceed max, got [" + bounds[0].value.Scalar() + ", " +
                           bounds[1].value.Scalar() + "]");
  } else {
    *lo = *hi = detail::whole_number(*f, 0, kMost);
  }
}

// limits.speed [min, max] m/s, spin, aim_deg (free | phi | [lo, hi]), cushions (n | [lo, hi]),
// elevation_deg [min, max].
Limits read_limits(const Mapping& root, FieldLines& lines) {
  Limits limits;
  const std::optional<Field> field = root.find("limits");
  if (!field) return limits;
  const Mapping m(*field,
                  {"speed", "spin", "aim_deg", "cushions", "elevation_deg",
                   "cushions_before_contact", "object_cushions"},
                  lines);

  if (const std::optional<Field> speed = m.find("speed")) {
    const auto bounds = detail::sequence(*speed, 2, "[min, max] in m/s");
    limits.speed_min = detail::positive_number(bounds[0]);
    limits.speed_max = detail::positive_number(bounds[1]);
    if (!(limits.speed_min < limits.speed_max))
      detail::fail(*speed, "min must be below max, got [" + bounds[0].value.Scalar() + ", " +
                               bounds[1].value.Scalar() + "]");
    // What no cue can give is refused here, as in a stroke (stroke_ranges.hpp).
    for (size_t i : {size_t{0}, size_t{1}})
      if (const StrokeRangeCheck c =
              check_speed_range(i == 0 ? limits.speed_min : limits.speed_max, "-");
          !c.ok())
        detail::fail(bounds[i], c.error.substr(2));
  }
  if (const std::optional<Field> spin = m.find("spin")) {
    limits.spin_max = detail::positive_number(*spin);
    if (const StrokeRangeCheck c = check_spin_range(limits.spin_max, "-"); !c.ok())
      detail::fail(*spin, c.error.substr(2));
  }

  if (const std::optional<Field> aim = m.find("aim_deg")) {
    if (detail::is_word(*aim, "free")) {
      limits.aim = {AimMode::free, 0.0, 0.0};
    } else if (aim->value.IsSequence()) {
      const auto bounds = detail::sequence(*aim, 2, "free, an angle, or [lo, hi] in deg");
      const double lo = detail::number(bounds[0]), hi = detail::number(bounds[1]);
      if (!(lo < hi) || hi - lo > 360.0)
        detail::fail(*aim, "needs lo < hi <= lo + 360 (deg), got [" + bounds[0].value.Scalar() +
                               ", " + bounds[1].value.Scalar() + "]");
      limits.aim = {AimMode::range, lo, hi};
    } else if (aim->value.IsScalar() && aim->value.Tag() == "?" &&
               !aim->value.Scalar().empty() &&
               std::isalpha(static_cast<unsigned char>(aim->value.Scalar().front()))) {
      detail::fail(*aim, "must be free, an angle, or [lo, hi] in deg, got " +
                             detail::describe_value(aim->value));
    } else {
      const double phi = detail::number(*aim);
      limits.aim = {AimMode::fixed, phi, phi};
    }
  }

  if (const std::optional<Field> elevation = m.find("elevation_deg")) {
    const auto bounds = detail::sequence(*elevation, 2, "[min, max] in deg, 0 <= min <= max < 90");
    limits.elevation_min_deg = detail::non_negative_number(bounds[0]);
    limits.elevation_max_deg = detail::non_negative_number(bounds[1]);
    if (!(limits.elevation_min_deg <= limits.elevation_max_deg) ||
        !(limits.elevation_max_deg < 90.0))
      detail::fail(*elevation, "needs 0 <= min <= max < 90 (deg), got [" +
                                   bounds[0].value.Scalar() + ", " + bounds[1].value.Scalar() + "]");
  }

  if (const std::optional<Field> cushions = m.find("cushions")) {
    constexpr int kMost = 1000;
    if (cushions->value.IsSequence()) {
      const auto bounds = detail::sequence(*cushions, 2, "a count n or a range [lo, hi]");
      limits.cushions_min = detail::whole_number(bounds[0], 0, kMost);
      limits.cushions_max = detail::whole_number(bounds[1], 0, kMost);
      if (limits.cushions_min > limits.cushions_max)
        detail::fail(*cushions, "lo must not exceed hi, got [" + bounds[0].value.Scalar() + ", " +
                                    bounds[1].value.Scalar() + "]");
    } else {
      limits.cushions_min = limits.cushions_max = detail::whole_number(*cushions, 0, kMost);
    }
  }
  read_count_range(m, "cushions_before_contact", &limits.cushions_before_contact_min,
                   &limits.cushions_before_contact_max);
  read_count_range(m, "object_cushions", &limits.object_cushions_min,
                   &limits.object_cushions_max);
  return limits;
}

// The stages of reading one problem, in order.
Problem read_problem(const Field& document, const std::string& source) {
  FieldLines lines;
  const Mapping root(
      document,
      {"name", "table", "ball", "physics", "cue_ball", "target", "tolerance", "obstacles", "balls",
       "limits", "max_strokes", "time_budget_s", "pot", "first_contact", "cue", "next", "leave"},
      lines);
  Problem problem;
  problem.source = source;
  problem.name = read_name(root, source);

  physics::Scene& scene = problem.scene;
  const bool preset = read_table_preset(root, lines, scene);
  const PocketsSpec pockets = read_table(root, lines, scene, preset);
  read_ball(root, lines, scene);
  // A preset's cushion keeps its own nose height unless physics.cushion_height says otherwise.
  if (preset) scene.ball_and_cushion.cushion_height = kCaromCushionHeight;
  build_pockets(pockets, lines, scene);
  read_physics(root, lines, scene);
  read_cue(root, lines, scene);
  read_obstacles(root, problem, lines);
  read_balls(root, lines, scene);
  problem.cue_ball = read_position(root, "cue_ball", "the cue ball's centre [x, y] in m");
  // With a pot the target may be left out: a pure pot, the cue ball free to stop anywhere;
  // with a first_contact and no pot, an escape: a legal hit is all that is asked.
  if (root.find("target") || !(root.find("pot") || root.find("first_contact")))
    problem.target = read_position(
        root, "target",
        "where the cue ball should stop, [x, y] in m (optional with a pot or a first_contact)");
  else
    problem.has_target = false;
  if (const std::optional<Field> f = root.find("tolerance"))
    problem.tolerance = detail::positive_number(*f);
  problem.limits = read_limits(root, lines);
  if (const std::optional<Field> f = root.find("max_strokes"))
    problem.max_strokes = detail::whole_number(*f, 1, kMostStrokes);
  if (const std::optional<Field> f = root.find("time_budget_s"))
    problem.time_budget_s = detail::positive_number(*f);
  read_pot(root, lines, problem);
  read_next(root, lines, problem);
  // A pot may be played with or without cushions: [0, 3] unless the file says otherwise.
  const std::optional<Field> limits = root.find("limits");
  const bool cushions_given = limits && limits->value.IsMap() && limits->value["cushions"];
  if (problem.pot && !cushions_given) problem.limits.cushions_min = 0;
  // An escape counts the cushions before the contact (cushions_before_contact); after it
  // the cue ball may meet any number, unless the file says otherwise.
  if (problem.is_escape() && !cushions_given) {
    problem.limits.cushions_min = 0;
    problem.limits.cushions_max = 1000;
  }
  if (const std::optional<Field> f = root.find("leave")) {
    if (!detail::is_word(*f, "safe"))
      detail::fail(*f, "must be safe (the opponent left no easy pot), got " +
                           detail::describe_value(f->value));
    if (!problem.is_escape())
      detail::fail(*f, "applies to an escape only (first_contact with no pot and no target)");
    problem.leave_safe = true;
  }
  // The physics' and the problem's own rules, on the finished problem.
  if (const physics::Validation error = validate(problem)) fail_on(*error, lines, root.line());
  return problem;
}

LoadResult failure(std::string error, std::string field = {}, int line = 0) {
  LoadResult r;
  r.error = std::move(error);
  r.field = std::move(field);
  r.line = line;
  return r;
}

// "FILE:LINE: FIELD: message" (without LINE when it is unknown).
LoadResult located(const std::string& source, int line, const std::string& field,
                   const std::string& message) {
  std::string where = source + ":";
  if (line > 0) where += std::to_string(line) + ":";
  return failure(where + " " + field + ": " + message, field, line);
}

// Where the first node of a YAML document starts; the rest of the events are ignored.
class FirstNodeLine : public YAML::EventHandler {
 public:
  int line() const { return line_; }

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { see(mark); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { see(mark); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                const std::string&) override {
    see(mark);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    see(mark);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    see(mark);
  }
  void OnMapEnd() override {}

 private:
  void see(const YAML::Mark& mark) {
    if (line_ == 0) line_ = mark.is_null() ? 1 : mark.line + 1;
  }
  int line_ = 0;
};

// The line at which a second YAML document starts in `text`, or 0 when there is none.
// Throws YAML exceptions for syntax errors in the first two documents. (YAML::LoadAll
// is not used: yaml-cpp 0.7 can loop forever in it on malformed text, jbeder/yaml-cpp
// pull request 1319; here the parser is asked for two documents at most.)
int second_document_line(const std::string& text) {
  std::istringstream stream(text);
  YAML::Parser parser(stream);
  FirstNodeLine first;
  if (!parser.HandleNextDocument(first)) return 0;
  FirstNodeLine second;
  if (!parser.HandleNextDocument(second)) return 0;
  return second.line() > 0 ? second.line() : 1;
}

}  // namespace

physics::Scene carom_scene() {
  physics::Scene scene;
  scene.length = 2.84;  // UMB match table: playing surface 2.84 x 1.42 m
  scene.width = 1.42;
  scene.pockets.clear();
  physics::CushionParams& c = scene.ball_and_cushion;
  c.radius = 0.03075;  // 61.5 mm ball (UMB: 61 to 61.5 mm)
  c.mass = 0.21;       // UMB: 205 to 220 g
  c.cushion_height = kCaromCushionHeight;
  c.mu_cushion = 0.14;   // Mathavan et al. 2010, ball on cushion rubber
  c.restitution = 0.85;  // Alciatore: ball-rail restitution 0.6 to 0.9
  physics::ClothParams& cloth = scene.cloth;
  cloth.mu_slide = c.mu_table = 0.2;  // Alciatore: ball-cloth sliding friction 0.15 to 0.4, typ. 0.2
  cloth.mu_roll = 0.005;  // Alciatore: 0.005 to 0.015; the low end for heated carom cloth
  // Alciatore: sidespin decays at 5 to 15 rad/s^2; 10 rad/s^2 = 5 mu_sp g / (2 R).
  cloth.mu_spin = 2.0 * c.radius * 10.0 / (5.0 * cloth.gravity);
  scene.ball_contact.mu_ball = 0.05;      // Alciatore 0.03 to 0.08; Mathavan et al. 2014
  scene.ball_contact.restitution = 0.94;  // Alciatore: ball-ball restitution 0.92 to 0.98
  return scene;
}

std::string apply_physics_block(const std::string& yaml_text, const std::string& source_name,
                                physics::Scene* scene) {
  try {
    const YAML::Node root = YAML::Load(yaml_text);
    const int line = detail::line_of(root) > 0 ? detail::line_of(root) : 1;
    if (!root.IsMap())
      return source_name + ":" + std::to_string(line) +
             ": (document): must be a mapping with a physics: block, got " +
             detail::describe_value(root);
    FieldLines lines;
    const Mapping m({root, "", line}, {"name", "physics"}, lines);
    if (!m.find("physics"))
      return source_name + ":" + std::to_string(line) + ": physics: is missing";
    read_physics(m, lines, *scene);
    if (const physics::Validation error = scene->validate()) {
      const std::string field = file_field(error->field.under({"scene"}));
      return source_name + ":" + std::to_string(line_in_file(field, lines, line)) + ": " + field +
             ": " + error->rule_text("");
    }
    return {};
  } catch (const FieldError& e) {
    return source_name + ":" + std::to_string(e.line) + ": " + e.field + ": " + e.message;
  } catch (const YAML::Exception& e) {
    return source_name + ":" + std::to_string(e.mark.is_null() ? 0 : e.mark.line + 1) +
           ": yaml: " + detail::printable(e.msg);
  } catch (const std::exception& e) {
    return source_name + ": cannot be read: " + detail::printable(e.what());
  }
}

LoadResult parse_problem(const std::string& yaml_text, const std::string& source_name) {
  try {
    const int second_line = second_document_line(yaml_text);
    const YAML::Node root = YAML::Load(yaml_text);
    if (root.IsNull())
      return (located(source_name, 1, kDocument,
                             "is empty; a problem needs at least cue_ball and target"));
    if (second_line > 0)
      return (located(source_name, second_line, kDocument,
                             "holds a second YAML document; one problem per file"));
    const int line = detail::line_of(root) > 0 ? detail::line_of(root) : 1;
    if (!root.IsMap())
      return (located(source_name, line, kDocument,
                             "must be a mapping of fields (name, table, ..., limits), got " +
                                 detail::describe_value(root)));
    LoadResult loaded;
    loaded.problem = read_problem({root, "", line}, source_name);
    return loaded;
  } catch (const FieldError& e) {
    return located(source_name, e.line, e.field.empty() ? kDocument : e.field, e.message);
  } catch (const YAML::Exception& e) {
    // Syntax errors: yaml-cpp counts lines and columns from 0.
    const int line = e.mark.is_null() ? 0 : e.mark.line + 1;
    std::string message = detail::printable(e.msg);
    if (!e.mark.is_null()) message += " (column " + std::to_string(e.mark.column + 1) + ")";
    return located(source_name, line, "yaml", message);
  } catch (const std::exception& e) {
    return failure(source_name + ": cannot be read: " + detail::printable(e.what()));
  } catch (...) {
    return failure(source_name + ": cannot be read: unknown error");
  }
}

LoadResult load_problem(const std::string& path) {
  try {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
      return failure(path + ": is a directory, not a problem file");
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      const int error = errno;
      return failure(path + ": cannot open: " +
                     (error != 0 ? std::generic_category().message(error) : "unknown error"));
    }
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) return failure(path + ": cannot read");
    return parse_problem(text.str(), path);
  } catch (const std::exception& e) {
    return failure(path + ": cannot be read: " + e.what());
  }
}

}  // namespace cueplan::problems
