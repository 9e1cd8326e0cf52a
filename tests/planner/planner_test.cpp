// The planner: finds shots that land, says so truthfully when it cannot, keeps every
// returned shot within the limits, and gives the same answer for the same seed.
//
// Everything here simulates with the exact impact method, so the suite needs no
// table cache.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "cueplan/physics/impact_table.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::planner {
namespace {

problems::Problem shipped(const std::string& file) {
  const problems::LoadResult r = problems::load_problem(std::string(CUEPLAN_PROBLEMS_DIR) + "/" + file);
  EXPECT_TRUE(r.ok()) << r.error;
  return r.ok() ? *r.problem : problems::Problem{};
}

PlannerOptions exact_options() {
  PlannerOptions o;
  o.simulation.record_path = false;
  return o;
}

// Every constraint of the problem, checked on a fresh simulation of the shot rather
// than on what the planner says about it.
void expect_within_limits(const problems::Problem& p, const PlannedShot& s, bool rigid_enforced,
                          const std::string& what) {
  SCOPED_TRACE(what + ": " + s.family);
  const problems::Limits& l = p.limits;
  EXPECT_GE(s.shot.speed, l.speed_min * (1 - 1e-12));
  EXPECT_LE(s.shot.speed, l.speed_max * (1 + 1e-12));
  EXPECT_LE(std::hypot(s.shot.topspin_k, s.shot.sidespin_k), l.spin_max * (1 + 1e-12));
  EXPECT_EQ(problems::check_shot(l, s.shot), "");
  physics::SimulationOptions sim;
  const physics::ShotResult r = physics::simulate(p.scene, p.cue_ball, s.shot, sim);
  EXPECT_EQ(r.status, physics::ShotStatus::rest);
  EXPECT_GE(r.cushion_hits, l.cushions_min);
  EXPECT_LE(r.cushion_hits, l.cushions_max);
  EXPECT_LE(problems::miss_distance(p, r), p.tolerance);
  if (rigid_enforced) {
    EXPECT_LE(r.max_cushion_normal_speed, 2.5);
  }
  EXPECT_TRUE(s.solves);
  EXPECT_EQ(s.violations, "");
  EXPECT_EQ(s.cushion_hits, r.cushion_hits);
  EXPECT_NEAR(s.miss_distance, problems::miss_distance(p, r), 1e-6);
}

// Problems whose target is where a known stroke lands (0-3 cushions, exactly that
// many required): the planner must solve at least 99 of 100. They are planned on two
// threads at once, which also exercises plan()'s thread safety.
TEST(PlannerTest, SolvesAtLeast99PercentOfProblemsWithAKnownAnswer) {
  physics::SimulationOptions sim;
  sim.record_path = false;
  const std::vector<KnownShotProblem> problems = known_shot_problems(100, 7, sim);
  ASSERT_EQ(problems.size(), 100u);
  PlannerOptions o = exact_options();
  o.robustness_samples = 0;  // probabilities are tested below; this is about finding shots
  std::vector<PlanResult> results(problems.size());
  std::vector<std::thread> threads;
  for (int t = 0; t < 2; ++t)
    threads.emplace_back([&, t] {
      for (size_t i = static_cast<size_t>(t); i < problems.size(); i += 2)
        results[i] = plan(problems[i].problem, o);
    });
  for (std::thread& t : threads) t.join();
  int solved = 0;
  for (size_t i = 0; i < problems.size(); ++i) {
    const PlanResult& r = results[i];
    if (r.status == PlanStatus::solved) {
      ++solved;
      expect_within_limits(problems[i].problem, r.best, false, problems[i].problem.name);
    } else {
      // Logged, not failed: the criterion is the count below.
      std::cout << problems[i].problem.name << " not solved: " << r.message << '\n';
    }
  }
  EXPECT_GE(solved, 99);
}

TEST(PlannerTest, SolvesEveryShippedProblemWithEveryShotWithinItsLimits) {
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(CUEPLAN_PROBLEMS_DIR)) {
    if (e.path().extension() != ".yaml") continue;
    ++files;
    const problems::Problem p = shipped(e.path().filename().string());
    PlannerOptions o = exact_options();
    o.robustness_samples = 20;
    const PlanResult r = plan(p, o);
    EXPECT_EQ(r.status, PlanStatus::solved) << p.name << ": " << r.message;
    expect_within_limits(p, r.best, false, p.name);
    for (const PlannedShot& alt : r.alternatives) expect_within_limits(p, alt, false, p.name);
  }
  EXPECT_GE(files, 10);
}

