// End-to-end tests of `prs render`: PNG files of the requested size (one per scene, or a grid),
// camera depth PNGs, scenes files as input, located usage errors (exit 2), no display needed.
#include <cstdint>

#include "cli/test/prs_test_fixture.h"

namespace prs::cli {
namespace {

struct PngHeader {
  uint32_t width = 0, height = 0;
  int bit_depth = 0;
};

// Width, height and bit depth from the IHDR chunk that every PNG starts with.
PngHeader ReadPngHeader(const fs::path& path) {
  const std::string bytes = ReadText(path);
  PngHeader header;
  if (bytes.size() < 26 || bytes.compare(1, 3, "PNG") != 0) return header;
  auto read_u32 = [&](size_t at) {
    uint32_t value = 0;
    for (size_t i = 0; i < 4; ++i) value = value << 8 | static_cast<uint8_t>(bytes[at + i]);
    return value;
  };
  header.width = read_u32(16);
  header.height = read_u32(20);
  header.bit_depth = static_cast<uint8_t>(bytes[24]);
  return header;
}

class RenderCommandTest : public PrsTest {
 protected:
  std::string Out(const std::string& name) const { return (dir_ / name).string(); }
};

TEST_F(RenderCommandTest, WritesAPngOfTheRequestedSize) {
  const Result r =
      Run({"render", Example("table_cube.prs"), "--size", "320x240", "-o", Out("a.png")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const PngHeader png = ReadPngHeader(Out("a.png"));
  EXPECT_EQ(png.width, 320u);
  EXPECT_EQ(png.height, 240u);
  EXPECT_NE(r.err.find("rendered 1 scene (320x240, overview)"), std::string::npos) << r.err;
}

TEST_F(RenderCommandTest, GridHoldsAllScenesAndSeveralScenesGetNumberedFiles) {
  ASSERT_EQ(Run({"render", Example("table_cube.prs"), "-n", "5", "--grid", "--size", "100x80", "-o",
                 Out("grid.png")})
                .exit_code,
            0);
  const PngHeader grid = ReadPngHeader(Out("grid.png"));
  EXPECT_EQ(grid.width, 3u * 100 + 2 * 4);  // 3 columns, 4-pixel gutters
  EXPECT_EQ(grid.height, 2u * 80 + 4);
  ASSERT_EQ(Run({"render", Example("table_cube.prs"), "-n", "2", "--start", "7", "--size", "64x48",
                 "-o", Out("one.png")})
                .exit_code,
            0);
  EXPECT_TRUE(fs::exists(Out("one_7.png")));
  EXPECT_TRUE(fs::exists(Out("one_8.png")));
  EXPECT_FALSE(fs::exists(Out("one.png")));
}

TEST_F(RenderCommandTest, CameraViewWritesSixteenBitDepth) {
  const Result r = Run({"render", Example("table_cube.prs"), "--view", "camera:Camera", "-o",
                        Out("rgb.png"), "--depth", Out("depth.png"), "--size", "160x120"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(ReadPngHeader(Out("rgb.png")).width, 160u);
  const PngHeader depth = ReadPngHeader(Out("depth.png"));
  EXPECT_EQ(depth.width, 160u);
  EXPECT_EQ(depth.bit_depth, 16);
}

TEST_F(RenderCommandTest, RendersAScenesFile) {
  const std::string scenes = Out("scenes.jsonl");
  ASSERT_EQ(Run({"sample", Example("table_cube.prs"), "-n", "3", "-o", scenes}).exit_code, 0);
  const Result r = Run({"render", scenes, "--start", "2", "--size", "64x48", "-o", Out("s.png")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(ReadPngHeader(Out("s.png")).width, 64u);
  const std::string bad = Write("bad.jsonl", ReadText(scenes).substr(0, 40) + "\n");
  const Result broken = Run({"render", bad, "-o", Out("b.png")});
  EXPECT_EQ(broken.exit_code, 1);
  EXPECT_NE(broken.err.find(bad + ":1: not valid JSON"), std::string::npos) << broken.err;
}

TEST_F(RenderCommandTest, BadViewAndSizeAreLocatedUsageErrors) {
  const std::string file = Example("table_cube.prs");
  const Result view = Run({"render", file, "--view", "side"});
  EXPECT_EQ(view.exit_code, 2);
  EXPECT_NE(view.err.find("--view"), std::string::npos) << view.err;
  EXPECT_NE(view.err.find("unknown view 'side' (expected overview, top, front or camera:NAME)"),
            std::string::npos)
      << view.err;
  for (const char* size : {"640", "0x480", "640x480x3", "wide"}) {
    const Result r = Run({"render", file, "--size", size});
    EXPECT_EQ(r.exit_code, 2) << size;
    EXPECT_NE(r.err.find("--size"), std::string::npos) << r.err;
  }
  const Result depth = Run({"render", file, "--depth", Out("d.png")});
  EXPECT_EQ(depth.exit_code, 2);
  EXPECT_NE(depth.err.find("--depth needs a camera view"), std::string::npos) << depth.err;
}

TEST_F(RenderCommandTest, ShowRegionsNeedsAScenario) {
  ASSERT_EQ(Run({"render", Example("table_cube.prs"), "--show-regions", "--size", "64x48", "-o",
                 Out("r.png")})
                .exit_code,
            0);
  EXPECT_TRUE(fs::exists(Out("r.png")));
  const std::string scenes = Out("scenes.jsonl");
  ASSERT_EQ(Run({"sample", Example("table_cube.prs"), "-n", "1", "-o", scenes}).exit_code, 0);
  const Result r = Run({"render", scenes, "--show-regions", "-o", Out("s.png")});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--show-regions needs the .prs scenario"), std::string::npos) << r.err;
}

TEST_F(RenderCommandTest, UnknownCameraNameListsTheSceneCameras) {
  const Result r =
      Run({"render", Example("table_cube.prs"), "--view", "camera:eye", "-o", Out("c.png")});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("prs: error: no object named 'eye' to look from (camera objects: "
                       "Camera#6)"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(Out("c.png")));
}

TEST_F(RenderCommandTest, NeedsNoDisplay) {
  ::unsetenv("DISPLAY");
  ::unsetenv("WAYLAND_DISPLAY");
  ::setenv("CI", "true", 1);
  const Result r =
      Run({"render", Example("table_cube.prs"), "--size", "64x48", "-o", Out("d.png")});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(ReadPngHeader(Out("d.png")).height, 48u);
}

}  // namespace
}  // namespace prs::cli
