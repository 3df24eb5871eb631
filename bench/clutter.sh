#!/usr/bin/env bash
# Clutter side by side: scenes/s of whole-scene rejection, --sampler partial-rejection (exact)
# and --sampler gibbs (effective scenes/s too) on 5 cm cubes at any yaw `completely on` a
# 0.5 x 0.4 m bin (5 to 20 of them) or a 4 x 4 m table (40 to 160, workspace widened to 5 m),
# and on examples/bin_clutter.prs (docs/sampling.md, docs/benchmarks.md "Clutter").
#
#   usage (from the repository root): bench/clutter.sh [ROW...]   (default: every row)
#     rows: bin5 bin8 bin10 bin12 bin15 bin20 table40 table80 table160 bin_clutter
#   environment: PRS=path/to/prs (default build/src/cli/prs), THREADS (default 2)
# Prints a Markdown table. A sampler that gives up (no scene within --max-attempts, or a
# partial-rejection draw past its rounds) shows its error's first words. Compare figures only
# within one run, on an otherwise idle machine.
set -euo pipefail
cd "$(dirname "$0")/.."
prs=${PRS:-build/src/cli/prs}
threads=${THREADS:-2}
[ -x "$prs" ] || { echo "clutter.sh: $prs is not built (scripts/build.sh app)" >&2; exit 1; }
rows=("$@")
((${#rows[@]})) || rows=(bin5 bin8 bin10 bin12 bin15 bin20 table40 table80 table160 bin_clutter)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

program() {  # ROW -> a program file
  local n
  case "$1" in
    bin*)
      n=${1#bin}
      printf 'from model import *\nbin = Table on V3D(0, 0, 0), with width 0.5, with length 0.4\n'
      printf 'for i in range(%s):\n    Cube completely on bin, with yaw Range(0, 2 * math.pi)\n' "$n"
      ;;
    table*)
      n=${1#table}
      printf 'from model import *\nworkspace = Cuboid(Vector3D(0, 0, 1.5), Vector3D(0, 0, 0), 5, 5, 3)\n'
      printf 't = Table on V3D(0, 0, 0), with width 4, with length 4\n'
      printf 'for i in range(%s):\n    Cube completely on t, with yaw Range(0, 2 * math.pi)\n' "$n"
      ;;
  esac
}

# Scenes a run draws, per sampler, so that each takes seconds, not minutes.
counts() {  # ROW -> "rejection partial gibbs"
  case "$1" in
    bin5 | bin8) echo "4000 4000 4000" ;;
    bin10) echo "2000 2000 4000" ;;
    bin12) echo "1000 400 4000" ;;
    bin15) echo "100 50 4000" ;;
    bin20 | bin_clutter) echo "10 10 4000" ;;
    table40) echo "2560 1000 2560" ;;
    table80) echo "1280 300 1280" ;;
    table160) echo "32 128 1280" ;;
  esac
}

# One table cell from `prs stats --json`.
cell_script='
import json, sys
j = json.load(sys.stdin)
cell = "{:,.0f} ({:,.1f} runs)".format(j["scenes_per_second"], j["attempts_per_scene"]["mean"])
if "gibbs" in j:
    cell += ", {:,.0f} effective".format(j["gibbs"]["effective_scenes_per_second"])
if "partial_rejection" in j:
    cell += ", {:.1f} rounds a draw".format(j["partial_rejection"]["mean_rounds"])
print(cell)'

measure() {  # FILE N SAMPLER -> one table cell
  local json
  if ! json=$("$prs" stats "$1" -I examples -n "$2" --threads "$threads" --sampler "$3" \
    --max-attempts 1000000 --json 2>"$work/err"); then
    sed -n '1s/^[^:]*:[0-9]*:[0-9]*: error: //p' "$work/err" | cut -c1-60
    return
  fi
  python3 -c "$cell_script" <<<"$json"
}

echo "| scenes | rejection scenes/s (program runs a scene) | partial-rejection scenes/s | gibbs scenes/s |"
echo "|---|---|---|---|"
for row in "${rows[@]}"; do
  if [ "$row" = bin_clutter ]; then
    file=examples/bin_clutter.prs
  else
    file=$work/$row.prs
    program "$row" >"$file"
  fi
  read -r n_rejection n_partial n_gibbs <<<"$(counts "$row")"
  printf '| %s | %s | %s | %s |\n' "$row" "$(measure "$file" "$n_rejection" rejection)" \
    "$(measure "$file" "$n_partial" partial-rejection)" "$(measure "$file" "$n_gibbs" gibbs)"
done
