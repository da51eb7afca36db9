"""Fails when a committed result is called "default" but was made at another
model, so that no figure or doc can go on calling a result the default model's
after the default moved (as the continuation diagrams did when s went from 0.85
to 0.8875).

    python scripts/check_default_model.py DEFAULT.parquet

DEFAULT.parquet is any file rtw wrote with the default options:
scripts/test.sh passes the scan of configs/smoke.toml it has just made (that
config sets no model key), so the default model's `rtw.variant` comes from the
library, never typed here. A *model* is the variant's choices before
`method=` (strings, friction, damping, normalization, start, labels); the
integrator, its tolerances and `t_max` are settings of the run, which a result
may choose (the plane scan runs 60 s, a continuation solves its own step map).

A committed Parquet file under results/ with an `rtw.variant` is *called
default* by
  * a Markdown paragraph of README.md, docs/ or results/ that says "default
    model" (or "model default", "model: default") and names the file: its
    directory and stem (`continuation/phi-fig7a.png` names
    results/continuation/phi-fig7a.parquet and its `.special`/`.curve`/`.steps`
    companions), or, in a Markdown file of the same directory, its bare stem;
    a paragraph is read with the heading above it, so a heading's claim holds
    for its section's paragraphs that name the file;
  * a Markdown file inside a scan's directory (results/NAME/*.md beside
    samples.parquet), anywhere in it;
  * a PNG of the same directory and stem (`phi-fig7a.png`, `phi-fig7a.plane.png`)
    whose Title text chunk (scripts/continuation.py and bifurcation.py write
    the figure's title there) says "default model".
Each such file's model must be the default's. A result without a Parquet
file states its model in its own Markdown instead: "default model, `LINE`"
(or "default model (`LINE`)"), where LINE is the `rtw.variant` line it ran
with (results/bench/work-precision.md, written by rtw-bench, says so of each
case and of its scan); LINE's model must be the default's too. The script
lists every one that is not, with where it is called default, and exits 1.
"""

from __future__ import annotations

import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pyarrow.parquet as pq
from PIL import Image

from rtwscripts import ROOT, model

CLAIM = re.compile(r"default model|model:? default", re.I)
# A claim followed by the `rtw.variant` line the result was made with.
STATED = re.compile(r"default model[,:]?\s*\(?`(rest_length_ratio=[^`]+)`", re.I)
# Companion suffixes of one result (rtw-scan continuation, bifurcation) and
# of its figures (scripts/continuation.py plane).
COMPANIONS = (".special", ".curve", ".steps", ".plane", ".segments")
NAME_CHAR = r"[A-Za-z0-9_-]"


def variant_of(path: Path) -> str | None:
    meta = pq.read_metadata(path).metadata or {}
    v = meta.get(b"rtw.variant")
    return v.decode() if v is not None else None


def base(path: Path) -> str:
    """A result's name without its extension and companion suffix."""
    stem = path.stem
    for suffix in COMPANIONS:
        stem = stem.removesuffix(suffix)
    return stem


@dataclass
class Result:
    path: Path  # relative to ROOT
    model: str

    @property
    def directory(self) -> Path:
        return self.path.parent

    @property
    def is_scan(self) -> bool:
        return self.path.name == "samples.parquet"

    def patterns(self, doc: Path) -> list[re.Pattern]:
        """How a Markdown file `doc` names this result."""
        rel = self.directory.relative_to("results").as_posix()
        names = [f"{rel}/{base(self.path)}"] if not self.is_scan else [f"{rel}/", f"{rel}`"]
        if doc.parent == self.directory and not self.is_scan:
            names.append(base(self.path))
        return [re.compile(rf"(?<!{NAME_CHAR}){re.escape(n)}(?!{NAME_CHAR})") for n in names]


def committed(pattern: str) -> list[Path]:
    out = subprocess.run(["git", "ls-files", "-z", "--", pattern], cwd=ROOT, capture_output=True, check=True)
    return [Path(p) for p in out.stdout.decode().split("\0") if p]


def paragraphs(text: str) -> list[str]:
    """Each paragraph with the heading it sits under."""
    out, heading, para = [], "", []
    for line in [*text.splitlines(), ""]:
        if line.startswith("#"):
            if para:
                out.append("\n".join([heading, *para]))
            heading, para = line, []
            out.append(heading)
        elif line.strip():
            para.append(line)
        elif para:
            out.append("\n".join([heading, *para]))
            para = []
    return out


def claims(results: list[Result], docs: list[Path]) -> dict[Path, list[str]]:
    """Where each result is called default: 'FILE: first words'."""
    found: dict[Path, list[str]] = {}
    for doc in docs:
        text = (ROOT / doc).read_text()
        for r in results:
            if r.is_scan and doc.parent == r.directory and CLAIM.search(text):
                found.setdefault(r.path, []).append(f"{doc} (the scan's own summary)")
                continue
            pats = r.patterns(doc)
            for p in paragraphs(text):
                if CLAIM.search(p) and any(pat.search(p) for pat in pats):
                    found.setdefault(r.path, []).append(f"{doc}: {' '.join(p.split())[:100]}…")
    for png in committed("results/*.png"):
        title = Image.open(ROOT / png).text.get("Title", "")
        if not CLAIM.search(title):
            continue
        for r in results:
            if r.directory == png.parent and base(r.path) == base(png):
                found.setdefault(r.path, []).append(f"{png}'s title: {title}")
    return found


def stated(docs: list[Path]) -> list[tuple[str, str]]:
    """Every model line a Markdown file calls the default model's: (where, line)."""
    out = []
    for doc in docs:
        text = (ROOT / doc).read_text()
        for m in STATED.finditer(text):
            line_no = text.count("\n", 0, m.start()) + 1
            out.append((f"{doc}:{line_no}", " ".join(m.group(1).split())))
    return out


def main() -> None:
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    default = variant_of(Path(sys.argv[1]))
    if default is None:
        sys.exit(f"check_default_model: {sys.argv[1]} has no rtw.variant")
    default = model(default)
    results = []
    for f in committed("results/*.parquet"):
        v = variant_of(ROOT / f)
        if v is not None:
            results.append(Result(f, model(v)))
    docs = [Path("README.md"), *committed("docs/*.md"), *committed("results/*.md")]
    bad = []
    for path, where in sorted(claims(results, docs).items()):
        r = next(r for r in results if r.path == path)
        if r.model != default:
            bad.append(f"{path}: model {r.model}\n  called default in\n    " + "\n    ".join(where))
    lines = stated(docs)
    for where, line in lines:
        if model(line) != default:
            bad.append(f"{where}: model {model(line)}\n  called default there")
    if bad:
        print(f"check_default_model: the default model is {default}", file=sys.stderr)
        sys.exit("\n".join(bad))
    print(
        f"check_default_model: every result called default is at the default model ({default}), "
        f"and so are the {len(lines)} model lines Markdown files call the default's"
    )


if __name__ == "__main__":
    main()
