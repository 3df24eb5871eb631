// The colour parser: names, grey levels, number lists in both scales, hex, and refusals.
#include "render/color.h"

#include <gtest/gtest.h>

namespace prs::render {
namespace {

void ExpectRgb(const std::optional<Rgba>& c, float r, float g, float b) {
  ASSERT_TRUE(c.has_value());
  EXPECT_NEAR((*c)[0], r, 1e-6);
  EXPECT_NEAR((*c)[1], g, 1e-6);
  EXPECT_NEAR((*c)[2], b, 1e-6);
}

TEST(ColorTest, NamesAreCaseInsensitiveAndGreySpelledBothWays) {
  const auto blue = ParseColorText("Blue");
  ASSERT_TRUE(blue);
  EXPECT_GT((*blue)[2], (*blue)[0] + 0.4f);
  EXPECT_EQ(ParseColorText("grey"), ParseColorText("GRAY"));
  EXPECT_NE(ParseColorText("red"), ParseColorText("green"));
  EXPECT_TRUE(ParseColorText("Navy"));
  EXPECT_TRUE(ParseColorText("darkgray"));
}

TEST(ColorTest, GreyLevelFromTextOrNumber) {
  ExpectRgb(ParseColorText("0.5"), 0.5f, 0.5f, 0.5f);
  ExpectRgb(ParseColorText(" 0.2 "), 0.2f, 0.2f, 0.2f);
  ExpectRgb(ParseColorNumbers({0.25}), 0.25f, 0.25f, 0.25f);
}

TEST(ColorTest, TriplesInUnitOr255Scale) {
  ExpectRgb(ParseColorText("0.1, 0.2 0.3"), 0.1f, 0.2f, 0.3f);
  ExpectRgb(ParseColorNumbers({255, 0, 51}), 1.0f, 0.0f, 0.2f);
  const auto rgba = ParseColorNumbers({1, 0, 0, 0.5});
  ASSERT_TRUE(rgba);
  EXPECT_FLOAT_EQ((*rgba)[3], 0.5f);
}

TEST(ColorTest, HexCodes) { ExpectRgb(ParseColorText("#FF8000"), 1.0f, 128 / 255.0f, 0.0f); }

TEST(ColorTest, RefusesWhatIsNotAColour) {
  EXPECT_FALSE(ParseColorText("bluish"));
  EXPECT_FALSE(ParseColorText(""));
  EXPECT_FALSE(ParseColorText("#12345"));
  EXPECT_FALSE(ParseColorText("0.1 0.2"));
  EXPECT_FALSE(ParseColorNumbers({-0.1, 0, 0}));
  EXPECT_FALSE(ParseColorNumbers({300, 0, 0}));
  EXPECT_FALSE(ParseColorNumbers({}));
}

}  // namespace
}  // namespace prs::render
