// Stress run of the cushion impact over its whole input domain and its edges.
//
// Draws impacts - the paper's form (V0, alpha, k_T, k_S) and general spin vectors,
// V0 from 1e-6 to 20 m/s, alpha from 1e-6 to 180 - 1e-6 deg, |k| up to 20, starts
// with zero slip at a contact, parameters at their limits (mu = 0, e = 1, friction at
// the edge of validity, extreme cushion heights, other radii and masses) and inputs
// that must be refused - resolves each with an exact method (`exact`, or with
// --method extrapolation the other one) and checks that
//   - every number in the result is finite, whatever the status, and a usable result
//     leaves the cushion (outgoing v_y < 0);
//   - the work (right-hand side calls) stays within the integrator's bound;
//   - the kinetic energy (translation + rotation) never rises beyond rounding;
//   - bad input comes back as invalid_input with a message naming the field;
//   - the same input gives a bit-identical result;
//   - on a subsample, the paper's scheme at large N agrees with exact to within its
//     first-order error.
// Prints the counts; exits 1 when a check fails, 2 for bad arguments.
//
//   stress_impacts [--impacts N] [--seed S] [--paper-sample M] [--paper-steps N]
//                  [--method exact|extrapolation] [--json FILE]
#include <algorithm>
#include <array>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "cueplan/physics/cushion_impact.hpp"
#include "support/impact_domain.hpp"
#include "support/physics_checks.hpp"
#include "support/stress_output.hpp"

