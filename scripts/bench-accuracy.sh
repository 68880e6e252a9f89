#!/usr/bin/env bash
# Speed against accuracy on the scene suite, in one command: build, run
# igi-accuracy on every scene (pt references cached under results/refs/),
# then charts, Pareto fronts and headline.md under results/accuracy/.
# Run on an otherwise idle machine: every point is timed in this one run.
#
#   scripts/bench-accuracy.sh [--size WxH] [--ref-spp N] [--scenes a,b] [--series a,b] [--quick]
#
# Defaults: 160x120, 4096-spp references, all scenes
# (cornell, corner, rooms, glossy, glossy-rough, large, glass), every series
# (pt,igi,ir,caustics,view,draws,lightcuts; see tests/bench/accuracy_bench.cpp).
set -euo pipefail
cd "$(dirname "$0")/.."
size=160x120
ref_spp=4096
scenes=cornell,corner,rooms,glossy,glossy-medium,glossy-rough,large,glass
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --size) size=$2; shift 2 ;;
    --ref-spp) ref_spp=$2; shift 2 ;;
    --scenes) scenes=$2; shift 2 ;;
    --series) extra+=(--series "$2"); shift 2 ;;
    --quick) extra+=(--quick); shift ;;
    *) echo "bench-accuracy.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
done
scripts/build.sh >/dev/null || ninja -C build igi-accuracy  # the bench alone when another target is broken
python="$(scripts/venv.sh)"
out=results/accuracy
mkdir -p "$out"
build/tests/igi-accuracy --scenes "$scenes" --size "$size" --ref-spp "$ref_spp" \
  --refs results/refs --out "$out/accuracy.csv" "${extra[@]}"
meta="$size pixels, $ref_spp-spp reference, $(nproc) threads on $(uname -n), $(date -u +%Y-%m-%d)"
"$python" scripts/charts/plot_accuracy.py "$out/accuracy.csv" "$out" --meta "$meta"
echo "charts, CSV and headline.md in $out/"
