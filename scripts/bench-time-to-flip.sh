#!/usr/bin/env bash
# Time to a FLIP target per suite scene and setting: does one set of
# defaults stay within 2x of the best setting's time everywhere?
# For each scene and each setting (igi's defaults and a few alternatives,
# and pt), renders 1, 2, 4, 8 ... passes (pt: spp) until FLIP against the pt
# reference falls to --target, and prints the first count that reaches it,
# its time, and a time interpolated between the last two counts (log time
# against log FLIP). Per scene: the best setting and defaults / best
# (target: within 2x). One run each; asserts nothing. Images, references and
# the table go to results/time-to-flip/ (references: shared with
# bench-converge.sh, scripts/lib/bench-common.sh).
#
#   scripts/bench-time-to-flip.sh [--size WxH] [--ref-spp N] [--scenes a,b] [--settings a,b] [--target F] [--cap SECONDS]
#
# --settings: only these rows of the table below, by name (defaults always).
set -euo pipefail
cd "$(dirname "$0")/.."
size=128x128
ref_spp=1024
scenes=cornell,corner,rooms,rooms-10,corridor,tilted-light,glossy-medium,glossy,glossy-rough,glass
target=0.1
cap=30
only=""
while [ $# -gt 0 ]; do
  case "$1" in
    --size) size=$2; shift 2 ;;
    --ref-spp) ref_spp=$2; shift 2 ;;
    --scenes) scenes=$2; shift 2 ;;
    --settings) only=$2; shift 2 ;;
    --target) target=$2; shift 2 ;;
    --cap) cap=$2; shift 2 ;;
    *) echo "bench-time-to-flip.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
done
scripts/build.sh >/dev/null
out=results/time-to-flip
mkdir -p "$out" results/converge
render=build/master/igi-render
compare=build/tests/igi-compare

# name|options: the defaults first.
settings=(
  "defaults|"
  "sets-3|--vpl-sets 3"
  "sets-8|--vpl-sets 8"
  "paths-64|--vpl-paths 64"
  "no-clamp|--clamp 0 --compensate 0"
  "no-compensation|--compensate 0"
  "aa-1|--aa 1"
  "power|--importance 0"
  "bidir|--vpl-paths 32 --bidir 32"
  "no-bidir|--bidir 0"
  "pt|--method pt"
)

flip() { "$compare" "$1" "$2" | awk 'NR == 2 { print $4 }'; }
source scripts/lib/bench-common.sh  # seconds, pt_reference
# Time at FLIP = target between (t0, f0) and (t1, f1), in log-log.
interpolate() {
  awk -v t0="$1" -v f0="$2" -v t1="$3" -v f1="$4" -v f="$target" 'BEGIN {
    if (t0 == "" || f0 <= f1) { print t1; exit }
    x = (log(f) - log(f0)) / (log(f1) - log(f0));
    printf "%.3f\n", exp(log(t0) + x * (log(t1) - log(t0))) }'
}

echo "== time to FLIP $target against pt ($size, $ref_spp spp), --threads 2, one run each"
printf "%-13s %-16s %6s %8s %8s %7s\n" scene setting passes seconds interp FLIP
for scene in ${scenes//,/ }; do
  ref=$(pt_reference "$scene" "$size" "$ref_spp")
  [ -f "$ref" ] || "$render" --scene "$scene" --method pt --spp "$ref_spp" --size "$size" -o "$ref" --quiet >/dev/null
  best=""; best_name=""; default_time=""
  for entry in "${settings[@]}"; do
    name=${entry%%|*}; options=${entry#*|}
    [ -z "$only" ] || [ "$name" = defaults ] || [[ ",$only," == *",$name,"* ]] || continue
    p=1; t_prev=""; f_prev=""; reached=""
    while :; do
      img="$out/$scene-$name-$p.exr"
      # shellcheck disable=SC2086
      t=$("$render" --scene "$scene" $options --spp "$p" --seed 1 --size "$size" --threads 2 -o "$img" --quiet | seconds)
      f=$(flip "$ref" "$img")
      if awk -v f="$f" -v g="$target" 'BEGIN { exit !(f <= g) }'; then
        reached=$(interpolate "$t_prev" "$f_prev" "$t" "$f")
        printf "%-13s %-16s %6s %8s %8s %7s\n" "$scene" "$name" "$p" "$t" "$reached" "$f"
        break
      fi
      if awk -v t="$t" -v c="$cap" 'BEGIN { exit !(t > c / 2) }'; then
        printf "%-13s %-16s %6s %8s %8s %7s\n" "$scene" "$name" ">$p" "$t" "-" "$f"
        break
      fi
      t_prev=$t; f_prev=$f; p=$((p * 2))
    done
    [ "$name" = defaults ] && default_time=$reached
    if [ -n "$reached" ] && { [ -z "$best" ] || awk -v a="$reached" -v b="$best" 'BEGIN { exit !(a < b) }'; }; then
      best=$reached; best_name=$name
    fi
  done
  if [ -n "$default_time" ] && [ -n "$best" ]; then
    ratio=$(awk -v a="$default_time" -v b="$best" 'BEGIN { printf "%.2f", a / b }')
    verdict=$(awk -v r="$ratio" 'BEGIN { print (r <= 2.0 ? "met" : "MISSED") }')
    echo "$scene: best $best_name ${best} s; defaults / best = $ratio (within 2x: $verdict)"
  else
    echo "$scene: defaults did not reach FLIP $target within the cap; best ${best_name:-none} ${best:--} s"
  fi
done | tee "$out/table.txt"
