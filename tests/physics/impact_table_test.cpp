// Tests of the impact table (the `table` method) against the exact method computed
// independently at points off the grid, and of its domain, symmetry, scaling and
// cache file handling.
//
// One table is built for the suite, coarser than the default and with a looser cell
// tolerance so that it builds in about a second and still interpolates in most
// cells; what is checked is that it stays within the error bound it measured.
#include "cueplan/physics/impact_table.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "support/physics_checks.hpp"

namespace cueplan::physics {
namespace {

// The suite's table: 3 deg, 0.15 in k_T and k_S; natural roll 2 deg by 0.05.
ImpactTableOptions suite_options() {
  ImpactTableOptions o;
  o.alpha_nodes = 31;
  o.topspin_nodes = 41;
  o.sidespin_nodes = 41;
  o.roll_alpha_nodes = 46;
  o.roll_sidespin_nodes = 121;
  o.cell_tolerance = 1e-5;
  return o;
}

ImpactTableOptions tiny_options() { return test::tiny_table_options(); }

// Measured bounds may be exceeded slightly between test points; this is the
// allowance, relative to the bound.
constexpr double kBoundMargin = 2.0;

struct Sample {
  double alpha, kt, ks, speed;
};

ImpactResult exact(const CushionParams& p, const BallState& in) {
  return resolve_impact(p, in);  // default: exact method
}

// Largest difference of the outgoing states, in units of V0 (spins as R w).
double state_difference(const CushionParams& p, const ImpactResult& a, const ImpactResult& b,
                        double v0) {
  const Vec3 dv = a.outgoing.velocity - b.outgoing.velocity;
  const Vec3 dw = a.outgoing.spin - b.outgoing.spin;
  return std::max({std::abs(dv.x), std::abs(dv.y), p.radius * std::abs(dw.x),
                   p.radius * std::abs(dw.y), p.radius * std::abs(dw.z)}) /
         v0;
}

// Largest difference of impulses / (M V0) and work / (M V0^2).
double impulse_difference(const CushionParams& p, const ImpactResult& a, const ImpactResult& b,
                          double v0) {
  const double pu = p.mass * v0, wu = p.mass * v0 * v0;
  return std::max({std::abs(a.impulse_compression - b.impulse_compression) / pu,
                   std::abs(a.impulse_total - b.impulse_total) / pu,
                   std::abs(a.work_compression - b.work_compression) / wu,
                   std::abs(a.work_total - b.work_total) / wu});
}

// ctest runs every test in a process of its own: the suite's table is cached
// between them, keyed by this binary's size and time of writing so that a rebuilt
// binary never reuses a table of older code. Empty when the binary is not found.
std::string suite_cache_dir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  const auto size = std::filesystem::file_size(exe, ec);
  if (ec) return {};
  const auto written = std::filesystem::last_write_time(exe, ec).time_since_epoch().count();
  if (ec) return {};
  return (std::filesystem::temp_directory_path() /
          ("cueplan_impact_table_test_" + std::to_string(size) + "_" + std::to_string(written)))
      .string();
}

class ImpactTableTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // The suite's table, kept between runs in the suite's own cache file.
    const std::string cache = suite_cache_dir();
    const std::string file =
        cache.empty() ? std::string()
                      : (std::filesystem::path(cache) /
                         ImpactTable::cache_file_name(params_, suite_options()))
                            .string();
    std::optional<ImpactTable> cached;
    if (!file.empty()) cached = ImpactTable::load(file);
    if (!cached || !cached->covers(params_) || !cached->built_with(suite_options())) {
      cached = ImpactTable::build(params_, suite_options());
      if (!file.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(cache, ec);
        cached->save(file);
      }
    }
    table_ = std::make_unique<ImpactTable>(std::move(*cached));
    std::random_device random;
    dir_ = std::filesystem::temp_directory_path() /
           ("cueplan_impact_table_test_" + std::to_string(random()));
    std::filesystem::create_directories(dir_);
  }
  static void TearDownTestSuite() {
    table_.reset();
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }

  // Seeded points off the grid over the whole domain, alpha in (0, 180).
  static std::vector<Sample> samples(int count, unsigned seed, bool natural_roll = false) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> alpha(0.01, 179.99), k(-3.0, 3.0), speed(0.1, 5.0);
    std::vector<Sample> out;
    for (int i = 0; i < count; ++i) {
      Sample s{alpha(rng), k(rng), k(rng), speed(rng)};
      if (natural_roll) s.kt = 1.0;
      out.push_back(s);
    }
    return out;
  }

  static BallState state_of(const Sample& s) {
    return incoming_state_k(s.speed, s.alpha, s.kt, s.ks, params_.radius);
  }

  // Checks every sample the table answers against the exact method; returns how
  // many it answered.
  static int expect_within_bound(const std::vector<Sample>& points) {
    const ImpactTableError& bound = table_->measured_error();
    int answered = 0;
    double worst_speed = 0.0, worst_angle = 0.0, worst_state = 0.0, worst_impulse = 0.0;
    for (const Sample& s : points) {
      const BallState in = state_of(s);
      ImpactResult r;
      if (!table_->resolve(params_, in, &r)) continue;
      ++answered;
      const ImpactResult x = exact(params_, in);
      EXPECT_TRUE(usable(x.status));
      EXPECT_EQ(r.status, x.status);
      EXPECT_EQ(r.method_used, ImpactMethod::table);
      EXPECT_EQ(r.rhs_evaluations, 0);
      EXPECT_EQ(r.transition_count, 0);
      const double speed = std::abs(r.rebound_speed - x.rebound_speed) / s.speed;
      const double angle = std::abs(r.rebound_angle_deg - x.rebound_angle_deg);
      const double state = state_difference(params_, r, x, s.speed);
      const double impulse = impulse_difference(params_, r, x, s.speed);
      worst_speed = std::max(worst_speed, speed);
      worst_angle = std::max(worst_angle, angle);
      worst_state = std::max(worst_state, state);
      worst_impulse = std::max(worst_impulse, impulse);
      EXPECT_LE(speed, kBoundMargin * bound.max_speed_relative)
          << "alpha " << s.alpha << " k_T " << s.kt << " k_S " << s.ks;
      EXPECT_LE(angle, kBoundMargin * bound.max_angle_deg)
          << "alpha " << s.alpha << " k_T " << s.kt << " k_S " << s.ks;
      EXPECT_LE(state, kBoundMargin * bound.max_state_relative)
          << "alpha " << s.alpha << " k_T " << s.kt << " k_S " << s.ks;
      EXPECT_LE(impulse, kBoundMargin * bound.max_impulse_relative)
          << "alpha " << s.alpha << " k_T " << s.kt << " k_S " << s.ks;
    }
    std::printf(
        "  table answered %d of %zu; worst / measured bound: speed %.3g / %.3g, angle %.3g / "
        "%.3g deg, state %.3g / %.3g, impulse %.3g / %.3g\n",
        answered, points.size(), worst_speed, bound.max_speed_relative, worst_angle,
        bound.max_angle_deg, worst_state, bound.max_state_relative, worst_impulse,
        bound.max_impulse_relative);
    return answered;
  }

  static inline CushionParams params_;
  static inline std::unique_ptr<ImpactTable> table_;
  static inline std::filesystem::path dir_;
};

