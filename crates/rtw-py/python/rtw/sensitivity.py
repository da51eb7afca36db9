"""Sobol sensitivity indices of a scan's outcome classes and outputs (``rtw-scan sensitivity``)."""

from __future__ import annotations

import os
from collections.abc import Callable
from typing import TYPE_CHECKING

from . import _rtw
from ._progress import Progress

if TYPE_CHECKING:
    import pyarrow


def sensitivity(
    table: pyarrow.Table | str | os.PathLike[str],
    *,
    resamples: int = 100,
    seed: int | None = None,
    progress: bool | Callable[[int, int], object] = True,
) -> pyarrow.Table:
    """First-order and total Sobol indices of every output to every uniform input.

    The same computation as ``rtw-scan sensitivity``: each outcome label as a
    0/1 indicator (failed samples included, never dropped), ``stable`` and
    ``failure``, and ``speed``, ``f_w`` and ``floquet_max`` where every row has
    a value. A scan run with ``sampling = "saltelli"`` gets S1 and ST as
    SALib's ``sobol.analyze(calc_second_order=False)`` computes them; any other
    scan the given-data binned first-order index (ST is NaN).

    Args:
        table: the table :func:`rtw.scan` returns, or a scan file's path
            (``samples.parquet``, or its directory); the config is read from
            the table's schema metadata, or the file's. Either is checked as
            ``rtw-scan sensitivity`` checks a scan file, by the same library
            code: its content hash (a file's, or a table's that carries
            one), its values, its ``sample_id`` once each in order from 0
            (Saltelli's estimator pairs rows by position), not a refine's
            combined file (its rows are not draws from the inputs).
        resamples: bootstrap resamples of the 95 % intervals, an integer in
            [2, 10000].
        seed: seed of the resamples, an integer in [0, 2^64 - 1] (default:
            the scan's seed).
        progress: as for :func:`rtw.scan`, counting bootstrap resamples (of
            each output, and of each input for the binned index).

    Returns:
        A ``pyarrow.Table`` with columns output, parameter, S1, S1_conf, ST,
        ST_conf (S1_conf, ST_conf: half-widths of 95 % bootstrap intervals).

    Warns:
        UserWarning: any 95 % half-width is above 0.1 (the words of
            ``rtw-scan sensitivity``'s warning).

    Raises:
        ValueError: the table or file is not a complete scan of uniform axes
            without a grid, is refused as corrupt or refined, or an argument
            is out of range (the words of ``rtw-scan sensitivity``, with
            ``resamples`` for ``--resamples``).
        KeyboardInterrupt: interrupted (Ctrl-C stops it within a resample).
    """
    if isinstance(table, (str, os.PathLike)):
        table = os.fspath(table)
    with Progress(progress, "rtw.sensitivity", "resamples") as report:
        return _rtw.sensitivity(table, resamples, seed, report)
