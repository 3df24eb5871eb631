#!/usr/bin/env bash
# A campaign on a real single-node Slurm (tests/slurm/cluster.sh), as docs/cluster.md walks it:
# init a 9-shard Table-Cube test campaign, submit it as a job array (at most 2 tasks at once),
# cancel one running task with scancel and SIGKILL another task's prs, check that `prs campaign
# status` reports both as failed, `prs campaign resume`, wait, merge, and compare the merged
# records with one machine's `prs test` of the same N and seed (every field but wall_s). Then a
# search campaign (three generations, each a job array and a next-step job that plans and
# submits the next) with one task cancelled: merged, it equals one machine's `prs search`. And an
# estimate campaign (six generations chained the same way): merged, its records and its printed
# estimate equal one machine's `prs estimate`. And a dataset campaign: merged, one machine's
# `prs dataset`, byte for byte.
# Without root or Slurm's packages it prints SKIPPED and the reason, and exits 0; on Debian 12
# as root after scripts/setup.sh it must run.
# Usage: tests/slurm/campaign_test.sh PRS_BINARY
set -euo pipefail
prs=$(realpath "${1:?usage: tests/slurm/campaign_test.sh PRS_BINARY}")
cd "$(dirname "$0")/../.."
example=$PWD/examples/table_cube.prs

skip() {
  echo "=================================================================" >&2
  echo "slurm campaign test: SKIPPED: $*" >&2
  echo "(install munge slurmctld slurmd slurm-client and run as root to test)" >&2
  echo "=================================================================" >&2
  exit 0
}
[[ $(id -u) -eq 0 ]] || skip "not root (slurmd must start jobs as their user)"
for program in munged slurmctld slurmd sbatch; do
  PATH=$PATH:/usr/sbin command -v "$program" >/dev/null || skip "$program is not installed"
done

work=$(mktemp -d /tmp/prs_slurm_test.XXXXXX)
chmod 755 "$work"
cleanup() {
  tests/slurm/cluster.sh stop "$work/cluster" || true
  rm -rf "$work"
}
trap cleanup EXIT
eval "$(tests/slurm/cluster.sh start "$work/cluster")"  # sets SLURM_CONF
export SLURM_CONF

fail() {
  echo "slurm campaign test: FAILED: $*" >&2
  echo "--- squeue:" >&2; squeue --array --states=all >&2 || true
  echo "--- slurmctld.log (end):" >&2; tail -20 "$work/cluster/log/slurmctld.log" >&2 || true
  exit 1
}
# wait_for SECONDS COMMAND...: polls COMMAND every 0.2 s until it succeeds.
wait_for() {
  local seconds=$1
  shift
  for _ in $(seq $((seconds * 5))); do "$@" && return 0; sleep 0.2; done
  return 1
}
task_state() { squeue --noheader --array --states=all --jobs="$1" --format='%K %T' 2>/dev/null; }
is_running() { task_state "$1" | grep -q "^$2 RUNNING$"; }
shard_process() { pgrep -f "campaign run-shard $camp $1 " >/dev/null; }
shard_gone() { ! shard_process "$1"; }
ended_as() { task_state "$1" | grep -q "^$2 $3$"; }
campaign_idle() { ! squeue --noheader --array --jobs="$1" --states=PENDING,RUNNING,COMPLETING \
  --format=%T 2>/dev/null | grep -q .; }

camp=$work/camp
n=100
"$prs" campaign init "$camp" "$example" --controller table-cube -n $n --shard-size 12 -s 7
job=$("$prs" campaign slurm "$camp" --max-running 2 --time 00:10:00)
echo "slurm campaign test: submitted job $job" >&2

# Cancel shard 0's task while it runs; SIGKILL shard 1's prs (a node losing the process).
wait_for 60 is_running "$job" 0 || fail "shard 0 never ran"
scancel "${job}_0"
wait_for 60 shard_process 1 || fail "shard 1's prs never started"
pkill -KILL -f "campaign run-shard $camp 1 " || fail "could not kill shard 1's prs"
wait_for 30 shard_gone 1 || fail "shard 1's prs lives on after SIGKILL"
wait_for 60 ended_as "$job" 0 CANCELLED || fail "Slurm did not record shard 0 as cancelled"
wait_for 60 ended_as "$job" 1 FAILED || fail "Slurm did not record shard 1 as failed"

status=$("$prs" campaign status "$camp")
echo "$status" >&2
grep -q "^shard 0: failed: Slurm job ${job}_0 ended CANCELLED" <<<"$status" ||
  fail "status does not report the cancelled shard 0"
grep -q "^shard 1: failed: Slurm job ${job}_1 ended FAILED" <<<"$status" ||
  fail "status does not report the killed shard 1"

wait_for 240 campaign_idle "$job" || fail "the job array did not finish in 240 s"
status=$("$prs" campaign status "$camp" 2>&1)
grep -q "7 of 9 done, 0 queued, 0 running, 2 failed" <<<"$status" || fail "after the array: $status"
resumed=$("$prs" campaign resume "$camp")
grep -q "#SBATCH --array=0-1%2" "$camp/slurm/submit-1.sh" || fail "resume did not submit 0 and 1"
grep -q "#SBATCH --time=00:10:00" "$camp/slurm/submit-1.sh" || fail "resume lost --time"
wait_for 240 campaign_idle "$resumed" || fail "the resumed array did not finish in 240 s"
status=$("$prs" campaign status "$camp" 2>&1)
grep -q "9 of 9 done" <<<"$status" || fail "after resume: $status"
"$prs" campaign merge "$camp" -o "$work/merged.jsonl"

