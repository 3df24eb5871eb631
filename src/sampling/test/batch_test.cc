// The batch sampler: the same scenes for any thread count and any split of the index range,
// totals that add up, the lowest failing index reported after the scenes before it, a bounded
// window of scenes in flight, and cancellation.
#include "sampling/batch.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "sampling/test/scene_checks.h"

namespace prs::sampling {
namespace {

using testing_checks::CompileOrDie;
using testing_checks::Fingerprint;
using testing_checks::RepoPath;

std::unique_ptr<lang::CompiledProgram> CompileTableCube() {
  lang::DiagnosticEngine diagnostics;
  lang::CompileOptions options;
  options.search_path = {RepoPath("examples")};
  auto program = lang::CompileFile(RepoPath("examples/table_cube.prs"), options, diagnostics);
  EXPECT_FALSE(diagnostics.has_errors());
  return program;
}

std::vector<std::string> SampleFingerprints(const lang::CompiledProgram& program, uint64_t start,
                                            int64_t count, int threads) {
  BatchOptions options;
  options.seed = 7;
  options.start = start;
  options.count = count;
  options.threads = threads;
  std::vector<std::string> fingerprints;
  SampleBatch(program, options, {.prepare = {}, .consume = [&](BatchScene&& scene) {
                                   fingerprints.push_back(Fingerprint(scene.sampled));
                                 }});
  return fingerprints;
}

// Collisions and a requirement: about half the attempts are rejected.
constexpr char kRejectingProgram[] =
    "from model import *\n"
    "t = Table on floor\n"
    "a = Cube on t\n"
    "b = Cube on t\n"
    "require a.position.x > 0\n";

TEST(BatchTest, SameScenesForAnyThreadCount) {
  auto table_cube = CompileTableCube();
  auto rejecting = CompileOrDie(kRejectingProgram);
  ASSERT_NE(table_cube, nullptr);
  ASSERT_NE(rejecting, nullptr);
  for (const lang::CompiledProgram* program : {table_cube.get(), rejecting.get()}) {
    const std::vector<std::string> one = SampleFingerprints(*program, 0, 40, 1);
    ASSERT_EQ(one.size(), 40u);
    EXPECT_EQ(SampleFingerprints(*program, 0, 40, 2), one);
    EXPECT_EQ(SampleFingerprints(*program, 0, 40, 4), one);
  }
}

TEST(BatchTest, SameScenesForAnySplitOfTheRange) {
  auto program = CompileTableCube();
  ASSERT_NE(program, nullptr);
  const std::vector<std::string> whole = SampleFingerprints(*program, 0, 10, 2);
  std::vector<std::string> split = SampleFingerprints(*program, 0, 4, 1);
  const std::vector<std::string> rest = SampleFingerprints(*program, 4, 6, 4);
  split.insert(split.end(), rest.begin(), rest.end());
  EXPECT_EQ(split, whole);
}

TEST(BatchTest, SummaryAddsUpOverTheScenes) {
  auto program = CompileOrDie(kRejectingProgram);
  ASSERT_NE(program, nullptr);
  BatchOptions options;
  options.seed = 3;
  options.count = 50;
  options.threads = 2;
  RejectionCounts summed;
  int64_t attempts = 0;
  const BatchSummary summary =
      SampleBatch(*program, options, {.prepare = {}, .consume = [&](BatchScene&& scene) {
                                        summed.Merge(scene.sampled.rejections);
                                        attempts += scene.sampled.attempts;
                                      }});
  EXPECT_EQ(summary.scenes, 50);
  EXPECT_GT(summary.rejections.total, 0);
  EXPECT_EQ(summary.attempts, attempts);
  EXPECT_EQ(summary.rejections.total, summed.total);
  EXPECT_EQ(summary.rejections.by_kind, summed.by_kind);
  EXPECT_EQ(summary.rejections.by_culprit, summed.by_culprit);
  EXPECT_EQ(summary.attempts, summary.scenes + summary.rejections.total);
  int64_t by_kind_total = 0;
  for (const auto& [kind, n] : summary.rejections.by_kind) by_kind_total += n;
  EXPECT_EQ(by_kind_total, summary.rejections.total);
}

// Scenes 7 and 12 fail in `prepare`; whatever the threads, 0..6 arrive and 7's error is thrown.
TEST(BatchTest, ReportsTheLowestFailingIndexAfterTheScenesBeforeIt) {
  auto program = CompileTableCube();
  ASSERT_NE(program, nullptr);
  for (int threads : {1, 2, 4}) {
    BatchOptions options;
    options.count = 30;
    options.threads = threads;
    std::vector<uint64_t> consumed;
    BatchCallbacks callbacks;
    callbacks.prepare = [](BatchScene& scene) {
      if (scene.sampled.index == 7 || scene.sampled.index == 12) {
        throw std::runtime_error("scene " + std::to_string(scene.sampled.index));
      }
    };
    callbacks.consume = [&](BatchScene&& scene) { consumed.push_back(scene.sampled.index); };
    try {
      SampleBatch(*program, options, callbacks);
      ADD_FAILURE() << "no error with " << threads << " threads";
    } catch (const std::runtime_error& error) {
      EXPECT_STREQ(error.what(), "scene 7") << threads << " threads";
    }
    EXPECT_EQ(consumed, (std::vector<uint64_t>{0, 1, 2, 3, 4, 5, 6})) << threads << " threads";
  }
}

// Some scenes of this program fail within 2 attempts and others do not; the first failure and
// the scenes before it are the same for every thread count.
TEST(BatchTest, SamplingFailureIsTheSameForAnyThreadCount) {
  auto program = CompileOrDie("x = Range(0, 1)\nrequire x > 0.8\n");
  ASSERT_NE(program, nullptr);
  auto run = [&](int threads) {
    BatchOptions options;
    options.sample.max_attempts = 2;
    options.count = 100;
    options.threads = threads;
    int64_t consumed = 0;
    try {
      SampleBatch(*program, options, {.prepare = {}, .consume = [&](BatchScene&&) { ++consumed; }});
    } catch (const lang::ScenarioError& error) {
      EXPECT_EQ(error.diagnostic().id, "sampling-failed");
      return std::to_string(consumed) + " " + error.diagnostic().message;
    }
    return std::string("no failure");
  };
  const std::string serial = run(1);
  EXPECT_NE(serial, "no failure");
  EXPECT_EQ(run(2), serial);
  EXPECT_EQ(run(4), serial);
}

TEST(BatchTest, KeepsAtMostTheWindowOfScenesInFlight) {
  auto program = CompileTableCube();
  ASSERT_NE(program, nullptr);
  BatchOptions options;
  options.count = 60;
  options.threads = 2;
  options.window_per_thread = 3;
  std::atomic<int64_t> prepared = 0, consumed = 0, worst_in_flight = 0;
  BatchCallbacks callbacks;
  callbacks.prepare = [&](BatchScene&) {
    const int64_t in_flight = ++prepared - consumed.load();
    int64_t worst = worst_in_flight.load();
    while (in_flight > worst && !worst_in_flight.compare_exchange_weak(worst, in_flight)) {
    }
  };
  callbacks.consume = [&](BatchScene&&) {
    std::this_thread::sleep_for(std::chrono::microseconds(500));  // a slow writer
    ++consumed;
  };
  SampleBatch(*program, options, callbacks);
  EXPECT_EQ(consumed.load(), 60);
  // The window (6) plus the scene the consumer has taken but not yet counted.
  EXPECT_LE(worst_in_flight.load(), 7);
}

TEST(BatchTest, StopsWhenCancelled) {
  auto program = CompileTableCube();
  ASSERT_NE(program, nullptr);
  for (int threads : {1, 2}) {
    std::atomic<bool> cancel = false;
    BatchOptions options;
    options.count = 1000;
    options.threads = threads;
    options.cancel = &cancel;
    int64_t consumed = 0;
    EXPECT_THROW(SampleBatch(*program, options,
                             {.prepare = {},
                              .consume =
                                  [&](BatchScene&&) {
                                    if (++consumed == 5) cancel = true;
                                  }}),
                 BatchCancelled);
    EXPECT_EQ(consumed, 5) << threads << " threads";
  }
}

// A tick for progress while a scene is hard: it runs on the calling thread while it waits, the
// live counts add up to the summary, and the scenes are the same as without either.
TEST(BatchTest, TicksWhileWaitingAndCountsAttemptsLiveWithoutChangingScenes) {
  auto program =
      CompileOrDie("x = Range(0, 1)\nrequire x < 0.0002\n");  // about 5,000 attempts a scene
  ASSERT_NE(program, nullptr);
  LiveCounts live;
  BatchOptions options;
  options.seed = 3;
  options.count = 4;
  options.threads = 1;
  options.sample.max_attempts = 1'000'000;
  options.sample.live = &live;
  std::vector<int64_t> with_tick, without_tick;
  std::atomic<int> ticks{0};
  const std::thread::id caller = std::this_thread::get_id();
  BatchCallbacks callbacks;
  callbacks.consume = [&](BatchScene&& scene) { with_tick.push_back(scene.sampled.attempts); };
  callbacks.tick = [&] {
    EXPECT_EQ(std::this_thread::get_id(), caller);
    ++ticks;
  };
  const BatchSummary summary = SampleBatch(*program, options, callbacks);
  EXPECT_EQ(live.attempts.load(), summary.attempts);
  EXPECT_EQ(live.rejections.load(), summary.rejections.total);
  EXPECT_GT(summary.attempts, 1000);
  options.sample.live = nullptr;
  SampleBatch(*program, options, {.prepare = {}, .consume = [&](BatchScene&& scene) {
                                    without_tick.push_back(scene.sampled.attempts);
                                  }});
  EXPECT_EQ(with_tick, without_tick);
  // Ticks need waiting: a scene slow enough to wait for.
  auto slow = CompileOrDie("x = Range(0, 1)\nrequire x < 0.000002\n");
  options.count = 1;
  options.sample.max_attempts = 10'000'000;
  ticks = 0;
  SampleBatch(*slow, options, callbacks);
  EXPECT_GT(ticks.load(), 0);
}

TEST(BatchTest, RejectsBadArguments) {
  auto program = CompileTableCube();
  ASSERT_NE(program, nullptr);
  BatchOptions options;
  options.count = -1;
  EXPECT_THROW(SampleBatch(*program, options, {}), std::invalid_argument);
  options.count = 2;
  options.threads = 0;
  EXPECT_THROW(SampleBatch(*program, options, {}), std::invalid_argument);
  options.threads = 1;
  options.start = UINT64_MAX;
  EXPECT_THROW(SampleBatch(*program, options, {}), std::invalid_argument);
}

// `format` on the workers and `write` on the calling thread: the text is every scene's, in
// index order, for any thread count; workers hand over runs of many scenes at once; `write`
// comes before `consume` gets the run's scenes, and the counts add up.
struct WrittenText {
  std::string text;
  int64_t lines = 0;
  int64_t writes = 0;
  int64_t widest_write = 0;
  std::vector<uint64_t> consumed;
  bool consumed_before_written = false;
};

WrittenText SampleText(const lang::CompiledProgram& program, int64_t count, int threads,
                       int64_t fail_at = -1) {
  BatchOptions options;
  options.seed = 5;
  options.count = count;
  options.threads = threads;
  WrittenText written;
  BatchCallbacks callbacks;
  callbacks.format = [fail_at](BatchScene& scene, std::string& text) {
    if (int64_t(scene.sampled.index) == fail_at) {
      text += "half a line";
      throw std::runtime_error("format failed");
    }
    text += Fingerprint(scene.sampled) + '\n';
  };
  callbacks.write = [&](std::string_view text, int64_t lines) {
    written.text += text;
    written.lines += lines;
    ++written.writes;
    written.widest_write = std::max(written.widest_write, lines);
  };
  callbacks.consume = [&](BatchScene&& scene) {
    written.consumed.push_back(scene.sampled.index);
    if (int64_t(written.consumed.size()) > written.lines) written.consumed_before_written = true;
  };
  try {
    const BatchSummary summary = SampleBatch(program, options, callbacks);
    EXPECT_EQ(summary.scenes, count);
  } catch (const std::runtime_error& error) {
    EXPECT_STREQ(error.what(), "format failed");
  }
  return written;
}

TEST(BatchTest, FormattedTextIsWrittenInOrderARunAtATime) {
  auto program = CompileOrDie(kRejectingProgram);
  ASSERT_NE(program, nullptr);
  const WrittenText one = SampleText(*program, 2000, 1);
  ASSERT_EQ(one.lines, 2000);
  EXPECT_EQ(one.writes, 2000);  // the calling thread alone: one scene at a time
  for (int threads : {2, 4}) {
    const WrittenText many = SampleText(*program, 2000, threads);
    EXPECT_EQ(many.text, one.text) << threads << " threads";
    EXPECT_EQ(many.lines, 2000);
    EXPECT_EQ(many.consumed, one.consumed);
    EXPECT_FALSE(many.consumed_before_written);
    EXPECT_GT(many.widest_write, 16) << "runs of scenes are handed over whole";
    EXPECT_LT(many.writes, 2000 / 16);
  }
}

// A scene that fails in `format` ends the batch after the scenes before it, whose text (and
// nothing of the failed scene or of the run after it) is written.
TEST(BatchTest, TextStopsAtTheFirstFailedScene) {
  auto program = CompileTableCube();
  ASSERT_NE(program, nullptr);
  const WrittenText one = SampleText(*program, 2000, 1);
  std::vector<std::string> lines;
  for (size_t begin = 0, end; (end = one.text.find('\n', begin)) != std::string::npos;
       begin = end + 1) {
    lines.push_back(one.text.substr(begin, end + 1 - begin));
  }
  ASSERT_EQ(lines.size(), 2000u);
  std::string first_777;
  for (int i = 0; i < 777; ++i) first_777 += lines[i];
  for (int threads : {1, 2, 4}) {
    const WrittenText failed = SampleText(*program, 2000, threads, 777);
    EXPECT_EQ(failed.text, first_777) << threads << " threads";
    EXPECT_EQ(failed.lines, 777);
    EXPECT_EQ(failed.consumed.size(), 777u);
  }
}

// The totals are counted per run on the workers and merged in order: the same counts and the
// same first example of each culprit as on one thread.
TEST(BatchTest, SummaryIsTheSameForAnyThreadCount) {
  auto program = CompileOrDie(kRejectingProgram);
  ASSERT_NE(program, nullptr);
  auto summarise = [&](int threads) {
    BatchOptions options;
    options.seed = 11;
    options.count = 3000;
    options.threads = threads;
    return SampleBatch(*program, options, {});
  };
  const BatchSummary one = summarise(1);
  ASSERT_GT(one.rejections.total, 100);
  for (int threads : {2, 3}) {
    const BatchSummary many = summarise(threads);
    EXPECT_EQ(many.scenes, one.scenes);
    EXPECT_EQ(many.attempts, one.attempts);
    EXPECT_EQ(many.rejections.by_culprit, one.rejections.by_culprit);
    ASSERT_EQ(many.rejections.examples.size(), one.rejections.examples.size());
    for (const auto& [key, example] : one.rejections.examples) {
      ASSERT_TRUE(many.rejections.examples.count(key));
      EXPECT_EQ(many.rejections.examples.at(key).detail, example.detail);
    }
  }
}

TEST(BatchTest, EmptyBatchConsumesNothing) {
  auto program = CompileTableCube();
  ASSERT_NE(program, nullptr);
  BatchOptions options;
  options.threads = 4;
  const BatchSummary summary = SampleBatch(
      *program, options,
      {.prepare = {}, .consume = [](BatchScene&&) { ADD_FAILURE() << "consumed a scene"; }});
  EXPECT_EQ(summary.scenes, 0);
}

}  // namespace
}  // namespace prs::sampling
