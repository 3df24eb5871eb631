// More scenes like the failures: records read back with their checks (another program, no
// failures, no coordinates), the fitted proposal, and scenes drawn from it that satisfy the
// program and fall in the planted failure region far more often than i.i.d. scenes.
#include "search/like.h"

#include <gtest/gtest.h>

#include "harness/registry.h"
#include "sampling/batch.h"
#include "sampling/test/scene_checks.h"
#include "search/search.h"

namespace prs::search {
namespace {

using sampling::testing_checks::CompileOrDie;

std::unique_ptr<lang::CompiledProgram> CompileTableCube() {
  return sampling::testing_checks::CompileExample("table_cube.prs");
}

std::vector<std::string> SearchRecords(const lang::CompiledProgram& program) {
  SearchOptions options;
  options.budget = 400;
  options.run.seed = 3;
  options.run.threads = 2;
  const SearchSummary summary = RunSearch(
      program, [] { return harness::MakePlantedController(harness::PlantedOnePermille()); },
      options);
  std::vector<std::string> lines;
  for (const auto& record : summary.records) lines.push_back(harness::FormatRecordJson(record));
  return lines;
}

TEST(LikeTest, ScenesLikeTheFailuresFallInTheFailureRegion) {
  const auto program = CompileTableCube();
  const int d = static_cast<int>(sampling::DescribeCoordinates(*program).size());
  const std::string hash = CalcSpecHash(*program);
  const FailureSet failures = ReadFailures(SearchRecords(*program), "r.jsonl", "", hash, d);
  ASSERT_GE(failures.coordinates.size(), 20u);
  const GaussianPoints like = FitLike(failures);
  sampling::BatchOptions options;
  options.seed = 8;
  options.count = 2000;
  options.threads = 2;
  options.sample.points = &like;
  auto planted = harness::MakePlantedController(harness::PlantedOnePermille());
  int64_t in_region = 0;
  sampling::SampleBatch(
      *program, options,
      {.prepare = {}, .consume = [&](sampling::BatchScene&& s) {
         // Still the program's scene: the same relations as every scene.
         using namespace sampling::testing_checks;
         ExpectCompletelyOn(FindClass(s.sampled.scene, "Cube"), Find(s.sampled.scene, "tr_1"));
         ExpectCompletelyOn(Find(s.sampled.scene, "tr_1"), Find(s.sampled.scene, "t"));
         in_region += planted->RunEpisode(s.sampled, "").outcome != "success";
       }});
  // I.i.d. scenes fall there 0.11 % of the time (about 2 in 2,000).
  EXPECT_GE(in_region, 200) << "of 2000";
}

TEST(LikeTest, RecordsAreCheckedAgainstTheProgram) {
  const auto program = CompileTableCube();
  const int d = static_cast<int>(sampling::DescribeCoordinates(*program).size());
  const std::vector<std::string> lines = SearchRecords(*program);
  auto error_of = [&](const std::vector<std::string>& l, const std::string& outcome,
                      const std::string& hash, int dimension) -> std::string {
    try {
      ReadFailures(l, "r.jsonl", outcome, hash, dimension);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  };
  const std::string hash = CalcSpecHash(*program);
  EXPECT_EQ(error_of(lines, "", hash, d), "");
  EXPECT_EQ(error_of(lines, "planted-failure", hash, d), "");
  EXPECT_NE(error_of(lines, "no-path", hash, d).find("(outcomes: planted-failure"),
            std::string::npos);
  // Another program: a changed source, or a -p override.
  const auto other =
      CompileOrDie("from model import *\nTable on V3D(0, 0, Range(0, 1))\n", "examples/other.prs");
  EXPECT_NE(CalcSpecHash(*other), hash);
  EXPECT_NE(error_of(lines, "", CalcSpecHash(*other), d).find("another program"),
            std::string::npos);
  EXPECT_NE(error_of(lines, "", hash, d + 1).find("must be 12 numbers"), std::string::npos);
  EXPECT_NE(error_of({"{\"outcome\": \"success\"}"}, "", hash, d).find("no record has scene"),
            std::string::npos);
  EXPECT_NE(error_of({"not json"}, "", hash, d).find("r.jsonl:1: not an episode record"),
            std::string::npos);
  EXPECT_EQ(CalcSpecHash(*program), CalcSpecHash(*CompileTableCube()));
}

}  // namespace
}  // namespace prs::search
