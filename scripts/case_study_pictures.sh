#!/usr/bin/env bash
# Regenerates the pictures of docs/case_study.md from the Release build (build/): scenes drawn
# by `prs render`, and what the controller's ceiling camera sees in the simulated world
# (build/src/sim/prs_camera_snapshot). Usage: scripts/case_study_pictures.sh
set -euo pipefail
cd "$(dirname "$0")/.."
build=${PRS_BUILD_DIR:-build}
cmake --build "$build" -j2 --target prs prs_camera_snapshot
out=docs/images/case_study
mkdir -p "$out"
prs=$build/src/cli/prs
snapshot=$build/src/sim/prs_camera_snapshot
# One scene per outcome of `prs test examples/table_cube.prs --controller table-cube -n 100 -s 1`,
# and the original model's cube against its tray's end wall (a poor grip of both controllers).
for scene in "0 success" "19 perception-fault" "39 poor-grip"; do
  set -- $scene
  "$prs" render examples/table_cube.prs -s 1 --start "$1" -n 1 --size 480x360 -q -o "$out/$2-$1.png"
done
"$prs" render examples/table_cube_paper_model.prs -s 1 --start 54 -n 1 --size 480x360 -q \
  -o "$out/paper-model-poor-grip-54.png"
"$snapshot" examples/table_cube.prs 1 4 "$out/camera-partly-out-of-view-4.png"
"$snapshot" examples/table_cube_high_camera.prs 1 19 "$out/camera-hidden-by-arm-19.png"
# The example with reachable by / visible from: where its cube and right tray may be, and the
# camera's view, from above.
"$prs" render examples/table_cube_reachable_visible.prs -s 1 --start 0 -n 1 --show-regions \
  --view top --size 640x400 -q -o "$out/reachable-visible-regions-0.png"
echo "case_study_pictures: wrote $(ls "$out" | wc -l) pictures in $out"
