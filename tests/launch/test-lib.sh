# Shared by the launch tests (sourced): the render they ask for, the
# single-process reference, the bit-for-bit check, and skipping.
#   BUILD: the build folder whose programs are tested (ctest passes it)

REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
SKIP=77  # ctest's SKIP_RETURN_CODE for these tests

# Small and quick, and it needs both workers: 30 tiles of 16 x 16 pixels.
RENDER=(--scene cornell --method igi --vpl-paths 8 --size 96x72 --tile 16)
FRAMES=3

# Under CI (CI=true, where scripts/setup.sh installs ssh, Slurm and munge and
# the run is root) a reason to skip is a missing install step: the test fails.
skip() {
  if [ "${CI:-}" = true ]; then echo "FAIL (CI=true, where this must run): $*"; exit 1; fi
  echo "SKIPPED: $*"; exit $SKIP
}
fail() { echo "FAIL: $*"; exit 1; }

# A TCP port on 127.0.0.1 that was free a moment ago.
free_port() { python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }

# The single-process render of the same scene and settings, in $1.
reference() {
  "$BUILD/master/igi-render" "${RENDER[@]}" --threads 1 --quiet -o "$1" >/dev/null 2>&1 || fail "igi-render failed"
}

# Every frame PREFIX-000N.exr equals REFERENCE bit for bit; a difference image
# is written to the test output folder otherwise.
check_frames() {
  local prefix=$1 reference=$2 label=$3 frame diff
  for ((frame = 0; frame < FRAMES; ++frame)); do
    local image=$(printf '%s-%04d.exr' "$prefix" $frame)
    [ -f "$image" ] || fail "$label: frame $frame was not written ($image)"
    diff="$BUILD/test-output/$label-diff-$frame.exr"
    if ! idiff -fail 0 -warn 0 "$image" "$reference" >/dev/null 2>&1; then
      mkdir -p "$BUILD/test-output"
      idiff -fail 0 -warn 0 -abs -o "$diff" "$image" "$reference" | tail -n 4
      fail "$label: frame $frame differs from the single-process render (difference image $diff)"
    fi
  done
  echo "$label: $FRAMES frames equal the single-process render bit for bit"
}

# Waits up to $1 seconds for the command after it to succeed.
wait_until() {
  local seconds=$1 tries
  shift
  for ((tries = 0; tries < seconds * 10; ++tries)); do
    "$@" >/dev/null 2>&1 && return 0
    sleep 0.1
  done
  return 1
}
