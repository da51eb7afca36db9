#!/usr/bin/env bash
# Runs README.md's "From Python" section as a newcomer would: its install
# line (a fresh venv, pip with build isolation, the extras it names), then
# its Python example, so the README cannot promise an example its own
# install line does not support. Both are read from README.md itself. The
# venv the README calls `v` is made in a temporary folder instead (removed
# afterwards), so no file of the checkout, nor a `v/` of the user's, is
# touched; the commands run from the repository's root, as the README's do.
#   ./scripts/check_readme_python.sh
. "$(dirname "$0")/lib.sh"

work="$(mktemp -d "${TMPDIR:-/tmp}/rtw-readme.XXXXXX")"
trap 'rm -rf "$work"' EXIT

# The section's first ```sh block is the install line, its first ```python
# block the example.
python3 - README.md "$work" <<'PY'
import re, sys
from pathlib import Path

readme, work = Path(sys.argv[1]).read_text(), Path(sys.argv[2])
section = readme.split("\n## From Python\n", 1)[1].split("\n## ", 1)[0]
def block(lang):
    m = re.search(rf"```{lang}\n(.*?)```", section, re.S)
    if not m:
        sys.exit(f"check_readme_python: README.md's 'From Python' has no ```{lang} block")
    return m.group(1)
install = [l.split("#", 1)[0].strip() for l in block("sh").splitlines()]
install = [l for l in install if l]
m = re.fullmatch(r"python3 -m venv (\S+) && \1/bin/pip install (.+)", " ".join(install))
if not m:
    sys.exit("check_readme_python: README.md's install line is not "
             "`python3 -m venv DIR && DIR/bin/pip install ...`: update this script with it")
(work / "install-args").write_text(m.group(2))
(work / "example.py").write_text(block("python"))
PY

echo "check_readme_python: python3 -m venv v && v/bin/pip install $(cat "$work/install-args")  (v = $work/v)"
python3 -m venv "$work/v"
# pip builds the package with maturin in an isolated environment; in the
# workspace's target/ an unchanged crate is only relinked.
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$PWD/target}"
eval "\"$work/v/bin/pip\" install --quiet --disable-pip-version-check $(cat "$work/install-args")"
echo "check_readme_python: the README's example"
"$work/v/bin/python" "$work/example.py"
