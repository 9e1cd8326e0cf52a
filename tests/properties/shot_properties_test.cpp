// Properties of the shot simulator on random strokes (RapidCheck): the mirrors and the
// half turn of the table, energy along the path, determinism, the event cap and the
// ball staying on the table. tests/physics/shot_simulator_test.cpp checks the same
// ideas on fixed shots and against closed-form motion.
// Reproduce a failure with RC_PARAMS="seed=<the seed printed>".
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <cstring>

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
