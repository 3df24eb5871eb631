#!/usr/bin/env bash
# Builds a libFuzzer target (scripts/build.sh fuzz) and fuzzes it for a bounded time.
# Usage: scripts/fuzz.sh [seconds] [long|scenes|urdf|mesh]   (default 30 s, the language)
#   (none): the language stage (prs_lang_fuzz), inputs up to 4 KiB, from a scratch corpus in
#           build-fuzz/ seeded with examples/, tests/lang/bad/ and tests/fuzz/corpus/;
#   long:   the language stage with inputs up to 1 MiB, from a separate corpus seeded with
#           100,000-term-class chains (tests/fuzz/make_long_seeds.py), for the stack limits;
#   scenes: the readers of other programs' text (prs_scene_json_fuzz): scenes-file lines as
#           prs export and prs render read them, and controller answers, seeded with
#           tests/fuzz/scene_corpus/;
#   urdf:   URDF robot descriptions as `reachable by` loads them (prs_urdf_fuzz), seeded with
#           the kinematics tests' URDF files;
#   mesh:   mesh files as `shape: Mesh(...)` reads them, then collisions and convex pieces
#           (prs_mesh_fuzz), seeded with tests/fuzz/mesh_corpus/ (first byte: the format).
# The language fuzzer computes reachable sets (`reachable by`) on a 10 cm grid, cached in
# build-fuzz/reach-cache.
# Replays the target's regression inputs (tests/fuzz/regressions/) first. Exits non-zero on any
# crash, hang (> 5 s per input; 20 s in the long run, 30 s for the language's ordinary run),
# leak, out-of-memory or sanitizer report;
# artifacts go to build-fuzz/artifacts/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
mode=${2:-}
case "$mode" in
  ""|long) target=prs_lang_fuzz; regression_glob='*.prs' ;;
  scenes)  target=prs_scene_json_fuzz; regression_glob='*.json*' ;;
  urdf)    target=prs_urdf_fuzz; regression_glob='*.urdf' ;;
  mesh)    target=prs_mesh_fuzz; regression_glob='mesh_*' ;;
  *) echo "usage: scripts/fuzz.sh [seconds] [long|scenes|urdf|mesh]" >&2; exit 2 ;;
esac
scripts/build.sh fuzz "$target"

fuzzer=build-fuzz/src/fuzz/$target
artifacts=build-fuzz/artifacts
export ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1
export LSAN_OPTIONS=suppressions=$PWD/tests/fuzz/lsan.supp  # urdfdom's own leak (see there)
export PRS_CACHE_DIR=$PWD/build-fuzz/reach-cache
# The readers' targets (scenes, urdf, mesh): a corpus and log named after the mode, small
# inputs, 5 s each, and the mode's dictionary.
if [[ -n $mode && $mode != long ]]; then
  corpus=build-fuzz/corpus-$mode
  log=build-fuzz/fuzz-$mode.log
  mkdir -p "$corpus" "$artifacts"
  flags=(-timeout=5 -rss_limit_mb=2048 -max_len=8192 -artifact_prefix="$artifacts"/
         -print_final_stats=1)
fi
if [[ $mode == long ]]; then
  corpus=build-fuzz/corpus-long
  log=build-fuzz/fuzz-long.log
  mkdir -p "$corpus" "$artifacts"
  /usr/bin/python3 tests/fuzz/make_long_seeds.py "$corpus"
  export PRS_FUZZ_MAX_BYTES=$((1024 * 1024))
  flags=(-timeout=20 -rss_limit_mb=2048 -max_len=$PRS_FUZZ_MAX_BYTES -len_control=0
         -dict=tests/fuzz/prs.dict -artifact_prefix="$artifacts"/ -print_final_stats=1)
elif [[ $mode == urdf ]]; then
  cp src/kinematics/test/data/*.urdf "$corpus"/
  for f in tests/lang/bad/data/*.urdf; do cp "$f" "$corpus/bad_program_$(basename "$f")"; done
  flags+=(-dict=tests/fuzz/urdf.dict)
elif [[ $mode == mesh ]]; then
  cp tests/fuzz/mesh_corpus/* "$corpus"/
  flags+=(-dict=tests/fuzz/mesh.dict)
elif [[ $mode == scenes ]]; then
  cp tests/fuzz/scene_corpus/* "$corpus"/
  flags+=(-dict=tests/fuzz/scene_json.dict)
else
  corpus=build-fuzz/corpus
  log=build-fuzz/fuzz.log
  mkdir -p "$corpus" "$artifacts"
  cp examples/*.prs tests/lang/bad/*.prs tests/fuzz/corpus/*.prs "$corpus"/
  # 30 s per input: an input is otherwise milliseconds, but one that needs a reachable set not
  # yet in build-fuzz/reach-cache computes it, several seconds under the sanitizers.
  flags=(-timeout=30 -rss_limit_mb=2048 -max_len=4096 -dict=tests/fuzz/prs.dict
         -artifact_prefix="$artifacts"/ -print_final_stats=1)
fi

shopt -s nullglob
regressions=(tests/fuzz/regressions/$regression_glob)
if ((${#regressions[@]})); then
  echo "fuzz: replaying ${#regressions[@]} regression input(s)" >&2
  if ! "$fuzzer" "${flags[@]}" "${regressions[@]}" >"$log" 2>&1; then
    tail -n 60 "$log" >&2
    echo "fuzz: FAILED: a regression input in tests/fuzz/regressions/ still fails (log: $log)" >&2
    exit 1
  fi
fi

echo "fuzz: fuzzing${mode:+ ($mode inputs)} for ${seconds}s (log: $log)" >&2
status=0
"$fuzzer" "${flags[@]}" -max_total_time="$seconds" "$corpus" >"$log" 2>&1 || status=$?
if ((status != 0)) || grep -qE '^SUMMARY: |runtime error:' "$log"; then
  tail -n 60 "$log" >&2
  echo "fuzz: FAILED (exit $status); reproduce with: $fuzzer $artifacts/<file>" >&2
  exit 1
fi
grep -E '^#[0-9]+[[:space:]]+DONE|^stat::' "$log" >&2 || true
echo "fuzz: no crash, hang, leak or sanitizer report in ${seconds}s" >&2