TEST_F(ImpactTableTest, BuildMeasuresItsErrorWithinTheTolerance) {
  const ImpactTableError& e = table_->measured_error();
  const ImpactTableOptions o = suite_options();
  ASSERT_FALSE(table_->empty());
  EXPECT_EQ(e.cells, int64_t{30} * 40 * 40);
  EXPECT_EQ(e.roll_cells, int64_t{45} * 120);
  EXPECT_GT(e.test_points, e.cells);
  // Interpolating cells passed the tolerance, and most cells interpolate.
  EXPECT_LE(e.max_speed_relative, o.cell_tolerance);
  EXPECT_LE(e.max_angle_deg, 100.0 * o.cell_tolerance);
  EXPECT_LE(e.max_state_relative, 10.0 * o.cell_tolerance);
  EXPECT_LE(e.max_impulse_relative, 10.0 * o.cell_tolerance);
  EXPECT_GT(e.max_speed_relative, 0.0);
  EXPECT_LT(table_->fallback_fraction(), 0.45);
  EXPECT_LT(table_->roll_fallback_fraction(), 0.1);
  std::printf("  fallback: %.1f%% of cells, %.1f%% of natural-roll cells\n",
              100.0 * table_->fallback_fraction(), 100.0 * table_->roll_fallback_fraction());
}

