"""rtw from Python: the rimless wheel-like tensegrity (RTW) of Zheng et al.

Simulate one design, trace its gait, scan a parameter box, find its limit
cycle and its modes, with the same code and the same checks as the
``rtw-scan`` command line (the Rust crates rtw-model and rtw-scan, built into
the extension module ``rtw._rtw``)::

    import rtw
    out = rtw.simulate(length=0.8, rho=2.5, alpha=0.125, fn=3.269, zeta=0.0514, phi=0.15)
    print(out.outcome, out.speed)                        # walk 1.72...
    table = rtw.scan("configs/smoke.toml")               # a pyarrow.Table
    df = __import__("polars").from_arrow(table)          # or table.to_pandas()

Options are the keys of ``rtw-scan simulate --set`` (docs/model.md §9):
keyword arguments for the undotted ones (``t_max=5.0``), and
``options={"contact.mu": 0.8}`` (or ``**{"contact.mu": 0.8}``) for the
dotted ones. Bad inputs and options raise ``ValueError`` with the command
line's message, naming the key and its valid range.

Tables cross from Rust through the Arrow C data interface: pyarrow imports
the Rust buffers as they are, without copying them or making a Python object
per value.
"""

from __future__ import annotations

import json
import math
import numbers
import os
import sys
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable, Mapping, TextIO

from . import _rtw

if TYPE_CHECKING:
    import pyarrow

__version__: str = _rtw.__version__

__all__ = [
    "LimitCycle",
    "Modes",
    "Outcome",
    "animate",
    "limit_cycle",
    "modal",
    "scan",
    "simulate",
    "trace",
]

Config = str | os.PathLike[str]
"""A config: a path (``str`` or ``os.PathLike``); for :func:`scan`, also TOML text."""


def __getattr__(name: str) -> Any:
    # `animate` lives in rtw.animation (matplotlib and friends), imported on first use.
    if name == "animate":
        from .animation import animate

        return animate
    raise AttributeError(f"module 'rtw' has no attribute {name!r}")


class Outcome:
    """One run's row: the fields of ``rtw-scan simulate --json``, as attributes.

    The same keys as a ``samples.parquet`` row (docs/data-dictionary.md), in
    column order: the inputs, the derived physical parameters, ``outcome``
    (the label), ``failure`` and ``message`` (``None`` when the run
    finished), the gait metrics, the limit-cycle summary, the work counts and
    ``wall_time_s`` (the run's own time in Rust). Metrics that do not apply,
    and non-finite values, are ``None``, as in the JSON. Immutable;
    :meth:`to_dict` gives a plain ``dict``.

    ``period`` is the gait's period as the ``period`` column has it: in
    touchdowns on the touchdown return map of this run, or, with
    ``limit_cycle=True`` and a cycle found, in steps on the step map
    (``LimitCycle.period``); the two can differ for one walk
    (docs/data-dictionary.md).
    """

    __slots__ = ("_fields",)

    sample_id: int
    length: float
    rho: float
    alpha: float
    fn: float
    zeta: float
    phi: float
    m: float
    l_c: float
    inertia: float
    r: float
    k: float
    c: float
    outcome: str
    failure: str | None
    message: str | None
    start: str | None
    t_end: float | None
    nlsp: float | None
    slsp: float | None
    dlsp: float | None
    tlsp: float | None
    window_steps: int | None
    flight_steps: float | None
    triple_steps: float | None
    touchdowns: int | None
    f_w: float | None
    f_w_newfoot: float | None
    speed: float | None
    mu_required: float | None
    slide_time: float | None
    energy_initial: float | None
    energy_last: float | None
    energy_gravity_released: float | None
    energy_impact_loss: float | None
    energy_damping_loss: float | None
    energy_friction_loss: float | None
    energy_balance_error: float | None
    period: int | None
    floquet_max: float | None
    cycle_residual: float | None
    steps: int | None
    rejected: int | None
    rhs_evals: int | None
    events: int | None
    wall_time_s: float

    def __init__(self, fields: Mapping[str, Any]) -> None:
        object.__setattr__(self, "_fields", dict(fields))

    def __getattr__(self, name: str) -> Any:
        try:
            return self._fields[name]
        except KeyError:
            raise AttributeError(f"Outcome has no field {name!r}") from None

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("Outcome is immutable")

    def __dir__(self) -> list[str]:
        return [*self._fields, "to_dict"]

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Outcome) and self._fields == other._fields

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        keys = ("outcome", "failure", "speed", "f_w", "period", "t_end")
        shown = ", ".join(f"{k}={self._fields.get(k)!r}" for k in keys)
        return f"Outcome({shown}, ...)"

    def to_dict(self) -> dict[str, Any]:
        """The fields as a new ``dict``, in column order (what ``--json`` prints)."""
        return dict(self._fields)


