"""The star's geometry and drawing, shared by the figures and the animation.

Python (numpy + matplotlib; the outcome labels are rtw-model's, from the native
module). A trace is any table with the columns
`rtw-scan simulate --trace` writes (and `rtw.trace` returns): a
`pyarrow.Table`, a polars or pandas DataFrame, or a mapping of column name to
array. Columns are taken whole as numpy arrays; nothing loops over rows.

The geometry is the model's, computed by it (rtw-model's `spoke_points`,
`SPOKES` and `STRINGS`, docs/model.md §1–§2): rod i has centre (x_i, y_i) in
the slope frame (x downhill, y normal to the slope) and angle θ_i; rtw-model
gives each spoke's tip and connection point and the spokes each string
joins. `check_geometry` holds the drawing to
the trace: every foot in contact on the ground and the strings' energy equal
to the trace's, at every sample.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import _rtw
from ._rtw import FAILURE_LABELS, STABLE_LABELS

RODS = "abc"
# Outcome styles, shared by every figure.
OUTCOME_COLOR = {
    "skip": "#d95f02",
    "walk": "#1b9e77",
    "crawl": "#7570b3",
    "collapse": "#e7298a",
    "stall": "#666666",
    "diverged": "#000000",
}
# The labels as rtw-model defines them (Label::is_stable, Label::is_failure).
STABLE = STABLE_LABELS
FAILED = FAILURE_LABELS
# contact_state = number of rods on the ground.
STATE_NAMES = ("NLSP", "SLSP", "DLSP", "TLSP")
STATE_COLOR = {"NLSP": "#e6ab02", "SLSP": "#1f78b4", "DLSP": "#33a02c", "TLSP": "#6a3d9a"}
ROD_COLOR = ("#1f77b4", "#d62728", "#2ca02c")  # rods a, b, c
STRING_COLOR = "#555555"
GROUND_COLOR = "#8c6d31"
EARTH_COLOR = "#e8dcc4"

# rtw-model's spokes in angular order (a+, b+, c+, a−, b−, c−) as (rod index,
# tip sign ±1), and its strings as the pair of spokes each joins.
SPOKES = _rtw.SPOKES
STRINGS = np.array(_rtw.STRINGS)
# The spoke of each rod's tip + and of its tip − (rows: rods a, b, c).
PLUS = [SPOKES.index((i, 1)) for i in range(3)]
MINUS = [SPOKES.index((i, -1)) for i in range(3)]

# The columns drawing and checking need (a trace has more).
TRACE_COLUMNS = ("t", *(f"{q}_{rod}" for rod in RODS for q in ("x", "y", "theta", "contact")),
                 "contact_state", "string_potential")

# A foot's contact code: 0 free, ±1 stick on tip ±, ±2 slide on tip ±.
STICK, SLIDE = 1, 2


class GeometryError(ValueError):
    """The drawing would not be the model's (a foot off the ground, strings' energy off the trace's)."""


@dataclass(frozen=True)
class Geometry:
    """The star's and slope's geometry for drawing a trace (not `rtw.Design`,
    a design's six inputs): what the drawing needs beyond the trace's columns: rod length L [m],
    connection radius r [m], slope φ [rad], the strings' rest length ratio
    s = ℓ₀/r and whether they go slack when short, and (optional, only to
    check the strings' energy exactly) the string stiffness k [N/m]."""

    length: float
    r: float
    phi: float
    rest_length_ratio: float = 0.0
    slack: bool = False
    k: float | None = None

    @classmethod
    def from_params(cls, length: float, alpha: float, phi: float, options: Mapping | None = None,
                    k: float | None = None) -> "Geometry":
        """From the design parameters and the run's options (the TOML of
        `[simulation]`, as a dict). r = L(1 − 2α)/2 is the model's definition
        (docs/model.md §1); k depends on the normalization, so it is not
        recomputed here: pass the run's (`Outcome.k`, `simulate --json`'s "k")."""
        strings = (options or {}).get("strings", {})
        return cls(length=float(length), r=float(length) * (1.0 - 2.0 * float(alpha)) / 2.0, phi=float(phi),
                   rest_length_ratio=float(strings.get("rest_length_ratio", 0.0)),
                   slack=bool(strings.get("slack", False)), k=None if k is None else float(k))

    @classmethod
    def from_metadata(cls, meta: Mapping | None) -> "Geometry | None":
        """From a trace file's Parquet metadata (`rtw.params`, `rtw.options`,
        as `simulate --trace` writes them), or None if they are not there."""
        import json
        import tomllib

        if not meta:
            return None
        meta = {(k.decode() if isinstance(k, bytes) else k): (v.decode() if isinstance(v, bytes) else v)
                for k, v in meta.items()}
        if "rtw.params" not in meta:
            return None
        p = json.loads(meta["rtw.params"])
        options = tomllib.loads(meta.get("rtw.options", ""))
        return cls.from_params(p["length"], p["alpha"], p["phi"], options)


