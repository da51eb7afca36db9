"""Type stubs of the native module ``rtw._rtw`` (crates/rtw-py/src).

Private but for the classes, which :mod:`rtw` re-exports: use the documented
functions of :mod:`rtw`. ``values`` are the six inputs (length, rho, alpha,
fn, zeta, phi); ``options`` is the options dict (dotted keys or nested
dicts), handed to the config layer as typed values.

tests/test_types.py checks every class's fields here against the module's
(``Outcome``'s against rtw-scan's row columns: names, order, types and
nullability), and every function's parameters.
"""

import os
from pathlib import Path
from typing import Any, Callable, Mapping

import pyarrow

# A config: a path, TOML text (a str holding a newline or "="), or a dict of its tables.
ConfigArg = str | os.PathLike[str] | Mapping[str, Any] | None

__version__: str
LABELS: tuple[str, ...]
STABLE_LABELS: tuple[str, ...]
FAILURE_LABELS: tuple[str, ...]
Z95: float
# The marker in every page rtw.report writes, by which write_page knows rtw's own.
PAGE_GENERATOR: str
# Each spoke (a+, b+, c+, a−, b−, c−) as (rod index, tip sign ±1); each string as its pair of spokes.
SPOKES: list[tuple[int, int]]
STRINGS: list[tuple[int, int]]

class Outcome:
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
    # Only when the options ask for them (docs/robustness.md), after the
    # columns: step_down_max (robustness.step_down), step_down_h50
    # (robustness.step_down_h50), step_down_survival, step_down_collapse,
    # step_down_stall, step_down_other_gait and step_down_diverged
    # (robustness.step_down_at), gsn (robustness.gsn), steps_to_fall…
    # (robustness.steps_to_fall), mfpt, mfpt_lo, mfpt_hi and fall_rate
    # (robustness.mfpt), all float | None; read them with getattr or to_dict().
    def to_dict(self) -> dict[str, Any]: ...

class LimitCycle:
    period: int
    fixed_point: tuple[float, ...]
    residual: float
    iterations: int
    multipliers: tuple[complex, ...]
    floquet_max: float
    stable: bool
    label: str
    step_times: tuple[float, ...]
    def to_dict(self) -> dict[str, Any]: ...

class Modes:
    s18_hz: float
    approx_hz: tuple[float, ...]
    approx_damped_hz: tuple[float, ...]
    approx_damping_ratio: tuple[float, ...]
    star_hz: tuple[float, ...]
    star_rigid_modes: int
    def to_dict(self) -> dict[str, Any]: ...

class Profile:
    intervals: dict[str, tuple[tuple[float, float], ...]]
    stable_intervals: tuple[tuple[float, float], ...]
    phi_min: float | None
    phi_lo: float | None
    phi_hi: float | None
    changes: tuple[tuple[float, float, str, str, bool], ...]
    runs: int
    table: pyarrow.Table
    def to_dict(self) -> dict[str, Any]: ...

class DesignSearch:
    summary: str
    runs: int
    evaluations: pyarrow.Table
    designs: pyarrow.Table
    archive: pyarrow.Table
    def to_dict(self) -> dict[str, Any]: ...

def simulate(
    values: list[float],
    config: ConfigArg,
    variant: str | None,
    options: Mapping[str, Any] | None,
) -> Outcome: ...
def trace(
    values: list[float],
    config: ConfigArg,
    variant: str | None,
    options: Mapping[str, Any] | None,
    limit: str,
) -> pyarrow.Table: ...
def scan(
    config: str | os.PathLike[str] | Mapping[str, Any],
    variant: str | None,
    options: Mapping[str, Any] | None,
    threads: int | None,
    progress: Callable[[int, int], object] | None = None,
    sampling: str | None = None,
    samples: int | None = None,
    seed: int | None = None,
) -> pyarrow.Table: ...
def limit_cycle(
    values: list[float],
    config: ConfigArg,
    variant: str | None,
    options: Mapping[str, Any] | None,
    settle_steps: int,
) -> LimitCycle: ...
def basin(
    values: list[float],
    config: ConfigArg,
    variant: str | None,
    options: Mapping[str, Any] | None,
    x: str,
    y: str,
    steps: int,
    tol: float,
    threads: int | None,
    progress: Callable[[int, int], object] | None = None,
) -> pyarrow.Table: ...
def profile(
    design: list[float],
    config: ConfigArg,
    variant: str | None,
    options: Mapping[str, Any] | None,
    phi_from: float,
    phi_to: float,
    tol: float,
    grid: float,
    threads: int | None,
) -> Profile: ...
def design(
    path: str,
    out: str | None,
    variant: str | None,
    options: Mapping[str, Any] | None,
    threads: int | None,
    force: bool,
    progress: Callable[[int, int], object] | None = None,
) -> DesignSearch: ...
def modes(
    values: list[float],
    config: ConfigArg,
    variant: str | None,
    options: Mapping[str, Any] | None,
) -> Modes: ...
def label(
    nlsp: float,
    tlsp: float,
    flight_steps: float,
    triple_steps: float,
    options: Mapping[str, Any] | None,
) -> str: ...
def wilson(k: int, n: int, z: float) -> tuple[float, float]: ...
def failure_clusters(path: str | os.PathLike[str]) -> list[tuple[int, int]] | None: ...
def sobol_points(dims: int, n: int, seed: int | None = None) -> list[list[float]]: ...
# `resamples`, `seed`, `steps` and `threads` are any object: the library checks each
# against its range (an int of any size, or the refusal that names its range).
def sensitivity(
    scan: pyarrow.Table | str,
    resamples: int,
    seed: int | None,
    progress: Callable[[int, int], object] | None = None,
) -> pyarrow.Table: ...
def read_scan(path: str | os.PathLike[str]) -> tuple[pyarrow.Table, list[Path]]: ...
def star_points(
    x: Sequence[float], y: Sequence[float], theta: Sequence[float], length: float, r: float
) -> tuple[list[float], list[float]]: ...
def read_scan_folder(
    path: str | os.PathLike[str],
) -> tuple[pyarrow.Table, list[Path], str | None, tuple[Path, list[tuple[int, int]]] | None]: ...
def read_indices(path: str | os.PathLike[str], scan: Mapping[str, str], rows: int) -> pyarrow.Table: ...
def read_design(path: str | os.PathLike[str]) -> list[tuple[Path, str, pyarrow.Table]] | None: ...
def density_grid(group: bytes, groups: int, x: bytes, y: bytes) -> list[list[int]]: ...
def check_page(path: str | os.PathLike[str], force: bool) -> None:
    """Refuses ``path`` as the place of a page: a symlink or not a regular
    file (always), a file without ``PAGE_GENERATOR`` (unless ``force``),
    a folder that does not exist (``FileNotFoundError``)."""
    ...
def write_page(path: str | os.PathLike[str], html: str, force: bool) -> None:
    """Writes ``html`` at ``path`` atomically, checked as ``check_page`` checks it."""
    ...
def scan_views(table: pyarrow.Table, columns: list[str], x: str, y: str, sample: int, seed: int) -> dict[str, Any]:
    """The report's aggregated views of a large scan: ``labels``, ``outcome``
    (bytes), ``columns`` ({name: (range or None, bytes)}), ``density`` (per
    label, row-major on ``code_bins`` × ``code_bins``), ``sample`` (row
    indices), ``code_bins``, ``code_none``."""
    ...
