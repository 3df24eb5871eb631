// Messages a user can trust (issue 42, items 10 and 11), end to end: a controller's signal under
// /bin/sh, the counts of Gibbs and partial rejection named for what they are, --sampler gibbs
// refused as a usage error where scenes are drawn at given points, a random object count located,
// too-dense clutter as a sampling failure, an arm that reaches nothing, a URDF whose joints make
// a loop, and a mesh with a vertex that is not a number. Fixtures are written per test.
#include <nlohmann/json.hpp>

#include <cstdio>

#include "cli/test/json_lines.h"
#include "cli/test/prs_test_fixture.h"

namespace prs::cli {
namespace {

using nlohmann::json;

std::string Include() { return (RepoRoot() / "examples").string(); }

// Five 5 cm cubes at any yaw on a 0.5 x 0.4 m bin.
constexpr const char* kBin =
    "from model import *\n"
    "bin = Table on V3D(0, 0, 0), with width 0.5, with length 0.4\n"
    "for i in range(5):\n"
    "    Cube completely on bin, with yaw Range(0, 2 * math.pi)\n";

// A URDF <joint> from `parent` to `child`.
std::string Joint(const std::string& name, const std::string& parent, const std::string& child) {
  return "  <joint name=\"" + name + "\" type=\"revolute\"><parent link=\"" + parent +
         "\"/><child link=\"" + child +
         "\"/><origin xyz=\"0 0 0.2\"/><axis xyz=\"0 1 0\"/>"
         "<limit lower=\"-1.5\" upper=\"1.5\" effort=\"1\" velocity=\"1\"/></joint>\n";
}

TEST_F(PrsTest, AControllerThatSegfaultsUnderTheShellIsSignal11) {
  const std::string records = (dir_ / "r.jsonl").string();
  // The shell runs the command as a child and reports its death by SIGSEGV as exit status 139.
  const Result r = Run({"test", Example("table_cube.prs"), "-n", "2", "-s", "1", "--exec",
                        "sh -c 'ulimit -c 0; kill -SEGV $$'; exit $?", "-o", records});
  ASSERT_NE(r.exit_code, 2) << r.err;
  const std::vector<json> lines = ReadRecords(records);
  ASSERT_EQ(lines.size(), 2u) << r.err;
  for (const json& record : lines) {
    EXPECT_EQ(record["outcome"], "signal-11") << record;
    EXPECT_NE(record["detail"].get<std::string>().find("/bin/sh reported exit status 139"),
              std::string::npos)
        << record;
  }
}

TEST_F(PrsTest, GibbsAndPartialRejectionCountProgramRunsNotAttempts) {
  const std::string file = Write("bin.prs", kBin);
  const Result gibbs =
      Run({"sample", file, "-I", Include(), "--sampler", "gibbs", "-n", "20", "-s", "1"});
  ASSERT_EQ(gibbs.exit_code, 0) << gibbs.err;
  EXPECT_NE(gibbs.err.find("prs: 20 scenes, "), std::string::npos) << gibbs.err;
  EXPECT_NE(gibbs.err.find(" program runs (Gibbs moves, each redrawing one object), "),
            std::string::npos)
      << gibbs.err;
  EXPECT_EQ(gibbs.err.find("attempts"), std::string::npos) << gibbs.err;

  const Result partial = Run(
      {"sample", file, "-I", Include(), "--sampler", "partial-rejection", "-n", "20", "-s", "1"});
  ASSERT_EQ(partial.exit_code, 0) << partial.err;
  EXPECT_NE(partial.err.find(" program runs (one-object probes of hard-core draws, and whole "
                             "scenes), 0 whole scenes rejected"),
            std::string::npos)
      << partial.err;
  EXPECT_EQ(partial.err.find("attempts"), std::string::npos) << partial.err;

  // The default sampler keeps attempts = scenes + rejections.
  const Result plain = Run({"sample", file, "-I", Include(), "-n", "20", "-s", "1"});
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  int attempts = 0, rejections = 0;
  ASSERT_EQ(std::sscanf(plain.err.c_str(), "prs: 20 scenes, %d attempts, %d rejections",
                        &attempts, &rejections),
            2)
      << plain.err;
  EXPECT_EQ(attempts, 20 + rejections);

  // The JSON summary of prs stats: program runs in place of attempts and an acceptance rate.
  for (const char* sampler : {"gibbs", "partial-rejection"}) {
    const Result stats = Run({"stats", file, "-I", Include(), "--sampler", sampler, "-n", "20",
                              "-s", "1", "--json"});
    ASSERT_EQ(stats.exit_code, 0) << stats.err;
    const json report = json::parse(stats.out);
    EXPECT_FALSE(report.contains("attempts")) << sampler;
    EXPECT_FALSE(report.contains("acceptance_rate")) << sampler;
    EXPECT_FALSE(report.contains("attempts_per_scene")) << sampler;
    EXPECT_GT(report["program_runs"].get<int64_t>(), 20) << sampler;
    EXPECT_GT(report["program_runs_per_scene"]["mean"].get<double>(), 1) << sampler;
  }
  const json plain_stats =
      json::parse(Run({"stats", file, "-I", Include(), "-n", "20", "--json"}).out);
  EXPECT_EQ(plain_stats["attempts"].get<int64_t>(),
            20 + plain_stats["rejections"]["total"].get<int64_t>());
  EXPECT_FALSE(plain_stats.contains("program_runs"));
}

TEST_F(PrsTest, SamplersThatChooseTheirOwnPointsAreAUsageErrorWithCommandsThatChooseThem) {
  const std::string file = Write("bin.prs", kBin);
  const auto expect_usage_error = [&](const std::vector<std::string>& args,
                                      const std::string& start) {
    const Result r = Run(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.rfind(start, 0), 0u) << r.err;
    EXPECT_NE(r.err.find("leave out"), std::string::npos) << "says what to use instead: " << r.err;
    EXPECT_EQ(r.err.find("bin.prs:1:1"), std::string::npos) << "not located: " << r.err;
  };
  expect_usage_error({"estimate", file, "-I", Include(), "--controller", "planted-1-permille",
                      "--budget", "200", "--sampler", "gibbs"},
                     "prs: error: --sampler gibbs cannot be used with prs estimate: ");
  expect_usage_error({"search", file, "-I", Include(), "--controller", "planted-1-permille",
                      "--budget", "200", "--sampler", "gibbs"},
                     "prs: error: --sampler gibbs cannot be used with prs search: ");
  expect_usage_error({"sample", file, "-I", Include(), "--sampler", "gibbs", "--design", "sobol",
                      "-n", "4"},
                     "prs: error: --sampler gibbs cannot be used with --design sobol: ");
  expect_usage_error({"test", file, "-I", Include(), "--sampler", "gibbs", "--design", "halton",
                      "-n", "4", "--exec", "true"},
                     "prs: error: --sampler gibbs cannot be used with --design halton: ");
  expect_usage_error({"sample", file, "-I", Include(), "--sampler", "partial-rejection", "--like",
                      (dir_ / "none.jsonl").string()},
                     "prs: error: --sampler partial-rejection cannot be used with --like: ");
  expect_usage_error({"estimate", file, "-I", Include(), "--controller", "planted-1-permille",
                      "--budget", "200", "--sampler", "partial-rejection"},
                     "prs: error: --sampler partial-rejection cannot be used with prs estimate: ");
}

TEST_F(PrsTest, GibbsRefusalOfARandomObjectCountPointsAtTheCount) {
  const std::string file = Write("varying.prs",
                                 "from model import *\n"
                                 "bin = Table on V3D(0, 0, 0)\n"
                                 "for i in range(DiscreteRange(1, 6)):\n"
                                 "    Cube completely on bin\n");
  const Result r = Run({"sample", file, "-I", Include(), "--sampler", "gibbs", "-n", "3"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err.rfind(file + ":3:16: error: --sampler gibbs cannot sample this program", 0), 0u)
      << r.err;
  EXPECT_NE(r.err.find("when DiscreteRange at varying.prs:3:16 was redrawn: it decides how "
                       "many objects"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("^~~~~~~~~~~~~~~~~~~"), std::string::npos) << "the count's range: " << r.err;
}

TEST_F(PrsTest, ClutterTooDenseForPartialRejectionIsASamplingFailure) {
  // Twenty 5 cm cubes on a 0.2 x 0.2 m bin always overlap: every round redraws, and a draw
  // passes 10,000 rounds.
  const std::string file =
      Write("dense.prs",
            "from model import *\n"
            "bin = Table on V3D(0, 0, 0), with width 0.2, with length 0.2\n"
            "for i in range(20):\n"
            "    Cube completely on bin\n");
  const Result r =
      Run({"sample", file, "-I", Include(), "--sampler", "partial-rejection", "-n", "1"});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("too dense for partial rejection sampling"), std::string::npos) << r.err;
}

TEST_F(PrsTest, AnArmThatReachesNothingIsSaidBeforeAnyAttempt) {
  Write("one_joint.urdf", "<?xml version=\"1.0\"?>\n<robot name=\"one_joint\">\n"
                          "  <link name=\"base\"/><link name=\"tool\"/>\n" +
                              Joint("shoulder", "base", "tool") + "</robot>\n");
  const std::string file =
      Write("one_joint.prs",
            "from model import *\n"
            "t = Table on floor\n"
            "r = Robot on (top back t), with arm \"one_joint.urdf\"\n"
            "c = Cube on t, reachable by r\n");
  const Result r = Run({"sample", file, "-I", Include(), "-n", "1", "--max-attempts", "2000"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find(file + ":4:16: error: r's arm \"one_joint.urdf\" reaches nothing: its "
                              "reachable set ("),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("0 cells"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(file + ":3:5: note: r is created here, with arm \"one_joint.urdf\" (" +
                       (dir_ / "one_joint.urdf").string() + ")"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("with one movable joint the tool moves on a curve"), std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("no valid scene"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("empty-region"), std::string::npos) << r.err;
}

TEST_F(PrsTest, AUrdfWhoseJointsMakeALoopNamesTheLinkThatClosesIt) {
  Write("looped.urdf", "<?xml version=\"1.0\"?>\n<robot name=\"looped\">\n"
                       "  <link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>\n" +
                           Joint("j1", "a", "b") + Joint("j2", "b", "c") + Joint("j3", "c", "a") +
                           "</robot>\n");
  const std::string file = Write("looped.prs",
                                 "from model import *\n"
                                 "t = Table on floor\n"
                                 "r = Robot on (top back t), with arm \"looped.urdf\"\n"
                                 "c = Cube on t, reachable by r\n");
  const Result r = Run({"sample", file, "-I", Include()});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("the joints do not connect the links as a tree: joint 'j3' makes link 'a' "
                       "a child of link 'c', which is below it already, closing the loop 'a' -> "
                       "'b' -> 'c' -> 'a'"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("root link"), std::string::npos) << "urdfdom's words: " << r.err;
  EXPECT_EQ(r.err.find("valid tree"), std::string::npos) << "urdfdom's words: " << r.err;
}

TEST_F(PrsTest, AMeshVertexThatIsNotANumberIsNamed) {
  Write("bad.obj",
        "# a tetrahedron whose third vertex is not a number\n"
        "v 0 0 0\n"
        "v 0.1 0 0\n"
        "v nan 0.1 0\n"
        "v 0 0 0.1\n"
        "f 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n");
  const std::string file = Write("mesh.prs",
                                 "from model import *\n"
                                 "t = Table on floor\n"
                                 "m = Cube on t, with shape Mesh(\"bad.obj\")\n");
  const Result r = Run({"sample", file, "-I", Include()});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("has a vertex that is not a number: vertex 3 (counting from 1, as the "
                       "file's faces do), line 4: 'v nan 0.1 0'"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("zero area"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace prs::cli
