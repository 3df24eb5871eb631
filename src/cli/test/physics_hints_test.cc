// Issue 42, items 4 and 9, end to end: --stable and --settle refuse a time too short to find
// anything at rest (naming the least) and find a cube at rest within it; an object with a mass
// and allowCollisions: True is a located error under either, and a warning when exported;
// `require settled` without --settle warns once, at the statement; `--stable 0.5` suggests
// `--stable=0.5`.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli/test/prs_test_fixture.h"

namespace prs::cli {
namespace {

class PhysicsHintsTest : public PrsTest {
 protected:
  // The cube.prs: a 5 cm cube completely on the table of examples/model.prs, with
  // `extra` properties.
  std::string WriteCube(const std::string& extra = "") {
    return Write("cube.prs",
                 "from model import *\nt = Table on V3D(0, 0, 0)\n"
                 "c = Cube completely on t" +
                     extra + "\n");
  }
  // `prs COMMAND FILE ARGS... -I examples -s 1 --threads 1`.
  Result RunOn(const std::string& command, const std::string& file,
               std::vector<std::string> args = {}) {
    args.insert(args.begin(), {command, file});
    args.insert(args.end(),
                {"-I", (RepoRoot() / "examples").string(), "-s", "1", "--threads", "1"});
    return Run(args);
  }
};

size_t CountOccurrences(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// Item 4: `--settle=0.4` rejected a cube at rest ("still moving at 0.000 m/s after 0.40 s"):
// rest is judged over 0.5 s of settling (0.2 s for --stable), so a shorter time is a usage
// error that names the least.
TEST_F(PhysicsHintsTest, ATimeTooShortToFindRestIsAUsageErrorNamingTheLeast) {
  const std::string cube = WriteCube();
  for (const auto& [option, least] :
       std::vector<std::pair<std::string, std::string>>{{"--settle=0.4", "at least 0.5 s"},
                                                        {"--settle=0.1", "at least 0.5 s"},
                                                        {"--stable=0.1", "at least 0.2 s"},
                                                        {"--stable=0.19", "at least 0.2 s"}}) {
    const Result r = RunOn("sample", cube, {option});
    EXPECT_EQ(r.exit_code, 2) << option << ": " << r.err;
    EXPECT_NE(r.err.find("prs: error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(least), std::string::npos) << option << ": " << r.err;
    EXPECT_NE(r.err.find("docs/physics.md"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("0.000 m/s"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty());
  }
  // The same for every command that makes scenes.
  const Result stats = RunOn("stats", cube, {"-n", "1", "--settle=0.3"});
  EXPECT_EQ(stats.exit_code, 2) << stats.err;
  EXPECT_NE(stats.err.find("at least 0.5 s"), std::string::npos) << stats.err;
}

TEST_F(PhysicsHintsTest, TheLeastTimeFindsACubeAtRest) {
  const std::string cube = WriteCube();
  for (const std::string& option : {"--settle=0.5", "--stable=0.2", "--settle", "--stable"}) {
    const Result r = RunOn("sample", cube, {"-n", "3", option});
    EXPECT_EQ(r.exit_code, 0) << option << ": " << r.err;
    EXPECT_EQ(CountOccurrences(r.out, "\n"), 3u) << option;
    EXPECT_NE(r.err.find("3 scenes, 3 attempts, 0 rejections"), std::string::npos)
        << option << ": " << r.err;
  }
}

// Item 9: a cube with a mass and allowCollisions: True has no contacts and falls through the
// table; --stable said only "fell 1.1 cm" and --settle "still moving at 29.43 m/s". Now either
// is an error at the object (exit 1), which names allowCollisions and says what to change.
TEST_F(PhysicsHintsTest, AFreeBodyWithoutContactsIsALocatedError) {
  const std::string cube = WriteCube(", with allowCollisions True");
  for (const std::string& option : {"--stable", "--settle", "--stable=0.5", "--settle=2"}) {
    const Result r = RunOn("sample", cube, {option});
    EXPECT_EQ(r.exit_code, 1) << option << ": " << r.err;
    EXPECT_NE(r.err.find("cube.prs:3:5: error: c has a mass and allowCollisions: True"),
              std::string::npos)
        << option << ": " << r.err;
    const std::string flag = option.substr(0, option.find('='));
    EXPECT_NE(r.err.find(flag + " can accept no scene with it"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("give c allowCollisions: False"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("fell"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("still moving"), std::string::npos) << r.err;
  }
  // Without --stable or --settle the scene is drawn as before; its export warns.
  EXPECT_EQ(RunOn("sample", cube).exit_code, 0);
  const Result exported = RunOn("export", cube, {"-o", (dir_ / "cube.xml").string()});
  EXPECT_EQ(exported.exit_code, 0) << exported.err;
  EXPECT_NE(exported.err.find("prs: warning: object c (Cube): a mass and allowCollisions: True "
                              "make a free body without contacts"),
            std::string::npos)
      << exported.err;
  // Static (no mass), it may allow collisions under either.
  const std::string fixed = WriteCube(", with allowCollisions True, with mass 0");
  EXPECT_EQ(RunOn("sample", fixed, {"--stable"}).exit_code, 0);
  EXPECT_EQ(RunOn("sample", fixed, {"--settle"}).exit_code, 0);
}

// Item 9: `require settled` without --settle was ignored silently. Now the first scene that
// runs one warns, once however many scenes and statements, at the statement.
TEST_F(PhysicsHintsTest, RequireSettledWithoutSettleWarnsOnceAtTheStatement) {
  const std::string cube = Write("cube.prs",
                                 "from model import *\nt = Table on V3D(0, 0, 0)\n"
                                 "c = Cube completely on t\n"
                                 "for i in range(2):\n"
                                 "    require settled c.z > 0.5\n"
                                 "require settled c.z > 0.6\n");
  for (const std::string& command : {"sample", "stats"}) {
    const Result r = RunOn(command, cube, {"-n", "4"});
    EXPECT_EQ(r.exit_code, 0) << command << ": " << r.err;
    EXPECT_EQ(CountOccurrences(r.err, "prs: warning: "), 1u) << command << ": " << r.err;
    EXPECT_NE(r.err.find("prs: warning: " + cube +
                         ":5:5: `require settled` is checked only on settled scenes, so without "
                         "--settle it is ignored"),
              std::string::npos)
        << command << ": " << r.err;
  }
  const Result settled = RunOn("sample", cube, {"-n", "2", "--settle"});
  EXPECT_EQ(settled.exit_code, 0) << settled.err;
  EXPECT_EQ(settled.err.find("warning"), std::string::npos) << settled.err;
  // A program without one does not warn.
  EXPECT_EQ(RunOn("sample", WriteCube()).err.find("warning"), std::string::npos);
}

// Item 9: `--stable 0.5` said "argument was not expected: 0.5" (or took 0.5 for FILE). Both
// options take an optional value, which must follow '='.
TEST_F(PhysicsHintsTest, ASpacedValueSuggestsTheEqualsSign) {
  const std::string cube = WriteCube();
  const std::string examples = (RepoRoot() / "examples").string();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"sample", cube, "--stable", "0.5", "-I", examples},
        std::vector<std::string>{"sample", "--stable", "0.5", cube, "-I", examples},
        std::vector<std::string>{"stats", cube, "-I", examples, "--settle", "2"}}) {
    const Result r = Run(args);
    const std::string flag = args[0] == "stats" ? "--settle" : "--stable";
    const std::string value = args[0] == "stats" ? "2" : "0.5";
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("prs: error: " + flag + " takes its time after '=': write " + flag + "=" +
                         value),
              std::string::npos)
        << r.err;
    EXPECT_EQ(r.err.find("not expected"), std::string::npos) << r.err;
  }
  // A word that is not a number after it is FILE, as before.
  EXPECT_EQ(Run({"sample", "--stable", cube, "-I", examples}).exit_code, 0);
}

}  // namespace
}  // namespace prs::cli
