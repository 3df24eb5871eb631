// Dataset campaigns: shards run in any order and on 1 or 2 threads merge into exactly the files
// of one machine's dataset; a shard whose folder went missing is bad; a merge waits for every
// shard.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "campaign/campaign.h"
#include "campaign/test/campaign_dir.h"
#include "sampling/test/scene_checks.h"

namespace prs::campaign {
namespace {

namespace fs = std::filesystem;

std::map<std::string, std::string> ReadTree(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    files[fs::relative(entry.path(), root).string()] = bytes.str();
  }
  return files;
}

TEST(DatasetCampaignTest, ShardsInAnyOrderMergeIntoOneMachinesDataset) {
  const std::string dir = MakeTestCampaignDir();
  const auto program = sampling::testing_checks::CompileExample("table_cube.prs");
  CampaignSpec spec;
  spec.kind = "dataset";
  spec.seed = 4;
  spec.count = 7;
  spec.shard_size = 3;
  spec.scenario_words = {"examples/table_cube.prs"};
  spec.version = "test";
  spec.dataset.cameras = {"Camera#6"};
  spec.dataset.width = 96;
  spec.dataset.height = 72;
  spec.dataset.images_per_chunk = 4;  // chunks that straddle shards
  spec = InitCampaign(dir, *program, spec);
  const CampaignSpec read = ReadCampaign(dir);
  EXPECT_EQ(read.dataset.cameras, spec.dataset.cameras);
  EXPECT_EQ(read.dataset.images_per_chunk, 4);
  const auto copy = CompileCampaign(dir, read);
  EXPECT_THROW(MergeDatasetShards(dir, read, dir + "/early"), CampaignError);
  for (uint64_t k = 3; k-- > 0;) RunShard(dir, read, *copy, k, nullptr, 1 + int(k % 2), nullptr);
  RunShard(dir, read, *copy, 1, nullptr, 2, nullptr);  // a re-run rewrites the same files
  MergeDatasetShards(dir, read, dir + "/merged");

  dataset::DatasetOptions options = spec.dataset;
  options.dir = dir + "/single";
  dataset::DatasetWriter writer(options, dataset::ListClassIds(*program));
  sampling::BatchOptions batch;
  batch.seed = 4;
  batch.count = 7;
  dataset::AddSampledScenes(writer, *program, batch);
  EXPECT_EQ(writer.Finish(), 7);
  const auto merged = ReadTree(dir + "/merged"), single = ReadTree(dir + "/single");
  EXPECT_GT(single.size(), 7u * 14);
  EXPECT_TRUE(fs::exists(dir + "/single/train_pbr/000001/scene_gt.json"));
  EXPECT_EQ(merged.size(), single.size());
  for (const auto& [path, bytes] : single) {
    EXPECT_TRUE(merged.count(path) && merged.at(path) == bytes) << path;
  }
  // A shard whose dataset folder is gone is bad, not done.
  fs::rename(DatasetShardPath(dir, 2), dir + "/moved");
  EXPECT_EQ(CheckShard(dir, read, 2).state, ShardStatus::State::kBad);
  EXPECT_NE(CheckShard(dir, read, 2).why.find("is missing"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace prs::campaign
