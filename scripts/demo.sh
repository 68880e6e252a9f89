#!/usr/bin/env bash
# The main job: the built-in Cornell box rendered with IGI by a master and two
# local workers. With a display: an interactive window (Esc quits). Without:
# one frame written to cornell-igi.png. Arguments go to igi-master.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
args=(--workers 2 --scene cornell --method igi --size 640x480)  # the defaults: README, "Defaults"
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  build/master/igi-master "${args[@]}" "$@"
else
  build/master/igi-master "${args[@]}" --frames 1 -o cornell-igi.png "$@"
  echo "wrote cornell-igi.png"
fi
