// Tests of the second cushion model, Han (2005), against facts derived by hand from its
// impulse equations (docs/cushion_models.md): the frictionless limit, a head-on impact
// worked through in both friction regimes, energy, symmetry, scale invariance, the limit
// where it and Mathavan (2010) must agree, and its place behind the impact interface and
// in the shot simulator.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "cueplan/physics/cushion_impact.hpp"
#include "cueplan/physics/shot.hpp"

namespace cueplan::physics {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

CushionParams han_params() {
  CushionParams p;
  p.model = CushionModel::han_2005;
  return p;
}

ImpactResult han(const CushionParams& p, double v0, double alpha, double kt, double ks) {
  return resolve_impact(p, incoming_state_k(v0, alpha, kt, ks, p.radius));
}

TEST(CushionModelNames, RoundTripAndRejectOthers) {
  for (CushionModel m :
       {CushionModel::mathavan_2010, CushionModel::han_2005, CushionModel::stronge_compliant}) {
    CushionModel parsed = CushionModel::mathavan_2010;
    ASSERT_TRUE(parse_cushion_model(to_string(m), &parsed));
    EXPECT_EQ(parsed, m);
  }
  CushionModel untouched = CushionModel::han_2005;
  EXPECT_FALSE(parse_cushion_model("stronge", &untouched));
  EXPECT_FALSE(parse_cushion_model("Han_2005", &untouched));
  EXPECT_EQ(untouched, CushionModel::han_2005);
  EXPECT_EQ(CushionParams{}.model, CushionModel::mathavan_2010);
}

// mu = 0: the impulse lies along the contact normal, through the centre. Its horizontal
// part (1 + e) M c^2 vy turns the normal velocity round; the tangential velocity and
// every spin stay as they were; the vertical part is dropped with the ball's vertical
// velocity. So vy' = vy (1 - (1 + e) cos^2 theta), not -e vy.
TEST(Han2005, FrictionlessImpactTurnsOnlyTheNormalVelocity) {
  CushionParams p = han_params();
  p.mu_cushion = 0.0;
  const double c2 = 1.0 - p.sin_theta() * p.sin_theta();
  for (double e : {0.6, 0.85, 0.98, 1.0}) {
    p.restitution = e;
    for (double alpha : {10.0, 45.0, 90.0, 150.0})
      for (double kt : {-1.0, 0.0, 1.0})
        for (double ks : {-0.7, 0.0, 0.5}) {
          const BallState in = incoming_state_k(1.3, alpha, kt, ks, p.radius);
          const ImpactResult r = resolve_impact(p, in);
          ASSERT_EQ(r.status, ImpactStatus::ok) << r.message;
          const double tol = 1e-14 * 1.3;
          EXPECT_NEAR(r.outgoing.velocity.y, in.velocity.y * (1.0 - (1.0 + e) * c2), tol);
          EXPECT_NEAR(r.outgoing.velocity.x, in.velocity.x, tol);
          const double spin_tol = tol / p.radius;
          EXPECT_NEAR(r.outgoing.spin.x, in.spin.x, spin_tol);
          EXPECT_NEAR(r.outgoing.spin.y, in.spin.y, spin_tol);
          EXPECT_NEAR(r.outgoing.spin.z, in.spin.z, spin_tol);
          EXPECT_EQ(r.outgoing.velocity.z, 0.0);
        }
  }
}

// Head-on, no spin: the slip at the contact is -V sin(theta) along t = (0, -s, c) only.
// Worked by hand: P_n = (1 + e) M c V; the slip stops when 2 M s V / 7 <= mu P_n
// (stick, friction (2M/7) s V along t), else friction mu P_n along t.
TEST(Han2005, HeadOnWithoutSpinMatchesTheHandSolution) {
  const double V = 2.0;
  for (double mu : {0.05, 0.14, 0.3}) {
    CushionParams p = han_params();
    p.mu_cushion = mu;
    const double m = p.mass, R = p.radius, e = p.restitution;
    const double s = p.sin_theta(), c = std::sqrt(1.0 - s * s);
    const double normal = (1.0 + e) * m * c * V;
    const bool sticks = 2.0 * m * s * V / 7.0 <= mu * normal;
    const double ft = sticks ? 2.0 * m * s * V / 7.0 : mu * normal;
    const ImpactResult r = han(p, V, 90.0, 0.0, 0.0);
    ASSERT_EQ(r.status, ImpactStatus::ok) << r.message;
    SCOPED_TRACE(mu);
    EXPECT_EQ(sticks, mu >= 0.14);  // the snooker geometry sticks from mu ~ 0.113 up
    EXPECT_NEAR(r.outgoing.velocity.x, 0.0, 1e-15);
    EXPECT_NEAR(r.outgoing.velocity.y, V - (c * normal + s * ft) / m, 1e-13);
    // A draw-like spin about X: w_x = R ft / I = 5 ft / (2 M R).
    EXPECT_NEAR(r.outgoing.spin.x, 5.0 * ft / (2.0 * m * R), 1e-11);
    EXPECT_NEAR(r.outgoing.spin.y, 0.0, 1e-12);
    EXPECT_NEAR(r.outgoing.spin.z, 0.0, 1e-12);
    EXPECT_NEAR(r.rebound_angle_deg, 90.0, 1e-12);
    EXPECT_NEAR(r.impulse_total, normal, 1e-15);
    EXPECT_EQ(r.transition_count, sticks ? 1 : 0);
    EXPECT_EQ(r.method_used, ImpactMethod::closed_form);
    EXPECT_EQ(r.model, CushionModel::han_2005);
  }
}

TEST(Han2005, KineticEnergyNeverRises) {
  std::mt19937_64 rng(20051);
  std::uniform_real_distribution<double> alpha(1.0, 179.0), k(-1.25, 1.25), mu(0.0, 0.4),
      e(0.75, 1.0), h(1.05, 1.6), v(0.05, 5.0);
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    CushionParams p = han_params();
    p.mu_cushion = mu(rng);
    p.restitution = e(rng);
    p.cushion_height = h(rng) * p.radius;
    if (p.validate()) continue;
    const BallState in = incoming_state_k(v(rng), alpha(rng), k(rng), k(rng), p.radius);
    const ImpactResult r = resolve_impact(p, in);
    ASSERT_TRUE(usable(r.status)) << r.message;
    const double before = kinetic_energy(p, in);
    ASSERT_LE(kinetic_energy(p, r.outgoing), before * (1.0 + 1e-13)) << i;
    // And the ball leaves the cushion.
    ASSERT_LT(r.outgoing.velocity.y, 0.0) << i;
    ++checked;
  }
  EXPECT_GT(checked, 15000);
}

