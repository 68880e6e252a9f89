#!/usr/bin/env bash
# Lightcuts against ir over the same VPLs and against pt, in one command:
# build, run igi-lightcuts-bench (pt references cached under results/refs/),
# then the chart and summary.md under results/lightcuts/. Run on an otherwise
# idle machine: every figure is timed in this one run, ratios within it.
#
#   scripts/bench-lightcuts.sh [--size WxH] [--vpls 1000,10000,100000] [--scenes a,b]
#                              [--ref-spp N] [--frames F] [--spacing S] [--samples K]
#
# Defaults: 96x72 (ir shades every VPL at every pixel: at 100,000 VPLs that is
# 6.9e8 shadow rays a frame), 1,000 / 10,000 / 100,000 VPLs, cornell,
# cornell-blob and rooms-4, 1024-spp references, medians of 3 frames (ir at
# 100,000 VPLs: 1), reconstruction cuts every 4 pixels, 4 gather points.
set -euo pipefail
cd "$(dirname "$0")/.."
args=(--size 96x72 --vpls 1000,10000,100000 --scenes cornell,cornell-blob,rooms-4 --ref-spp 1024 --frames 3)
args+=("$@")  # later options win
scripts/build.sh >/dev/null || ninja -C build igi-lightcuts-bench  # the bench alone when another target is broken
python="$(scripts/venv.sh)"
out=results/lightcuts
mkdir -p "$out"
build/tests/igi-lightcuts-bench "${args[@]}" --refs results/refs --out "$out/lightcuts.csv"
size=$(printf '%s\n' "${args[@]}" | awk 'prev == "--size" { s = $0 } { prev = $0 } END { print s }')
meta="$size pixels, $(nproc) threads on $(uname -n), $(date -u +%Y-%m-%d)"
"$python" scripts/charts/plot_lightcuts.py "$out/lightcuts.csv" "$out" --meta "$meta"
echo "chart, CSV and summary.md in $out/"