@dataclass(frozen=True)
class LimitCycle:
    """A periodic gait on the step map (the section at each new foot's touchdown).

    Attributes:
        period: the step map's period in steps (1: every step the same), the
            fixed point of ``Pⁿ``. Not the ``Outcome.period`` of a run
            without ``limit_cycle=True``, which counts touchdowns on the
            touchdown return map of the simulated run.
        fixed_point: the fixed point ``z`` of ``Pⁿ`` (the map's coordinates in
            the orbit's contact modes).
        residual: ``max |Pⁿ(z) − z| / scale`` at the solution.
        iterations: Newton iterations taken.
        multipliers: the nontrivial Floquet multipliers of ``Pⁿ``, largest
            modulus first.
        floquet_max: the largest multiplier modulus.
        stable: every multiplier inside the unit circle.
        label: the gait label of the orbit's steps (walk, skip, crawl, ...).
        step_times: the duration of each step of the orbit (s).
    """

    period: int
    fixed_point: tuple[float, ...]
    residual: float
    iterations: int
    multipliers: tuple[complex, ...]
    floquet_max: float
    stable: bool
    label: str
    step_times: tuple[float, ...]


@dataclass(frozen=True)
class Modes:
    """Eigen-frequencies of one design (rtw-model's ``modal``), in Hz.

    Attributes:
        s18_hz: the supplementary's S18 ``f_n`` of the derived constants.
        approx_hz: undamped frequencies of the approximate 3-rotor model's
            oscillating modes (``√3 f_n`` twice at zero rest length).
        approx_damped_hz: damped frequencies of its complex pairs.
        approx_damping_ratio: their damping ratios, same order.
        star_hz: the nine frequencies of the free 9-DOF star, sorted; the
            first ``star_rigid_modes`` are rigid (≈ 0).
        star_rigid_modes: how many of ``star_hz`` are rigid modes (3).
    """

    s18_hz: float
    approx_hz: tuple[float, ...]
    approx_damped_hz: tuple[float, ...]
    approx_damping_ratio: tuple[float, ...]
    star_hz: tuple[float, ...]
    star_rigid_modes: int


