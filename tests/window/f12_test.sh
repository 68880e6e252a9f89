#!/usr/bin/env bash
# Presses M, then F12, in igi-master's window as a user does, under Xvfb, in
# a scratch folder, the exposure fixed at -2 EV to begin with: M meters it
# from the image, F12 writes the accumulated image (the PNG at the metered
# exposure), and each says so on the terminal (and, for a few seconds, in the
# window). Prints the master's output, then the files written. Run by
# tests/master/display/test_window.cpp (Window.F12WritesTheImageAndSaysSo).
#   f12_test.sh SLOWDOWN IGI_MASTER DIR     (inside xvfb-run)
set -euo pipefail
slowdown=$1 master=$2 dir=$3
pause() { sleep "$(awk -v s="$1" -v k="$slowdown" 'BEGIN { print s * k }')"; }
cd "$dir"
"$master" --workers 1 --worker-threads 1 --scene cornell --size 320x240 --vpl-paths 4 --ev -2 >master.log 2>&1 &
pid=$!
trap 'kill $pid 2>/dev/null || true' EXIT
window=$(timeout 30 xdotool search --sync --name "igi-master" | head -1)
pause 3  # frames accumulate
xdotool mousemove --window "$window" 300 200 windowfocus --sync "$window"  # keys go where the focus is (no window manager)
# Taps of a few milliseconds, shorter than the 50 ms between the panel's frames: they must still count.
xdotool key M
pause 0.5
xdotool key F12
pause 1
xdotool key Escape
wait $pid
cat master.log
ls
