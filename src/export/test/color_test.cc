// Colour parsing: names, grey levels, triples as text and as values, and what is refused.
#include "export/color.h"

#include <gtest/gtest.h>

namespace prs::exporting {
namespace {

void ExpectColor(const std::optional<Rgba>& color, double r, double g, double b, double a = 1) {
  ASSERT_TRUE(color.has_value());
  EXPECT_NEAR(color->r, r, 1e-9);
  EXPECT_NEAR(color->g, g, 1e-9);
  EXPECT_NEAR(color->b, b, 1e-9);
  EXPECT_NEAR(color->a, a, 1e-9);
}

TEST(ColorTest, ReadsNamesWhateverTheCaseAndSpacing) {
  ExpectColor(ParseColorText("blue"), 0, 0, 1);
  ExpectColor(ParseColorText("Red"), 1, 0, 0);
  ExpectColor(ParseColorText("grey"), 128 / 255.0, 128 / 255.0, 128 / 255.0);
  ExpectColor(ParseColorText("light gray"), 211 / 255.0, 211 / 255.0, 211 / 255.0);
  ExpectColor(ParseColorText("#ff8000"), 1, 128 / 255.0, 0);
}

TEST(ColorTest, ReadsGreyLevelsAndTriples) {
  ExpectColor(ParseColorText("0.5"), 0.5, 0.5, 0.5);
  ExpectColor(ParseColorText("0.1 0.2 0.3"), 0.1, 0.2, 0.3);
  ExpectColor(ParseColorText("(0.1, 0.2, 0.3, 0.5)"), 0.1, 0.2, 0.3, 0.5);
  ExpectColor(ParseColorText("255, 0, 51"), 1, 0, 0.2);
}

TEST(ColorTest, RefusesWhatIsNotAColour) {
  EXPECT_FALSE(ParseColorText("bleu"));
  EXPECT_FALSE(ParseColorText(""));
  EXPECT_FALSE(ParseColorText("0.1 0.2"));
  EXPECT_FALSE(ParseColorText("-0.5"));
  EXPECT_FALSE(ParseColorText("300 0 0"));
  EXPECT_FALSE(ParseColor(lang::Value(true)));
  EXPECT_FALSE(ParseColor(lang::Value(1.5)));
}

TEST(ColorTest, ReadsValuesOfTheLanguage) {
  ExpectColor(ParseColor(lang::MakeString("white")), 1, 1, 1);
  ExpectColor(ParseColor(lang::Value(0.25)), 0.25, 0.25, 0.25);
  ExpectColor(ParseColor(lang::Value(Eigen::Vector3d(0, 0.5, 1))), 0, 0.5, 1);
  ExpectColor(ParseColor(lang::MakeTuple({lang::Value(1.0), lang::Value(0.0), lang::Value(0.0)})),
              1, 0, 0);
  ExpectColor(ParseColor(lang::MakeList({lang::Value(0.0), lang::Value(1.0), lang::Value(0.0)})), 0,
              1, 0);
  EXPECT_FALSE(
      ParseColor(lang::MakeList({lang::Value(0.0), lang::MakeString("x"), lang::Value(0.0)})));
}

}  // namespace
}  // namespace prs::exporting
