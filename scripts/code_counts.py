#!/usr/bin/env python3
"""The structure counts docs/architecture.md reports, measured on the tree:

- production lines per folder: the lines of each crate's `src/` folder (one
  level down: `rtw-scan/src/scan`, …) outside `#[cfg(test)]` modules and
  test-only files;
- imports against the layers (scripts/rtwscripts/structure.py, rule 3);
- files over 600 raw lines, tests included;
- integration-test binaries: each `tests/*.rs` file and each `tests/NAME/main.rs`
  of a crate is one binary cargo builds and links.

Usage: python3 scripts/code_counts.py [--folders]
"""

import os
import sys

from rtwscripts import structure as cs

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def production_lines(crate):
    """Folder (relative to the crate's src/) -> lines outside tests."""
    src = os.path.join(crate, "src")
    files = cs.module_files(src)
    tests = cs.test_modules(files)
    out = {}
    for mod, path in files.items():
        if any(mod[: len(t)] == t for t in tests):
            continue
        raw = open(path, encoding="utf-8").read()
        n = raw.count("\n") - sum(b - a + 1 for a, b in cs.test_block_spans(raw))
        folder = os.path.relpath(os.path.dirname(path), src)
        key = os.path.join(os.path.basename(crate), folder if folder != "." else "")
        out[key] = out.get(key, 0) + n
    return out


def main():
    crates = cs.default_crates()
    per_folder = {}
    for c in crates:
        per_folder.update(production_lines(c))
    raw_over = []
    for dirpath, _, names in os.walk(os.path.join(ROOT, "crates")):
        if "/target" in dirpath:
            continue
        for n in names:
            if n.endswith(".rs"):
                p = os.path.join(dirpath, n)
                lines = open(p, encoding="utf-8").read().count("\n")
                if lines > cs.MAX_LINES:
                    raw_over.append((lines, os.path.relpath(p, ROOT)))
    binaries = []
    for c in crates:
        tests = os.path.join(c, "tests")
        if not os.path.isdir(tests):
            continue
        for n in sorted(os.listdir(tests)):
            if n.endswith(".rs") or os.path.isfile(os.path.join(tests, n, "main.rs")):
                binaries.append(os.path.join(os.path.basename(c), "tests", n))
    import io
    import contextlib

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        bad = [b for c in crates for b in cs.check(c)]
    against = [b for b in bad if b.startswith("import against the layers")]
    if "--folders" in sys.argv:
        for k in sorted(per_folder):
            print(f"{per_folder[k]:6d}  {k}")
    crate_totals = {}
    for k, v in per_folder.items():
        crate_totals[k.split("/")[0]] = crate_totals.get(k.split("/")[0], 0) + v
    print("production lines per crate: " + ", ".join(f"{k} {v}" for k, v in sorted(crate_totals.items())))
    print(f"imports against the layers: {len(against)}")
    print(f"files over {cs.MAX_LINES} raw lines (tests included): {len(raw_over)}"
          + "".join(f"\n  {n} {p}" for n, p in sorted(raw_over, reverse=True)))
    print(f"integration-test binaries: {len(binaries)}")


if __name__ == "__main__":
    main()
