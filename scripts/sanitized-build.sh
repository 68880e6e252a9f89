#!/usr/bin/env bash
# Configures and builds a sanitizer build with clang:
#   scripts/sanitized-build.sh asan [ninja targets...]  ASan + UBSan, and the libFuzzer
#                                                       targets, into build-asan/
#   scripts/sanitized-build.sh tsan [ninja targets...]  ThreadSanitizer, into build-tsan/
# Without targets it builds everything. -O1 and line tables only keep the build
# short (CI builds both); reports still name file and line.
set -euo pipefail
cd "$(dirname "$0")/.."
kind=${1:?usage: scripts/sanitized-build.sh asan|tsan [targets...]}
shift
scripts/setup.sh
case "$kind" in
  asan) sanitize="-fsanitize=address,undefined -fno-sanitize-recover=undefined"; extra=(-DIGI_FUZZ=ON) ;;
  tsan) sanitize="-fsanitize=thread"; extra=() ;;
  *) echo "sanitized-build.sh: unknown kind '$kind' (asan or tsan)" >&2; exit 2 ;;
esac
dir="build-$kind"
if [ ! -f "$dir/build.ninja" ]; then
  CC=clang-14 CXX=clang++-14 cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Sanitize \
    -DCMAKE_CXX_FLAGS_SANITIZE="-O1 -gline-tables-only -fno-omit-frame-pointer $sanitize" \
    -DCMAKE_EXE_LINKER_FLAGS="$sanitize" "${extra[@]}" >/dev/null
fi
ninja -C "$dir" "$@"
