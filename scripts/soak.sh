#!/usr/bin/env bash
# Faults under load, for longer than ctest's bounded run: builds (scripts/build.sh),
# then runs build/tests/soak/igi-soak. Defaults: 1000 frames, a new seed each run
# (printed: --seed S repeats a run's faults), working folder build/soak-run.
# Any igi-soak option may be given (they override the defaults); --help lists them.
#   scripts/soak.sh                                  # 1000 frames, 100 faults of every kind
#   scripts/soak.sh --frames 5000 --real-oversized   # longer, plus one real 512 MB message
#   scripts/soak.sh --seed 7 --frames 300            # the ctest's run
# Network namespaces need root; without, that part is skipped (and the summary says why).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
exec build/tests/soak/igi-soak --frames 1000 --dir build/soak-run "$@"
