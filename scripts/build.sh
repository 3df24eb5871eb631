#!/usr/bin/env bash
# Configures and builds one flavour of the project. Usage: scripts/build.sh [release|asan|fuzz]
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${PRS_JOBS:-2}
case "${1:-release}" in
  release) cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
           cmake --build build -j"$jobs" ;;
  asan)    cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DPRS_SANITIZE=ON \
             -DPRS_BUILD_BENCHMARKS=OFF -DCMAKE_CXX_FLAGS="-O1" >/dev/null
           cmake --build build-asan -j"$jobs" ;;
  fuzz)    cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
             -DCMAKE_CXX_COMPILER=clang++ -DPRS_BUILD_FUZZERS=ON -DPRS_BUILD_BENCHMARKS=OFF >/dev/null
           cmake --build build-fuzz -j"$jobs" ;;
  *) echo "usage: scripts/build.sh [release|asan|fuzz]" >&2; exit 2 ;;
esac
