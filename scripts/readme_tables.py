"""Copies generated tables into README.md and docs/*.md between markers, so
that no number in the documentation is typed by hand:

    <!-- begin: results/reproduction.md -->
    ...replaced by the file's Markdown tables...
    <!-- end: results/reproduction.md -->

A marker may name a section: `results/variants/summary.md#At a glance` takes
only the tables under that heading, and a row filter after `|` keeps the
header and the rows whose first cell is listed:
`results/variants/summary.md#Fig. 7(a)|literal,prestress-0.85`.

Usage: python scripts/readme_tables.py [FILE ...]
(default: README.md and every docs/*.md; source paths are relative to the
repository root whichever file holds the marker, so a block moves with its
section.)
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BLOCK = re.compile(r"(<!-- begin: (?P<src>[^>]+?) -->\n)(?P<body>.*?)(<!-- end: (?P=src) -->)", re.S)


def tables(src: str) -> str:
    src, _, keep = src.partition("|")
    path, _, section = src.partition("#")
    text = (ROOT / path).read_text()
    if section:
        m = re.search(rf"^#+ {re.escape(section)}.*?$(?P<body>.*?)(?=^#+ |\Z)", text, re.S | re.M)
        if not m:
            sys.exit(f"readme_tables: no section {section!r} in {path}")
        text = m.group("body")
    rows = [line for line in text.splitlines() if line.startswith("|")]
    if keep:
        names = set(keep.split(","))

        def first(line: str) -> str:
            return line.split("|")[1].strip().strip("*").split("*")[0].strip()

        rows = [r for i, r in enumerate(rows) if i < 2 or first(r) in names]
    if not rows:
        sys.exit(f"readme_tables: no table in {src}")
    # A section with several tables keeps them apart: a blank line before each
    # later table's header (the row above its |---| separator), or Markdown
    # would read them as one.
    sep = re.compile(r"^\|[\s:|-]+\|$")
    out = []
    for i, r in enumerate(rows):
        if i > 0 and i + 1 < len(rows) and sep.match(rows[i + 1]) and not sep.match(r):
            out.append("")
        out.append(r)
    return "\n".join(out) + "\n"


def refresh(doc: Path) -> None:
    text = doc.read_text()
    new, n = BLOCK.subn(lambda m: m.group(1) + tables(m.group("src")) + m.group(4), text)
    doc.write_text(new)
    print(f"readme_tables: {n} tables refreshed in {doc}")


def documents() -> list[Path]:
    """The files whose marked blocks are generated: the README and docs/."""
    return [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


if __name__ == "__main__":
    for doc in [Path(a) for a in sys.argv[1:]] or documents():
        refresh(doc)
