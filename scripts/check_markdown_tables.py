"""Fails when a Markdown table in README.md, docs/ or results/ has a row with
another number of cells than its header: a bare `|` inside a cell (a
period-2 mode sequence, say) shifts every later cell of its row.

Usage: python3 scripts/check_markdown_tables.py [FILE ...]
(default: README.md, docs/**/*.md and results/**/*.md)
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
# A cell boundary: a `|` not escaped as `\|` and not inside `code`.
CODE = re.compile(r"`[^`]*`")


def cells(line: str) -> int:
    line = CODE.sub("", line.strip())
    bars = len(re.findall(r"(?<!\\)\|", line))
    return bars - 1


def check(path: Path) -> list[str]:
    bad, header = [], None
    for no, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
        if not line.lstrip().startswith("|"):
            header = None
            continue
        n = cells(line)
        if header is None:
            header = n
        elif n != header:
            bad.append(f"{path.relative_to(ROOT)}:{no}: {n} cells, its header has {header}")
    return bad


def main() -> int:
    files = [Path(f).resolve() for f in sys.argv[1:]] or [
        ROOT / "README.md",
        *sorted((ROOT / "docs").rglob("*.md")),
        *sorted((ROOT / "results").rglob("*.md")),
    ]
    bad = [b for f in files for b in check(f)]
    for b in bad:
        print(b, file=sys.stderr)
    print(f"check_markdown_tables: {len(files)} files, {len(bad)} rows with a shifted cell")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
