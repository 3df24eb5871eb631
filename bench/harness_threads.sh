#!/usr/bin/env bash
# Whether `prs test` and `prs search` keep every thread busy to the end of a run, on any
# machine: the controller's episode is 50 ms of waiting (bench/waiting_controller.py, a
# persistent worker per thread), so T threads can all wait at once even on 2 cores, and the
# harness's share of busy time is measured apart from the CPU count. For each thread count:
# episodes/min of `prs test` and of `prs search` (generations of 2 x T), and the busy share,
# episodes x 50 ms / (threads x wall time); a worker's start-up (Python's, ~0.1 s) counts as
# idle.
#
#   usage (from the repository root): bench/harness_threads.sh [THREADS...]   (default: 1 4 16 32)
#   environment: PRS=path/to/prs (default build/src/cli/prs)
#                EPISODES=N episodes per thread (default 40)
#                PRS_BENCH_EPISODE_S=S the episode's wait (default 0.05)
# Prints a Markdown table (docs/benchmarks.md, "Every thread busy").
set -euo pipefail
prs=${PRS:-build/src/cli/prs}
per_thread=${EPISODES:-40}
episode_s=${PRS_BENCH_EPISODE_S:-0.05}
export PRS_BENCH_EPISODE_S=$episode_s
threads_list=("$@")
[ ${#threads_list[@]} -eq 0 ] && threads_list=(1 4 16 32)
controller="/usr/bin/python3 bench/waiting_controller.py"

# Wall seconds of one command, its output thrown away.
wall() {
  local start end
  start=$(date +%s.%N)
  "$@" > /dev/null 2>&1
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN { print b - a }'
}

echo "| threads | episodes | \`prs test\` episodes/min | busy | \`prs search\` episodes/min | busy |"
echo "|---|---|---|---|---|---|"
for t in "${threads_list[@]}"; do
  n=$((per_thread * t))
  test_s=$(wall "$prs" test examples/table_cube.prs --exec "$controller" --persistent \
    -n "$n" -s 1 --threads "$t" -q)
  search_s=$(wall "$prs" search examples/table_cube.prs --exec "$controller" --persistent \
    --budget "$n" --batch $((2 * t)) -s 1 --threads "$t" -q)
  row() { # wall seconds -> "episodes/min | busy %"
    awk -v n="$n" -v t="$t" -v e="$episode_s" -v s="$1" \
      'BEGIN { printf "%.0f | %.0f%%", n * 60 / s, 100 * n * e / (t * s) }'
  }
  echo "| $t | $n | $(row "$test_s") | $(row "$search_s") |"
done
echo
echo "$(nproc) cores ($(lscpu | sed -n 's/^Model name: *//p')), $(date +%F), $prs," \
  "episodes of ${episode_s} s"
