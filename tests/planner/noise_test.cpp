// What side costs in the execution noise (docs/squirt.md): the tip offset's deviation
// growing with the offset, the misjudged squirt, and the cue pivoting at the bridge
// against the squirt of a tip error, checked against the natural pivot length worked
// out from the squirt's small-offset slope.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cueplan/physics/shot.hpp"
#include "cueplan/planner/planner.hpp"
#include "robustness.hpp"

namespace cueplan::planner {
namespace {

constexpr double kPoolMass = 0.17, kPoolRadius = 0.028575;

// The direction (deg) the noisy stroke sends the ball: the cue's aim turned by its squirt.
double ball_direction(const physics::Shot& s, const physics::CueParams& cue) {
  return s.aim_deg + physics::squirt_angle_deg(cue, kPoolMass, kPoolRadius, s.sidespin_k);
}

TEST(NoiseModel, TipOffsetDeviationGrowsWithTheOffsetIntended) {
  NoiseModel noise;
  noise.bridge_length = 0.0;
  const detail::NoiseDraw draw{0.0, 0.0, 1.0, -1.0};
  const double dk = physics::kSpinPerTipOffset * noise.tip_offset / kPoolRadius;
  for (double k : {0.0, 0.3, -0.6, 0.9}) {
    const physics::Shot shot{1.0, 10.0, 0.5 * k, k};
    physics::Shot out;
    ASSERT_TRUE(detail::noisy_stroke(shot, draw, noise, kPoolRadius, 1.25, 0.0, &out));
    EXPECT_NEAR(out.sidespin_k - k, dk + noise.tip_offset_relative * std::abs(k), 1e-12);
    EXPECT_NEAR(out.topspin_k - 0.5 * k, -(dk + noise.tip_offset_relative * std::abs(0.5 * k)),
                1e-12);
    EXPECT_EQ(out.aim_deg, 10.0);  // no aim draw, no squirt to misjudge, no pivot
  }
}

TEST(NoiseModel, SquirtJudgementAddsToTheAimInQuadrature) {
  NoiseModel noise;
  noise.bridge_length = 0.0;
  const detail::NoiseDraw draw{1.0, 0.0, 0.0, 0.0};
  physics::Shot out;
  for (double squirt : {0.0, 1.0, -2.5}) {
    ASSERT_TRUE(detail::noisy_stroke({1.0, 0.0, 0.0, 0.5}, draw, noise, kPoolRadius, 1.25, squirt,
                                     &out));
    EXPECT_NEAR(out.aim_deg, std::hypot(noise.aim_deg, noise.squirt_judgement * squirt), 1e-12);
  }
  noise.scale = 2.0;  // --noise scales it too
  ASSERT_TRUE(detail::noisy_stroke({1.0, 0.0, 0.0, 0.5}, draw, noise, kPoolRadius, 1.25, 2.0, &out));
  EXPECT_NEAR(out.aim_deg, 2.0 * std::hypot(noise.aim_deg, noise.squirt_judgement * 2.0), 1e-12);
}

TEST(NoiseModel, ABridgeAtTheNaturalPivotLengthCancelsTheSquirtOfATipError) {
  // Small offsets squirt tan s = (b/R) 2.5 / (3.5 + m/m_e) (TP A-31 at b -> 0), so a tip
  // error d turns the ball by d 2.5 / (R (3.5 + m/m_e)): a cue pivoting at L = R (3.5 +
  // m/m_e) / 2.5 behind the tip turns the other way by d / L.
  const physics::CueParams cue = physics::pool_cue();
  const double pivot = kPoolRadius * (3.5 + kPoolMass / cue.end_mass) / 2.5;
  EXPECT_NEAR(pivot, 0.234, 0.001);
  const detail::NoiseDraw draw{0.0, 0.0, 0.2, 0.0};  // 0.1 mm to the right
  const physics::Shot centre{1.0, 0.0, 0.0, 0.0};
  NoiseModel noise;
  physics::Shot out;
  double turned[3];
  const double lengths[3] = {0.0, pivot, 0.25};
  for (int i = 0; i < 3; ++i) {
    noise.bridge_length = lengths[i];
    ASSERT_TRUE(detail::noisy_stroke(centre, draw, noise, kPoolRadius, 1.25, 0.0, &out));
    turned[i] = ball_direction(out, cue);
  }
  // Shifted sideways: the squirt of 0.1 mm, to the left.
  EXPECT_NEAR(turned[0], 1e-4 * 2.5 / pivot * 180.0 / std::numbers::pi / 2.5, 1e-6);
  EXPECT_GT(turned[0], 0.0);
  EXPECT_LT(std::abs(turned[1]), 1e-3 * turned[0]);  // cancelled to first order
  EXPECT_GT(turned[2], 0.0);
  EXPECT_LT(turned[2], 0.1 * turned[0]);  // a 25 cm bridge: nearly
}

TEST(NoiseModel, ValidationNamesTheNewFields) {
  NoiseModel n;
  n.tip_offset_relative = -0.1;
  EXPECT_EQ(n.validate()->field.text(), "tip_offset_relative");
  n = NoiseModel{};
  n.squirt_judgement = std::nan("");
  EXPECT_EQ(n.validate()->field.text(), "squirt_judgement");
  n = NoiseModel{};
  n.bridge_length = -1.0;
  EXPECT_EQ(n.validate()->field.text(), "bridge_length");
  EXPECT_FALSE(NoiseModel{}.validate());
}

}  // namespace
}  // namespace cueplan::planner
