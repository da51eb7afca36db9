"""Runs every documented command of README.md and docs/*.md as written, so
that no page promises a command that fails, and checks that none of them
writes into a committed file.

A documented command is a line of a fenced code block (```sh, ```bash or a
block without a language) that starts with `rtw-scan `, `cargo run
--release -p rtw-scan -- `, `v/bin/python -m rtw ` (the README's venv;
here the test command's `.venv`) or `cp configs/` (a config to edit). Lines continued with a backslash are
joined; a trailing `# comment` is dropped. A line that still holds a
placeholder (`CONFIG`, `DIR`, `[--flag]`, `…`, `|`) is a synopsis, not a
command, and is only counted. A block preceded by
`<!-- check: skip (why) -->` is not run (a command of minutes); the reason
is printed.

The commands run in the order they appear, file by file, in a temporary
folder that holds what a fresh clone has of `configs/`, `results/` and
`scripts/` (`git archive HEAD`), with `rtw-scan` on the PATH as
`target/release/rtw-scan`. Afterwards every committed file there must be
unchanged: examples write under `runs/`, never into `results/`.

Usage: .venv/bin/python scripts/check_doc_commands.py [FILE ...]
"""

from __future__ import annotations

import hashlib
import os
import re
import shlex
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BLOCK = re.compile(r"(?P<before>[^\n]*)\n```(?P<lang>[a-z]*)\n(?P<body>.*?)```", re.S)
PREFIXES = ("rtw-scan ", "cargo run --release -p rtw-scan -- ", "v/bin/python -m rtw ", "cp configs/")
PLACEHOLDER = re.compile(r"\[|…|\.\.\.| \| |\b(?:CONFIG|DIR|FILE|SAMPLES|SCAN|TRACE|OUT|K/N|KEY|N)\b")
SKIP = re.compile(r"<!-- check: skip \((?P<why>[^)]+)\) -->")
TIMEOUT_S = 180


def commands(path: Path) -> tuple[list[str], int, list[str]]:
    """The commands of one page, its synopsis lines and its skipped blocks."""
    text = path.read_text()
    run, synopsis, skipped = [], 0, []
    for m in BLOCK.finditer(text):
        if m.group("lang") not in ("", "sh", "bash"):
            continue
        lines = m.group("body").replace("\\\n", " ").splitlines()
        lines = [re.sub(r"\s+#.*$", "", l).strip() for l in lines]
        lines = [" ".join(l.split()) for l in lines if l.startswith(PREFIXES)]
        why = SKIP.search(m.group("before"))
        if why and lines:
            skipped.append(f"{path.relative_to(ROOT)}: {lines[0][:60]}… ({why.group('why')})")
            continue
        for line in lines:
            if PLACEHOLDER.search(line):
                synopsis += 1
            else:
                run.append(line)
    return run, synopsis, skipped


def digest(folder: Path) -> dict[str, str]:
    return {
        str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
        for p in sorted(folder.rglob("*"))
        if p.is_file()
    }


def main() -> int:
    pages = [Path(a).resolve() for a in sys.argv[1:]] or [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    binary = ROOT / "target" / "release" / "rtw-scan"
    if not binary.exists():
        sys.exit(f"check_doc_commands: {binary} is missing: build it first (cargo build --release -p rtw-scan)")
    python = ROOT / ".venv" / "bin" / "python"
    failed, ran, synopsis = [], 0, 0
    with tempfile.TemporaryDirectory(prefix="rtw-doc-commands.") as tmp:
        work = Path(tmp)
        archive = subprocess.run(
            ["git", "-C", str(ROOT), "archive", "HEAD", "configs", "results", "scripts"],
            check=True, capture_output=True,
        ).stdout
        subprocess.run(["tar", "-x", "-C", str(work)], input=archive, check=True)
        committed = digest(work)
        bindir = work / ".bin"
        bindir.mkdir()
        (bindir / "rtw-scan").symlink_to(binary)
        env = dict(os.environ, PATH=f"{bindir}:{os.environ['PATH']}", CARGO_TARGET_DIR=str(ROOT / "target"))
        for page in pages:
            run, n_synopsis, skipped = commands(page)
            synopsis += n_synopsis
            for s in skipped:
                print(f"  skipped: {s}")
            for line in run:
                argv = shlex.split(line)
                if line.startswith("v/bin/python "):
                    if not python.exists():
                        sys.exit(f"check_doc_commands: {python} is missing: make it with ./scripts/venv.sh and install rtw")
                    argv[0] = str(python)
                if line.startswith("cargo run"):
                    argv[2:2] = ["--manifest-path", str(ROOT / "Cargo.toml"), "-q"]
                start = time.monotonic()
                try:
                    done = subprocess.run(argv, cwd=work, env=env, capture_output=True, text=True, timeout=TIMEOUT_S)
                    code, err = done.returncode, done.stderr
                except subprocess.TimeoutExpired:
                    code, err = None, f"still running after {TIMEOUT_S} s: mark its block <!-- check: skip (why) -->"
                took = time.monotonic() - start
                ran += 1
                name = page.relative_to(ROOT)
                if code == 0:
                    print(f"  ok {took:5.1f} s  {name}: {line}")
                else:
                    print(f"  FAILED ({code}) {took:5.1f} s  {name}: {line}\n{err[-2000:]}")
                    failed.append(f"{name}: {line}")
        changed = [f for f, h in digest(work).items() if f in committed and committed[f] != h]
        gone = [f for f in committed if not (work / f).exists()]
    for f in changed + gone:
        print(f"  a documented command changed or removed the committed file {f}")
    print(f"check_doc_commands: {ran} commands run, {len(failed)} failed; {synopsis} synopsis lines not run")
    return 1 if failed or changed or gone else 0


if __name__ == "__main__":
    sys.exit(main())
