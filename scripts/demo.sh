#!/usr/bin/env bash
# The first five minutes: installs only what the `prs` program needs (scripts/setup.sh app),
# builds only `prs` (scripts/build.sh app), then shows the main job on the paper's Table-Cube
# scenario (examples/table_cube.prs): 10,000 scenes written to a file, a picture of nine of
# them, and 30 episodes of the simulated case study with their outcome table. Everything it
# writes goes to out/demo/. A second run installs and rebuilds nothing and takes seconds.
# Usage: scripts/demo.sh
set -euo pipefail
cd "$(dirname "$0")/.."
started=$SECONDS
out=out/demo
prs=build/src/cli/prs
spec=examples/table_cube.prs
mkdir -p "$out"

echo "demo: installing what prs needs (Debian packages, only those missing)" >&2
scripts/setup.sh app
echo "demo: building prs (a few minutes the first time; log in $out/build.log)" >&2
if ! scripts/build.sh app >"$out/build.log" 2>&1; then
  tail -n 40 "$out/build.log" >&2
  echo "demo: the build failed; the whole log is $out/build.log" >&2
  exit 1
fi

# The commands' own summaries (on stderr, "prs: ...") are what the screen shows.
note() { sed -n 's/^prs: //p' "$1"; }

echo "demo: sampling, drawing and testing" >&2
"$prs" sample "$spec" -n 10000 -s 1 -o "$out/table_cube.jsonl" 2>"$out/sample.txt"
"$prs" render "$spec" -n 9 -s 1 --grid -o "$out/table_cube_grid.png" 2>"$out/render.txt"
"$prs" test "$spec" --controller table-cube -n 30 -s 1 -o "$out/episodes.jsonl" \
  >"$out/outcomes.txt" 2>"$out/test.txt"

cat <<EOF

ProbRobScene on the paper's Table-Cube scenario ($spec)

1. Scenes: every one satisfies all of the scenario's relations, drawn exactly, reproducibly
   $out/table_cube.jsonl (one JSON line per scene)
   $(note "$out/sample.txt")

2. A picture of scenes 0-8 of seed 1, drawn offscreen (no GPU, no display)
   $out/table_cube_grid.png

3. A controller tested in 30 scenes: the paper's case study simulated in MuJoCo
   (two Franka Panda arms, a ceiling RGB-D camera, perception, inverse kinematics)
$(sed 's/^/   /' "$out/outcomes.txt")
   $(note "$out/test.txt")
   one record per episode, each failure with the command that regenerates its scene:
   $out/episodes.jsonl

Next, try:
   $prs view $spec -s 1        # the scenes in 3D in your browser
   $prs check $spec            # what the scenario places where, and what varies
   $prs test $spec --exec 'python3 examples/controllers/reach_check.py' -n 100 -s 1
                                # your own controller: scene JSON in, outcome out (docs/harness.md)
   $prs render $spec --view camera:Camera -o rgb.png   # what the robot's camera sees
   $prs test examples/table_cube_paper_model.prs --controller table-cube-paper -n 100 -s 1
                                # the paper's Table III: the original's files and controller
   $prs search $spec --controller planted-1-permille --budget 1000 -o found.jsonl
                                # search for failures instead of sampling blindly (docs/search.md)
   $prs campaign init camp $spec --controller table-cube -n 2000 --shard-size 100 -s 1
                                # a run cut into shards for Slurm or Dask (docs/cluster.md)
   docs/language.md (the language), docs/case_study.md (the failures and a fix), docs/cli.md

demo: done in $((SECONDS - started)) s
EOF