TEST(PlannerTest, EnforcedRigidLimitHoldsInEveryReturnedShot) {
  problems::Problem p = shipped("three_rail_position.yaml");
  PlannerOptions o = exact_options();
  o.enforce_rigid_limit = true;
  o.robustness_samples = 0;
  const PlanResult r = plan(p, o);
  ASSERT_EQ(r.status, PlanStatus::solved) << r.message;
  expect_within_limits(p, r.best, true, "best");
  for (const PlannedShot& alt : r.alternatives) expect_within_limits(p, alt, true, "alternative");
}

TEST(PlannerTest, ReturnsDistinctFamiliesIncludingFollowAndDraw) {
  // One cushion off y = 0: played with follow (the file's witness) or with draw.
  const problems::Problem p = shipped("one_rail_position.yaml");
  PlannerOptions o = exact_options();
  o.robustness_samples = 20;
  const PlanResult r = plan(p, o);
  ASSERT_EQ(r.status, PlanStatus::solved) << r.message;
  std::vector<PlannedShot> all{r.best};
  all.insert(all.end(), r.alternatives.begin(), r.alternatives.end());
  EXPECT_GE(all.size(), 2u);
  bool follow = false, draw = false;
  for (size_t i = 0; i < all.size(); ++i) {
    follow = follow || all[i].family.find("follow") != std::string::npos;
    draw = draw || all[i].family.find("draw") != std::string::npos;
    for (size_t j = 0; j < i; ++j) EXPECT_NE(all[i].family, all[j].family);
  }
  EXPECT_TRUE(follow);
  EXPECT_TRUE(draw);
}

TEST(PlannerTest, TargetBeyondTheSpeedLimitFindsNoSolution) {
  problems::Problem p = shipped("one_rail_position.yaml");
  p.limits.speed_max = 0.4;  // rolls about 0.8 m at most; the one-cushion route is ~2.5 m
  PlannerOptions o = exact_options();
  const PlanResult r = plan(p, o);
  EXPECT_EQ(r.status, PlanStatus::no_solution_found) << r.message;
  EXPECT_FALSE(r.best.solves);
  EXPECT_GT(r.best.miss_distance, p.tolerance);
  EXPECT_NE(r.message.find("No solution found"), std::string::npos) << r.message;
  EXPECT_TRUE(r.alternatives.empty());
}

TEST(PlannerTest, TargetBehindAWallWithNoCushionRouteFindsNoSolution) {
  // Without a cushion the path is a straight line, and the wall stands across it.
  problems::Problem p = shipped("blocked_direct_route.yaml");
  p.limits.cushions_min = p.limits.cushions_max = 0;
  PlannerOptions o = exact_options();
  const PlanResult r = plan(p, o);
  EXPECT_EQ(r.status, PlanStatus::no_solution_found) << r.message;
  EXPECT_FALSE(r.best.solves);
  EXPECT_FALSE(r.message.empty());
}

TEST(PlannerTest, SmallBudgetIsReportedAsExhaustedNotAsSuccess) {
  problems::Problem p = shipped("three_rail_position.yaml");
  PlannerOptions o = exact_options();
  o.max_evaluations = 10;
  const PlanResult r = plan(p, o);
  EXPECT_NE(r.status, PlanStatus::solved);
  if (r.status != PlanStatus::solved) {
    EXPECT_EQ(r.status, PlanStatus::budget_exhausted) << r.message;
    EXPECT_NE(r.message.find("budget"), std::string::npos) << r.message;
  }
}

