#!/usr/bin/env bash
# How far one igi-master goes: igi-loadgen runs the real master with 8 to 256
# simulated workers (real ZeroMQ sockets, pre-rendered tiles) at 640x480 and
# 1920x1080, 32- and 64-pixel tiles, paced for 30 frames a second and flat out,
# and measures the master's CPU per tile (robust to a loaded machine), its
# cores, frames a second, frame latency and memory. Results in results/master/:
# master.csv, master.png, summary.md. Arguments go to scripts/charts/bench_master.py
# (e.g. --frames 300, --quick).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
python="$(scripts/venv.sh)"
"$python" scripts/charts/bench_master.py "$@"
