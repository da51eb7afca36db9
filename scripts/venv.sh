#!/usr/bin/env bash
# Creates (once) the project's Python venv in .venv and installs
# scripts/requirements.txt into it. Used by the test command, the figures
# and the report scripts; safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."
# The scripts need Python >= 3.11 (tomllib).
python3 -c 'import sys; sys.exit(sys.version_info < (3, 11))' ||
  { echo "venv.sh: Python >= 3.11 is needed, python3 is $(python3 --version 2>&1)" >&2; exit 1; }
if [ ! -x .venv/bin/python ]; then
  python3 -m venv .venv
fi
.venv/bin/pip install --quiet --disable-pip-version-check -r scripts/requirements.txt
