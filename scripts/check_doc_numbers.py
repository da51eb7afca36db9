"""Fails when a number that the prose of a docs page quotes from a results
file is no longer the number in that file, so that no page can go on quoting
a result after it was remade. (Whole tables are copied by
scripts/readme_tables.py instead; this is for numbers inside sentences.)

    python3 scripts/check_doc_numbers.py

Each pin names a phrase of a page, as a regular expression whose groups are
the numbers it quotes (the page is read with its line breaks as spaces, so a
phrase may wrap anywhere), and where each number comes from, in order: the
groups of a regular expression's one match in a results file (`Rx`), a cell
of a Markdown table in a section of one (`Cell`: picked by its column and the
row's other cells, or the min, max, sum or count over rows), or the min or
max, median or count of a Parquet column (`Col`). The phrase must match exactly once (a page
that rewords it must update its pin), and each quoted number must be the
result's to the precision the page prints it with (`4.00` pins 4.0000 to
±0.005; `0.2119` pins 0.21185; thin or plain spaces between thousands are
ignored; a cell such as `(0.14662` or `1.10×` gives its leading number). A
quote that is not a number must equal its source as text. Every pin is also
checked to fail on a copy of its page whose first quoted number moved by one
in its last digit, so that no pin passes whatever the page says.

Run by the test command (scripts/test.sh). Only numbers that come from a
results file are pinned; measured times, constants and config inputs are not.
"""

from __future__ import annotations

import fnmatch
import re
import statistics
import sys
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
# Where a pattern below says `N`, any number the page may print.
N = r"([−-]?\d[\d  ]*(?:\.\d+)?(?:e[−-]?\d+)?)"


@dataclass
class Rx:
    """The groups of `pattern`'s one match in `source` (in its `section`, the
    text from the heading that starts with it to the next heading of its
    level or above, if given)."""

    source: str
    pattern: str
    section: str = ""

    def values(self) -> tuple[str, ...] | str:
        text = section_text(self.source, self.section)
        m = only(self.pattern, text, self.source)
        return m if isinstance(m, str) else m.groups()


@dataclass
class Cell:
    """One cell of the Markdown tables in `source`'s `section`: the column
    `column` of the `nth` row whose cells match `where` (shell patterns:
    `*` for any text); `part` picks a piece of a range cell (`a – b`,
    `a → b`, `a–b, c–d`); `agg` (min, max, sum, count) takes all such rows
    instead of one."""

    source: str
    section: str
    column: str
    where: dict[str, str]
    nth: int = 0
    part: int | None = None
    agg: str = ""

    def values(self) -> tuple[str, ...] | str:
        rows = [r for r in table_rows(section_text(self.source, self.section)) if matches(r, self.where)]
        if self.agg == "count":
            return (str(len(rows)),)
        cells = [pieces(r[self.column])[self.part] if self.part is not None else r[self.column] for r in rows
                 if self.column in r]
        if self.agg:
            nums = [value(c) for c in cells]
            if not nums or None in nums:
                return f"{self.source}: no numbers in column {self.column!r} where {self.where}"
            return (repr({"min": min, "max": max, "sum": sum}[self.agg](nums)),)
        if len(cells) <= self.nth:
            return f"{self.source}: no row {self.nth} where {self.where} in {self.section!r}"
        return (cells[self.nth],)


@dataclass
class Col:
    """`agg` (min, max, median, count) of a Parquet column over the rows whose
    `key` is `equals` (and each column of `also` its value)."""

    source: str
    column: str
    key: str
    equals: object
    agg: str
    also: dict[str, object] = field(default_factory=dict)

    def values(self) -> tuple[str, ...]:
        import pyarrow.parquet as pq

        names = list(dict.fromkeys([self.key, self.column, *self.also]))
        t = pq.read_table(ROOT / self.source, columns=names).to_pylist()
        where = {self.key: self.equals, **self.also}
        xs = [r[self.column] for r in t if all(r[k] == v for k, v in where.items()) and r[self.column] is not None]
        if self.agg == "count":
            return (str(len(xs)),)
        return (repr({"min": min, "max": max, "median": statistics.median}[self.agg](xs)),)


@dataclass
class Pin:
    """A phrase of a page (groups: the numbers it quotes) and where each
    number comes from, in order."""

    doc: str
    phrase: str
    sources: list[Rx | Cell | Col]


def section_text(source: str, heading: str) -> str:
    text = (ROOT / source).read_text()
    if not heading:
        return text
    m = re.search(rf"^(#+) {re.escape(heading)}.*?$", text, re.M)
    if not m:
        return ""
    level = len(m.group(1))
    end = re.search(rf"^#{{1,{level}}} ", text[m.end() :], re.M)
    return text[m.start() : m.end() + end.start() if end else len(text)]


def split_cells(line: str) -> list[str]:
    return [c.strip() for c in re.split(r"(?<!\\)\|", line.strip())[1:-1]]


def table_rows(text: str) -> list[dict[str, str]]:
    """Every row of every table in `text`, keyed by its table's header."""
    rows, header = [], None
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if not line.startswith("|"):
            header = None
            continue
        if header is None:
            header = split_cells(line)
        elif not re.fullmatch(r"\|[\s:|-]+\|", line.strip()):
            rows.append(dict(zip(header, split_cells(line), strict=False)))
    return rows


def matches(row: dict[str, str], where: dict[str, str]) -> bool:
    return all(k in row and fnmatch.fnmatchcase(row[k], v) for k, v in where.items())


def pieces(cell: str) -> list[str]:
    return [p.strip() for p in re.split(r"\s*(?:–|→|,)\s*", cell) if p.strip()]


def value(text: str) -> float | None:
    """The number a cell or a quote starts with (`(0.14662`, `1.10×`,
    `-1.0000+0.0000i`: its real part), or None."""
    m = re.match(r"\(?([−-]?\d[\d  ]*(?:\.\d+)?(?:e[−-]?\d+)?)", text.strip())
    if not m:
        return None
    return float(m.group(1).replace(" ", "").replace(" ", "").replace("−", "-"))


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


