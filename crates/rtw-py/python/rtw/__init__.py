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

A design's six inputs are keyword arguments or one :class:`Design`.
Options are the keys of ``rtw-scan simulate --set`` (docs/model.md §9), in
the keyword ``options=`` of every function (``{"contact.mu": 0.8}`` or
``{"contact": {"mu": 0.8}}``), and, for one design, as keyword arguments
(``t_max=5.0``); their values go to the config layer as typed values, not
text. Bad inputs and options raise ``ValueError`` with the command line's
message, naming the key and its valid range. Results are typed, frozen
objects (:class:`Outcome`, :class:`LimitCycle`, :class:`Modes`) whose fields
are the Rust definitions' (``_rtw.pyi`` is checked against them).

Tables cross from Rust through the Arrow C data interface: pyarrow imports
the Rust buffers as they are, without copying them or making a Python object
per value.
"""

from __future__ import annotations

import os
import warnings
from dataclasses import dataclass, fields
from typing import TYPE_CHECKING, Any, Callable, Mapping

from . import _rtw
from ._checks import flag, number
from ._progress import Progress
from ._rtw import FAILURE_LABELS, LABELS, STABLE_LABELS, Z95, DesignSearch, LimitCycle, Modes, Outcome, Profile
from .report import report
from .sensitivity import sensitivity

if TYPE_CHECKING:
    import pyarrow

__version__: str = _rtw.__version__

__all__ = [
    "FAILURE_LABELS",
    "LABELS",
    "STABLE_LABELS",
    "Design",
    "DesignSearch",
    "LimitCycle",
    "Modes",
    "Outcome",
    "Profile",
    "animate",
    "basin",
    "design",
    "label",
    "limit_cycle",
    "modal",
    "profile",
    "read_scan",
    "report",
    "scan",
    "sensitivity",
    "simulate",
    "trace",
    "wilson",
]

Config = str | os.PathLike[str] | Mapping[str, Any]
"""A config: a path (``str`` or ``os.PathLike``), TOML text (a ``str``
holding a newline or ``=``), or a dict of its tables (``{"simulation":
{"contact": {"mu": 0.8}}}``), as a file would hold them. A variant is a path."""


def __getattr__(name: str) -> Any:
    # `animate` lives in rtw.animation (matplotlib and friends), imported on first use.
    if name == "animate":
        from .animation import animate

        return animate
    raise AttributeError(f"module 'rtw' has no attribute {name!r}")


@dataclass(frozen=True)
class Design:
    """One design: the six inputs of docs/model.md §1, as a scan row's columns name them.

    Every function of one design takes a ``Design`` or the six inputs as
    keyword arguments (``rtw.simulate(length=0.8, rho=2.5, ...)``); a
    ``Design`` is checked to hold numbers, the model checks their ranges.

    Attributes:
        length: rod length L (m).
        rho: mass per length ρ (kg/m).
        alpha: connection ratio α, in [0, 0.49].
        fn: eigen-frequency f_n (Hz).
        zeta: damping ratio ζ.
        phi: slope φ (rad).
    """

    length: float
    rho: float
    alpha: float
    fn: float
    zeta: float
    phi: float

    def __post_init__(self) -> None:
        for name in _INPUTS:
            object.__setattr__(self, name, number(name, getattr(self, name)))


_INPUTS = tuple(f.name for f in fields(Design))


def _design(who: str, given: tuple[Any, ...], kwargs: dict[str, Any]) -> list[float]:
    """The six inputs of a call: a ``Design``, or numbers by position then by
    keyword (taken out of ``kwargs``, which then holds only options)."""
    if len(given) == 1 and isinstance(given[0], Design):
        clash = [n for n in _INPUTS if n in kwargs]
        if clash:
            raise TypeError(f"{who}() got a Design and the input {clash[0]!r}: give one of them")
        d = given[0]
    else:
        if len(given) > len(_INPUTS):
            raise TypeError(f"{who}() takes a Design or at most 6 inputs, got {len(given)}")
        values = dict(zip(_INPUTS, given))
        for name in _INPUTS[len(given):]:
            if name in kwargs:
                values[name] = kwargs.pop(name)
        clash = [n for n in _INPUTS[: len(given)] if n in kwargs]
        if clash:
            raise TypeError(f"{who}() got multiple values for the input {clash[0]!r}")
        missing = [n for n in _INPUTS if n not in values]
        if missing:
            raise TypeError(
                f"{who}() is missing the input(s) {', '.join(missing)}: give a Design or "
                "length, rho, alpha, fn, zeta and phi"
            )
        d = Design(**values)
    return [d.length, d.rho, d.alpha, d.fn, d.zeta, d.phi]


def _options(options: Mapping[str, Any] | None, extra: Mapping[str, Any]) -> dict[str, Any] | None:
    """``options=`` then the keyword arguments, as one dict for the config layer."""
    if options is not None and not isinstance(options, Mapping):
        raise ValueError(f"options: {options!r} is invalid: must be a dict of option keys and values")
    merged = {**(options or {}), **extra}
    return merged or None


def _path(config: Config | None) -> str | None:
    return None if config is None else os.fspath(config)


def simulate(
    *design: Design | float,
    config: Config | None = None,
    variant: Config | None = None,
    options: Mapping[str, Any] | None = None,
    **more: Any,
) -> Outcome:
    """Runs one design, as ``rtw-scan simulate --json`` does.

    ``rtw.simulate(length=0.8, rho=2.5, alpha=0.125, fn=3.269, zeta=0.0514,
    phi=0.15)``, or ``rtw.simulate(Design(...))``: every function of one
    design (:func:`trace`, :func:`limit_cycle`, :func:`modal`) takes its
    inputs and options this way.

    Args:
        design: a :class:`Design`; or give its six inputs ``length``,
            ``rho``, ``alpha``, ``fn``, ``zeta``, ``phi`` as keyword
            arguments (or, in that order, by position).
        config: take the ``[simulation]`` options of this config: a file,
            TOML text, or a dict of its tables (:data:`Config`).
        variant: then layer this variant file's (``configs/variants/*.toml``).
        options: then these options (docs/model.md §9), by dotted key
            (``{"contact.mu": 0.8}``) or nested (``{"contact": {"mu": 0.8}}``);
            values are bool, int, float, str, or lists of them.
        **more: the six inputs when no ``Design`` is given; then more
            options, which win over ``options`` (``t_max=5.0``,
            ``**{"contact.mu": 0.8}``).

    Returns:
        The run's :class:`Outcome`. A run that did not finish is returned too,
        with ``outcome`` ``"diverged"`` and its ``message``.

    Raises:
        ValueError: an input or option is invalid (the message names it and
            its valid range), or a file cannot be read.
        TypeError: an input is missing or given twice.
    """
    values = _design("simulate", design, more)
    return _rtw.simulate(values, config, _path(variant), _options(options, more))


def trace(
    *design: Design | float,
    dt: float | None = None,
    limit: str | int = "2GB",
    config: Config | None = None,
    variant: Config | None = None,
    options: Mapping[str, Any] | None = None,
    **more: Any,
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
        design, config, variant, options, more: as for :func:`simulate`.

    Raises:
        ValueError: as :func:`simulate`; for a ``limit`` that is not a size,
            or above the machine's memory (a longer trace goes to a file:
            ``rtw-scan simulate --trace``); for a trace estimated above
            ``limit`` (the message says how big, and to raise ``dt``, lower
            ``t_max`` or raise ``limit``).
        MemoryError: the trace does not fit in memory after all.
    """
    values = _design("trace", design, more)
    if dt is not None:
        more["trace_dt"] = dt
    return _rtw.trace(values, config, _path(variant), _options(options, more), str(limit))


