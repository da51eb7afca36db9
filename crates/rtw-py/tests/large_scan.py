"""A scan too large for the report to carry row by row (more than
rtw.report.PLOT_ROWS rows), shared by test_report_large.py and the browser
test: configs/paper.toml with PLOT_ROWS + 1000 samples and t_max = 1 s (about
2 s on 2 cores; the short runs make a mix with a rare outcome), run by the
rtw-scan binary and reported once per test module."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

from rtw.report import PLOT_ROWS

ROOT = Path(__file__).resolve().parents[3]
BINARY = Path(os.environ.get("RTW_SCAN", Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "release/rtw-scan"))
SAMPLES = PLOT_ROWS + 1000


def make_scan(folder: Path, alpha: float | None = None) -> Path:
    """The scan in `folder`/scan (its samples.parquet and summary); with
    `alpha`, α held fixed at that value instead of drawn."""
    assert BINARY.is_file(), f"{BINARY} is missing: cargo build --release -p rtw-scan (or set RTW_SCAN)"
    text = (ROOT / "configs/paper.toml").read_text()
    assert "\nsamples = 1000\n" in text and "\nt_max = 20.0\n" in text
    text = text.replace("\nsamples = 1000\n", f"\nsamples = {SAMPLES}\n").replace("\nt_max = 20.0\n", "\nt_max = 1.0\n")
    if alpha is not None:
        drawn = "\nalpha = { uniform = [0.0, 0.4] }\n"
        assert drawn in text
        text = text.replace(drawn, f"\nalpha = {alpha}\n")
    config = folder / "large.toml"
    config.write_text(text)
    scan = folder / "scan"
    subprocess.run([str(BINARY), "run", str(config), "--out", str(scan), "--quiet"], check=True,
                   capture_output=True, timeout=600)
    return scan