BENCH = "results/bench/work-precision.md"
BIF = "results/bifurcation/summary.md"
CONT = "results/continuation/summary.md"
SEG = "results/continuation/segments.md"
PLANE = "results/continuation/plane/summary.md"
PERF = "docs/performance.md"
PEERS = "results/bench/peers.md"
LC = "docs/limit-cycles.md"
CONTD = "docs/continuation.md"
ROB_STEP = "docs/robustness-step-down.md"
ROB_GSN = "docs/robustness-gsn.md"
ROB_ROUGH = "docs/robustness-rough.md"
ROB_STUDY = "docs/robustness-study.md"
REF = "docs/refine.md"
README = "README.md"
RS = "results/robustness/summary.md"
ROUGH = "results/robustness/roughness.md"
MCOST = "results/robustness/mfpt_cost-robustness-map.txt"
PCOST = "results/robustness/mfpt_cost.txt"
BASIN = "results/robustness/basin_fig7a.txt"
ATLAS = "results/design/atlas.md"
FAMILIES = "results/design/families.md"
DESIGN_BENCH = "results/design/bench.md"
ATLAS_PAGE = "docs/design-atlas.md"
CURVE = "results/robustness/step_down_curve.md"
RB = "results/refine/summary.md"
MAPS = "results/robustness/map/samples.parquet"
BASIN_ROWS = "results/robustness/basin_fig7a.parquet"
# Sections of the results files.
B1 = "Default model"
B0 = "s = 0:"
WALK = "The Fig. 7(a) walk in φ at the default model"
TAG = "The s = 0 skip on the touch-and-go section"
PLANE_CHECK = "Its period-doubling curve in (φ, f_n)"
PAPER = "The paper scan"
MAP = "The (φ, f_n) map"
PW = "Paper: where each measure is defined"
MW = "Map: where each measure is defined"
PRC = "Paper: rank correlation with the MFPT"
MRC = "Map: rank correlation with the MFPT"
PT = "Paper: censored regression of log10 MFPT (Tobit)"
PTEN = "Paper: what sets the designs with no fall counted apart"
PSEEDS = "Paper: over terrain seeds"
# Where a results file prints a correlation or slope with its sign (`+0.06`).
P = r"\+?" + N


def fam(column: str, family: str, role: str) -> Cell:
    return Cell(FAMILIES, "Winners", column, {"family": family, "role": role})


def fam_apart(column: str, gait: str) -> Cell:
    return Cell(FAMILIES, "What sets the families apart", f"{column}: median [IQR]", {"gait": gait})


def scan_row(setting: str, cells: int) -> Rx:
    """The first `cells` numeric cells of the benchmark scan table's row of `setting`."""
    return Rx(BENCH, rf"^\| {re.escape(setting)} \| " + r" \| ".join([N] * cells), "Scan")


def early(scan: str, column: str, part: int | None = None) -> Cell:
    """A cell of the benchmark's early-stop table."""
    return Cell(BENCH, "Early stop", column, {"scan": f"`{scan}`"}, part=part)


def peer(column: str, tool: str, method: str, tol: str) -> Cell:
    """A cell of the peer benchmark's rimless-wheel table."""
    return Cell(PEERS, "Rimless wheel", column, {"tool": tool, "method": method, "tol": tol})


def bif(section: str, column: str, nth: int = 0, part: int | None = None, **where: str) -> Cell:
    """A cell of a bifurcation sweep's table of gait bands."""
    return Cell(BIF, section, column, where, nth, part)


def bif_line(section: str, change: str, mult: str = N) -> Rx:
    """A change line of a sweep: groups (its leading multiplier's parts, then
    the φ it is taken at); `mult` matches the multiplier."""
    return Rx(BIF, rf"^- {re.escape(change)} between phi = [^;]+; leading multiplier at (?=[\d.]+: {mult}){N}:", section)


def walk(column: str, part: int | None = None, nth: int = 0, **where: str) -> Cell:
    """A cell of the continued Fig. 7(a) walk's tables."""
    return Cell(CONT, WALK, column, where, nth, part)


def tag(column: str, part: int | None = None, nth: int = 0, **where: str) -> Cell:
    """A cell of the touch-and-go skip's tables."""
    return Cell(CONT, TAG, column, where, nth, part)


def seg(length: str, column: str, nth: int = 0, part: int | None = None, agg: str = "", **where: str) -> Cell:
    """A cell of a length's segments table in results/continuation/segments.md."""
    return Cell(SEG, f"L = {length}", column, where, nth, part, agg)


def paper_row(measure: str, section: str = PRC) -> Rx:
    """A measure's row of a paper-scan table: groups (its first cell's value and interval)."""
    return Rx(RS, rf"^\| {re.escape(measure)} \| {P} \[{P}, {P}\] \|", section)


def alone(measure: str) -> Rx:
    """The last column of a rank-correlation row: groups (ρ where the measure alone is defined, its gaits)."""
    return Rx(RS, rf"^\| {re.escape(measure)} \|.*\| {P} \[[^]]*\] \({N}\) \|$", PRC)


def tobit(measure: str) -> Rx:
    """A measure's Tobit row alone: groups (its slope, the likelihood ratio's p)."""
    return Rx(RS, rf"^\| {re.escape(measure)} alone \| {P} \[[^|]*\| [^|]*\| [^|]*, {N} \|$", PT)


PD = {"bifurcation": "period doubling"}
NS = {"bifurcation": "neimark sacker"}
P2 = "up, branch 2 (period 2)*"

