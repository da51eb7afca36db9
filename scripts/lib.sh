# The preamble of every shell script in scripts/, sourced, never run:
#   . "$(dirname "$0")/lib.sh"            (from scripts/slurm/: "$(dirname "$0")/../lib.sh")
# Sourcing it turns on strict mode (set -euo pipefail), moves to the
# repository's root (so a script's paths are the root's, wherever it was
# started from) and defines:
#   RTW_BIN            the release rtw-scan, ${CARGO_TARGET_DIR:-target}/release/rtw-scan
#   RTW_PY             the venv's Python, .venv/bin/python
#   rtw_build [ARGS]   cargo build --release -q ARGS (ARGS default: -p rtw-scan, RTW_BIN)
#   rtw_venv           .venv (once) with scripts/requirements.txt; needs Python >= 3.11
#   rtw_install        rtw_venv, then the package rtw (crates/rtw-py) built and installed
#                      into .venv, once per run (the scripts' labels and statistics are its)
#   rtw_need CMD...    fails, naming the first CMD that is not on PATH
#   rtw_die MSG        MSG on stderr, after the script's name; exit 1
set -euo pipefail
RTW_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$RTW_ROOT"
RTW_BIN=${CARGO_TARGET_DIR:-target}/release/rtw-scan
RTW_PY=.venv/bin/python
RTW_NAME=$(basename "$0" .sh)

rtw_die() {
  echo "$RTW_NAME: $*" >&2
  exit 1
}

rtw_need() {
  local c
  for c in "$@"; do
    command -v "$c" >/dev/null || rtw_die "needs $c on PATH"
  done
}

rtw_build() {
  [ $# -gt 0 ] || set -- -p rtw-scan
  cargo build --release -q "$@"
}

rtw_venv() {
  # The scripts need Python >= 3.11 (tomllib).
  python3 -c 'import sys; sys.exit(sys.version_info < (3, 11))' ||
    rtw_die "Python >= 3.11 is needed, python3 is $(python3 --version 2>&1)"
  if [ ! -x "$RTW_PY" ]; then
    python3 -m venv .venv
  fi
  .venv/bin/pip install --quiet --disable-pip-version-check -r scripts/requirements.txt
}

rtw_install() {
  # Once per run: a script that calls another (reproduce.sh) installs it for both.
  [ -z "${RTW_INSTALLED:-}" ] || return 0
  rtw_venv
  # maturin comes from scripts/requirements.txt (found on PATH in .venv/bin) and
  # builds in the workspace's target/, so an unchanged crate is only relinked.
  PATH="$RTW_ROOT/.venv/bin:$PATH" "$RTW_PY" -m pip install --quiet --disable-pip-version-check \
    --no-build-isolation ./crates/rtw-py
  export RTW_INSTALLED=1
}