// Reflecting X -> -X maps the incoming (alpha, k_T, k_S) onto (180 - alpha, k_T, -k_S);
// the outgoing state reflects the same way (spin is a pseudovector: w_x stays).
TEST(Han2005, MirrorSymmetryOfSidespin) {
  const CushionParams p = han_params();
  for (double alpha : {20.0, 45.0, 70.0, 90.0})
    for (double kt : {-0.8, 0.0, 1.0})
      for (double ks : {-1.0, 0.3, 0.9}) {
        const ImpactResult a = han(p, 1.5, alpha, kt, ks);
        const ImpactResult b = han(p, 1.5, 180.0 - alpha, kt, -ks);
        ASSERT_EQ(a.status, ImpactStatus::ok);
        ASSERT_EQ(b.status, ImpactStatus::ok);
        const double tol = 1e-13, spin_tol = tol / p.radius;
        EXPECT_NEAR(b.outgoing.velocity.x, -a.outgoing.velocity.x, tol);
        EXPECT_NEAR(b.outgoing.velocity.y, a.outgoing.velocity.y, tol);
        EXPECT_NEAR(b.outgoing.spin.x, a.outgoing.spin.x, spin_tol);
        EXPECT_NEAR(b.outgoing.spin.y, -a.outgoing.spin.y, spin_tol);
        EXPECT_NEAR(b.outgoing.spin.z, -a.outgoing.spin.z, spin_tol);
        EXPECT_NEAR(b.rebound_angle_deg, 180.0 - a.rebound_angle_deg, 1e-9);
      }
}

