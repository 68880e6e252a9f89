#!/usr/bin/env bash
# The test suite under sanitizers (clang 14):
#   scripts/test-sanitizers.sh asan   AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/)
#   scripts/test-sanitizers.sh tsan   ThreadSanitizer (build-tsan/)
#   scripts/test-sanitizers.sh        both
# Further arguments go to ctest (e.g. -R Distributed). Every process the tests
# start (masters, workers, igi-render) inherits the options below and writes
# any report to build-KIND/sanitizer-logs/; the run fails if a report appears
# there, so a report from a worker that a test killed is not lost either.
# Leak checking is off: third-party libraries (OpenImageIO, TBB) drown it.
set -euo pipefail
cd "$(dirname "$0")/.."
kinds=(asan tsan)
if [ $# -gt 0 ] && { [ "$1" = asan ] || [ "$1" = tsan ]; }; then kinds=("$1"); shift; fi

# What the tests run: the suite, the programs it starts, and the soak driver.
targets=(igi_tests igi-master igi-worker igi-render igi-keys igi-soak)

# Under TSan (5-15x slower) the statistical accuracy tests would take most of
# CI's time (the glossy one-pass test alone 33 s): they run the same render
# pool single-process that TileInvariance, WhiteFurnace and the distributed
# tests run, and check numbers, not threads.
tsan_skip='IgiAccuracy|ImportanceAccuracy|LightcutsAccuracy|Clamping\.|Stability\.|CornellMean|CornerRegains|SuiteScenes\.Large|GroupsKeepTheMean|VplFurnace\.|CausticAccuracy|CausticFurnace|Glossy\.OnePassAtTheDefaults'

status=0
for kind in "${kinds[@]}"; do
  scripts/sanitized-build.sh "$kind" "${targets[@]}"
  logs="$PWD/build-$kind/sanitizer-logs"
  rm -rf "$logs" && mkdir -p "$logs"
  export ASAN_OPTIONS="detect_leaks=0:abort_on_error=1:log_path=$logs/asan"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:log_path=$logs/ubsan"
  export TSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/tsan.supp:detect_deadlocks=0:halt_on_error=1:log_path=$logs/tsan"
  skip=()
  [ "$kind" = tsan ] && skip=(-E "$tsan_skip")
  echo "== $kind: ctest"
  start=$SECONDS
  (cd "build-$kind" && ctest --output-on-failure -j2 --timeout 900 "${skip[@]}" "$@") || status=1
  echo "== $kind: ctest took $((SECONDS - start)) s"
  if [ -n "$(ls -A "$logs")" ]; then
    echo "== $kind: sanitizer reports:"
    for f in "$logs"/*; do echo "--- $f"; head -60 "$f"; done
    status=1
  fi
done
exit $status