def star_points(x, y, theta, length: float, r: float):
    """Every spoke's tip and connection point, as rtw-model computes them
    (`spoke_points`), for the rods' centres (x, y) and angles θ given as
    arrays [rod, ...] (one frame: [rod]): (tips, connection points), each
    [spoke, ..., xy] in the order of SPOKES."""
    x, y, theta = (np.asarray(a, dtype=float) for a in (x, y, theta))
    shape = x.shape[1:]
    flat = lambda a: np.moveaxis(a.reshape(3, -1), 0, -1).ravel().tolist()  # noqa: E731 ([frame, rod])
    tips, conns = _rtw.star_points(flat(x), flat(y), flat(theta), float(length), float(r))
    unflat = lambda v: np.moveaxis(np.asarray(v).reshape(-1, 6, 2), 1, 0).reshape(6, *shape, 2)  # noqa: E731
    return unflat(tips), unflat(conns)


def stance_tips(plus, minus, code):
    """The tip a rod touches the ground with: tip + for a positive contact
    code, tip − for a negative one (meaningless where the code is 0)."""
    return np.where((np.asarray(code) > 0)[..., None], plus, minus)


def _column_names(table) -> list[str]:
    names = getattr(table, "column_names", None)  # pyarrow.Table
    if names is None:
        names = getattr(table, "columns", None)  # polars, pandas
    if names is None:
        names = table.keys()  # a mapping
    return [str(n) for n in names]


def _column(table, name: str) -> np.ndarray:
    """One column as a numpy array, from pyarrow, polars, pandas or a mapping."""
    col = table[name]
    return np.asarray(col.to_numpy() if hasattr(col, "to_numpy") else col)


def _schema_metadata(table) -> Mapping | None:
    schema = getattr(table, "schema", None)
    return getattr(schema, "metadata", None) if schema is not None and not callable(schema) else None


class Trace:
    """A trace's columns as numpy arrays plus the design that draws them.

    `table`: pyarrow.Table, polars/pandas DataFrame or mapping with the trace
    columns. `design`: taken from the table's Parquet metadata when it has it
    (a pyarrow.Table read from a trace file, `Trace.read`), else required."""

    def __init__(self, table, design: Geometry | None = None):
        self.design = design or Geometry.from_metadata(_schema_metadata(table))
        if self.design is None:
            raise ValueError("design: the trace carries no rtw.params metadata (a DataFrame loses it); "
                             "pass design=rtw.draw.Geometry(length=…, r=…, phi=…, …) or read the Parquet "
                             "file with Trace.read(path)")
        missing = [c for c in TRACE_COLUMNS if c not in set(_column_names(table))]
        if missing:
            raise ValueError(f"the trace lacks the columns {', '.join(missing)} (a trace from "
                             "`rtw-scan simulate --trace` or rtw.trace has them)")
        cols = {name: _column(table, name) for name in TRACE_COLUMNS}
        self.t = cols["t"].astype(float)
        if len(self.t) == 0:
            raise ValueError("the trace has no samples")
        if np.any(np.diff(self.t) < 0):
            raise ValueError("the trace's column t is not in time order")
        # Rod-major arrays: [rod, sample].
        self.x = np.stack([cols[f"x_{rod}"] for rod in RODS]).astype(float)
        self.y = np.stack([cols[f"y_{rod}"] for rod in RODS]).astype(float)
        self.theta = np.stack([cols[f"theta_{rod}"] for rod in RODS]).astype(float)
        self.contact = np.stack([cols[f"contact_{rod}"] for rod in RODS]).astype(np.int64)
        self.state = cols["contact_state"].astype(np.int64)
        self.string_potential = cols["string_potential"].astype(float)

    @classmethod
    def read(cls, path: str | Path, design: Geometry | None = None) -> "Trace":
        """A trace Parquet file (`rtw-scan simulate --trace`), its design from the file's metadata."""
        import pyarrow.parquet as pq

        path = Path(path)
        if not path.is_file():
            raise FileNotFoundError(f"trace file {path} does not exist (make one with "
                                    "`rtw-scan simulate … --trace FILE`)")
        # The rtw.* keys are the file's key-value metadata, which pyarrow does
        # not carry into the table's schema when the file has an Arrow schema.
        design = design or Geometry.from_metadata(pq.read_metadata(path).metadata)
        return cls(pq.read_table(path, columns=list(TRACE_COLUMNS)), design)

    def __len__(self) -> int:
        return len(self.t)

    def points(self):
        """(tips, connection points) of every spoke at every sample, each [spoke, sample, xy] (star_points)."""
        return star_points(self.x, self.y, self.theta, self.design.length, self.design.r)

    def feet(self) -> np.ndarray:
        """The tip each rod stands on (+ for a positive code, − for a negative), [rod, sample, xy]."""
        tips, _ = self.points()
        return stance_tips(tips[PLUS], tips[MINUS], self.contact)

    def nearest(self, times) -> np.ndarray:
        """Index of the sample nearest each time (the earlier one on a tie)."""
        times = np.asarray(times, dtype=float)
        n = len(self.t)
        if n == 1:
            return np.zeros(times.shape, dtype=np.int64)
        right = np.clip(np.searchsorted(self.t, times, side="left"), 1, n - 1)
        left = right - 1
        return np.where(self.t[right] - times < times - self.t[left], right, left)

