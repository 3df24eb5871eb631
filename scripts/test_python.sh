#!/usr/bin/env bash
# Tests the probrobscene Python package with Debian's python3: builds it in the Release build
# (build/, configured by scripts/build.sh release), runs the pytest suite in python/tests against
# the built `prs`, then installs it offline with pip into a temporary directory and imports it.
# Usage: scripts/test_python.sh      (PRS_PYTHON overrides /usr/bin/python3)
set -euo pipefail
cd "$(dirname "$0")/.."
python=${PRS_PYTHON:-/usr/bin/python3}
build=$PWD/build

[[ -f $build/build.ninja ]] || scripts/build.sh release
cmake --build "$build" -j"${PRS_JOBS:-2}" --target prs prs_python

# pytest's exit codes: 0 passed, 1 tests failed, 2 interrupted, 3 internal error, 4 usage
# error, 5 no tests collected (a broken suite, so a failure here too).
set +e
PRS_BINARY=$build/src/cli/prs PYTHONPATH=$build/python \
  "$python" -m pytest -q -p no:cacheprovider python/tests
status=$?
set -e
case $status in
  0) ;;
  1) echo "test_python: tests failed" >&2; exit 1 ;;
  5) echo "test_python: pytest collected no tests" >&2; exit 1 ;;
  *) echo "test_python: pytest stopped with exit code $status" >&2; exit "$status" ;;
esac

# The documented install (pip from the source tree, no package index), into a throwaway
# directory, reusing the build above; then the import from a directory outside the tree.
site=$(mktemp -d)
trap 'rm -rf "$site"' EXIT
PRS_CMAKE_BUILD_DIR=$build "$python" -m pip install --quiet --root-user-action=ignore \
  --no-index --no-build-isolation --no-deps --target "$site" .
(cd / && PYTHONPATH=$site "$python" -c '
import sys, probrobscene
assert probrobscene.__file__.startswith(sys.argv[1]), probrobscene.__file__
print("test_python: pip-installed probrobscene", probrobscene.__version__, "imports")' "$site")
