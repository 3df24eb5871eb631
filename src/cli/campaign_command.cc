// `prs campaign init|run-shard|status|merge` (docs/cluster.md): a test or sample run cut into
// shards that any machine runs alone from a self-describing directory, and merged back into
// exactly what one machine's `prs test` / `prs sample` writes.
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "campaign/campaign.h"
#include "cli/commands.h"
#include "cli/common.h"
#include "cli/controller_options.h"
#include "cli/interrupt.h"
#include "output/line_writer.h"

namespace prs::cli {
namespace {

struct CampaignArgs {
  // init
  ScenarioArgs scenario;
  SamplingArgs sampling;
  ControllerArgs controller;
  int64_t count = 0;
  int64_t shard_size = 1000;
  // every subcommand
  std::string dir;
  // run-shard
  int64_t shard = 0;
  // merge
  std::string output;
  bool partial = false;
  // slurm
  campaign::SlurmOptions slurm;
  std::string extra;  // more sbatch arguments
  bool print_only = false;
};

int RunInit(const CampaignArgs& args) {
  auto program = CompileScenario(args.scenario);
  if (!program) return kExitScenarioError;
  campaign::CampaignSpec spec;
  spec.kind =
      args.controller.controller.empty() && args.controller.exec.empty() ? "sample" : "test";
  if (spec.kind == "test") {
    InterruptWatch interrupt;
    if (!ChooseController(args.controller, interrupt.flag())) return kExitUsage;
  }
  spec.scenario_words = MakeScenarioWords(args.scenario, args.sampling);
  for (const auto& [name, value] : program->param_overrides) spec.params.emplace_back(name, value);
  spec.naive = args.sampling.naive;
  spec.max_attempts = args.sampling.max_attempts;
  spec.seed = args.sampling.seed;
  spec.count = static_cast<uint64_t>(args.count);
  spec.shard_size = static_cast<uint64_t>(args.shard_size);
  spec.controller = args.controller.controller;
  spec.exec = args.controller.exec;
  spec.timeout_s = args.controller.timeout_s;
  spec.version = PRS_VERSION;
  try {
    spec = campaign::InitCampaign(args.dir, *program, spec);
  } catch (const campaign::CampaignError& error) {
    PrintError(error.what());
    return kExitScenarioError;
  }
  PrintNote(fmt::format(
      "campaign {} in {}: {} of {} in {} of up to {}; run each with prs "
      "campaign run-shard {} K (K = 0..{})",
      spec.id, args.dir, FormatCount(spec.count, spec.kind == "test" ? "episode" : "scene"),
      args.scenario.file, FormatCount(spec.shards(), "shard"), spec.shard_size, args.dir,
      spec.shards() - 1));
  return kExitSuccess;
}

int RunShardCommand(const CampaignArgs& args) {
  InterruptWatch interrupt;
  std::unique_ptr<lang::CompiledProgram> program;  // for locating a run-time error
  try {
    const campaign::CampaignSpec spec = campaign::ReadCampaign(args.dir);
    program = campaign::CompileCampaign(args.dir, spec);
    std::optional<harness::ControllerFactory> factory;
    if (spec.kind == "test") {
      factory = ChooseController({spec.controller, spec.exec, spec.timeout_s}, interrupt.flag());
      if (!factory) return kExitUsage;
    }
    campaign::RunShard(args.dir, spec, *program, static_cast<uint64_t>(args.shard),
                       factory ? &*factory : nullptr, args.sampling.threads, &interrupt.flag());
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

int RunStatus(const CampaignArgs& args) {
  return WithCampaign(args.dir, [&](const campaign::CampaignSpec& spec) {
    int64_t done = 0, missing = 0, running = 0, bad = 0;
    for (uint64_t k = 0; k < spec.shards(); ++k) {
      const campaign::ShardStatus s = campaign::CheckShard(args.dir, spec, k);
      using State = campaign::ShardStatus::State;
      if (s.state == State::kDone) ++done;
      if (s.state == State::kMissing) ++missing;
      if (s.state == State::kRunning) {
        ++running;
        std::cout << fmt::format("shard {}: running or stopped ({} exists)\n", k, s.why);
      }
      if (s.state == State::kBad) {
        ++bad;
        std::cout << fmt::format("shard {}: bad: {}; run it again\n", k, s.why);
      }
    }
    std::cout << fmt::format("{}: {} of {} done, {} missing, {} running or stopped, {} bad\n",
                             args.dir, done, spec.shards(), missing, running, bad);
    return kExitSuccess;
  });
}

int RunMerge(const CampaignArgs& args) {
  return WithCampaign(args.dir, [&](const campaign::CampaignSpec& spec) {
    std::vector<uint64_t> skipped;
    const std::vector<std::string> lines =
        campaign::MergeShards(args.dir, spec, args.partial, &skipped);
    output::LineWriter out(args.output);
    for (const std::string& line : lines) out.AddLine(line);
    out.Commit();
    if (spec.kind == "test") {
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
        "{} merged into {}{}", FormatCount(lines.size(), spec.kind == "test" ? "record" : "scene"),
        args.output,
        skipped.empty() ? "" : fmt::format(" ({} skipped)", FormatCount(skipped.size(), "shard"))));
    return kExitSuccess;
  });
}

// Writes DIR/slurm/submit-N.sh for the unfinished shards and submits it with sbatch (unless
// --print): the first submission and every resume are the same command.
int RunSlurm(CampaignArgs args) {
  namespace fs = std::filesystem;
  return WithCampaign(args.dir, [&](const campaign::CampaignSpec& spec) {
    const std::string dir = fs::absolute(args.dir).lexically_normal().string();
    const std::vector<uint64_t> shards = campaign::FindUnfinishedShards(dir, spec);
    if (shards.empty()) {
      PrintNote("every shard is done; nothing to submit (prs campaign merge " + args.dir + ")");
      return kExitSuccess;
    }
    std::error_code error;
    args.slurm.prs = fs::read_symlink("/proc/self/exe", error).string();
    if (error) args.slurm.prs = "prs";
    fs::create_directories(dir + "/logs", error);
    fs::create_directories(dir + "/slurm", error);
    int n = 0;
    while (fs::exists(fmt::format("{}/slurm/submit-{}.sh", dir, n))) ++n;
    const std::string script = fmt::format("{}/slurm/submit-{}.sh", dir, n);
    const std::string text = campaign::FormatSlurmScript(dir, spec, shards, args.slurm);
    output::LineWriter writer(script);
    writer.AddLine(std::string_view(text).substr(0, text.size() - 1));
    writer.Commit();
    if (args.print_only) {
      std::cout << text << std::flush;
      PrintNote(fmt::format("{} for {} written to {} (not submitted: --print)",
                            FormatCount(static_cast<int64_t>(shards.size()), "array task"),
                            FormatCount(static_cast<int64_t>(shards.size()), "shard"), script));
      return kExitSuccess;
    }
    if (std::system("command -v sbatch >/dev/null 2>&1") != 0) {
      PrintError(
          "sbatch is not installed here: run prs campaign slurm on a machine of the "
          "cluster (Debian: the slurm-client package), or submit " +
          script + " yourself");
      return kExitScenarioError;
    }
    const std::string command =
        "sbatch --parsable " + args.extra + " " + harness::QuoteForShell(script);
    const int status = std::system(command.c_str());
    if (status != 0) {
      PrintError("sbatch refused the job (its message is above); the script is " + script);
      return kExitScenarioError;
    }
    PrintNote(fmt::format("submitted {} (the job id above); follow with prs campaign status {}",
                          FormatCount(static_cast<int64_t>(shards.size()), "shard"), args.dir));
    return kExitSuccess;
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
  merge->add_option("-o,--output", args->output, "the merged JSON Lines file")
      ->type_name("OUT")
      ->required()
      ->check(NonEmptyPath());
  merge->add_flag("--partial", args->partial, "merge the done shards even when some are not");
  CLI::App* slurm = command.add_subcommand(
      "slurm", "submit the unfinished shards as a Slurm job array (again to resume)");
  slurm->add_option("DIR", args->dir, "the campaign directory")->required();
  slurm->add_option("--partition", args->slurm.partition, "sbatch --partition")->type_name("P");
  slurm->add_option("--time", args->slurm.time, "sbatch --time, per shard")->type_name("T");
  slurm->add_option("--mem", args->slurm.mem, "sbatch --mem, per shard")->type_name("M");
  slurm->add_option("--cpus-per-task", args->slurm.cpus_per_task, "CPUs (threads) per shard")
      ->type_name("C")
      ->check(IntegerInRange(1, 1024))
      ->capture_default_str();
  slurm->add_option("--max-running", args->slurm.max_running, "at most this many tasks at once")
      ->type_name("N")
      ->check(IntegerAtLeast(1));
  slurm->add_option("--extra", args->extra, "more sbatch arguments, as one string")
      ->type_name("ARGS");
  slurm->add_flag("--print", args->print_only, "write and print the script, do not submit it");
  return [args, init, run, status, slurm] {
    if (init->parsed()) return RunInit(*args);
    if (run->parsed()) return RunShardCommand(*args);
    if (status->parsed()) return RunStatus(*args);
    if (slurm->parsed()) return RunSlurm(*args);
    return RunMerge(*args);
  };
}

}  // namespace prs::cli
