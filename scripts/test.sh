#!/usr/bin/env bash
# Installs what is missing, builds, and runs the test suite with ctest.
#   scripts/test.sh [ctest args]   the suite in the Release build (build/), e.g. -R Sampler
#   scripts/test.sh --all          what CI runs: the suite, then the suite again under
#                                  ASan + UBSan (build-asan/), each fuzz target for 60 s,
#                                  and the suite under TSan (build-tsan/)
# With --all every stage runs even when an earlier one failed; the exit status
# is non-zero when any failed, and a summary line names them.
set -euo pipefail
cd "$(dirname "$0")/.."
all=0
if [ "${1:-}" = --all ]; then all=1; shift; fi

scripts/build.sh
if [ $all = 0 ]; then
  cd build
  exec ctest --output-on-failure -j2 "$@"
fi

failed=()
stage() {
  local name=$1; shift
  local start=$SECONDS
  echo "=== $name"
  if "$@"; then echo "=== $name: passed in $((SECONDS - start)) s"
  else echo "=== $name: FAILED after $((SECONDS - start)) s"; failed+=("$name"); fi
}
stage "release suite" bash -c 'cd build && ctest --output-on-failure -j2'
stage "asan+ubsan suite" scripts/test-sanitizers.sh asan
stage "fuzzing (60 s a target)" scripts/fuzz.sh 60
stage "tsan suite" scripts/test-sanitizers.sh tsan
if [ ${#failed[@]} -gt 0 ]; then
  echo "=== failed: ${failed[*]}"
  exit 1
fi
echo "=== all stages passed"
