// Properties of the shot simulator on random strokes (RapidCheck): the mirrors and the
// half turn of the table, energy along the path, determinism, the event cap and the
// ball staying on the table; with object balls, the mirror, energy across contacts and
// no overlaps. tests/physics/shot_simulator_test.cpp checks the same
// ideas on fixed shots and against closed-form motion.
// Reproduce a failure with RC_PARAMS="seed=<the seed printed>".
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "cueplan/physics/shot.hpp"
#include "support/physics_checks.hpp"

namespace cueplan::physics {
namespace {

rc::Gen<double> in_range(double lo, double hi) {
  return rc::gen::map(rc::gen::inRange<int64_t>(0, int64_t{1} << 40), [lo, hi](int64_t k) {
    return lo + (hi - lo) * static_cast<double>(k) / static_cast<double>(int64_t{1} << 40);
  });
}

// A stroke inside the miscue limit, a cue ball anywhere on the table.
Shot draw_shot() {
  const double k = 1.25 * std::sqrt(*in_range(0.0, 1.0)),
               turn = *in_range(0.0, 2.0 * std::numbers::pi);
  return {*in_range(0.05, 5.0), *in_range(0.0, 360.0), k * std::cos(turn), k * std::sin(turn)};
}

Vec2 draw_spot(const Scene& s) {
  const double off = s.contact_offset() + 0.1;
  return {*in_range(off, s.length - off), *in_range(off, s.width - off)};
}

// Two results agree when their statuses and cushion counts do and their final
// positions lie within `tol` of the given mirror images.
void expect_mirrored(const ShotResult& a, const ShotResult& b, Vec2 expected, double tol) {
  RC_ASSERT(a.status == b.status);
  RC_ASSERT(a.cushion_hits == b.cushion_hits);
  RC_ASSERT(std::abs(b.final_position.x - expected.x) <= tol);
  RC_ASSERT(std::abs(b.final_position.y - expected.y) <= tol);
}

RC_GTEST_PROP(ShotProperties, MirrorSymmetryOfTheTable, ()) {
  // Across x = L/2: aim -> 180 - aim; across y = W/2: aim -> -aim; sidespin reverses
  // in both. The six pockets are symmetric too.
  const Scene s = snooker_scene();
  const Vec2 p = draw_spot(s);
  const Shot shot = draw_shot();
  const ShotResult a = simulate(s, p, shot);
  RC_ASSERT(a.status != ShotStatus::invalid_input);
  const ShotResult bx =
      simulate(s, {s.length - p.x, p.y},
               {shot.speed, 180.0 - shot.aim_deg, shot.topspin_k, -shot.sidespin_k});
  expect_mirrored(a, bx, {s.length - a.final_position.x, a.final_position.y}, 1e-6);
  const ShotResult by = simulate(s, {p.x, s.width - p.y},
                                 {shot.speed, -shot.aim_deg, shot.topspin_k, -shot.sidespin_k});
  expect_mirrored(a, by, {a.final_position.x, s.width - a.final_position.y}, 1e-6);
}

RC_GTEST_PROP(ShotProperties, HalfTurnOfTheTable, ()) {
  // Turning the table by 180 degrees: aim + 180, the same spins.
  const Scene s = snooker_scene();
  const Vec2 p = draw_spot(s);
  const Shot shot = draw_shot();
  const ShotResult a = simulate(s, p, shot);
  const ShotResult b =
      simulate(s, {s.length - p.x, s.width - p.y},
               {shot.speed, shot.aim_deg + 180.0, shot.topspin_k, shot.sidespin_k});
  expect_mirrored(a, b, {s.length - a.final_position.x, s.width - a.final_position.y}, 1e-6);
}

RC_GTEST_PROP(ShotProperties, EnergyNeverRisesAlongThePath, ()) {
  Scene s = snooker_scene();
  s.ball_and_cushion.restitution = *in_range(0.5, 1.0);
  s.ball_and_cushion.mu_cushion = *in_range(0.0, 0.3);
  const ShotResult r = simulate(s, draw_spot(s), draw_shot());
  RC_ASSERT(test::all_finite(r));
  const test::PathAudit audit = test::audit_path(s, r);
  RC_ASSERT(audit.max_energy_gain <= 1e-10);
  // The exact method's error at its default accuracy 1e-9 bounds a gain in an impact.
  RC_ASSERT(audit.max_impact_energy_gain <= 1e-9);
  RC_ASSERT(audit.max_outside <= 1e-12);
  RC_ASSERT(audit.max_gap <= 1e-9);
  RC_ASSERT(audit.times_ordered);
  RC_ASSERT(audit.segments_matched);
}

RC_GTEST_PROP(ShotProperties, SameInputBitIdenticalOutput, ()) {
  const Scene s = snooker_scene();
  const Vec2 p = draw_spot(s);
  const Shot shot = draw_shot();
  SimulationOptions o;
  o.impact_method = *rc::gen::element(ImpactMethod::exact, ImpactMethod::paper);
  const ShotResult a = simulate(s, p, shot, o), b = simulate(s, p, shot, o);
  RC_ASSERT(a.status == b.status);
  RC_ASSERT(a.events.size() == b.events.size());
  for (size_t i = 0; i < a.events.size(); ++i) {
    RC_ASSERT(std::memcmp(&a.events[i].time, &b.events[i].time, sizeof(double)) == 0);
    RC_ASSERT(std::memcmp(&a.events[i].position, &b.events[i].position, sizeof(Vec2)) == 0);
    RC_ASSERT(std::memcmp(&a.events[i].spin, &b.events[i].spin, sizeof(Vec3)) == 0);
  }
}

RC_GTEST_PROP(ShotProperties, EventCapBoundsEveryShot, ()) {
  // With a cap of n events a shot ends with at most n + 1 of them, and says so when
  // the cap ended it.
  Scene s = snooker_scene();
  s.pockets.clear();
  SimulationOptions o;
  o.max_events = *rc::gen::inRange(1, 12);
  const ShotResult r = simulate(s, draw_spot(s), draw_shot(), o);
  RC_ASSERT(r.events.size() <= static_cast<size_t>(o.max_events) + 1);
  if (r.status == ShotStatus::event_limit) {
    RC_ASSERT(!r.message.empty());
  } else {
    RC_ASSERT(r.status == ShotStatus::rest);
    RC_ASSERT(r.events.back().type == EventType::rest);
  }
}

RC_GTEST_PROP(ShotProperties, TheBallRestsOnTheTable, ()) {
  const Scene s = snooker_scene();
  const ShotResult r = simulate(s, draw_spot(s), draw_shot());
  const double off = s.contact_offset();
  if (r.status == ShotStatus::rest) {
    RC_ASSERT(r.final_position.x >= off - 1e-12 && r.final_position.x <= s.length - off + 1e-12);
    RC_ASSERT(r.final_position.y >= off - 1e-12 && r.final_position.y <= s.width - off + 1e-12);
    RC_ASSERT(r.events.back().velocity.x == 0.0 && r.events.back().velocity.y == 0.0);
  }
}

}  // namespace
}  // namespace cueplan::physics

