// Failure search: the cross-entropy method finds the planted 0.1 % failure within a fixed
// budget where i.i.d. sampling does not, every evaluated scene satisfies the whole program
// (checked independently), records are the same for any thread count, and bad requests are
// refused.
#include "search/search.h"

#include <gtest/gtest.h>

#include "harness/registry.h"
#include "sampling/test/scene_checks.h"

namespace prs::search {
namespace {

using sampling::testing_checks::CompileOrDie;

std::unique_ptr<lang::CompiledProgram> CompileTableCube() {
  return sampling::testing_checks::CompileExample("table_cube.prs");
}

// Runs the planted controller and checks each scene against table_cube.prs's relations on
// the way, independently of the sampler (the scene is only available inside the episode).
class CheckingPlanted : public harness::Controller {
 public:
  explicit CheckingPlanted(harness::PlantedFailure failure)
      : inner_(harness::MakePlantedController(failure)) {}
  harness::EpisodeResult RunEpisode(const sampling::SampledScene& sampled,
                                    const std::string& json) override {
    using namespace sampling::testing_checks;
    const lang::Scene& s = sampled.scene;
    const auto& table = Find(s, "t");
    const auto& r1 = Find(s, "r1");
    const auto& r2 = Find(s, "r2");
    const auto& tray1 = Find(s, "tr_1");
    const auto& tray2 = Find(s, "tr_2");
    const auto& cube = FindClass(s, "Cube");
    ExpectCompletelyOn(tray1, table);
    ExpectCompletelyOn(tray2, table);
    ExpectCompletelyOn(cube, tray1);
    // Ahead of r1 / r2, left / right of t: beyond the plane through the centre (spec §5).
    ExpectBeyond(tray1, r1.p_WO, {0, 1, 0});
    ExpectBeyond(tray2, r2.p_WO, {0, 1, 0});
    ExpectBeyond(tray1, table.p_WO, {-1, 0, 0});
    ExpectBeyond(tray2, table.p_WO, {1, 0, 0});
    EXPECT_FALSE(BoxesOverlapByPoints(tray1, tray2));
    const auto& camera = FindClass(s, "Camera");
    EXPECT_TRUE(std::abs(camera.p_WO.x()) <= 0.1 && std::abs(camera.p_WO.y()) <= 0.1 &&
                camera.p_WO.z() >= 1.9 && camera.p_WO.z() <= 2.1);
    return inner_->RunEpisode(sampled, json);
  }

 private:
  std::unique_ptr<harness::Controller> inner_;
};

SearchSummary Search(const lang::CompiledProgram& program, Strategy strategy, int64_t budget,
                     uint64_t seed, int threads, harness::PlantedFailure failure,
                     bool with_score = true) {
  SearchOptions options;
  options.strategy = strategy;
  options.budget = budget;
  options.run.seed = seed;
  options.run.threads = threads;
  return RunSearch(
      program,
      [failure, with_score]() -> std::unique_ptr<harness::Controller> {
        if (with_score) return std::make_unique<CheckingPlanted>(failure);
        // Outcomes alone: the same controller with its score dropped.
        class NoScore : public harness::Controller {
         public:
          explicit NoScore(harness::PlantedFailure f) : inner_(harness::MakePlantedController(f)) {}
          harness::EpisodeResult RunEpisode(const sampling::SampledScene& s,
                                            const std::string& j) override {
            harness::EpisodeResult r = inner_->RunEpisode(s, j);
            r.score.reset();
            return r;
          }
          std::unique_ptr<harness::Controller> inner_;
        };
        return std::make_unique<NoScore>(failure);
      },
      options);
}

TEST(SearchTest, CrossEntropyFindsThePlantedPermilleFailure) {
  const auto program = CompileTableCube();
  const SearchSummary ce =
      Search(*program, Strategy::kCrossEntropy, 1000, 1, 2, harness::PlantedOnePermille());
  const SearchSummary iid =
      Search(*program, Strategy::kRandom, 1000, 1, 2, harness::PlantedOnePermille());
  ASSERT_EQ(ce.records.size(), 1000u);
  EXPECT_EQ(ce.batch, 20);
  EXPECT_EQ(ce.generations, 50);
  // About 1 failure in 1,000 i.i.d. episodes (0.11 % of the scenes); the search finds hundreds.
  EXPECT_LE(iid.failures, 6);
  EXPECT_GE(ce.failures, 200);
  ASSERT_GT(ce.first_failure, 0);
  EXPECT_LE(ce.first_failure, 400);
  ASSERT_EQ(ce.proposal_mean.size(), ce.coordinates.size());
  for (const auto& record : ce.records) {
    EXPECT_EQ(record.coordinates.size(), ce.coordinates.size());
    EXPECT_EQ(record.search["strategy"], "ce");
    ASSERT_TRUE(record.result.score.has_value());
    EXPECT_EQ(*record.result.score <= 0, record.result.outcome == "planted-failure");
  }
}

TEST(SearchTest, AnnealAndOutcomeOnlySearchesBeatIid) {
  const auto program = CompileTableCube();
  const auto percent = harness::PlantedOnePercent();
  const SearchSummary iid = Search(*program, Strategy::kRandom, 1000, 2, 2, percent);
  const SearchSummary anneal = Search(*program, Strategy::kAnneal, 1000, 2, 2, percent);
  const SearchSummary blind = Search(*program, Strategy::kCrossEntropy, 1000, 2, 2, percent,
                                     /*with_score=*/false);
  EXPECT_LE(iid.failures, 25);  // about 10.5 expected
  EXPECT_GE(anneal.failures, 3 * iid.failures);
  EXPECT_GE(blind.failures, 3 * iid.failures);
}

TEST(SearchTest, RecordsAreTheSameForAnyThreadCount) {
  const auto program = CompileTableCube();
  for (Strategy strategy : {Strategy::kCrossEntropy, Strategy::kAnneal, Strategy::kRandom}) {
    const SearchSummary one = Search(*program, strategy, 120, 9, 1, harness::PlantedOnePercent());
    const SearchSummary two = Search(*program, strategy, 120, 9, 2, harness::PlantedOnePercent());
    ASSERT_EQ(one.records.size(), two.records.size());
    for (size_t i = 0; i < one.records.size(); ++i) {
      EXPECT_EQ(one.records[i].index, i);
      EXPECT_EQ(one.records[i].coordinates, two.records[i].coordinates) << StrategyName(strategy);
      EXPECT_EQ(one.records[i].result.outcome, two.records[i].result.outcome);
    }
  }
}

TEST(SearchTest, BadRequestsAreRefused) {
  const auto program = CompileTableCube();
  EXPECT_THROW(Search(*program, Strategy::kCrossEntropy, 0, 1, 1, harness::PlantedOnePercent()),
               std::invalid_argument);
  const auto fixed = CompileOrDie(
      "from model import *\nTable on V3D(0, 0, 0)\nCube on V3D(0, 0, 1)\n", "examples/fixed.prs");
  try {
    Search(*fixed, Strategy::kCrossEntropy, 10, 1, 1, harness::PlantedOnePercent());
    ADD_FAILURE() << "a program without random draws was searched";
  } catch (const NothingToSearch& error) {
    EXPECT_NE(std::string(error.what()).find("draws nothing at random"), std::string::npos);
  }
  Strategy strategy;
  EXPECT_TRUE(ParseStrategy("anneal", &strategy));
  EXPECT_FALSE(ParseStrategy("bo", &strategy));
}

}  // namespace
}  // namespace prs::search
