// Tests of resolve_impacts, the batch entry point: every impact of a batch comes out
// bit for bit as resolve_impact gives it - whatever the SIMD lane width, the mix of
// inputs (steps of every kind side by side, invalid rows among them), the method, the
// order of the batch or how it is split over threads.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "cueplan/physics/cushion_impact.hpp"
#include "cueplan/physics/impact_table.hpp"
#include "support/impact_domain.hpp"

namespace cueplan::physics {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(const Vec3& a, const Vec3& b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}

// Every field of two results, numbers compared bit for bit.
::testing::AssertionResult identical(const ImpactResult& a, const ImpactResult& b) {
  bool same = a.status == b.status && a.message == b.message && a.method_used == b.method_used &&
              same_bits(a.outgoing.velocity, b.outgoing.velocity) &&
              same_bits(a.outgoing.spin, b.outgoing.spin) && same_bits(a.rebound_speed, b.rebound_speed) &&
              same_bits(a.rebound_angle_deg, b.rebound_angle_deg) &&
              same_bits(a.impulse_compression, b.impulse_compression) &&
              same_bits(a.impulse_total, b.impulse_total) &&
              same_bits(a.work_compression, b.work_compression) &&
              same_bits(a.work_total, b.work_total) &&
              a.cushion_slipping_at_start == b.cushion_slipping_at_start &&
              a.table_slipping_at_start == b.table_slipping_at_start &&
              a.transition_count == b.transition_count && a.rhs_evaluations == b.rhs_evaluations;
  for (int i = 0; same && i < a.transition_count; ++i)
    same = a.transitions[i].contact == b.transitions[i].contact &&
           a.transitions[i].sticking == b.transitions[i].sticking &&
           same_bits(a.transitions[i].impulse, b.transitions[i].impulse);
  if (same) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "status " << to_string(a.status) << " / " << to_string(b.status) << ", vx "
         << a.outgoing.velocity.x << " / " << b.outgoing.velocity.x << ", work "
         << a.rhs_evaluations << " / " << b.rhs_evaluations;
}

// A mixed batch for the snooker parameters: uniform incidence and spins, natural roll,
// head-on (stick and slip), stun and draw (sticks at the cushion), general spin
// vectors, zero slip at the cushion, grazing incidence, and a few invalid states.
std::vector<BallState> mixed_batch(const CushionParams& p, int count) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> alpha(0.01, 179.99), k(-3.0, 3.0), v(0.01, 5.0), u(-1, 1);
  std::vector<BallState> out;
  for (int i = 0; i < count; ++i) {
    const double v0 = v(rng), a = alpha(rng), kt = k(rng), ks = k(rng);
    switch (i % 10) {
      case 0: out.push_back(incoming_state_k(v0, a, 1.0, ks, p.radius)); break;
      case 1: out.push_back(incoming_state_k(v0, 90.0, kt, 0.0, p.radius)); break;
      case 2: out.push_back(incoming_state_k(v0, a, 0.0, 0.0, p.radius)); break;
      case 3: {
        BallState b;
        b.velocity = {3 * u(rng), 0.01 + 2.5 * std::abs(u(rng)), 0.0};
        b.spin = {300 * u(rng), 300 * u(rng), 300 * u(rng)};
        out.push_back(b);
        break;
      }
      case 4: {
        // No slip at the cushion: y_I' = -v_y s + w_x R = 0, x_I = 0.
        BallState b = incoming_state(v0, a, 0.0, 0.0);
        const double s = p.sin_theta(), c = p.cos_theta(), wy = kt * v0 / p.radius;
        b.spin = {b.velocity.y * s / p.radius, wy, (b.velocity.x + wy * p.radius * s) / (p.radius * c)};
        out.push_back(b);
        break;
      }
      case 5: out.push_back(incoming_state_k(v0, 1e-4, kt, ks, p.radius)); break;
      case 6:
        if (i % 40 == 6) {
          BallState bad = incoming_state_k(v0, a, kt, ks, p.radius);
          bad.velocity.y = -bad.velocity.y;  // moving away: invalid
          out.push_back(bad);
          break;
        }
        [[fallthrough]];
      default: out.push_back(incoming_state_k(v0, a, kt, ks, p.radius)); break;
    }
  }
  return out;
}

