#!/usr/bin/env bash
# Sets up, builds and runs every test: the Release build (C++ tests, the simulated case study,
# the headless-Chromium viewer test), a campaign on a real single-node Slurm started for the test
# (tests/slurm/campaign_test.sh), the Python package with a Dask LocalCluster
# (scripts/test_python.sh), the same C++ tests under AddressSanitizer +
# UndefinedBehaviorSanitizer, then libFuzzer: the language stage for 20 s of ordinary inputs and
# 10 s of inputs up to 1 MiB (long chains), the readers of scenes files and controller
# answers for 10 s, URDF robot descriptions for 10 s and mesh files for 10 s (scripts/fuzz.sh).
# Exits non-zero if anything fails.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh release
ctest --test-dir build --output-on-failure -j2
tests/slurm/campaign_test.sh build/src/cli/prs
scripts/test_python.sh
scripts/build.sh asan
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  LSAN_OPTIONS=suppressions=$PWD/tests/asan/lsan.supp \
  ctest --test-dir build-asan --output-on-failure -j2
scripts/fuzz.sh 20
scripts/fuzz.sh 10 long
scripts/fuzz.sh 10 scenes
scripts/fuzz.sh 10 urdf
scripts/fuzz.sh 10 mesh