TEST(Han2005, OutcomeScalesWithSpeed) {
  const CushionParams p = han_params();
  for (double alpha : {15.0, 60.0, 90.0, 130.0})
    for (double kt : {-1.0, 0.5})
      for (double ks : {-0.6, 0.0, 0.8}) {
        const ImpactResult one = han(p, 1.0, alpha, kt, ks);
        for (double scale : {0.1, 3.7}) {
          const ImpactResult r = han(p, scale, alpha, kt, ks);
          EXPECT_NEAR(r.rebound_speed / scale, one.rebound_speed, 1e-13);
          EXPECT_NEAR(r.rebound_angle_deg, one.rebound_angle_deg, 1e-10);
          EXPECT_NEAR(r.outgoing.spin.z / scale, one.outgoing.spin.z, 1e-10);
          EXPECT_NEAR(r.outgoing.spin.x / scale, one.outgoing.spin.x, 1e-10);
        }
      }
}

// Both models frictionless (no cushion nor cloth friction): Mathavan's cloth carries the
// vertical part of the contact impulse, so its ball leaves with -e vy; Han's drops it,
// leaving vy (1 - (1 + e) cos^2 theta). They differ by exactly (1 + e) sin^2 theta vy,
// and agree as the contact comes down to the equator. Tangential velocity and spin
// are untouched by both.
TEST(CushionModels, FrictionlessModelsDifferOnlyByTheDroppedVerticalImpulse) {
  for (double rise : {0.4, 0.1, 1e-3}) {  // sin(theta)
    CushionParams mathavan;
    mathavan.mu_cushion = 0.0;
    mathavan.mu_table = 0.0;
    mathavan.cushion_height = mathavan.radius * (1.0 + rise);
    CushionParams hanp = mathavan;
    hanp.model = CushionModel::han_2005;
    for (double alpha : {30.0, 90.0})
      for (double ks : {0.0, 0.7}) {
        const BallState in = incoming_state_k(1.2, alpha, 0.6, ks, mathavan.radius);
        ImpactOptions exact;
        exact.tolerance = 1e-13;
        const ImpactResult a = resolve_impact(mathavan, in, exact);
        const ImpactResult b = resolve_impact(hanp, in, exact);
        ASSERT_EQ(a.status, ImpactStatus::ok) << a.message;
        ASSERT_EQ(b.status, ImpactStatus::ok) << b.message;
        const double e = mathavan.restitution, vy = in.velocity.y;
        const double s = mathavan.sin_theta();
        EXPECT_NEAR(a.outgoing.velocity.y, -e * vy, 1e-10);
        EXPECT_NEAR(b.outgoing.velocity.y - a.outgoing.velocity.y, (1.0 + e) * s * s * vy,
                    1e-10);
        EXPECT_NEAR(b.outgoing.velocity.x, a.outgoing.velocity.x, 1e-10);
        const double spin_tol = 1e-10 / mathavan.radius;
        EXPECT_NEAR(b.outgoing.spin.x, a.outgoing.spin.x, spin_tol);
        EXPECT_NEAR(b.outgoing.spin.y, a.outgoing.spin.y, spin_tol);
        EXPECT_NEAR(b.outgoing.spin.z, a.outgoing.spin.z, spin_tol);
        if (rise <= 1e-3) {
          EXPECT_NEAR(b.rebound_angle_deg, a.rebound_angle_deg, 1e-4);
        }
      }
  }
}

