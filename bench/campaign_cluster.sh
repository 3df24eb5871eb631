#!/usr/bin/env bash
# Campaign throughput and overhead on this machine (docs/benchmarks.md, docs/cluster.md): a
# single-node Slurm started for the run (tests/slurm/cluster.sh), then
#   - the overhead per shard: init, submission (sbatch), run-shard's start (a 1-scene shard),
#     status and merge of a 200-shard campaign;
#   - an N-episode --controller table-cube campaign in shards of B on Slurm with at most 1 and
#     at most 2 tasks at once (one CPU each), on a Dask LocalCluster of 2 worker processes, and
#     one machine's `prs test` on 2 threads for reference; each merged campaign is checked
#     against that run (every field but wall_s);
#   - a `prs estimate --budget N` of --controller table-cube as an estimate campaign in shards of
#     B, on Slurm (at most 2 tasks of one CPU) and on the Dask LocalCluster, against one
#     machine's `prs estimate` on 2 threads; each merge is checked against it.
# Needs root and the packages of scripts/setup.sh. Takes about 20 minutes with the defaults
# (PART "test": the first two; "estimate": the last; "all", the default: every part).
# Usage: bench/campaign_cluster.sh [PRS_BINARY] [N] [B] [PART]
set -euo pipefail
cd "$(dirname "$0")/.."
prs=$(realpath "${1:-build/src/cli/prs}")
n=${2:-2000}
shard=${3:-100}
part=${4:-all}
example=$PWD/examples/table_cube.prs
python=${PRS_PYTHON:-/usr/bin/python3}  # Debian's, which has python3-distributed
work=$(mktemp -d /tmp/prs_campaign_bench.XXXXXX)
chmod 755 "$work"
trap 'tests/slurm/cluster.sh stop "$work/cluster" || true; rm -rf "$work"' EXIT
eval "$(tests/slurm/cluster.sh start "$work/cluster")"
export SLURM_CONF

now() { date +%s.%N; }
since() { python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.2f}')" "$1" "$(now)"; }
wait_done() {  # wait_done DIR SHARDS
  until "$prs" campaign status "$1" 2>/dev/null | grep -q "^$1: $2 of $2 done"; do sleep 0.5; done
}
same_records() {
  python3 - "$1" "$2" <<'EOF'
import json, sys
def records(path):
    return [{k: v for k, v in json.loads(line).items() if k != "wall_s"} for line in open(path)]
assert records(sys.argv[1]) == records(sys.argv[2]), "the merged campaign differs"
EOF
}

if [[ $part != estimate ]]; then
echo "== overhead per shard (200 shards of 1 scene)"
t=$(now); "$prs" campaign init "$work/small" "$example" -n 200 --shard-size 1 -s 1 2>/dev/null
echo "init: $(since "$t") s"
t=$(now); for k in $(seq 0 49); do "$prs" campaign run-shard "$work/small" "$k" --threads 1; done
echo "run-shard of a 1-scene shard, start to end: $(python3 -c "print(f'{($(since "$t")) / 50 * 1000:.1f}')") ms"
t=$(now); "$prs" campaign slurm "$work/small" --max-running 2 >/dev/null 2>&1
echo "prs campaign slurm (write the script, sbatch an array of 150): $(since "$t") s"
wait_done "$work/small" 200
t=$(now); "$prs" campaign status "$work/small" >/dev/null 2>&1; echo "status of 200 shards (with squeue): $(since "$t") s"
t=$(now); "$prs" campaign merge "$work/small" -o "$work/small.jsonl" 2>/dev/null
echo "merge of 200 shards: $(since "$t") s"

echo "== $n episodes of table-cube in shards of $shard"
t=$(now); "$prs" test "$example" --controller table-cube -n "$n" -s 1 --threads 2 -q \
  -o "$work/single.jsonl" >/dev/null
echo "one machine, prs test --threads 2: $(since "$t") s"
for running in 1 2; do
  dir=$work/slurm$running
  "$prs" campaign init "$dir" "$example" --controller table-cube -n "$n" --shard-size "$shard" \
    -s 1 2>/dev/null
  shards=$(( (n + shard - 1) / shard ))
  t=$(now)
  "$prs" campaign slurm "$dir" --max-running "$running" --cpus-per-task 1 >/dev/null 2>&1
  wait_done "$dir" "$shards"
  echo "Slurm, at most $running task(s) of 1 CPU: $(since "$t") s"
  "$prs" campaign merge "$dir" -o "$dir.jsonl" >/dev/null 2>&1
  same_records "$dir.jsonl" "$work/single.jsonl"
done
PYTHONPATH=${PYTHONPATH:-$PWD/build/python} "$python" bench/campaign_dask.py "$work" "$example" "$n" \
  "$shard"
same_records "$work/dask.jsonl" "$work/single.jsonl"
fi

if [[ $part != test ]]; then
echo "== an estimate of $n episodes of table-cube in shards of $shard"
t=$(now); "$prs" estimate "$example" --controller table-cube --budget "$n" -s 1 --threads 2 -q \
  -o "$work/estimate_single.jsonl" >/dev/null
echo "one machine, prs estimate --threads 2: $(since "$t") s"
dir=$work/estimate_slurm
"$prs" campaign init "$dir" "$example" --controller table-cube -n "$n" --shard-size "$shard" \
  -s 1 --estimate 2>&1 | tail -1
shards=$("$prs" campaign status "$dir" 2>/dev/null | sed -n 's/.* of \([0-9]*\) done.*/\1/p')
t=$(now)
"$prs" campaign slurm "$dir" --max-running 2 --cpus-per-task 1 >/dev/null 2>&1
wait_done "$dir" "$shards"
echo "Slurm, at most 2 tasks of 1 CPU, $shards shards: $(since "$t") s"
"$prs" campaign merge "$dir" -o "$dir.jsonl" >/dev/null 2>&1
same_records "$dir.jsonl" "$work/estimate_single.jsonl"
PYTHONPATH=${PYTHONPATH:-$PWD/build/python} "$python" bench/campaign_dask.py "$work" "$example" \
  "$n" "$shard" estimate
same_records "$work/dask_estimate.jsonl" "$work/estimate_single.jsonl"
fi
echo "every merged campaign equals one machine's run"
