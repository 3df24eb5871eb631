// The rough edges a new user met, each with the exit code and message it should give: long
// inputs, empty scenes files, empty -o, non-finite params, leftovers, `prs view` of a scenes
// file, /dev/null, byte-order marks, string escapes and directory names in messages.
#include <gtest/gtest.h>

#include <fstream>

#include "cli/test/prs_test_fixture.h"

namespace prs::cli {
namespace {

class RoughEdgesTest : public PrsTest {};

std::string Repeat(const std::string& head, const std::string& piece, int n) {
  std::string out = head;
  for (int i = 0; i < n; ++i) out += piece;
  return out;
}

// 100,000 terms in one expression: a located error and exit 1, never a crash.
TEST_F(RoughEdgesTest, LongChainsAreALocatedError) {
  for (const std::string& text : {Repeat("x = 1", " + 1", 100'000) + "\n",
                                  Repeat("x = Vector3D(1, 0, 0)", ".normalized()", 100'000) + "\n",
                                  Repeat("x = [0]", "[0]", 100'000) + "\n"}) {
    const std::string file = Write("long.prs", text);
    const Result r = Run({"check", file});
    EXPECT_EQ(r.exit_code, 1) << r.err.substr(0, 500);
    EXPECT_NE(r.err.find("long.prs:1:"), std::string::npos) << r.err.substr(0, 500);
    EXPECT_NE(r.err.find("expression nested too deeply"), std::string::npos);
    EXPECT_LT(r.err.size(), 2000u);  // a window of the line, not the whole of it
  }
}

TEST_F(RoughEdgesTest, EmptyScenesFilesAreRefused) {
  const std::string empty = Write("empty.jsonl", "\n\n");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"export", empty, "-o", (dir_ / "x.xml").string()},
        std::vector<std::string>{"view", empty, "--html", (dir_ / "v.html").string()}}) {
    const Result r = Run(args);
    EXPECT_EQ(r.exit_code, 1) << args[0];
    EXPECT_NE(r.err.find("empty.jsonl has no scenes"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir_ / "x.xml"));
  EXPECT_FALSE(fs::exists(dir_ / "v.html"));
}

TEST_F(RoughEdgesTest, ViewReadsAScenesFile) {
  const std::string scenes = (dir_ / "s.jsonl").string();
  ASSERT_EQ(Run({"sample", Example("table_cube.prs"), "-n", "3", "-o", scenes}).exit_code, 0);
  const std::string page = (dir_ / "v.html").string();
  const Result r = Run({"view", scenes, "--html", page});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(page);
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The three scenes' lines are embedded, escaped as JSON strings.
  EXPECT_NE(html.find("\\\"index\\\":2"), std::string::npos);
  const std::string broken = Write("broken.jsonl", "{\"format\":\"prs-scene/1\"}\n");
  const Result bad = Run({"view", broken, "--html", page});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("broken.jsonl:1:"), std::string::npos) << bad.err;
}

TEST_F(RoughEdgesTest, EmptyOutputPathIsAUsageError) {
  for (const char* command : {"sample", "export", "render"}) {
    const Result r = Run({command, Example("table_cube.prs"), "-o", ""});
    EXPECT_EQ(r.exit_code, 2) << command;
    EXPECT_NE(r.err.find("expects a path, got an empty one"), std::string::npos) << r.err;
  }
}

TEST_F(RoughEdgesTest, NonFiniteParamIsAnError) {
  const std::string file = Write("p.prs", "param x = 1\n");
  for (const char* value : {"inf", "-inf", "nan", "1e999"}) {
    const Result r = Run({"sample", file, "-p", std::string("x=") + value});
    EXPECT_EQ(r.exit_code, 1) << value;
    EXPECT_NE(r.err.find("a param must be a finite number"), std::string::npos) << r.err;
  }
  EXPECT_EQ(Run({"sample", file, "-p", "x=infinite"}).exit_code, 0);  // a string
}

TEST_F(RoughEdgesTest, NoEmptyPartialFileIsLeftBehind) {
  const std::string file = Write("fails.prs", "require False\n");
  const fs::path out = dir_ / "out.jsonl";
  const Result r = Run({"sample", file, "-o", out.string()});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(out.string() + ".partial"));
}

TEST_F(RoughEdgesTest, DevicesDirectoriesAndByteOrderMarks) {
  const Result null_device = Run({"check", "/dev/null", "-n", "1"});
  EXPECT_EQ(null_device.exit_code, 0) << null_device.err;  // an empty program
  const Result directory = Run({"check", dir_.string()});
  EXPECT_EQ(directory.exit_code, 1);
  EXPECT_NE(directory.err.find("it is a directory"), std::string::npos) << directory.err;
  const Result missing = Run({"check", (dir_ / "nope.prs").string()});
  EXPECT_NE(missing.err.find("no such file"), std::string::npos) << missing.err;
  const std::string bom = Write("bom.prs", "\xEF\xBB\xBFx = 1 +\n");
  const Result r = Run({"check", bom});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bom.prs:1:8:"), std::string::npos) << r.err;  // columns without the mark
}

TEST_F(RoughEdgesTest, StringEscapes) {
  const std::string file = Write("s.prs", "param a = '\\x41\\u00e9'\nparam b = 'C:\\dir'\n");
  const Result r = Run({"sample", file});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"a\":\"A\xC3\xA9\""), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("s.prs:2:14: warning: unknown escape sequence '\\d'"), std::string::npos)
      << r.err;
  const Result bad = Run({"check", Write("x.prs", "a = '\\x4'\n")});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("x.prs:1:6: error: '\\x' needs 2 hexadecimal digits"), std::string::npos)
      << bad.err;
}

