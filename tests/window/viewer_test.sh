#!/usr/bin/env bash
# igi-view driving an igi-master --viewer-listen, as a user does, under Xvfb:
# F5 saves the viewer's camera before and after a drag, F12 asks the master to
# save its image (and send it: the first viewer runs in DIR/laptop, where it
# keeps it), then the viewer is killed (SIGKILL, frames in flight) and a
# second viewer connects and takes a screenshot: the master rendered on.
# Run by tests/master/display/test_window.cpp (Window.AViewerDrivesAMasterAndOneKilledLeavesItRendering).
#   viewer_test.sh SLOWDOWN IGI_MASTER IGI_VIEW DIR     (inside xvfb-run; DIR holds master.key,
#   viewers/ and laptop.key, and gets the logs, camera files and screenshot)
set -euo pipefail
slowdown=$1 master=$2 view=$3 dir=$4
pause() { sleep "$(awk -v s="$1" -v k="$slowdown" 'BEGIN { print s * k }')"; }
cd "$dir"
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
"$master" --workers 2 --worker-threads 1 --scene cornell --size 320x240 --key master.key \
  --viewer-listen "tcp://127.0.0.1:$port" --viewer-keys viewers 2>master.log &
master_pid=$!
connect=(--connect "tcp://127.0.0.1:$port" --key "$dir/laptop.key" --master-key "$dir/master.pub" --panel off)
mkdir -p laptop
(cd laptop && exec "$view" "${connect[@]}" --camera-file "$dir/camera.json" 2>"$dir/viewer-1.log") &
viewer_pid=$!
trap 'kill $master_pid $viewer_pid 2>/dev/null || true' EXIT
window=$(timeout 30 xdotool search --sync --name "igi-view" | head -1)
pause 3
xdotool key --window "$window" F5 && pause 0.5 && cp camera.json before.json
xdotool mousemove --window "$window" 160 120 mousedown 1
for _ in $(seq 30); do xdotool mousemove_relative -- 6 0; pause 0.05; done  # 1.5 s of drag
xdotool mouseup 1
pause 2
xdotool key --window "$window" F5 && pause 0.5 && cp camera.json after.json
xdotool key --window "$window" F12
pause 1
echo "title: $(xdotool getwindowname "$window")"
kill -KILL $viewer_pid
wait $viewer_pid || true
pause 1
"$view" "${connect[@]}" --screenshot second.png --screenshot-after 4 2>viewer-2.log
echo "second viewer: exit $?"
kill -TERM $master_pid
wait $master_pid
echo "master: exit $?"