PINS: list[Pin] = [
    # docs/performance.md: the peer benchmark (results/bench/peers.md).
    Pin(PERF, rf"On the wheel at tol 1e-9 rtw's DOP853 takes {N} µs a trajectory, heyoka {N} µs and "
        rf"diffrax's vmapped Dopri8 {N} µs",
        [peer("µs per trajectory", "rtw", "dop853", "1e-09"),
         peer("µs per trajectory", "heyoka", "taylor, order *", "1e-09"),
         peer("µs per trajectory", "diffrax", "Dopri8, vmap", "1e-09")]),
    Pin(PERF, rf"touchdown times to {N} s at tol 1e-12, rtw's DOP853 {N} s\)",
        [peer("event-time error (s)", "heyoka", "taylor, order *", "1e-12"),
         peer("event-time error (s)", "rtw", "dop853", "1e-12")]),
    Pin(PERF, rf"event times within 1e-11 s: heyoka {N} µs a trajectory, rtw {N} µs \(its DP5\(4\) at tol 1e-12\)",
        [Rx(PEERS, rf"^- error ≤ 1e-11 s: [^\n]*; heyoka taylor at tol 1e-12, {N} µs;", "Rimless wheel"),
         Rx(PEERS, rf"^- error ≤ 1e-11 s: rtw dp54 at tol 1e-12, {N} µs;", "Rimless wheel")]),
    # docs/performance.md: the per-core target's events, from the Hot path table.
    Pin(PERF, rf"\(Fig\. 7\(a\): {N} events in {N} steps, the Hot path table\)",
        [Rx("results/bench/page.md", rf"^\| RHS evaluations / steps / rejected / events \| [^|]* / {N} \|"),
         Rx("results/bench/page.md", rf"^\| RHS evaluations / steps / rejected / events \| [\d  ]+ / {N} /")]),
    # docs/performance.md: the work-precision benchmark.
    Pin(PERF, rf"the Fig\. 7\(a\) walk's reference f_w is {N} Hz",
        [Rx(BENCH, rf"^Reference: \*\*walk\*\*, f_w {N} Hz", "Fig. 7(a) walk")]),
    Pin(PERF, rf"hence skip ≈ {N} % and walk ≈ {N} %",
        [Cell(BENCH, "Scan", "skip %", {"setting": "**dop853 1e-13 (reference)**"}),
         Cell(BENCH, "Scan", "walk %", {"setting": "**dop853 1e-13 (reference)**"})]),
    Pin(PERF, r"the rule picks \*\*(\S+ \S+)\*\* \(" + rf"{N} RHS evaluations, max Δ {N} pp",
        [Rx(BENCH, r"errs by less than 1 %: \*\*(\S+ \S+)\*\* \(" + rf"{N} RHS evaluations, [^;]*; [^;]*; max Δ {N} pp")]),
    Pin(PERF, rf"DP5\(4\) at 1e-4 does {N} with max Δ {N} pp and {N} flips",
        [Cell(BENCH, "Scan", c, {"setting": "dp54 1e-4"}) for c in ("RHS evals", "max Δ (pp)", "flips")]),
    Pin(PERF, r"the early stop at \*\*(\S+ \S+)\*\*", [Rx(BENCH, r"^## Early stop \(`stop_when_settled`\) at (\S+ \S+)$")]),
    Pin(PERF, rf"ratio is {N}× on the 200 samples and {N}× on `configs/paper\.toml`",
        [early("configs/bench/scan200.toml", "work ratio"), early("configs/paper.toml", "work ratio")]),
    Pin(PERF, rf"at most {N} pp of any outcome on the 200 samples \({N} labels\) and {N} pp on the paper scan \({N} of its",
        [early("configs/bench/scan200.toml", "max Δ (pp)"), early("configs/bench/scan200.toml", "flips"),
         early("configs/paper.toml", "max Δ (pp)"), early("configs/paper.toml", "flips")]),
    # docs/limit-cycles.md: the step map's walk at Fig. 7(a).
    Pin(LC, rf"\(\|μ\| = {N}\), then", [Rx(CONT, rf"from the period-1 gait at phi = 0\.15 \(max\|μ\| {N}\)")]),
    # The attractor sweeps (results/bifurcation/summary.md).
    Pin(LC, rf"slopes\*\*: φ = {N} to {N} \({N} of 121 values\), max \|μ\| {N}–{N} \({N} near φ = 0\.15\)",
        [bif(B1, c, label="walk", period="1") for c in ("phi from", "phi to", "values")]
        + [bif(B1, r"max \|μ\| range", part=i, label="walk", period="1") for i in (0, 1)]
        + [Rx(CONT, rf"from the period-1 gait at phi = 0\.15 \(max\|μ\| {N}\)")]),
    Pin(LC, rf"down to φ ≈ {N}, the robot walks", [bif(B1, "phi from", label="walk", period="none")]),
    Pin(LC, rf"period-4 and period-5 walks at φ = {N} and {N}\)",
        [bif(B1, "phi from", label="walk", period="4"), bif(B1, "phi from", label="walk", period="5")]),
    Pin(LC, rf"for φ ≤ {N} no new foot lands", [bif(B1, "phi to", label="failure")]),
    Pin(LC, rf"Past φ = {N} the sweep's robot walks with period 2\*\* \({N}–{N}, stable\)",
        [bif(B1, "phi to", label="walk", period="1"), bif(B1, "phi from", label="walk", period="2"),
         bif(B1, "phi to", label="walk", period="2")]),
    Pin(LC, rf"leading multiplier is still {N} at {N}: the two walks coexist", [bif_line(B1, "period 1 → 2", rf"{N}\+")]),
    Pin(LC, rf"period doubling is at φ = {N}, with the period-2 walk stable from {N}:",
        [walk("value", **PD), walk("stable on", 0, period="2")]),
    Pin(LC, rf"gains flight at φ ≈ {N} \(a period-2 skip to {N}\), doubles again through {N} at {N} \(period 4 to {N}\), "
        rf"returns to period 2 up to {N};",
        [bif(B1, "phi from", label="skip", period="2"), bif(B1, "phi to", label="skip", period="2"),
         bif_line(B1, "period 2 → 4", rf"{N}\+"), bif(B1, "phi to", label="skip", period="4"),
         bif(B1, "phi to", 2, label="skip", period="2")]),
    Pin(LC, rf"a period-1 skip at {N}–{N} loses its period with a complex pair near the unit circle \({N} ± {N}i at {N}:",
        [bif(B1, "phi from", label="skip", period="1"), bif(B1, "phi to", label="skip", period="1"),
         bif_line(B1, "period 1 → none", rf"{N}\+{N}i \(\|μ\| = [\d.]+, complex pair")]),
    Pin(LC, rf"period-1 skips again at {N}–{N} and {N}–0\.35, with a period doubling between \({N} at {N}\)",
        [bif(B1, "phi from", 1, label="skip", period="1"), bif(B1, "phi to", 1, label="skip", period="1"),
         bif(B1, "phi from", 3, label="skip", period="1"),
         bif_line(B1, "period 1 → none", rf"{N}\+0\.000i")]),
    Pin(LC, rf"gets going only from φ ≈ {N}", [bif(B0, "phi from", label="skip", period="none")]),
    Pin(LC, rf"and up to {N} the skip has no period", [bif(B0, "phi to", label="skip", period="none")]),
    Pin(LC, rf"barely stable \(max \|μ\| {N}–{N}\): {N}–{N}, ending in a period doubling \({N} at {N}\), and {N}–{N}, "
        rf"ending in a Neimark–Sacker bifurcation \({N} ± {N}i at {N}\)",
        [bif(B0, r"max \|μ\| range", 1, 0, label="skip", period="1", stable="yes"),
         bif(B0, r"max \|μ\| range", 0, 1, label="skip", period="1", stable="yes"),
         bif(B0, "phi from", label="skip", period="1"), bif(B0, "phi to", label="skip", period="1"),
         bif_line(B0, "period 1 → none", rf"{N}\+0\.000i"),
         bif(B0, "phi from", 1, label="skip", period="1", stable="yes"),
         bif(B0, "phi to", 1, label="skip", period="1", stable="yes"),
         bif_line(B0, "period 1 → none", rf"{N}\+{N}i \(\|μ\| = [\d.]+, complex pair")]),
    Pin(LC, rf"For φ ≥ {N} at s = 0 this sweep's map stops", [bif(B0, "phi from", 1, label="failure")]),
    # docs/continuation.md: continuation of the Fig. 7(a) walk (results/continuation/summary.md).
    Pin(CONTD, rf"the s = 0 skip's {N} s of wall time",
        [Rx(CONT, rf"from the period-1 gait at phi = 0\.34 \(max\|μ\| [^)]*\);[^\n]*; {N} s$")]),
    Pin(CONTD, rf"--curve-to 3\.9`: 3 min 55 s of CPU, {N} s of wall time",
        [Rx(CONT, rf"from the period-1 gait at phi = 0\.15 \(max\|μ\| [^)]*\);[^\n]*; {N} s$")]),
    Pin(CONTD, rf"stable from φ ≈ {N} up to its \*\*period doubling at φ = {N}\*\* \(multiplier {N}\)",
        [walk("stable on", 0, branch="1"), walk("value", **PD),
         Rx(CONT, rf"^\| 0 \| period doubling \| [\d.]+ \| {N}\+0\.0000i \|", WALK)]),
    Pin(CONTD, rf"where the attractor sweep of limit-cycles\.md goes from period 1 to period 2 between φ = {N} and {N}\.",
        [Rx(BIF, rf"^- period 1 → 2 between phi = {N} and {N};", B1)]),
    Pin(CONTD, rf"\(max \|μ\| up to {N}\) to φ = {N}\.",
        [Col("results/continuation/phi-fig7a.parquet", "floquet_max", "branch", 0, "max"),
         walk("values", 1, branch="0")]),
    Pin(CONTD, rf"turns near φ = {N} \(flagged a fold, but with its critical multiplier at {N}:",
        [walk("value", bifurcation="fold"), walk("critical multiplier", bifurcation="fold")]),
    Pin(CONTD, rf"is stable from {N} to its end at {N}\. The period doubling",
        [walk("stable on", 0, period="2"), walk("stable on", 1, period="2")]),
    Pin(CONTD, rf"between {N} and {N} the period-1 and the period-2 walk are both stable",
        [walk("stable on", 0, period="2"), walk("value", **PD)]),
    Pin(CONTD, rf"jumps to period 2 at {N} instead of passing", [bif(B1, "phi from", label="walk", period="2")]),
    Pin(CONTD, rf"The branches end \({N}, {N} and {N}, \"no continuation\"\)",
        [walk("values", 1, branch="1"), walk("values", 1, branch="0"), walk("values", 1, branch="2")]),
    # Through the changes of mode sequence (results/continuation/segments.md).
    Pin(CONTD, rf"step frequency within {N} relative; the table there\)",
        [Cell(SEG, "L = 0.8 against", "max rel. Δ step frequency", {}, agg="max")]),
    Pin(CONTD, rf"past the corner at φ = {N} where the sweep is stable \(its {N} values from φ = 0\.19875 to 0\.207, "
        rf"the step frequency within {N} relative\)",
        [seg("0.8", "at", way=P2, segment="0"),
         Cell(SEG, "L = 0.8 against", "sweep values compared", {"way": P2}, agg="sum"),
         Cell(SEG, "L = 0.8 against", "max rel. Δ step frequency", {"way": P2}, agg="max")]),
    Pin(CONTD, rf"turns back at φ = {N}, its multiplier at {N}\)",
        [seg("0.8", "at", end="fold"), seg("0.8", "max\\|μ\\| before → after", part=0, end="fold")]),
    Pin(CONTD, rf"L = 0\.8 going down at φ = {N}, where", [seg("0.8", "at", way="down", end="gait lost")]),
    Pin(CONTD, rf"winds back and forth over φ = {N}–{N} through its {N} segments",
        [seg("0.7", "at", agg="min", way=P2), seg("0.7", "at", agg="max", way=P2),
         seg("0.7", "segment", agg="count", way=P2)]),
    # The period-doubling curve in (φ, f_n) and its brute-force check.
    Pin(CONTD, rf"from \({N}, {N} Hz\), where its continuation stops",
        [walk("last point", 0, curve="1"), walk("last point", 1, curve="1")]),
    Pin(CONTD, rf"diagram's doubling to \({N}, {N} Hz\)\.", [walk("last point", 0, curve="0"), walk("last point", 1, curve="0")]),
    Pin(CONTD, rf"limit cycle solved \({N} s of wall time\)", [Rx(PLANE, rf"^- wall time: {N} s")]),
    Pin(CONTD, rf"unresolved within a column \(f_n = {N} here\)",
        [Cell(CONT, PLANE_CHECK, "fn", {"curve crosses at phi": "* (open)"})]),
    Pin(CONTD, rf"\(f_n = {N} has two at φ = {N} and {N}, well before the band\)",
        [Cell(CONT, PLANE_CHECK, "fn", {"agrees": "yes (2 period-2*"}),
         Cell(CONT, PLANE_CHECK, "scan: stable period-2 walk", {"agrees": "yes (2 period-2*"}, part=0),
         Cell(CONT, PLANE_CHECK, "scan: stable period-2 walk", {"agrees": "yes (2 period-2*"}, part=1)]),
    Pin(CONTD, rf"where that band is known \({N}–{N}\)", [walk("stable on", 0, period="2"), walk("value", **PD)]),
    # The s = 0 skip on the touch-and-go section.
    Pin(CONTD, rf"stable only in two narrow windows, {N}–{N} and {N}–{N}, between a period doubling at {N} and "
        rf"Neimark–Sacker points at {N}, {N}–{N}, {N} and {N} \(and one at {N} on the unstable branch\)",
        [tag("stable on", 0, branch="1"), tag("stable on", 1, branch="1"),
         tag("stable on", 0, branch="0"), tag("stable on", 1, branch="0"),
         tag("value", branch="1", **PD),
         tag("value", nth=1, branch="1", **NS), tag("value", nth=0, branch="1", **NS),
         tag("value", nth=0, branch="0", **NS), tag("value", nth=1, branch="0", **NS),
         tag("value", nth=2, branch="0", **NS), tag("value", nth=2, branch="1", **NS)]),
    # docs/robustness-*.md: the robustness study (results/robustness/summary.md) and its run times.
    Pin(ROB_STEP, rf"over its {N} stable gaits, median {N} m \(skips {N} m, walks {N} m, crawls {N} m\), 10th percentile "
        rf"{N} m; {N} reach the 16 L cap \({N} m\); `step_down_h50` equals `step_down_max` for {N} of them",
        [Rx(RS, rf"^step_down_max over these {N} stable gaits: median {N} m \(skips {N} m, walks {N} m, crawls {N} m\), "
            rf"10th percentile {N} m; {N} at the 16 L cap \({N} m\); step_down_h50 equals step_down_max for {N}\.$",
            PAPER)]),
    Pin(ROB_STUDY, rf"\*\*The scans took\*\* {N} s \(the map\) and {N} s \(the paper scan\)",
        [Rx(RS, rf"^- map scan \(all measures\): {N} s", "Run times"),
         Rx(RS, rf"^- paper scan \(all measures\): {N} s", "Run times")]),
    Pin(ROB_ROUGH, rf"took {N} s for the map and {N} s for the paper scan on 2 shared cores",
        [Rx(RS, rf"^- map scan \(all measures\): {N} s", "Run times"),
         Rx(RS, rf"^- paper scan \(all measures\): {N} s", "Run times")]),
    # The MFPT's ranking across roughness (results/robustness/roughness.md).
    Pin(ROB_STUDY, rf"Somers' D is {P} \[{P}, {P}\] over all {N} stable gaits, with the 1 cm MFPT censored where no fall "
        rf"was seen\. Of the 20 gaits that walk longest at 5 cm, {N} saw no fall at 1 cm; of all gaits, {N} of {N} did\. "
        rf"The second draw at 5 cm gives the same figures \({P} \[{P}, {P}\], {N} of 20\)",
        [Rx(ROUGH, rf"^\| 5 cm → 1 cm \| [^|]* \| {P} \[{P}, {P}\] \(\d+ of {N}\) \| {N} of 20 \({N} of {N}\) \|$"),
         Rx(ROUGH, rf"^\| 5 cm \(terrain\.seed 100\) → 1 cm \| [^|]* \| {P} \[{P}, {P}\] \(\d+ of \d+\) \| "
            rf"{N} of 20 \(\d+ of \d+\) \|$")]),
    # The study over three draws of the ground (results/robustness/summary.md, "Paper: over terrain seeds").
    Pin(ROB_STUDY, rf"and both again at the two other seeds {N} s",
        [Rx(RS, rf"^- both scans at 2 more terrain seeds \(steps to fall and mfpt\): {N} s", "Run times")]),
    Pin(ROB_STUDY, rf"the GSN's Somers' D is {N} ± {N} and its Tobit slope {N} ± {N} decades per SD; Floquet max \|μ\|'s "
        rf"Somers' D \+{N} ± {N}, `step_down_max`'s \+{N} ± {N} and `step_down_h50`'s \+{N} ± {N}\.",
        [Rx(RS, rf"^\| GSN \| (?:[^|p]*censored\) \| ){{3}}{P} ± {N} \|$", PSEEDS),
         Rx(RS, rf"^\| GSN \| (?:[^|]*, p [^|]*\| ){{3}}{P} ± {N} \|$", PSEEDS)]
        + [Rx(RS, rf"^\| {m} \| (?:[^|p]*censored\) \| ){{3}}{P} ± {N} \|$", PSEEDS)
           for m in (r"Floquet max \\\|μ\\\|", r"step_down_max \(m\)", r"step_down_h50 \(m\)")]),
    Pin(ROB_STUDY, rf"the GSN's is {N}, {N} and {N} \({N} ± {N}\)",
        [Rx(RS, rf"^\| GSN \| {P} \[[^|]*\(\d+ gaits\) \| {P} \[[^|]*\(\d+ gaits\) \| {P} \[[^|]*\(\d+ gaits\) \| "
            rf"{P} ± {N} \|$", PSEEDS)]),
    Pin(ROB_STUDY, rf"seed 100's MFPTs correlate {P} with them over the {N} gaits finite at both, {N} of the {N} inside seed 0's "
        rf"interval, and whether any fall is counted agrees for {N} of the {N} stable gaits; seed 200's {P} over {N}, "
        rf"{N} of the {N}, and {N} of the {N}",
        [Rx(RS, rf"^\| seed {s} against seed 0 \| {P} \({N}\) \| {N} of {N} \| {N} of {N} \|$", PSEEDS)
         for s in (100, 200)]),
    Pin(ROB_STUDY, rf"Spearman {N} \[{N}, {P}\] on the {N} with a finite MFPT, Somers' D {N} \[{N}, {N}\] on the {N} with "
        rf"the censored ones, and in the Tobit model {N} decades less MFPT per standard deviation of its rank "
        rf"\(likelihood ratio p = {N}\)",
        [paper_row("GSN"), Rx(RS, rf"^Spearman's ρ on the {N} gaits", PRC),
         Rx(RS, rf"^\| GSN \| [^|]* \| {P} \[{P}, {P}\] \|", PRC),
         Rx(RS, rf"no fall seen \({N} gaits, \d+ censored\)", PRC),
         Rx(RS, rf"^\| GSN alone \| -([\d.]+) \[[^|]*\| [^|]*\| [^|]*, {N} \|$", PT)]),
    Pin(ROB_STUDY, rf"max \|μ\| barely does, the other way \(Spearman \+{N} \[{N}, \+{N}\]; Tobit slope \+{N}, likelihood "
        rf"ratio p = {N}\)", [paper_row(r"Floquet max \|μ\|"), tobit(r"Floquet max \|μ\|")]),
    Pin(ROB_STUDY, rf"\(`step_down_max` {P} \[{P}, {P}\], `step_down_h50` {P} \[{P}, {P}\] on the common gaits\), and over "
        rf"all {N} gaits with a finite MFPT they correlate \+{N} and \+{N}",
        [paper_row("step_down_max (m)"), paper_row("step_down_h50 (m)"),
         Rx(RS, rf"^\| MFPT \| {N} finite", PW), Rx(RS, rf"^\| step_down_max \(m\) \|.*\| {P} \[[^]]*\] \(\d+\) \|$", PRC),
         Rx(RS, rf"^\| step_down_h50 \(m\) \|.*\| {P} \[[^]]*\] \(\d+\) \|$", PRC)]),
    Pin(ROB_STUDY, rf"On the map \({N} common gaits? with a finite MFPT, {N} with the censored ones, all of them censored\) "
        rf"nothing is ranked",
        [Rx(RS, rf"^Spearman's ρ on the {N} gaits", MRC), Rx(RS, rf"no fall seen \({N} gaits, \d+ censored\)", MRC)]),
    Pin(ROB_STUDY, rf"ranks the gaits as the MFPT does \(\+{N} \[\+{N}, \+{N}\] on the common gaits, \+{N} over the {N}\)",
        [paper_row("steps_to_fall (Monte Carlo, censored at max_steps)"),
         alone("steps_to_fall (Monte Carlo, censored at max_steps)")]),
    Pin(ROB_STUDY, rf"\(φ: \+{N} over the {N} gaits; f_n \+{N};",
        [Rx(RS, rf"^\| φ \(rad\) \| {P} \[", "Paper: the inputs"), Rx(RS, rf"^\| MFPT \| {N} finite", PW),
         Rx(RS, rf"^\| f_n \(Hz\) \| {P} \[", "Paper: the inputs")]),
    Pin(ROB_STUDY, rf"{N} gaits had no fall counted \({N} skips, {N} walks, {N} crawls?\)",
        [Rx(RS, rf"^\| \| no fall counted \({N}\)", PTEN),
         Rx(RS, rf"^Gaits: no fall counted skip {N}, walk {N}, crawl {N};", PTEN)]),
    Pin(ROB_STUDY, rf"\(φ median {N} against {N}, Mann–Whitney p = {N}\), with a smaller α \({N} against {N}, p = {N}\)",
        [Rx(RS, rf"^\| {x} \| {N} \[[^\]]*\](?: \(\d+ defined\))? \| {N} \[[^\]]*\] \| {N} \|$", PTEN) for x in (r"φ \(rad\)", "α")]),
    Pin(ROB_STUDY, rf"\(`step_down_max` median {N} m against {N} m, p = {N}\) and their GSN smaller \({N} against {N}, p = {N}\); "
        rf"Floquet max \|μ\| is defined for {N} of them and the GSN for {N}",
        [Rx(RS, rf"^\| {x} \| {N} \[[^\]]*\](?: \(\d+ defined\))? \| {N} \[[^\]]*\] \| {N} \|$", PTEN) for x in (r"step_down_max \(m\)", "GSN")]
        + [Rx(RS, rf"^\| {x} \| [^|(]*\({N} defined\)", PTEN) for x in (r"Floquet max \\\|μ\\\|", "GSN")]),
    Pin(ROB_STUDY, rf"The crawls have the smallest MFPTs \(median {N} steps\)",
        [Cell(RS, "Paper: by gait", "median MFPT", {"gait": "crawl"})]),
    Pin(ROB_STUDY, rf"Of the paper scan's {N} stable gaits, {N} have a finite MFPT, {N} of them with an interval open above "
        rf"\(few falls counted\), and {N} no fall counted at all .* For {N} of the {N} the Monte Carlo",
        [Rx(RS, rf"^## The paper scan \(configs/paper\.toml\): {N} stable gaits"),
         Rx(RS, rf"^\| MFPT \| {N} finite", PW),
         Rx(RS, rf"^\| MFPT \| \d+ finite \({N} of them with mfpt_hi = ∞, the interval open above\); {N} with no fall", PW),
         Rx(RS, rf"trials fall for {N} of them", PAPER), Rx(RS, rf"^No fall was counted for {N} stable gaits", PAPER)]),
    Pin(ROB_STUDY, rf"At σ = 5 cm \(Fig\. 7\(a\): {N} \[119, 215\]",
        [Cell(ATLAS, "Winners", "MFPT at 0.15, σ 5 cm", {"role": "Fig. 7(a)"})]),
    Pin("docs/design-atlas.md", rf"the `robust` search found at that slope \(a walker, α {N} and f_n {N} Hz\)",
        [Cell(ATLAS, "Winners", "α", {"role": "robust-1"}), Cell(ATLAS, "Winners", "f_n", {"role": "robust-1"})]),
    Pin("docs/design-atlas.md", rf"design before it falls \({N} against {N}\); the widest-walk winner, searched for its "
        rf"range, reaches {N}\.",
        [Cell(ATLAS, "Winners", "MFPT at 0.15, σ 5 cm", {"role": "robust-1"}),
         Cell(ATLAS, "Winners", "MFPT at 0.15, σ 5 cm", {"role": "Fig. 7(a)"}),
         Cell(ATLAS, "Winners", "MFPT at 0.15, σ 5 cm", {"role": "widest-walk-17"})]),
    Pin("docs/design-atlas.md", rf"the robust winner gives {N} and {N}, the Fig\. 7\(a\) design {N} and {N}, and the "
        rf"widest-walk winner {N} and {N}",
        [Cell(ATLAS, "Winners", "on fresh draws (seeds 100, 200)", {"role": role}, part=k)
         for role in ("robust-1", "Fig. 7(a)", "widest-walk-17") for k in (0, 1)]),
    Pin("docs/design-atlas.md", rf"the robust winner as rounded there goes {N} steps at seed 0",
        [Rx(ATLAS, rf"the robust winner as rounded in the table: {N} steps at seed 0")]),
    # The design searches against Sobol designs (scripts/design_bench.sh).
    Pin("docs/design.md", rf"The archive's verified interval on `widest` \(\+{N}\) comes closest",
        [Rx(DESIGN_BENCH, rf"^\| widest \| MAP-Elites archive, fall model \|(?: [^|]* \|){{5}} \+{N} \[")]),
    Pin("docs/design.md", rf"on `widest-walk`, {N} % of Sobol's designs have no walking slope at all, against {N} % of "
        rf"CMA-ES's and {N} % of the archive's, and CMA-ES without the model draws {N} %",
        [Cell(DESIGN_BENCH, "", "infeasible", {"config": "widest-walk", "method": m})
         for m in ("Sobol designs (baseline)", "CMA-ES, fall model", "MAP-Elites archive, fall model",
                   "CMA-ES, no fall model")]),
    Pin("docs/design.md", rf"it draws the same designs at {N} of {N} seeds either way, and with the model {N} percentage "
        rf"points of falls",
        [Cell(DESIGN_BENCH, "What the fall model changes", "same", {"config": "widest-walk", "search": "CMA-ES"}),
         Rx(DESIGN_BENCH, rf"^\| widest-walk \| CMA-ES \|(?: [^|]* \|){{3}} \d+ of {N} \|$"),
         Cell(DESIGN_BENCH, "What the fall model changes", "infeasible, with − without (pp)",
              {"config": "widest-walk", "search": "CMA-ES"})]),
    # The gait families of the design atlas (scripts/design_atlas.sh).
    Pin(ATLAS_PAGE, rf"median f_n of {N} Hz, against {N} Hz for its walks and {N} Hz for its skips, and at small α "
        rf"\(median {N}\); no crawl winner has f_n above {N} Hz",
        [fam_apart("fn", "crawl"), fam_apart("fn", "walk"), fam_apart("fn", "skip"), fam_apart("alpha", "crawl"),
         Cell(FAMILIES, "Winners", "f_n", {"family": "crawl"}, agg="max")]),
    Pin(ATLAS_PAGE, rf"the widest skipper \(α {N}, f_n {N} Hz\) skips on every checked slope from {N} to {N} rad; the "
        rf"paper scan's skips have a median α of {N}\.",
        [fam("α", "skip", "widest"), fam("f_n", "skip", "widest"), fam("phi_lo", "skip", "widest"),
         fam("phi_hi", "skip", "widest"), fam_apart("alpha", "skip")]),
    Pin(ATLAS_PAGE, rf"at median α {N}: the widest walker \(α {N}, f_n {N} Hz\) is softer than the widest skipper, "
        rf"and walks from {N} to {N}\.",
        [fam_apart("alpha", "walk"), fam("α", "walk", "widest"), fam("f_n", "walk", "widest"),
         fam("phi_lo", "walk", "widest"), fam("phi_hi", "walk", "widest")]),
    Pin(ATLAS_PAGE, rf"the fastest walker goes {N} m/s, the fastest skipper {N} and the fastest crawler {N}; on the 5 cm "
        rf"rough slope the most robust walker goes {N} steps before it falls, the most robust skipper {N} and the "
        rf"most robust crawler {N}:",
        [*(fam("speed at 0.15", g, "fastest") for g in ("walk", "skip", "crawl")),
         *(fam("MFPT at 0.15, σ 5 cm", g, "robust") for g in ("walk", "skip", "crawl"))]),
    Pin(ATLAS_PAGE, rf"its shallowest skip is {N}\)", [fam("phi_min", "skip", "robust")]),
    # The survival curves of scripts/step_down_curve.py.
    Pin(ROB_STEP, rf"the crawl's `step_down_max`, {N} m, is a fifth of its `step_down_h50`",
        [Rx(CURVE, rf"^`step_down_max` {N} m \(the best phase\)", "crawl")]),
    Pin(ROB_STEP, rf"the skip's `step_down_h50`, {N} m, is where its ladder first found `S < ½` \(at a height just "
        rf"above it\), though `S` is {N} at 0\.2 m",
        [Rx(CURVE, rf"`step_down_h50` {N} m;", "skip"), Rx(CURVE, rf"^\| 0\.2000 \| [\d.]+ \| {N} \|", "skip")]),
    # The MFPT over the map (results/robustness/map/samples.parquet and the summary).
    Pin(ROB_STUDY, rf"φ 0\.08 with f_n 4\.25–4\.5 Hz \({N} and {N} steps, closed intervals, the Monte Carlo's {N} and {N} "
        rf"beside them\)\. {N} of the {N} stable gaits have no fall counted, across the whole map; {N} have a finite "
        rf"MFPT, {N} of them with an interval open above",
        [Col(MAPS, "mfpt", "phi", 0.08, "min"), Col(MAPS, "mfpt", "phi", 0.08, "min", {"fn": 4.25}),
         Col(MAPS, "steps_to_fall", "phi", 0.08, "min"), Col(MAPS, "steps_to_fall", "phi", 0.08, "min", {"fn": 4.25}),
         Rx(RS, rf"^No fall was counted for {N} stable gaits", MAP),
         Rx(RS, rf"^## The \(φ, f_n\) map [^:]*: {N} stable"),
         Rx(RS, rf"^\| MFPT \| {N} finite", MW),
         Rx(RS, rf"^\| MFPT \| \d+ finite \({N} of them", MW)]),
    # The cost of the MFPT on the map (results/robustness/mfpt_cost-robustness-map.txt).
    Pin(ROB_ROUGH, rf"{N} s for the map's {N} designs \({N} stable gaits\) on 2 threads; per stable gait a median of {N} s "
        rf"and a mean of {N} s of one thread \(90 % below {N} s, the slowest {N} s\); {P} s per decade of MFPT over the "
        rf"{N} gaits with a finite MFPT \(log–log slope {P}; Spearman {P}\)",
        [Rx(MCOST, rf"^wall times: [^;]*; median {N} s"), Rx(MCOST, rf"^stable gaits: \d+ of {N};"),
         Rx(MCOST, rf"^stable gaits: {N} of"), Rx(MCOST, rf"median {N} s, mean {N} s, 90 % {N} s, max {N} s;"),
         Rx(MCOST, rf"{P} s per decade of MFPT"), Rx(MCOST, rf"^time against log10 MFPT over the {N} finite"),
         Rx(MCOST, rf"log-log slope {P}"), Rx(MCOST, rf"Spearman {P}$")]),
    # The cost of the MFPT on the paper scan (results/robustness/mfpt_cost.txt).
    Pin(ROB_ROUGH, rf"The scan took a median of {N} s of wall time and \*\*{N} s of CPU\*\*: on 2 idle cores at perfect "
        rf"scaling that is \*\*{N} minutes,",
        [Rx(PCOST, rf"^wall times: [^;]*; median {N} s"), Rx(PCOST, rf"^CPU times [^;]*; median {N} s"),
         Rx(PCOST, rf"half of it {N} min")]),
    Pin(ROB_ROUGH, rf"Its {N} stable gaits took a median of {N} s and a mean of {N} s of one thread each \(90 % below {N} s, "
        rf"the slowest {N} s\)",
        [Rx(PCOST, rf"^stable gaits: {N} of"), Rx(PCOST, rf"median {N} s, mean {N} s, 90 % {N} s, max {N} s;")]),
    Pin(ROB_ROUGH, rf"not by its MFPT \({P} s per decade of MFPT, log–log slope {P}; Spearman {P}\)",
        [Rx(PCOST, rf"{P} s per decade of MFPT"), Rx(PCOST, rf"log-log slope {P}"), Rx(PCOST, rf"Spearman {P}$")]),
    Pin(ROB_ROUGH, rf"from {N} s for MFPT 10–100 \({N} gaits\) to {N} s for 10⁴–10⁵ \({N}\); the {N} gaits with no fall "
        rf"counted take {N} s",
        [Rx(PCOST, rf"10–100: {N} s \({N}\)"), Rx(PCOST, rf"10000–100000: {N} s \({N}\)"),
         Rx(PCOST, rf"no fall seen: [\d.]+ s \({N}\)$"), Rx(PCOST, rf"no fall seen: {N} s \(\d+\)$")]),
    # The basin of the Fig. 7(a) walk (results/robustness/basin_fig7a.{txt,parquet}).
    Pin(ROB_GSN, rf"the walk's own ω_a = {N} rad/s, θ_b = {N} rad\): {N} points return, {N} fail and {N} start with a tip in "
        rf"the ground; none survives",
        [Rx(BASIN, rf"omega_a = {N}, theta_b = {N}$"),
         Rx(BASIN, rf"points: returns {N}, survives 0, fails {N}, infeasible {N}$")]),
    Pin(ROB_GSN, rf"come back within 1e-3 in 23 to {N} steps \(median {N}; the fixed point itself in {N}\)",
        [Col(BASIN_ROWS, "steps", "outcome", "returns", agg) for agg in ("max", "median", "min")]),
    Pin(ROB_GSN, rf"Every failure is a `collapse` \(`rod_down`\) in the first step \({N}\) or the second \({N}\)",
        [Col(BASIN_ROWS, "steps", "outcome", "fails", "count", {"steps": k, "failure": "rod_down"}) for k in (0, 1)]),
    Pin(ROB_GSN, rf"its largest multiplier, {N}, predicts", [Rx(BASIN, rf"max \|mu\| {N}\)")]),
    Pin(ROB_GSN, rf"Fig\. 7\(a\) \(a period-1 walk, largest Floquet multiplier {N}\)", [Rx(BASIN, rf"max \|mu\| {N}\)")]),
    Pin(ROB_GSN, rf"\(41 × 41 = {N} points, ≤ 60 steps\) took {N} s on the 2 worker threads of this shared machine \(load "
        rf"average about 19 at the time; {N} ms of wall-clock per point",
        [Rx(BASIN, rf"^{N} points:"), Rx(BASIN, rf"^{N} s \({N} ms per point")]),
    # docs/refine.md: the refinement benchmark (results/refine/summary.md).
    Pin(REF, rf"reference: `configs/refine/reference\.toml`, {N} uniform samples",
        [Rx(RB, rf"^Reference: `results/refine/reference`, {N} uniform samples")]),
    Pin(REF, rf"\({N} samples, ~2\.5 min on two cores", [Rx(RB, rf"^Reference: `results/refine/reference`, {N} uniform")]),
    Pin(REF, rf"for each seed S of 1 … {N}, a uniform start of {N} samples of the slice \(seed S\), then `rtw-scan refine "
        rf"--budget {N} --rounds {N} --seed S`",
        [Rx(RB, rf"Seeds (?:\d+, )*{N};"),
         Rx(RB, rf"a uniform start of {N} samples, then `rtw-scan refine --budget {N} --rounds {N}`")]),
    Pin(REF, rf"{N} refined seeds, {N} rounds of 25; the uniform arm over {N} seeds",
        [Rx(RB, rf"resamples of the {N} refined"), Rx(RB, rf"--rounds {N}`"), Rx(RB, rf"refined and {N} uniform seeds")]),
    # README.md: the Python example's Fig. 7(a) walk, recorded by the design atlas.
    Pin(README, rf"# walk {N}… \(Fig\. 7\(a\)\)", [Cell(ATLAS, "Winners", "speed at 0.15", {"role": "Fig. 7(a)"})]),
]