// Searching with an impact table, the planner reports (and if need be re-polishes)
// every returned shot with the exact method. A deliberately coarse table (a few
// nodes, loose tolerance) makes the table's answers differ from the exact ones.
TEST(PlannerTest, SearchWithATableReportsExactOutcomes) {
  const problems::Problem p = shipped("two_rail_position.yaml");
  physics::ImpactTableOptions coarse;
  coarse.alpha_nodes = 7;
  coarse.topspin_nodes = 9;
  coarse.sidespin_nodes = 7;
  coarse.roll_alpha_nodes = 7;
  coarse.roll_sidespin_nodes = 7;
  coarse.cell_tolerance = 1e-1;
  const physics::ImpactTable table = physics::ImpactTable::build(p.scene.ball_and_cushion, coarse);
  ASSERT_FALSE(table.empty());
  PlannerOptions o = exact_options();
  o.simulation.impact_method = physics::ImpactMethod::table;
  o.simulation.table = &table;
  o.simulation.impact_accuracy = 1.0;  // accept the coarse table for the search
  ASSERT_EQ(physics::chosen_impact_method(p.scene, o.simulation), physics::ImpactMethod::table);
  o.robustness_samples = 20;
  const PlanResult r = plan(p, o);
  ASSERT_EQ(r.status, PlanStatus::solved) << r.message;
  EXPECT_EQ(r.best.impact_method, physics::ImpactMethod::exact);
  expect_within_limits(p, r.best, false, "best");
  for (const PlannedShot& alt : r.alternatives) {
    EXPECT_EQ(alt.impact_method, physics::ImpactMethod::exact);
    expect_within_limits(p, alt, false, "alternative");
  }
}

void expect_identical(const PlanResult& a, const PlanResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.message, b.message);
  EXPECT_EQ(a.evaluations, b.evaluations);
  ASSERT_EQ(a.alternatives.size(), b.alternatives.size());
  std::vector<const PlannedShot*> sa{&a.best}, sb{&b.best};
  for (size_t i = 0; i < a.alternatives.size(); ++i) {
    sa.push_back(&a.alternatives[i]);
    sb.push_back(&b.alternatives[i]);
  }
  for (size_t i = 0; i < sa.size(); ++i) {
    EXPECT_EQ(sa[i]->shot.speed, sb[i]->shot.speed);
    EXPECT_EQ(sa[i]->shot.aim_deg, sb[i]->shot.aim_deg);
    EXPECT_EQ(sa[i]->shot.topspin_k, sb[i]->shot.topspin_k);
    EXPECT_EQ(sa[i]->shot.sidespin_k, sb[i]->shot.sidespin_k);
    EXPECT_EQ(sa[i]->success_probability, sb[i]->success_probability);
    EXPECT_EQ(sa[i]->success, sb[i]->success);
    EXPECT_EQ(sa[i]->family, sb[i]->family);
  }
}

TEST(PlannerTest, SameSeedGivesTheSameAnswer) {
  const problems::Problem p = shipped("two_rail_position.yaml");
  PlannerOptions o = exact_options();
  o.robustness_samples = 50;
  expect_identical(plan(p, o), plan(p, o));
}

TEST(PlannerTest, ThreadCountDoesNotChangeTheAnswer) {
  const problems::Problem p = shipped("two_rail_position.yaml");
  PlannerOptions o = exact_options();
  o.robustness_samples = 50;
  const PlanResult one = plan(p, o);
  o.threads = 2;
  expect_identical(one, plan(p, o));
}

