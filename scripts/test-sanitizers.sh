#!/usr/bin/env bash
# The test suite under sanitizers (clang 14):
#   scripts/test-sanitizers.sh asan   AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/)
#   scripts/test-sanitizers.sh tsan   ThreadSanitizer (build-tsan/)
#   scripts/test-sanitizers.sh        both
#   scripts/test-sanitizers.sh KIND --build-only   only build what the tests run
# Further arguments go to ctest (e.g. -R Distributed, or -L threads: the tests
# that start threads or processes, which CI runs under TSan; labels in
# tests/CMakeLists.txt). Every process the tests
# start (masters, workers, igi-render) inherits the options below and writes
# any report to build-KIND/sanitizer-logs/; the run fails if a report appears
# there, so a report from a worker that a test killed is not lost either.
# Leak checking is off: third-party libraries (OpenImageIO, TBB) drown it.
set -euo pipefail
cd "$(dirname "$0")/.."
kinds=(asan tsan)
if [ $# -gt 0 ] && { [ "$1" = asan ] || [ "$1" = tsan ]; }; then kinds=("$1"); shift; fi
build_only=0
if [ "${1:-}" = --build-only ]; then build_only=1; shift; fi

# What the tests run: the suite, the programs it starts, and the soak driver;
# under ASan also the fuzz targets (scripts/fuzz.sh).
targets=(igi_tests igi-master igi-worker igi-render igi-keys igi-soak)

status=0
for kind in "${kinds[@]}"; do
  kind_targets=("${targets[@]}")
  [ "$kind" = asan ] && kind_targets+=(igi-fuzz-seeds igi-fuzz-decode igi-fuzz-scene)
  scripts/sanitized-build.sh "$kind" "${kind_targets[@]}"
  [ $build_only = 1 ] && continue
  logs="$PWD/build-$kind/sanitizer-logs"
  rm -rf "$logs" && mkdir -p "$logs"
  export ASAN_OPTIONS="detect_leaks=0:abort_on_error=1:log_path=$logs/asan"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:log_path=$logs/ubsan"
  export TSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/tsan.supp:detect_deadlocks=0:halt_on_error=1:log_path=$logs/tsan"
  echo "== $kind: ctest"
  start=$SECONDS
  (cd "build-$kind" && ctest --output-on-failure -j2 "$@") || status=1
  echo "== $kind: ctest took $((SECONDS - start)) s"
  if [ -n "$(ls -A "$logs")" ]; then
    echo "== $kind: sanitizer reports:"
    for f in "$logs"/*; do echo "--- $f"; head -60 "$f"; done
    status=1
  fi
done
exit $status
