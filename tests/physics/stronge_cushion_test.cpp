// Tests of the stronge_compliant cushion model (docs/cushion_models.md): where it must
// agree with han_2005 (no friction; gross slip), what only compliance gives (the slip
// reverses when the contact sticks, at the tangential spring's own frequency), energy,
// symmetry and scaling, its parameter rule, and its place in the shot simulator.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "cueplan/physics/cushion_impact.hpp"
#include "cueplan/physics/shot.hpp"

namespace cueplan::physics {
namespace {

CushionParams params(CushionModel model) {
  CushionParams p;
  p.model = model;
  return p;
}

ImpactResult resolve(const CushionParams& p, double v0, double alpha, double kt, double ks) {
  return resolve_impact(p, incoming_state_k(v0, alpha, kt, ks, p.radius));
}

// Without friction the springs carry no tangential force: the outcome is Han's impulse.
TEST(StrongeCompliant, FrictionlessEqualsHan) {
  CushionParams s = params(CushionModel::stronge_compliant);
  CushionParams h = params(CushionModel::han_2005);
  s.mu_cushion = h.mu_cushion = 0.0;
  for (double alpha : {20.0, 60.0, 90.0, 140.0}) {
    const ImpactResult a = resolve(s, 2.0, alpha, 0.7, -0.5);
    const ImpactResult b = resolve(h, 2.0, alpha, 0.7, -0.5);
    ASSERT_EQ(a.status, ImpactStatus::ok) << a.message;
    EXPECT_EQ(a.method_used, ImpactMethod::closed_form);
    EXPECT_EQ(a.model, CushionModel::stronge_compliant);
    EXPECT_NEAR(a.outgoing.velocity.x, b.outgoing.velocity.x, 1e-12);
    EXPECT_NEAR(a.outgoing.velocity.y, b.outgoing.velocity.y, 1e-12);
    EXPECT_NEAR(a.outgoing.spin.z, b.outgoing.spin.z, 1e-9);
  }
}

// A ball that slips fast along the cushion slides throughout: friction mu P_n against the
// slip, as in Han's slide; the integration's quadrature of the normal force is the only
// difference.
TEST(StrongeCompliant, GrossSlipEqualsHansSlide) {
  CushionParams s = params(CushionModel::stronge_compliant);
  CushionParams h = params(CushionModel::han_2005);
  s.mu_cushion = h.mu_cushion = 0.14;
  const ImpactResult a = resolve(s, 2.0, 25.0, 0.0, 0.0);
  const ImpactResult b = resolve(h, 2.0, 25.0, 0.0, 0.0);
  ASSERT_EQ(b.transition_count, 0);  // Han slides too
  EXPECT_NEAR(a.outgoing.velocity.x, b.outgoing.velocity.x, 2e-4 * 2.0);
  EXPECT_NEAR(a.outgoing.velocity.y, b.outgoing.velocity.y, 2e-4 * 2.0);
  EXPECT_NEAR(a.outgoing.spin.z * s.radius, b.outgoing.spin.z * h.radius, 2e-4 * 2.0);
  EXPECT_LT(std::fabs(a.outgoing.velocity.x - b.outgoing.velocity.x), 1e-3);
}

// Head-on with sidespin only, the contact almost at the equator and friction that never
// lets go: the slip along the cushion swings on the tangential spring for the contact's
// time pi / omega (e = 1) at the frequency sqrt(3.5 / eta^2) omega, so it leaves at
// cos(pi sqrt(3.5 / eta^2)) of its start (to the integration's step: the spring lets go in
// the last step, 1/160 of the contact); the rigid stick of han_2005 leaves none.
TEST(StrongeCompliant, StickingSlipSwingsOnTheTangentialSpring) {
  for (double eta2 : {1.0, 1.5, 2.5}) {
    CushionParams s = params(CushionModel::stronge_compliant);
    s.restitution = 1.0;
    s.cushion_height = 1.0001 * s.radius;
    s.mu_cushion = 1000.0;  // the cone binds only as the normal force vanishes
    s.eta_squared = eta2;
    ASSERT_FALSE(s.validate().has_value());
    const BallState in = incoming_state_k(1.0, 90.0, 0.0, 0.6, s.radius);
    const double c = s.cos_theta(), sn = s.sin_theta();
    const double slip0 = in.velocity.x + s.radius * (in.spin.y * sn - in.spin.z * c);
    const ImpactResult r = resolve_impact(s, in);
    ASSERT_EQ(r.status, ImpactStatus::ok) << r.message;
    const double slip1 =
        r.outgoing.velocity.x + s.radius * (r.outgoing.spin.y * sn - r.outgoing.spin.z * c);
    EXPECT_NEAR(slip1 / slip0, std::cos(std::numbers::pi * std::sqrt(3.5 / eta2)), 0.02) << eta2;
    CushionParams h = s;
    h.model = CushionModel::han_2005;
    const ImpactResult rh = resolve_impact(h, in);
    const double slip_h =
        rh.outgoing.velocity.x + s.radius * (rh.outgoing.spin.y * sn - rh.outgoing.spin.z * c);
    EXPECT_NEAR(slip_h, 0.0, 1e-12);
  }
}

TEST(StrongeCompliant, KineticEnergyNeverRisesAndTheBallLeaves) {
  std::mt19937_64 rng(19941);
  std::uniform_real_distribution<double> alpha(1.0, 179.0), k(-1.25, 1.25), mu(0.0, 0.4),
      e(0.75, 1.0), h(1.05, 1.6), v(0.05, 5.0), eta(0.9, 3.4);
  int checked = 0;
  for (int i = 0; i < 5000; ++i) {
    CushionParams p = params(CushionModel::stronge_compliant);
    p.mu_cushion = mu(rng);
    p.restitution = e(rng);
    p.cushion_height = h(rng) * p.radius;
    p.eta_squared = eta(rng);
    if (p.validate()) continue;
    const BallState in = incoming_state_k(v(rng), alpha(rng), k(rng), k(rng), p.radius);
    const ImpactResult r = resolve_impact(p, in);
    ASSERT_TRUE(usable(r.status)) << r.message;
    ASSERT_LE(kinetic_energy(p, r.outgoing), kinetic_energy(p, in) * (1.0 + 1e-9)) << i;
    ASSERT_LT(r.outgoing.velocity.y, 0.0) << i;
    ++checked;
  }
  EXPECT_GT(checked, 3000);
}

TEST(StrongeCompliant, MirrorSymmetryAndScaling) {
  const CushionParams p = params(CushionModel::stronge_compliant);
  const ImpactResult a = resolve(p, 1.5, 55.0, 0.4, 0.8);
  const ImpactResult m = resolve(p, 1.5, 125.0, 0.4, -0.8);
  EXPECT_NEAR(a.outgoing.velocity.x, -m.outgoing.velocity.x, 1e-12);
  EXPECT_NEAR(a.outgoing.velocity.y, m.outgoing.velocity.y, 1e-12);
  EXPECT_NEAR(a.outgoing.spin.z, -m.outgoing.spin.z, 1e-9);
  const ImpactResult b = resolve(p, 3.0, 55.0, 0.4, 0.8);
  EXPECT_NEAR(b.outgoing.velocity.x, 2.0 * a.outgoing.velocity.x, 1e-12);
  EXPECT_NEAR(b.outgoing.velocity.y, 2.0 * a.outgoing.velocity.y, 1e-12);
  EXPECT_NEAR(b.outgoing.spin.z, 2.0 * a.outgoing.spin.z, 1e-9);
}

TEST(StrongeCompliant, StiffnessRatioHasItsRange) {
  CushionParams p = params(CushionModel::stronge_compliant);
  for (double bad : {0.875, 3.5, 0.0, -1.0, std::nan("")}) {
    p.eta_squared = bad;
    const Validation v = p.validate();
    ASSERT_TRUE(v.has_value()) << bad;
    EXPECT_EQ(v->field.text(), "eta_squared");
  }
  p.eta_squared = 1.2;
  EXPECT_FALSE(p.validate().has_value());
  // Mathavan's model does not read it.
  p.model = CushionModel::mathavan_2010;
  p.eta_squared = 100.0;
  EXPECT_FALSE(p.validate().has_value());
}

TEST(StrongeCompliant, SimulatorResolvesCushionsWithIt) {
  Scene scene = snooker_scene();
  scene.pockets.clear();
  scene.ball_and_cushion.model = CushionModel::stronge_compliant;
  SimulationOptions options;
  options.impact_method = ImpactMethod::table;  // ignored: no table is needed
  EXPECT_EQ(chosen_impact_method(scene, options), ImpactMethod::closed_form);
  const ShotResult r = simulate(scene, {2.5, 0.9}, Shot{1.5, 10.0, 0.5, 0.6}, options);
  ASSERT_EQ(r.status, ShotStatus::rest) << r.message;
  EXPECT_EQ(r.cushion_model, CushionModel::stronge_compliant);
  EXPECT_GT(r.cushion_hits, 0);
}

}  // namespace
}  // namespace cueplan::physics