def check(pin: Pin, doc_text: str) -> str | None:
    """None if the pin holds, else what is wrong."""
    q = only(pin.phrase, doc_text, pin.doc)
    if isinstance(q, str):
        return q
    results: list[str] = []
    for src in pin.sources:
        got = src.values()
        if isinstance(got, str):
            return got
        results += got
    if len(results) != len(q.groups()):
        return f"{pin.doc}: “{q.group(0)}” quotes {len(q.groups())} numbers, its sources give {len(results)}"
    bad = [(a, b) for a, b in zip(q.groups(), results, strict=True) if not agrees(a, b)]
    if bad:
        said = ", ".join(f"{a} (the result: {b})" for a, b in bad)
        files = ", ".join(sorted({src.source for src in pin.sources}))
        return f"{pin.doc}: {said} in “{q.group(0)}”, from {files}"
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
    texts = {p.doc: page(p.doc) for p in PINS}
    bad = [e for e in (check(p, texts[p.doc]) for p in PINS) if e is not None]
    # Each pin must see a drift: a page with its first number moved fails it.
    bad += [
        f"{p.doc}: the pin of {p.phrase.replace(N, 'N')!r} does not fail when its number drifts"
        for p in PINS
        if not bad and check(p, drifted(p, texts[p.doc])) is None
    ]
    if bad:
        sys.exit("check_doc_numbers: quoted numbers that are not the results' now:\n  " + "\n  ".join(bad))
    quoted = sum(re.compile(p.phrase).groups for p in PINS)
    print(
        f"check_doc_numbers: {quoted} numbers in {len(PINS)} phrases of "
        f"{', '.join(sorted(texts))} agree with their results files"
    )


if __name__ == "__main__":
    main()