TEST(PlannerTest, RobustModeDoesNotLowerTheSuccessProbability) {
  const problems::Problem p = shipped("paper_figure8_rolling.yaml");
  PlannerOptions o = exact_options();
  o.robustness_samples = 100;
  const PlanResult nominal = plan(p, o);
  ASSERT_EQ(nominal.status, PlanStatus::solved) << nominal.message;
  o.robust = true;
  o.robust_max_evaluations = 6000;
  const PlanResult robust = plan(p, o);
  ASSERT_EQ(robust.status, PlanStatus::solved) << robust.message;
  EXPECT_GE(robust.best.success_probability, nominal.best.success_probability);
  expect_within_limits(p, robust.best, false, "robust best");
  EXPECT_EQ(robust.best.success_probability,
            success_probability(p, robust.best.shot, o.noise, o.robustness_samples, kReferenceSeed,
                                o.simulation));
}

// A coach gives the same advice every time (issue 31, "Stable answers"): the
// reference search and the success draws do not depend on the seed, so seeds 1..3 (which
// recommended follow, draw and follow before) recommend the same family with the same
// success.
TEST(RankingTest, TheSameFamilyWhateverTheSeed) {
  const problems::Problem p = shipped("one_rail_position.yaml");
  PlannerOptions o = exact_options();
  const PlanResult first = plan(p, o);
  ASSERT_EQ(first.status, PlanStatus::solved) << first.message;
  for (uint64_t seed : {2, 3}) {
    SCOPED_TRACE(seed);
    o.seed = seed;
    const PlanResult r = plan(p, o);
    ASSERT_EQ(r.status, PlanStatus::solved) << r.message;
    EXPECT_EQ(r.best.family, first.best.family);
    EXPECT_EQ(r.best.success.both, first.best.success.both);
  }
}

// A wider limit never answers worse (issue 31): with the speed limit raised from the
// default 4.5 m/s to 7 m/s, these pots' answers used to lose success (only_draw 3.5 % ->
// 0 % at 5.8 m/s, pool_two_ball_position 78 % -> 60 %, two_cushion_position 3.5 % ->
// 0.5 %); the wide plan now succeeds at least as often as the default one, and its
// stroke keeps within the wide limits.
TEST(RankingTest, AWiderSpeedLimitNeverAnswersWorse) {
  for (const char* file : {"pots/only_draw.yaml", "pots/pool_two_ball_position.yaml",
                           "pots/two_cushion_position.yaml"}) {
    SCOPED_TRACE(file);
    const problems::Problem p = shipped(file);
    ASSERT_EQ(p.limits.speed_max, problems::Limits{}.speed_max);
    problems::Problem wide = p;
    wide.limits.speed_max = 7.0;
    const PlannerOptions o = exact_options();
    const PlanResult narrow_plan = plan(p, o);
    const PlanResult wide_plan = plan(wide, o);
    ASSERT_EQ(narrow_plan.status, PlanStatus::solved) << narrow_plan.message;
    ASSERT_EQ(wide_plan.status, PlanStatus::solved) << wide_plan.message;
    EXPECT_GE(wide_plan.best.success_probability, narrow_plan.best.success_probability);
    EXPECT_LE(wide_plan.best.shot.speed, 7.0);
    EXPECT_EQ(problems::check_shot(wide.limits, wide_plan.best.shot), "");
    EXPECT_GE(wide_plan.evaluations, narrow_plan.evaluations);  // both searches counted
  }
}

// Every reported stroke's success is what an independent estimate on the same draws
// gives (the first `samples` draws of kReferenceSeed, whatever the seed), P(success) is success.both.p, and the
// answer's interval is not below any alternative's.
TEST(RankingTest, TheAnswersIntervalIsNotBelowAnAlternativesAndEstimatesAreReproducible) {
  for (const char* file : {"one_rail_position.yaml", "two_rail_position.yaml", "near_pocket.yaml",
                           "three_rail_position.yaml"}) {
    SCOPED_TRACE(file);
    const problems::Problem p = shipped(file);
    const PlannerOptions o = exact_options();
    const PlanResult r = plan(p, o);
    ASSERT_EQ(r.status, PlanStatus::solved) << r.message;
    ASSERT_FALSE(r.alternatives.empty());
    std::vector<PlannedShot> all{r.best};
    all.insert(all.end(), r.alternatives.begin(), r.alternatives.end());
    for (const PlannedShot& s : all) {
      SCOPED_TRACE(s.family);
      const Estimate& e = s.success.both;
      EXPECT_GT(e.samples, 0);
      EXPECT_LE(e.samples, o.robustness_samples);
      EXPECT_FALSE(s.success.pot);  // no pot in these problems
      EXPECT_EQ(s.success.position, e);
      EXPECT_EQ(s.success_probability, e.p);
      EXPECT_EQ(estimate_success(p, s.shot, o.noise, e.samples, kReferenceSeed, o.simulation), s.success);
      EXPECT_GE(r.best.success.both.high, e.low);
    }
    EXPECT_EQ(r.best.success.both.samples, o.robustness_samples);
  }
}