def string_lengths(trace: Trace) -> np.ndarray:
    """The six strings' lengths, [string, sample]."""
    _, conns = trace.points()
    return np.linalg.norm(conns[STRINGS[:, 0]] - conns[STRINGS[:, 1]], axis=-1)


def check_geometry(trace: Trace, k: float | None = None) -> float:
    """The drawing's geometry must be the model's: every foot the trace says
    is on the ground (contact code ±1 stick, ±2 slide on tip ±) lies on y = 0
    (the tip sign convention), and the six strings drawn (spoke j to j+1,
    natural length s·r, slack when short if the run's strings go slack) store
    the string energy the trace reports, at every sample. With the stiffness
    k (argument or design) the energy is compared as it is; without, k is
    fitted (least squares) and every sample must agree with that one k, which
    still pins the geometry. Raises GeometryError rather than let a wrong
    picture be drawn; returns the k used."""
    d = trace.design
    on = trace.contact != 0
    if on.any():
        worst = float(np.max(np.abs(trace.feet()[..., 1][on])))
        if worst > 1e-6 * d.length:
            raise GeometryError(f"a foot in contact is drawn {worst:.3g} m off the ground: geometry mismatch")
    rest = d.rest_length_ratio * d.r
    sides = string_lengths(trace)
    taut = ~(d.slack & (sides < rest))
    # Energy per unit stiffness, per sample.
    q = np.sum(np.where(taut, 0.5 * (sides - rest) ** 2, 0.0), axis=0)
    e = trace.string_potential
    k = k if k is not None else d.k
    if k is None:
        qq = float(np.dot(q, q))
        k = float(np.dot(q, e) / qq) if qq > 0 else 0.0
    rel = np.abs(k * q - e) / np.maximum(np.abs(e), 1e-12)
    worst_energy = float(np.max(rel))
    if worst_energy > 1e-6:
        raise GeometryError(f"the strings drawn store energy off the trace's by {worst_energy:.3g} (relative) "
                            f"at t = {trace.t[int(np.argmax(rel))]:.4g} s: geometry mismatch")
    return float(k)


def slope_axes(phi: float) -> np.ndarray:
    """Rows: the slope frame's x (downhill) and y (normal) in the world, so that
    a slope-frame point p is p @ slope_axes(φ) in the world."""
    return np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])


