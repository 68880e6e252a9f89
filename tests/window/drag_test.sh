#!/usr/bin/env bash
# Drags the mouse in igi-master's window as a user does, under Xvfb, and
# prints the window's title (its status line) before, during and after the
# drag: one line each, "before: ...", "drag-1: ..." ... "after: ...".
# Run by tests/master/display/test_window.cpp (Window.ADragShowsPreviewFramesAndTheStopFullOnes).
#   drag_test.sh SLOWDOWN IGI_MASTER [EXTRA OPTIONS...]     (inside xvfb-run)
# SLOWDOWN stretches every wait (5 under the sanitizers, tests/support/sanitizers.h).
set -euo pipefail
slowdown=$1 master=$2; shift 2
pause() { sleep "$(awk -v s="$1" -v k="$slowdown" 'BEGIN { print s * k }')"; }
"$master" --workers 2 --worker-threads 1 --scene cornell --size 320x240 --panel off --quiet "$@" &
pid=$!
trap 'kill $pid 2>/dev/null || true' EXIT
window=$(timeout 30 xdotool search --sync --name "igi-master" | head -1)
title() { xdotool getwindowname "$window"; }
pause 3  # full frames accumulate
echo "before: $(title)"
xdotool mousemove --window "$window" 160 120 mousedown 1
for step in 1 2 3; do  # 1.5 s of drag, 6 px every 50 ms
  for _ in $(seq 10); do xdotool mousemove_relative -- 6 0; pause 0.05; done
  echo "drag-$step: $(title)"
done
xdotool mouseup 1
pause 3
echo "after: $(title)"
# The window may close on the key's press, before xdotool sends its release
# to it (BadWindow, exit 1, seen under load): the master's exit status judges.
xdotool key --window "$window" Escape || true
wait $pid