"$prs" test "$example" --controller table-cube -n $n -s 7 -o "$work/single.jsonl" >/dev/null
same_records() {  # same_records A.jsonl B.jsonl N: equal in every field but wall_s
  python3 - "$@" <<'EOF'
import json, sys
def records(path):
    out = []
    for line in open(path):
        r = json.loads(line)
        r.pop("wall_s", None)
        out.append(r)
    return out
merged, single = records(sys.argv[1]), records(sys.argv[2])
assert len(merged) == len(single) == int(sys.argv[3]), (len(merged), len(single))
for i, (a, b) in enumerate(zip(merged, single)):
    assert a == b, f"record {i} differs"
print(f"slurm campaign test: {len(merged)} merged records equal one machine's run but wall_s",
      file=sys.stderr)
EOF
}
same_records "$work/merged.jsonl" "$work/single.jsonl" $n || fail "merged != one machine's run"

# A search campaign on Slurm: three generations of 20 in shards of 10; the next-step job of
# generation 0 submits generation 1, one of whose tasks is cancelled as it runs; the next step
# after that submits it again. The controller sleeps 0.4 s an episode and answers from the
# episode's index: a shard takes 4 s without using the CPUs, so the test sees its task running
# and cancels it well before it ends (with the simulated case study, two tasks kept both CPUs
# busy and the test, starved, once cancelled a shard that had just been written).
search=$work/search
controller='sleep 0.4; case $((PRS_INDEX % 4)) in 0) echo "{\"outcome\": \"no-path\", \"score\": -1}";;
  *) echo "{\"outcome\": \"success\", \"score\": $((PRS_INDEX % 7 + 1))}";; esac'
"$prs" campaign init "$search" "$example" --exec "$controller" -n 60 --search ce --batch 20 \
  --shard-size 10 -s 3
"$prs" campaign slurm "$search" --max-running 2 >/dev/null
second_array() { [[ -f $search/slurm/submit-1.json ]]; }
wait_for 120 second_array || fail "no next step submitted generation 1"
second=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["job_id"])' \
  "$search/slurm/submit-1.json")
wait_for 60 is_running "$second" 2 || fail "generation 1's shard 2 never ran"
scancel "${second}_2"
search_done() { "$prs" campaign status "$search" 2>/dev/null | grep -q "6 of 6 done"; }
wait_for 300 search_done ||
  fail "the search campaign did not finish: $("$prs" campaign status "$search" 2>&1)"
grep -qx "#SBATCH --array=2%2" "$search"/slurm/submit-2.sh ||
  fail "the cancelled shard 2 was not submitted again: $(cat "$search"/slurm/submit-2.sh)"
"$prs" campaign merge "$search" -o "$work/search_merged.jsonl" >/dev/null
"$prs" search "$example" --exec "$controller" --budget 60 --batch 20 -s 3 -q \
  -o "$work/search_single.jsonl" >/dev/null
same_records "$work/search_merged.jsonl" "$work/search_single.jsonl" 60 ||
  fail "the merged search != one machine's prs search"

# An estimate campaign on Slurm: a budget of 200 is six generations (the search's three of 20,
# the exploration's 20, one round of 16 walks, the sampling's 104 in three shards), each a job
# array chained by next-step jobs. Merged, its records and its estimate are one machine's.
estimate=$work/estimate
"$prs" campaign init "$estimate" "$example" --controller planted-1-percent -n 200 --estimate \
  --shard-size 50 -s 4
"$prs" campaign slurm "$estimate" --max-running 2 >/dev/null
estimate_done() { "$prs" campaign status "$estimate" 2>/dev/null | grep -q "8 of 8 done"; }
wait_for 300 estimate_done ||
  fail "the estimate campaign did not finish: $("$prs" campaign status "$estimate" 2>&1)"
"$prs" campaign merge "$estimate" -o "$work/estimate_merged.jsonl" >"$work/estimate_merged.txt"
"$prs" estimate "$example" --controller planted-1-percent --budget 200 -s 4 -q \
  -o "$work/estimate_single.jsonl" >"$work/estimate_single.txt"
same_records "$work/estimate_merged.jsonl" "$work/estimate_single.jsonl" 200 ||
  fail "the merged estimate's records != one machine's prs estimate"
cmp -s "$work/estimate_merged.txt" "$work/estimate_single.txt" ||
  fail "the merged estimate printed $(cat "$work/estimate_merged.txt"), prs estimate printed \
$(cat "$work/estimate_single.txt")"

# A dataset campaign on Slurm: 5 scenes in 3 shards, each shard a dataset (pictures rendered in
# the Slurm task). Merged, it is one machine's `prs dataset` of the same scenes, byte for byte.
data=$work/dataset
"$prs" campaign init "$data" "$example" --dataset -n 5 --shard-size 2 -s 3 --size 160x120 \
  2>/dev/null
"$prs" campaign slurm "$data" --max-running 2 >/dev/null
data_done() { "$prs" campaign status "$data" 2>/dev/null | grep -q "3 of 3 done"; }
wait_for 300 data_done ||
  fail "the dataset campaign did not finish: $("$prs" campaign status "$data" 2>&1)"
"$prs" campaign merge "$data" -o "$work/data_merged" 2>/dev/null
"$prs" dataset "$example" -n 5 -s 3 --size 160x120 -o "$work/data_single" -q
diff -r "$work/data_merged" "$work/data_single" >/dev/null ||
  fail "the merged dataset campaign differs from one machine's prs dataset"
[[ $(ls "$work/data_merged/train_pbr/000000/rgb" | wc -l) -eq 5 ]] ||
  fail "the merged dataset does not hold 5 pictures"
echo "slurm campaign test: passed" >&2
