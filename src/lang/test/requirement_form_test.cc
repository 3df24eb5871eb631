// ClassifyRequirement: the naive-mode reason of a failed `require`, read from its form.
#include "lang/requirement_form.h"

#include <gtest/gtest.h>

#include "lang/parser.h"

namespace prs::lang {
namespace {

// The kind for `require CONDITION`, parsed on its own.
RejectionKind KindOf(const std::string& condition) {
  SourceManager sources;
  DiagnosticEngine diagnostics;
  const FileId file = sources.AddFile("test.prs", "require " + condition + "\n");
  const Module module = Parse(file, sources, diagnostics, ParseOptions{});
  EXPECT_FALSE(diagnostics.has_errors()) << condition;
  if (module.body.size() != 1) return RejectionKind::kCollision;  // never a requirement's kind
  const auto* require = std::get_if<RequireStmt>(&module.body[0]->node);
  if (!require) return RejectionKind::kCollision;
  return ClassifyRequirement(*require->condition);
}

TEST(RequirementFormTest, ContainmentIsInOrContains) {
  EXPECT_EQ(KindOf("space.contains(tray)"), RejectionKind::kContainment);
  EXPECT_EQ(KindOf("Cuboid(V3D(0, 0, 0), V3D(0, 0, 0), 1, 1, 1).contains(c)"),
            RejectionKind::kContainment);
  EXPECT_EQ(KindOf("c.position in region"), RejectionKind::kContainment);
  EXPECT_EQ(KindOf("a.contains(b) and c in d"), RejectionKind::kContainment);
}

TEST(RequirementFormTest, RelativePositionIsAComparisonOfPositions) {
  EXPECT_EQ(KindOf("tr.y - tr.length / 2 >= r.y"), RejectionKind::kRelativePosition);
  EXPECT_EQ(KindOf("tr.x + tr.width / 2 <= t.x"), RejectionKind::kRelativePosition);
  EXPECT_EQ(KindOf("distance from a to b < 0.5"), RejectionKind::kRelativePosition);
  EXPECT_EQ(KindOf("-0.2 < a.position.x < 0.2"), RejectionKind::kRelativePosition);
  EXPECT_EQ(KindOf("abs(a.z - b.z) == 0"), RejectionKind::kRelativePosition);
  EXPECT_EQ(KindOf("a.x < b.x or a.y < b.y"), RejectionKind::kRelativePosition);
}

TEST(RequirementFormTest, AnythingElseStaysARequirement) {
  EXPECT_EQ(KindOf("a.width < 0.3"), RejectionKind::kRequirement);  // a size, not a position
  EXPECT_EQ(KindOf("flag"), RejectionKind::kRequirement);
  EXPECT_EQ(KindOf("not (a.x < b.x)"), RejectionKind::kRequirement);
  EXPECT_EQ(KindOf("not a.contains(b)"), RejectionKind::kRequirement);
  EXPECT_EQ(KindOf("a.x < b.x and a.contains(b)"), RejectionKind::kRequirement);  // mixed
  EXPECT_EQ(KindOf("len(items) > 2"), RejectionKind::kRequirement);
  EXPECT_EQ(KindOf("a.color == \"red\""), RejectionKind::kRequirement);
  EXPECT_EQ(KindOf("is_far(a, b)"), RejectionKind::kRequirement);
}

}  // namespace
}  // namespace prs::lang