TEST_F(ImpactTableTest, MatchesExactWithinMeasuredBound) {
  const std::vector<Sample> points = samples(2000, 20240501);
  EXPECT_GT(expect_within_bound(points), 1000);
}

TEST_F(ImpactTableTest, NaturalRollMatchesExactWithinMeasuredBound) {
  const std::vector<Sample> points = samples(1000, 7, /*natural_roll=*/true);
  EXPECT_GT(expect_within_bound(points), 900);
}

TEST_F(ImpactTableTest, SlippingAtStartAgreesWithExact) {
  for (const Sample& s : samples(300, 11, /*natural_roll=*/true)) {
    const BallState in = state_of(s);
    ImpactResult r;
    if (!table_->resolve(params_, in, &r)) continue;
    const ImpactResult x = exact(params_, in);
    EXPECT_EQ(r.cushion_slipping_at_start, x.cushion_slipping_at_start) << s.alpha << " " << s.ks;
    EXPECT_EQ(r.table_slipping_at_start, x.table_slipping_at_start) << s.alpha << " " << s.ks;
  }
}

TEST_F(ImpactTableTest, MirrorSymmetryForAlphaAbove90) {
  int compared = 0;
  for (const Sample& s : samples(500, 3)) {
    if (s.alpha <= 90.0) continue;
    const Sample m{180.0 - s.alpha, s.kt, -s.ks, s.speed};
    ImpactResult a, b;
    const bool ha = table_->resolve(params_, state_of(s), &a);
    const bool hb = table_->resolve(params_, state_of(m), &b);
    ASSERT_EQ(ha, hb) << "alpha " << s.alpha;
    if (!ha) continue;
    ++compared;
    const double v = s.speed, w = s.speed / params_.radius;
    EXPECT_NEAR(a.outgoing.velocity.x, -b.outgoing.velocity.x, 1e-9 * v);
    EXPECT_NEAR(a.outgoing.velocity.y, b.outgoing.velocity.y, 1e-9 * v);
    EXPECT_NEAR(a.outgoing.spin.x, b.outgoing.spin.x, 1e-9 * w);
    EXPECT_NEAR(a.outgoing.spin.y, -b.outgoing.spin.y, 1e-9 * w);
    EXPECT_NEAR(a.outgoing.spin.z, -b.outgoing.spin.z, 1e-9 * w);
    EXPECT_NEAR(a.rebound_angle_deg, 180.0 - b.rebound_angle_deg, 1e-7);
    EXPECT_NEAR(a.impulse_total, b.impulse_total, 1e-9 * params_.mass * v);
  }
  EXPECT_GT(compared, 50);
}

