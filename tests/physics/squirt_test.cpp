// Squirt and swerve at the cue strike (PHYSICS.md, "Squirt and swerve"): the squirt angle
// against limits derived here independently of the code's formula, its direction and
// size for the cue presets, and the swerve of an elevated cue against a numerical
// integration of the sliding ball from the strike's impulse.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "cueplan/physics/shot.hpp"

namespace cueplan::physics {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A snooker ball and a pool ball (the pool one: 170 g, 57.15 mm).
constexpr double kSnookerMass = 0.1406, kSnookerRadius = 0.02625;
constexpr double kPoolMass = 0.170, kPoolRadius = 0.028575;

// Sidespin k_S for a tip offset of `fraction` R (k = 2.5 d / R).
double side_k(double fraction) { return kSpinPerTipOffset * fraction; }

TEST(Squirt, ZeroAtCentreAndAwayFromTheSide) {
  for (const CueParams cue : {snooker_cue(), pool_cue()}) {
    EXPECT_EQ(squirt_angle_deg(cue, kPoolMass, kPoolRadius, 0.0), 0.0);
    // Right side (k_S > 0) squirts left: counter-clockwise, positive.
    EXPECT_GT(squirt_angle_deg(cue, kPoolMass, kPoolRadius, side_k(0.25)), 0.0);
    EXPECT_LT(squirt_angle_deg(cue, kPoolMass, kPoolRadius, -side_k(0.25)), 0.0);
    EXPECT_DOUBLE_EQ(squirt_angle_deg(cue, kPoolMass, kPoolRadius, -side_k(0.3)),
                     -squirt_angle_deg(cue, kPoolMass, kPoolRadius, side_k(0.3)));
  }
}

TEST(Squirt, GrowsWithTheOffsetUpToTheMiscueLimit) {
  const CueParams cue = pool_cue();
  double last = 0.0;
  for (double f = 0.025; f <= 0.5 + 1e-12; f += 0.025) {
    const double s = squirt_angle_deg(cue, kPoolMass, kPoolRadius, side_k(f));
    EXPECT_GT(s, last) << "offset " << f << " R";
    last = s;
  }
}

TEST(Squirt, GrowsWithTheEndMass) {
  double last = 0.0;
  for (double me : {0.002, 0.005, 0.01, 0.02, 0.05}) {
    const double s = squirt_angle_deg(CueParams{me}, kPoolMass, kPoolRadius, side_k(0.25));
    EXPECT_GT(s, last) << "end mass " << me;
    last = s;
  }
}

TEST(Squirt, PresetsAtAQuarterRadiusAreThoseOfRealCues) {
  // The done-when band for the pool cue, and the values the docs quote.
  const double pool = squirt_angle_deg(pool_cue(), kPoolMass, kPoolRadius, side_k(0.25));
  EXPECT_GT(pool, 0.5);
  EXPECT_LT(pool, 3.0);
  EXPECT_NEAR(pool, 1.70, 0.01);
  const double snooker =
      squirt_angle_deg(snooker_cue(), kSnookerMass, kSnookerRadius, side_k(0.25));
  EXPECT_GT(snooker, 0.5);
  EXPECT_LT(snooker, 3.0);
  EXPECT_NEAR(snooker, 2.30, 0.01);
}

// Small offsets, derived here from the impulses: the tip (a free end mass m_e sideways)
// pushes with F_x along the cue and F_y sideways at (-R, -d) from the centre; the tip
// does not slip, so the contact point's sideways speed v_y - w R equals the tip's, -F_y /
// m_e. With I = 2 m R^2 / 5 and I w = d F_x - R F_y this gives, to first order in d / R,
//   tan s = v_y / v_x = (d / R) / (1 + (2/5)(1 + m / m_e)),
// and the two limits: a rigid tip (m_e -> inf) squirts (5/7) d / R, a massless one not
// at all.
TEST(Squirt, SmallOffsetsMatchTheImpulseBalance) {
  const double a = 1e-3;  // d / R
  for (double me : {0.001, 0.01, 0.1, 1e6}) {
    const double expected = std::atan(a / (1.0 + 0.4 * (1.0 + kPoolMass / me))) / kDeg;
    const double s = squirt_angle_deg(CueParams{me}, kPoolMass, kPoolRadius, side_k(a));
    EXPECT_NEAR(s / expected, 1.0, 1e-5) << "end mass " << me;
  }
  const double rigid = squirt_angle_deg(CueParams{1e12}, kPoolMass, kPoolRadius, side_k(a));
  EXPECT_NEAR(std::tan(rigid * kDeg) / a, 5.0 / 7.0, 1e-5);
  const double massless = squirt_angle_deg(CueParams{1e-12}, kPoolMass, kPoolRadius, side_k(0.4));
  EXPECT_LT(std::abs(massless), 1e-8);
}

TEST(Squirt, TheCueBallLeavesOffTheCuesLine) {
  Scene scene;  // snooker, default (snooker) cue
  const double aim = 30.0;
  for (double k : {-0.8, -0.3, 0.0, 0.3, 0.8}) {
    const ShotResult r = simulate(scene, {1.0, 0.9}, Shot{1.0, aim, 0.5, k});
    ASSERT_EQ(r.status, ShotStatus::rest) << r.message;
    ASSERT_EQ(r.events[0].type, EventType::strike);
    const Vec2 v = r.events[0].velocity;
    const double left = std::atan2(v.y, v.x) / kDeg - aim;
    EXPECT_NEAR(left, squirt_angle_deg(scene.cue, scene.ball_and_cushion.mass, scene.radius(), k),
                1e-9);
    EXPECT_NEAR(std::hypot(v.x, v.y), 1.0, 1e-12);
    // Topspin about the horizontal axis across the actual motion: natural-roll sense,
    // no component along the motion for a level cue.
    const Vec3 w = r.events[0].spin;
    const double across = (-w.x * v.y + w.y * v.x) / std::hypot(v.x, v.y);
    const double along = (w.x * v.x + w.y * v.y) / std::hypot(v.x, v.y);
    EXPECT_NEAR(across * scene.radius() / 1.0, 0.5, 1e-12);
    EXPECT_NEAR(along, 0.0, 1e-12);
    if (k == 0.0) {
      EXPECT_NEAR(left, 0.0, 1e-12);
    } else {
      EXPECT_EQ(left > 0.0, k > 0.0);  // right side squirts left
    }
  }
}

TEST(Squirt, ValidationNamesTheFields) {
  Scene scene;
  scene.cue.end_mass = 0.0;
  ShotResult r = simulate(scene, {1.0, 0.9}, Shot{1.0, 0.0, 0.0, 0.0});
  ASSERT_EQ(r.status, ShotStatus::invalid_input);
  ASSERT_TRUE(r.error);
  EXPECT_EQ(r.error->field.text(), "cue.end_mass");
  scene.cue.end_mass = std::nan("");
  EXPECT_EQ(scene.validate()->field.text(), "cue.end_mass");

  Scene ok;
  for (double e : {-1.0, 90.0, 120.0, std::nan(""), static_cast<double>(INFINITY)}) {
    Shot shot{1.0, 0.0, 0.0, 0.3};
    shot.elevation_deg = e;
    r = simulate(ok, {1.0, 0.9}, shot);
    ASSERT_EQ(r.status, ShotStatus::invalid_input) << e;
    EXPECT_EQ(r.error->field.text(), "shot.elevation_deg") << e;
  }
}

// The sliding ball integrated by RK4 from the state an elevated cue's impulse gives it,
// worked out here in 3-D: (p, v, w) with dv/dt = -mu g u/|u|, dw/dt = (5 mu g / 2R) z x
// u/|u| (for the horizontal spin; the sidespin does not enter the slip), u = v + w x
// (-R z).
struct Slider {
  double px, py, vx, vy, wx, wy;
};

Slider rk4_step(const Slider& s, double h, double mu_g, double radius) {
  auto deriv = [&](const Slider& x) {
    const double ux = x.vx - radius * x.wy, uy = x.vy + radius * x.wx;
    const double n = std::hypot(ux, uy);
    const double dx = n > 0.0 ? ux / n : 0.0, dy = n > 0.0 ? uy / n : 0.0;
    const double k = 2.5 * mu_g / radius;
    // z x (dx, dy, 0) = (-dy, dx, 0)
    return Slider{x.vx, x.vy, -mu_g * dx, -mu_g * dy, -k * dy, k * dx};
  };
  auto add = [](const Slider& a, const Slider& b, double f) {
    return Slider{a.px + f * b.px, a.py + f * b.py, a.vx + f * b.vx,
                  a.vy + f * b.vy, a.wx + f * b.wx, a.wy + f * b.wy};
  };
  const Slider k1 = deriv(s), k2 = deriv(add(s, k1, h / 2)), k3 = deriv(add(s, k2, h / 2)),
               k4 = deriv(add(s, k3, h));
  Slider out = s;
  out = add(out, k1, h / 6);
  out = add(out, k2, h / 3);
  out = add(out, k3, h / 3);
  out = add(out, k4, h / 6);
  return out;
}

TEST(Swerve, RightSideWithElevationCurvesRightAsTheSlidingOdeSays) {
  Scene scene;
  const double R = scene.radius(), m = scene.ball_and_cushion.mass;
  const double mu_g = scene.cloth.mu_slide * scene.cloth.gravity;
  const Vec2 start{0.6, 0.9};
  const double V = 2.0, aim = 10.0, k = 0.8;
  for (double elevation : {0.0, 15.0, 30.0, 50.0}) {
    Shot shot{V, aim, 0.0, k};
    shot.elevation_deg = elevation;
    const ShotResult r = simulate(scene, start, shot);
    ASSERT_NE(r.status, ShotStatus::invalid_input) << r.message;
    ASSERT_GE(r.events.size(), 2u);
    ASSERT_EQ(r.events[1].type, EventType::slide_to_roll) << elevation;
    const double t_roll = r.events[1].time;

    // The strike from the impulse, independently of the simulator: in the frame of the
    // ball's motion (x ahead, y left, z up) the cue pushes J (cos e, 0, -sin e) through
    // r = (0, -d, 0), d = k R / 2.5 to the right, and J cos e = m V.
    const double e = elevation * kDeg, d = k * R / kSpinPerTipOffset;
    const double J = m * V / std::cos(e);
    const std::array<double, 3> rv{0.0, -d, 0.0}, Jv{J * std::cos(e), 0.0, -J * std::sin(e)};
    const std::array<double, 3> L{rv[1] * Jv[2] - rv[2] * Jv[1], rv[2] * Jv[0] - rv[0] * Jv[2],
                                  rv[0] * Jv[1] - rv[1] * Jv[0]};
    const double I = 0.4 * m * R * R;
    EXPECT_NEAR(L[2] / I * R / V, k, 1e-12);  // k_S keeps its meaning
    const double heading =
        (aim + squirt_angle_deg(scene.cue, m, R, k)) * kDeg;  // the squirted line
    const double c = std::cos(heading), s = std::sin(heading);
    Slider x{start.x, start.y, V * c, V * s, (L[0] * c - L[1] * s) / I, (L[0] * s + L[1] * c) / I};
    // Up to just before the ball rolls (where the slip's direction is undefined), then
    // against the simulator's sliding piece at that instant.
    const double t_end = 0.999 * t_roll;
    const int steps = 4000;
    const double h = t_end / steps;
    for (int i = 0; i < steps; ++i) x = rk4_step(x, h, mu_g, R);
    ASSERT_FALSE(r.path.empty());
    const PathSegment& slide = r.path.front();
    ASSERT_EQ(slide.motion, Motion::sliding);
    const Vec2 at = slide.at(t_end);
    const double dt = t_end - slide.t0;
    EXPECT_NEAR(at.x, x.px, 1e-9) << elevation;
    EXPECT_NEAR(at.y, x.py, 1e-9) << elevation;
    EXPECT_NEAR(slide.v0.x + slide.accel.x * dt, x.vx, 1e-9) << elevation;
    EXPECT_NEAR(slide.v0.y + slide.accel.y * dt, x.vy, 1e-9) << elevation;
    // The slip the RK4 ball has left there is what remains of 0.1 % of the slide.
    const double ux = x.vx - R * x.wy, uy = x.vy + R * x.wx;
    // |u| at the strike: V ahead (no topspin) and R w_par = k V tan e sideways.
    const double u0 = V * std::hypot(1.0, k * std::tan(e));
    EXPECT_NEAR(std::hypot(ux, uy), 1e-3 * u0, 1e-6 * V) << elevation;
    const Vec2 p = r.events[1].position;

    // Sideways from the squirted line at the end of the slide: right is negative.
    const double side = -(p.x - start.x) * s + (p.y - start.y) * c;
    if (elevation == 0.0) {
      EXPECT_NEAR(side, 0.0, 1e-12);
    } else {
      EXPECT_LT(side, -1e-3) << "elevation " << elevation << " swerves right";
    }
    // Left side swerves the other way, by the same amount.
    Shot mirror = shot;
    mirror.sidespin_k = -k;
    const ShotResult l = simulate(scene, start, mirror);
    const Vec2 q = l.events[1].position;
    const double hl = (aim - squirt_angle_deg(scene.cue, m, R, k)) * kDeg;
    EXPECT_NEAR(-(q.x - start.x) * std::sin(hl) + (q.y - start.y) * std::cos(hl), -side, 1e-12);
  }
}

TEST(Swerve, MoreElevationSwervesMore) {
  Scene scene;
  double last = 0.0;
  for (double elevation : {5.0, 10.0, 20.0, 40.0}) {
    Shot shot{1.5, 0.0, 0.0, 0.6};
    shot.elevation_deg = elevation;
    const ShotResult r = simulate(scene, {0.6, 0.9}, shot);
    ASSERT_EQ(r.events[1].type, EventType::slide_to_roll);
    const double h = squirt_angle_deg(scene.cue, scene.ball_and_cushion.mass, scene.radius(), 0.6) * kDeg;
    const Vec2 p = r.events[1].position;
    const double right = (p.x - 0.6) * std::sin(h) - (p.y - 0.9) * std::cos(h);
    EXPECT_GT(right, last) << elevation;
    last = right;
  }
}

}  // namespace
}  // namespace cueplan::physics