namespace cueplan::physics {
namespace {

using test::draw_params;
using test::draw_state;
using test::Sampler;

constexpr double kDeg = std::numbers::pi / 180.0;

struct Options {
  long long impacts = 1000000;
  uint64_t seed = 1;
  long long paper_sample = 1000;  // impacts also solved with the paper's scheme
  int paper_steps = 100000;       // its N
  ImpactMethod method = ImpactMethod::exact;  // the exact method under test
  std::string json;               // write the figures here too, when set
};

// The exact methods' work bounds per step, from their structure.
// Extrapolation (physics/src/impact_extrapolation.cpp): every one of at most max_steps steps -
// accepted, rejected or searching for a stick break - costs at most 64 right-hand side
// calls in its deepest extrapolation column, plus one at its start and one per
// stick-break search.
// Taylor (physics/src/impact_taylor.cpp; its work counts series orders): a step
// computes at most kMaxOrder + 1 = 25 orders, twice each where a slip grows from zero,
// plus 4 for that slip's Jacobian and at most 4 sweeps x 2 slips x 20 Newton steps x
// 2 evaluations of order 0 for its direction: 376.
int work_per_step(ImpactMethod method) { return method == ImpactMethod::extrapolation ? 66 : 376; }
// Energy may rise by rounding only.
constexpr double kEnergySlack = 1e-12;
// The paper's scheme is first order in dP_I = (1 + e) V0 sin(alpha) M / N: its error
// relative to V0 stays below kPaperConstant dP_I / (M V0) per N steps it takes, plus
// the exact method's own error at its default tolerance (about 3e-10, bench/README.md).
constexpr double kPaperConstant = 20.0;
constexpr double kExactError = 1e-9;

// One drawn impact: parameters, state, options, and what it exercises.
struct Case {
  CushionParams params;
  BallState state;
  ImpactOptions options;
  std::string params_kind;
  std::string state_kind;
  std::string bad_field;  // set when the input must be refused: the field to name
};

// Input that must be refused, with the field the message must name.
void spoil(Sampler& s, Case* c) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  c->params_kind = "spoiled";
  switch (s.index(14)) {
    case 0:
      c->state.velocity.y = s.chance(0.5) ? 0.0 : -s.speed();
      c->bad_field = "velocity.y";
      break;
    case 1:
      c->state.velocity.y = nan;
      c->bad_field = "velocity.y";
      break;
    case 2:
      c->state.velocity.x = s.chance(0.5) ? nan : -inf;
      c->bad_field = "velocity.x";
      break;
    case 3:
      c->state.spin.x = inf;
      c->bad_field = "spin.x";
      break;
    case 4:
      c->state.spin.z = nan;
      c->bad_field = "spin.z";
      break;
    case 5:
      c->state.velocity.z = s.uniform(-1.0, 1.0);
      c->bad_field = "velocity.z";
      break;
    case 6:
      c->params.mass = s.chance(0.5) ? 0.0 : -1.0;
      c->bad_field = "mass";
      break;
    case 7:
      c->params.radius = s.chance(0.5) ? -0.02 : nan;
      c->bad_field = "radius";
      break;
    case 8:
      c->params.cushion_height = c->params.radius * (s.chance(0.5) ? 1.0 : 2.0);
      c->bad_field = "cushion_height";
      break;
    case 9:
      c->params.restitution = s.chance(0.5) ? 0.0 : 1.0 + 1e-9;
      c->bad_field = "restitution";
      break;
    case 10:
      c->params.mu_cushion = s.chance(0.5) ? -1e-9 : 10.0;
      c->bad_field = "mu_cushion";
      break;
    case 11:
      c->params.mu_table = s.chance(0.5) ? -0.1 : inf;
      c->bad_field = "mu_table";
      break;
    case 12:
      c->params.rigid_speed_limit = 0.0;
      c->bad_field = "rigid_speed_limit";
      break;
    default:
      c->options.tolerance = s.chance(0.5) ? 0.0 : 0.1;
      c->bad_field = "tolerance";
      break;
  }
  c->state_kind = "bad " + c->bad_field;
}

Case draw_case(Sampler& s, ImpactMethod method) {
  Case c;
  c.options.method = method;
  c.params = draw_params(s, &c.params_kind);
  c.state = draw_state(s, c.params, &c.state_kind);
  // One impact in ten at another tolerance of the exact method.
  if (s.chance(0.1)) c.options.tolerance = s.log_uniform(1e-14, 1e-6);
  if (s.chance(0.02)) spoil(s, &c);
  return c;
}

std::string reproducer(const Case& c) {
  char buf[1024];
  const CushionParams& p = c.params;
  std::snprintf(buf, sizeof buf,
                "params {mass %.17g, radius %.17g, cushion_height %.17g, mu_cushion %.17g, "
                "mu_table %.17g, restitution %.17g, rigid_speed_limit %.17g} state {velocity "
                "(%.17g, %.17g, %.17g), spin (%.17g, %.17g, %.17g)} tolerance %.17g max_steps %d "
                "[%s, %s]",
                p.mass, p.radius, p.cushion_height, p.mu_cushion, p.mu_table, p.restitution,
                p.rigid_speed_limit, c.state.velocity.x, c.state.velocity.y, c.state.velocity.z,
                c.state.spin.x, c.state.spin.y, c.state.spin.z, c.options.tolerance,
                c.options.max_steps, c.params_kind.c_str(), c.state_kind.c_str());
  return buf;
}

bool same_bits(const ImpactResult& a, const ImpactResult& b) {
  auto eq = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  auto eq3 = [&](Vec3 x, Vec3 y) { return eq(x.x, y.x) && eq(x.y, y.y) && eq(x.z, y.z); };
  return a.status == b.status && eq3(a.outgoing.velocity, b.outgoing.velocity) &&
         eq3(a.outgoing.spin, b.outgoing.spin) && eq(a.impulse_total, b.impulse_total) &&
         eq(a.work_total, b.work_total) && a.rhs_evaluations == b.rhs_evaluations &&
         a.transition_count == b.transition_count;
}

// Failures, each kept with its first few reproducers.
struct Failures {
  std::map<std::string, long long> count;
  std::vector<std::string> examples;
  void add(const std::string& what, const std::string& detail) {
    if (++count[what] <= 3) examples.push_back(what + ": " + detail);
  }
  long long total() const {
    long long n = 0;
    for (const auto& [what, k] : count) n += k;
    return n;
  }
};

int run(const Options& opt) {
  Sampler s(opt.seed);
  Failures fail;
  std::map<std::string, long long> statuses, params_kinds, state_kinds;
  long long nonfinite = 0, refused_right = 0, refused = 0, energy_checked = 0;
  long long repeats = 0;
  int max_rhs = 0;
  double max_gain = -INFINITY, max_seconds = 0.0, total_seconds = 0.0;
  std::string slowest, costliest;
  long long step_limit_default_tol = 0;
  Failures known;  // limits of the methods, counted and shown but not failures
  std::map<std::string, long long> step_limit_kinds;
  std::vector<std::string> step_limit_examples;

  struct PaperCase {
    Case c;
    ImpactResult exact;
  };
  std::vector<PaperCase> paper_cases;
  const long long paper_every =
      opt.paper_sample > 0 ? std::max<long long>(1, opt.impacts / opt.paper_sample) : 0;

  for (long long i = 0; i < opt.impacts; ++i) {
    const Case c = draw_case(s, opt.method);
    const auto t0 = std::chrono::steady_clock::now();
    const ImpactResult r = resolve_impact(c.params, c.state, c.options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    total_seconds += seconds;
    if (seconds > max_seconds) {
      max_seconds = seconds;
      slowest = reproducer(c);
    }
    ++statuses[to_string(r.status)];
    ++params_kinds[c.params_kind];
    ++state_kinds[c.state_kind];

    if (!test::all_finite(r)) {
      ++nonfinite;
      fail.add("non-finite result", reproducer(c) + " status " + to_string(r.status));
    }
    if (!c.bad_field.empty()) {
      ++refused;
      // The message names the field (a pair of limits that only fail together, such as
      // mu_cushion with mu_table, may be named the other way round).
      if (r.status == ImpactStatus::invalid_input &&
          r.message.find(c.bad_field) != std::string::npos)
        ++refused_right;
      else
        fail.add("bad input not refused by name",
                 reproducer(c) + " status " + to_string(r.status) + " message '" + r.message + "'");
      continue;
    }
    if (r.status == ImpactStatus::invalid_input)
      fail.add("valid input refused", reproducer(c) + " message '" + r.message + "'");
    if (r.status == ImpactStatus::step_limit) {
      if (r.message.empty()) fail.add("step_limit without a message", reproducer(c));
      if (c.options.tolerance == ImpactOptions{}.tolerance) ++step_limit_default_tol;
      // The first reproducer of each kind of parameters and state.
      if (++step_limit_kinds[c.params_kind + " / " + c.state_kind] == 1)
        step_limit_examples.push_back(reproducer(c));
    }
    if (r.rhs_evaluations > max_rhs) {
      max_rhs = r.rhs_evaluations;
      costliest = reproducer(c);
    }
    if (r.rhs_evaluations > work_per_step(opt.method) * c.options.max_steps)
      fail.add("work bound exceeded", reproducer(c) + " rhs " + std::to_string(r.rhs_evaluations));
    // A usable result leaves the cushion. The end of the impact is landed on to about
    // the tolerance in V0 (scaled t = -v_y / V0), so where e v_y is below that the
    // outgoing v_y may round to zero or past it: counted, and a failure only beyond
    // the tolerance.
    if (usable(r.status) && !(r.outgoing.velocity.y < 0.0)) {
      const double tan_theta = c.params.sin_theta() / c.params.cos_theta();
      if (r.outgoing.velocity.y == 0.0 && c.options.tolerance != ImpactOptions{}.tolerance)
        known.add("outgoing v_y = 0 at a loose tolerance", reproducer(c));
      else if (r.outgoing.velocity.y == 0.0 && c.params.mu_cushion > tan_theta * (1.0 - 1e-5))
        known.add("outgoing v_y = 0 with mu_cushion within 1e-5 of tan(theta)", reproducer(c));
      else
        fail.add("ball does not leave the cushion",
                 reproducer(c) + " outgoing velocity.y " + std::to_string(r.outgoing.velocity.y));
    }
    const bool flagged = r.status == ImpactStatus::rigid_limit_exceeded;
    if (flagged != (c.state.velocity.y > c.params.rigid_speed_limit) && usable(r.status))
      fail.add("rigid limit flag wrong", reproducer(c));

    // Energy, for every result that has an outgoing state (step_limit ones too).
    if (r.status != ImpactStatus::invalid_input) {
      const double before = kinetic_energy(c.params, c.state);
      const double after = kinetic_energy(c.params, r.outgoing);
      const double gain = (after - before) / before;
      ++energy_checked;
      max_gain = std::max(max_gain, gain);
      if (!(after <= before * (1.0 + kEnergySlack)))
        fail.add("kinetic energy rose", reproducer(c) + " relative gain " + std::to_string(gain) +
                                            " status " + to_string(r.status));
    }

    // Determinism: one impact in a thousand again.
    if (i % 1000 == 0) {
      ++repeats;
      if (!same_bits(r, resolve_impact(c.params, c.state, c.options)))
        fail.add("same input, different result", reproducer(c));
    }
    if (paper_every > 0 && i % paper_every == 0 && usable(r.status) &&
        static_cast<long long>(paper_cases.size()) < opt.paper_sample)
      paper_cases.push_back({c, r});
  }

  // The paper's scheme against exact on the subsample.
  double paper_max = 0.0, paper_max_regular = 0.0, paper_max_scaled = 0.0, paper_gain = -INFINITY,
         paper_seconds = 0.0;
  std::string paper_worst;
  long long paper_unusable = 0;
  for (const PaperCase& pc : paper_cases) {
    ImpactOptions o;
    o.method = ImpactMethod::paper;
    o.paper_steps = opt.paper_steps;
    const auto t0 = std::chrono::steady_clock::now();
    const ImpactResult r = resolve_impact(pc.c.params, pc.c.state, o);
    paper_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!usable(r.status)) {
      ++paper_unusable;
      fail.add("paper scheme failed", reproducer(pc.c) + " " + r.message);
      continue;
    }
    const double v0 = std::hypot(pc.c.state.velocity.x, pc.c.state.velocity.y);
    const double sin_alpha = pc.c.state.velocity.y / v0;
    const double diff = test::state_difference(pc.c.params, r, pc.exact, v0);
    // The bound in units of the scheme's step (1 + e) sin(alpha) / N.
    // The scheme takes about P_I / dP_I steps; more than N where friction slows the
    // normal approach little (mu near its limits).
    const double step = (1.0 + pc.c.params.restitution) * sin_alpha / opt.paper_steps;
    const double steps_ratio = std::max(
        1.0, pc.exact.impulse_total /
                 ((1.0 + pc.c.params.restitution) * pc.c.params.mass * pc.c.state.velocity.y));
    const double scaled = diff / (step * steps_ratio);
    if (diff > paper_max) paper_max = diff;
    if (scaled > paper_max_scaled) {
      paper_max_scaled = scaled;
      paper_worst = reproducer(pc.c);
    }
    // Two cases where the methods part for reasons of their own: a slip that starts at
    // zero (the slipping direction it takes is not determined by the state), and a
    // cushion nose near the top of the ball (cos(theta) small: the paper's increments
    // fall below the rounding of the state).
    const CushionParams& cp = pc.c.params;
    const BallState& in = pc.c.state;
    const double rs = cp.radius * cp.sin_theta(), rc = cp.radius * cp.cos_theta();
    const double slip_i = std::hypot(in.velocity.x + in.spin.y * rs - in.spin.z * rc,
                                     -in.velocity.y * cp.sin_theta() + in.spin.x * cp.radius);
    const double slip_c =
        std::hypot(in.velocity.x - in.spin.y * cp.radius, in.velocity.y + in.spin.x * cp.radius);
    const bool beyond = diff > kPaperConstant * step * steps_ratio + kExactError;
    const bool known_case = std::min(slip_i, slip_c) < 1e-9 * v0 || cp.cos_theta() < 1e-2;
    if (!known_case) paper_max_regular = std::max(paper_max_regular, diff);
    if (beyond && std::min(slip_i, slip_c) < 1e-9 * v0)
      known.add("paper and exact part where a slip starts at zero",
                reproducer(pc.c) + " difference " + std::to_string(1e9 * diff) + "e-9");
    else if (beyond && cp.cos_theta() < 1e-2)
      known.add("paper and exact part with cos(theta) < 0.01",
                reproducer(pc.c) + " difference " + std::to_string(1e9 * diff) + "e-9");
    else if (beyond)
      fail.add("paper and exact disagree beyond first order",
               reproducer(pc.c) + " difference " + std::to_string(1e9 * diff) + "e-9");
    const double before = kinetic_energy(pc.c.params, pc.c.state);
    paper_gain = std::max(paper_gain, (kinetic_energy(pc.c.params, r.outgoing) - before) / before);
  }

  // Figures.
  std::printf("stress_impacts: seed %" PRIu64 ", %lld impacts (%s method)\n", opt.seed,
              opt.impacts, to_string(opt.method));
  std::printf("  statuses:");
  for (const auto& [k, n] : statuses) std::printf(" %s %lld;", k.c_str(), n);
  std::printf("\n  step_limit at the default tolerance: %lld; by parameters / state:",
              step_limit_default_tol);
  for (const auto& [k, n] : step_limit_kinds) std::printf(" %s %lld;", k.c_str(), n);
  std::printf("\n");
  for (const std::string& e : step_limit_examples) std::printf("    step_limit: %s\n", e.c_str());
  std::printf("  parameter sets:");
  for (const auto& [k, n] : params_kinds) std::printf(" %s %lld;", k.c_str(), n);
  std::printf("\n  states:");
  for (const auto& [k, n] : state_kinds) std::printf(" %s %lld;", k.c_str(), n);
  std::printf("\n  non-finite results: %lld\n", nonfinite);
  std::printf("  bad inputs refused naming the field: %lld of %lld\n", refused_right, refused);

  std::printf("  energy checked: %lld, rises beyond %.0e: %lld, largest relative change %.3e\n",
              energy_checked, kEnergySlack, fail.count["kinetic energy rose"], max_gain);
  std::printf("  work: most RHS calls (exact: series orders) %d (bound %d = %d x max_steps)\n",
              max_rhs, work_per_step(opt.method) * ImpactOptions{}.max_steps,
              work_per_step(opt.method));
  std::printf("    costliest: %s\n", costliest.c_str());
  std::printf("  time per impact: mean %.2f us, max %.1f us\n",
              1e6 * total_seconds / static_cast<double>(std::max<long long>(1, opt.impacts)),
              1e6 * max_seconds);
  std::printf("    slowest: %s\n", slowest.c_str());
  std::printf("  determinism: %lld repeats, %lld differed\n", repeats,
              fail.count["same input, different result"]);
  std::printf(
      "  paper N = %d vs exact on %zu impacts: max state difference %.3e (of V0), "
      "max %.2f steps (bound %.0f steps + %.0e), paper failures %lld, largest energy change %.3e, "
      "%.1f s\n",
      opt.paper_steps, paper_cases.size(), paper_max, paper_max_scaled, kPaperConstant, kExactError,
      paper_unusable, paper_gain, paper_seconds);
  std::printf(
      "    without the two known cases below (a slip starting at zero, cos(theta) < "
      "0.01): max state difference %.3e\n",
      paper_max_regular);
  if (!paper_worst.empty()) std::printf("    most steps: %s\n", paper_worst.c_str());
  std::printf("  known limits (counted, not failures): %lld\n", known.total());
  for (const auto& [what, n] : known.count) std::printf("    %s: %lld\n", what.c_str(), n);
  for (const std::string& e : known.examples) std::printf("      %s\n", e.c_str());
  std::printf("  failed checks: %lld\n", fail.total());
  for (const std::string& e : fail.examples) std::printf("    %s\n", e.c_str());

  if (!opt.json.empty()) {
    std::ofstream out(opt.json);
    out << "{\"impacts\": " << opt.impacts << ", \"seed\": " << opt.seed
        << ", \"nonfinite\": " << nonfinite
        << ", \"energy_violations\": " << fail.count["kinetic energy rose"]
        << ", \"max_energy_gain\": " << (std::isfinite(max_gain) ? max_gain : 0.0)
        << ", \"max_rhs\": " << max_rhs << ", \"max_us\": " << 1e6 * max_seconds
        << ", \"known_limits\": " << known.total()
        << ", \"step_limit_default_tolerance\": " << step_limit_default_tol
        << ", \"mean_us\": " << 1e6 * total_seconds / static_cast<double>(opt.impacts)
        << ", \"refused\": " << refused << ", \"refused_by_name\": " << refused_right
        << ", \"paper_sample\": " << paper_cases.size() << ", \"paper_steps\": " << opt.paper_steps
        << ", \"paper_max_difference\": " << paper_max
        << ", \"paper_max_difference_regular\": " << paper_max_regular
        << ", \"failed_checks\": " << fail.total() << ", \"statuses\": ";
    test::write_counts_json(out, statuses);
    out << "}\n";
    if (!out) {
      std::fprintf(stderr, "stress_impacts: could not write %s\n", opt.json.c_str());
      return 1;
    }
  }
  return fail.total() == 0 ? 0 : 1;
}

}  // namespace
}  // namespace cueplan::physics