def _literal(key: str, value: Any) -> str:
    """``value`` as the VALUE of ``--set KEY=VALUE``."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        # As on the command line: TOML if it parses (`0.8`, `"eigen"`), else a bare string.
        return value
    raise ValueError(
        f"{key}: {value!r} is invalid: must be a bool, int, float or str (an option's value)"
    )


def _sets(options: Mapping[str, Any] | None, extra: Mapping[str, Any]) -> list[str]:
    """Options (``options=`` then keyword arguments) as ``--set`` assignments."""
    merged = {**(options or {}), **extra}
    sets = []
    for key, value in merged.items():
        if not isinstance(key, str) or "=" in key or not key:
            raise ValueError(f"{key!r}: not an option key (a dotted name such as contact.mu)")
        sets.append(f"{key}={_literal(key, value)}")
    return sets


def _path(config: Config | None) -> str | None:
    return None if config is None else os.fspath(config)


def _inputs(
    length: float, rho: float, alpha: float, fn: float, zeta: float, phi: float
) -> list[float]:
    values = [length, rho, alpha, fn, zeta, phi]
    names = ("length", "rho", "alpha", "fn", "zeta", "phi")
    for name, v in zip(names, values):
        if isinstance(v, bool) or not isinstance(v, numbers.Real):
            raise ValueError(f"{name}: {v!r} is invalid: must be a number")
    return [float(v) for v in values]


def _native_args(
    inputs: tuple[float, float, float, float, float, float],
    config: Config | None,
    variant: Config | None,
    options: Mapping[str, Any] | None,
    more_options: Mapping[str, Any],
) -> tuple[list[float], str | None, str | None, list[str]]:
    """The arguments every native call of one design takes: inputs, config, variant, sets."""
    return _inputs(*inputs), _path(config), _path(variant), _sets(options, more_options)


def simulate(
    length: float,
    rho: float,
    alpha: float,
    fn: float,
    zeta: float,
    phi: float,
    *,
    config: Config | None = None,
    variant: Config | None = None,
    options: Mapping[str, Any] | None = None,
    **more_options: Any,
) -> Outcome:
    """Runs one design, as ``rtw-scan simulate --json`` does.

    Args:
        length: rod length L (m).
        rho: mass per length ρ (kg/m).
        alpha: connection ratio α, in [0, 0.49].
        fn: eigen-frequency f_n (Hz).
        zeta: damping ratio ζ.
        phi: slope φ (rad).
        config: take the ``[simulation]`` options of this config file.
        variant: then layer this variant file's (configs/variants/*.toml).
        options: then these ``--set`` options, dotted keys allowed
            (``{"contact.mu": 0.8}``).
        **more_options: then these (``t_max=5.0``, ``**{"contact.mu": 0.8}``).

    Returns:
        The run's :class:`Outcome`. A run that did not finish is returned too,
        with ``outcome`` ``"diverged"`` and its ``message``.

    Raises:
        ValueError: an input or option is invalid (the message names it and
            its valid range), or a file cannot be read.
    """
    inputs = (length, rho, alpha, fn, zeta, phi)
    row = _rtw.simulate(*_native_args(inputs, config, variant, options, more_options))
    return Outcome(json.loads(row))


def trace(
    length: float,
    rho: float,
    alpha: float,
    fn: float,
    zeta: float,
    phi: float,
    *,
    dt: float | None = None,
    limit: str | int = "2GB",
    config: Config | None = None,
    variant: Config | None = None,
    options: Mapping[str, Any] | None = None,
    **more_options: Any,
) -> pyarrow.Table:
    """Runs one design and returns its time series, as ``rtw-scan simulate --trace``.

    The table has the trace file's columns, units and descriptions (field
    metadata ``unit``, ``description``): ``t``; per rod a, b, c its pose
    ``x_*``, ``y_*``, ``theta_*``, velocities ``vx_*``, ``vy_*``, ``omega_*``
    and contact mode ``contact_*``; ``contact_state`` (rods on the ground);
    the energies. Its schema metadata holds the file's: ``rtw.version``,
    ``rtw.params`` (JSON), ``rtw.options`` (TOML), and ``rtw.outcome``, the
    run's :class:`Outcome` as JSON.

    Args:
        dt: sampling interval (s) — the option ``trace_dt`` (0: every step);
            default: the options' (docs/model.md §9).
        limit: the most memory the table may take before the run, as
            ``--trace-limit``: a size such as ``"2GB"`` or ``"500MB"``
            (decimal units), or bytes. The run is refused, not cut, when its
            estimate (samples × 196 bytes) is larger.
        length, rho, alpha, fn, zeta, phi, config, variant, options,
        more_options: as for :func:`simulate`.

    Raises:
        ValueError: as :func:`simulate`; for a ``limit`` that is not a size,
            or above the machine's memory (a longer trace goes to a file:
            ``rtw-scan simulate --trace``); for a trace estimated above
            ``limit`` (the message says how big, and to raise ``dt``, lower
            ``t_max`` or raise ``limit``).
        MemoryError: the trace does not fit in memory after all.
    """
    extra = dict(more_options)
    if dt is not None:
        extra["trace_dt"] = dt
    inputs = (length, rho, alpha, fn, zeta, phi)
    row, table = _rtw.trace(*_native_args(inputs, config, variant, options, extra), str(limit))
    meta = dict(table.schema.metadata or {})
    meta[b"rtw.outcome"] = row.encode()
    return table.replace_schema_metadata(meta)


class _Bar:
    """A scan's progress on stderr, drawn as Python users know it from tqdm.

    A terminal gets a bar redrawn in place (``\\r``), ended by a newline
    when the scan is done; a notebook (ipykernel's stream, which draws
    ``\\r`` too) one text line updated in place; any other stream (a log, a
    pipe) a plain line every 10 % or 10 s and at the end, as ``rtw-scan
    run`` prints when stderr is not a terminal. No dependency: tqdm is not
    needed.
    """

    REDRAW = 0.1  # s between redraws in place
    LOG_EVERY = 10.0  # s between plain lines

    def __init__(self, stream: TextIO) -> None:
        self.stream = stream
        self.started = time.monotonic()
        self.drawn_at = -math.inf
        self.decile = 0
        self.last_done = -1
        self.in_place = _draws_in_place(stream)
        encoding = (getattr(stream, "encoding", None) or "").lower().replace("-", "")
        self.fill = "█" if encoding == "utf8" or not self.in_place else "#"

    def __call__(self, done: int, total: int) -> None:
        now = time.monotonic()
        finished = done >= total
        if self.in_place:
            if finished or now - self.drawn_at >= self.REDRAW:
                self.drawn_at = now
                self.stream.write("\r" + self._bar(done, total, now) + ("\n" if finished else ""))
                self.stream.flush()
            return
        decile = done * 10 // max(total, 1)
        if done != self.last_done and (
            finished or decile > self.decile or now - self.drawn_at >= self.LOG_EVERY
        ):
            self.drawn_at, self.decile, self.last_done = now, decile, done
            self.stream.write(f"rtw.scan: {self._counts(done, total, now)}\n")
            self.stream.flush()

    def _counts(self, done: int, total: int, now: float) -> str:
        elapsed = now - self.started
        rate = done / elapsed if elapsed > 0 else 0.0
        left = (total - done) / rate if rate > 0 else math.inf
        pct = 100 * done // max(total, 1)
        return (
            f"{done}/{total} ({pct}%) [{_clock(elapsed)}<{_clock(left)}, {rate:.1f} samples/s]"
        )

    def _bar(self, done: int, total: int, now: float) -> str:
        elapsed = now - self.started
        rate = done / elapsed if elapsed > 0 else 0.0
        left = (total - done) / rate if rate > 0 else math.inf
        pct = 100 * done // max(total, 1)
        width = 25
        full = width * done // max(total, 1)
        bar = self.fill * full + " " * (width - full)
        return (
            f"rtw.scan {pct:3d}%|{bar}| {done}/{total} "
            f"[{_clock(elapsed)}<{_clock(left)}, {rate:.1f} samples/s]"
        )


def _draws_in_place(stream: TextIO) -> bool:
    """Whether ``\\r`` redraws a line on ``stream``: a terminal, or a notebook's output."""
    if type(stream).__module__.startswith("ipykernel"):
        return True
    try:
        return stream.isatty()
    except (AttributeError, ValueError):
        return False


