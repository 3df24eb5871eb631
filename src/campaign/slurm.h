// Campaigns on Slurm (docs/cluster.md): the job-array script, the record of each submission
// (DIR/slurm/submit-N.sh and .json), what squeue says about the campaign's array tasks, and each
// shard's state from its files and the queue together — what `prs campaign status` prints and
// what `prs campaign resume` resubmits.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "campaign/campaign.h"

namespace prs::campaign {

/// What `prs campaign slurm` puts in the job script.
struct SlurmOptions {
  std::string partition;  // --partition, when set
  std::string time;       // --time (e.g. "01:00:00"), when set
  std::string mem;        // --mem (e.g. "4G"), when set
  int cpus_per_task = 1;  // --cpus-per-task; run-shard uses as many threads
  int max_running = 0;    // the array's % throttle, when > 0
  std::string prs;        // the prs program to run (an absolute path)
  std::string extra;      // more sbatch arguments, given to sbatch as they are
};

/// The sbatch script of a job array with one task per shard in `shards` (all >= `offset`; the
/// array's indices are shard - offset, so that they stay below Slurm's MaxArraySize), named
/// SlurmJobName(spec), each task running `prs campaign run-shard DIR OFFSET+INDEX` with its
/// output in DIR/logs/shard-K.JOB.out and .err (JOB: the array's job id, so a resubmission
/// keeps the earlier logs) and Slurm's own messages in DIR/logs/slurm-JOB_INDEX.out. `dir`
/// should be absolute.
std::string FormatSlurmScript(const std::string& dir, const CampaignSpec& spec,
                              const std::vector<uint64_t>& shards, uint64_t offset,
                              const SlurmOptions& options);

/// Cuts `shards` (ascending) into the arrays of one submission: each a run of shards whose
/// indices from its first shard stay below `max_array_size` (Slurm's MaxArraySize).
std::vector<std::vector<uint64_t>> SplitIntoArrays(const std::vector<uint64_t>& shards,
                                                   uint64_t max_array_size);

/// Slurm's MaxArraySize from `scontrol show config`, or 1001 (its default) when it cannot be
/// asked.
uint64_t QueryMaxArraySize();

/// "prs-" and the first 8 characters of the campaign id: how squeue finds the campaign's jobs.
std::string SlurmJobName(const CampaignSpec& spec);

/// One accepted sbatch: DIR/slurm/submit-N.sh and its record DIR/slurm/submit-N.json.
struct SlurmSubmission {
  int number = 0;                // N
  std::string job_id;            // the array job id sbatch printed
  std::vector<uint64_t> shards;  // the shards: array index + offset
  uint64_t offset = 0;           // the shard of array index 0
  SlurmOptions options;
  int64_t generation = -1;  // search campaigns: the generation the shards belong to
  std::string next_job_id;  // search campaigns: the job that plans and submits the next
};

/// A search campaign's next step on Slurm: a job that waits for the array `job_id` to end
/// (`--dependency=afterany`) and then runs `prs campaign resume DIR --chained`, which plans the
/// next generation and submits it with its own next step (DIR/slurm/next-N.sh, logs in
/// DIR/logs/next-N.out and .err).
std::string FormatNextStepScript(const std::string& dir, const CampaignSpec& spec, int number,
                                 const std::string& job_id, const SlurmOptions& options);

/// Writes the script of submission `number` (DIR/slurm/NAME-N.sh: "submit" for a job array,
/// "next" for a search's next step) atomically and creates DIR/logs; returns its path.
std::string WriteSlurmScript(const std::string& dir, int number, const std::string& script,
                             const char* name = "submit");

/// The next free N of DIR/slurm/submit-N.sh.
int FindNextSubmissionNumber(const std::string& dir);

/// Records an accepted submission (DIR/slurm/submit-N.json, atomically).
void WriteSubmission(const std::string& dir, const SlurmSubmission& submission);

/// Every recorded submission, oldest first. A record that cannot be read is skipped.
std::vector<SlurmSubmission> ReadSubmissions(const std::string& dir);

/// Runs `sbatch --parsable [extra] SCRIPT` and returns the job id it prints. Throws
/// CampaignError when sbatch is not installed or refuses the job (with its message).
std::string SubmitToSlurm(const std::string& script, const std::string& extra);

/// One array task as squeue lists it.
struct QueuedTask {
  std::string job_id;   // the array job id
  std::string state;    // Slurm's word: PENDING, RUNNING, CANCELLED, FAILED, TIMEOUT, ...
  std::string reason;   // squeue's %r (why pending), or "None"
  uint64_t index = 0;   // the array index (the shard minus its submission's offset)
  bool active() const;  // still queued or running (the shard may yet be written)
};

/// What squeue says about a campaign: for each shard, its task of the latest submission squeue
/// still knows. `available` is false (and `why_not` says why) when squeue could not be asked.
struct SlurmQueue {
  bool available = false;
  std::string why_not;
  std::map<uint64_t, QueuedTask> tasks;
  /// Search campaigns: the recorded next-step jobs still queued or running (never the job that
  /// asks, $SLURM_JOB_ID).
  std::vector<std::string> next_steps;
};

/// Parses `squeue --noheader --array --states=all --format=%F|%K|%T|%r` lines (%F: the array's
/// job id; %A would be each task's own), keeping the tasks of the given array jobs, each
/// mapped to its shard (index + the job's offset); for a shard listed twice, the later job wins.
std::map<uint64_t, QueuedTask> ParseSqueueLines(const std::string& text,
                                                const std::map<std::string, uint64_t>& offsets);

/// Asks squeue about the campaign's recorded submissions and next steps (none recorded:
/// available, empty).
SlurmQueue QuerySlurmQueue(const std::string& dir, const CampaignSpec& spec);

/// A shard's state from its files and the queue together.
struct ShardState {
  enum class Kind {
    kDone,     // written and checked
    kQueued,   // its array task waits in the queue
    kRunning,  // its array task runs (or a .partial file exists and the queue is not known)
    kFailed,   // submitted, no longer in the queue, not written: cancelled, killed, timed out
    kMissing,  // never submitted (as far as the records show), not written
    kBad,      // a written file that cannot be trusted (CheckShard's reason)
    kWaiting,  // a search campaign's shard whose generation cannot be planned yet (the one
               // before it is not done)
  } kind = Kind::kMissing;
  std::string why;  // what the files, squeue and the task's log say
};

/// "done", "queued", "running", "failed", "missing", "bad", "waiting": what status prints.
const char* ShardStateName(ShardState::Kind kind);
constexpr int kShardStateKinds = 7;

/// Every shard's state. `queue` may be unavailable (then running/failed come from files only).
std::vector<ShardState> DescribeShards(const std::string& dir, const CampaignSpec& spec,
                                       const SlurmQueue& queue);

/// The shards `prs campaign resume` submits again: neither done nor queued nor running nor
/// waiting.
std::vector<uint64_t> FindShardsToResubmit(const std::vector<ShardState>& states);

}  // namespace prs::campaign
