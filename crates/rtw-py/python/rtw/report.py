"""A scan, or a design search, as one HTML page you can open: ``rtw.report(DIR)``
/ ``python -m rtw report DIR``.

:func:`report` runs four stages: it reads the folder with rtw-scan's
verified readers (a scan, else a design search's folder or an atlas), picks
what the page shows and renders it (a scan's page: ``scan_page.py``; a
design search's: ``design_report.py``; what both share: ``_page.py``), and
writes it through the native layer (``_rtw.write_page``: rtw-scan's
refusals, an atomic write). The page itself is described in docs/report.md.

Only the standard library is imported here at module level, so that
``import rtw`` stays light; numpy (the ``report`` extra:
``pip install 'rtw[report]'``) is needed when a report is made.
"""

from __future__ import annotations

import numbers
import os
from pathlib import Path
from typing import Any, Callable, Iterable, Sequence

from . import _rtw
from ._checks import flag
from ._page import ASSETS, GENERATOR, PLOTLY_JS, ReportError, plotly_bundle
from ._progress import Progress
from .design_report import design_page
from .scan_page import DEFAULT_OUTPUTS, INPUTS, MAX_ROWS, PER_OUTCOME, PLOT_ROWS, Scan, pick, render, scan_of

__all__ = ["ASSETS", "GENERATOR", "INPUTS", "MAX_ROWS", "PER_OUTCOME", "PLOTLY_JS", "PLOT_ROWS", "ReportError",
           "report"]


def _sample_ids(samples: Any) -> list[int]:
    """`samples` as a list of ids: an iterable of integers >= 0 (not bools,
    not floats, not a string)."""
    if isinstance(samples, (str, bytes)) or not isinstance(samples, Iterable):
        raise TypeError(f"samples: {samples!r} is not a list of sample ids (integers >= 0)")
    ids = []
    for s in samples:
        if isinstance(s, bool) or not isinstance(s, numbers.Integral):
            raise TypeError(f"samples: {s!r} is not a sample id: must be an integer >= 0")
        if s < 0:
            raise ReportError(f"samples: {s} is invalid: must be a sample id >= 0")
        ids.append(int(s))
    return ids


def _column_names(outputs: Any) -> list[str]:
    """`outputs` as a list of column names (a list, not one string)."""
    if isinstance(outputs, (str, bytes)) or not isinstance(outputs, Iterable):
        raise TypeError(f"outputs: {outputs!r} is not a list of column names (e.g. ['speed', 'f_w'])")
    names = list(outputs)
    for c in names:
        if not isinstance(c, str):
            raise TypeError(f"outputs: {c!r} is not a column name: must be a string")
    return names


def report(directory: str | os.PathLike[str], out: str | os.PathLike[str] | None = None, *,
           outputs: Sequence[str] | None = None, per_outcome: int = PER_OUTCOME,
           samples: Iterable[int] = (), force: bool = False,
           progress: bool | Callable[[int, int], object] = True) -> Path:
    """Writes one self-contained HTML report of a scan, or of a design
    search's folder or atlas (the design page, docs/design.md); returns its path.

    Args:
        directory: a scan directory (``samples.parquet``, or the
            ``part-*.parquet`` of a shard set), or a scan Parquet file.
        out: the HTML file; default ``DIR/report.html``. A file that is not
            an rtw report is never written over (``force=True`` does), nor
            a symlink or anything but a regular file (not even with
            ``force``); the page is written whole or not at all (a
            temporary file beside it, renamed).
        outputs: the output columns on the parallel coordinates beside the
            inputs (default ``speed``, ``f_w``, ``mu_required``).
        per_outcome: representative samples with a gait per outcome, in [0, 10].
        samples: sample ids whose gait is computed too.
        force: write over a file that is not an rtw report.
        progress: as for :func:`rtw.scan`, counting the gaits computed
            (the slow part: each is a run of its sample).

    Raises:
        FileNotFoundError: no such directory or file, or no folder for ``out``.
        ValueError: not a scan, or a scan rtw-scan refuses (read with
            :func:`rtw.read_scan`: corrupt, altered, an incomplete shard
            set; the message names the file), a summary.json, assignments
            file or sensitivity indices beside it that are not its own
            (another scan's, or altered), an unknown output column, a bad option,
            an output that is not an rtw report (without ``force``), a symlink
            or not a regular file, or a page that cannot be written.
        TypeError: ``samples`` not a list of integer ids, ``outputs`` not
            a list of column names.
        ImportError: numpy is missing (``pip install 'rtw[report]'``), or
            rtw's Plotly.js bundle is missing or changed.
    """
    directory = Path(directory)
    if not directory.exists():
        raise FileNotFoundError(f"DIR: {directory} is neither a scan directory nor a Parquet file")
    base = directory if directory.is_dir() else directory.parent
    out = Path(out) if out is not None else base / "report.html"
    if isinstance(per_outcome, bool) or not isinstance(per_outcome, int) or not 0 <= per_outcome <= 10:
        raise ReportError(f"per_outcome: {per_outcome!r} is invalid: must be an integer in [0, 10]")
    samples = _sample_ids(samples)
    outputs = list(DEFAULT_OUTPUTS) if outputs is None else _column_names(outputs)
    force = flag("force", force)
    # Refused before any work; checked again as it is written.
    _rtw.check_page(out, force)
    plotly_js = plotly_bundle()
    tell = Progress(progress, "rtw.report", "gaits")

    found = _read(directory, base)
    if isinstance(found, Scan):
        page = render(found, pick(found, outputs, per_outcome, samples, tell), plotly_js)
    else:
        page = design_page(directory, found, plotly_js)
    _rtw.write_page(out, page, force)
    return out


def _read(directory: Path, base: Path) -> Scan | list[tuple[Path, str, Any]]:
    """The folder (or file) `directory` read by rtw-scan's verified readers:
    a scan (its files' hashes, the rows' values, the ids once each in order,
    every shard of an unmerged set; beside it its summary.json and
    assignments file only when they are its own), else a design search's
    folder or an atlas (its files, each with its role). Errors name the file."""
    try:
        table, files, summary_text, assigned = _rtw.read_scan_folder(directory)
    except ValueError as e:
        # Not a scan: a design search's folder or an atlas is reported as one
        # (the design page), read by rtw-scan's verified design reader.
        try:
            designs = _rtw.read_design(directory)
        except ValueError as d:
            raise ReportError(f"DIR: {d}") from None
        if designs is None:
            raise ReportError(f"DIR: {e}") from None
        return designs
    return scan_of(base, table, files, summary_text, assigned)
