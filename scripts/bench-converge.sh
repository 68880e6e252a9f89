#!/usr/bin/env bash
# Does the renderer converge to the right image? Two rulers, in one run:
#   1. pt against Mitsuba 3 (scripts/mitsuba/, the independent reference) on
#      every suite scene, both at --ref-spp from the same glTF: mean ratio
#      and relMSE (target: pt within 1 % of Mitsuba in mean).
#   2. igi at the defaults against that pt reference at 1, 4, 16 and 64
#      passes (--spp), the median over --seeds seeds: mean ratio, relMSE,
#      FLIP and time (targets: within 5 % of pt in mean at 4 passes, 2 % at
#      16; relMSE and FLIP never rise from 4 to 16 to 64 passes).
# Prints figures and the targets met or missed; asserts nothing. Images,
# references and the table go to results/converge/.
#
#   scripts/bench-converge.sh [--size WxH] [--ref-spp N] [--scenes a,b] [--seeds K] [--passes 1,4,16,64]
set -euo pipefail
cd "$(dirname "$0")/.."
size=128x128
ref_spp=1024
scenes=cornell,corner,rooms,rooms-10,corridor,tilted-light,glossy,glossy-rough,glass
seeds=3
passes=1,4,16,64
while [ $# -gt 0 ]; do
  case "$1" in
    --size) size=$2; shift 2 ;;
    --ref-spp) ref_spp=$2; shift 2 ;;
    --scenes) scenes=$2; shift 2 ;;
    --seeds) seeds=$2; shift 2 ;;
    --passes) passes=$2; shift 2 ;;
    *) echo "bench-converge.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
done
scripts/build.sh >/dev/null
python="$(scripts/venv.sh --mitsuba)"
out=results/converge
mkdir -p "$out"
render=build/master/igi-render
compare=build/tests/igi-compare

# Columns of igi-compare's row for IMAGE against REF: relMSE RMSE FLIP mean.
metrics() { "$compare" "$1" "$2" | awk 'NR == 2 { print $2, $4, $5 }'; }
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
source scripts/lib/bench-common.sh  # seconds, pt_reference

echo "== pt against Mitsuba 3 ($size, $ref_spp spp each; mean = pt / Mitsuba)"
printf "%-14s %8s %9s %8s %9s\n" scene mean relMSE pt_s mitsuba_s
for scene in ${scenes//,/ }; do
  gltf="$out/$scene.gltf"
  "$render" --scene "$scene" --export-gltf "$gltf" --quiet >/dev/null
  mts="$out/$scene-mitsuba-$size-$ref_spp.exr"
  mts_s=cached
  if [ ! -f "$mts" ]; then
    mts_s=$("$python" scripts/mitsuba/render.py "$gltf" -o "$mts" --size "$size" --spp "$ref_spp" |
            sed -n 's/.* \([0-9.]*\) s$/\1/p' | tail -1)
  fi
  ref=$(pt_reference "$scene" "$size" "$ref_spp")
  pt_s=cached
  if [ ! -f "$ref" ]; then
    pt_s=$("$render" --scene "$scene" --method pt --spp "$ref_spp" --size "$size" -o "$ref" --quiet | seconds)
  fi
  read -r relmse _ mean <<<"$(metrics "$mts" "$ref")"
  printf "%-14s %8s %9s %8s %9s\n" "$scene" "$mean" "$relmse" "$pt_s" "$mts_s"
done

echo
echo "== igi at the defaults against pt ($size, medians over $seeds seeds; mean = igi / pt)"
printf "%-14s %6s %8s %9s %7s %7s\n" scene passes mean relMSE FLIP s
for scene in ${scenes//,/ }; do
  ref=$(pt_reference "$scene" "$size" "$ref_spp")
  for p in ${passes//,/ }; do
    rows=()
    for k in $(seq 1 "$seeds"); do
      # Pass q of a render uses seed + q (master/offline_render.cpp): seeds 1000 apart share no pass.
      seed=$(( (k - 1) * 1000 + 1 ))
      img="$out/$scene-igi-$p-$seed.exr"
      s=$("$render" --scene "$scene" --spp "$p" --seed "$seed" --size "$size" -o "$img" --quiet | seconds)
      rows+=("$(metrics "$ref" "$img") $s")
    done
    col() { printf "%s\n" "${rows[@]}" | awk -v c="$1" '{ print $c }' | median; }
    printf "%-14s %6s %8s %9s %7s %7s\n" "$scene" "$p" "$(col 3)" "$(col 1)" "$(col 2)" "$(col 4)"
  done
done | tee "$out/igi.txt"
