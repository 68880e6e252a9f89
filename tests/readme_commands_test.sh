#!/usr/bin/env bash
# Every igi-render and local igi-master command in the README's sh blocks
# runs as written, at 48x36 (a --size appended last wins; frames, passes and
# everything else stay as the README says), in a scratch folder:
#   tests/readme_commands_test.sh SOURCE_DIR BUILD_DIR
# The user's own files the commands name (my-scene.glb, anim.glb, scene.glb)
# are stood in for by the Cornell box, exported. A window (--show, or a master
# without --frames) runs under xvfb-run and closes after its first frame
# (--screenshot); without xvfb-run those commands are skipped, and under CI
# (CI=true, where scripts/setup.sh installs it) that is a failure.
set -euo pipefail
src=$1 build=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
mkdir -p build
ln -s "$build/master" build/master
ln -s "$build/worker" build/worker
build/master/igi-render --scene cornell --export-gltf my-scene.glb >/dev/null
cp my-scene.glb scene.glb
cp my-scene.glb anim.glb

# The sh blocks' lines, continuations joined, comments dropped.
commands=$(awk '/^```sh/{f=1;next} /^```/{f=0} f' "$src/README.md" |
           sed -e ':a' -e '/\\$/N; s/\\\n//; ta' | sed -e 's/[[:space:]]#.*$//' |
           grep -E '^build/master/igi-(render|master --workers [1-9])' || true)
[ -n "$commands" ] || { echo "no igi-render or igi-master command found in the README"; exit 1; }
have_xvfb=0
command -v xvfb-run >/dev/null 2>&1 && have_xvfb=1
ran=0 skipped=0 failed=0
while IFS= read -r line; do
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
  if out=$(eval "$run" 2>&1 </dev/null); then
    echo "ok: $line"
  else
    echo "FAILED: $line"; echo "$out" | tail -5; failed=$((failed + 1))
  fi
  ran=$((ran + 1))
done <<<"$commands"
echo "$ran README commands run, $failed failed, $skipped skipped"
[ $failed = 0 ]