// Without a cushion, sidespin moves nothing in this model (no swerve; it wears off on
// the cloth): the premise is checked stroke by stroke, and no stroke reported carries
// side.
TEST(RankingTest, SideThatChangesNothingIsNotRecommended) {
  problems::Problem p = shipped("near_pocket.yaml");
  p.limits.cushions_min = p.limits.cushions_max = 0;
  PlannerOptions o = exact_options();
  o.robustness_samples = 100;
  const PlanResult r = plan(p, o);
  ASSERT_EQ(r.status, PlanStatus::solved) << r.message;
  std::vector<PlannedShot> all{r.best};
  all.insert(all.end(), r.alternatives.begin(), r.alternatives.end());
  for (const PlannedShot& s : all) {
    SCOPED_TRACE(s.family);
    physics::Shot with_side = s.shot;
    with_side.sidespin_k = std::sqrt(p.limits.spin_max * p.limits.spin_max -
                                     s.shot.topspin_k * s.shot.topspin_k);
    // Aimed off by the difference of the two strokes' squirts, so that the cue ball
    // leaves along the same line.
    const auto squirt = [&](double k) {
      return physics::squirt_angle_deg(p.scene.cue, p.scene.ball_and_cushion.mass,
                                       p.scene.radius(), k);
    };
    with_side.aim_deg += squirt(s.shot.sidespin_k) - squirt(with_side.sidespin_k);
    const physics::ShotResult a = physics::simulate(p.scene, p.cue_ball, s.shot);
    const physics::ShotResult b = physics::simulate(p.scene, p.cue_ball, with_side);
    // A stroke that meets a pocket's jaw is a cushion contact there, where side acts:
    // the premise holds for the strokes that meet nothing.
    if (a.balls[0].jaw_hits == 0) {
      EXPECT_NEAR(a.final_position.x, b.final_position.x, 1e-9);
      EXPECT_NEAR(a.final_position.y, b.final_position.y, 1e-9);
    }
    EXPECT_LT(std::abs(s.shot.sidespin_k), physics::kSpinPerTipOffset / 32.0);
    EXPECT_NE(s.family.find("no side"), std::string::npos);
  }
}

// The three-cushion problem's file gives a plain follow stroke (1.943 m/s, aim 40
// deg) that lands 1.3 mm from the target; the planner once answered with a 3.99 m/s
// draw stroke. Judged on fresh draws (another seed, 1000 strokes), the answer now
// succeeds at least as often as the file's stroke and more often than the old answer
// (3.5 % against 1.6 % since the search's reference half is seed-independent; the
// seed-1 answer before was measurably better, issue 31). Planned with 3000 simulations:
// at the default 2000 whether the search meets the 3-cushion follow family that succeeds
// (5-8 %) depends on rounding in its path - it did at 2000 and 2400 and did not at 1600,
// 1800 and 2200 simulations before the event solver's root finder changed, and does
// not at 2000 since; from 2800 to 3200 it does with either.
TEST(RankingTest, ThreeRailAnswerSucceedsAtLeastAsOftenAsThePlainFollowStroke) {
  // On the capture-circle pockets the strokes above were measured on (the file's
  // default is now the snooker preset's jaws, whose corners let other strokes through).
  problems::Problem p = shipped("three_rail_position.yaml");
  p.scene.pockets = physics::standard_pockets(p.scene.length, p.scene.width,
                                              physics::kDefaultPocketRadius);
  PlannerOptions o = exact_options();
  o.max_evaluations = 3000;
  const PlanResult r = plan(p, o);
  ASSERT_EQ(r.status, PlanStatus::solved) << r.message;
  const auto fresh = [&](const physics::Shot& shot) {
    return estimate_success(p, shot, o.noise, 1000, 99, o.simulation).both;
  };
  const Estimate answer = fresh(r.best.shot);
  const Estimate witness = fresh({1.943, 40.0, 1.0, 0.0});
  const Estimate old_answer = fresh({3.9884, -180.0, -0.828659, 0.00906197});
  EXPECT_GE(answer.high, witness.low) << answer.p << " against " << witness.p;
  EXPECT_GT(answer.p, old_answer.p) << answer.p << " against " << old_answer.p;
}

