#!/bin/sh
# The benchmarks' one entry. Without arguments: each benchmark, what it
# measures, and the RESULTS.md section its figures replace. With NAME [ARGS]:
# runs scripts/bench-NAME.sh ARGS (each builds what it needs and writes
# results/NAME/; its --help says its options).
#   scripts/bench.sh                      # the list
#   scripts/bench.sh igi                  # IGI throughput (RESULTS.md, "Frame time")
#   scripts/bench.sh converge --scenes cornell
set -e
here=$(cd "$(dirname "$0")" && pwd)
if [ $# -eq 0 ]; then
  cat <<'LIST'
benchmark     what it measures                                                  RESULTS.md section
igi           frames a second; igi against raw Embree on the same rays          Frame time
accuracy      speed against accuracy on the scene suite, Pareto fronts          Time to an error
converge      pt against Mitsuba 3; igi against pt over 1-256 passes            Convergence, Convergence on images
time-to-flip  per scene, the time each setting takes to FLIP 0.1                Time to an error
lightcuts     lightcuts against ir over the same VPLs, and against pt           Lightcuts
caustics      the caustic photon map's cost and gain on the glass scene         (history/)
motion        the window's session while a scripted user drags or walks         While the camera moves
stability     the first pass: flicker over seeds, FLIP at one pass, guide on/off  A first pass you can trust
display       the window's display and panel costs under Xvfb                   (history/)
scaling       master + workers against the single-process render                The cluster
master        one master with 8 to 256 simulated workers                        The cluster
network       (root) master and workers over a shaped 1 and 10 Gbit/s link      The cluster, "Over a shaped link"
trust         a slow worker, colluding keys, fakes, a flood (real processes)    The cluster, "Trust"
viewer        (root) igi-view driving a master over a shaped 20/50 Mbit/s link    A window on another machine
LIST
  exit 0
fi
name=$1
shift
script="$here/bench-$name.sh"
if [ ! -x "$script" ]; then
  echo "bench.sh: no benchmark '$name' (scripts/bench.sh lists them)" >&2
  exit 2
fi
exec "$script" "$@"
