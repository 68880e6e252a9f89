#!/usr/bin/env bash
# Creates .venv (python3 -m venv) with matplotlib for the chart scripts.
# Idempotent: quick when matplotlib is already there. Prints the venv's python.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! .venv/bin/python -c "import matplotlib" >/dev/null 2>&1; then
  if ! python3 -m venv .venv >/dev/null 2>&1; then
    echo "python3 -m venv failed: install python3-venv (apt-get install python3-venv)" >&2
    exit 1
  fi
  .venv/bin/pip install --quiet --upgrade pip >&2
  .venv/bin/pip install --quiet matplotlib >&2
fi
echo "$PWD/.venv/bin/python"
