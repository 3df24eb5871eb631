#!/usr/bin/env bash
# Configures and builds one flavour of the project.
# Usage: scripts/build.sh [release|app|asan|fuzz] [TARGET...]   (no TARGET: everything the flavour has)
#   release: build/, Release, everything (tests, benchmarks, the Python package)
#   app:     build/, Release, the prs program only (no tests, benchmarks or Python; scripts/demo.sh)
#   asan:    build-asan/, AddressSanitizer + UndefinedBehaviorSanitizer, the tests
#   fuzz:    build-fuzz/, clang with libFuzzer, the fuzz target
# Compiles through ccache when it is installed (scripts/setup.sh installs it); the cache is keyed
# relative to the repository root, so a fresh clone on the same machine reuses earlier objects.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${PRS_JOBS:-2}
flavour=${1:-release}
shift || true

launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR=$PWD CCACHE_NOHASHDIR=1 CCACHE_MAXSIZE=${CCACHE_MAXSIZE:-8G}
fi

case "$flavour" in
  release) dir=build
           cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DPRS_BUILD_TESTS=ON \
             -DPRS_BUILD_BENCHMARKS=ON -DPRS_BUILD_PYTHON=ON "${launcher[@]}" >/dev/null ;;
  app)     dir=build  # the same objects as release: switching between the two recompiles nothing
           cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DPRS_BUILD_TESTS=OFF \
             -DPRS_BUILD_BENCHMARKS=OFF -DPRS_BUILD_PYTHON=OFF "${launcher[@]}" >/dev/null
           (($#)) || set -- prs ;;
  asan)    dir=build-asan
           cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DPRS_SANITIZE=ON \
             -DPRS_BUILD_BENCHMARKS=OFF -DCMAKE_CXX_FLAGS="-O1" "${launcher[@]}" >/dev/null ;;
  fuzz)    dir=build-fuzz
           cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
             -DCMAKE_CXX_COMPILER=clang++ -DPRS_BUILD_FUZZERS=ON -DPRS_BUILD_BENCHMARKS=OFF \
             "${launcher[@]}" >/dev/null ;;
  *) echo "usage: scripts/build.sh [release|app|asan|fuzz] [TARGET...]" >&2; exit 2 ;;
esac
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build "$dir" -j"$jobs" "${targets[@]}"
