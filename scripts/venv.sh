#!/usr/bin/env bash
# Creates .venv (python3 -m venv) with matplotlib for the chart scripts;
# --mitsuba also installs mitsuba==3.9.1 and numpy for scripts/mitsuba/.
# Idempotent: quick when the packages are already there. Prints the venv's python.
set -euo pipefail
cd "$(dirname "$0")/.."
mitsuba=0
case "${1:-}" in
  "") ;;
  --mitsuba) mitsuba=1 ;;
  *) echo "usage: scripts/venv.sh [--mitsuba]" >&2; exit 2 ;;
esac
if ! .venv/bin/python -c "import matplotlib" >/dev/null 2>&1; then
  if ! python3 -m venv .venv >/dev/null 2>&1; then
    echo "python3 -m venv failed: install python3-venv (apt-get install python3-venv)" >&2
    exit 1
  fi
  .venv/bin/pip install --quiet --upgrade pip >&2
  .venv/bin/pip install --quiet matplotlib >&2
fi
if [ "$mitsuba" = 1 ] && ! .venv/bin/python -c \
    "import numpy, mitsuba; assert mitsuba.__version__ == '3.9.1'" >/dev/null 2>&1; then
  .venv/bin/pip install --quiet mitsuba==3.9.1 numpy >&2
fi
echo "$PWD/.venv/bin/python"
