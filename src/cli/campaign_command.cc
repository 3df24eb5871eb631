// `prs campaign init|run-shard|status|merge|slurm|resume` (docs/cluster.md): a test or sample
// run cut into shards that any machine runs alone from a self-describing directory, submitted to
// Slurm as job arrays, and merged back into exactly what one machine's `prs test` / `prs sample`
// writes.
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "campaign/campaign.h"
#include "campaign/search_campaign.h"
#include "campaign/slurm.h"
#include "cli/commands.h"
#include "cli/common.h"
#include "cli/controller_options.h"
#include "cli/dataset_options.h"
#include "cli/estimate_report.h"
#include "cli/interrupt.h"
#include "output/line_writer.h"

namespace prs::cli {
namespace {

// The physics check the campaign's spec asks for (--stable or --settle at init), or none.
sampling::SceneTest MakePhysicsTest(const campaign::CampaignSpec& spec) {
  return sim::MakePhysicsTest(
      {spec.stable_s, spec.stable_move_m, spec.stable_turn_deg, spec.settle_s});
}

struct CampaignArgs {
  // init
  ScenarioArgs scenario;
  SamplingArgs sampling;
  ControllerArgs controller;
  int64_t count = 0;
  int64_t shard_size = 1000;
  std::string strategy;   // --search: a search campaign
  int64_t batch = 0;      // its generation size (0: as prs search picks)
  bool estimate = false;  // --estimate: an estimate campaign (prs estimate, -n its budget)
  bool dataset = false;   // --dataset: a dataset campaign (prs dataset, -n scenes)
  DatasetPictureArgs pictures;
  // every subcommand
  std::string dir;
  // run-shard
  int64_t shard = 0;
  // merge
  std::string output;
  bool partial = false;
  // slurm
  campaign::SlurmOptions slurm;
  std::set<std::string> given;  // the slurm/resume flags given on the command line
  bool print_only = false;
  bool chained = false;  // resume run by a search campaign's next-step job
};

// How many times a search generation is submitted by next-step jobs before they give up and
// leave it to the user (a shard that fails every time would otherwise loop forever).
constexpr int kMaxChainedSubmissions = 3;

int RunInit(const CampaignArgs& args) {
  auto program = CompileScenario(args.scenario);
  if (!program) return kExitScenarioError;
  campaign::CampaignSpec spec;
  spec.kind =
      args.controller.controller.empty() && args.controller.exec.empty() ? "sample" : "test";
  if (!args.strategy.empty()) {
    if (spec.kind != "test") {
      PrintError("--search needs a controller (--controller NAME or --exec CMD)");
      return kExitUsage;
    }
    spec.kind = "search";
    spec.strategy = args.strategy;
    spec.batch = static_cast<uint64_t>(args.batch);  // 0: as prs search picks
  } else if (args.batch > 0) {
    PrintError("--batch is the generation size of a search campaign: give --search too");
    return kExitUsage;
  }
  if (args.estimate) {
    if (spec.kind != "test") {
      PrintError(spec.kind == "search"
                     ? "--estimate and --search are two kinds of campaign: give one"
                     : "--estimate needs a controller (--controller NAME or --exec CMD)");
      return kExitUsage;
    }
    if (!CheckSamplerTakesPoints(args.sampling, "an estimate campaign",
                                 "leave out --sampler (the default, rejection, is exact for any "
                                 "program, which the estimate's weights need)")) {
      return kExitUsage;
    }
    if (args.count < search::kMinEstimateBudget) {
      PrintError(
          fmt::format("an estimate campaign's budget (-n {}) is too small to adapt a "
                      "proposal and then sample: give at least {}",
                      args.count, search::kMinEstimateBudget));
      return kExitUsage;
    }
    spec.kind = "estimate";
  }
  if (args.dataset) {
    if (spec.kind != "sample") {
      PrintError("--dataset makes labelled pictures of scenes: it takes no controller, "
                 "--search or --estimate");
      return kExitUsage;
    }
    if (const std::string problem = ReadDatasetPictureArgs(args.pictures, spec.dataset);
        !problem.empty()) {
      PrintError(problem);
      return kExitUsage;
    }
    spec.kind = "dataset";
  } else if (!args.pictures.cameras.empty() || !args.pictures.size.empty() ||
             !args.pictures.labels.empty() || args.pictures.format != "both" ||
             args.pictures.jpeg) {
    PrintError("--camera, --size, --format, --label and --jpeg are a dataset campaign's: give "
               "--dataset");
    return kExitUsage;
  }
  if (spec.kind != "sample" && spec.kind != "dataset") {
    InterruptWatch interrupt;
    if (!ChooseController(args.controller, interrupt.flag())) return kExitUsage;
  }
  spec.scenario_words = MakeScenarioWords(args.scenario, args.sampling);
  for (const auto& [name, value] : program->param_overrides) spec.params.emplace_back(name, value);
  spec.naive = args.sampling.naive;
  spec.sampler = args.sampling.sampler;
  spec.max_attempts = args.sampling.max_attempts;
  const sim::PhysicsCheck physics = MakePhysicsCheck(args.sampling);
  spec.stable_s = physics.stable_s;
  spec.stable_move_m = physics.stable_move_m;
  spec.stable_turn_deg = physics.stable_turn_deg;
  spec.settle_s = physics.settle_s;
  spec.seed = args.sampling.seed;
  spec.count = static_cast<uint64_t>(args.count);
  spec.shard_size = static_cast<uint64_t>(args.shard_size);
  spec.controller = args.controller.controller;
  spec.exec = args.controller.exec;
  spec.timeout_s = args.controller.timeout_s;
  spec.persistent = args.controller.persistent;
  spec.startup_timeout_s = args.controller.startup_timeout_s;
  spec.perception = args.controller.perception;
  spec.version = PRS_VERSION;
  try {
    // Every shard looks through the same cameras: scene 0 of the seed's, named now.
    if (spec.kind == "dataset" && spec.dataset.cameras.empty()) {
      spec.dataset.cameras =
          dataset::ListDefaultCameras(*program, campaign::MakeSampleOptions(spec), spec.seed);
      if (spec.dataset.cameras.empty()) {
        PrintError(DescribeNoCamera(fmt::format("scene 0 of seed {}", spec.seed)));
        return kExitUsage;
      }
    }
    spec = campaign::InitCampaign(args.dir, *program, spec);
  } catch (const lang::ScenarioError& error) {
    // A search's trial attempts (its coordinates) met a run-time error: located, as prs search.
    return ReportScenarioError(error, program->sources);
  } catch (const campaign::CampaignError& error) {
    PrintError(error.what());
    return kExitScenarioError;
  }
  PrintNote(fmt::format(
      "campaign {} in {}: {} of {} in {} of up to {}; run each with prs "
      "campaign run-shard {} K (K = 0..{})",
      spec.id, args.dir,
      FormatCount(spec.count, spec.kind == "sample" || spec.kind == "dataset" ? "scene" : "episode"),
      args.scenario.file, FormatCount(spec.shards(), "shard"), spec.shard_size, args.dir,
      spec.shards() - 1));
  if (spec.kind == "search") {
    PrintNote(fmt::format(
        "a {} search in {} of {}: generation g's shards can run once generation g - 1's are "
        "done (prs campaign slurm chains them)",
        spec.strategy, FormatCount(spec.generations(), "generation"), spec.batch));
  } else if (spec.kind == "estimate") {
    PrintNote(fmt::format(
        "an estimate in {} (the adaptation's, then the sampling's {}): generation g's shards can "
        "run once generation g - 1's are done (prs campaign slurm chains them)",
        FormatCount(spec.generations(), "generation"),
        FormatCount(spec.generation_sizes.back(), "episode")));
  }
  return kExitSuccess;
}

int RunShardCommand(const CampaignArgs& args) {
  InterruptWatch interrupt;
  std::unique_ptr<lang::CompiledProgram> program;  // for locating a run-time error
  try {
    const campaign::CampaignSpec spec = campaign::ReadCampaign(args.dir);
    program = campaign::CompileCampaign(args.dir, spec);
    std::optional<harness::ControllerFactory> factory;
    if (spec.kind != "sample" && spec.kind != "dataset") {
      factory = ChooseController({spec.controller, spec.exec, spec.timeout_s, spec.persistent,
                                  spec.startup_timeout_s, spec.perception},
                                 interrupt.flag());
      if (!factory) return kExitUsage;
    }
    campaign::RunShard(args.dir, spec, *program, static_cast<uint64_t>(args.shard),
                       factory ? &*factory : nullptr, args.sampling.threads, &interrupt.flag(),
                       {WarnOnce(), MakePhysicsTest(spec)});
    return kExitSuccess;
  } catch (const campaign::CampaignError& error) {
    PrintError(error.what());
    return kExitUsage;
  } catch (const sampling::BatchCancelled&) {
    PrintNote("interrupted; the shard was not written (run it again)");
    return kExitInterruptedBase + interrupt.signal_number();
  } catch (const lang::ScenarioError& error) {
    return ReportScenarioError(error, program->sources);  // exit 1, or 3 for a sampling failure
  } catch (const std::exception& error) {
    PrintError(error.what());
    return kExitScenarioError;
  }
}

// Reads DIR's campaign and runs `body` with it. A CampaignError (not a campaign, a changed
// spec, shards not done) is a usage error (exit 2); other failures (a file that cannot be
// written) exit 1.
template <typename Body>
int WithCampaign(const std::string& dir, Body body) {
  try {
    return body(campaign::ReadCampaign(dir));
  } catch (const campaign::CampaignError& error) {
    PrintError(error.what());
    return kExitUsage;
  } catch (const std::exception& error) {
    PrintError(error.what());
    return kExitScenarioError;
  }
}

// Prints the shards that need a look (running, failed, bad, missing with a reason: at most 20 of
// each kind) and one line of counts.
int RunStatus(const CampaignArgs& args) {
  return WithCampaign(args.dir, [&](const campaign::CampaignSpec& spec) {
    const campaign::SlurmQueue queue = campaign::QuerySlurmQueue(args.dir, spec);
    const std::vector<campaign::ShardState> states =
        campaign::DescribeShards(args.dir, spec, queue);
    using Kind = campaign::ShardState::Kind;
    int64_t counts[campaign::kShardStateKinds] = {};
    for (uint64_t k = 0; k < states.size(); ++k) {
      const int kind = static_cast<int>(states[k].kind);
      if (++counts[kind] <= 20 && states[k].kind != Kind::kDone &&
          states[k].kind != Kind::kQueued && !states[k].why.empty()) {
        std::cout << fmt::format("shard {}: {}: {}\n", k, campaign::ShardStateName(states[k].kind),
                                 states[k].why);
      }
    }
    for (Kind kind : {Kind::kRunning, Kind::kFailed, Kind::kMissing, Kind::kBad}) {
      const int64_t count = counts[static_cast<int>(kind)];
      if (count > 20) {
        std::cout << fmt::format("... and {} more {}\n", count - 20,
                                 campaign::ShardStateName(kind));
      }
    }
    std::cout << fmt::format(
        "{}: {} of {} done, {} queued, {} running, {} failed, {} missing, {} bad", args.dir,
        counts[0], spec.shards(), counts[1], counts[2], counts[3], counts[4], counts[5]);
    if (spec.planned()) {
      // The generation under way: the first one with a shard not done.
      uint64_t g = 0;
      for (; g < spec.generations(); ++g) {
        const std::vector<uint64_t> shards = spec.generation_shards(g);
        if (!std::all_of(shards.begin(), shards.end(),
                         [&](uint64_t k) { return states[k].kind == Kind::kDone; })) {
          break;
        }
      }
      std::cout << fmt::format(", {} waiting; {} generation {} of {}", counts[6], spec.kind,
                               std::min(g + 1, spec.generations()), spec.generations());
    }
    std::cout << "\n";
    if (!queue.available) PrintNote("the Slurm queue was not asked: " + queue.why_not);
    const size_t to_submit = campaign::FindShardsToResubmit(states).size();
    if (to_submit > 0 && counts[0] + counts[1] + counts[2] < static_cast<int64_t>(spec.shards())) {
      const bool submitted = !campaign::ReadSubmissions(args.dir).empty();
      PrintNote(fmt::format("prs campaign {} {} submits the {}{} (or run-shard them)",
                            submitted ? "resume" : "slurm", args.dir,
                            FormatCount(static_cast<int64_t>(to_submit), "shard"),
                            submitted ? " again" : ""));
    }
    return kExitSuccess;
  });
}

// An estimate campaign's records with their weights, as prs estimate -o writes them, and the
// estimate as prs estimate prints it.
ExitCode MergeEstimate(const CampaignArgs& args, const campaign::CampaignSpec& spec) {
  if (args.partial) {
    PrintError(
        "an estimate's weights come from every generation's records, so its shards merge only "
        "when all are done: leave out --partial and run the rest (prs campaign status " +
        args.dir + " names them)");
    return kExitUsage;
  }
  const campaign::EstimateMerge merge =
      campaign::MergeEstimate(args.dir, spec, *campaign::CompileCampaign(args.dir, spec));
  output::LineWriter out(args.output);
  for (const std::string& line : merge.lines) out.AddLine(line);
  out.Commit();
  PrintNote(fmt::format(
      "{} merged into {}: {} adapting the proposal, {} weighted (effective sample size {:.0f}); "
      "prs estimate --from {} gives the same estimate",
      FormatCount(merge.lines.size(), "record"), args.output, merge.summary.adapt_episodes,
      merge.summary.estimate.episodes, merge.summary.estimate.ess, args.output));
  PrintEstimate(merge.summary.estimate, false, false);
  return kExitSuccess;
}

int RunMerge(const CampaignArgs& args) {
  return WithCampaign(args.dir, [&](const campaign::CampaignSpec& spec) {
    if (spec.kind == "estimate") return MergeEstimate(args, spec);
    if (spec.kind == "dataset") {
      if (args.partial) {
        PrintError("a dataset campaign merges when every shard is done (prs campaign status " +
                   args.dir + " names the others)");
        return kExitUsage;
      }
      campaign::MergeDatasetShards(args.dir, spec, args.output);
      PrintNote(fmt::format("{} merged into the dataset {}: the files of one prs dataset run",
                            FormatCount(spec.shards(), "shard"), args.output));
      return kExitSuccess;
    }
    std::vector<uint64_t> skipped;
    const std::vector<std::string> lines =
        campaign::MergeShards(args.dir, spec, args.partial, &skipped);
    output::LineWriter out(args.output);
    for (const std::string& line : lines) out.AddLine(line);
    out.Commit();
    if (spec.kind != "sample") {
      std::vector<harness::EpisodeRecord> records;
      for (const std::string& line : lines) {
        harness::EpisodeRecord r;
        const auto j = nlohmann::json::parse(line, nullptr, false);
        r.result.outcome = j.is_object() ? j.value("outcome", "") : "";
        records.push_back(std::move(r));
      }
      std::cout << FormatOutcomeTable(records) << std::flush;
    }
    PrintNote(fmt::format(
        "{} merged into {}{}",
        FormatCount(lines.size(), spec.kind == "sample" ? "scene" : "record"), args.output,
        skipped.empty() ? "" : fmt::format(" ({} skipped)", FormatCount(skipped.size(), "shard"))));
    return kExitSuccess;
  });
}

// Writes DIR/slurm/submit-N.sh for the shards that are neither done nor in the Slurm queue and
// submits it with sbatch (unless --print), recording the job in DIR/slurm/submit-N.json. The
// first submission and every resume are the same command; `resume` takes the options of the
// last recorded submission, each overridden by the flag when given.
int RunSlurm(CampaignArgs args, bool resume) {
  namespace fs = std::filesystem;
  return WithCampaign(args.dir, [&](const campaign::CampaignSpec& spec) {
    const std::string dir = fs::absolute(args.dir).lexically_normal().string();
    const std::vector<campaign::SlurmSubmission> earlier = campaign::ReadSubmissions(dir);
    if (resume) {
      if (earlier.empty()) {
        PrintError("no Slurm submission of " + args.dir +
                   " is recorded: submit it first with prs campaign slurm " + args.dir);
        return kExitUsage;
      }
      const campaign::SlurmOptions& last = earlier.back().options;
      const auto keep = [&](const char* flag, auto& value, const auto& saved) {
        if (args.given.count(flag) == 0) value = saved;
      };
      keep("--partition", args.slurm.partition, last.partition);
      keep("--time", args.slurm.time, last.time);
      keep("--mem", args.slurm.mem, last.mem);
      keep("--cpus-per-task", args.slurm.cpus_per_task, last.cpus_per_task);
      keep("--max-running", args.slurm.max_running, last.max_running);
      keep("--extra", args.slurm.extra, last.extra);
    }
    int64_t generation = -1;  // search and estimate campaigns: the generation to submit
    std::vector<uint64_t> generation_shards;
    if (spec.planned()) {
      const campaign::SearchStep step =
          campaign::PlanSearchStep(dir, spec, *campaign::CompileCampaign(dir, spec));
      if (step.finished) {
        PrintNote("the " + spec.kind +
                  " is complete: every generation is done (prs campaign merge " + args.dir +
                  " -o OUT)");
        return kExitSuccess;
      }
      generation = static_cast<int64_t>(step.generation);
      generation_shards = spec.generation_shards(step.generation);
      const auto same_generation = std::count_if(
          earlier.begin(), earlier.end(),
          [&](const campaign::SlurmSubmission& s) { return s.generation == generation; });
      if (args.chained && same_generation >= kMaxChainedSubmissions) {
        PrintError(fmt::format(
            "generation {} was submitted {} times and its shards {} are still not done; "
            "see prs campaign status {} and the logs, then prs campaign resume {}",
            generation, same_generation, fmt::join(step.unfinished, ", "), args.dir, args.dir));
        return kExitScenarioError;
      }
    }
    const campaign::SlurmQueue queue = campaign::QuerySlurmQueue(dir, spec);
    if (!queue.available && !earlier.empty()) {
      PrintNote("warning: the Slurm queue was not asked (" + queue.why_not +
                "): shards still queued or running are submitted again");
    }
    if (!queue.next_steps.empty()) {
      PrintNote(
          fmt::format("Slurm job {} (this {}'s next step) plans and submits what follows when "
                      "generation {}'s tasks end; nothing to do (scancel it first to take over)",
                      queue.next_steps.front(), spec.kind, generation));
      return kExitSuccess;
    }
    const std::vector<uint64_t> shards =
        campaign::FindShardsToResubmit(campaign::DescribeShards(dir, spec, queue));
    // A search's generation whose tasks are all queued or running still needs a next step.
    std::vector<std::string> active_jobs;
    for (uint64_t k : generation_shards) {
      const auto task = queue.tasks.find(k);
      if (task != queue.tasks.end() && task->second.active() &&
          std::find(active_jobs.begin(), active_jobs.end(), task->second.job_id) ==
              active_jobs.end()) {
        active_jobs.push_back(task->second.job_id);
      }
    }
    const bool last_generation =
        generation < 0 || static_cast<uint64_t>(generation) + 1 >= spec.generations();
    if (shards.empty() && (active_jobs.empty() || args.print_only || last_generation)) {
      PrintNote("no shard to submit: each is done, queued or running (prs campaign status " +
                args.dir + ")");
      return kExitSuccess;
    }
    std::error_code error;
    args.slurm.prs = fs::read_symlink("/proc/self/exe", error).string();
    if (error) args.slurm.prs = "prs";
    // One job array per run of shards whose indices fit below Slurm's MaxArraySize.
    // Indices are the shard numbers where they fit, else counted from the array's first shard.
    const uint64_t max_array_size = campaign::QueryMaxArraySize();
    const std::vector<std::vector<uint64_t>> arrays =
        campaign::SplitIntoArrays(shards, max_array_size);
    const auto offset_of = [&](const std::vector<uint64_t>& array) {
      return array.back() < max_array_size ? uint64_t{0} : array.front();
    };
    int number = campaign::FindNextSubmissionNumber(dir);
    const std::string tasks = FormatCount(static_cast<int64_t>(shards.size()), "array task");
    if (args.print_only) {
      for (const std::vector<uint64_t>& array : arrays) {
        const std::string text =
            campaign::FormatSlurmScript(dir, spec, array, offset_of(array), args.slurm);
        const std::string script = campaign::WriteSlurmScript(dir, number++, text);
        std::cout << text << std::flush;
        PrintNote(fmt::format("{} written to {} (not submitted: --print)",
                              FormatCount(static_cast<int64_t>(array.size()), "array task"),
                              script));
      }
      return kExitSuccess;
    }
    try {
      campaign::SlurmSubmission submission;
      std::vector<std::string> job_ids;
      for (const std::vector<uint64_t>& array : arrays) {
        const std::string script = campaign::WriteSlurmScript(
            dir, number,
            campaign::FormatSlurmScript(dir, spec, array, offset_of(array), args.slurm));
        submission = {number++,   campaign::SubmitToSlurm(script, args.slurm.extra),
                      array,      offset_of(array),
                      args.slurm, generation,
                      ""};
        campaign::WriteSubmission(dir, submission);  // recorded before anything else can fail
        job_ids.push_back(submission.job_id);
        active_jobs.push_back(submission.job_id);
        std::cout << submission.job_id << "\n" << std::flush;
      }
      // A search's next generation is planned from this one's records: a job that waits for
      // this generation's arrays plans and submits it, with its own next step, up to the last.
      if (!last_generation) {
        if (arrays.empty()) submission = {number, "", {}, 0, args.slurm, generation, ""};
        const std::string next = campaign::WriteSlurmScript(
            dir, submission.number,
            campaign::FormatNextStepScript(dir, spec, submission.number,
                                           fmt::format("{}", fmt::join(active_jobs, ":")),
                                           args.slurm),
            "next");
        try {
          submission.next_job_id = campaign::SubmitToSlurm(next, args.slurm.extra);
        } catch (const campaign::CampaignError& error) {
          PrintError(fmt::format(
              "{}{}; run prs campaign resume {} when this generation's tasks have ended",
              error.what(),
              job_ids.empty() ? ""
                              : fmt::format(" (Slurm job {} with the generation's shards was "
                                            "submitted)",
                                            fmt::join(job_ids, ", ")),
              args.dir));
          return kExitScenarioError;
        }
        campaign::WriteSubmission(dir, submission);
      }
      PrintNote(fmt::format(
          "submitted {}{}; follow it with prs campaign status {}",
          job_ids.empty() ? std::string("no shard (each is queued or running)")
                          : fmt::format("Slurm job {} ({}{})", fmt::join(job_ids, ", "), tasks,
                                        generation >= 0 ? fmt::format(" of {} generation {}",
                                                                      spec.kind, generation)
                                                        : ""),
          submission.next_job_id.empty()
              ? ""
              : fmt::format(" and job {}, which submits the next generation when it ends",
                            submission.next_job_id),
          args.dir));
      return kExitSuccess;
    } catch (const campaign::CampaignError& error) {
      PrintError(error.what());
      return kExitScenarioError;  // sbatch missing or refusing is not a usage error
    }
  });
}

}  // namespace

CommandRunner ConfigureCampaignCommand(CLI::App& command) {
  auto args = std::make_shared<CampaignArgs>();
  command.require_subcommand(1);
  CLI::App* init = command.add_subcommand("init", "make a campaign directory");
  init->add_option("DIR", args->dir, "the campaign directory (new or empty)")->required();
  AddScenarioOptions(*init, args->scenario);
  AddControllerOptions(*init, args->controller);
  init->add_option("-n,--count", args->count, "episodes (with a controller) or scenes")
      ->type_name("N")
      ->required()
      ->check(IntegerAtLeast(1));
  init->add_option("--shard-size", args->shard_size, "episodes or scenes per shard")
      ->type_name("B")
      ->check(IntegerAtLeast(1))
      ->capture_default_str();
  init->add_option("--search", args->strategy,
                   "a failure search of N episodes in generations, each one job array "
                   "(strategies: " +
                       fmt::format("{}", fmt::join(search::StrategyNames(), ", ")) + ")")
      ->type_name("STRATEGY")
      ->check(CLI::IsMember(search::StrategyNames()));
  init->add_option("--batch", args->batch, "a search's generation size (default as prs search)")
      ->type_name("B")
      ->check(IntegerAtLeast(1));
  init->add_flag("--estimate", args->estimate,
                 "prs estimate's run of budget N in generations, each one job array; merge "
                 "gives its records and its estimate");
  init->add_flag("--dataset", args->dataset,
                 "prs dataset's labelled pictures of N scenes; merge gives one dataset "
                 "(docs/dataset.md)");
  AddDatasetPictureOptions(*init, args->pictures);
  AddSamplingOptions(*init, args->sampling);
  CLI::App* run = command.add_subcommand("run-shard", "run one shard and write it atomically");
  run->add_option("DIR", args->dir, "the campaign directory")->required();
  run->add_option("K", args->shard, "the shard, from 0")->required()->check(IntegerAtLeast(0));
  run->add_option("--threads", args->sampling.threads, "worker threads")
      ->type_name("T")
      ->check(IntegerInRange(1, 1024));
  args->sampling.threads = CountHardwareThreads();
  CLI::App* status = command.add_subcommand("status", "which shards are done, missing or bad");
  status->add_option("DIR", args->dir, "the campaign directory")->required();
  CLI::App* merge = command.add_subcommand("merge", "every shard's lines in index order");
  merge->add_option("DIR", args->dir, "the campaign directory")->required();
  merge->add_option("-o,--output", args->output,
                    "the merged JSON Lines file (a dataset campaign's: the dataset directory)")
      ->type_name("OUT")
      ->required()
      ->check(NonEmptyPath());
  merge->add_flag("--partial", args->partial, "merge the done shards even when some are not");
  CLI::App* slurm = command.add_subcommand(
      "slurm", "submit the shards not done and not queued as a Slurm job array");
  CLI::App* resume = command.add_subcommand(
      "resume", "submit the shards not done and not queued again, as the last submission did");
  for (CLI::App* sub : {slurm, resume}) {
    sub->add_option("DIR", args->dir, "the campaign directory")->required();
    const auto note = [args](const char* flag) {
      return [args, flag](const auto&) { args->given.insert(flag); };
    };
    sub->add_option("--partition", args->slurm.partition, "sbatch --partition")
        ->type_name("P")
        ->each(note("--partition"));
    sub->add_option("--time", args->slurm.time, "sbatch --time, per shard")
        ->type_name("T")
        ->each(note("--time"));
    sub->add_option("--mem", args->slurm.mem, "sbatch --mem, per shard")
        ->type_name("M")
        ->each(note("--mem"));
    sub->add_option("--cpus-per-task", args->slurm.cpus_per_task, "CPUs (threads) per shard")
        ->type_name("C")
        ->check(IntegerInRange(1, 1024))
        ->each(note("--cpus-per-task"))
        ->capture_default_str();
    sub->add_option("--max-running", args->slurm.max_running, "at most this many tasks at once")
        ->type_name("N")
        ->check(IntegerAtLeast(1))
        ->each(note("--max-running"));
    sub->add_option("--extra", args->slurm.extra, "more sbatch arguments, as one string")
        ->type_name("ARGS")
        ->each(note("--extra"));
    sub->add_flag("--print", args->print_only, "write and print the script, do not submit it");
  }
  // Given by a search campaign's next-step job (FormatNextStepScript), not by people.
  resume->add_flag("--chained", args->chained, "")->group("");
  return [args, init, run, status, slurm, resume] {
    if (init->parsed()) return RunInit(*args);
    if (run->parsed()) return RunShardCommand(*args);
    if (status->parsed()) return RunStatus(*args);
    if (slurm->parsed()) return RunSlurm(*args, false);
    if (resume->parsed()) return RunSlurm(*args, true);
    return RunMerge(*args);
  };
}

}  // namespace prs::cli