TEST_F(ImpactTableTest, OutcomeScalesWithSpeedMassAndRadius) {
  // Same dimensionless parameters, another ball: the table covers it.
  CushionParams other = params_for_radius(0.5 * params_.radius);
  other.mass = 3.0 * params_.mass;
  ASSERT_TRUE(table_->covers(other));
  int compared = 0;
  for (const Sample& s : samples(200, 5)) {
    ImpactResult a, b;
    if (!table_->resolve(params_, state_of(s), &a)) continue;
    const double k = 1.7;  // speed factor
    ASSERT_TRUE(table_->resolve(
        other, incoming_state_k(k * s.speed, s.alpha, s.kt, s.ks, other.radius), &b));
    ++compared;
    EXPECT_NEAR(b.rebound_speed, k * a.rebound_speed, 1e-12 * k * s.speed);
    EXPECT_NEAR(b.rebound_angle_deg, a.rebound_angle_deg, 1e-9);
    EXPECT_NEAR(b.outgoing.spin.z * other.radius / k, a.outgoing.spin.z * params_.radius,
                1e-12 * s.speed);
    EXPECT_NEAR(b.impulse_total / (other.mass * k), a.impulse_total / params_.mass,
                1e-12 * s.speed);
    EXPECT_NEAR(b.work_total / (other.mass * k * k), a.work_total / params_.mass,
                1e-12 * s.speed * s.speed);
  }
  EXPECT_GT(compared, 100);
}

TEST_F(ImpactTableTest, DeclinesStatesOutsideTheDomainOrNotOfPaperForm) {
  const double r = params_.radius;
  ImpactResult out;
  auto declines = [&](const BallState& in) { return !table_->resolve(params_, in, &out); };
  EXPECT_TRUE(declines(incoming_state_k(1.0, 40.0, 3.2, 0.0, r)));  // |k_T| > k_max
  EXPECT_TRUE(declines(incoming_state_k(1.0, 40.0, -3.2, 0.0, r)));
  EXPECT_TRUE(declines(incoming_state_k(1.0, 40.0, 0.5, 3.01, r)));  // |k_S| > k_max
  EXPECT_TRUE(declines(incoming_state_k(1.0, 140.0, 0.5, -3.01, r)));
  BallState along = incoming_state_k(1.0, 40.0, 0.5, 0.2, r);  // spin along motion
  along.spin.x += 1e-3 * std::cos(40.0 * std::numbers::pi / 180.0) / r;
  along.spin.y += 1e-3 * std::sin(40.0 * std::numbers::pi / 180.0) / r;
  EXPECT_TRUE(declines(along));
  BallState away = incoming_state_k(1.0, 40.0, 0.5, 0.2, r);  // moving off the cushion
  away.velocity.y = -away.velocity.y;
  EXPECT_TRUE(declines(away));
  BallState grazing = incoming_state_k(1.0, 40.0, 0.5, 0.2, r);  // no normal speed
  grazing.velocity.y = 0.0;
  EXPECT_TRUE(declines(grazing));
  BallState lifted = incoming_state_k(1.0, 40.0, 0.5, 0.2, r);  // off the cloth
  lifted.velocity.z = 0.1;
  EXPECT_TRUE(declines(lifted));
  BallState broken = incoming_state_k(1.0, 40.0, 0.5, 0.2, r);
  broken.spin.z = std::nan("");
  EXPECT_TRUE(declines(broken));
  EXPECT_FALSE(table_->resolve(params_, incoming_state_k(1.0, 40.0, 0.5, 0.2, r), nullptr));
  // The edges of the domain are inside it (unless their cell falls back).
  int answered = 0;
  for (double a : {0.5, 30.0, 60.0, 89.9})
    for (double k : {-3.0, 3.0})
      answered += table_->resolve(params_, incoming_state_k(1.0, a, k, -k, r), &out);
  EXPECT_GT(answered, 0);
}

