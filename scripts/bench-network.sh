#!/usr/bin/env bash
# The cluster over a shaped link inside this machine: igi-master in one network
# namespace, simulated workers (a rendered frame's tiles) and real igi-workers
# in another, a veth pair between them shaped by tc to 1 and 10 Gbit/s, CURVE
# on. Prints fps, bytes a pixel and the master's CPU at 640x480 and 1080p, raw
# and packed, half and rgb9e5. Needs root. Results in results/network/.
# Arguments go to scripts/charts/bench_network.py (e.g. --rates 1gbit --frames 30).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
python="$(scripts/venv.sh)"
"$python" scripts/charts/bench_network.py "$@"