// With the contact near the equator and no cloth friction, a ball sliding along the
// cushion (no spin about X, so the slip at the contact lies along X) meets Coulomb
// friction of the same size in both models: Mathavan's integration slides against a slip
// that keeps its direction, Han's one impulse does the same in closed form. They agree
// to O(sin theta).
TEST(CushionModels, SlidingAlongTheCushionAgreesNearTheEquator) {
  const double rise = 1e-4;
  CushionParams mathavan;
  mathavan.mu_table = 0.0;
  mathavan.cushion_height = mathavan.radius * (1.0 + rise);
  mathavan.mu_cushion = 0.5 * rise;  // Mathavan needs mu_w < tan(theta)
  CushionParams hanp = mathavan;
  hanp.model = CushionModel::han_2005;
  for (double alpha : {20.0, 45.0, 80.0}) {
    BallState in = incoming_state(1.0, alpha, 0.0, 0.0);
    const ImpactResult a = resolve_impact(mathavan, in);
    const ImpactResult b = resolve_impact(hanp, in);
    ASSERT_EQ(a.status, ImpactStatus::ok) << a.message;
    ASSERT_EQ(b.status, ImpactStatus::ok) << b.message;
    // What the friction changed, compared relative to its size.
    const double dvx_a = a.outgoing.velocity.x - in.velocity.x;
    const double dvx_b = b.outgoing.velocity.x - in.velocity.x;
    ASSERT_LT(dvx_a, 0.0);  // the friction did act
    EXPECT_NEAR(dvx_b / dvx_a, 1.0, 10 * rise);
    EXPECT_NEAR(b.outgoing.spin.z / a.outgoing.spin.z, 1.0, 10 * rise);
    EXPECT_NEAR(b.outgoing.velocity.y / a.outgoing.velocity.y, 1.0, 10 * rise);
  }
}

TEST(Han2005, ValidationHasItsOwnRules) {
  CushionParams p = han_params();
  // Mathavan's mu_w < tan(theta) does not bind Han's model.
  p.mu_cushion = 0.5;
  EXPECT_FALSE(p.validate());
  CushionParams m = p;
  m.model = CushionModel::mathavan_2010;
  ASSERT_TRUE(m.validate());
  EXPECT_EQ(m.validate()->field, FieldPath{"mu_cushion"});
  // A restitution too small to turn the ball round is refused, naming it.
  p.mu_cushion = 0.14;
  p.restitution = 0.1;
  const Validation v = p.validate();
  ASSERT_TRUE(v);
  EXPECT_EQ(v->field, FieldPath{"restitution"});
  EXPECT_NE(v->message().find("han_2005"), std::string::npos) << v->message();
  const ImpactResult r = resolve_impact(p, incoming_state(1.0, 45.0, 0.0, 0.0));
  EXPECT_EQ(r.status, ImpactStatus::invalid_input);
  // closed_form belongs to han_2005: Mathavan refuses it as a method.
  ImpactOptions o;
  o.method = ImpactMethod::closed_form;
  const ImpactResult refused = resolve_impact(CushionParams{}, incoming_state(1.0, 45.0, 0.0, 0.0), o);
  ASSERT_EQ(refused.status, ImpactStatus::invalid_input);
  EXPECT_EQ(refused.error->field, FieldPath{"method"});
}