int main(int argc, char** argv) {
  using cueplan::physics::test::parse_count;
  cueplan::physics::Options opt;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const char* value = i + 1 < argc ? argv[i + 1] : nullptr;
    long long n = 0;
    bool ok = value != nullptr;
    if (arg == "--impacts" && ok && (ok = parse_count(value, 1, &n))) {
      opt.impacts = n;
    } else if (arg == "--seed" && ok && (ok = parse_count(value, 0, &n))) {
      opt.seed = static_cast<uint64_t>(n);
    } else if (arg == "--paper-sample" && ok && (ok = parse_count(value, 0, &n))) {
      opt.paper_sample = n;
    } else if (arg == "--paper-steps" && ok && (ok = parse_count(value, 1, &n)) && n <= 100000000) {
      opt.paper_steps = static_cast<int>(n);
    } else if (arg == "--method" && ok && cueplan::physics::parse_method(value, &opt.method) &&
               (opt.method == cueplan::physics::ImpactMethod::exact ||
                opt.method == cueplan::physics::ImpactMethod::extrapolation)) {
      // an exact method
    } else if (arg == "--json" && ok) {
      opt.json = value;
    } else {
      std::fprintf(stderr,
                   "stress_impacts: bad argument '%s'; usage: stress_impacts [--impacts N] "
                   "[--seed S] [--paper-sample M] [--paper-steps N] "
                   "[--method exact|extrapolation] [--json FILE]\n",
                   arg.c_str());
      return 2;
    }
    ++i;
  }
  return cueplan::physics::run(opt);
}
