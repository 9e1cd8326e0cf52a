// Properties of the cushion impact on random inputs (RapidCheck): mirror symmetry,
// scale invariance in V0 and in the ball's size, energy, determinism, the frictionless
// limit and the shape of every result. tests/physics/cushion_impact_test.cpp checks
// the same ideas on fixed cases and against independent solutions.
// Reproduce a failure with RC_PARAMS="seed=<the seed printed>".
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <cstring>

#include "cueplan/physics/cushion_impact.hpp"
#include "support/physics_checks.hpp"

namespace cueplan::physics {
namespace {

// Doubles drawn uniformly from [lo, hi] (RapidCheck's own doubles are not bounded).
rc::Gen<double> in_range(double lo, double hi) {
  return rc::gen::map(rc::gen::inRange<int64_t>(0, int64_t{1} << 40), [lo, hi](int64_t k) {
    return lo + (hi - lo) * static_cast<double>(k) / static_cast<double>(int64_t{1} << 40);
  });
}

// An incoming state in the paper's form over the target domain.
struct PaperState {
  double v0, alpha, kt, ks;
};

PaperState draw_paper_state() {
  return {*in_range(0.01, 5.0), *in_range(0.5, 179.5), *in_range(-3.0, 3.0), *in_range(-3.0, 3.0)};
}

// A general state: any direction into the cushion, any spin vector (R|w| up to 3 V).
BallState draw_general_state(const CushionParams& p) {
  const double v0 = *in_range(0.01, 5.0), alpha = *in_range(0.5, 179.5);
  BallState b = incoming_state(v0, alpha, 0.0, 0.0);
  const double unit = v0 / p.radius;
  b.spin = {*in_range(-3.0, 3.0) * unit, *in_range(-3.0, 3.0) * unit, *in_range(-3.0, 3.0) * unit};
  return b;
}

ImpactResult solve(const CushionParams& p, const PaperState& s) {
  return resolve_impact(p, incoming_state_k(s.v0, s.alpha, s.kt, s.ks, p.radius));
}

// Friction and restitution over the range of real tables and beyond; the stress run
// (tests/stress) covers the edges (e near 0, mu at its limits).
CushionParams draw_params() {
  CushionParams p;
  p.mu_cushion = *in_range(0.0, 0.3);
  p.mu_table = *in_range(0.0, 0.5);
  p.restitution = *in_range(0.2, 1.0);
  return p;
}

RC_GTEST_PROP(ImpactProperties, MirrorSymmetryAcrossTheNormal, ()) {
  // alpha -> 180 - alpha and k_S -> -k_S mirror the whole impact: beta -> 180 - beta,
  // the speed unchanged, w_x kept, w_y and w_z reversed.
  const CushionParams p = draw_params();
  const PaperState a = draw_paper_state();
  const PaperState b{a.v0, 180.0 - a.alpha, a.kt, -a.ks};
  const ImpactResult ra = solve(p, a), rb = solve(p, b);
  RC_ASSERT(usable(ra.status));
  RC_ASSERT(usable(rb.status));
  RC_ASSERT(std::abs(rb.rebound_speed - ra.rebound_speed) <= 1e-8 * a.v0);
  RC_ASSERT(std::abs(rb.outgoing.velocity.x + ra.outgoing.velocity.x) <= 1e-8 * a.v0);
  const double w = a.v0 / p.radius;
  RC_ASSERT(std::abs(rb.outgoing.spin.x - ra.outgoing.spin.x) <= 1e-8 * w);
  RC_ASSERT(std::abs(rb.outgoing.spin.y + ra.outgoing.spin.y) <= 1e-8 * w);
  RC_ASSERT(std::abs(rb.outgoing.spin.z + ra.outgoing.spin.z) <= 1e-8 * w);
  if (ra.rebound_speed > 1e-3 * a.v0)
    RC_ASSERT(std::abs(rb.rebound_angle_deg - (180.0 - ra.rebound_angle_deg)) <= 1e-5);
}

RC_GTEST_PROP(ImpactProperties, MirrorSymmetryOfGeneralStates, ()) {
  // The same mirror for any spin vector: (v_x, w_y, w_z) change sign.
  const CushionParams p = draw_params();
  const BallState a = draw_general_state(p);
  BallState b = a;
  b.velocity.x = -a.velocity.x;
  b.spin.y = -a.spin.y;
  b.spin.z = -a.spin.z;
  const ImpactResult ra = resolve_impact(p, a), rb = resolve_impact(p, b);
  RC_ASSERT(usable(ra.status));
  RC_ASSERT(usable(rb.status));
  const double v0 = std::hypot(a.velocity.x, a.velocity.y), w = v0 / p.radius;
  RC_ASSERT(std::abs(rb.outgoing.velocity.x + ra.outgoing.velocity.x) <= 1e-8 * v0);
  RC_ASSERT(std::abs(rb.outgoing.velocity.y - ra.outgoing.velocity.y) <= 1e-8 * v0);
  RC_ASSERT(std::abs(rb.outgoing.spin.x - ra.outgoing.spin.x) <= 1e-8 * w);
  RC_ASSERT(std::abs(rb.outgoing.spin.y + ra.outgoing.spin.y) <= 1e-8 * w);
  RC_ASSERT(std::abs(rb.outgoing.spin.z + ra.outgoing.spin.z) <= 1e-8 * w);
}

RC_GTEST_PROP(ImpactProperties, OutcomeScalesWithSpeed, ()) {
  // PHYSICS.md: for fixed (alpha, k_T, k_S) the rebound speed / V0 and beta do not
  // depend on V0, and impulses scale with V0.
  const CushionParams p = draw_params();
  const PaperState a = draw_paper_state();
  const double factor = *in_range(1e-3, 1e3);
  const PaperState b{a.v0 * factor, a.alpha, a.kt, a.ks};
  const ImpactResult ra = solve(p, a), rb = solve(p, b);
  RC_ASSERT(usable(ra.status));
  RC_ASSERT(usable(rb.status));
  RC_ASSERT(std::abs(rb.rebound_speed / b.v0 - ra.rebound_speed / a.v0) <= 1e-8);
  RC_ASSERT(std::abs(rb.impulse_total / b.v0 - ra.impulse_total / a.v0) <= 1e-8 * p.mass);
  if (ra.rebound_speed > 1e-3 * a.v0)
    RC_ASSERT(std::abs(rb.rebound_angle_deg - ra.rebound_angle_deg) <= 1e-5);
}

RC_GTEST_PROP(ImpactProperties, OutcomeScalesWithBallSizeAndMass, ()) {
  // impact_table.hpp: with the cushion at 7R/5, mass and radius scale out of the
  // outcome divided by V0 (spins as R w).
  PaperState s = draw_paper_state();
  const CushionParams a = params_for_radius(0.02625);
  CushionParams b = params_for_radius(*in_range(0.005, 0.1));
  b.mass = *in_range(0.01, 1.0);
  const ImpactResult ra = solve(a, s), rb = solve(b, s);
  RC_ASSERT(usable(ra.status));
  RC_ASSERT(usable(rb.status));
  RC_ASSERT(std::abs(rb.rebound_speed - ra.rebound_speed) <= 1e-8 * s.v0);
  RC_ASSERT(std::abs(b.radius * rb.outgoing.spin.z - a.radius * ra.outgoing.spin.z) <= 1e-8 * s.v0);
  RC_ASSERT(std::abs(rb.impulse_total / b.mass - ra.impulse_total / a.mass) <= 1e-8 * s.v0);
}

RC_GTEST_PROP(ImpactProperties, KineticEnergyNeverRises, ()) {
  const CushionParams p = draw_params();
  const BallState in = draw_general_state(p);
  const ImpactResult r = resolve_impact(p, in);
  RC_ASSERT(usable(r.status));
  RC_ASSERT(kinetic_energy(p, r.outgoing) <= kinetic_energy(p, in) * (1.0 + 1e-12));
  // The energetic restitution: the work at the contact is (1 - e^2) of compression's.
  RC_ASSERT(std::abs(r.work_total - (1.0 - p.restitution * p.restitution) * r.work_compression) <=
            1e-9 * p.mass * dot(in.velocity, in.velocity));
}

RC_GTEST_PROP(ImpactProperties, EveryResultLeavesTheCushionAndIsFinite, ()) {
  const CushionParams p = draw_params();
  const BallState in = draw_general_state(p);
  const ImpactResult r = resolve_impact(p, in);
  RC_ASSERT(usable(r.status));
  RC_ASSERT(test::all_finite(r));
  RC_ASSERT(r.outgoing.velocity.y < 0.0);
  RC_ASSERT(r.outgoing.velocity.z == 0.0);
  RC_ASSERT(r.impulse_compression > 0.0);
  RC_ASSERT(r.impulse_total >= r.impulse_compression);
  RC_ASSERT((r.status == ImpactStatus::rigid_limit_exceeded) ==
            (in.velocity.y > p.rigid_speed_limit));
}

RC_GTEST_PROP(ImpactProperties, SameInputBitIdenticalOutput, ()) {
  const CushionParams p = draw_params();
  const BallState in = draw_general_state(p);
  ImpactOptions o;
  o.method = *rc::gen::element(ImpactMethod::exact, ImpactMethod::paper);
  o.paper_steps = 500;
  const ImpactResult a = resolve_impact(p, in, o), b = resolve_impact(p, in, o);
  RC_ASSERT(a.status == b.status);
  RC_ASSERT(std::memcmp(&a.outgoing, &b.outgoing, sizeof a.outgoing) == 0);
  RC_ASSERT(std::memcmp(&a.impulse_total, &b.impulse_total, sizeof a.impulse_total) == 0);
  RC_ASSERT(a.rhs_evaluations == b.rhs_evaluations);
}

RC_GTEST_PROP(ImpactProperties, FrictionlessImpactReflectsAnyState, ()) {
  // Without friction only the normal velocity changes, to -e times itself.
  CushionParams p = draw_params();
  p.mu_cushion = p.mu_table = 0.0;
  const BallState in = draw_general_state(p);
  const ImpactResult r = resolve_impact(p, in);
  RC_ASSERT(usable(r.status));
  const double v0 = std::hypot(in.velocity.x, in.velocity.y), w = v0 / p.radius;
  RC_ASSERT(std::abs(r.outgoing.velocity.y + p.restitution * in.velocity.y) <= 1e-10 * v0);
  RC_ASSERT(std::abs(r.outgoing.velocity.x - in.velocity.x) <= 1e-12 * v0);
  RC_ASSERT(std::abs(r.outgoing.spin.x - in.spin.x) <= 1e-10 * w);
  RC_ASSERT(std::abs(r.outgoing.spin.y - in.spin.y) <= 1e-10 * w);
  RC_ASSERT(std::abs(r.outgoing.spin.z - in.spin.z) <= 1e-10 * w);
}

RC_GTEST_PROP(ImpactProperties, PaperSchemeWithinItsFirstOrderError, ()) {
  // The paper's scheme at N steps differs from exact by at most a few of its steps
  // (1 + e) sin(alpha) / N, relative to V0.
  const CushionParams p = draw_params();
  const PaperState s = draw_paper_state();
  ImpactOptions o;
  o.method = ImpactMethod::paper;
  o.paper_steps = 2000;
  const BallState in = incoming_state_k(s.v0, s.alpha, s.kt, s.ks, p.radius);
  const ImpactResult paper = resolve_impact(p, in, o), exact = resolve_impact(p, in);
  RC_ASSERT(usable(paper.status));
  RC_ASSERT(usable(exact.status));
  const double step = (1.0 + p.restitution) * std::sin(s.alpha * std::numbers::pi / 180.0) / 2000;
  RC_ASSERT(test::state_difference(p, paper, exact, s.v0) <= 20.0 * step);
}

}  // namespace
}  // namespace cueplan::physics
