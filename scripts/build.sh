#!/usr/bin/env bash
# Configures and builds one flavour of the project.
# Usage: scripts/build.sh [release|asan|fuzz] [TARGET...]   (no TARGET: everything the flavour has)
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
           cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >/dev/null ;;
  asan)    dir=build-asan
           cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DPRS_SANITIZE=ON \
             -DPRS_BUILD_BENCHMARKS=OFF -DCMAKE_CXX_FLAGS="-O1" "${launcher[@]}" >/dev/null ;;
  fuzz)    dir=build-fuzz
           cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
             -DCMAKE_CXX_COMPILER=clang++ -DPRS_BUILD_FUZZERS=ON -DPRS_BUILD_BENCHMARKS=OFF \
             "${launcher[@]}" >/dev/null ;;
  *) echo "usage: scripts/build.sh [release|asan|fuzz] [TARGET...]" >&2; exit 2 ;;
esac
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build "$dir" -j"$jobs" "${targets[@]}"
