#!/usr/bin/env bash
# The caustic photon map's cost and gain, in one command: build, render the
# glass scene's pt reference once (cached under results/refs/), run
# igi-caustics-bench, then the chart under results/caustics/. Run on an
# otherwise idle machine: every figure is timed in this one run.
#
#   scripts/bench-caustics.sh [--size WxH] [--ref-spp N] [--frames F] [--threads T] [igi-caustics-bench options]
#
# Defaults: 128x96 reference of 16384 spp (pt's caustics converge slowly:
# two 1024-spp renders differ by relMSE 0.005), photon pass and 640x480
# frames on 2 threads, medians of 5 frames.
set -euo pipefail
cd "$(dirname "$0")/.."
size=128x96
ref_spp=16384
args=(--frames 5 --threads 2)
while [ $# -gt 0 ]; do
  case "$1" in
    --size) size=$2; shift 2 ;;
    --ref-spp) ref_spp=$2; shift 2 ;;
    *) args+=("$1"); shift ;;
  esac
done
scripts/build.sh >/dev/null || ninja -C build igi-caustics-bench igi-render
python="$(scripts/venv.sh)"
out=results/caustics
mkdir -p "$out" results/refs
ref=results/refs/glass-$size-$ref_spp-pt-seed7.exr
if [ ! -f "$ref" ]; then
  echo "rendering the reference $ref (pt, $ref_spp spp)..."
  build/master/igi-render --scene glass --method pt --spp "$ref_spp" --size "$size" --seed 7 -o "$ref" --quiet
fi
build/tests/igi-caustics-bench --scene glass --ref "$ref" --out "$out" "${args[@]}"
meta="$size pixels ($ref_spp-spp pt reference), $(nproc) threads on $(uname -n), $(date -u +%Y-%m-%d)"
"$python" scripts/charts/plot_caustics.py "$out" --meta "$meta"
echo "charts, CSVs and reach.md in $out/"