// ---- Object balls ----------------------------------------------------------------

namespace cueplan::physics {
namespace {

// One to four object balls at random places where balls may lie (never on the cue ball).
Scene with_random_balls(Scene s, Vec2 cue) {
  const int n = *rc::gen::inRange(1, 5);
  for (int i = 0; i < n; ++i) {
    s.balls.push_back({"b" + std::to_string(i), draw_spot(s)});
    if (s.validate() || s.check_position(cue, {"cue_ball"})) s.balls.pop_back();
  }
  return s;
}

// A stroke that, half the time, goes near the first object ball (within 10 deg).
Shot draw_shot_at_balls(const Scene& s, Vec2 cue) {
  Shot shot = draw_shot();
  if (!s.balls.empty() && *rc::gen::arbitrary<bool>()) {
    const Vec2 b = s.balls.front().position;
    shot.aim_deg = std::atan2(b.y - cue.y, b.x - cue.x) * 180.0 / std::numbers::pi +
                   *in_range(-10.0, 10.0);
  }
  return shot;
}

RC_GTEST_PROP(ShotProperties, MirrorSymmetryWithObjectBalls, ()) {
  // Across y = W/2, every ball's outcome mirrors (pockets bottom <-> top).
  const Scene base = snooker_scene();
  const Vec2 p = draw_spot(base);
  const Scene s = with_random_balls(base, p);
  Scene m = s;
  for (ObjectBall& b : m.balls) b.position.y = s.width - b.position.y;
  const Shot shot = draw_shot_at_balls(s, p);
  const ShotResult a = simulate(s, p, shot);
  const ShotResult b = simulate(m, {p.x, s.width - p.y},
                                {shot.speed, -shot.aim_deg, shot.topspin_k, -shot.sidespin_k});
  RC_CLASSIFY(a.first_contact > 0, "the cue ball strikes a ball");
  // A push of balls pressed together (collision_failed) and a cascade of ever smaller
  // contacts that reaches the event cap are no outcome, and rounding decides which of
  // the two a mirror image meets: the symmetry holds for shots with an outcome.
  const auto outcome = [](const ShotResult& r) {
    return r.status != ShotStatus::collision_failed && r.status != ShotStatus::event_limit;
  };
  RC_PRE(outcome(a) && outcome(b));
  RC_ASSERT(a.status == b.status);
  RC_ASSERT(a.first_contact == b.first_contact);
  for (size_t k = 0; k < a.balls.size(); ++k) {
    RC_ASSERT(a.balls[k].pocketed == b.balls[k].pocketed);
    RC_ASSERT(a.balls[k].cushion_hits == b.balls[k].cushion_hits);
    RC_ASSERT(std::abs(b.balls[k].final_position.x - a.balls[k].final_position.x) <= 1e-6);
    RC_ASSERT(std::abs(b.balls[k].final_position.y - (s.width - a.balls[k].final_position.y)) <=
              1e-6);
  }
}

RC_GTEST_PROP(ShotProperties, ObjectBallsNeitherGainEnergyNorOverlap, ()) {
  // Each ball's energy never rises on the cloth nor across a cushion; two balls' energy
  // never rises across their contact; balls in contact are 2R apart and none overlap.
  Scene base = snooker_scene();
  base.ball_contact.model =
      *rc::gen::element(BallModel::mathavan_2014, BallModel::frictional_inelastic);
  base.ball_contact.restitution = *in_range(0.5, 1.0);
  const Vec2 p = draw_spot(base);
  const Scene s = with_random_balls(base, p);
  const ShotResult r = simulate(s, p, draw_shot_at_balls(s, p));
  RC_ASSERT(test::all_finite(r));
  std::vector<test::PathAudit> audits;
  for (const BallOutcome& b : r.balls) {
    audits.push_back(test::audit_path(s, b.events, b.path));
    RC_ASSERT(audits.back().max_energy_gain <= 1e-10);
    RC_ASSERT(audits.back().max_impact_energy_gain <= 1e-9);
    RC_ASSERT(audits.back().max_outside <= 1e-12);
    RC_ASSERT(audits.back().segments_matched);
  }
  const test::ContactAudit contacts = test::audit_contacts(s, r, audits);
  RC_CLASSIFY(contacts.contacts > 0, "balls collide");
  RC_ASSERT(contacts.paired);
  RC_ASSERT(contacts.max_gap <= 1e-9);
  RC_ASSERT(contacts.max_energy_gain <= 1e-8);
  RC_ASSERT(contacts.max_overlap <= 1e-9);
}

}  // namespace
}  // namespace cueplan::physics
