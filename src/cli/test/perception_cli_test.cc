// End-to-end tests of `prs test --controller table-cube --perception CMD`: a perception worker
// that finds the blue cube by its own pinhole math gives the built-in detector's outcomes, on 1
// and 2 threads alike; a worker that crashes, hangs, answers garbage, another scene, an error
// or a cube off the table costs that episode only (and is started afresh); one that cannot
// start stops the run; a campaign's shards keep the worker; the flag is refused where it cannot
// apply. (The request's camera fields
// against a dataset's labels: python/tests/test_learning.py.)
#include <nlohmann/json.hpp>

#include "cli/test/json_lines.h"
#include "cli/test/prs_test_fixture.h"

namespace prs::cli {
namespace {

using nlohmann::json;

// A perception worker in Python (the standard library, and Pillow for `blob`): `worker.py MODE
// [INDEX]` misbehaves in MODE on the scene INDEX and says "found": false on the others.
constexpr const char* kWorker = R"PY(
import json, os, sys, time
mode = sys.argv[1]
at = int(sys.argv[2]) if len(sys.argv) > 2 else -1
if mode == "no-handshake":
    print("cannot load the model: weights.pt is missing", file=sys.stderr)
    sys.exit(1)
print(json.dumps({"ready": True}), flush=True)

def blob(request):
    from PIL import Image
    rgb = Image.open(request["rgb"]).convert("RGB")
    depth = Image.open(request["depth"])
    w, h = rgb.size
    pixels, depths = rgb.load(), depth.load()
    us, vs, zs = [], [], []
    for v in range(h):
        for u in range(w):
            r, g, b = pixels[u, v]
            if b > 60 and b > 2 * r and b > 2 * g:
                us.append(u); vs.append(v); zs.append(depths[u, v] * request["depth_scale"] / 1000)
    if len(us) < 12:
        return {"found": False, "detail": "no blue pixels"}
    zs.sort()
    z = zs[len(zs) // 2]
    K = request["cam_K"]
    u, v = sum(us) / len(us), sum(vs) / len(vs)
    p_C = [(u - K[2]) * z / K[0], (v - K[5]) * z / K[4], z]
    t = [x / 1000 for x in request["cam_t_w2c"]]
    R = request["cam_R_w2c"]
    # p_W = R^T (p_C - t), then from the top face down to the centre
    d = [p_C[i] - t[i] for i in range(3)]
    p_W = [sum(R[3 * i + j] * d[i] for i in range(3)) for j in range(3)]
    p_W[2] -= 0.025
    return {"p_WCube_m": p_W}

for line in sys.stdin:
    request = json.loads(line)
    ids = {k: request[k] for k in ("seed", "index", "sighting")}
    mine = request["index"] == at
    if mode == "blob":
        answer = blob(request)
    elif mine and mode == "crash":
        sys.exit(3)
    elif mine and mode == "hang":
        time.sleep(60)
    elif mine and mode == "garbage":
        print("{the cube is somewhere", flush=True)
        continue
    elif mine and mode == "other-scene":
        ids["index"] += 1
        answer = {"p_WCube_m": [0, 0, 1]}
    elif mine and mode == "error":
        answer = {"error": "RuntimeError: the model's input has the wrong size"}
    elif mine and mode == "off-table":
        answer = {"p_WCube_m": [3.0, 0.5, 0.9]}
    elif mine and mode == "nan":
        print('{"seed": %d, "index": %d, "sighting": 0, "p_WCube_m": [NaN, 0, 1]}'
              % (request["seed"], request["index"]), flush=True)
        continue
    else:
        answer = {"found": False, "detail": "test worker: no cube here"}
    print(json.dumps({**answer, **ids}), flush=True)
)PY";

class PerceptionTest : public PrsTest {
 protected:
  void SetUp() override {
    PrsTest::SetUp();
    worker_ = Write("worker.py", kWorker);
  }
  std::string Worker(const std::string& mode, int at = -1) const {
    std::string command = "/usr/bin/python3 " + Quote(worker_) + " " + mode;
    if (at >= 0) command.append(" ").append(std::to_string(at));
    return command;
  }
  // prs test on the scenes where the camera sees the cube and the arms reach it.
  Result Test(const std::string& perception, std::vector<std::string> more) {
    std::vector<std::string> args = {"test",         Example("table_cube_reachable_visible.prs"),
                                     "--controller", "table-cube-clear-view",
                                     "--perception", perception,
                                     "-s",           "1"};
    args.insert(args.end(), more.begin(), more.end());
    return Run(args);
  }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string worker_;
};

std::vector<json> WithoutTimes(std::vector<json> records) {
  for (json& record : records) record.erase("wall_s");
  return records;
}

TEST_F(PerceptionTest, AWorkerThatFindsTheCubeItselfGivesTheBuiltInDetectorsOutcomes) {
  const Result built_in =
      Run({"test", Example("table_cube_reachable_visible.prs"), "--controller",
           "table-cube-clear-view", "-s", "1", "-n", "4", "-o", Path("built_in.jsonl")});
  ASSERT_EQ(built_in.exit_code, 0) << built_in.err;
  std::vector<json> runs[2];
  for (const int threads : {1, 2}) {
    const std::string out = Path("learned" + std::to_string(threads) + ".jsonl");
    const Result r =
        Test(Worker("blob"), {"-n", "4", "--threads", std::to_string(threads), "-o", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    runs[threads - 1] = WithoutTimes(ReadRecords(out));
  }
  EXPECT_EQ(runs[0], runs[1]);
  const std::vector<json> expected = ReadRecords(Path("built_in.jsonl"));
  ASSERT_EQ(runs[0].size(), expected.size());
  int successes = 0;
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(runs[0][i]["outcome"], expected[i]["outcome"]) << runs[0][i].dump();
    successes += expected[i]["outcome"] == "success";
    // The worker's own back-projection lands within a few millimetres of the cube.
    EXPECT_LT(runs[0][i]["extra"]["sighting_error_start_m"].get<double>(), 0.005) << i;
  }
  EXPECT_GE(successes, 2);
}

TEST_F(PerceptionTest, EachMisbehaviourCostsItsEpisodeOnlyAndTheWorkerStartsAfresh) {
  struct Case {
    std::string mode, outcome, detail;
  };
  const std::vector<Case> cases = {
      {"crash", "controller-error", "exited with code 3 while answering a sighting"},
      {"hang", "controller-error", "did not answer within 2 s and was killed"},
      {"garbage", "controller-error", "answered a line that is not JSON: {the cube is somewhere"},
      {"other-scene", "controller-error", "to the request of seed 1, index 1, sighting 0"},
      {"nan", "controller-error", "answered a line that is not JSON"},
      {"error", "controller-error", "failed: RuntimeError: the model's input has the wrong size"},
      {"off-table", "perception-fault", "off the table's top (outside its footprint)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.mode);
    const std::string out = Path(c.mode + ".jsonl");
    const Result r =
        Test(Worker(c.mode, 1), {"-n", "3", "--threads", "1", "--timeout", "2", "-o", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<json> records = ReadRecords(out);
    ASSERT_EQ(records.size(), 3u);
    for (int i : {0, 2}) {  // before and after: the worker's own "found": false
      EXPECT_EQ(records[i]["outcome"], "perception-fault") << records[i].dump();
      EXPECT_NE(records[i]["detail"].get<std::string>().find("test worker: no cube here"),
                std::string::npos)
          << records[i].dump();
    }
    EXPECT_EQ(records[1]["outcome"], c.outcome) << records[1].dump();
    const std::string detail = records[1]["detail"];
    EXPECT_NE(detail.find(c.detail), std::string::npos) << detail;
    if (c.outcome == "controller-error" && c.mode != "error") {
      EXPECT_NE(detail.find("the perception worker '"), std::string::npos) << detail;
    }
  }
}

TEST_F(PerceptionTest, AWorkerThatCannotStartStopsTheRunWithItsLastErrorLine) {
  const Result r = Test(Worker("no-handshake"), {"-n", "2", "-o", Path("r.jsonl")});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("the perception worker '"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cannot load the model: weights.pt is missing"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\"p_WCube_m\""), std::string::npos) << r.err;  // what a worker must do
}

TEST_F(PerceptionTest, ACampaignKeepsItsPerceptionWorkerForEveryShard) {
  const std::string dir = Path("camp");
  Result r = Run({"campaign", "init", dir, Example("table_cube_reachable_visible.prs"),
                  "--controller", "table-cube", "--perception", Worker("other-scene", 2), "-n",
                  "4", "--shard-size", "2", "-s", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string shard : {"0", "1"}) {
    r = Run({"campaign", "run-shard", dir, shard, "--threads", "1"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  r = Run({"campaign", "merge", dir, "-o", Path("merged.jsonl")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<json> records = ReadRecords(Path("merged.jsonl"));
  ASSERT_EQ(records.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(records[i]["outcome"], i == 2 ? "controller-error" : "perception-fault")
        << records[i].dump();
  }
}

TEST_F(PerceptionTest, TheFlagIsRefusedWhereNoPerceptionIsAsked) {
  Result r = Run({"test", Example("table_cube.prs"), "--controller", "table-cube-paper",
                  "--perception", Worker("blob"), "-n", "1"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--perception: only --controller table-cube and table-cube-clear-view "
                       "take a perception worker, not 'table-cube-paper'"),
            std::string::npos)
      << r.err;
  r = Run({"test", Example("table_cube.prs"), "--exec", "true", "--perception", Worker("blob"),
           "-n", "1"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--exec excludes --perception"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace prs::cli
