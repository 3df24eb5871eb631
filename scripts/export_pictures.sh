#!/usr/bin/env bash
# Makes the pictures of docs/export.md: scenes exported by `prs export --format mjcf`, loaded
# and drawn by MuJoCo (prs_mjcf_snapshot), as exported and after one second of simulation.
# Usage: scripts/export_pictures.sh   (after scripts/build.sh release)
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --build build -j"${PRS_JOBS:-2}" --target prs prs_mjcf_snapshot
prs=build/src/cli/prs
snapshot=build/src/export/prs_mjcf_snapshot
out=docs/images
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
"$prs" export examples/table_cube.prs -s 1 -o "$tmp/table_cube.xml" -q
"$snapshot" "$tmp/table_cube.xml" "$out/export_mujoco_table_cube.png"
"$prs" export examples/constructs.prs -s 1 -o "$tmp/constructs.xml" -q
"$snapshot" "$tmp/constructs.xml" "$out/export_mujoco_constructs_0s.png"
"$snapshot" "$tmp/constructs.xml" "$out/export_mujoco_constructs_1s.png" 1
