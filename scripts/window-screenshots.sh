#!/usr/bin/env bash
# Screenshots of igi-master's window as a user drives it, under Xvfb: the
# window opens on SCENE, full frames accumulate for --settle seconds, the
# mouse drags the camera for 2 s (6 pixels every 50 ms), and the screen is
# taken mid-drag, 0.2 s and 1 s after the stop (each with the window's title,
# its status line, printed). Writes OUT/mid-drag.png, OUT/0.2s-after-the-stop.png
# and OUT/1s-after-the-stop.png.
#
#   scripts/window-screenshots.sh OUT SCENE [--settle S] [igi-master options...]
set -euo pipefail
cd "$(dirname "$0")/.."
out=$1 scene=$2; shift 2
settle=8
if [ "${1:-}" = --settle ]; then settle=$2; shift 2; fi
scripts/build.sh >/dev/null
python="$(scripts/venv.sh)"
mkdir -p "$out"
out=$(cd "$out" && pwd)
export IGI_SHOT_OUT=$out IGI_SHOT_PYTHON=$python IGI_SHOT_SETTLE=$settle
# shellcheck disable=SC2016  # expanded by the inner shell
xvfb-run -a -s "-screen 0 1100x600x24" bash -c '
  set -euo pipefail
  shot() { "$IGI_SHOT_PYTHON" -c "import os, sys; from PIL import ImageGrab; ImageGrab.grab(xdisplay=os.environ[\"DISPLAY\"]).crop((0, 0, 860, 480)).save(sys.argv[1])" "$IGI_SHOT_OUT/$1.png"
         echo "$1: $(xdotool getwindowname "$window")"; }
  build/master/igi-master --workers 1 --worker-threads 2 --size 640x480 --quiet "$@" &
  pid=$!
  trap "kill $pid 2>/dev/null || true" EXIT
  window=$(timeout 60 xdotool search --sync --name "igi-master" | head -1)
  xdotool windowmove "$window" 0 0
  sleep "$IGI_SHOT_SETTLE"
  xdotool mousemove --window "$window" 320 240 mousedown 1
  for step in $(seq 40); do
    xdotool mousemove_relative -- 6 0
    sleep 0.05
    [ "$step" = 30 ] && shot mid-drag
  done
  xdotool mouseup 1
  sleep 0.2; shot 0.2s-after-the-stop
  sleep 0.8; shot 1s-after-the-stop
  xdotool key --window "$window" Escape || true
  wait $pid || true
' bash --scene "$scene" "$@"