TEST_F(RoughEdgesTest, ExportSummaryNamesTheDirectoryOnce) {
  const Result r = Run({"export", Example("table_cube.prs"), "-n", "2", "--format", "sdf", "-o",
                        (dir_ / "worlds").string() + "/"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("worlds//"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("worlds/ (table_cube_s0_i0.sdf"), std::string::npos) << r.err;
}

// Scene JSON and controller answers nested 100,000 levels deep: refused or ignored, never a
// stack overflow in the readers or in the writers that dump what they read.
TEST_F(RoughEdgesTest, DeeplyNestedJsonIsRefusedNotACrash) {
  const Result one = Run({"sample", Example("table_cube.prs"), "-n", "1"});
  ASSERT_EQ(one.exit_code, 0);
  std::string line = one.out.substr(0, one.out.find('\n'));
  const std::string deep = std::string(100'000, '[') + std::string(100'000, ']');
  const size_t at = line.find("\"color\":\"0.5\"");
  ASSERT_NE(at, std::string::npos);
  line.insert(at, "\"deep\":" + deep + ",");
  const std::string file = Write("deep.jsonl", line + "\n");
  const Result exported = Run({"export", file, "-o", (dir_ / "d.xml").string()});
  EXPECT_EQ(exported.exit_code, 1);
  EXPECT_NE(exported.err.find("property \"deep\" is nested more than 1000 levels deep"),
            std::string::npos)
      << exported.err.substr(0, 500);
  EXPECT_EQ(Run({"view", file, "--html", (dir_ / "d.html").string()}).exit_code, 1);
  std::string color_line = one.out.substr(0, one.out.find('\n'));
  color_line.replace(color_line.find("\"0.5\""), 5, deep);
  const Result rendered =
      Run({"render", Write("color.jsonl", color_line + "\n"), "-o", (dir_ / "c.png").string()});
  EXPECT_EQ(rendered.exit_code, 0) << rendered.err.substr(0, 500);  // drawn in the default colour
  // A format or class of the wrong type: a located message, not the JSON library's.
  const std::string odd = Write("odd.jsonl", "{\"format\":[[1]],\"objects\":[]}\n");
  for (const std::string command : {"render", "export"}) {
    const Result r =
        Run({command, odd, "-o", (dir_ / (command == "render" ? "o.png" : "o.xml")).string()});
    EXPECT_EQ(r.exit_code, 1) << command;
    EXPECT_EQ(r.err.find("json.exception"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("odd.jsonl:1:"), std::string::npos) << r.err;
  }
  // A controller whose answer nests 10,000 levels (within the 64 KiB of output kept): a bad
  // answer, recorded.
  const std::string controller =
      "/usr/bin/python3 -c 'print(\"{\\\"outcome\\\": \\\"success\\\", \\\"x\\\": \" + "
      "\"[\" * 10000 + \"]\" * 10000 + \"}\")'";
  const Result tested = Run({"test", Example("table_cube.prs"), "--exec", controller, "-n", "1",
                             "-o", (dir_ / "r.jsonl").string()});
  EXPECT_EQ(tested.exit_code, 0) << tested.err.substr(0, 500);
  std::ifstream in(dir_ / "r.jsonl");
  const std::string record((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(record.find("\"outcome\":\"bad-answer\""), std::string::npos) << record.substr(0, 500);
  EXPECT_NE(record.find("nests JSON more than 64 levels deep"), std::string::npos);
}

}  // namespace
}  // namespace prs::cli