// The Mathavan methods play no part: any method (even table without a table) gives the
// same closed form, and a batch gives what single calls give.
TEST(Han2005, MethodsAndBatchesGiveTheClosedForm) {
  const CushionParams p = han_params();
  std::vector<BallState> in;
  for (double alpha : {10.0, 50.0, 90.0, 140.0})
    for (double ks : {-0.5, 0.5}) in.push_back(incoming_state_k(1.1, alpha, 0.7, ks, p.radius));
  std::vector<ImpactResult> out(in.size());
  resolve_impacts(p, in, out);
  for (size_t i = 0; i < in.size(); ++i) {
    const ImpactResult one = resolve_impact(p, in[i]);
    for (ImpactMethod method : {ImpactMethod::paper, ImpactMethod::table,
                                ImpactMethod::extrapolation}) {
      ImpactOptions o;
      o.method = method;
      const ImpactResult r = resolve_impact(p, in[i], o);
      ASSERT_EQ(r.status, ImpactStatus::ok) << r.message;
      EXPECT_EQ(r.outgoing.velocity.x, one.outgoing.velocity.x);
      EXPECT_EQ(r.outgoing.spin.z, one.outgoing.spin.z);
      EXPECT_EQ(r.method_used, ImpactMethod::closed_form);
    }
    EXPECT_EQ(out[i].outgoing.velocity.y, one.outgoing.velocity.y);
    EXPECT_EQ(out[i].outgoing.spin.x, one.outgoing.spin.x);
  }
}

// A rolling ball sent straight at the cushion x = length: its state at the contact follows
// from rolling resistance alone (v^2 = v0^2 - 2 mu_r g d), and the simulator must give the
// han_2005 answer for that state, turned into the table frame.
TEST(Han2005, SimulatorResolvesCushionsWithTheScenesModel) {
  Scene scene = snooker_scene();
  scene.pockets.clear();
  scene.ball_and_cushion.model = CushionModel::han_2005;
  const Vec2 start{2.5, 0.9};
  const Shot shot{1.5, 0.0, 1.0, 0.0};
  SimulationOptions options;
  options.impact_method = ImpactMethod::table;  // ignored: no table is needed
  EXPECT_EQ(chosen_impact_method(scene, options), ImpactMethod::closed_form);
  const ShotResult r = simulate(scene, start, shot, options);
  ASSERT_EQ(r.status, ShotStatus::rest) << r.message;
  EXPECT_EQ(r.impact_method, ImpactMethod::closed_form);
  EXPECT_EQ(r.cushion_model, CushionModel::han_2005);
  const ShotEvent* cushion = nullptr;
  for (const ShotEvent& e : r.events)
    if (e.type == EventType::cushion && cushion == nullptr) cushion = &e;
  ASSERT_NE(cushion, nullptr);
  ASSERT_EQ(cushion->cushion, 1);
  const CushionParams& p = scene.ball_and_cushion;
  const double d = scene.length - scene.contact_offset() - start.x;
  const double v = std::sqrt(shot.speed * shot.speed - 2.0 * scene.cloth.mu_roll *
                                                           scene.cloth.gravity * d);
  const ImpactResult want = resolve_impact(p, incoming_state(v, 90.0, v / p.radius, 0.0));
  ASSERT_EQ(want.status, ImpactStatus::ok);
  // Cushion 1's frame: X = (0, -1), Y = (1, 0).
  EXPECT_NEAR(cushion->velocity.x, want.outgoing.velocity.y, 1e-9);
  EXPECT_NEAR(cushion->velocity.y, -want.outgoing.velocity.x, 1e-9);
  EXPECT_NEAR(cushion->spin.x, want.outgoing.spin.y, 1e-9 / p.radius);
  EXPECT_NEAR(cushion->spin.y, -want.outgoing.spin.x, 1e-9 / p.radius);
  EXPECT_NEAR(cushion->normal_speed, v, 1e-9);
  // The Mathavan scene gives another rebound (the models differ).
  Scene mathavan = scene;
  mathavan.ball_and_cushion.model = CushionModel::mathavan_2010;
  const ShotResult m = simulate(mathavan, start, shot);
  ASSERT_EQ(m.status, ShotStatus::rest) << m.message;
  EXPECT_EQ(m.cushion_model, CushionModel::mathavan_2010);
  EXPECT_GT(std::abs(m.final_position.x - r.final_position.x), 1e-3);
}

}  // namespace
}  // namespace cueplan::physics
