#!/usr/bin/env bash
# Builds the libFuzzer target (scripts/build.sh fuzz) and fuzzes the language stage for a
# bounded time. Usage: scripts/fuzz.sh [seconds] [long]   (default 30 s)
# Replays tests/fuzz/regressions/*.prs first, then fuzzes from a scratch corpus in build-fuzz/
# seeded with examples/, tests/lang/bad/ and tests/fuzz/corpus/. With `long`, inputs up to
# 1 MiB from a separate corpus seeded with 100,000-term-class chains (tests/fuzz/
# make_long_seeds.py), for the stack-depth limits. Exits non-zero on any crash, hang (> 5 s per
# input; 20 s in the long run), leak, out-of-memory or sanitizer report; artifacts go to
# build-fuzz/artifacts/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
mode=${2:-}
scripts/build.sh fuzz prs_lang_fuzz

fuzzer=build-fuzz/src/fuzz/prs_lang_fuzz
artifacts=build-fuzz/artifacts
export ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1
if [[ $mode == long ]]; then
  corpus=build-fuzz/corpus-long
  log=build-fuzz/fuzz-long.log
  mkdir -p "$corpus" "$artifacts"
  /usr/bin/python3 tests/fuzz/make_long_seeds.py "$corpus"
  export PRS_FUZZ_MAX_BYTES=$((1024 * 1024))
  flags=(-timeout=20 -rss_limit_mb=2048 -max_len=$PRS_FUZZ_MAX_BYTES -len_control=0
         -dict=tests/fuzz/prs.dict -artifact_prefix="$artifacts"/ -print_final_stats=1)
else
  corpus=build-fuzz/corpus
  log=build-fuzz/fuzz.log
  mkdir -p "$corpus" "$artifacts"
  cp examples/*.prs tests/lang/bad/*.prs tests/fuzz/corpus/*.prs "$corpus"/
  flags=(-timeout=5 -rss_limit_mb=2048 -max_len=4096 -dict=tests/fuzz/prs.dict
         -artifact_prefix="$artifacts"/ -print_final_stats=1)
fi

shopt -s nullglob
regressions=(tests/fuzz/regressions/*.prs)
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