TEST_F(ImpactTableTest, DeclinesOtherParameters) {
  const BallState in = incoming_state_k(1.0, 40.0, 0.5, 0.2, params_.radius);
  ImpactResult out;
  CushionParams p = params_;
  p.mu_cushion = 0.15;
  EXPECT_FALSE(table_->covers(p));
  EXPECT_FALSE(table_->resolve(p, in, &out));
  p = params_;
  p.mu_table = 0.2;
  EXPECT_FALSE(table_->covers(p));
  p = params_;
  p.restitution = 0.9;
  EXPECT_FALSE(table_->covers(p));
  p = params_;
  p.cushion_height = 1.5 * p.radius;
  EXPECT_FALSE(table_->covers(p));
  p = params_;
  p.rigid_speed_limit = 1.0;  // not a dimensionless parameter of the outcome
  EXPECT_TRUE(table_->covers(p));
}

TEST_F(ImpactTableTest, FlagsTheRigidSpeedLimitLikeExact) {
  for (const Sample& s : samples(200, 17)) {
    const BallState in = incoming_state_k(4.0, s.alpha, s.kt, s.ks, params_.radius);
    ImpactResult r;
    if (!table_->resolve(params_, in, &r)) continue;
    const ImpactResult x = exact(params_, in);
    EXPECT_EQ(r.status, x.status);
    EXPECT_EQ(r.message.empty(), x.message.empty());
  }
}

TEST_F(ImpactTableTest, ResolveImpactUsesTableOrFallsBackToExact) {
  ImpactOptions options;
  options.method = ImpactMethod::table;
  options.table = table_.get();
  int by_table = 0, by_exact = 0;
  for (const Sample& s : samples(300, 23)) {
    const BallState in = state_of(s);
    ImpactResult direct;
    const bool answered = table_->resolve(params_, in, &direct);
    const ImpactResult r = resolve_impact(params_, in, options);
    ASSERT_TRUE(usable(r.status));
    EXPECT_EQ(r.method_used, answered ? ImpactMethod::table : ImpactMethod::exact);
    if (answered) {
      EXPECT_EQ(r.rebound_speed, direct.rebound_speed);
      ++by_table;
    } else {
      ++by_exact;
    }
  }
  EXPECT_GT(by_table, 0);
  EXPECT_GT(by_exact, 0);  // fallback cells and |k| beyond nothing: both kinds occur
}

// Where the table declines, resolve_impact answers with the exact method at the
// tolerance matched to the table, and stays inside the table's own bounds against a
// converged run (tolerance 1e-14, an independent computation).
TEST_F(ImpactTableTest, FallbackIsAsAccurateAsTheTable) {
  ImpactOptions options;
  options.method = ImpactMethod::table;
  options.table = table_.get();
  ImpactOptions strict = options;
  strict.table_fallback_tolerance = 1e-12;
  ImpactOptions converged;
  converged.tolerance = 1e-14;
  converged.max_steps = 1000000;
  const double bound = table_->options().cell_tolerance;
  int fallbacks = 0;
  long matched_work = 0, strict_work = 0;
  for (const Sample& s : samples(400, 31)) {
    const BallState in = state_of(s);
    ImpactResult direct;
    if (table_->resolve(params_, in, &direct)) continue;
    const ImpactResult r = resolve_impact(params_, in, options);
    ASSERT_TRUE(usable(r.status));
    EXPECT_EQ(r.method_used, ImpactMethod::exact);
    ++fallbacks;
    const ImpactResult x = resolve_impact(params_, in, converged);
    EXPECT_LE(std::abs(r.rebound_speed - x.rebound_speed) / s.speed, bound);
    EXPECT_LE(std::abs(r.rebound_angle_deg - x.rebound_angle_deg), 100.0 * bound);
    EXPECT_LE(state_difference(params_, r, x, s.speed), 10.0 * bound);
    // The tolerance used is the table's own, and a caller can ask for a stricter one.
    ImpactOptions same;
    same.tolerance = table_->fallback_tolerance();
    EXPECT_EQ(r.outgoing.velocity.x, resolve_impact(params_, in, same).outgoing.velocity.x);
    matched_work += r.rhs_evaluations;
    strict_work += resolve_impact(params_, in, strict).rhs_evaluations;
  }
  ASSERT_GT(fallbacks, 20);
  EXPECT_LT(matched_work, strict_work);
}

