#!/usr/bin/env bash
# Every command in the README's sh blocks runs as written, in a scratch
# folder that holds the build and the repository's tests/ (the sample scenes
# the README names, tests/data/interior/):
#   tests/readme_commands_test.sh SOURCE_DIR BUILD_DIR
# Renders run at 48x36 (a --size appended last wins; frames, passes and
# everything else stay as the README says). A window (--show, or a master
# without --frames) runs under xvfb-run and closes after its first frame
# (--screenshot); without xvfb-run those commands are skipped, and under CI
# (CI=true, where scripts/setup.sh installs it) that is a failure. The
# several-machines block runs on this one: its master in the background, its
# worker with MASTER-HOST read as 127.0.0.1. Not run: scripts/ (setup, build
# and test: what runs this), and the cluster launchers, which need ssh hosts
# or Slurm (tests/launch/ runs them against stand-ins).
set -euo pipefail
src=$1 build=$2
work=$(mktemp -d)
master_pid=
trap '[ -n "$master_pid" ] && kill "$master_pid" 2>/dev/null; rm -rf "$work"' EXIT
cd "$work"
mkdir -p build
ln -s "$build/master" build/master
ln -s "$build/worker" build/worker
ln -s "$src/tests" tests
ln -s "$src/scripts" scripts

# The sh blocks' lines, continuations joined, comments dropped.
commands=$(awk '/^```sh/{f=1;next} /^```/{f=0} f' "$src/README.md" |
           sed -e ':a' -e '/\\$/N; s/\\\n//; ta' | sed -e 's/[[:space:]]#.*$//' -e 's/[[:space:]]*$//' |
           grep -v -E '^(#|$)' || true)
[ -n "$commands" ] || { echo "no command found in the README"; exit 1; }
have_xvfb=0
command -v xvfb-run >/dev/null 2>&1 && have_xvfb=1
ran=0 skipped=0 failed=0

run_one() {  # LINE COMMAND: runs COMMAND, reports it under LINE
  local out
  if out=$(eval "$2" 2>&1 </dev/null); then
    echo "ok: $1"
  else
    echo "FAILED: $1"; echo "$out" | tail -5; failed=$((failed + 1))
  fi
  ran=$((ran + 1))
}

while IFS= read -r line; do
  case "$line" in
    scripts/demo.sh*|scripts/test.sh*|scripts/launch-*|sbatch\ *|salloc\ *|printf\ *\>\ hosts.txt)
      echo "not run here: $line"; continue ;;
    build/master/igi-keys\ *|mkdir\ *|cp\ *)
      run_one "$line" "$line"; continue ;;
    build/master/igi-master\ --workers\ 0\ *)  # waits for the worker line that follows
      eval "timeout -s KILL 150 $line --size 48x36" >master.log 2>&1 </dev/null &
      master_pid=$!
      continue ;;
    build/worker/igi-worker\ *)
      run_one "$line" "timeout -s KILL 120 ${line//MASTER-HOST/127.0.0.1}"
      if [ -n "$master_pid" ]; then
        if wait "$master_pid"; then echo "ok: the master it served"
        else echo "FAILED: the master it served"; tail -5 master.log; failed=$((failed + 1)); fi
        master_pid=
      fi
      continue ;;
  esac
  run="$line --size 48x36"
  window=0
  case "$line" in
    *--help*) run="$line" ;;
    *--show*) window=1; run="$run --screenshot shot-$ran.png" ;;
    *igi-master*) case "$line" in *--frames*) ;; *) window=1; run="$run --screenshot shot-$ran.png --screenshot-after 1" ;; esac ;;
  esac
  if [ $window = 1 ]; then
    if [ $have_xvfb = 0 ]; then
      [ "${CI:-}" = true ] && { echo "FAILED (no xvfb-run under CI): $line"; failed=$((failed + 1)); continue; }
      echo "skipped (no xvfb-run): $line"; skipped=$((skipped + 1)); continue
    fi
    run="timeout -s KILL 120 xvfb-run -a -s '-screen 0 640x480x24' $run"
  fi
  run_one "$line" "$run"
done <<<"$commands"
[ -z "$master_pid" ] || { echo "FAILED: a master with --workers 0 and no worker line after it"; failed=$((failed + 1)); }
echo "$ran README commands run, $failed failed, $skipped skipped"
[ $failed = 0 ]
