#!/usr/bin/env bash
# Throughput of the IGI renderer (issue figures in the README): igi against
# raw Embree on the same rays, fps, border overhead, filter cost per width.
# Run on an otherwise idle machine; prints figures, asserts nothing. Without
# arguments it writes its figures into tests/bench/RESULTS.md ("Frame time";
# scripts/lib/results.sh); with arguments (other scenes or settings) it only prints.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/results.sh
scripts/build.sh >/dev/null
out=$(mktemp)
trap 'rm -f "$out"' EXIT
build/tests/igi-bench "$@" | tee "$out"
echo
build/tests/filter-bench
[ $# -eq 0 ] || exit 0
# "igi, 2 threads  836.9  1.19 ..." in scene S's section: the fps column.
fps() { awk -v scene="$1" -v row="$2" '/^== /{in_scene = ($2 == scene ":")} in_scene && index($0, row) == 1 {print $(NF - 3)}' "$out"; }
line() { awk -v scene="$1" -v text="$2" '/^== /{in_scene = ($2 == scene ":")} in_scene && index($0, text) {print; exit}' "$out"; }
share() { line "$1" "igi / raw Embree throughput" | sed 's/.*: //'; }
aa_pairs() { line "$1" "median of 5 frame pairs" | sed -E 's/4x AA costs ([0-9.]+x).*/\1/'; }
results_set igi-cornell-fps "$(fps cornell 'igi, 2 threads') / $(fps cornell 'igi, 1 thread') fps"
results_set igi-cornell-aa "$(fps cornell 'igi 4x AA, 2 threads') fps ($(aa_pairs cornell) the plain frame, median of 5 frame pairs)"
share1() { line "$1" "with the shadow rays one at a time" | sed 's/.*: //'; }
results_set igi-embree-share "$(share cornell) (Cornell box), $(share cornell-blob) (cornell-blob); against Embree tracing the shadow rays one at a time: $(share1 cornell), $(share1 cornell-blob)"
results_set igi-blob-aa "$(fps cornell-blob 'igi 4x AA, 2 threads') fps"
