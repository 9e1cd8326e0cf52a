// Names games give balls: snooker reds and colours, pool numbers, and the first-contact
// classes built on them.
#include "cueplan/problems/ball_names.hpp"

#include <gtest/gtest.h>

namespace cueplan::problems {
namespace {

TEST(BallNames, SnookerRedsAndColoursCarryTheirValues) {
  EXPECT_EQ(identify_ball("red").kind, BallKind::red);
  EXPECT_EQ(identify_ball("red12").kind, BallKind::red);
  EXPECT_EQ(identify_ball("red12").number, 1);
  EXPECT_EQ(identify_ball("reddish").kind, BallKind::plain);
  EXPECT_EQ(identify_ball("yellow").number, 2);
  EXPECT_EQ(identify_ball("brown").number, 4);
  EXPECT_EQ(identify_ball("black").number, 7);
  EXPECT_EQ(identify_ball("black").kind, BallKind::colour);
}

TEST(BallNames, PoolNumbersSplitIntoSolidsTheEightAndStripes) {
  EXPECT_EQ(identify_ball("1").kind, BallKind::pool_solid);
  EXPECT_EQ(identify_ball("ball7").kind, BallKind::pool_solid);
  EXPECT_EQ(identify_ball("8").kind, BallKind::pool_eight);
  EXPECT_EQ(identify_ball("9").kind, BallKind::pool_stripe);
  EXPECT_TRUE(identify_ball("9").striped);
  EXPECT_FALSE(identify_ball("1").striped);
  // A stripe wears its solid's colour: 9 is yellow like 1, 15 maroon like 7.
  EXPECT_EQ(identify_ball("9").colour, identify_ball("1").colour);
  EXPECT_EQ(identify_ball("15").colour, identify_ball("7").colour);
  EXPECT_EQ(identify_ball("16").kind, BallKind::plain);
  EXPECT_EQ(identify_ball("0").kind, BallKind::plain);
  EXPECT_EQ(identify_ball("07").kind, BallKind::plain);
  EXPECT_TRUE(identify_ball("object").colour.empty());
}

TEST(BallNames, ContactClassesFollowTheRules) {
  const std::vector<physics::ObjectBall> rack{{"9", {1, 1}}, {"3", {1, 1.2}}, {"5", {2, 1}}};
  EXPECT_EQ(lowest_pool_ball(rack), "3");
  EXPECT_TRUE(contact_allowed("lowest", "3", rack));
  EXPECT_FALSE(contact_allowed("lowest", "5", rack));
  EXPECT_TRUE(contact_allowed("solids", "5", rack));
  EXPECT_FALSE(contact_allowed("solids", "9", rack));
  EXPECT_TRUE(contact_allowed("stripes", "9", rack));
  EXPECT_TRUE(contact_allowed("any_red", "red4", rack));
  EXPECT_FALSE(contact_allowed("any_red", "pink", rack));
  EXPECT_TRUE(contact_allowed("any_colour", "pink", rack));
  EXPECT_TRUE(contact_allowed("5", "5", rack));
  EXPECT_FALSE(contact_allowed("5", "3", rack));
  EXPECT_TRUE(is_contact_class("lowest"));
  EXPECT_FALSE(is_contact_class("red"));
  EXPECT_FALSE(lowest_pool_ball({{"red", {1, 1}}}).has_value());
}

}  // namespace
}  // namespace cueplan::problems
