"""Type stubs of the native module ``rtw._rtw`` (crates/rtw-py/src/lib.rs).

Private: use the documented functions of :mod:`rtw`. ``values`` are the six
inputs (length, rho, alpha, fn, zeta, phi); ``sets`` are ``KEY=VALUE``
option assignments as ``rtw-scan --set`` takes them.
"""

from typing import Any, Callable

import pyarrow

__version__: str

def simulate(
    values: list[float], config: str | None, variant: str | None, sets: list[str]
) -> str: ...
def trace(
    values: list[float],
    config: str | None,
    variant: str | None,
    sets: list[str],
    limit: str,
) -> tuple[str, pyarrow.Table]: ...
def scan(
    path: str | None,
    text: str | None,
    variant: str | None,
    sets: list[str],
    threads: int | None,
    progress: Callable[[int, int], object] | None = None,
) -> pyarrow.Table: ...
def limit_cycle(
    values: list[float],
    config: str | None,
    variant: str | None,
    sets: list[str],
    settle_steps: int,
) -> dict[str, Any]: ...
def modes(
    values: list[float], config: str | None, variant: str | None, sets: list[str]
) -> dict[str, Any]: ...
def sobol_points(dims: int, n: int, seed: int | None = None) -> list[list[float]]: ...
def sensitivity(table: pyarrow.Table, resamples: int, seed: int | None) -> pyarrow.Table: ...
