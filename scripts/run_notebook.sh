#!/usr/bin/env bash
# Executes docs/examples/quickstart.ipynb (the Python tutorial) top to bottom with
# nbclient, so the notebook cannot rot: any cell that raises fails this script.
# The executed copy goes to a temporary folder (its path is printed); the
# committed notebook is never rewritten, and must carry no outputs.
# Needs the package installed in the venv (.venv/bin/python -m pip install
# ./crates/rtw-py) and scripts/requirements.txt (nbclient, ipykernel).
#   ./scripts/run_notebook.sh [NOTEBOOK]      PYTHON=... to use another interpreter
. "$(dirname "$0")/lib.sh"

python="${PYTHON:-.venv/bin/python}"
notebook="${1:-docs/examples/quickstart.ipynb}"
work="$(mktemp -d "${TMPDIR:-/tmp}/rtw-notebook.XXXXXX")"

"$python" - "$notebook" "$work" <<'PY'
import sys
from pathlib import Path

import nbformat
from nbclient import NotebookClient

source, work = Path(sys.argv[1]), Path(sys.argv[2])
nb = nbformat.read(source, as_version=4)
stale = [i for i, c in enumerate(nb.cells) if c.cell_type == "code" and (c.outputs or c.execution_count)]
if stale:
    sys.exit(f"run_notebook: {source} is committed with outputs in code cells {stale}: "
             "strip them (Jupyter: Edit > Clear Outputs of All Cells, then save)")
# The kernel runs in the temporary folder: whatever a cell writes lands there.
NotebookClient(nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(work)}}).execute()
out = work / source.name
nbformat.write(nb, out)
print(f"run_notebook: {source}: {sum(c.cell_type == 'code' for c in nb.cells)} code cells ran; executed copy {out}")
PY
