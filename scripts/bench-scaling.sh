#!/usr/bin/env bash
# Scalability of master + workers against the single-process render, in one
# run: frame time and Mrays/s against workers and tile size, the master's cost
# per tile and bytes per frame. Results in results/scaling/. Arguments go to
# scripts/charts/bench_scaling.py (e.g. --scene cornell --frames 20).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
python="$(scripts/venv.sh)"
"$python" scripts/charts/bench_scaling.py "$@"