TEST_F(ImpactTableTest, BadFallbackToleranceIsRefusedByName) {
  ImpactOptions options;
  options.method = ImpactMethod::table;
  options.table = table_.get();
  const BallState in = incoming_state_k(1.0, 45.0, 1.0, 0.0, params_.radius);
  for (double bad : {-1e-9, 1.0, std::nan(""), 1e-20}) {
    options.table_fallback_tolerance = bad;
    const ImpactResult r = resolve_impact(params_, in, options);
    EXPECT_EQ(r.status, ImpactStatus::invalid_input) << bad;
    EXPECT_NE(r.message.find("table_fallback_tolerance"), std::string::npos) << r.message;
  }
}

TEST_F(ImpactTableTest, ConcurrentQueriesGiveTheSameAnswers) {
  const std::vector<Sample> points = samples(400, 29);
  std::vector<double> serial(points.size(), -1.0);
  for (size_t i = 0; i < points.size(); ++i) {
    ImpactResult r;
    if (table_->resolve(params_, state_of(points[i]), &r)) serial[i] = r.rebound_speed;
  }
  std::vector<std::vector<double>> parallel(4, std::vector<double>(points.size(), -1.0));
  std::vector<std::thread> threads;
  for (auto& out : parallel)
    threads.emplace_back([&points, &out] {
      for (size_t i = 0; i < points.size(); ++i) {
        ImpactResult r;
        if (table_->resolve(params_, state_of(points[i]), &r)) out[i] = r.rebound_speed;
      }
    });
  for (std::thread& t : threads) t.join();
  for (const auto& out : parallel) EXPECT_EQ(out, serial);
}

TEST_F(ImpactTableTest, SaveLoadRoundTripGivesIdenticalAnswers) {
  const std::string path = (dir_ / "round_trip.bin").string();
  ASSERT_TRUE(table_->save(path));
  const std::optional<ImpactTable> loaded = ImpactTable::load(path);
  ASSERT_TRUE(loaded.has_value());
  EXPECT_TRUE(loaded->covers(params_));
  EXPECT_EQ(loaded->measured_error().max_speed_relative,
            table_->measured_error().max_speed_relative);
  EXPECT_EQ(loaded->measured_error().fallback_cells, table_->measured_error().fallback_cells);
  // Same data and code: bit-identical answers (a deliberate determinism check).
  for (bool roll : {false, true}) {
    for (const Sample& s : samples(300, 31, roll)) {
      ImpactResult a, b;
      const bool ha = table_->resolve(params_, state_of(s), &a);
      ASSERT_EQ(ha, loaded->resolve(params_, state_of(s), &b));
      if (!ha) continue;
      EXPECT_EQ(a.outgoing.velocity.x, b.outgoing.velocity.x);
      EXPECT_EQ(a.outgoing.velocity.y, b.outgoing.velocity.y);
      EXPECT_EQ(a.outgoing.spin.z, b.outgoing.spin.z);
      EXPECT_EQ(a.impulse_total, b.impulse_total);
    }
  }
}

TEST_F(ImpactTableTest, TruncatedOrCorruptFileIsRejected) {
  const std::string path = (dir_ / "damaged.bin").string();
  ASSERT_TRUE(table_->save(path));
  const auto size = std::filesystem::file_size(path);
  std::vector<char> bytes(size);
  std::ifstream(path, std::ios::binary).read(bytes.data(), static_cast<std::streamsize>(size));

  auto write = [&](const std::vector<char>& data) {
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(data.data(), static_cast<std::streamsize>(data.size()));
  };
  write(std::vector<char>(bytes.begin(), bytes.begin() + static_cast<long>(size / 2)));
  EXPECT_FALSE(ImpactTable::load(path).has_value()) << "truncated to half";
  write(std::vector<char>(bytes.begin(), bytes.end() - 1));
  EXPECT_FALSE(ImpactTable::load(path).has_value()) << "one byte short";
  std::vector<char> flipped = bytes;
  flipped[size / 3] = static_cast<char>(flipped[size / 3] ^ 0x10);
  write(flipped);
  EXPECT_FALSE(ImpactTable::load(path).has_value()) << "one bit flipped";
  write({});
  EXPECT_FALSE(ImpactTable::load(path).has_value()) << "empty";
  EXPECT_FALSE(ImpactTable::load((dir_ / "missing.bin").string()).has_value());
  write(bytes);
  EXPECT_TRUE(ImpactTable::load(path).has_value()) << "the intact file loads";
}

