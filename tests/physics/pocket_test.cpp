// Tests of jawed pockets (PHYSICS.md, "Jawed pockets"): their geometry, the checks of a
// bad shape, contacts with the points and facings resolved by the cushion model, and
// the effective target size of a pool pocket against Alciatore's technical proofs
// TP 3.5 (side pocket) and TP 3.6 (corner pocket).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>

#include "cueplan/physics/shot.hpp"

namespace cueplan::physics {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kInch = 0.0254;

Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
double norm(Vec2 a) { return std::hypot(a.x, a.y); }
Vec2 rotate(Vec2 a, double rad) {
  return {a.x * std::cos(rad) - a.y * std::sin(rad), a.x * std::sin(rad) + a.y * std::cos(rad)};
}

// TP 3.6's corner pocket: mouth 4.5875 in, wall angle 7 deg, hole radius 2.75 in, shelf
// 1.125 in. The point rounding is not part of TP 3.6's model (sharp points): a small
// 1/16 in here.
PocketShape tp36_corner() {
  return {4.5875 * kInch, 7.0, 1.125 * kInch, 2.75 * kInch, 0.0625 * kInch};
}
// TP 3.5's side pocket (WPA side pocket: mouth 5 in, pocket angle 104 deg = wall angle
// 14 deg, shelf 0.375 in, hole as the corner's).
PocketShape tp35_side() { return {5.0 * kInch, 14.0, 0.375 * kInch, 2.75 * kInch, 0.0625 * kInch}; }

// An 8-ft pool table (88 x 44 in playing surface), pool balls (R = 1.125 in, 6 oz).
Scene pool_scene(const PocketShape& corner, const PocketShape& middle) {
  Scene s;
  s.length = 88.0 * kInch;
  s.width = 44.0 * kInch;
  s.ball_and_cushion = params_for_radius(1.125 * kInch);
  s.ball_and_cushion.mass = 0.17;
  s.pockets = jawed_pockets(s.length, s.width, corner, middle);
  return s;
}

// Whether a slowly rolling ball on the line at `angle` (rad) from the pocket's centre
// line, `offset` (m) to the left of the line through the mouth's centre, drops into
// pocket `pocket`. nullopt when that line's start is not on the table.
std::optional<bool> drops(const CompiledScene& scene, int pocket, double angle, double offset,
                          double speed) {
  const PocketJaws& j = *scene.scene().pockets[static_cast<size_t>(pocket)].jaws;
  const Vec2 d = rotate(j.inward, angle);
  const Vec2 left{-d.y, d.x};
  const double back = 0.3;  // m before the mouth
  const Vec2 start = j.mouth_centre - back * d + offset * left;
  if (scene.scene().check_position(start, {"cue_ball"})) return std::nullopt;
  SimulationOptions o;
  o.record_path = false;
  const ShotResult r =
      simulate(scene, start, {speed, std::atan2(d.y, d.x) / kDeg, 1.0, 0.0}, o);
  return r.status == ShotStatus::pocketed && r.balls[0].pocket == pocket;
}

// The effective target size (m): the width of the band of parallel lines of approach
// at `angle_deg` from the centre line along which the ball drops, found by scanning the
// lateral offset in steps of `step`.
double target_size(const CompiledScene& scene, int pocket, double angle_deg,
                   double speed = 0.5, double step = 0.1e-3) {
  int dropped = 0;
  const double span = 0.12;
  for (double b = -span; b <= span; b += step) {
    const std::optional<bool> in = drops(scene, pocket, angle_deg * kDeg, b, speed);
    if (in && *in) ++dropped;
  }
  return dropped * step;
}

TEST(Pockets, GeometryOfTheCornerPocket) {
  const PocketShape shape = tp36_corner();
  const Scene s = pool_scene(shape, tp35_side());
  ASSERT_FALSE(s.validate()) << s.validate()->message();
  const PocketJaws& j = *s.pockets[0].jaws;
  // Nose corners on the cushion lines, a mouth apart, symmetric about the bisector.
  EXPECT_NEAR(norm(j.corner[0] - j.corner[1]), shape.mouth, 1e-12);
  EXPECT_NEAR(j.corner[0].y, 0.0, 1e-12);
  EXPECT_NEAR(j.corner[1].x, 0.0, 1e-12);
  EXPECT_NEAR(j.corner[0].x, j.corner[1].y, 1e-12);
  // Facings converge at the wall angle.
  const double between = std::acos(dot(j.facing_dir[0], j.facing_dir[1])) / kDeg;
  EXPECT_NEAR(between, 2.0 * shape.wall_angle_deg, 1e-9);
  // The point's rounding touches the nose line and the facing line at point_radius.
  const Vec2 p = j.point_centre[0];
  EXPECT_NEAR(-p.y, shape.point_radius, 1e-12);  // below the nose y = 0
  const Vec2 f = j.facing_dir[0];
  const Vec2 n{-f.y, f.x};
  EXPECT_NEAR(dot(p - j.corner[0], n), shape.point_radius, 1e-12);
  // The hole: its nearest edge `shelf` beyond the mouth line on the centre line.
  EXPECT_NEAR(dot(j.hole_centre - j.mouth_centre, j.inward), shape.shelf + shape.hole_radius,
              1e-12);
}

TEST(Pockets, BallDownTheCentreLineDrops) {
  const CompiledScene s(pool_scene(tp36_corner(), tp35_side()));
  for (const int pocket : {0, 1, 2, 3, 4, 5}) {
    for (const double speed : {0.3, 1.0, 3.0}) {
      const std::optional<bool> in = drops(s, pocket, 0.0, 0.0, speed);
      ASSERT_TRUE(in.has_value());
      EXPECT_TRUE(*in) << "pocket " << pocket << " speed " << speed;
    }
  }
}

TEST(Pockets, BallAimedAtAPointReboundsOffItWithTheCushionModel) {
  // A rounding of 1/2 in, so that the ball meets the arc well inside its span.
  PocketShape side = tp35_side();
  side.point_radius = 0.5 * kInch;
  const CompiledScene s(pool_scene(tp36_corner(), side));
  const PocketJaws& j = *s.scene().pockets[1].jaws;  // bottom middle
  // Head on at the left point, along the normal through the middle of its arc (the
  // line from the unrounded corner through the rounding's centre).
  const Vec2 p = j.point_centre[0];
  const Vec2 c = j.corner[0];
  const Vec2 n = (1.0 / norm(p - c)) * (p - c);  // from the ball into the point
  const double off = s.scene().contact_offset();
  const double travel = 0.25;  // m from the start to the contact
  const Vec2 start = p - (side.point_radius + off + travel) * n;
  const double aim = std::atan2(n.y, n.x) / kDeg;
  const ShotResult r = simulate(s, start, {1.0, aim, 1.0, 0.0});
  ASSERT_NE(r.status, ShotStatus::invalid_input) << r.message;
  const ShotEvent* jaw = nullptr;
  for (const ShotEvent& e : r.events)
    if (e.type == EventType::jaw) {
      jaw = &e;
      break;
    }
  ASSERT_NE(jaw, nullptr);
  EXPECT_EQ(jaw->index, 1);
  EXPECT_EQ(jaw->cushion, 0);  // left point
  EXPECT_NEAR(norm(jaw->position - p), side.point_radius + off, 1e-9);
  // The same stroke head on into a flat cushion (y = 0), the same distance away.
  Scene flat = s.scene();
  flat.pockets.clear();
  const ShotResult f = simulate(flat, {1.0, off + travel}, {1.0, -90.0, 1.0, 0.0});
  const ShotEvent* cushion = nullptr;
  for (const ShotEvent& e : f.events)
    if (e.type == EventType::cushion) {
      cushion = &e;
      break;
    }
  ASSERT_NE(cushion, nullptr);
  // The rebound in the contact's frame is the flat cushion's: straight back at the same
  // speed, with the same spin about the same axis.
  EXPECT_NEAR(jaw->normal_speed, cushion->normal_speed, 1e-9);
  EXPECT_NEAR(dot(jaw->velocity, n), -cushion->velocity.y, 1e-9);
  EXPECT_NEAR(jaw->velocity.x * n.y - jaw->velocity.y * n.x, 0.0, 1e-9);
  const Vec2 jaw_spin{jaw->spin.x, jaw->spin.y};
  EXPECT_NEAR(jaw_spin.x * -n.y + jaw_spin.y * n.x, cushion->spin.x, 1e-6);
  // Jaw contacts are not rail contacts, but their speed counts.
  EXPECT_EQ(r.balls[0].jaw_hits >= 1, true);
  EXPECT_EQ(r.cushion_hits + r.balls[0].jaw_hits,
            static_cast<int>(std::count_if(r.events.begin(), r.events.end(), [](const ShotEvent& e) {
              return e.type == EventType::jaw || e.type == EventType::cushion;
            })));
  EXPECT_GE(r.max_cushion_normal_speed, jaw->normal_speed);
}

TEST(Pockets, MirrorSymmetryOfThePocket) {
  // Lines mirrored about the centre line give mirrored outcomes.
  const CompiledScene s(pool_scene(tp36_corner(), tp35_side()));
  for (const double angle : {0.0, 10.0, 25.0}) {
    for (const double offset : {0.004, 0.011, 0.016, 0.021}) {
      const std::optional<bool> a = drops(s, 0, angle * kDeg, offset, 0.5);
      const std::optional<bool> b = drops(s, 0, -angle * kDeg, -offset, 0.5);
      ASSERT_TRUE(a && b);
      EXPECT_EQ(*a, *b) << angle << " deg, " << offset << " m";
    }
  }
}

TEST(Pockets, BadShapesAreErrorsNamingTheField) {
  const double r = 1.125 * kInch;
  const auto field = [&](PocketShape shape) {
    const Validation e = shape.validate(r);
    return e ? e->field.text() : std::string("none");
  };
  PocketShape ok = tp36_corner();
  EXPECT_EQ(field(ok), "none");
  PocketShape narrow = ok;
  narrow.mouth = 2.0 * r - 1e-4;
  EXPECT_EQ(field(narrow), "mouth");
  PocketShape shelf = ok;
  shelf.shelf = -0.001;
  EXPECT_EQ(field(shelf), "shelf");
  PocketShape crossing = ok;
  crossing.wall_angle_deg = 40.0;
  EXPECT_EQ(field(crossing), "wall_angle_deg");
  PocketShape point = ok;
  point.point_radius = -0.001;
  EXPECT_EQ(field(point), "point_radius");
  PocketShape hole = ok;
  hole.wall_angle_deg = 0.0;
  hole.mouth = 8.0 * kInch;
  hole.hole_radius = 1.5 * kInch;
  EXPECT_EQ(field(hole), "hole_radius");
  // In a scene, under the pocket.
  Scene s = pool_scene(ok, tp35_side());
  s.pockets[2].jaws->shape.shelf = -1.0;
  const Validation e = s.validate();
  ASSERT_TRUE(e);
  EXPECT_EQ(e->field.text(), "pockets[2].shelf");
}

TEST(Pockets, PresetsAreValid) {
  for (const char* name : {"snooker", "pool"}) {
    const std::optional<PocketPreset> p = pocket_preset(name);
    ASSERT_TRUE(p) << name;
    const double r = std::string(name) == "pool" ? 1.125 * kInch : 0.02625;
    EXPECT_FALSE(p->corner.validate(r)) << name;
    EXPECT_FALSE(p->middle.validate(r)) << name;
  }
  EXPECT_FALSE(pocket_preset("carom"));
}

TEST(Pockets, BallInTheHoleIsInThePocket) {
  const Scene s = pool_scene(tp36_corner(), tp35_side());
  const Validation e = s.check_position(s.pockets[0].jaws->hole_centre, {"cue_ball"});
  ASSERT_TRUE(e);
  EXPECT_EQ(e->other->text(), "pockets[0]");
  // The mouth's centre is open cloth no longer, but a ball just in front of it is fine.
  const PocketJaws& j = *s.pockets[1].jaws;
  EXPECT_FALSE(s.check_position(j.mouth_centre - 0.05 * j.inward, {"cue_ball"}));
}

// The band of lines at 0 deg whose centre passes both rounded points untouched: an
// analytic lower bound on the target size straight in (a ball on such a line meets
// nothing before the hole, whose edge spans the channel), and the mouth an upper bound
// (a line outside it meets a cushion nose and comes back).
double clear_band(const Scene& s, int pocket) {
  const PocketJaws& j = *s.pockets[static_cast<size_t>(pocket)].jaws;
  const Vec2 left{-j.inward.y, j.inward.x};
  const double reach = j.shape.point_radius + s.contact_offset();
  return dot(j.point_centre[0] - j.mouth_centre, left) - reach +
         (dot(j.mouth_centre - j.point_centre[1], left) - reach);
}

// Alciatore TP 3.6 publishes the effective target size of a pool corner pocket for a
// slowly rolling ball: about 1.5 in straight in, 1.3 in at 30 deg and 3-3.5 in near
// 45 deg. cueplan's curve (docs/pockets.md, bench_pockets) does not reproduce the
// straight-in 1.5 in: the mouth is 4.59 in and the clear band past both points alone is
// 2.5 in, so what is checked here is the geometry's own bounds and the curve's shape:
// symmetric, and larger near 45 deg than straight in, where the rail helps.
TEST(Pockets, CornerTargetSizeWithinGeometricBoundsAndRailHelps) {
  const CompiledScene s(pool_scene(tp36_corner(), tp35_side()));
  const bool print = std::getenv("CUEPLAN_POCKET_CURVE") != nullptr;
  if (print)
    for (double a = -45.0; a <= 45.0; a += 5.0)
      std::printf("corner %6.1f deg  %.3f in\n", a, target_size(s, 0, a) / kInch);
  const double straight = target_size(s, 0, 0.0);
  EXPECT_GE(straight, clear_band(s.scene(), 0) - 2e-4);
  EXPECT_LE(straight, tp36_corner().mouth);
  for (const double a : {15.0, 30.0, 40.0})
    EXPECT_NEAR(target_size(s, 0, a), target_size(s, 0, -a), 2e-4) << a << " deg";
  double near_rail = 0.0;
  for (const double a : {35.0, 38.0, 41.0}) near_rail = std::max(near_rail, target_size(s, 0, a));
  EXPECT_GT(near_rail, 1.2 * straight);
}

// TP 3.5's side pocket: straight in it takes more than the corner pocket (its mouth is
// wider), and its target shrinks steadily as the approach turns from straight in.
TEST(Pockets, SidePocketTargetShrinksWithAngle) {
  const CompiledScene s(pool_scene(tp36_corner(), tp35_side()));
  const bool print = std::getenv("CUEPLAN_POCKET_CURVE") != nullptr;
  if (print)
    for (double a = 0.0; a <= 70.0; a += 5.0)
      std::printf("side %6.1f deg  %.3f in\n", a, target_size(s, 1, a) / kInch);
  const double straight = target_size(s, 1, 0.0);
  EXPECT_GE(straight, clear_band(s.scene(), 1) - 2e-4);
  EXPECT_LE(straight, tp35_side().mouth);
  EXPECT_GT(straight, target_size(s, 0, 0.0));
  double last = straight;
  for (const double a : {20.0, 40.0, 60.0}) {
    const double size = target_size(s, 1, a);
    EXPECT_LT(size, last) << a << " deg";
    last = size;
  }
}

}  // namespace
}  // namespace cueplan::physics
