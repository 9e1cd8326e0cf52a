// Tests of the Taylor method (`exact`, physics/src/impact_taylor.cpp) against
// independent computations: the extrapolation method (a different integrator of the
// same equations), the paper's first-order scheme at very large N extrapolated to
// zero step (where the two exact methods disagree), closed forms and limits. The tests
// of the model's physics that run for both exact methods are in cushion_impact_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cueplan/physics/cushion_impact.hpp"
#include "support/impact_domain.hpp"
#include "support/physics_checks.hpp"

namespace cueplan::physics {
namespace {

using test::state_difference;

ImpactResult with(ImpactMethod method, const CushionParams& p, const BallState& in,
                  double tolerance = ImpactOptions{}.tolerance) {
  ImpactOptions o;
  o.method = method;
  o.tolerance = tolerance;
  return resolve_impact(p, in, o);
}

double speed_of(const BallState& in) { return std::hypot(in.velocity.x, in.velocity.y); }

std::string scientific(double x) {
  std::ostringstream out;
  out << std::scientific << x;
  return out.str();
}

// The uniform domain of the accuracy targets (bench/bench_impact.cpp): alpha in
// (0, 180), |k_T|, |k_S| <= 3, V0 in (0.01, 5) m/s; natural roll fixes k_T = 1.
std::vector<BallState> uniform_domain(int count, bool natural_roll, uint64_t seed) {
  const CushionParams p;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> alpha(0.01, 179.99), k(-3.0, 3.0), v(0.01, 5.0);
  std::vector<BallState> out;
  for (int i = 0; i < count; ++i) {
    const double v0 = v(rng), a = alpha(rng), kt = k(rng), ks = k(rng);
    out.push_back(incoming_state_k(v0, a, natural_roll ? 1.0 : kt, ks, p.radius));
  }
  return out;
}

// The two exact methods at their default tolerance differ by at most 1e-10 of V0 over
// the uniform domain (each errs by under 1e-11 against the other converged).
TEST(TaylorImpact, AgreesWithExtrapolationOverTheUniformDomain) {
  const CushionParams p;
  double worst = 0.0;
  for (const BallState& in : uniform_domain(3000, false, 2010)) {
    const ImpactResult t = with(ImpactMethod::exact, p, in);
    const ImpactResult x = with(ImpactMethod::extrapolation, p, in);
    ASSERT_TRUE(usable(t.status)) << t.message;
    ASSERT_TRUE(usable(x.status)) << x.message;
    const double d = state_difference(p, t, x, speed_of(in));
    worst = std::max(worst, d);
    EXPECT_LT(d, 1e-10) << "velocity (" << in.velocity.x << ", " << in.velocity.y << ") spin ("
                        << in.spin.x << ", " << in.spin.y << ", " << in.spin.z << ")";
  }
  RecordProperty("worst_difference", scientific(worst));
}

// Natural roll, the commonest state at a cushion: the cloth slip starts at exactly
// zero and grows from it (the Taylor method's series in P^m v, the extrapolation
// method's quasi-static start).
TEST(TaylorImpact, AgreesWithExtrapolationAtNaturalRoll) {
  const CushionParams p;
  double worst = 0.0;
  for (const BallState& in : uniform_domain(2000, true, 1963)) {
    const ImpactResult t = with(ImpactMethod::exact, p, in);
    const ImpactResult x = with(ImpactMethod::extrapolation, p, in);
    ASSERT_TRUE(usable(t.status)) << t.message;
    ASSERT_TRUE(usable(x.status)) << x.message;
    EXPECT_EQ(t.table_slipping_at_start, x.table_slipping_at_start);
    EXPECT_EQ(t.cushion_slipping_at_start, x.cushion_slipping_at_start);
    const double d = state_difference(p, t, x, speed_of(in));
    worst = std::max(worst, d);
    EXPECT_LT(d, 1e-10);
  }
  RecordProperty("worst_difference", scientific(worst));
}

// Slips growing from zero (the cloth's at natural roll; the cushion's where its stick
// breaks, common with high friction and low restitution) are stepped in P with the
// young-slip series, whose orders are solved one by one; at the default tolerance the
// outcome lies within 1e-11 of V0 of the extrapolation method converged.
TEST(TaylorImpact, YoungSlipsAgreeWithAConvergedRun) {
  CushionParams sticky;
  sticky.mu_cushion = 0.35;
  sticky.mu_table = 0.6;
  sticky.restitution = 0.3;
  struct Case {
    const char* name;
    CushionParams p;
    bool natural_roll;
  };
  for (const Case& c : {Case{"natural roll", CushionParams{}, true}, Case{"sticky", sticky, false},
                        Case{"sticky, natural roll", sticky, true}}) {
    double worst = 0.0;
    int breaks = 0;
    for (const BallState& in : uniform_domain(300, c.natural_roll, 31)) {
      const ImpactResult t = with(ImpactMethod::exact, c.p, in);
      ASSERT_TRUE(usable(t.status)) << t.message;
      ImpactOptions converged;
      converged.method = ImpactMethod::extrapolation;
      converged.tolerance = 1e-14;
      converged.max_steps = 1000000;
      const ImpactResult x = resolve_impact(c.p, in, converged);
      ASSERT_TRUE(usable(x.status)) << x.message;
      breaks += t.transition_count >= 2;
      worst = std::max(worst, state_difference(c.p, t, x, speed_of(in)));
    }
    EXPECT_LE(worst, 1e-11) << c.name;
    if (!c.natural_roll) {
      EXPECT_GE(breaks, 10) << c.name << ": sticks that break";
    }
    RecordProperty(std::string("worst_difference ") + c.name, scientific(worst));
  }
}

// A young step evaluates each of its N + 1 orders once: the order's solution moves the
// rates it evaluated at zero unknowns along their slopes (measured at order 1), instead
// of evaluating them again. Beyond the N + 1 orders of each step, natural roll costs the
// young step's order 0 (its direction, here already exact) and order 1 (the slopes:
// one evaluation per unknown, and the solution): at most 10 evaluations in all; with
// the rates evaluated twice per order the excess was N + 7 = 23.
TEST(TaylorImpact, NaturalRollYoungStepEvaluatesEachOrderOnce) {
  const CushionParams p;
  const int order_terms = 17;  // order 16 at the default tolerance 1e-12
  for (const BallState& in : uniform_domain(200, true, 1963)) {
    std::vector<TraceSample> trace;
    ImpactOptions o;
    o.trace = &trace;
    const ImpactResult r = resolve_impact(p, in, o);
    ASSERT_TRUE(usable(r.status)) << r.message;
    const int steps = (static_cast<int>(trace.size()) - 1) / 8;  // 8 samples a step
    EXPECT_LE(r.rhs_evaluations - order_terms * steps, 10);
    EXPECT_GE(r.rhs_evaluations - order_terms * steps, 0);
  }
}

// Natural roll is the limit of a small cloth slip: the outcome varies like d log d in
// d = k_T - 1, so at d = +-1e-13 it moves by about 3e-12. The two sides are stepped by
// other code than k_T = 1 (an ordinary slip, regularised, from a size of 1e-13).
TEST(TaylorImpact, NaturalRollIsTheLimitOfASmallClothSlip) {
  const CushionParams p;
  for (double alpha : {5.0, 30.0, 60.0, 89.0, 120.0, 175.0})
    for (double ks : {-2.0, -0.5, 0.0, 0.7, 2.5}) {
      const ImpactResult roll = with(ImpactMethod::exact, p, incoming_state_k(1.0, alpha, 1.0, ks, p.radius));
      ASSERT_EQ(roll.status, ImpactStatus::ok) << roll.message;
      for (double d : {-1e-13, 1e-13}) {
        const ImpactResult near =
            with(ImpactMethod::exact, p, incoming_state_k(1.0, alpha, 1.0 + d, ks, p.radius));
        ASSERT_EQ(near.status, ImpactStatus::ok) << near.message;
        EXPECT_LT(state_difference(p, roll, near, 1.0), 1e-10)
            << "alpha " << alpha << " k_S " << ks << " d " << d;
      }
    }
}

// The paper's scheme at N and 4 N, extrapolated to zero step (Richardson: the scheme
// is first order), with its resolution: twice the extrapolation correction.
struct PaperReference {
  ImpactResult result;
  double resolution = 0.0;
};

PaperReference paper_reference(const CushionParams& p, const BallState& in, int n) {
  ImpactOptions paper;
  paper.method = ImpactMethod::paper;
  paper.paper_steps = n;
  const ImpactResult coarse = resolve_impact(p, in, paper);
  paper.paper_steps = 4 * n;
  const ImpactResult fine = resolve_impact(p, in, paper);
  PaperReference ref{fine, 0.0};
  ref.result.outgoing.velocity =
      (4.0 / 3.0) * fine.outgoing.velocity - (1.0 / 3.0) * coarse.outgoing.velocity;
  ref.result.outgoing.spin = (4.0 / 3.0) * fine.outgoing.spin - (1.0 / 3.0) * coarse.outgoing.spin;
  ref.resolution = 2.0 * state_difference(p, fine, ref.result, speed_of(in)) + 1e-10;
  return ref;
}

// Over the stress domain (tests/support/impact_domain.hpp: any parameters, spins up
// to 20, zero slip at either contact, grazing and head-on incidence) the two exact
// methods agree to 1e-10 of V0 - except where the extrapolation method errs. Each
// disagreement is judged by the methods run to convergence (tolerance 1e-14): where
// those agree with each other, the Taylor method at its default tolerance must lie
// within 1e-10 of the converged extrapolation run. Where the converged runs disagree
// too, the paper's scheme extrapolated to zero step judges: the Taylor method must lie
// within its resolution or ten times nearer to it than the extrapolation method (the
// reference is refined once, N = 4e6 to 1.6e7, when it resolves neither). Where the
// scheme would need more than 2e8 steps (friction that hardly slows the ball) no
// reference is computed. Reproducers of the extrapolation method's errors are in
// tests/README.md.
TEST(TaylorImpact, AgreesWithExtrapolationOverTheStressDomainOrTheirDisagreementIsItsError) {
  test::Sampler sampler(16);
  int compared = 0, disagreed = 0, by_convergence = 0, by_paper = 0, unjudged = 0;
  double worst_agreeing = 0.0;
  for (int i = 0; i < 3000; ++i) {
    std::string params_kind, state_kind;
    const CushionParams p = test::draw_params(sampler, &params_kind);
    const BallState in = test::draw_state(sampler, p, &state_kind);
    const std::string where = "[" + params_kind + ", " + state_kind + "]";
    const ImpactResult t = with(ImpactMethod::exact, p, in);
    const ImpactResult x = with(ImpactMethod::extrapolation, p, in);
    ASSERT_TRUE(usable(t.status)) << t.message << " " << where;
    if (!usable(x.status)) continue;
    ++compared;
    const double v0 = speed_of(in);
    const double d = state_difference(p, t, x, v0);
    if (d <= 1e-10) {
      worst_agreeing = std::max(worst_agreeing, d);
      continue;
    }
    ++disagreed;
    ImpactOptions converged;
    converged.tolerance = 1e-14;
    converged.max_steps = 1000000;
    converged.method = ImpactMethod::extrapolation;
    const ImpactResult x_converged = resolve_impact(p, in, converged);
    converged.method = ImpactMethod::exact;
    const ImpactResult t_converged = resolve_impact(p, in, converged);
    if (usable(x_converged.status) && state_difference(p, t_converged, x_converged, v0) <= 1e-10) {
      ++by_convergence;
      EXPECT_LE(state_difference(p, t, x_converged, v0), 1e-10)
          << where << " Taylor at its default tolerance, against extrapolation converged";
      continue;
    }
    // The scheme's steps at 4 N: P_total over dP = (1 + e) M v_y / (4 N).
    const double steps_per_n = t.impulse_total / ((1.0 + p.restitution) * p.mass * in.velocity.y);
    if (!(16e6 * steps_per_n <= 2e8)) {
      ++unjudged;
      continue;
    }
    ++by_paper;
    auto sides_with_taylor = [&](const PaperReference& ref) {
      const double off = state_difference(p, t, ref.result, v0);
      return off <= ref.resolution || off <= 0.1 * state_difference(p, x, ref.result, v0);
    };
    PaperReference ref = paper_reference(p, in, 1000000);
    if (!sides_with_taylor(ref)) ref = paper_reference(p, in, 4000000);
    EXPECT_TRUE(sides_with_taylor(ref))
        << where << " Taylor and extrapolation differ by " << d << "; from the reference: Taylor "
        << state_difference(p, t, ref.result, v0) << ", extrapolation "
        << state_difference(p, x, ref.result, v0) << ", resolution " << ref.resolution;
  }
  EXPECT_GE(compared, 2900);
  EXPECT_LE(unjudged, 2);
  RecordProperty("disagreements", std::to_string(disagreed));
  RecordProperty("judged_by_convergence", std::to_string(by_convergence));
  RecordProperty("judged_by_the_paper_scheme", std::to_string(by_paper));
  RecordProperty("unjudged", std::to_string(unjudged));
  RecordProperty("worst_agreeing_difference", scientific(worst_agreeing));
}

// An impact within rounding of the head-on plane (alpha = 90 deg, no sidespin: the
// lateral parts are cos(pi/2) ~ 6e-17) stays in it exactly: no motion along the
// cushion and no sidespin come out of rounding.
TEST(TaylorImpact, HeadOnImpactStaysInItsPlane) {
  const CushionParams p;
  for (double kt : {-3.0, -1.0, 0.0, 0.5, 1.0, 2.0, 3.0}) {
    const BallState in = incoming_state_k(4.0, 90.0, kt, 0.0, p.radius);
    ASSERT_NE(in.velocity.x, 0.0);  // the rounding the test is about
    const ImpactResult r = with(ImpactMethod::exact, p, in);
    ASSERT_TRUE(usable(r.status)) << r.message;
    EXPECT_EQ(r.outgoing.velocity.x, 0.0) << "k_T " << kt;
    EXPECT_EQ(r.outgoing.spin.y, 0.0) << "k_T " << kt;
    EXPECT_EQ(r.outgoing.spin.z, 0.0) << "k_T " << kt;
  }
}

// With k_T = 2 head-on neither slip changes direction, u_y falls linearly in P_I and
// the energetic restitution gives |vy_out| = e V0 exactly (cushion_impact_test.cpp).
// The end of the impact, W_total = (1 - e^2) W_c, is then within e^2 W_c of W_c: the
// Taylor method counts the work of restitution from the end of compression, so even
// for e = 1e-6 the rebound keeps its relative precision.
TEST(TaylorImpact, RestitutionKeepsItsPrecisionWhenTiny) {
  CushionParams p;
  for (double e : {1e-6, 1e-4, 0.01, 0.5}) {
    p.restitution = e;
    const ImpactResult r = with(ImpactMethod::exact, p, incoming_state_k(1.0, 90.0, 2.0, 0.0, p.radius));
    ASSERT_EQ(r.status, ImpactStatus::ok) << r.message;
    EXPECT_NEAR(-r.outgoing.velocity.y / e, 1.0, 1e-9) << "e " << e;
    EXPECT_NEAR(r.work_total / r.work_compression, 1.0 - e * e, 1e-12) << "e " << e;
  }
}

// The tolerance bounds the error: over the uniform domain the worst state error is
// within a few tolerances of the extrapolation method converged, at every tolerance.
TEST(TaylorImpact, ErrorFollowsTheTolerance) {
  const CushionParams p;
  const std::vector<BallState> inputs = uniform_domain(400, false, 7);
  std::vector<ImpactResult> reference;
  for (const BallState& in : inputs) {
    ImpactOptions o;
    o.method = ImpactMethod::extrapolation;
    o.tolerance = 1e-14;
    o.max_steps = 1000000;
    reference.push_back(resolve_impact(p, in, o));
  }
  for (double tol : {1e-6, 1e-8, 1e-10, 1e-12}) {
    double worst = 0.0;
    for (size_t i = 0; i < inputs.size(); ++i) {
      const ImpactResult r = with(ImpactMethod::exact, p, inputs[i], tol);
      ASSERT_TRUE(usable(r.status)) << r.message;
      worst = std::max(worst, state_difference(p, r, reference[i], speed_of(inputs[i])));
    }
    EXPECT_LT(worst, 20.0 * tol + 1e-13) << "tolerance " << tol;
  }
}

}  // namespace
}  // namespace cueplan::physics
