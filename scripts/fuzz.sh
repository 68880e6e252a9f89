#!/usr/bin/env bash
# Fuzzes the wire decoder and the glTF loader with libFuzzer under ASan+UBSan:
#   scripts/fuzz.sh [seconds-per-target]   (default 60)
# Builds build-asan/ (scripts/sanitized-build.sh asan), writes the seed corpora
# (igi-fuzz-seeds: one message of every type, the Cornell box and small scenes
# as .glb and .gltf) and runs each target with its working corpus in
# build-asan/fuzz-corpus/<target>/, which grows from run to run. Prints each
# target's executions, exec/s, coverage and corpus size. A crash, leak, timeout
# or out-of-memory stops that target, its input is kept in
# build-asan/fuzz-crashes/<target>/ and the script exits non-zero.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
targets=(decode scene)
scripts/sanitized-build.sh asan igi-fuzz-seeds "${targets[@]/#/igi-fuzz-}"

dir=build-asan
"$dir/tests/fuzz/igi-fuzz-seeds" "$dir/fuzz-seeds" >/dev/null
# Scenes: up to 1 MB each, with glTF's keys as a dictionary. Messages: up to
# 64 kB (the pixel block of a 64 x 64 tile is 48 kB; larger inputs only repeat).
declare -A options=(
  [decode]="-max_len=65536"
  [scene]="-max_len=1048576 -dict=tests/fuzz/gltf.dict"
)
failed=()
summary="$dir/fuzz-summary.txt"  # scripts/test.sh repeats it at the end of a CI run
: >"$summary"
for target in "${targets[@]}"; do
  corpus="$dir/fuzz-corpus/$target" crashes="$dir/fuzz-crashes/$target"
  mkdir -p "$corpus" "$crashes"
  log="$dir/fuzz-$target.log"
  # New inputs go to the first folder only; seeds and regressions are read.
  # shellcheck disable=SC2086
  if "$dir/tests/fuzz/igi-fuzz-$target" "$corpus" "$dir/fuzz-seeds/$target" "tests/fuzz/regressions/$target" \
      ${options[$target]} -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 \
      -artifact_prefix="$crashes/" -print_final_stats=1 >"$log" 2>&1; then
    status=ok
  else
    status=FAILED
    failed+=("$target")
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
  coverage=$(grep -o 'cov: [0-9]* ft: [0-9]* corp: [0-9]*/[0-9a-zA-Z]*' "$log" | tail -n 1)
  {
  printf '%-7s %-6s %s runs in %s s, %s exec/s, %s (corpus %s files)\n' "$target" "$status" "${runs:-?}" \
    "$seconds" "${rate:-?}" "${coverage:-no coverage line}" "$(find "$corpus" -type f | wc -l)"
  if [ "$status" = FAILED ]; then
    grep -m 1 -E 'ERROR: |runtime error:|igi-fuzz-[a-z]*: ' "$log" || true
    artifact=$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$log" | tail -n 1)
    echo "  input: ${artifact:-see $log}; full report: $log"
    echo "  reproduce: $dir/tests/fuzz/igi-fuzz-$target ${artifact:-CRASH-FILE}"
    echo "  after the fix, keep it: cp ${artifact:-CRASH-FILE} tests/fuzz/regressions/$target/<what-it-was>"
    echo "  (the replay test in igi_tests then runs it in every build)"
    # The input itself, so that a CI log alone can reproduce it (at most 4 kB shown).
    if [ -n "$artifact" ] && [ -f "$artifact" ]; then
      echo "  input, $(stat -c %s "$artifact") bytes, base64 (first 4 kB):"
      head -c 4096 "$artifact" | base64 -w 100 | sed 's/^/    /'
    fi
  fi
  } | tee -a "$summary"
done
if [ "${#failed[@]}" -gt 0 ]; then
  echo "fuzz.sh: ${failed[*]} failed" >&2
  exit 1
fi
