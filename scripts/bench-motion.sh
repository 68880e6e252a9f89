#!/usr/bin/env bash
# The window's behaviour while the camera moves, measured headless through
# the same session code (igi-master --motion, master/run/motion_run.cpp): a
# scripted user drags (30 degrees a second) or walks (W held) for 2 s, then
# holds still for 4 s; one mode after the other on the same machine:
#   sharp   today's: sharp previews (camera rays at every pixel, light on a
#           lattice), refining after the stop (--previews sharp)
#   coarse  previews over fewer pixels, the full frame at once after the
#           stop (--previews coarse: the window before sharp previews)
#   legacy  as before motion was handled (--motion-legacy: no budget, stale
#           frames dropped, the image thrown away on every move)
# Prints per scene, path and mode: frames shown a second while moving, the
# share of moving frames within the budget, the longest wait between two
# frames while moving, the median FLIP of moving frames at every 10th pose
# (previews upscaled as the window shows them), the flicker between
# consecutive moving frames (the median and largest change of a frame's mean
# luminance against the one before), and the time after the stop to the
# first frame at full resolution and to FLIP 0.1, 0.05 and 0.03; beside raw
# Embree's rate (igi-bench). References: igi at --ref-spp passes at each 10th
# pose, cached in results/motion/refs/. Charts FLIP against time after the
# stop (results/motion/SCENE-PATH.png). One run each; asserts nothing.
# A scene is a built-in name or a .gltf/.glb file (named by its file name in
# results/); --args passes igi-master options to every run (e.g.
# --no-light-guide). --real DIR adds the third-party scenes there, Sponza and
# BreakfastRoom, each under a sky of 1, 1, 1, dragged (their references at
# --real-ref-spp passes).
#
#   scripts/bench-motion.sh [--scenes cornell,glossy,rooms-10] [--paths drag,walk] [--size 640x480]
#                           [--threads 2] [--budget-ms 40] [--ref-spp 64] [--args "OPTIONS"]
#                           [--modes sharp,coarse,legacy] [--real ../shared/scenes] [--real-ref-spp 16]
set -euo pipefail
cd "$(dirname "$0")/.."
scenes=cornell,glossy,rooms-10
paths=drag,walk
size=640x480
threads=2
budget=40
ref_spp=64
args=""
modes=sharp,coarse,legacy
real=""
real_ref_spp=16
while [ $# -gt 0 ]; do
  case "$1" in
    --scenes) scenes=$2; shift 2 ;;
    --paths) paths=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --budget-ms) budget=$2; shift 2 ;;
    --ref-spp) ref_spp=$2; shift 2 ;;
    --args) args=$2; shift 2 ;;
    --modes) modes=$2; shift 2 ;;
    --real) real=$2; shift 2 ;;
    --real-ref-spp) real_ref_spp=$2; shift 2 ;;
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
# measure SCENE_ARG NAME PATH REF_SPP [igi-master options...]: every mode, the references, the chart and the row.
measure() {
  local scene_arg=$1 scene=$2 path=$3 spp=$4; shift 4
  local runs=() mode dir extra camera pose ref
  for mode in ${modes//,/ }; do
    dir="$out/$scene-$path-$mode"
    rm -rf "$dir"
    case "$mode" in
      sharp) extra="--previews sharp" ;;
      coarse) extra="--previews coarse" ;;
      legacy) extra="--motion-legacy" ;;
      *) echo "bench-motion.sh: unknown mode '$mode'" >&2; exit 2 ;;
    esac
    # shellcheck disable=SC2086  # $args and $extra are lists of options
    build/master/igi-master --scene "$scene_arg" --size "$size" --workers 1 --worker-threads "$threads" --quiet \
      --motion "$path" --motion-out "$dir" --frame-budget-ms "$budget" $extra $args "$@"
    runs+=("$dir")
  done
  # References at every 10th pose (the cameras the runs wrote), cached.
  for camera in "${runs[0]}"/camera-*.json; do
    pose=$(basename "$camera" .json); pose=${pose#camera-}
    ref="$out/refs/$scene-$path-$size-$spp-$pose.exr"
    # shellcheck disable=SC2086
    [ -f "$ref" ] || build/master/igi-render --scene "$scene_arg" --size "$size" --camera "$camera" --spp "$spp" \
                       --threads "$threads" $args "$@" -o "$ref" --quiet >/dev/null
  done
  "$python" scripts/charts/plot_motion.py --compare build/tests/igi-compare --refs "$out/refs" \
    --ref-prefix "$scene-$path-$size-$spp" --budget-ms "$budget" --chart "$out/$scene-$path.png" \
    --title "$scene, $path" "${runs[@]}"
  # The RESULTS.md row of this scene and path, at the defaults only: sharp against coarse previews.
  if [ "$size/$threads/$budget/$args/$modes" = 640x480/2/40//sharp,coarse,legacy ]; then
    results_set "motion-$scene-$path" "$(python3 - "$out/$scene-$path.json" <<'PY'
import json, sys
new, old, _ = json.load(open(sys.argv[1]))
print("%.1f fps moving (coarse previews: %.1f), %.0f %% in budget (%.0f %%); FLIP moving %.3f (%.3f); flicker "
      "%.1f %%; after the stop: full resolution %s s (%s s), FLIP 0.1 %s s (%s s), 0.05 %s s (%s s)" % (
      new["fps"], old["fps"], 100 * new["within"], 100 * old["within"], new["moving_flip"], old["moving_flip"],
      100 * new["flicker"], new["to_full_res"], old["to_full_res"], new["to10"], old["to10"], new["to05"], old["to05"]))
PY
)"
  fi
}

for scene_arg in ${scenes//,/ }; do
  scene=$(basename "$scene_arg"); scene=${scene%.gltf}; scene=${scene%.glb}
  for path in ${paths//,/ }; do measure "$scene_arg" "$scene" "$path" "$ref_spp"; done
done
if [ -n "$real" ]; then
  for file in "$real/sponza/Sponza.gltf" "$real/breakfast_room/BreakfastRoom.gltf"; do
    scene=$(basename "$file" .gltf)-sky
    if [ -f "$file" ]; then measure "$file" "$scene" drag "$real_ref_spp" --environment 1,1,1
    else echo "($file is not there: skipped)"; fi
  done
fi