def scan(
    config: Config,
    *,
    variant: Config | None = None,
    options: Mapping[str, Any] | None = None,
    threads: int | None = None,
    progress: bool | Callable[[int, int], object] = True,
    set: Mapping[str, Any] | None = None,
    sampling: str | None = None,
    samples: int | None = None,
    seed: int | None = None,
) -> pyarrow.Table:
    """Runs a scan in memory: the rows ``rtw-scan run CONFIG`` writes to samples.parquet.

    Same schema (units and descriptions in the field metadata, the file's
    metadata — config, its hash, version, seed, variant, wall time — in the
    schema's) and the same values but ``wall_time_s``, computed in parallel
    (rayon) with the GIL released. Ctrl-C (KeyboardInterrupt) stops it within
    the samples in flight and raises; nothing is kept.

    Args:
        config: a config file path, TOML text (a ``str`` holding a newline
            or ``=``), or a dict of its tables (:data:`Config`), as
            ``rtw-scan run`` reads.
        variant: layer this variant file's ``[simulation]`` keys over the config's.
        options: then these options (``{"contact.mu": 0.8}``), as ``--set``
            and as for :func:`simulate`.
        threads: worker threads (default: one per core; at most 4 per core).
        progress: show the scan's progress on stderr (the default), drawn
            by tqdm: a bar redrawn in place in a terminal, one line updated
            in place in a notebook, a status line every 10 s and at the end
            elsewhere (a log). ``False``: nothing.
            A callable is called instead with ``(done, total)`` (rows
            computed, rows in all) every 50 ms and at the end; an exception
            it raises stops the scan and is raised.
        set: the former name of ``options``: deprecated (a
            ``DeprecationWarning``), removed in the next release.
        sampling: the design of the uniform axes, over the config's
            ``sampling``: ``"random"``, ``"sobol"``, ``"halton"``, ``"lhs"``,
            ``"grid"`` (``samples = m^D``) or ``"saltelli"`` (``samples`` base
            rows of ``D + 2`` runs each).
        samples: draws per grid point (base rows of a Saltelli design), over
            the config's ``samples``.
        seed: the seed of every draw, over the config's ``seed``. With any of
            the three, the rows are those of ``rtw-scan run`` on the config
            holding them. ``samples`` and ``seed`` are integers in
            [0, 2^63 - 1], as a config holds them, then checked as its keys
            are (``samples`` at least 1).

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
    tell = Progress(progress, "rtw.scan", "samples")
    if set is not None:
        warnings.warn(
            "rtw.scan(set=...) is deprecated: use options=..., the keyword of every rtw function",
            DeprecationWarning,
            stacklevel=2,
        )
        if options is not None:
            raise TypeError("scan() got both set= and options=: give options= only")
        options = set
    with tell as report:
        return _rtw.scan(config, _path(variant), _options(options, {}), threads, report, sampling, samples, seed)


def limit_cycle(
    *design: Design | float,
    settle_steps: int = 60,
    config: Config | None = None,
    variant: Config | None = None,
    options: Mapping[str, Any] | None = None,
    **more: Any,
) -> LimitCycle:
    """The limit cycle the run from the initial state settles into, and its stability.

    The step map (section at each new foot's touchdown, integrated with
    DOP853 at tight tolerances) is iterated ``settle_steps`` steps from the
    start, the period (up to 12) is recognised on the section points, Newton
    solves ``Pⁿ(z) = z`` with variational Jacobians, and the Floquet
    multipliers are the eigenvalues of the Jacobian there (as
    ``rtw-scan bifurcation`` does at each value).

    Args:
        settle_steps: steps iterated before looking for the period, an
            integer in [1, 10000000].
        design, config, variant, options, more: as for :func:`simulate`.

    Raises:
        ValueError: an input or option is invalid.
        RuntimeError: no limit cycle (a step failed, no period, or Newton
            did not converge), with the reason.
    """
    values = _design("limit_cycle", design, more)
    return _rtw.limit_cycle(
        values, config, _path(variant), _options(options, more), settle_steps
    )


def basin(
    *design: Design | float,
    x: str,
    y: str,
    steps: int = 60,
    tol: float = 1e-3,
    threads: int | None = None,
    progress: bool | Callable[[int, int], object] = True,
    config: Config | None = None,
    variant: Config | None = None,
    options: Mapping[str, Any] | None = None,
    **more: Any,
) -> pyarrow.Table:
    """A slice of the gait's basin of attraction, as ``rtw-scan basin`` makes it.

    The design's gait is solved on the step map; two section coordinates
    are offset from its fixed point over a grid, every other one held, and
    each point is iterated up to ``steps`` steps and classified
    (``returns``, ``survives``, ``fails``, ``infeasible``; docs/robustness-gsn.md).

    Args:
        x, y: the grid's axes, ``"COORD:FROM:TO:POINTS"`` with COORD one of
            ``omega_a``, ``omega_b``, ``omega_c``, ``theta_a``, ``theta_b``,
            ``theta_c`` (e.g. ``"omega_a:-40:40:41"``).
        steps: most steps a point is iterated, an integer in [1, 100000].
        tol: a point returns at this scaled distance to the orbit, in (0, 0.1].
        threads: worker threads (default: one per core; at most 4 per
            core); the rows do not depend on it.
        progress: as for :func:`scan`, counting grid points.
        design, config, variant, options, more: as for :func:`simulate`.

    Returns:
        One row per grid point, ``y`` outer and ``x`` inner: the columns of
        the CLI's Parquet file (docs/results-on-disk.md).

    Raises:
        ValueError: an input, option or setting is invalid (named with its
            range, in the words of ``rtw-scan basin``), or the gait has no
            stable limit cycle.
        KeyboardInterrupt: interrupted (Ctrl-C stops it after the points in
            flight).
    """
    values = _design("basin", design, more)
    with Progress(progress, "rtw.basin", "points") as report:
        return _rtw.basin(
            values, config, _path(variant), _options(options, more), x, y, steps, number("tol", tol), threads, report
        )


def profile(
    *design: Design | float,
    phi_from: float,
    phi_to: float,
    tol: float = 1e-3,
    grid: float = 0.01,
    threads: int | None = None,
    config: Config | None = None,
    variant: Config | None = None,
    options: Mapping[str, Any] | None = None,
    **more: Any,
) -> Profile:
    """The slope profile of one design, as ``rtw-scan profile`` makes it.

    ``rtw.profile(length=0.8, rho=2.5, alpha=0.125, fn=3.269, zeta=0.0514,
    phi_from=0.05, phi_to=0.3)``: the design's gait at each slope of
    [``phi_from``, ``phi_to``], on a grid at most ``grid`` apart, then each
    pair of neighbouring slopes whose labels differ halved until it is at
    most ``tol`` wide (docs/design.md).

    Args:
        design: the five inputs ``length``, ``rho``, ``alpha``, ``fn``,
            ``zeta`` (by keyword or position), or a :class:`Design`, whose
            ``phi`` is not used: the slope is the profile's axis.
        phi_from, phi_to: the slope range [rad], each in (-pi/2, pi/2),
            ``phi_to`` above ``phi_from``.
        tol: each change of label is located to this [rad], in [1e-9, grid].
        grid: the coarse grid's spacing, at most [rad]; a feature narrower
            than it, with one label at both its ends, is not seen.
        threads: worker threads (default: one per core; at most 4 per core);
            the profile does not depend on it.
        config, variant, options, more: as for :func:`simulate`.

    Returns:
        A :class:`Profile`: ``intervals`` per stable gait, ``stable_intervals``,
        ``phi_min``, ``phi_lo``, ``phi_hi``, ``changes``, ``runs`` and
        ``table`` (every simulated slope as a ``pyarrow.Table``).

    Raises:
        ValueError: an input, option or setting is invalid (named with its
            range, in the words of ``rtw-scan profile``).
        KeyboardInterrupt: interrupted (Ctrl-C stops the runs in flight).
    """
    if "phi" in more:
        raise TypeError("profile() takes no phi: the slope is its axis (phi_from, phi_to)")
    given_design = len(design) == 1 and isinstance(design[0], Design)
    # The slope is not an input of a profile: a placeholder completes the design.
    if not given_design:
        more["phi"] = 0.0
    values = _design("profile", design, more)  # takes the inputs out of `more`
    more.pop("phi", None)
    return _rtw.profile(
        values[:5],
        config,
        _path(variant),
        _options(options, more),
        number("phi_from", phi_from),
        number("phi_to", phi_to),
        number("tol", tol),
        number("grid", grid),
        threads,
    )


def modal(
    *design: Design | float,
    config: Config | None = None,
    variant: Config | None = None,
    options: Mapping[str, Any] | None = None,
    **more: Any,
) -> Modes:
    """The eigen-frequencies of one design: S18's f_n, the approximate model's, the free star's.

    The string model (rest length ``strings.rest_length_ratio``, damping)
    and the normalization come from the options, as in a run.

    Args:
        design, config, variant, options, more: as for :func:`simulate`.

    Raises:
        ValueError: an input or option is invalid.
    """
    values = _design("modal", design, more)
    return _rtw.modes(values, config, _path(variant), _options(options, more))


def label(
    nlsp: float,
    tlsp: float,
    flight_steps: float,
    triple_steps: float,
    *,
    options: Mapping[str, Any] | None = None,
    **more: Any,
) -> str:
    """The label the model gives a stable gait: ``"skip"``, ``"walk"`` or ``"crawl"``.

    Table S1's rule as rtw-model applies it (docs/model.md §5): flight
    (``nlsp`` above ``labels.flight`` and ``flight_steps`` at least
    ``labels.flight_steps``) makes a skip, else triple support likewise a
    crawl, else a walk. The arguments are a scan row's columns of the same
    names, so a stored stable row can be relabelled under other thresholds.

    Args:
        nlsp, tlsp: the gait window's fractions of time with no foot and
            with three feet on the ground.
        flight_steps, triple_steps: the shares of its steps with flight and
            with triple support.
        options, more: the ``labels.*`` thresholds over the defaults, as
            for :func:`simulate` (``{"labels.flight_steps": 0.0}``).

    Raises:
        ValueError: an option is invalid (named, with its range).
    """
    shares = [number(k, v) for k, v in zip(("nlsp", "tlsp", "flight_steps", "triple_steps"),
                                           (nlsp, tlsp, flight_steps, triple_steps))]
    return _rtw.label(*shares, _options(options, more))


def wilson(k: int, n: int, z: float = Z95) -> tuple[float, float]:
    """The Wilson score interval ``(lo, hi)`` of ``k`` successes in ``n`` trials, as fractions.

    The interval of rtw-scan's summaries (``z`` = :data:`Z95`, 95 %);
    ``(0.0, 1.0)`` when ``n`` is 0.

    Raises:
        ValueError: ``k`` > ``n``; OverflowError: a negative count.
    """
    return _rtw.wilson(k, n, number("z", z))


def read_scan(path: str | os.PathLike[str]) -> pyarrow.Table:
    """A scan's rows as one ``pyarrow.Table``, read and checked as
    ``rtw-scan summary`` and ``sensitivity`` read them.

    ``path`` is a scan file, or a directory with ``samples.parquet`` (a plain
    or merged scan) or else the ``part-K.parquet`` of a shard set. Each
    file's footer and rows must match the hashes written with them, the row
    values must be valid, the ``sample_id`` s must run once each, in order,
    and a shard set must hold every shard of one scan. The table's schema
    metadata is the scan's (``rtw.config``, ``rtw.seed``,
    ``rtw.content_hash``, ...); a shard set's is what its merged file's
    would be (``rtw.shards``, and the content hash of all its rows).

    Raises:
        ValueError: not a scan, or a file rtw-scan refuses (corrupt,
            altered, an incomplete shard set); the message names the file.
    """
    return _rtw.read_scan(path)[0]


def design(
    config: Config,
    out: Config | None = None,
    threads: int | None = None,
    force: bool = False,
    progress: bool | Callable[[int, int], object] = True,
    variant: Config | None = None,
    options: Mapping[str, Any] | None = None,
) -> DesignSearch:
    """A design search, as ``rtw-scan design CONFIG`` runs it.

    ``rtw.design("configs/design/widest.toml", out="runs/design/widest")``:
    searches the config's box of designs for those that maximise its
    objectives (``slope_range``, ``phi_min``, ``speed``, ``mfpt``) by the
    config's ``method`` (``cmaes``, ``archive`` or ``sobol``), each candidate
    judged by its slope profile, falls learned as a constraint
    (docs/design.md).

    Args:
        config: the search's config (a TOML file, ``configs/design/*.toml``).
        out: the search's folder: its files are written there as the CLI
            writes them, and an interrupted search of the same config resumes
            from them. Without it the search runs in memory.
        threads: worker threads (default: one per core; at most 4 per core);
            the search does not depend on it.
        force: write over files in ``out`` that are not this search's.
        progress: as for :func:`scan`, counting simulations (then the
            reported designs' verification).
        variant, options: the model over the config's own [simulation] table,
            as for :func:`simulate` over its ``config``.

    Returns:
        A :class:`DesignSearch`: ``summary`` (Markdown), ``runs``,
        ``evaluations``, ``designs`` and ``archive`` (``pyarrow.Table``).

    Raises:
        ValueError: a config key, option or setting is invalid (named with
            its range, in the words of ``rtw-scan design``), or ``out`` holds
            files that are not this search's.
        KeyboardInterrupt: interrupted (Ctrl-C stops the runs in flight;
            with ``out``, every finished design is kept).
    """
    with Progress(progress, "rtw.design", "runs") as report:
        return _rtw.design(
            os.fspath(config), _path(out), _path(variant), _options(options, {}), threads, flag("force", force), report
        )

