"""Sobol sensitivity indices of a scan's outcome classes and outputs (``rtw-scan sensitivity``)."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from . import _rtw

if TYPE_CHECKING:
    import pyarrow


def sensitivity(
    table: pyarrow.Table | str | os.PathLike[str],
    *,
    resamples: int = 100,
    seed: int | None = None,
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
            the table's schema metadata, or the file's.
        resamples: bootstrap resamples of the 95 % intervals.
        seed: seed of the resamples (default: the scan's seed).

    Returns:
        A ``pyarrow.Table`` with columns output, parameter, S1, S1_conf, ST,
        ST_conf (S1_conf, ST_conf: half-widths of 95 % bootstrap intervals).

    Raises:
        ValueError: the table is not a complete scan of uniform axes without
            a grid, or an argument is out of range.
    """
    if isinstance(resamples, bool) or not isinstance(resamples, int) or resamples < 2:
        raise ValueError(f"resamples: {resamples!r} is invalid: must be an integer >= 2")
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, int) or not 0 <= seed < 2**64):
        raise ValueError(f"seed: {seed!r} is invalid: must be an integer in [0, 2^64)")
    if isinstance(table, (str, os.PathLike)):
        import pyarrow.parquet as pq

        path = os.fspath(table)
        if os.path.isdir(path):
            path = os.path.join(path, "samples.parquet")
        # The config is in the file's key-value metadata, which pyarrow keeps
        # out of the table's schema when the file stores an Arrow schema.
        meta = pq.read_metadata(path).metadata or {}
        table = pq.read_table(path)
        table = table.replace_schema_metadata({**(table.schema.metadata or {}), **meta})
    return _rtw.sensitivity(table, resamples, seed)