// --max-time bounds everything plan() does, the Monte Carlo included: with an
// unbounded evaluation budget and far more samples than fit, the plan ends on time
// and its estimates say how many strokes they counted.
TEST(RankingTest, MaxTimeBoundsThePlanMonteCarloIncluded) {
  const problems::Problem p = shipped("two_rail_position.yaml");
  PlannerOptions o = exact_options();
  o.max_evaluations = 100000000;
  o.robustness_samples = 10000000;
  o.max_time_s = 0.2;
  const PlanResult r = plan(p, o);
  EXPECT_LE(r.time_s, o.max_time_s + 0.05);
  EXPECT_GT(r.evaluations, 0);
  EXPECT_LT(r.best.success.both.samples, o.robustness_samples);
  EXPECT_LE(r.best.success.both.samples, r.evaluations);
}

// The witness of paper_figure8_rolling.yaml: natural roll at 0.8 m/s, aim -45 deg.
const physics::Shot kFigure8Witness{0.8, -45.0, 1.0, 0.0};

TEST(SuccessProbabilityTest, IsOneWithoutNoiseForAShotThatLands) {
  const problems::Problem p = shipped("paper_figure8_rolling.yaml");
  NoiseModel none;
  none.scale = 0.0;
  EXPECT_EQ(success_probability(p, kFigure8Witness, none, 50, 1, {}), 1.0);
  const physics::Shot off{0.6, -45.0, 1.0, 0.0};  // stops far short
  EXPECT_EQ(success_probability(p, off, none, 50, 1, {}), 0.0);
}

TEST(SuccessProbabilityTest, FallsAsTheNoiseGrows) {
  const problems::Problem p = shipped("paper_figure8_rolling.yaml");
  double previous = 1.0;
  for (double scale : {0.0, 0.5, 2.0, 8.0}) {
    NoiseModel noise;
    noise.scale = scale;
    const double prob = success_probability(p, kFigure8Witness, noise, 200, 3, {});
    SCOPED_TRACE(scale);
    EXPECT_LE(prob, previous + 0.03);  // same draws, scaled: falls up to sampling wobble
    previous = prob;
  }
  NoiseModel huge;
  huge.scale = 8.0;
  EXPECT_LT(success_probability(p, kFigure8Witness, huge, 200, 3, {}), 0.5);
}

TEST(SuccessProbabilityTest, IsDeterministicForASeed) {
  const problems::Problem p = shipped("paper_figure8_rolling.yaml");
  const NoiseModel noise;
  const double a = success_probability(p, kFigure8Witness, noise, 100, 11, {});
  EXPECT_EQ(a, success_probability(p, kFigure8Witness, noise, 100, 11, {}));
  EXPECT_GT(a, 0.0);
  EXPECT_LT(a, 1.0);
}

