#!/usr/bin/env bash
# The ruler checked: pt's image mean within 1 % of Mitsuba 3's (the
# independent reference, scripts/mitsuba/) on every suite scene and the sky-lit courtyard, both
# rendered from the same exported glTF at a small size with fixed seeds (so
# the test is deterministic; at these sample counts either mean's noise is
# about 0.3 %). Writes both images beside each other on failure.
#   pt_matches_mitsuba.sh BUILD_DIR [SCENE ...]
set -euo pipefail
build=$(cd "$1" && pwd); shift
cd "$(dirname "$0")/../.."
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(cornell corner rooms rooms-10 corridor tilted-light glossy glossy-rough glass courtyard)
python="$(scripts/venv.sh --mitsuba)"
out="$build/test-output/reference"
mkdir -p "$out"
size=64x64
failed=0
for scene in "${scenes[@]}"; do
  # Scenes whose light mostly arrives after several bounces need more samples for 0.3 %.
  case "$scene" in corner|corridor|rooms-10) spp=1024 ;; *) spp=512 ;; esac
  "$build/master/igi-render" --scene "$scene" --export-gltf "$out/$scene.gltf" --quiet >/dev/null
  "$python" scripts/mitsuba/render.py "$out/$scene.gltf" -o "$out/$scene-mitsuba.exr" --size $size --spp $spp --seed 1 >/dev/null
  "$build/master/igi-render" --scene "$out/$scene.gltf" --method pt --spp $spp --size $size --seed 1 \
    -o "$out/$scene-pt.exr" --quiet >/dev/null
  printf "%-14s " "$scene"
  "$python" scripts/mitsuba/compare.py "$out/$scene-mitsuba.exr" "$out/$scene-pt.exr" --max-mean-diff 0.01 || failed=1
done
[ $failed = 0 ] && echo "pt within 1 % of Mitsuba on ${#scenes[@]} scenes" || { echo "images in $out"; exit 1; }