std::vector<ImpactResult> one_by_one(const CushionParams& p, const std::vector<BallState>& in,
                                     const ImpactOptions& o) {
  std::vector<ImpactResult> out;
  for (const BallState& b : in) out.push_back(resolve_impact(p, b, o));
  return out;
}

std::vector<ImpactResult> batch(const CushionParams& p, const std::vector<BallState>& in,
                                const ImpactOptions& o) {
  std::vector<ImpactResult> out(in.size());
  resolve_impacts(p, in, out, o);
  return out;
}

// Readable names for the lane widths: 0 is the widest the CPU has.
std::string lanes_name(const ::testing::TestParamInfo<int>& param) {
  return param.param == 0 ? std::string("widest") : std::to_string(param.param) + "_lanes";
}

class BatchLanes : public ::testing::TestWithParam<int> {};

TEST_P(BatchLanes, EveryImpactBitIdenticalToResolveImpact) {
  const CushionParams p;
  const std::vector<BallState> in = mixed_batch(p, 1200);
  for (double tol : {1e-12, 1e-9, 1e-6}) {
    ImpactOptions o;
    o.tolerance = tol;
    o.batch_lanes = GetParam();
    const std::vector<ImpactResult> single = one_by_one(p, in, o), lanes = batch(p, in, o);
    int invalid = 0, sticking = 0;
    for (size_t i = 0; i < in.size(); ++i) {
      EXPECT_TRUE(identical(lanes[i], single[i])) << "impact " << i << " tolerance " << tol;
      invalid += single[i].status == ImpactStatus::invalid_input;
      for (int t = 0; t < single[i].transition_count; ++t) sticking += single[i].transitions[t].sticking;
    }
    // The batch holds what it is meant to: refused rows and stick phases among the rest.
    EXPECT_GT(invalid, 0);
    EXPECT_GT(sticking, 10);
  }
}

