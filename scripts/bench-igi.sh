#!/usr/bin/env bash
# Throughput of the IGI renderer (issue figures in the README): igi against
# raw Embree on the same rays, fps, border overhead, filter cost per width.
# Run on an otherwise idle machine; prints figures, asserts nothing.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
build/tests/igi-bench "$@"
echo
build/tests/filter-bench
