#!/usr/bin/env bash
# How sampling and the simulated case study scale with threads: for each thread count, scenes/s
# of `prs sample` on four examples and episodes/min of `prs test --controller table-cube`, with
# the speed-up over the first thread count, and a check that the scenes are byte-identical for
# every thread count (SHA-256 of a shorter run).
#
#   usage (from the repository root): bench/scaling.sh [THREADS...]     (default: 1 2)
#   environment: PRS=path/to/prs (default build/src/cli/prs; a bundle's OUT/prs works too)
#                SCALE=F multiplies every scene and episode count (default 1; 0.1 for a quick look)
#                EPISODES=0 skips the case study
# Prints a Markdown table (docs/benchmarks.md, "Scaling with threads"). Wall times are what
# count: run it on an otherwise idle machine, and compare figures only within one run.
set -euo pipefail
cd "$(dirname "$0")/.."
prs=${PRS:-build/src/cli/prs}
scale=${SCALE:-1}
threads=("$@")
((${#threads[@]})) || threads=(1 2)
[ -x "$prs" ] || { echo "scaling.sh: $prs is not built (scripts/build.sh app)" >&2; exit 1; }

count() { awk -v n="$1" -v s="$scale" 'BEGIN { c = int(n * s); print (c < 1 ? 1 : c) }'; }
seconds() {  # wall seconds of a command, its output discarded
  local begin end
  begin=$(date +%s.%N)
  "$@" >/dev/null 2>&1 || { echo "scaling.sh: failed: $*" >&2; exit 1; }
  end=$(date +%s.%N)
  awk -v a="$begin" -v b="$end" 'BEGIN { printf "%.3f", b - a }'
}

# The end of a table row: the speed-up of the last rate over the first, and whether every
# thread count gave the same digest.
end_row() {
  local same=yes d
  for d in "${digests[@]}"; do [ "$d" = "${digests[0]}" ] || same=NO; done
  echo "$row $(awk -v a="$first" -v b="$last" 'BEGIN { printf "%.2f×", b / a }') | $same |"
}

# example and scene count: counts chosen for a few seconds a run on one core
samples=("table_cube.prs $(count 2000000)"
         "table_cube_reachable_visible.prs $(count 400000)"
         "pantry_shapes.prs $(count 200000)"
         "kitchen_meshes.prs $(count 150000)")
episodes=$(count "${EPISODES:-320}")

header="| work |"; rule="|---|"
for t in "${threads[@]}"; do header+=" $t |"; rule+="---|"; done
header+=" ${threads[-1]} vs ${threads[0]} | same scenes |"; rule+="---|---|"
echo "$header"; echo "$rule"

for entry in "${samples[@]}"; do
  read -r file n <<<"$entry"
  row="| \`prs sample $file -n $n\` scenes/s |"
  first= last= digests=()
  for t in "${threads[@]}"; do
    s=$(seconds "$prs" sample "examples/$file" -n "$n" -s 1 --threads "$t" -q -o /dev/null)
    rate=$(awk -v n="$n" -v s="$s" 'BEGIN { printf "%.0f", n / s }')
    row+=" $rate |"; first=${first:-$rate}; last=$rate
    digests+=("$("$prs" sample "examples/$file" -n "$(( n / 20 + 1 ))" -s 1 --threads "$t" -q | sha256sum | cut -c1-16)")
  done
  end_row
done

if [ "$episodes" != 0 ] && [ "${EPISODES:-320}" != 0 ]; then
  row="| \`prs test table_cube.prs --controller table-cube -n $episodes\` episodes/min |"
  first= last= digests=()
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  for t in "${threads[@]}"; do
    s=$(seconds "$prs" test examples/table_cube.prs --controller table-cube -n "$episodes" -s 1 \
        --threads "$t" -q -o "$tmp/episodes_$t.jsonl")
    rate=$(awk -v n="$episodes" -v s="$s" 'BEGIN { printf "%.0f", 60 * n / s }')
    row+=" $rate |"; first=${first:-$rate}; last=$rate
    # Records carry each episode's wall time; everything else must match.
    digests+=("$(sed 's/"wall_s":[0-9.e+-]*,//' "$tmp/episodes_$t.jsonl" | sha256sum | cut -c1-16)")
  done
  end_row
fi
echo
echo "$(nproc) cores ($(lscpu | sed -n 's/^Model name: *//p' | head -1)), $(date -u +%Y-%m-%d), $prs"
