// End-to-end tests of `prs dataset`: identical bytes for 1 and 2 threads and for a split of the
// index range, COCO ids unique across shards, a scenes file giving the program's own images,
// scene lines that prs reads back, and located errors that leave nothing but DIR.partial.
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "cli/test/prs_test_fixture.h"

namespace prs::cli {
namespace {

// Every file under `root`, by path relative to it, with its bytes.
std::map<std::string, std::string> ReadTree(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.is_regular_file())
      files[fs::relative(entry.path(), root).string()] = ReadText(entry.path());
  }
  return files;
}

class DatasetCommandTest : public PrsTest {
 protected:
  Result Dataset(const std::string& out, std::vector<std::string> more) {
    std::vector<std::string> args = {
        "dataset", Example("table_cube.prs"), "-s", "1", "--size", "160x120",
        "-o",      (dir_ / out).string()};
    args.insert(args.end(), more.begin(), more.end());
    return Run(args);
  }
};

TEST_F(DatasetCommandTest, SameBytesForAnyThreadCountAndSplit) {
  Result r = Dataset("one", {"-n", "6", "--threads", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("6 labelled images of 6 scenes (BOP and COCO)"), std::string::npos) << r.err;
  ASSERT_EQ(Dataset("two", {"-n", "6", "--threads", "2"}).exit_code, 0);
  const auto one = ReadTree(dir_ / "one"), two = ReadTree(dir_ / "two");
  EXPECT_GT(one.size(), 6u * 14);  // rgb, depth and 2 masks for each of 6 objects, per image
  EXPECT_TRUE(one == two);
  // Scenes 3..5 alone: the same pictures and masks as in the whole run.
  ASSERT_EQ(Dataset("a", {"-n", "3"}).exit_code, 0);
  ASSERT_EQ(Dataset("b", {"-n", "3", "--start", "3"}).exit_code, 0);
  const auto b = ReadTree(dir_ / "b");
  int pictures = 0;
  for (const auto& [path, bytes] : b) {
    if (path.ends_with(".png")) {
      EXPECT_EQ(bytes, one.at(path)) << path;
      ++pictures;
    }
  }
  EXPECT_GE(pictures, 3 * 14);
  EXPECT_FALSE(b.count("train_pbr/000000/rgb/000000.png"));
  // COCO annotation ids and image ids: unique across the two shards.
  std::set<int64_t> annotations, images;
  size_t total = 0;
  for (const char* shard : {"a", "b"}) {
    const auto coco =
        nlohmann::json::parse(ReadText(dir_ / shard / "train_pbr/000000/annotations.json"));
    for (const auto& a : coco["annotations"]) annotations.insert(a["id"].get<int64_t>()), ++total;
    for (const auto& i : coco["images"]) images.insert(i["id"].get<int64_t>());
  }
  EXPECT_EQ(annotations.size(), total);
  EXPECT_EQ(images, (std::set<int64_t>{0, 1, 2, 3, 4, 5}));
}

TEST_F(DatasetCommandTest, AScenesFileGivesTheProgramsImagesAndItsLinesReadBack) {
  ASSERT_EQ(Dataset("ds", {"-n", "2"}).exit_code, 0);
  ASSERT_EQ(Run({"sample", Example("table_cube.prs"), "-s", "1", "-n", "2", "-o",
                 (dir_ / "scenes.jsonl").string()})
                .exit_code,
            0);
  // Numbered by the program's classes, the file's dataset is the program's, byte for byte.
  Result r = Run({"dataset", (dir_ / "scenes.jsonl").string(), "-n", "2", "--size", "160x120",
                  "--classes", Example("table_cube.prs"), "-o", (dir_ / "from_file").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto from_program = ReadTree(dir_ / "ds"), from_file = ReadTree(dir_ / "from_file");
  EXPECT_GT(from_file.size(), 2u * 14);
  EXPECT_TRUE(from_program == from_file);
  // Without --classes, the same pictures, objects numbered by the file's own classes (a note
  // says so), and --classes with a program is a usage error.
  r = Run({"dataset", (dir_ / "scenes.jsonl").string(), "-n", "2", "--size", "160x120", "-o",
           (dir_ / "own").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("--classes PROGRAM.prs"), std::string::npos) << r.err;
  EXPECT_TRUE(ReadText(dir_ / "own/train_pbr/000000/rgb/000001.png") ==
              from_program.at("train_pbr/000000/rgb/000001.png"));
  EXPECT_EQ(Dataset("x", {"--classes", Example("table_cube.prs")}).exit_code, 2);
  // Each scene's line, with its images and features, is a scene prs reads.
  const std::string lines = (dir_ / "ds/train_pbr/000000/scenes.jsonl").string();
  const auto first = nlohmann::json::parse(ReadText(lines).substr(0, ReadText(lines).find('\n')));
  EXPECT_EQ(first["seed"], 1);
  EXPECT_EQ(first["images"][0]["im_id"], 0);
  EXPECT_TRUE(first["features"].contains("t.x"));
  const Result again =
      Run({"export", lines, "--format", "mjcf", "-o", (dir_ / "exported").string()});
  EXPECT_EQ(again.exit_code, 0) << again.err;
}

TEST_F(DatasetCommandTest, BadInputIsRefusedWithAReasonAndNothingHalfWritten) {
  Result r = Dataset("ds", {"--camera", "nope"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no object named 'nope'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "ds"));
  EXPECT_TRUE(fs::exists(dir_ / "ds.partial"));
  EXPECT_NE(r.err.find("ds.partial"), std::string::npos) << r.err;

  r = Dataset("sized", {"--size", "0x0"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--size"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "sized.partial"));

  // A directory that holds anything is never written into.
  fs::create_directories(dir_ / "taken");
  Write("taken/notes.txt", "mine");
  r = Dataset("taken", {});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("is not an empty directory"), std::string::npos) << r.err;
  EXPECT_EQ(ReadText(dir_ / "taken/notes.txt"), "mine");

  // An earlier run's DIR.partial is kept, not overwritten.
  r = Dataset("ds", {});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("earlier run"), std::string::npos) << r.err;

  r = Dataset("labelled", {"--label", "Chair"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no object of class Chair"), std::string::npos) << r.err;

  const std::string no_depths = Write("no_depths.prs",
                                      "class Camera:\n    fovy_deg: 40\n    aspect: 1.5\n"
                                      "b = Object at V3D(0, 0, 0.1)\n"
                                      "Camera at V3D(0, 0, 2), facing V3D(0, 0, -1)\n");
  r = Run({"dataset", no_depths, "-o", (dir_ / "d").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("has no near and far"), std::string::npos) << r.err;

  const std::string no_camera = Write("no_camera.prs", "b = Object at V3D(0, 0, 0.1)\n");
  r = Run({"dataset", no_camera, "-o", (dir_ / "e").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no camera object"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "e.partial"));
}

TEST_F(DatasetCommandTest, LikeDrawsTheScenesPrsSampleLikeDraws) {
  const std::string records = (dir_ / "search.jsonl").string();
  ASSERT_EQ(Run({"search", Example("table_cube.prs"), "--controller", "planted-1-percent",
                 "--budget", "120", "-s", "2", "-o", records})
                .exit_code,
            0);
  Result r = Dataset("like", {"-n", "3", "--like", records});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("drawing scenes like the"), std::string::npos) << r.err;
  ASSERT_EQ(Run({"sample", Example("table_cube.prs"), "-s", "1", "-n", "3", "--like", records,
                 "-o", (dir_ / "like.jsonl").string()})
                .exit_code,
            0);
  ASSERT_EQ(Run({"dataset", (dir_ / "like.jsonl").string(), "-n", "3", "--size", "160x120",
                 "--classes", Example("table_cube.prs"), "-o", (dir_ / "file").string()})
                .exit_code,
            0);
  // The same files but the scene lines, which from the program carry the scene coordinates.
  auto from_program = ReadTree(dir_ / "like"), from_file = ReadTree(dir_ / "file");
  const std::string lines = from_program.at("train_pbr/000000/scenes.jsonl");
  EXPECT_NE(lines.find("\"coordinates\":["), std::string::npos);
  from_program.erase("train_pbr/000000/scenes.jsonl");
  from_file.erase("train_pbr/000000/scenes.jsonl");
  EXPECT_GT(from_file.size(), 3u * 14);
  EXPECT_TRUE(from_program == from_file);
  r = Run({"dataset", (dir_ / "like.jsonl").string(), "--like", records, "-o",
           (dir_ / "x").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("give the .prs file"), std::string::npos) << r.err;
}

TEST_F(DatasetCommandTest, AppendGrowsADatasetIntoOneRunsFiles) {
  ASSERT_EQ(Dataset("grown", {"-n", "2"}).exit_code, 0);
  Result r = Dataset("grown", {"-n", "3", "--start", "2", "--append"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(Dataset("whole", {"-n", "5"}).exit_code, 0);
  EXPECT_TRUE(ReadTree(dir_ / "grown") == ReadTree(dir_ / "whole"));
  EXPECT_FALSE(fs::exists(dir_ / "grown.append"));
  // Images it has already: refused, the dataset unchanged, the new images kept aside.
  r = Dataset("grown", {"-n", "2", "--start", "4", "--append"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("their ranges overlap"), std::string::npos) << r.err;
  EXPECT_TRUE(ReadTree(dir_ / "grown") == ReadTree(dir_ / "whole"));
  EXPECT_TRUE(fs::exists(dir_ / "grown.append"));
  r = Dataset("nothing", {"--append"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("is not a dataset"), std::string::npos) << r.err;
}

TEST_F(DatasetCommandTest, ACampaignMergesIntoOneRunsDataset) {
  const std::string dir = (dir_ / "camp").string();
  Result r = Run({"campaign", "init", dir, Example("table_cube.prs"), "--dataset", "-n", "5",
                  "--shard-size", "2", "-s", "1", "--size", "160x120"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("5 scenes"), std::string::npos) << r.err;
  r = Run({"campaign", "merge", dir, "-o", (dir_ / "early").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("shards not done"), std::string::npos) << r.err;
  for (const char* k : {"2", "0", "1"}) {
    r = Run({"campaign", "run-shard", dir, k, "--threads", "1"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  EXPECT_EQ(Run({"campaign", "merge", dir, "-o", (dir_ / "m").string(), "--partial"}).exit_code, 2);
  r = Run({"campaign", "merge", dir, "-o", (dir_ / "merged").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(Dataset("single", {"-n", "5"}).exit_code, 0);
  const auto merged = ReadTree(dir_ / "merged"), single = ReadTree(dir_ / "single");
  EXPECT_GT(single.size(), 5u * 14);
  EXPECT_TRUE(merged == single);
  // The picture options belong to a dataset campaign, which takes no controller.
  r = Run({"campaign", "init", (dir_ / "c2").string(), Example("table_cube.prs"), "-n", "4",
           "--size", "64x48"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("give --dataset"), std::string::npos) << r.err;
  r = Run({"campaign", "init", (dir_ / "c3").string(), Example("table_cube.prs"), "-n", "4",
           "--dataset", "--controller", "table-cube"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("takes no controller"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace prs::cli
