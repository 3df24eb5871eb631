// End-to-end tests of `prs export`: one file per scene in a directory, one file or stdout for
// one scene, the same files for any thread count and from a scenes file, and a located message
// with the documented exit code for each bad command line or input.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "cli/test/prs_test_fixture.h"

namespace prs::cli {
namespace {

using ExportTest = PrsTest;

TEST_F(ExportTest, WritesOneFilePerSceneIntoADirectory) {
  const fs::path out = dir_ / "mjcf";
  const Result r = Run({"export", Example("table_cube.prs"), "-n", "3", "-s", "1", "--format",
                        "mjcf", "-o", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("prs: wrote 3 files to"), std::string::npos) << r.err;
  std::vector<std::string> files;
  for (const char* name :
       {"table_cube_s1_i0.xml", "table_cube_s1_i1.xml", "table_cube_s1_i2.xml"}) {
    files.push_back(ReadText(out / name));
    EXPECT_NE(files.back().find("<mujoco model=\"prs_scene\">"), std::string::npos) << name;
    EXPECT_NE(files.back().find("<freejoint name=\"Cube_5_free\"/>"), std::string::npos) << name;
  }
  EXPECT_NE(files[0], files[1]);  // different scenes
}

TEST_F(ExportTest, OneSceneGoesToAFileNamedByItsExtensionOrToStdout) {
  const fs::path file = dir_ / "scene.urdf";
  const Result to_file =
      Run({"export", Example("table_cube.prs"), "-s", "5", "--start", "2", "-o", file.string()});
  ASSERT_EQ(to_file.exit_code, 0) << to_file.err;
  EXPECT_NE(ReadText(file).find("<robot name=\"prs_scene\">"), std::string::npos);
  const Result to_stdout =
      Run({"export", Example("table_cube.prs"), "-s", "5", "--start", "2", "--format", "urdf"});
  ASSERT_EQ(to_stdout.exit_code, 0) << to_stdout.err;
  EXPECT_EQ(to_stdout.out, ReadText(file));
  const fs::path glb = dir_ / "scene.glb";
  ASSERT_EQ(Run({"export", Example("table_cube.prs"), "-o", glb.string()}).exit_code, 0);
  EXPECT_EQ(ReadText(glb).substr(0, 4), "glTF");  // the binary container's magic
}

TEST_F(ExportTest, FilesAreTheSameForAnyThreadCount) {
  auto export_with = [&](const char* threads) {
    const fs::path out = dir_ / (std::string("t") + threads);
    const Result r = Run({"export", Example("constructs.prs"), "-n", "6", "-s", "3", "--format",
                          "sdf", "--threads", threads, "-o", out.string()});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return ReadText(out / "constructs_s3_i5.sdf");
  };
  const std::string one = export_with("1");
  EXPECT_NE(one.find("<sdf version=\"1.9\">"), std::string::npos);
  EXPECT_EQ(export_with("2"), one);
}

TEST_F(ExportTest, AScenesFileExportsToTheSameFilesAsItsScenario) {
  const std::string scenes = (dir_ / "scenes.jsonl").string();
  ASSERT_EQ(
      Run({"sample", Example("table_cube.prs"), "-n", "2", "-s", "4", "-o", scenes}).exit_code, 0);
  for (const char* format : {"mjcf", "usda", "gltf"}) {
    const fs::path from_file = dir_ / (std::string("file_") + format);
    const fs::path direct = dir_ / (std::string("direct_") + format);
    const Result r = Run({"export", scenes, "--format", format, "-o", from_file.string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_EQ(Run({"export", Example("table_cube.prs"), "-n", "2", "-s", "4", "--format", format,
                   "-o", direct.string()})
                  .exit_code,
              0);
    const std::string extension =
        std::string(format) == "mjcf" ? ".xml" : fmt::format(".{}", format);
    const std::string a = ReadText(from_file / ("scenes_s4_i1" + extension));
    const std::string b = ReadText(direct / ("table_cube_s4_i1" + extension));
    ASSERT_FALSE(a.empty()) << format;
    EXPECT_EQ(a, b) << format;
  }
}

TEST_F(ExportTest, BadCommandLinesAreUsageErrors) {
  const std::string file = Example("table_cube.prs");
  const std::pair<std::vector<std::string>, std::string> cases[] = {
      {{"--format", "mjc"}, "--format: unknown format 'mjc'; did you mean 'mjcf'?"},
      {{"-n", "2", "-o", (dir_ / "a.xml").string()}, "names one file, but 2 scenes"},
      {{"-o", (dir_ / "a.urdf").string(), "--format", "sdf"}, "has the extension of urdf"},
      {{}, "no format: give --format"},
      {{"--format", "sdf", "-n", "2"}, "2 scenes make 2 files: give a directory with -o DIR"},
      {{"--format", "sdf", "-n", "0"}, "expects an integer >= 1"},
  };
  for (const auto& [extra, message] : cases) {
    std::vector<std::string> args = {"export", file};
    args.insert(args.end(), extra.begin(), extra.end());
    const Result r = Run(args);
    EXPECT_EQ(r.exit_code, 2) << message << "\n" << r.err;
    EXPECT_NE(r.err.find("prs: error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  }
}

TEST_F(ExportTest, BadInputsAreLocated) {
  const std::string scenes =
      Write("bad.jsonl", "\n{\"format\":\"prs-scene/1\",\"objects\":[]}\n{oops\n");
  const Result bad_line = Run({"export", scenes, "--format", "mjcf", "-o", (dir_ / "o").string()});
  EXPECT_EQ(bad_line.exit_code, 1);
  EXPECT_NE(bad_line.err.find("bad.jsonl:3: not valid JSON"), std::string::npos) << bad_line.err;

  const std::string typo = Write("typo.prs", "from model import *\nt = Tabel on floor\n");
  const Result compile = Run({"export", typo, "-I", Example(""), "--format", "mjcf"});
  EXPECT_EQ(compile.exit_code, 1);
  EXPECT_NE(compile.err.find(typo + ":2:5: error: unknown class 'Tabel'"), std::string::npos)
      << compile.err;

  const std::string impossible =
      Write("impossible.prs", "from model import *\nt = Table on floor\nrequire t.x > 5\n");
  const Result failed =
      Run({"export", impossible, "-I", Example(""), "--format", "mjcf", "--max-attempts", "20"});
  EXPECT_EQ(failed.exit_code, 3) << failed.err;
  EXPECT_NE(failed.err.find("no valid scene after 20 attempts"), std::string::npos) << failed.err;

  const std::string unwritable = (dir_ / "no" / "such" / "dir" / "x.sdf").string();
  const Result write = Run({"export", Example("table_cube.prs"), "-o", unwritable});
  EXPECT_EQ(write.exit_code, 1);
  EXPECT_NE(write.err.find("prs: error: cannot write " + unwritable), std::string::npos)
      << write.err;
}

TEST_F(ExportTest, UnreadablePropertiesAreWarnedAboutOnce) {
  const std::string file =
      Write("bleu.prs", "from model import *\nCube at V3D(0, 0, 0.5), with color \"bleu\"\n");
  const Result r = Run({"export", file, "-I", Example(""), "-n", "3", "--format", "usda", "-o",
                        (dir_ / "usd").string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::string warning = "prs: warning: object Cube_0 (Cube): color 'bleu'";
  ASSERT_NE(r.err.find(warning), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(warning, r.err.find(warning) + 1), std::string::npos) << r.err;
}

}  // namespace
}  // namespace prs::cli
