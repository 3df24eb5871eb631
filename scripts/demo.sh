#!/usr/bin/env bash
# Sets up, builds (Release) and samples five scenes of the paper's Table-Cube scenario.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh release >/dev/null
./build/src/cli/prs sample examples/table_cube.prs -n 5 -s 1
