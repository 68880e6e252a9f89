#!/usr/bin/env bash
# The main job: renders the built-in Cornell box with IGI and writes
# cornell-igi.png (and .exr). Arguments are passed on to igi-render.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build/master/igi-render --scene cornell --method igi --size 640x480 --vpl-paths 64 --clamp 0.05 -o cornell-igi.exr "$@"
build/master/igi-render --scene cornell --method igi --size 640x480 --vpl-paths 64 --clamp 0.05 -o cornell-igi.png --quiet "$@" >/dev/null
echo "wrote cornell-igi.png and cornell-igi.exr"