class Star:
    """The artists of one drawing of the star on its slope (ground, strings,
    rods, feet with their contact mode); `update(trace, i)` moves them to
    sample i and the view with the star. Drawn in the world, so the ground
    appears at its angle φ. The figures draw one, the animation redraws one."""

    def __init__(self, ax, design: Geometry, window: float, marks: float | None = None, aspect: float = 1.2):
        from matplotlib.collections import LineCollection
        from matplotlib.patches import Polygon

        # The view: `window` metres wide, aspect · window high, following the star.
        self.ax, self.design, self.window, self.aspect = ax, design, window, aspect
        self.to_world = slope_axes(design.phi)
        self.earth = Polygon(np.zeros((4, 2)), closed=True, color=EARTH_COLOR, zorder=0)
        ax.add_patch(self.earth)
        (self.ground,) = ax.plot([], [], color=GROUND_COLOR, lw=1.5, zorder=1)
        # Distance marks on the ground every `marks` metres, so a moving view still shows the travel.
        self.marks = marks
        self.mark_lines = LineCollection([], colors=GROUND_COLOR, linewidths=1.0, zorder=1)
        if marks:
            ax.add_collection(self.mark_lines)
        self.strings = [ax.plot([], [], color=STRING_COLOR, lw=0.9, zorder=2)[0] for _ in STRINGS]
        self.rods = [ax.plot([], [], color=ROD_COLOR[i], lw=3.2, solid_capstyle="round", zorder=3)[0]
                     for i in range(3)]
        feet = dict(ls="none", zorder=4, markersize=math.sqrt(38), markeredgecolor="black", markeredgewidth=1.2)
        (self.stick,) = ax.plot([], [], marker="o", color="black", **feet)
        (self.slide,) = ax.plot([], [], marker="D", markerfacecolor="white", **feet)
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
        for s in ax.spines.values():
            s.set_visible(False)

    def world(self, p: np.ndarray) -> np.ndarray:
        return p @ self.to_world

    def update(self, trace: Trace, i: int) -> list:
        """Move every artist to sample i; returns the artists changed."""
        d = self.design
        tips, conns = (self.world(p) for p in star_points(trace.x[:, i], trace.y[:, i], trace.theta[:, i],
                                                           d.length, d.r))  # [spoke, xy]
        hub_x = float(np.mean(trace.x[:, i]))
        centre = self.world(np.array([hub_x, 0.0])) + np.array([0.0, 0.45 * d.length])
        # Ground: the slope line y = 0 and a band below it.
        reach = max(2 * d.length, self.window)
        g0, g1 = self.world(np.array([hub_x - reach, 0.0])), self.world(np.array([hub_x + reach, 0.0]))
        below = -0.6 * d.length * self.to_world[1]
        self.earth.set_xy([g0, g1, g1 + below, g0 + below])
        self.ground.set_data([g0[0], g1[0]], [g0[1], g1[1]])
        if self.marks:
            xs = np.arange(math.ceil((hub_x - reach) / self.marks),
                           math.floor((hub_x + reach) / self.marks) + 1) * self.marks
            top = self.world(np.stack([xs, np.zeros_like(xs)], axis=-1))
            self.mark_lines.set_segments([[p, p + 0.06 * below] for p in top])
        for j, (a, b) in enumerate(STRINGS):
            p, q = conns[a], conns[b]
            self.strings[j].set_data([p[0], q[0]], [p[1], q[1]])
        for r in range(3):
            ends = tips[[PLUS[r], MINUS[r]]]
            self.rods[r].set_data(ends[:, 0], ends[:, 1])
        code = trace.contact[:, i]
        foot = stance_tips(tips[PLUS], tips[MINUS], code)
        for artist, kind in ((self.stick, STICK), (self.slide, SLIDE)):
            m = np.abs(code) == kind
            artist.set_data(foot[m, 0], foot[m, 1])
        w, h = self.window, self.aspect * self.window
        self.ax.set_xlim(centre[0] - w / 2, centre[0] + w / 2)
        # A little more below the centre than above: the ground band.
        self.ax.set_ylim(centre[1] - 0.62 / 1.2 * h, centre[1] + 0.58 / 1.2 * h)
        return [self.earth, self.ground, self.mark_lines, *self.strings, *self.rods, self.stick, self.slide]


def draw_star(ax, trace: Trace, i: int, window: float) -> Star:
    """One still of the star at sample i (a filmstrip frame)."""
    star = Star(ax, trace.design, window)
    star.update(trace, i)
    return star


def state_label(trace: Trace, i: int) -> str:
    """'t = 1.23 s  DLSP': the sample's time and contact state."""
    return f"t = {trace.t[i]:.2f} s  {STATE_NAMES[trace.state[i]]}"


def timeline(ax_modes, ax_state, trace: Trace, t0: float, t1: float, frames: np.ndarray) -> None:
    """Per-rod contact mode (stick / slide / free) and the number of rods on the ground."""
    m = (trace.t >= t0) & (trace.t <= t1)
    t = trace.t[m]
    nxt = np.append(t[1:], t1)
    for i in range(3):
        code = trace.contact[i, m]
        for kind, hatch, alpha in ((STICK, None, 0.95), (SLIDE, "////", 0.45)):
            sel = np.abs(code) == kind
            spans = list(zip(t[sel], nxt[sel] - t[sel]))
            ax_modes.broken_barh(spans, (2 - i - 0.38, 0.76), facecolors=ROD_COLOR[i], alpha=alpha,
                                 hatch=hatch, edgecolor=ROD_COLOR[i] if hatch else "none", linewidth=0)
    ax_modes.set_yticks([2, 1, 0], [f"rod {rod}" for rod in RODS], fontsize=8)
    ax_modes.set_ylim(-0.6, 2.6)
    ax_state.step(t, trace.state[m], where="post", color="black", lw=1.1)
    ax_state.set_yticks([0, 1, 2, 3], [f"{n} {s}" for n, s in enumerate(STATE_NAMES)], fontsize=7.5)
    ax_state.set_ylim(-0.3, 3.3)
    ax_state.set_xlabel("time t [s]")
    for ax in (ax_modes, ax_state):
        ax.set_xlim(t0, t1)
        ax.axvspan(frames[0], frames[-1], color="#fff3c4", zorder=-1)
        for f in frames:
            ax.axvline(f, color="#999999", lw=0.7, ls=":", zorder=0)
        ax.grid(axis="x", alpha=0.2)
