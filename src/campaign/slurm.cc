// Campaigns on Slurm: the job-array script, submission records, squeue's view of the array
// tasks, and each shard's state from files and queue together.
#include "campaign/slurm.h"

#include <fmt/format.h>
#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "campaign/files.h"
#include "campaign/search_campaign.h"
#include "harness/harness.h"

namespace prs::campaign {
namespace fs = std::filesystem;
namespace {

struct CommandResult {
  int exit_code = -1;  // -1: could not run, or ended by a signal
  std::string output;  // stdout and stderr together
};

// Runs `command` with /bin/sh, capturing what it prints.
CommandResult RunCommand(const std::string& command) {
  CommandResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  char buffer[4096];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
    result.output.append(buffer, n);
  const int status = ::pclose(pipe);
  if (status != -1 && WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  return result;
}

bool HasProgram(const std::string& name) {
  return RunCommand("command -v " + harness::QuoteForShell(name)).exit_code == 0;
}

std::string Trim(std::string text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  size_t start = 0;
  while (start < text.size() && std::isspace(static_cast<unsigned char>(text[start]))) ++start;
  return text.substr(start);
}

// The last non-empty line of a task's log, shortened: what the task said before it ended.
std::string ReadLastLogLine(const std::string& path) {
  bool ok = false;
  std::stringstream text(ReadFileText(path, &ok));
  std::string line, last;
  while (std::getline(text, line)) {
    if (!Trim(line).empty()) last = Trim(line);
  }
  if (last.size() > 160) last = last.substr(0, 157) + "...";
  return last;
}

// squeue's `%F|%K|%T|%r` lines as fields; lines of fewer than 3 fields are dropped.
std::vector<std::vector<std::string>> SplitSqueueLines(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> fields;
    std::stringstream parts(Trim(line));
    for (std::string field; std::getline(parts, field, '|');) fields.push_back(field);
    if (fields.size() >= 3) rows.push_back(std::move(fields));
  }
  return rows;
}

std::string SubmissionPath(const std::string& dir, int number, const char* extension) {
  return fmt::format("{}/slurm/submit-{}.{}", dir, number, extension);
}

// Orders Slurm job ids numerically ("9" before "10"); ids that are not numbers by text.
bool IsLaterJob(const std::string& a, const std::string& b) {
  if (a.size() != b.size() && a.find_first_not_of("0123456789") == std::string::npos &&
      b.find_first_not_of("0123456789") == std::string::npos) {
    return a.size() > b.size();
  }
  return a > b;
}

}  // namespace

std::string SlurmJobName(const CampaignSpec& spec) { return "prs-" + spec.id.substr(0, 8); }

std::string FormatSlurmScript(const std::string& dir, const CampaignSpec& spec,
                              const std::vector<uint64_t>& shards, uint64_t offset,
                              const SlurmOptions& options) {
  // The array's indices, shard - offset: runs of consecutive ones as ranges ("0-7,9,12-15").
  std::string array;
  for (size_t i = 0; i < shards.size();) {
    size_t j = i;
    while (j + 1 < shards.size() && shards[j + 1] == shards[j] + 1) ++j;
    const uint64_t a = shards[i] - offset, b = shards[j] - offset;
    array += fmt::format("{}{}", array.empty() ? "" : ",",
                         i == j ? fmt::format("{}", a) : fmt::format("{}-{}", a, b));
    i = j + 1;
  }
  if (options.max_running > 0) array += fmt::format("%{}", options.max_running);
  // Slurm's own messages (cancelled, timed out) go to slurm-JOB_INDEX.out; the shard's output
  // to shard-K.JOB.out and .err, named by the shard, not the array index.
  std::string script = fmt::format(
      "#!/bin/bash\n"
      "# prs campaign {} ({}): {} of {} shard(s), written by prs campaign slurm.\n"
      "#SBATCH --job-name={}\n"
      "#SBATCH --array={}\n"
      "#SBATCH --output={}/logs/slurm-%A_%a.out\n"
      "#SBATCH --cpus-per-task={}\n",
      spec.id, spec.kind, shards.size(), spec.shards(), SlurmJobName(spec), array, dir,
      options.cpus_per_task);
  if (!options.partition.empty()) script += "#SBATCH --partition=" + options.partition + "\n";
  if (!options.time.empty()) script += "#SBATCH --time=" + options.time + "\n";
  if (!options.mem.empty()) script += "#SBATCH --mem=" + options.mem + "\n";
  const std::string logs =
      harness::QuoteForShell(dir + "/logs") + "/shard-$shard.$SLURM_ARRAY_JOB_ID";
  script += fmt::format(
      "set -eu\n"
      "shard=$(({} + SLURM_ARRAY_TASK_ID))\n"
      "exec {} campaign run-shard {} \"$shard\" --threads \"${{SLURM_CPUS_PER_TASK:-{}}}\" "
      ">\"{}.out\" 2>\"{}.err\"\n",
      offset, harness::QuoteForShell(options.prs), harness::QuoteForShell(dir),
      options.cpus_per_task, logs, logs);
  return script;
}

std::vector<std::vector<uint64_t>> SplitIntoArrays(const std::vector<uint64_t>& shards,
                                                   uint64_t max_array_size) {
  std::vector<std::vector<uint64_t>> arrays;
  for (uint64_t k : shards) {
    if (arrays.empty() || k - arrays.back().front() >= std::max<uint64_t>(max_array_size, 1)) {
      arrays.emplace_back();
    }
    arrays.back().push_back(k);
  }
  return arrays;
}

uint64_t QueryMaxArraySize() {
  constexpr uint64_t kSlurmDefault = 1001;
  if (!HasProgram("scontrol")) return kSlurmDefault;
  const CommandResult result = RunCommand("scontrol show config");
  if (result.exit_code != 0) return kSlurmDefault;
  std::stringstream lines(result.output);
  for (std::string line; std::getline(lines, line);) {
    // "MaxArraySize            = 1001"
    if (line.rfind("MaxArraySize", 0) != 0) continue;
    const size_t equals = line.find('=');
    if (equals == std::string::npos) break;
    const std::string value = Trim(line.substr(equals + 1));
    if (value.empty() || value.size() > 12 ||
        value.find_first_not_of("0123456789") != std::string::npos) {
      break;
    }
    return std::max<uint64_t>(std::stoull(value), 1);
  }
  return kSlurmDefault;
}

std::string FormatNextStepScript(const std::string& dir, const CampaignSpec& spec, int number,
                                 const std::string& job_id, const SlurmOptions& options) {
  std::string script = fmt::format(
      "#!/bin/bash\n"
      "# prs campaign {} (search): plans and submits the next generation once job {} ends,\n"
      "# written by prs campaign slurm.\n"
      "#SBATCH --job-name={}-next\n"
      "#SBATCH --dependency=afterany:{}\n"
      "#SBATCH --kill-on-invalid-dep=yes\n"
      "#SBATCH --output={}/logs/next-{}.out\n"
      "#SBATCH --error={}/logs/next-{}.err\n"
      "#SBATCH --cpus-per-task=1\n",
      spec.id, job_id, SlurmJobName(spec), job_id, dir, number, dir, number);
  if (!options.partition.empty()) script += "#SBATCH --partition=" + options.partition + "\n";
  script += fmt::format("set -eu\nexec {} campaign resume {} --chained\n",
                        harness::QuoteForShell(options.prs), harness::QuoteForShell(dir));
  return script;
}

std::string WriteSlurmScript(const std::string& dir, int number, const std::string& script,
                             const char* name) {
  std::error_code error;
  fs::create_directories(dir + "/logs", error);
  fs::create_directories(dir + "/slurm", error);
  const std::string path = fmt::format("{}/slurm/{}-{}.sh", dir, name, number);
  WriteFileAtomically(path, script);
  return path;
}

int FindNextSubmissionNumber(const std::string& dir) {
  int n = 0;
  std::error_code error;
  while (fs::exists(SubmissionPath(dir, n, "sh"), error) ||
         fs::exists(SubmissionPath(dir, n, "json"), error)) {
    ++n;
  }
  return n;
}

void WriteSubmission(const std::string& dir, const SlurmSubmission& s) {
  const nlohmann::json record = {{"job_id", s.job_id},
                                 {"shards", s.shards},
                                 {"partition", s.options.partition},
                                 {"time", s.options.time},
                                 {"mem", s.options.mem},
                                 {"cpus_per_task", s.options.cpus_per_task},
                                 {"max_running", s.options.max_running},
                                 {"prs", s.options.prs},
                                 {"extra", s.options.extra},
                                 {"offset", s.offset},
                                 {"generation", s.generation},
                                 {"next_job_id", s.next_job_id}};
  WriteFileAtomically(SubmissionPath(dir, s.number, "json"), record.dump() + "\n");
}

std::vector<SlurmSubmission> ReadSubmissions(const std::string& dir) {
  std::vector<SlurmSubmission> submissions;
  const int end = FindNextSubmissionNumber(dir);
  for (int n = 0; n < end; ++n) {
    bool ok = false;
    const auto j =
        nlohmann::json::parse(ReadFileText(SubmissionPath(dir, n, "json"), &ok), nullptr, false);
    if (!ok || !j.is_object()) continue;  // written by --print, or sbatch refused it
    try {
      SlurmSubmission s;
      s.number = n;
      s.job_id = j.at("job_id").get<std::string>();
      s.shards = j.at("shards").get<std::vector<uint64_t>>();
      s.options.partition = j.value("partition", "");
      s.options.time = j.value("time", "");
      s.options.mem = j.value("mem", "");
      s.options.cpus_per_task = j.value("cpus_per_task", 1);
      s.options.max_running = j.value("max_running", 0);
      s.options.prs = j.value("prs", "");
      s.options.extra = j.value("extra", "");
      s.offset = j.value("offset", uint64_t{0});
      s.generation = j.value("generation", int64_t{-1});
      s.next_job_id = j.value("next_job_id", "");
      submissions.push_back(std::move(s));
    } catch (const nlohmann::json::exception&) {
      continue;  // a record edited by hand: the shards' own files still tell what is done
    }
  }
  return submissions;
}

std::string SubmitToSlurm(const std::string& script, const std::string& extra) {
  if (!HasProgram("sbatch")) {
    throw CampaignError(
        "sbatch is not installed here: run this on a machine of the cluster (Debian: the "
        "slurm-client package), or submit " +
        script + " yourself");
  }
  const CommandResult result =
      RunCommand("sbatch --parsable " + extra + " " + harness::QuoteForShell(script));
  const std::string output = Trim(result.output);
  // --parsable prints "JOBID" or "JOBID;CLUSTER" (and warnings, if any, on lines before it).
  const std::string last = output.substr(output.find_last_of('\n') + 1);
  const std::string job_id = last.substr(0, last.find(';'));
  if (result.exit_code != 0 || job_id.empty() ||
      job_id.find_first_not_of("0123456789") != std::string::npos) {
    throw CampaignError("sbatch refused the job: " + (output.empty() ? "(no message)" : output) +
                        "; the script is " + script);
  }
  return job_id;
}

bool QueuedTask::active() const {
  static const std::set<std::string> kActive = {
      "PENDING",     "RUNNING",  "CONFIGURING", "COMPLETING", "REQUEUED",  "REQUEUE_HOLD",
      "REQUEUE_FED", "RESIZING", "SUSPENDED",   "STOPPED",    "SIGNALING", "STAGE_OUT"};
  return kActive.count(state) > 0;
}

std::map<uint64_t, QueuedTask> ParseSqueueLines(const std::string& text,
                                                const std::map<std::string, uint64_t>& offsets) {
  std::map<uint64_t, QueuedTask> tasks;
  for (const std::vector<std::string>& fields : SplitSqueueLines(text)) {
    const auto job = offsets.find(fields[0]);
    if (job == offsets.end()) continue;
    const std::string& index = fields[1];
    if (index.empty() || index.size() > 18 ||
        index.find_first_not_of("0123456789") != std::string::npos) {
      continue;
    }
    const uint64_t shard = job->second + std::stoull(index);
    QueuedTask task{fields[0], fields[2], fields.size() > 3 ? fields[3] : "", std::stoull(index)};
    auto it = tasks.find(shard);
    if (it == tasks.end() || IsLaterJob(task.job_id, it->second.job_id)) tasks[shard] = task;
  }
  return tasks;
}

SlurmQueue QuerySlurmQueue(const std::string& dir, const CampaignSpec& spec) {
  SlurmQueue queue;
  std::map<std::string, uint64_t> offsets;  // array job id -> its first index's shard
  std::vector<std::string> next_ids;
  for (const SlurmSubmission& s : ReadSubmissions(dir)) {
    if (!s.job_id.empty()) offsets[s.job_id] = s.offset;
    if (!s.next_job_id.empty()) next_ids.push_back(s.next_job_id);
  }
  if (offsets.empty() && next_ids.empty()) {
    queue.available = true;
    return queue;
  }
  if (!HasProgram("squeue")) {
    queue.why_not = "squeue is not installed here";
    return queue;
  }
  // --states=all also lists tasks that ended in the last MinJobAge seconds (300 by default),
  // with how they ended; --array lists every task of an array on its own line.
  const CommandResult result =
      RunCommand("squeue --noheader --array --states=all --name=" + SlurmJobName(spec) + "," +
                 SlurmJobName(spec) + "-next --format='%F|%K|%T|%r'");
  if (result.exit_code != 0) {
    queue.why_not = "squeue failed: " + Trim(result.output);
    return queue;
  }
  queue.available = true;
  queue.tasks = ParseSqueueLines(result.output, offsets);
  const char* self = std::getenv("SLURM_JOB_ID");
  for (const std::vector<std::string>& fields : SplitSqueueLines(result.output)) {
    const std::string& id = fields[0];
    if (std::find(next_ids.begin(), next_ids.end(), id) != next_ids.end() &&
        QueuedTask{id, fields[2], "", 0}.active() && !(self && id == self)) {
      queue.next_steps.push_back(id);
    }
  }
  return queue;
}

std::vector<ShardState> DescribeShards(const std::string& dir, const CampaignSpec& spec,
                                       const SlurmQueue& queue) {
  std::map<uint64_t, std::pair<std::string, uint64_t>> submitted;  // shard -> job id, index
  for (const SlurmSubmission& s : ReadSubmissions(dir)) {
    for (uint64_t k : s.shards) submitted[k] = {s.job_id, k - s.offset};
  }
  using Kind = ShardState::Kind;
  std::vector<ShardState> states;
  // Search campaigns: whether every shard of each generation so far is done.
  std::vector<bool> generation_done(spec.generations(), true);
  for (uint64_t k = 0; k < spec.shards(); ++k) {
    const ShardStatus files = CheckShard(dir, spec, k);
    const uint64_t g = spec.generation(k);
    if (files.state != ShardStatus::State::kDone) generation_done[g] = false;
    ShardState state;
    if (files.state == ShardStatus::State::kDone) {
      state.kind = Kind::kDone;
    } else if (files.state == ShardStatus::State::kBad) {
      state = {Kind::kBad, files.why};
    } else if (auto task = queue.tasks.find(k);
               task != queue.tasks.end() && task->second.active()) {
      const QueuedTask& t = task->second;
      const std::string job = fmt::format("Slurm job {}_{}", t.job_id, t.index);
      if (t.state == "PENDING") {
        state = {Kind::kQueued,
                 job + (t.reason.empty() || t.reason == "None" ? "" : " waits: " + t.reason)};
      } else {
        state = {Kind::kRunning, job + " is " + t.state};
      }
    } else if (submitted.count(k) && queue.available) {
      const auto& [job_id, index] = submitted[k];
      std::string why = task != queue.tasks.end()
                            ? fmt::format("Slurm job {}_{} ended {}", task->second.job_id,
                                          task->second.index, task->second.state)
                            : fmt::format("Slurm job {}_{} ended", job_id, index);
      why += " without writing it";
      if (files.state == ShardStatus::State::kRunning) why += " (a .partial file is left)";
      // What the shard's prs said last, else what Slurm said (cancelled, timed out, ...).
      for (const std::string& log_name : {fmt::format("logs/shard-{}.{}.err", k, job_id),
                                          fmt::format("logs/slurm-{}_{}.out", job_id, index)}) {
        const std::string log = ReadLastLogLine(dir + "/" + log_name);
        if (log.empty()) continue;
        why += fmt::format("; {} ends: {}", log_name, log);
        break;
      }
      state = {Kind::kFailed, why};
    } else if (files.state == ShardStatus::State::kRunning) {
      state = {Kind::kRunning, "running or stopped (" + files.why + " exists)"};
    } else if (spec.planned() && g > 0 && !fs::exists(GenerationPlanPath(dir, g)) &&
               (!generation_done[g - 1] || !queue.next_steps.empty())) {
      state = {Kind::kWaiting, generation_done[g - 1]
                                   ? fmt::format("Slurm job {} plans and submits generation {}",
                                                 queue.next_steps.front(), g)
                                   : ""};
    } else {
      state.kind = Kind::kMissing;
      if (submitted.count(k)) {
        state.why = fmt::format(
            "submitted as Slurm job {}_{}; {}, so whether it still waits is "
            "not known",
            submitted[k].first, submitted[k].second, queue.why_not);
      }
    }
    states.push_back(std::move(state));
  }
  return states;
}

const char* ShardStateName(ShardState::Kind kind) {
  constexpr const char* kNames[kShardStateKinds] = {"done",    "queued", "running", "failed",
                                                    "missing", "bad",    "waiting"};
  return kNames[static_cast<int>(kind)];
}

std::vector<uint64_t> FindShardsToResubmit(const std::vector<ShardState>& states) {
  std::vector<uint64_t> shards;
  for (uint64_t k = 0; k < states.size(); ++k) {
    const ShardState::Kind kind = states[k].kind;
    if (kind == ShardState::Kind::kFailed || kind == ShardState::Kind::kMissing ||
        kind == ShardState::Kind::kBad) {
      shards.push_back(k);
    }
  }
  return shards;
}

}  // namespace prs::campaign