TEST_F(ImpactTableTest, CacheFileNameEncodesParametersAndOptions) {
  const ImpactTableOptions o = tiny_options();
  const std::string base = ImpactTable::cache_file_name(params_, o);
  auto differs = [&](const CushionParams& p, const ImpactTableOptions& q) {
    return ImpactTable::cache_file_name(p, q) != base;
  };
  CushionParams p = params_;
  p.restitution = 0.97;
  EXPECT_TRUE(differs(p, o));
  p = params_;
  p.mu_cushion = 0.14000001;
  EXPECT_TRUE(differs(p, o));
  ImpactTableOptions q = o;
  q.sidespin_nodes += 1;
  EXPECT_TRUE(differs(params_, q));
  q = o;
  q.roll_alpha_nodes += 1;
  EXPECT_TRUE(differs(params_, q));
  q = o;
  q.cell_tolerance *= 0.5;
  EXPECT_TRUE(differs(params_, q));
  q = o;
  q.threads = 3;  // does not change the table
  EXPECT_FALSE(differs(params_, q));
  EXPECT_FALSE(differs(params_for_radius(0.03), o));  // nor does the ball's size
}

TEST(ImpactTableOptionsTest, ValidateNamesTheField) {
  EXPECT_FALSE(ImpactTableOptions{}.validate());
  auto message = [](auto change) {
    ImpactTableOptions o;
    change(o);
    const Validation e = o.validate();
    return e ? e->message() : std::string();
  };
  EXPECT_NE(message([](auto& o) { o.alpha_nodes = 3; }).find("alpha_nodes"), std::string::npos);
  EXPECT_NE(message([](auto& o) { o.topspin_nodes = 6; }).find("topspin_nodes"), std::string::npos);
  EXPECT_NE(message([](auto& o) { o.sidespin_nodes = 2; }).find("sidespin_nodes"),
            std::string::npos);
  EXPECT_NE(message([](auto& o) { o.roll_sidespin_nodes = 0; }).find("roll_sidespin_nodes"),
            std::string::npos);
  EXPECT_NE(message([](auto& o) { o.k_max = 0.0; }).find("k_max"), std::string::npos);
  EXPECT_NE(message([](auto& o) { o.k_max = INFINITY; }).find("k_max"), std::string::npos);
  EXPECT_NE(message([](auto& o) { o.cell_tolerance = -1.0; }).find("cell_tolerance"),
            std::string::npos);
  EXPECT_NE(message([](auto& o) { o.threads = -1; }).find("threads"), std::string::npos);
}

TEST(ImpactTableBuildTest, InvalidOptionsGiveAnEmptyTableThatCoversNothing) {
  ImpactTableOptions o = tiny_options();
  o.alpha_nodes = 2;
  const ImpactTable t = ImpactTable::build(CushionParams{}, o);
  EXPECT_TRUE(t.empty());
  EXPECT_FALSE(t.covers(CushionParams{}));
  ImpactResult r;
  EXPECT_FALSE(t.resolve(CushionParams{}, incoming_state_k(1.0, 45.0, 0.0, 0.0, 0.02625), &r));
  EXPECT_FALSE(t.save((std::filesystem::temp_directory_path() / "cueplan_never.bin").string()));
}

}  // namespace
}  // namespace cueplan::physics
