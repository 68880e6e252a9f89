#!/usr/bin/env bash
# Does the renderer converge to the right image? Two rulers, in one run:
#   1. pt against Mitsuba 3 (scripts/mitsuba/, the independent reference) on
#      every suite scene, both at --ref-spp from the same glTF: mean ratio
#      and relMSE (target: pt within 1 % of Mitsuba in mean).
#   2. igi at the defaults against that pt reference at 1, 4, 16, 64 and 256
#      passes (--spp), the median over --seeds seeds: mean ratio, relMSE,
#      relMSE2 (relMSE against two independent pt references, their own
#      noise cancelled: image/metrics.h), FLIP and time; then per scene the
#      fitted rate (relMSE2 ~ passes^-rate from 16 passes on) and relMSE2 at
#      the last pass over 16 passes' (targets: within 5 % of pt in mean at 4
#      passes, 1 % at 16; relMSE at 256 passes at most 0.4x its value at 16,
#      rate 1 where noise alone is left).
# Prints figures and the targets met or missed; asserts nothing. Images,
# references and the table go to results/converge/.
#
#   scripts/bench-converge.sh [--size WxH] [--ref-spp N] [--scenes a,b] [--seeds K] [--passes 1,4,16,64,256]
#                             [--igi-only]   (part 2 alone: no Mitsuba renders)
set -euo pipefail
cd "$(dirname "$0")/.."
size=128x128
ref_spp=1024
scenes=cornell,corner,rooms,rooms-10,corridor,tilted-light,glossy-medium,glossy,glossy-rough,glass
seeds=3
passes=1,4,16,64,256
igi_only=0
while [ $# -gt 0 ]; do
  case "$1" in
    --size) size=$2; shift 2 ;;
    --ref-spp) ref_spp=$2; shift 2 ;;
    --scenes) scenes=$2; shift 2 ;;
    --seeds) seeds=$2; shift 2 ;;
    --passes) passes=$2; shift 2 ;;
    --igi-only) igi_only=1; shift ;;
    *) echo "bench-converge.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
done
scripts/build.sh >/dev/null
python="$(scripts/venv.sh --mitsuba)"
out=results/converge
mkdir -p "$out"
render=build/master/igi-render
compare=build/tests/igi-compare

# Columns of igi-compare's row for IMAGE ($3) against REF ($1) and REF2 ($2): relMSE FLIP mean relMSE2.
metrics() { "$compare" --second-reference "$2" "$1" "$3" | awk 'NR == 2 { print $2, $4, $5, $6 }'; }
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
source scripts/lib/bench-common.sh  # seconds, pt_reference

[ $igi_only = 0 ] && echo "== pt against Mitsuba 3 ($size, $ref_spp spp each; mean = pt / Mitsuba)"
[ $igi_only = 0 ] && printf "%-14s %8s %9s %8s %9s\n" scene mean relMSE pt_s mitsuba_s
for scene in ${scenes//,/ }; do
  gltf="$out/$scene.gltf"
  "$render" --scene "$scene" --export-gltf "$gltf" --quiet >/dev/null
  mts="$out/$scene-mitsuba-$size-$ref_spp.exr"
  mts_s=cached
  if [ ! -f "$mts" ] && [ $igi_only = 0 ]; then
    mts_s=$("$python" scripts/mitsuba/render.py "$gltf" -o "$mts" --size "$size" --spp "$ref_spp" |
            sed -n 's/.* \([0-9.]*\) s$/\1/p' | tail -1)
  fi
  ref=$(pt_reference "$scene" "$size" "$ref_spp")
  pt_s=cached
  if [ ! -f "$ref" ]; then
    pt_s=$("$render" --scene "$scene" --method pt --spp "$ref_spp" --size "$size" -o "$ref" --quiet | seconds)
  fi
  # A second, independent reference (other samples): relMSE2 cancels the two references' noise.
  ref2=${ref%.exr}-b.exr
  [ -f "$ref2" ] || "$render" --scene "$scene" --method pt --spp "$ref_spp" --seed 7001 --size "$size" -o "$ref2" --quiet >/dev/null
  [ $igi_only = 1 ] && continue
  read -r relmse _ mean <<<"$("$compare" "$mts" "$ref" | awk 'NR == 2 { print $2, $4, $5 }')"
  printf "%-14s %8s %9s %8s %9s\n" "$scene" "$mean" "$relmse" "$pt_s" "$mts_s"
done

echo
echo "== igi at the defaults against pt ($size, medians over $seeds seeds; mean = igi / pt)"
printf "%-14s %6s %8s %9s %9s %7s %7s\n" scene passes mean relMSE relMSE2 FLIP s
for scene in ${scenes//,/ }; do
  ref=$(pt_reference "$scene" "$size" "$ref_spp")
  ref2=${ref%.exr}-b.exr
  for p in ${passes//,/ }; do
    rows=()
    for k in $(seq 1 "$seeds"); do
      # Pass q of a render uses seed + q (master/offline_render.cpp): seeds 1000 apart share no pass.
      seed=$(( (k - 1) * 1000 + 1 ))
      img="$out/$scene-igi-$p-$seed.exr"
      s=$("$render" --scene "$scene" --spp "$p" --seed "$seed" --size "$size" -o "$img" --quiet | seconds)
      rows+=("$(metrics "$ref" "$ref2" "$img") $s")
    done
    col() { printf "%s\n" "${rows[@]}" | awk -v c="$1" '{ print $c }' | median; }
    printf "%-14s %6s %8s %9s %9s %7s %7s\n" "$scene" "$p" "$(col 3)" "$(col 1)" "$(col 4)" "$(col 2)" "$(col 5)"
  done
done | tee "$out/igi.txt"

echo
echo "== how relMSE2 falls from 16 passes on (rate: least-squares slope of -log relMSE2 on log passes; target ratio <= 0.4 at 256)"
awk '$2 ~ /^[0-9]+$/ && $2 >= 16 { n[$1]++; x = log($2); y = log($5 > 1e-7 ? $5 : 1e-7)
       sx[$1] += x; sy[$1] += y; sxx[$1] += x * x; sxy[$1] += x * y
       if ($2 == 16) first[$1] = $5; last[$1] = $5; lastp[$1] = $2 }
     END { printf "%-14s %7s %14s %7s\n", "scene", "rate", "last/16", "target"
           for (s in n) { if (n[s] < 2) continue
             rate = -(n[s] * sxy[s] - sx[s] * sy[s]) / (n[s] * sxx[s] - sx[s] * sx[s])
             ratio = first[s] > 0 ? last[s] / first[s] : 0
             target = "-"; if (lastp[s] >= 256) target = ratio <= 0.4 ? "met" : "missed"
             printf "%-14s %7.2f %8.3f (%3d) %7s\n", s, rate, ratio, lastp[s], target } }' \
  "$out/igi.txt"
