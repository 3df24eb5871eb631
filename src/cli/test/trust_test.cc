// Issue 42's numbers a user must be able to trust, end to end: records that say which program
// and scene options made them, `prs compare` refusing runs of different programs or a replay of
// failures, replays that keep their records' law (an estimate's weights), `estimate --from` and
// `report` refusing to call non-i.i.d. records i.i.d., intervals right at the edges (few
// failures, everything failing, a kind seen only while adapting), and the usage errors of
// options that would be ignored.
#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "cli/test/json_lines.h"
#include "cli/test/prs_test_fixture.h"

namespace prs::cli {
namespace {

using nlohmann::json;

class TrustTest : public PrsTest {
 protected:
  // The cube.prs: a 5 cm cube completely on the table of examples/model.prs.
  std::string WriteCube() {
    return Write("cube.prs",
                 "from model import *\nt = Table on V3D(0, 0, 0)\nc = Cube completely on t\n");
  }
  std::string Out(const std::string& name) { return (dir_ / name).string(); }
  std::string Examples() { return (RepoRoot() / "examples").string(); }

  // `n` i.i.d. records of one program, the first `failing` failing with `outcome`.
  std::string WriteIidRecords(const std::string& name, int n, int failing,
                              const std::string& outcome = "no-path") {
    std::string text;
    for (int i = 0; i < n; ++i) {
      text += fmt::format(
          "{{\"seed\":1,\"index\":{},\"outcome\":\"{}\",\"spec\":\"00000000000000aa\","
          "\"scene_options\":\"\",\"features\":{{\"c.x\":{},\"c.y\":{}}}}}\n",
          i, i < failing ? outcome : "success", 0.001 * i, 0.002 * (i % 7));
    }
    return Write(name, text);
  }
};

// P(X >= k) for X ~ Binomial(n, p), summed here (independent of the code under test).
double BinomialAtLeast(int k, int n, double p) {
  double sum = 0;
  for (int i = k; i <= n; ++i) {
    sum += std::exp(std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0) +
                    i * std::log(p) + (n - i) * std::log1p(-p));
  }
  return sum;
}

TEST_F(TrustTest, RecordsNameTheirProgramAndSceneOptions) {
  const std::string cube = WriteCube(), out = Out("r.jsonl");
  ASSERT_EQ(Run({"test", cube, "-I", Examples(), "--exec", "true", "-n", "3", "-s", "1",
                 "--stable=0.5", "-o", out})
                .exit_code,
            0);
  for (const json& r : ReadRecords(out)) {
    EXPECT_EQ(r["spec"].get<std::string>().size(), 16u) << r;
    EXPECT_EQ(r["scene_options"], "--stable=0.5") << r;
  }
}

TEST_F(TrustTest, CompareRefusesRunsOfDifferentPrograms) {
  // The reproduction: cube.prs with an --exec controller against table_cube.prs with
  // demo-reach, same seed and count, was "300 scenes, the same in both runs".
  const std::string cube = WriteCube(), a = Out("cube.jsonl"), b = Out("table.jsonl");
  ASSERT_EQ(
      Run({"test", cube, "-I", Examples(), "--exec", "true", "-n", "300", "-s", "1", "-o", a, "-q"})
          .exit_code,
      0);
  ASSERT_EQ(Run({"test", Example("table_cube.prs"), "--controller", "demo-reach", "-n", "300", "-s",
                 "1", "-o", b, "-q"})
                .exit_code,
            0);
  const Result r = Run({"compare", a, b});
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("the runs are not of the same scenes"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(a + " has the program fingerprint"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(b + " has the program fingerprint"), std::string::npos) << r.err;
  // The same program with other scene options is refused too, naming both options.
  const std::string settled = Out("stable.jsonl");
  ASSERT_EQ(Run({"test", cube, "-I", Examples(), "--exec", "true", "-n", "5", "-s", "1",
                 "--stable=0.5", "-o", settled, "-q"})
                .exit_code,
            0);
  const std::string plain = Out("plain.jsonl");
  ASSERT_EQ(Run({"test", cube, "-I", Examples(), "--exec", "true", "-n", "5", "-s", "1", "-o",
                 plain, "-q"})
                .exit_code,
            0);
  const Result options = Run({"compare", plain, settled});
  EXPECT_EQ(options.exit_code, 1);
  EXPECT_NE(options.err.find("scene options '--stable=0.5'"), std::string::npos) << options.err;
  EXPECT_NE(options.err.find("scene options ''"), std::string::npos) << options.err;
}

TEST_F(TrustTest, CompareRefusesAReplayOfFailuresAndSaysWhatToDo) {
  const std::string full = Out("full.jsonl"), failed = Out("failed.jsonl"), all = Out("all.jsonl");
  ASSERT_EQ(Run({"test", Example("table_cube.prs"), "--controller", "planted-1-percent", "-n",
                 "300", "-s", "1", "-o", full, "-q"})
                .exit_code,
            0);
  ASSERT_EQ(Run({"test", Example("table_cube.prs"), "--controller", "demo-reach", "--replay", full,
                 "--failed", "-o", failed, "-q"})
                .exit_code,
            0);
  Result r = Run({"compare", full, failed});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("replays only the failures of " + full), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Replay every scene"), std::string::npos) << r.err;
  // The documented way: replay every scene, then compare.
  ASSERT_EQ(Run({"test", Example("table_cube.prs"), "--controller", "demo-reach", "--replay", full,
                 "-o", all, "-q"})
                .exit_code,
            0);
  r = Run({"compare", full, all});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("300 scenes, the same in both runs"), std::string::npos) << r.out;
}

TEST_F(TrustTest, AReplayKeepsTheEstimatesLaw) {
  // A replay of an estimate's records with the same controller gives the same estimate (it was
  // 6.60 % against 1.40 % when the replay dropped the weights and read as i.i.d.).
  const std::string est = Out("est.jsonl"), replay = Out("replay.jsonl");
  ASSERT_EQ(Run({"estimate", Example("table_cube.prs"), "--controller", "planted-1-percent",
                 "--budget", "600", "-s", "3", "-o", est, "-q"})
                .exit_code,
            0);
  ASSERT_EQ(Run({"test", Example("table_cube.prs"), "--controller", "planted-1-percent", "--replay",
                 est, "-o", replay, "-q"})
                .exit_code,
            0);
  const Result original = Run({"estimate", "--from", est, "--json"});
  const Result replayed = Run({"estimate", "--from", replay, "--json"});
  ASSERT_EQ(original.exit_code, 0) << original.err;
  ASSERT_EQ(replayed.exit_code, 0) << replayed.err;
  EXPECT_EQ(json::parse(replayed.out), json::parse(original.out));
  const std::vector<json> lines = ReadRecords(replay);
  EXPECT_EQ(lines.back()["search"]["strategy"], "importance");
  EXPECT_EQ(lines.back()["replay"]["of"], est);
  EXPECT_EQ(lines.back()["replay"]["failed_only"], false);

  // A replay of the failures alone is chosen by outcome: no estimate, and the report says so.
  const std::string failures = Out("failures.jsonl");
  ASSERT_EQ(Run({"test", Example("table_cube.prs"), "--controller", "planted-1-percent", "--replay",
                 est, "--failed", "-o", failures, "-q"})
                .exit_code,
            0);
  Result r = Run({"estimate", "--from", failures});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("a replay of failures alone"), std::string::npos) << r.err;
  r = Run({"report", failures, "-o", Out("f.md")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string md = ReadText(Out("f.md"));
  EXPECT_EQ(md.find("i.i.d."), std::string::npos) << md;
  EXPECT_NE(md.find("a replay of failures alone"), std::string::npos) << md;
}

TEST_F(TrustTest, AChainsRecordsAreNotCalledIid) {
  const std::string out = Out("gibbs.jsonl");
  ASSERT_EQ(Run({"test", Example("table_cube.prs"), "--controller", "planted-1-percent", "-n",
                 "400", "-s", "1", "--sampler", "gibbs", "-o", out, "-q"})
                .exit_code,
            0);
  Result r = Run({"estimate", "--from", out});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("Markov chains"), std::string::npos) << r.err;
  // A replay makes each scene again at its point, without the chain, and keeps the records'
  // law; --sampler there is a usage error.
  const std::string again = Out("again.jsonl");
  r = Run({"test", Example("table_cube.prs"), "--controller", "planted-1-percent", "--replay",
           out, "-o", again, "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(ReadRecords(again).front()["scene_options"], "--sampler gibbs");
  EXPECT_EQ(Run({"estimate", "--from", again}).exit_code, 1);
  r = Run({"test", Example("table_cube.prs"), "--controller", "planted-1-percent", "--replay",
           out, "--sampler", "gibbs"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--sampler gibbs cannot be used with --replay"), std::string::npos)
      << r.err;
  r = Run({"report", out, "-o", Out("g.md")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string md = ReadText(Out("g.md"));
  EXPECT_EQ(md.find("(i.i.d.)"), std::string::npos) << md;
  EXPECT_NE(md.find("Markov chains"), std::string::npos) << md;
  EXPECT_NE(md.find("worth about"), std::string::npos) << md;
}

TEST_F(TrustTest, FewFailuresGetAnExactIntervalInEveryCommand) {
  // 2 failures in 500 i.i.d. records: estimate --from said 0.00–0.953 %, report 0.1–1.4 %.
  const std::string records = WriteIidRecords("two.jsonl", 500, 2);
  Result r = Run({"estimate", "--from", records, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json ci = json::parse(r.out)["estimates"]["no-path"]["ci95"];
  const double low = ci[0].get<double>(), high = ci[1].get<double>();
  // Each bound leaves 2.5 % in its tail (Clopper–Pearson), by a binomial sum written here.
  EXPECT_NEAR(BinomialAtLeast(2, 500, low), 0.025, 1e-6);
  EXPECT_NEAR(1 - BinomialAtLeast(3, 500, high), 0.025, 1e-6);
  r = Run({"estimate", "--from", records});
  EXPECT_NE(r.err.find("500 i.i.d. episodes"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("weighted"), std::string::npos) << r.err;
  // prs report gives the same interval for the same records.
  r = Run({"report", records, "-o", Out("two.md")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string md = ReadText(Out("two.md"));
  EXPECT_NE(md.find(fmt::format("| no-path | 2 | 0.4 % | {:#.3g} % – {:#.3g} % |", 100 * low,
                                100 * high)),
            std::string::npos)
      << md;
  EXPECT_EQ(md.find("failed (0.4 %, 95 % CI"), std::string::npos) << "no second interval";
}

TEST_F(TrustTest, EverythingFailingIsNotOneHundredToOneHundred) {
  const std::string records = WriteIidRecords("all.jsonl", 200, 200);
  const Result r = Run({"estimate", "--from", records});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("100.0 % - 100.0 %"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("100. % - 100. %"), std::string::npos) << r.out;
  // The lower bound of 200 of 200: 0.025^(1/200).
  EXPECT_NE(r.out.find(fmt::format("{:#.3g} %", 100 * std::pow(0.025, 1.0 / 200))),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find(" 0\n"), std::string::npos) << "no '0 i.i.d. episodes' column: " << r.out;
}

TEST_F(TrustTest, AKindSeenOnlyWhileAdaptingGetsABound) {
  // An estimate's file: a search's records (the adaptation) with "no-path", then weighted
  // records in which only "planted-failure" occurs.
  std::string text;
  for (int i = 0; i < 20; ++i) {
    text += fmt::format(
        "{{\"seed\":1,\"index\":{},\"outcome\":\"{}\",\"search\":{{\"strategy\":"
        "\"cross-entropy\"}}}}\n",
        i, i < 5 ? "no-path" : "success");
  }
  for (int i = 20; i < 420; ++i) {
    text += fmt::format(
        "{{\"seed\":1,\"index\":{},\"outcome\":\"{}\",\"search\":{{\"strategy\":\"importance\","
        "\"weight\":1,\"uniform_share\":1,\"normalised\":false}}}}\n",
        i, i % 40 == 0 ? "planted-failure" : "success");
  }
  const Result r = Run({"estimate", "--from", Write("e.jsonl", text), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json e = json::parse(r.out)["estimates"];
  ASSERT_TRUE(e.contains("no-path")) << r.out;
  EXPECT_EQ(e["no-path"]["failing_episodes"], 0);
  EXPECT_EQ(e["no-path"]["ci95"][0], 0);
  // No no-path in 400 draws of weight 1: below 1 - 0.05^(1/400) at 95 %.
  EXPECT_NEAR(e["no-path"]["ci95"][1].get<double>(), 1 - std::pow(0.05, 1.0 / 400), 1e-12);
}

TEST_F(TrustTest, FromRefusesTheOptionsItWouldIgnore) {
  const std::string records = WriteIidRecords("r.jsonl", 50, 1);
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--controller", "demo-reach"}, {"--budget", "500"}, {"-s", "3"}}) {
    std::vector<std::string> args = {"estimate", "--from", records};
    args.insert(args.end(), extra.begin(), extra.end());
    const Result r = Run(args);
    EXPECT_EQ(r.exit_code, 2) << extra[0];
    EXPECT_NE(r.err.find(extra[0] + ": --from makes the estimate from the records alone"),
              std::string::npos)
        << r.err;
  }
  // prs test records are checked against the program too.
  const std::string cube = WriteCube(), out = Out("cube.jsonl");
  ASSERT_EQ(Run({"test", cube, "-I", Examples(), "--exec", "true", "-n", "40", "-o", out, "-q"})
                .exit_code,
            0);
  const Result r = Run({"estimate", Example("table_cube.prs"), "--from", out});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("drawn from another program"), std::string::npos) << r.err;
}

TEST_F(TrustTest, SavedScenesRefuseWhatWouldBeIgnored) {
  const std::string scenes = Out("s.jsonl");
  ASSERT_EQ(Run({"sample", Example("table_cube.prs"), "-n", "300", "-o", scenes}).exit_code, 0);
  Result r = Run({"test", scenes, "--exec", "true", "-n", "5", "--start", "298"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("holds 300 scenes, so only 2 are left from --start 298; give -n 2"),
            std::string::npos)
      << r.err;
  r = Run({"test", scenes, "--exec", "true", "-s", "4", "-n", "2"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("carry their own seeds"), std::string::npos) << r.err;
  const std::string records = Out("r.jsonl");
  ASSERT_EQ(
      Run({"test", Example("table_cube.prs"), "--exec", "true", "-n", "3", "-o", records, "-q"})
          .exit_code,
      0);
  r = Run({"test", Example("table_cube.prs"), "--exec", "true", "--replay", records, "-s", "2"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--replay: the records carry their scenes' seeds; leave out -s"),
            std::string::npos)
      << r.err;
}

TEST_F(TrustTest, AWorkerThatCannotStartClaimsNoRecordFile) {
  const std::string out = Out("r.jsonl");
  const Result r = Run({"test", Example("table_cube.prs"), "--exec", "exit 3", "--persistent", "-n",
                        "4", "-o", out});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("no episode finished, so no record was written"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out + ".partial"));
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace prs::cli
