#!/usr/bin/env bash
# The display link over a shaped link inside this machine (issue 62):
# igi-master --viewer-listen (two local workers) in one network namespace,
# igi-view under its own Xvfb in another, a veth pair between them shaped by tc
# tbf on both ends (the link of scripts/bench-network.sh). Per case xdotool
# drags in the viewer for 3 s (right and back), holds still for 2 s, then presses F12 (the
# master saves its image at the viewer's exposure) and Esc (the viewer saves
# what it shows). Prints per case: the viewer's frames a second during the
# drag, bytes a pixel during the drag and after it, the delay from an input
# to the first frame that shows it (the viewer stamps each View, the master
# echoes the stamp; median over the drag), and the FLIP of the viewer's last
# still frame against the master's image. Needs root (ip netns, tc), Xvfb, xdotool.
#   scripts/bench-viewer.sh [SIZE:RATE:CODEC ...]   RATE a tc rate or "none" (unshaped)
# default: 640x480:none:h264 640x480:20mbit:h264 640x480:20mbit:zstd 1920x1080:50mbit:h264
# Results in results/viewer/: viewer.csv, each case's logs, frame log and screenshots.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
[ "$(id -u)" -eq 0 ] || { echo "bench-viewer: needs root (ip netns, tc); traffic stays inside this machine"; exit 1; }
for tool in Xvfb xdotool; do command -v $tool >/dev/null || { echo "bench-viewer: needs $tool (scripts/setup.sh)"; exit 1; }; done
nice ninja -C build igi-master igi-worker igi-view igi-keys igi-compare >/dev/null
cases=("$@")
[ ${#cases[@]} -gt 0 ] || cases=(640x480:none:h264 640x480:20mbit:h264 640x480:20mbit:zstd 1920x1080:50mbit:h264)
out=$root/results/viewer
rm -rf "$out" && mkdir -p "$out/keys/viewers"
ns_m=igi-viewer-master ns_v=igi-viewer-laptop addr_m=10.99.62.1 addr_v=10.99.62.2 display=:62
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  ip netns del $ns_m 2>/dev/null || true
  ip netns del $ns_v 2>/dev/null || true
}
trap cleanup EXIT
cleanup
ip netns add $ns_m && ip netns add $ns_v
ip link add vm62 type veth peer name vv62
for pair in "vm62 $ns_m $addr_m" "vv62 $ns_v $addr_v"; do
  set -- $pair
  ip link set "$1" netns "$2"
  ip netns exec "$2" ip addr add "$3/30" dev "$1"
  ip netns exec "$2" ip link set "$1" up
  ip netns exec "$2" ip link set lo up
done
shape() {  # RATE: tbf on both ends, or none
  for pair in "vm62 $ns_m" "vv62 $ns_v"; do
    set -- $pair
    ip netns exec "$2" tc qdisc del dev "$1" root 2>/dev/null || true
    [ "$rate" = none ] || ip netns exec "$2" tc qdisc add dev "$1" root tbf rate "$rate" burst 64kb latency 50ms
  done
}
(cd "$out/keys" && "$root/build/master/igi-keys" new master >/dev/null && "$root/build/master/igi-keys" new laptop >/dev/null \
  && cp laptop.pub viewers/)
ip netns exec $ns_v Xvfb $display -screen 0 2048x1200x24 -nolisten tcp 2>/dev/null &
pids+=($!)
sleep 1
in_view() { ip netns exec $ns_v env DISPLAY=$display "$@"; }
now_ms() { date +%s%3N; }

# Frame log lines "WALL_MS CODEC BYTES PIXELS DELAY|-" between two wall times: fps, bytes a pixel, median delay.
figures() {
  local median
  median=$(awk -v a="$1" -v b="$2" '$1 >= a && $1 <= b && $5 != "-" { print $5 }' "$3" | sort -g |
           awk '{ d[NR] = $1 } END { print NR ? d[int((NR + 1) / 2)] : "-" }')
  awk -v a="$1" -v b="$2" -v m="$median" '$1 >= a && $1 <= b { n++; bytes += $3; px += $4 }
    END { if (n < 2) print "0 0 -"; else printf "%.1f %.3f %s\n", n / ((b - a) / 1000), bytes / px, m }' "$3"
}

run_case() {  # SIZE RATE CODEC
  local size=$1 rate=$2 codec=$3 dir="$out/$1-$2-$3"
  mkdir -p "$dir" && shape
  (cd "$dir" && exec ip netns exec $ns_m "$root/build/master/igi-master" --workers 2 --worker-threads 1 \
     --scene cornell --size "$size" --key "$out/keys/master.key" --viewer-listen "tcp://$addr_m:5600" \
     --viewer-keys "$out/keys/viewers" --viewer-codec "$codec" 2>master.log) &
  local master=$!
  pids+=($master)
  sleep 1
  in_view "$root/build/master/igi-view" --connect "tcp://$addr_m:5600" --key "$out/keys/laptop.key" \
    --master-key "$out/keys/master.pub" --panel off --frame-log "$dir/frames.log" \
    --screenshot-at-exit "$dir/viewer.png" 2>"$dir/viewer.log" &
  local viewer=$!
  local window
  window=$(in_view timeout 30 xdotool search --sync --name "igi-view" | head -1)
  sleep 4  # the image accumulates
  in_view xdotool mousemove --window "$window" 200 200 mousedown 1
  local drag_start drag_end
  drag_start=$(now_ms)
  for dx in 4 -4; do  # 1.5 s right, 1.5 s back: the box stays in view and the drag ends where it began
    for _ in $(seq 30); do in_view xdotool mousemove_relative -- $dx 0; sleep 0.05; done
  done
  drag_end=$(now_ms)
  in_view xdotool mouseup 1
  sleep 2
  in_view xdotool key --window "$window" F12
  sleep 0.3  # the request leaves with the viewer's next panel frame
  in_view xdotool key --window "$window" Escape || true
  wait $viewer || true
  sleep 0.5
  kill -TERM $master 2>/dev/null || true
  wait $master || true
  read -r fps bpp delay < <(figures "$drag_start" "$drag_end" "$dir/frames.log")
  read -r _ still_bpp _ < <(figures "$((drag_end + 300))" "$(now_ms)" "$dir/frames.log")
  local flip=-
  if [ -f "$dir/igi-shot-0000.png" ] && [ -f "$dir/viewer.png" ]; then
    flip=$("$root/build/tests/igi-compare" "$dir/igi-shot-0000.png" "$dir/viewer.png" |
           awk '$1 ~ /viewer.png$/ { print $4 }')
  fi
  printf '%-10s %-7s %-5s %8s %12s %12s %10s %8s\n' "$size" "$rate" "$codec" "$fps" "$bpp" "$still_bpp" \
    "$delay" "${flip:--}"
  echo "$size,$rate,$codec,$fps,$bpp,$still_bpp,$delay,${flip:--}" >> "$out/viewer.csv"
}

echo "size,rate,codec,drag_fps,drag_bytes_per_pixel,still_bytes_per_pixel,input_to_frame_ms,still_flip" > "$out/viewer.csv"
printf '%-10s %-7s %-5s %8s %12s %12s %10s %8s\n' size link codec "drag fps" "drag B/px" "still B/px" \
  "delay ms" FLIP
for c in "${cases[@]}"; do
  IFS=: read -r size rate codec <<< "$c"
  run_case "$size" "$rate" "$codec"
done
echo "results in $out (viewer.csv; per case master.log, viewer.log, frames.log, viewer.png, igi-shot-0000.png)"
