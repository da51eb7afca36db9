#!/usr/bin/env bash
# Creates (once) the project's Python venv in .venv and installs
# scripts/requirements.txt into it (scripts/lib.sh's rtw_venv). Used by the
# test command, the figures and the report scripts; safe to run again.
. "$(dirname "$0")/lib.sh"
rtw_venv
