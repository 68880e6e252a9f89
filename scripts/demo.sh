#!/usr/bin/env bash
# The main job: renders the built-in Cornell box with IGI, writes
# cornell-igi.png, and shows it in a window when a display exists.
# Arguments are passed on to igi-render (e.g. --method pt --spp 64).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
show=()
[ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ] && show=(--show)
build/master/igi-render --scene cornell --method igi --size 640x480 --vpl-paths 64 --clamp 0.05 \
  -o cornell-igi.png "${show[@]}" "$@"
