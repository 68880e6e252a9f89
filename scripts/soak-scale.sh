#!/usr/bin/env bash
# The soak at simulated scale: igi-loadgen runs the real master with 64 and
# then 256 simulated workers for longer than ctest's run (Scale.*Churn*):
# a tenth of the workers join late, a tenth stall past the master's timeout,
# a tenth die and are replaced, one reports other VPL sets; the master writes
# float frames, and every tenth frame is checked pixel by pixel. Any other
# igi-loadgen option may follow (e.g. --frames 3000, --churn 42).
#   scripts/soak-scale.sh                 # 900 frames (30 s) at 64 and at 256 workers
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
seed=${SOAK_SEED:-$RANDOM}
echo "churn seed $seed (SOAK_SEED=$seed repeats the schedule)"
status=0
for workers in 64 256; do
  build/tests/loadgen/igi-loadgen --workers "$workers" --size 320x240 --tile 16 --frames 900 --warmup 30 \
    --pixels float --write-frames --check-every 10 --churn "$seed" --diverging 1 --timeout-ms 500 \
    --heartbeat-ms 100 --dir "build/soak-scale-$workers" --label "soak $workers" "$@" || status=1
  rm -f "build/soak-scale-$workers"/frame-*.exr  # checked; the logs stay
done
exit $status
