#!/usr/bin/env bash
# Installs what is missing, builds, and runs the test suite with ctest.
#   scripts/test.sh [ctest args]   the suite in the Release build (build/), e.g. -R Sampler
#   scripts/test.sh --all          what CI runs (.ci/run), each build and each suite a timed stage:
#                                  the whole suite in Release (build/); under ASan + UBSan
#                                  (build-asan/) the unit tests (ctest label unit) and each fuzz
#                                  target for 30 s; under TSan (build-tsan/) the tests that start
#                                  threads or processes (label threads). Every test runs in
#                                  Release and under one sanitizer at most. Labels, timeouts:
#                                  tests/CMakeLists.txt.
# With --all every stage runs even when an earlier one failed; the exit status
# is non-zero when any failed, and the summary names the stages and the tests
# and ends with each stage's time. Builds compile through ccache (CMakeLists.txt).
set -euo pipefail
cd "$(dirname "$0")/.."
all=0
if [ "${1:-}" = --all ]; then all=1; shift; fi

build_start=$SECONDS
scripts/build.sh
release_build_seconds=$((SECONDS - build_start))
if [ $all = 0 ]; then
  cd build
  exec ctest --output-on-failure -j2 "$@"
fi

# A test that fails is run once more (ctest --repeat until-pass:2), so one
# slow moment on a loaded machine does not fail the run; a test that failed
# once and then passed is still named in the summary, as flaky.
retry=(--repeat until-pass:2)
failed=()
failed_tests=()
flaky_tests=()
stage_times=("$(printf '%-24s %5d s  %s' "release build" "$release_build_seconds" passed)")
stage() {
  local name=$1 dir=$2; shift 2
  local start=$SECONDS status=0
  echo "=== $name"
  local log=/dev/null
  if [ "$dir" != - ]; then
    rm -f "$dir/Testing/Temporary/LastTestsFailed.log"
    log="$dir/stage.log"
    mkdir -p "$dir"  # a fresh clone has no build-asan/ or build-tsan/ before its stage builds them
  fi
  "$@" 2>&1 | tee "$log" || status=${PIPESTATUS[0]}
  # CI keeps only the end of the log: the summary names the tests.
  local finally_failed=""
  if [ "$dir" != - ] && [ -f "$dir/Testing/Temporary/LastTestsFailed.log" ]; then
    finally_failed=$(sed 's/^[0-9]*://' "$dir/Testing/Temporary/LastTestsFailed.log")
  fi
  local t
  for t in $finally_failed; do failed_tests+=("$name: $t"); done
  if [ "$dir" != - ]; then
    for t in $(grep -E '\*\*\*(Failed|Timeout|Exception)' "$log" | sed -E 's/.*Test +#[0-9]+: ([^ ]+) .*/\1/' | sort -u); do
      grep -qxF "$t" <<<"$finally_failed" || flaky_tests+=("$name: $t")
    done
  fi
  local result=passed
  if [ "$status" = 0 ]; then echo "=== $name: passed in $((SECONDS - start)) s"
  else echo "=== $name: FAILED after $((SECONDS - start)) s"; failed+=("$name"); result=FAILED; fi
  stage_times+=("$(printf '%-24s %5d s  %s' "$name" $((SECONDS - start)) "$result")")
}
all_start=$SECONDS
stage "release suite" build bash -c "cd build && ctest --output-on-failure -j2 ${retry[*]}"
stage "asan+ubsan build" - scripts/test-sanitizers.sh asan --build-only
stage "asan+ubsan suite" build-asan scripts/test-sanitizers.sh asan -L unit "${retry[@]}"
stage "fuzzing (30 s a target)" - scripts/fuzz.sh 30
stage "tsan build" - scripts/test-sanitizers.sh tsan --build-only
stage "tsan suite" build-tsan scripts/test-sanitizers.sh tsan -L threads "${retry[@]}"
for t in "${flaky_tests[@]}"; do echo "=== flaky (failed, then passed when run again): $t"; done
echo "=== stage times"
for t in "${stage_times[@]}"; do echo "=== $t"; done
echo "=== total $((SECONDS - all_start + release_build_seconds)) s"
if [ ${#failed[@]} -gt 0 ]; then
  # CI keeps only the end of the log: repeat what the fuzzer found.
  if [[ " ${failed[*]} " == *" fuzzing "* ]] && [ -f build-asan/fuzz-summary.txt ]; then
    sed 's/^/=== fuzzing: /' build-asan/fuzz-summary.txt
  fi
  for t in "${failed_tests[@]}"; do echo "=== failed test: $t"; done
  echo "=== failed: ${failed[*]}"
  exit 1
fi
echo "=== all stages passed"