def _clock(seconds: float) -> str:
    """``mm:ss`` (``h:mm:ss`` from an hour on; ``?`` when unknown), as tqdm shows times."""
    if not math.isfinite(seconds):
        return "?"
    m, sec = divmod(int(seconds), 60)
    h, m = divmod(m, 60)
    return f"{h}:{m:02d}:{sec:02d}" if h else f"{m:02d}:{sec:02d}"


def scan(
    config: Config,
    *,
    variant: Config | None = None,
    set: Mapping[str, Any] | None = None,
    threads: int | None = None,
    progress: bool | Callable[[int, int], object] = True,
) -> pyarrow.Table:
    """Runs a scan in memory: the rows ``rtw-scan run CONFIG`` writes to samples.parquet.

    Same schema (units and descriptions in the field metadata, the file's
    metadata — config, its hash, version, seed, variant, wall time — in the
    schema's) and the same values but ``wall_time_s``, computed in parallel
    (rayon) with the GIL released. Ctrl-C (KeyboardInterrupt) stops it within
    the samples in flight and raises; nothing is kept.

    Args:
        config: a config file path, or TOML text (a ``str`` holding a newline
            or ``=``), as ``rtw-scan run`` reads.
        variant: layer this variant file's ``[simulation]`` keys over the config's.
        set: then these options (``{"contact.mu": 0.8}``), as ``--set``.
        threads: worker threads (default: one per core; at most 4 per core).
        progress: show the scan's progress on stderr (the default): a bar
            redrawn in place in a terminal, one line updated in place in a
            notebook, a line every 10 % elsewhere (a log). ``False``: nothing.
            A callable is called instead with ``(done, total)`` (rows
            computed, rows in all) every 50 ms and at the end; an exception
            it raises stops the scan and is raised.

    The rows are held in memory: a scan of more than 1 000 000 rows is
    refused (``ValueError``); run it with ``rtw-scan run CONFIG --out DIR``,
    which streams its rows to ``DIR/samples.parquet``, and read that file.

    Raises:
        ValueError: the config, a variant or an option is invalid, a file
            cannot be read (the message names the file and the key), or the
            scan has more rows than a scan in memory may have.
        MemoryError: the rows do not fit in memory.
        KeyboardInterrupt: interrupted.
    """
    path: str | None = None
    text: str | None = None
    if isinstance(config, str) and ("\n" in config or "=" in config):
        text = config
    else:
        path = os.fspath(config)
    if threads is not None and (isinstance(threads, bool) or not isinstance(threads, int) or threads < 1):
        raise ValueError(f"threads: {threads!r} is invalid: must be an integer >= 1")
    if isinstance(progress, bool):
        stream = sys.stderr
        report = _Bar(stream) if progress and stream is not None else None
    elif callable(progress):
        report = progress
    else:
        raise ValueError(f"progress: {progress!r} is invalid: must be True, False or a callable")
    return _rtw.scan(path, text, _path(variant), _sets(set, {}), threads, report)


