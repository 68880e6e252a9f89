#!/usr/bin/env bash
# The window's per-frame display and panel costs at 1920x1080 (issue 18), under
# Xvfb: Mesa's llvmpipe draws in software on the CPU, so GL figures here are a
# software renderer's (a GPU's would be lower). Prints medians of wall and process CPU time.
# Usage: scripts/bench-display.sh [WIDTH HEIGHT [FRAMES]]
set -euo pipefail
cd "$(dirname "$0")/.."
ninja -C build igi-display-bench >/dev/null
w=${1:-1920} h=${2:-1080}
xvfb-run -a -s "-screen 0 ${w}x${h}x24" build/tests/igi-display-bench "$w" "$h" "${3:-20}"
