#!/usr/bin/env python3
"""The time of each step of one scan report, as one line of text:

    .venv/bin/python scripts/report_steps.py DIR OUT.html

Steps: reading the scan through rtw-scan's verified reader; aggregating it
(the coded columns, densities and stratified sample of a scan of more than
PLOT_ROWS rows, in Rust); clustering the failures (rtw-scan's k-means, when
no assignments file is beside the scan); the gaits (a run of each
representative sample); packing the page (JSON, gzip, base64) and writing
it; and the rest. Each is
timed by wrapping the report modules' own functions (rtw.report, which reads
and writes; rtw.scan_page, which picks and renders; rtw._page, which packs),
so what is timed is what `python -m rtw report` runs (scripts/report_scale.sh).
"""

from __future__ import annotations

import sys
import time
from collections import defaultdict

import rtw  # noqa: F401  (loads rtw.report)

report = sys.modules["rtw.report"]
scan_page = sys.modules["rtw.scan_page"]
page = sys.modules["rtw._page"]
spent: dict[str, float] = defaultdict(float)


def timed(step: str, f):
    def wrapper(*args, **kwargs):
        t = time.perf_counter()
        try:
            return f(*args, **kwargs)
        finally:
            spent[step] += time.perf_counter() - t
    return wrapper


class Rtw:
    """rtw.report's `_rtw`, with its reader and its writer timed."""

    def __getattr__(self, name):
        f = getattr(report._rtw_module, name)
        step = {"read_scan_folder": "read", "write_page": "pack"}.get(name)
        return timed(step, f) if step else f


report._rtw_module = report._rtw
report._rtw = Rtw()
scan_page._big = timed("aggregate", scan_page._big)
scan_page._big_clusters = timed("aggregate", scan_page._big_clusters)
scan_page.failure_clusters = timed("clusters", scan_page.failure_clusters)
scan_page._gait = timed("gaits", scan_page._gait)
page.b64gz = timed("pack", page.b64gz)
start = time.perf_counter()
report.report(sys.argv[1], sys.argv[2], force=True, progress=False)
total = time.perf_counter() - start
parts = ["read", "aggregate", "clusters", "gaits", "pack"]
rest = total - sum(spent[p] for p in parts)
print(", ".join(f"{p} {spent[p]:.1f}" for p in parts) + f", the rest {rest:.1f}")
