#!/usr/bin/env bash
# The window's behaviour while the camera moves, measured headless through
# the same session code (igi-master --motion, master/run/motion_run.cpp): a
# scripted user drags (30 degrees a second) or walks (W held) for 2 s, then
# holds still for 4 s; today's behaviour against the one before motion was
# handled (--motion-legacy: no budget, stale frames dropped, the image thrown
# away on every move), one after the other on the same machine. Prints per
# scene and path: frames shown a second while moving, the share of moving
# frames within the budget, the longest wait between two frames while
# moving, the median FLIP of moving frames at every 10th pose (previews
# upscaled), the flicker between consecutive moving frames (the median and
# largest change of a frame's mean luminance against the one before), and
# the time after the stop to FLIP 0.05 and 0.03; beside raw
# Embree's rate (igi-bench). References: igi at --ref-spp passes at each 10th
# pose, cached in results/motion/refs/. Charts FLIP against time after the
# stop (results/motion/SCENE-PATH.png). One run each; asserts nothing.
# A scene is a built-in name or a .gltf/.glb file (named by its file name in
# results/); --args passes igi-master options to every run (e.g.
# --no-light-guide, to measure the flicker without light paths that find
# the view).
#
#   scripts/bench-motion.sh [--scenes cornell,glossy,rooms-10] [--paths drag,walk] [--size 640x480]
#                           [--threads 2] [--budget-ms 40] [--ref-spp 64] [--args "OPTIONS"]
set -euo pipefail
cd "$(dirname "$0")/.."
scenes=cornell,glossy,rooms-10
paths=drag,walk
size=640x480
threads=2
budget=40
ref_spp=64
args=""
while [ $# -gt 0 ]; do
  case "$1" in
    --scenes) scenes=$2; shift 2 ;;
    --paths) paths=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --budget-ms) budget=$2; shift 2 ;;
    --ref-spp) ref_spp=$2; shift 2 ;;
    --args) args=$2; shift 2 ;;
    *) echo "bench-motion.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
done
scripts/build.sh >/dev/null
python="$(scripts/venv.sh)"
source scripts/lib/results.sh  # results_set
out=results/motion
mkdir -p "$out/refs"
embree=$(build/tests/igi-bench --scenes cornell --size 320x240 --frames 3 2>/dev/null |
         sed -n 's/.*primary 16-wide \([0-9.]*\) Mrays.*/\1/p' | head -1)
echo "== motion: $size, one worker of $threads threads, budget $budget ms; raw Embree ${embree:-?} Mrays per cpu-s (Cornell box primary rays, 16-wide)"
for scene_arg in ${scenes//,/ }; do
  scene=$(basename "$scene_arg"); scene=${scene%.gltf}; scene=${scene%.glb}
  for path in ${paths//,/ }; do
    for mode in new legacy; do
      dir="$out/$scene-$path-$mode"
      rm -rf "$dir"
      extra=""
      [ "$mode" = legacy ] && extra="--motion-legacy"
      # shellcheck disable=SC2086  # $args and $extra are lists of options
      build/master/igi-master --scene "$scene_arg" --size "$size" --workers 1 --worker-threads "$threads" --quiet \
        --motion "$path" --motion-out "$dir" --frame-budget-ms "$budget" $extra $args
    done
    # References at every 10th pose (the cameras the runs wrote), cached.
    for camera in "$out/$scene-$path-new"/camera-*.json; do
      pose=$(basename "$camera" .json); pose=${pose#camera-}
      ref="$out/refs/$scene-$path-$size-$ref_spp-$pose.exr"
      # shellcheck disable=SC2086
      [ -f "$ref" ] || build/master/igi-render --scene "$scene_arg" --size "$size" --camera "$camera" --spp "$ref_spp" \
                         --threads "$threads" $args -o "$ref" --quiet >/dev/null
    done
    "$python" scripts/charts/plot_motion.py --compare build/tests/igi-compare --refs "$out/refs" \
      --ref-prefix "$scene-$path-$size-$ref_spp" --budget-ms "$budget" --chart "$out/$scene-$path.png" \
      --title "$scene, $path" "$out/$scene-$path-new" "$out/$scene-$path-legacy"
    # The RESULTS.md row of this scene and path, at the defaults only.
    if [ "$size/$threads/$budget/$ref_spp/$args" = 640x480/2/40/64/ ]; then
      results_set "motion-$scene-$path" "$(python3 - "$out/$scene-$path.json" <<'PY'
import json, sys
new, old = json.load(open(sys.argv[1]))
print("%.1f fps moving (before: %.1f), %.0f %% in budget, longest wait %.0f ms; FLIP moving %.3f (one full "
      "frame: %.3f), flicker between moving frames %.1f %% (largest %.1f %%); FLIP 0.05 %s s after the stop "
      "(before: %s s), 0.03 %s s (%s s)" % (
      new["fps"], old["fps"], 100 * new["within"], 1e3 * new["gap"], new["moving_flip"], old["moving_flip"],
      100 * new["flicker"], 100 * new["flicker_max"], new["to05"], old["to05"], new["to03"], old["to03"]))
PY
)"
    fi
  done
done