TEST(EvaluateTest, DescribesTheOneRailWitness) {
  const problems::Problem p = shipped("one_rail_position.yaml");
  const PlannedShot s = evaluate(p, {1.002, -60.36, 0.8, 0.0}, {});
  EXPECT_EQ(s.outcome, physics::ShotStatus::rest);
  EXPECT_TRUE(s.solves);
  EXPECT_TRUE(s.within_limits);
  EXPECT_EQ(s.route, std::vector<int>{0});
  EXPECT_EQ(s.family, "1 cushion (y = 0), follow, no side");
  EXPECT_LT(s.miss_distance, 0.002);
  EXPECT_EQ(s.success_probability, 0.0);
}

TEST(EvaluateTest, ReportsABrokenLimit) {
  const problems::Problem p = shipped("one_rail_position.yaml");
  const PlannedShot s = evaluate(p, {5.0, -60.36, 0.8, 0.0}, {});  // faster than 4.5 m/s
  EXPECT_FALSE(s.within_limits);
  EXPECT_FALSE(s.solves);
  EXPECT_NE(s.violations.find("speed"), std::string::npos) << s.violations;
}

TEST(PlannerOptionsTest, BadOptionsAreInvalidInputNamingTheField) {
  const problems::Problem p = shipped("one_rail_position.yaml");
  struct Case {
    const char* field;
    void (*spoil)(PlannerOptions*);
  };
  const Case cases[] = {
      {"max_evaluations", [](PlannerOptions* o) { o->max_evaluations = 0; }},
      {"max_time_s", [](PlannerOptions* o) { o->max_time_s = -1.0; }},
      {"local_starts", [](PlannerOptions* o) { o->local_starts = 0; }},
      {"global_share", [](PlannerOptions* o) { o->global_share = 1.5; }},
      {"threads", [](PlannerOptions* o) { o->threads = 0; }},
      {"noise.speed", [](PlannerOptions* o) { o->noise.speed = -0.1; }},
      {"noise.scale", [](PlannerOptions* o) { o->noise.scale = std::nan(""); }},
      {"robustness_samples", [](PlannerOptions* o) { o->robustness_samples = -1; }},
      {"max_alternatives", [](PlannerOptions* o) { o->max_alternatives = -1; }},
      {"simulation.max_events", [](PlannerOptions* o) { o->simulation.max_events = 0; }},
  };
  EXPECT_FALSE(PlannerOptions{}.validate());
  for (const Case& c : cases) {
    PlannerOptions o;
    c.spoil(&o);
    const physics::Validation e = o.validate();
    ASSERT_TRUE(e) << c.field;
    EXPECT_EQ(e->field.text(), c.field);
    const PlanResult r = plan(p, o);
    EXPECT_EQ(r.status, PlanStatus::invalid_input) << c.field;
    ASSERT_TRUE(r.error) << c.field;
    EXPECT_EQ(r.error->field.text(), c.field);
    EXPECT_EQ(r.message.rfind(std::string(c.field) + " ", 0), 0u) << r.message;
    EXPECT_EQ(r.evaluations, 0);
  }
}

TEST(PlannerOptionsTest, BadProblemIsInvalidInputNamingTheField) {
  problems::Problem p = shipped("one_rail_position.yaml");
  p.tolerance = 0.0;
  const PlanResult r = plan(p, PlannerOptions{});
  EXPECT_EQ(r.status, PlanStatus::invalid_input);
  ASSERT_TRUE(r.error);
  EXPECT_EQ(r.error->field, physics::FieldPath{"tolerance"});
  EXPECT_EQ(r.message, "problem: tolerance must be positive and finite (m), got 0");
  // A field of the scene is named as the problem file names it.
  p = shipped("one_rail_position.yaml");
  p.scene.cloth.mu_roll = -1.0;
  const PlanResult bad_cloth = plan(p, PlannerOptions{});
  ASSERT_TRUE(bad_cloth.error);
  EXPECT_EQ(bad_cloth.error->field, (physics::FieldPath{"scene", "cloth", "mu_roll"}));
  EXPECT_EQ(bad_cloth.message.rfind("problem: physics.mu_roll must be positive", 0), 0u)
      << bad_cloth.message;
}

}  // namespace
}  // namespace cueplan::planner
