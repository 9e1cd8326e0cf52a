#include "cueplan/physics/validation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace cueplan::physics {
namespace {

TEST(FieldPath, TextJoinsNamesWithDotsAndIndicesInBrackets) {
  EXPECT_EQ((FieldPath{"table", "length"}).text(), "table.length");
  EXPECT_EQ((FieldPath{"balls", "red", 0}).text(), "balls.red[0]");
  EXPECT_EQ((FieldPath{"pockets", 2, "radius"}).text(), "pockets[2].radius");
  EXPECT_EQ((FieldPath{"obstacles", 3}).text(), "obstacles[3]");
  EXPECT_EQ(FieldPath{}.text(), "");
}

TEST(FieldPath, UnderPrefixesAndDropFrontUndoesIt) {
  const FieldPath inner{"mu_roll"};
  const FieldPath outer = inner.under({"cloth"});
  EXPECT_EQ(outer, (FieldPath{"cloth", "mu_roll"}));
  EXPECT_TRUE(outer.starts_with({"cloth"}));
  EXPECT_FALSE(outer.starts_with({"mu_roll"}));
  EXPECT_EQ(outer.drop_front(1), inner);
  EXPECT_TRUE(outer.drop_front(5).empty());
  // A name and an index are different steps even when they print alike.
  EXPECT_NE((FieldPath{"pockets", 0}), (FieldPath{"pockets", "0"}));
}

TEST(ValidationError, MessageNamesTheFieldTheRuleAndTheValue) {
  const ValidationError e = invalid({"table", "length"}, "must be positive and finite (m)", -1.5);
  EXPECT_EQ(e.message(), "table.length must be positive and finite (m), got -1.5");
  EXPECT_EQ(e.message("--length"), "--length must be positive and finite (m), got -1.5");
  EXPECT_EQ(e.rule_text(), "must be positive and finite (m), got -1.5");
  // Ten significant digits, as the messages have always shown them.
  EXPECT_EQ(invalid({"x"}, "must be small", 1.0 / 3.0).message(),
            "x must be small, got 0.3333333333");
  EXPECT_EQ(invalid({"x"}, "must be finite", NAN).message(), "x must be finite, got nan");
  EXPECT_EQ(invalid({"x"}, "must be given").message(), "x must be given");
}

TEST(ValidationError, OtherFieldIsNamedByEachLayer) {
  ValidationError e = invalid({"obstacles", 2}, "overlaps {other}");
  e.other = FieldPath{"obstacles", 0};
  EXPECT_EQ(e.message(), "obstacles[2] overlaps obstacles[0]");
  EXPECT_EQ(e.message("ball 3", "ball 1"), "ball 3 overlaps ball 1");
  const ValidationError moved = e.under({"scene"});
  EXPECT_EQ(moved.field, (FieldPath{"scene", "obstacles", 2}));
  EXPECT_EQ(*moved.other, (FieldPath{"scene", "obstacles", 0}));
}

}  // namespace
}  // namespace cueplan::physics
