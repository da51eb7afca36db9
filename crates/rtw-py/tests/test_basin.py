"""rtw.basin: the basin slice of `rtw-scan basin`, from the same library function."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pyarrow.parquet as pq
import pytest

import rtw
from test_rtw import assert_same_columns

ROOT = Path(__file__).resolve().parents[3]
BINARY = Path(os.environ.get("RTW_SCAN", Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "release/rtw-scan"))
FIG7A = (0.8, 2.5, 0.125, 3.269, 0.0514, 0.15)
# A coarse slice through the walk's fixed point (the centre point is the fixed point itself).
X, Y = "omega_a:-30:30:3", "theta_b:-0.3:0.3:3"


def test_basin_gives_the_rows_rtw_scan_basin_writes(tmp_path: Path) -> None:
    table = rtw.basin(*FIG7A, x=X, y=Y, steps=8, threads=2)
    assert table.num_rows == 9
    assert BINARY.is_file(), f"{BINARY} is missing: cargo build --release -p rtw-scan (or set RTW_SCAN)"
    design = ["--length", "0.8", "--rho", "2.5", "--alpha", "0.125", "--fn", "3.269", "--zeta", "0.0514", "--phi", "0.15"]
    out = tmp_path / "basin.parquet"
    subprocess.run([str(BINARY), "basin", *design, "--x", X, "--y", Y, "--steps", "8", "--out", str(out)],
                   check=True, capture_output=True)
    assert_same_columns(table, pq.read_table(out))
    # The grid's centre is the gait's own fixed point: it returns at once.
    centre = table.slice(4, 1).to_pylist()[0]
    assert (centre["x"], centre["y"], centre["outcome"]) == (0.0, 0.0, "returns"), centre
    # The same rows on one thread.
    assert rtw.basin(*FIG7A, x=X, y=Y, steps=8, threads=1).equals(table)


@pytest.mark.parametrize(
    ("kwargs", "named"),
    [
        ({"x": "omega_q:-1:1:3", "y": Y}, "x"),
        ({"x": X, "y": "theta_b:-1:1"}, "y"),
        ({"x": X, "y": Y, "tol": 5.0}, "tol"),
        ({"x": X, "y": Y, "threads": 0}, "threads"),
    ],
)
def test_bad_settings_raise_naming_the_setting(kwargs: dict, named: str) -> None:
    with pytest.raises(ValueError, match=rf"^{named}\b"):
        rtw.basin(*FIG7A, steps=8, **kwargs)
