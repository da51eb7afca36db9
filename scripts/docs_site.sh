#!/usr/bin/env bash
# Builds the documentation site (Sphinx with MyST over docs/, results/ and
# the README; docs/conf.py says why that pair) into target/docs-site/, with
# every warning an error (a page no table of contents reaches, a link to a
# page or anchor that does not exist), then checks it with
# scripts/check_site.py: every local link and anchor of every page resolves,
# and the first page renders in headless Chromium. Needs the project's .venv
# with rtw installed (the Python API page is read from the package):
# ./scripts/test.sh makes both first. Open target/docs-site/docs/index.html.
. "$(dirname "$0")/lib.sh"
rtw_venv >/dev/null
out="${CARGO_TARGET_DIR:-target}/docs-site"
rm -rf "$out"
.venv/bin/python -m sphinx -q -W --keep-going -b html -c docs . "$out"
"$RTW_PY" scripts/check_site.py "$out"
