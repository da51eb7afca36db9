"""Fails when a number that the prose of a docs page quotes from a results
file is no longer the number in that file, so that no page can go on quoting
a result after it was remade. (Whole tables are copied by
scripts/readme_tables.py instead; this is for numbers inside sentences.)

    python3 scripts/check_doc_numbers.py

Each pin names a phrase of a page, as a regular expression whose groups are
the numbers it quotes, and the place in a results file they come from, as a
regular expression with as many groups. Both must match exactly once (a page
that rewords the phrase must update its pin), and each quoted number must be
the result's to the precision the page prints it with (`4.00` pins 4.0000 to
±0.005; thin or plain spaces between thousands are ignored). A group that is
not a number must be equal as text.
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
# Where a pattern below says `N`, any number the page may print.
N = r"([−-]?\d[\d  ]*(?:\.\d+)?(?:e[−-]?\d+)?)"


@dataclass
class Pin:
    doc: str
    phrase: str
    source: str
    where: str


BENCH = "results/bench/work-precision.md"
BIF = "results/bifurcation/summary.md"
CONT = "results/continuation/summary.md"
SEG = "results/continuation/segments.md"
TAG = "results/continuation/touch-and-go.md"
PERF = "docs/performance.md"
LC = "docs/limit-cycles.md"


def bench_row(setting: str, cells: int) -> str:
    """The first `cells` numeric cells of the scan table's row of `setting`."""
    return r"^## Scan(?:.|\n)*?" + rf"^\| {re.escape(setting)} \| " + r" \| ".join([N] * cells)


def early_row(scan: str, moves: bool = False) -> str:
    """The early-stop table's row of `scan`: its work ratio, or its max Δ and flips."""
    cells = r" \| [^|]+\| [^|]+\| " + (rf"{N} \| {N} \|" if moves else r"[^|]+\|")
    return rf"^\| `{re.escape(scan)}` \| [^|]+\| [^|]+\| [^|]+\| " + (r"[^|]+" if moves else rf"{N}×") + cells


PINS: list[Pin] = [
    # docs/performance.md: the work-precision benchmark.
    Pin(PERF, rf"the Fig\. 7\(a\) walk's reference f_w is {N} Hz", BENCH,
        rf"### Fig\. 7\(a\) walk [^\n]*\n(?:[^\n]*\n)*?Reference: \*\*walk\*\*, f_w {N} Hz"),
    Pin(PERF, rf"hence skip ≈ {N} % and walk ≈ {N} %", BENCH,
        r"^\| \*\*dop853 1e-13 \(reference\)\*\* \| [^|]+\| [^|]+\| [^|]+\| – \| – \| – \| " + rf"{N} \| {N} \|"),
    Pin(PERF, r"the rule picks \*\*(\S+ \S+)\*\* \(" + rf"{N} RHS evaluations, max Δ {N} pp", BENCH,
        r"errs by less than 1 %: \*\*(\S+ \S+)\*\* \(" + rf"{N} RHS evaluations, [^;]*; [^;]*; max Δ {N} pp"),
    Pin(PERF, rf"DP5\(4\) at 1e-4 does {N} with max Δ {N} pp and {N} flips", BENCH,
        bench_row("dp54 1e-4", 1) + rf" \| [^|]+\| [^|]+\| {N} \| {N} \|"),
    Pin(PERF, r"the early stop at \*\*(\S+ \S+)\*\*", BENCH, r"^## Early stop \(`stop_when_settled`\) at (\S+ \S+)$"),
    Pin(PERF, rf"ratio is {N}× on the 200 samples and {N}× on `configs/paper\.toml`", BENCH,
        early_row("configs/bench/scan200.toml") + r"(?:.|\n)*?" + early_row("configs/paper.toml")),
    Pin(PERF, rf"at most {N} pp of any outcome on the 200 samples \({N} labels\) and {N} pp on the paper scan \({N} of its",
        BENCH, early_row("configs/bench/scan200.toml", moves=True) + r"(?:.|\n)*?" + early_row("configs/paper.toml", moves=True)),
]


def value(text: str) -> float | None:
    text = text.replace(" ", "").replace(" ", "").replace("−", "-")
    try:
        return float(text)
    except ValueError:
        return None


def decimals(text: str) -> int:
    mantissa = text.lower().split("e")[0]
    return len(mantissa.split(".")[1]) if "." in mantissa else 0


def agrees(quoted: str, result: str) -> bool:
    q, r = value(quoted), value(result)
    if q is None or r is None:
        return quoted.strip() == result.strip()
    if "e" in quoted.lower():
        exp = int(quoted.lower().split("e")[1].replace("−", "-"))
        return abs(q - r) <= 0.5 * 10.0 ** (exp - decimals(quoted)) * (1 + 1e-9)
    return abs(q - r) <= 0.5 * 10.0 ** -decimals(quoted) * (1 + 1e-9)


def only(pattern: str, text: str, where: str) -> re.Match | str:
    found = list(re.finditer(pattern, text, re.M))
    if len(found) != 1:
        return f"{where}: {len(found)} matches of {pattern.replace(N, 'N')!r} (need exactly 1)"
    return found[0]


def page(doc: str) -> str:
    """A page with its lines read as one: a phrase may wrap anywhere."""
    return re.sub(r"\s+", " ", (ROOT / doc).read_text())


def check(pin: Pin, doc_text: str, source_text: str) -> str | None:
    """None if the pin holds, else what is wrong."""
    q = only(pin.phrase, doc_text, pin.doc)
    if isinstance(q, str):
        return q
    r = only(pin.where, source_text, pin.source)
    if isinstance(r, str):
        return r
    bad = [(a, b) for a, b in zip(q.groups(), r.groups(), strict=True) if not agrees(a, b)]
    if bad:
        said = ", ".join(f"{a} (the result: {b})" for a, b in bad)
        return f"{pin.doc}: {said} in “{q.group(0)}”, from {pin.source}"
    return None


def drifted(pin: Pin, doc_text: str) -> str:
    """The page with the pin's first quoted number moved by one in its last
    digit (or its text changed): what a page that went stale looks like."""
    m = only(pin.phrase, doc_text, pin.doc)
    assert not isinstance(m, str), m
    quoted = m.group(1)
    digits = [i for i, c in enumerate(quoted) if c.isdigit()]
    if value(quoted) is None or not digits:
        moved = quoted + "x"
    else:
        i = digits[-1] if "e" not in quoted.lower() else [d for d in digits if d < quoted.lower().index("e")][-1]
        moved = quoted[:i] + str((int(quoted[i]) + 1) % 10) + quoted[i + 1 :]
    return doc_text[: m.start(1)] + moved + doc_text[m.end(1) :]


def main() -> None:
    if len(sys.argv) != 1:
        sys.exit(__doc__)
    texts = {f: page(f) if f.startswith("docs/") else (ROOT / f).read_text() for p in PINS for f in (p.doc, p.source)}
    bad = [e for e in (check(p, texts[p.doc], texts[p.source]) for p in PINS) if e is not None]
    # Each pin must see a drift: a page with its first number moved fails it.
    bad += [
        f"{p.doc}: the pin of {p.phrase.replace(N, 'N')!r} does not fail when its number drifts"
        for p in PINS
        if not bad and check(p, drifted(p, texts[p.doc]), texts[p.source]) is None
    ]
    if bad:
        sys.exit("check_doc_numbers: quoted numbers that are not the results' now:\n  " + "\n  ".join(bad))
    print(f"check_doc_numbers: {len(PINS)} quoted numbers agree with their results files")


if __name__ == "__main__":
    main()