TEST_P(BatchLanes, StressDomainBitIdenticalToResolveImpact) {
  // Parameters at their limits: one batch per parameter set, of states drawn for it.
  test::Sampler sampler(5);
  for (int set = 0; set < 40; ++set) {
    std::string params_kind, state_kind;
    const CushionParams p = test::draw_params(sampler, &params_kind);
    std::vector<BallState> in;
    for (int i = 0; i < 60; ++i) in.push_back(test::draw_state(sampler, p, &state_kind));
    ImpactOptions o;
    o.batch_lanes = GetParam();
    const std::vector<ImpactResult> single = one_by_one(p, in, o), lanes = batch(p, in, o);
    for (size_t i = 0; i < in.size(); ++i)
      EXPECT_TRUE(identical(lanes[i], single[i])) << params_kind << " impact " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(LaneWidths, BatchLanes, ::testing::Values(0, 1, 2, 4, 8), lanes_name);

TEST(ImpactBatch, OtherMethodsBitIdenticalToResolveImpact) {
  const CushionParams p;
  const std::vector<BallState> in = mixed_batch(p, 200);
  for (ImpactMethod m : {ImpactMethod::extrapolation, ImpactMethod::paper}) {
    ImpactOptions o;
    o.method = m;
    o.paper_steps = 500;
    const std::vector<ImpactResult> single = one_by_one(p, in, o), lanes = batch(p, in, o);
    for (size_t i = 0; i < in.size(); ++i)
      EXPECT_TRUE(identical(lanes[i], single[i])) << to_string(m) << " impact " << i;
  }
}

TEST(ImpactBatch, TableAndItsFallbacksBitIdenticalToResolveImpact) {
  // A small, coarse table: many of its cells fall back, so the batch mixes table
  // answers with exact impacts in lanes at the table's fallback tolerance.
  const CushionParams p;
  ImpactTableOptions t;
  t.alpha_nodes = 10;
  t.topspin_nodes = 13;
  t.sidespin_nodes = 9;
  t.roll_alpha_nodes = 10;
  t.roll_sidespin_nodes = 13;
  t.k_max = 1.5;
  t.cell_tolerance = 1e-2;  // coarse: enough of its cells answer
  t.threads = 1;
  const ImpactTable table = ImpactTable::build(p, t);
  ASSERT_FALSE(table.empty());
  const std::vector<BallState> in = mixed_batch(p, 600);
  ImpactOptions o;
  o.method = ImpactMethod::table;
  o.table = &table;
  const std::vector<ImpactResult> single = one_by_one(p, in, o), lanes = batch(p, in, o);
  int by_table = 0, by_exact = 0;
  for (size_t i = 0; i < in.size(); ++i) {
    EXPECT_TRUE(identical(lanes[i], single[i])) << "impact " << i;
    by_table += single[i].method_used == ImpactMethod::table;
    by_exact += single[i].method_used == ImpactMethod::exact && usable(single[i].status);
  }
  EXPECT_GT(by_table, 0);
  EXPECT_GT(by_exact, 0);
}

TEST(ImpactBatch, ResultsDoNotDependOnTheThreadsOrTheOrder) {
  const CushionParams p;
  const std::vector<BallState> in = mixed_batch(p, 1000);
  const std::vector<ImpactResult> whole = batch(p, in, {});
  // The same impacts split into pieces resolved on several threads at once.
  for (int threads : {2, 3, 7}) {
    std::vector<ImpactResult> out(in.size());
    std::vector<std::thread> pool;
    const size_t piece = (in.size() + threads - 1) / threads;
    for (int t = 0; t < threads; ++t)
      pool.emplace_back([&, t] {
        const size_t begin = std::min(in.size(), t * piece), end = std::min(in.size(), begin + piece);
        resolve_impacts(p, std::span(in).subspan(begin, end - begin),
                        std::span(out).subspan(begin, end - begin), {});
      });
    for (std::thread& th : pool) th.join();
    for (size_t i = 0; i < in.size(); ++i)
      EXPECT_TRUE(identical(out[i], whole[i])) << threads << " threads, impact " << i;
  }
  // Reversed: every impact meets other neighbours in the lanes.
  const std::vector<BallState> reversed(in.rbegin(), in.rend());
  const std::vector<ImpactResult> back = batch(p, reversed, {});
  for (size_t i = 0; i < in.size(); ++i)
    EXPECT_TRUE(identical(back[in.size() - 1 - i], whole[i])) << "impact " << i;
  // And again: deterministic.
  const std::vector<ImpactResult> again = batch(p, in, {});
  for (size_t i = 0; i < in.size(); ++i) EXPECT_TRUE(identical(again[i], whole[i]));
}

TEST(ImpactBatch, BadArgumentsComeBackAsInvalidInputNamingThem) {
  const CushionParams p;
  const std::vector<BallState> in = mixed_batch(p, 4);
  auto expect_all_refused = [&](std::vector<ImpactResult>& out, const ImpactOptions& o,
                                const std::string& field) {
    resolve_impacts(p, in, out, o);
    for (const ImpactResult& r : out) {
      EXPECT_EQ(r.status, ImpactStatus::invalid_input) << field;
      EXPECT_NE(r.message.find(field), std::string::npos) << r.message;
    }
  };
  std::vector<ImpactResult> short_out(3), out(4);
  expect_all_refused(short_out, {}, "out");
  ImpactOptions lanes;
  lanes.batch_lanes = 3;
  expect_all_refused(out, lanes, "batch_lanes");
  std::vector<TraceSample> trace;
  ImpactOptions traced;
  traced.trace = &trace;
  expect_all_refused(out, traced, "trace");
  CushionParams bad = p;
  bad.radius = -1.0;
  resolve_impacts(bad, in, out, {});
  for (const ImpactResult& r : out) EXPECT_EQ(r.message.rfind("radius", 0), 0u) << r.message;
  // An empty batch is fine.
  resolve_impacts(p, {}, {}, {});
}

}  // namespace
}  // namespace cueplan::physics
