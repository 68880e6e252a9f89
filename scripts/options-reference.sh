#!/bin/sh
# Writes master/options/OPTIONS.md, the options reference the README links,
# from the settings' table and the programs' command lines (igi-options-reference
# prints it). Run after adding or changing an option; ctest's
# Options.TheOptionsReferenceIsCurrent fails until then.
# Usage: scripts/options-reference.sh [BUILD_DIR]   (default: build)
set -e
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-"$root/build"}
ninja -C "$build" igi-options-reference >/dev/null
"$build/master/igi-options-reference" > "$root/master/options/OPTIONS.md"
echo "wrote master/options/OPTIONS.md"
