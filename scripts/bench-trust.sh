#!/usr/bin/env bash
# Trust that a slow worker, two colluding keys or a flood of results cannot
# break a run (issue 64), on loopback with real processes:
#   slow      a master whose maths library is 1 ulp off (LD_PRELOAD) and two
#             igi-workers with CURVE keys of their own render a 30-frame
#             orbit at 64x48 (the default --timeout-ms 1500); one worker is
#             held by SIGSTOP for --delay seconds, from its start (it joins
#             late) in half the runs and right after it joined in the other
#             half. Per run: exit statuses, frames written, frames identical
#             (cmp) to an unshimmed run's, frames in doubt, quarantines.
#   flood     igi-loadgen, 4 workers, 320x240, 120 frames at 30 fps, zstd,
#             alone and beside a fifth that sends 100 results a second for
#             jobs never issued (1 KB each, a 1024 x 1024 tile unpacked):
#             median run time of each, and when the flooder was quarantined.
#   collude, fakes, follow: the suite's Scale tests of two colluding keys, two
#             anonymous fakes and a following master's failed job, repeated.
# Targets: slow 30/30 frames, 0 quarantined, every frame identical, in every
# run; flood at most 1.2x, quarantined within 1 s. Prints figures; asserts
# nothing. Runs go to results/trust/.
#
#   scripts/bench-trust.sh [--runs N] [--delay S] [--pairs P] [--repeat R]
set -euo pipefail
cd "$(dirname "$0")/.."
runs=20
delay=1.4
pairs=5
repeat=5
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs=$2; shift 2 ;;
    --delay) delay=$2; shift 2 ;;
    --pairs) pairs=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "bench-trust.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
done
scripts/build.sh >/dev/null
out=$(pwd)/results/trust
b=$(pwd)/build
mkdir -p "$out"
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
common=(--scene cornell --method igi --vpl-paths 8 --size 64x48 --tile 16 --frames 30 --camera-path orbit --worker-threads 1)

slow_setup() {
  rm -rf "$out/keys" "$out/reference"
  mkdir -p "$out/keys/workers" "$out/reference"
  (cd "$out/keys" && "$b/master/igi-keys" new master && "$b/master/igi-keys" new workers/w1 &&
    "$b/master/igi-keys" new workers/w2) >/dev/null
  "$b/master/igi-master" "${common[@]}" --workers 2 --quiet -o "$out/reference/out.exr" >/dev/null 2>&1
}

# One run: MODE (start or joined) N.
slow_run() {
  local mode=$1 n=$2 dir="$out/slow" ep="tcp://127.0.0.1:$((20000 + RANDOM % 20000))"
  rm -rf "$dir" && mkdir -p "$dir"
  env LD_PRELOAD="$b/tests/libigi_test_off_by_one_libm.so" "$b/master/igi-master" "${common[@]}" --workers 0 \
    --key "$out/keys/master.key" --authorized-keys "$out/keys/workers" --listen "$ep" -o "$dir/out.exr" \
    >"$dir/master.log" 2>&1 &
  local m=$! w=()
  for k in w1 w2; do
    "$b/worker/igi-worker" --connect "$ep" --threads 1 --quiet --master-key "$out/keys/master.pub" \
      --key "$out/keys/workers/$k.key" &
    w+=($!)
  done
  if [ "$mode" = joined ]; then
    for _ in $(seq 200); do [ "$(grep -c ' joined' "$dir/master.log")" -ge 2 ] && break; sleep 0.01; done
  fi
  kill -STOP "${w[1]}"; sleep "$delay"; kill -CONT "${w[1]}"
  local mrc=0 r1=0 r2=0 same=0
  wait $m || mrc=$?; wait "${w[0]}" || r1=$?; wait "${w[1]}" || r2=$?
  for f in "$out"/reference/out-*.exr; do cmp -s "$f" "$dir/$(basename "$f")" && same=$((same + 1)); done
  echo "slow $mode $n: master $mrc, workers $r1 $r2, frames $(ls "$dir"/out-*.exr 2>/dev/null | wc -l)," \
       "identical $same, in doubt $(grep -c 'no worker agrees' "$dir/master.log" || true)," \
       "quarantined $(grep -c 'quarantined:' "$dir/master.log" || true)"
}

flood_run() {
  "$b/tests/loadgen/igi-loadgen" --workers 4 --frames 120 --size 320x240 --tile 32 --pixels float \
    --pixel-codec zstd --fps 30 --flood "$1" --dir "$out/loadgen" 2>&1
}

slow_setup
for n in $(seq "$runs"); do slow_run $([ $((n % 2)) -eq 1 ] && echo start || echo joined) "$n"; done | tee "$out/slow.txt"
echo "slow: $(grep -c 'master 0, workers 0 0, frames 30, identical 30, in doubt 0, quarantined 0' "$out/slow.txt")" \
     "of $runs runs with 30 of 30 frames identical and no one quarantined"

: >"$out/flood.txt"
for _ in $(seq "$pairs"); do
  for n in 0 100; do
    start=$(date +%s.%N)
    flood_run $n >"$out/flood-$n.log"
    echo "$n $(echo "$(date +%s.%N) - $start" | bc) $(sed -n 's/.*quarantined \([0-9.]*\) s after its first.*/\1/p' "$out/flood-$n.log")" >>"$out/flood.txt"
  done
done
clean=$(awk '$1 == 0 { print $2 }' "$out/flood.txt" | median)
flooded=$(awk '$1 == 100 { print $2 }' "$out/flood.txt" | median)
printf 'flood: run %.2f s alone, %.2f s with 100 results a second (%.2fx, ' "$clean" "$flooded" \
  "$(echo "$flooded / $clean" | bc -l)"
echo "medians of $pairs); quarantined $(awk '$1 == 100 { print $3 }' "$out/flood.txt" | sort -g | tr '\n' ' ')s after the first"

"$b/tests/igi_tests" --gtest_repeat="$repeat" --gtest_filter='Scale.TwoColludingKeys*:Scale.TwoFakesThatAgree*:Scale.AFollowingMasters*' \
  >"$out/scale.log" 2>&1 || true
for t in TwoColludingKeys TwoFakesThatAgree AFollowingMasters; do
  echo "$t: $(grep -c "^\[       OK \] Scale.$t" "$out/scale.log") of $repeat runs pass"
done