def limit_cycle(
    length: float,
    rho: float,
    alpha: float,
    fn: float,
    zeta: float,
    phi: float,
    *,
    settle_steps: int = 60,
    config: Config | None = None,
    variant: Config | None = None,
    options: Mapping[str, Any] | None = None,
    **more_options: Any,
) -> LimitCycle:
    """The limit cycle the run from the initial state settles into, and its stability.

    The step map (section at each new foot's touchdown, integrated with
    DOP853 at tight tolerances) is iterated ``settle_steps`` steps from the
    start, the period (up to 12) is recognised on the section points, Newton
    solves ``Pⁿ(z) = z`` with variational Jacobians, and the Floquet
    multipliers are the eigenvalues of the Jacobian there (as
    ``rtw-scan bifurcation`` does at each value).

    Args:
        settle_steps: steps iterated before looking for the period.
        length, rho, alpha, fn, zeta, phi, config, variant, options,
        more_options: as for :func:`simulate`.

    Raises:
        ValueError: an input or option is invalid.
        RuntimeError: no limit cycle (a step failed, no period, or Newton
            did not converge), with the reason.
    """
    inputs = (length, rho, alpha, fn, zeta, phi)
    if isinstance(settle_steps, bool) or not isinstance(settle_steps, int) or settle_steps < 1:
        raise ValueError(f"settle_steps: {settle_steps!r} is invalid: must be an integer >= 1")
    d = _rtw.limit_cycle(
        *_native_args(inputs, config, variant, options, more_options), settle_steps
    )
    return LimitCycle(
        period=d["period"],
        fixed_point=tuple(d["fixed_point"]),
        residual=d["residual"],
        iterations=d["iterations"],
        multipliers=tuple(complex(re, im) for re, im in d["multipliers"]),
        floquet_max=d["floquet_max"],
        stable=d["stable"],
        label=d["label"],
        step_times=tuple(d["step_times"]),
    )


def modal(
    length: float,
    rho: float,
    alpha: float,
    fn: float,
    zeta: float,
    phi: float,
    *,
    config: Config | None = None,
    variant: Config | None = None,
    options: Mapping[str, Any] | None = None,
    **more_options: Any,
) -> Modes:
    """The eigen-frequencies of one design: S18's f_n, the approximate model's, the free star's.

    The string model (rest length ``strings.rest_length_ratio``, damping)
    and the normalization come from the options, as in a run.

    Args:
        length, rho, alpha, fn, zeta, phi, config, variant, options,
        more_options: as for :func:`simulate`.

    Raises:
        ValueError: an input or option is invalid.
    """
    inputs = (length, rho, alpha, fn, zeta, phi)
    d = _rtw.modes(*_native_args(inputs, config, variant, options, more_options))
    return Modes(
        s18_hz=d["s18_hz"],
        approx_hz=tuple(d["approx_hz"]),
        approx_damped_hz=tuple(d["approx_damped_hz"]),
        approx_damping_ratio=tuple(d["approx_damping_ratio"]),
        star_hz=tuple(d["star_hz"]),
        star_rigid_modes=d["star_rigid_modes"],
    )
