"""rtw-scan's sampling designs against scipy.stats.qmc."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import numpy as np
import pyarrow.parquet as pq
import pytest

import rtw
from rtw import _rtw
from test_rtw import assert_same_columns

qmc = pytest.importorskip("scipy.stats.qmc")

# The paper's box (configs/paper.toml) with a short run: only the inputs matter.
BOX = {"rho": (1.0, 5.0), "alpha": (0.0, 0.4), "fn": (1.5, 5.0), "zeta": (0.05, 0.1), "phi": (0.05, 0.3)}


def _config(sampling: str, n: int, seed: int = 11) -> str:
    axes = "\n".join(f"{k} = {{ uniform = [{lo}, {hi}] }}" for k, (lo, hi) in BOX.items())
    return (
        f'seed = {seed}\nsamples = {n}\nsampling = "{sampling}"\n[params]\nlength = 0.8\n{axes}\n'
        "[simulation]\nt_max = 0.2\n"
    )


def _unit(table) -> np.ndarray:
    cols = [(np.asarray(table.column(k)) - lo) / (hi - lo) for k, (lo, hi) in BOX.items()]
    return np.column_stack(cols)


@pytest.mark.parametrize("m", [0, 1, 4, 10])
def test_unscrambled_sobol_points_equal_scipy(m: int) -> None:
    """The first 2^m points in all 12 dimensions are scipy's, bit for bit."""
    ours = np.array(_rtw.sobol_points(12, 2**m))
    theirs = qmc.Sobol(d=12, scramble=False).random_base2(m)
    assert ours.shape == theirs.shape
    np.testing.assert_array_equal(ours, theirs)


def test_sobol_points_refuse_bad_sizes() -> None:
    with pytest.raises(ValueError, match=r"dims: 13 is invalid: must be in \[1, 12\]"):
        _rtw.sobol_points(13, 4)
    with pytest.raises(ValueError, match="n: "):
        _rtw.sobol_points(2, 2**21)


@pytest.mark.parametrize("sampling", ["sobol", "halton", "lhs"])
def test_designed_scans_beat_random_sampling_in_centred_discrepancy(sampling: str) -> None:
    """At equal n, a scan's designed inputs cover the box more evenly than its random ones."""
    n = 256
    random = _unit(rtw.scan(_config("random", n), progress=False))
    designed_table = rtw.scan(_config(sampling, n), progress=False)
    designed = _unit(designed_table)
    assert designed.shape == (n, 5)
    assert ((designed >= 0) & (designed <= 1)).all()
    cd_random = qmc.discrepancy(random, method="CD")
    cd_designed = qmc.discrepancy(designed, method="CD")
    assert cd_designed < cd_random, (cd_designed, cd_random)
    # The scan's Sobol inputs are the Sobol points of its seed, in id order.
    if sampling == "sobol":
        points = np.array(_rtw.sobol_points(5, n, 11))
        np.testing.assert_allclose(designed, points, atol=1e-12)


ROOT = Path(__file__).resolve().parents[3]
BINARY = Path(os.environ.get("RTW_SCAN", Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "release/rtw-scan"))


@pytest.mark.parametrize("sampling", ["sobol", "saltelli"])
def test_design_options_give_the_rows_rtw_scan_runs(sampling: str, tmp_path: Path) -> None:
    """rtw.scan(random config, sampling=..., samples=..., seed=...) is row for row the run of the config holding them."""
    short = "\n[simulation]\nt_max = 0.2\n", "\n[simulation]\nt_max = 3.0\n"
    given = _config("random", 10, seed=1).replace(*short)
    table = rtw.scan(given, sampling=sampling, samples=16, seed=23, progress=False)
    holding = _config(sampling, 16, seed=23).replace(*short)
    assert BINARY.is_file(), f"{BINARY} is missing: cargo build --release -p rtw-scan (or set RTW_SCAN)"
    (tmp_path / "c.toml").write_text(holding)
    subprocess.run([str(BINARY), "run", str(tmp_path / "c.toml"), "--out", str(tmp_path / "scan")],
                   check=True, capture_output=True)
    ran = pq.read_table(tmp_path / "scan/samples.parquet")
    assert table.num_rows == ran.num_rows == 16 * (7 if sampling == "saltelli" else 1)
    assert len(set(table.column("outcome").to_pylist())) > 1
    assert_same_columns(table, ran, skip={"wall_time_s"})
    # The same config, hash included, as the text holding the keys.
    meta = pq.read_metadata(tmp_path / "scan/samples.parquet").metadata
    assert table.schema.metadata[b"rtw.config_hash"] == meta[b"rtw.config_hash"]


def test_design_options_are_checked_with_the_field_and_valid_values() -> None:
    config = _config("random", 8)
    designs = "must be one of random, sobol, halton, lhs, grid, saltelli"
    with pytest.raises(ValueError, match=f'sampling: "sobl" is invalid: {designs}'):
        rtw.scan(config, sampling="sobl", progress=False)
    with pytest.raises(ValueError, match=f"sampling: 3 is invalid: {designs}"):
        rtw.scan(config, sampling=3, progress=False)
    with pytest.raises(ValueError, match=r'samples: 100 is invalid for sampling = "grid" with 5 uniform axes: must be m\^5'):
        rtw.scan(config, sampling="grid", samples=100, progress=False)
    with pytest.raises(ValueError, match="samples: 0 is invalid: must be an integer >= 1"):
        rtw.scan(config, samples=0, progress=False)
    for key, bad in (("samples", -1), ("samples", True), ("seed", -1), ("seed", 2**64), ("seed", 1.5)):
        with pytest.raises(ValueError, match=f"{key}: {bad!r} is invalid: must be an integer"):
            rtw.scan(config, progress=False, **{key: bad})


@pytest.mark.parametrize("key, bad", [("samples", -1), ("samples", True), ("samples", 2**63), ("samples", "8"),
                                      ("seed", -1), ("seed", 2**63), ("seed", 1.5), ("seed", False)])
def test_design_counts_are_checked_by_the_native_layer_with_their_range(key, bad) -> None:
    """`samples` and `seed` are counts the native layer reads (rtw-scan's
    `config::count`): anything but an integer a config can hold is refused
    naming the key, the value and the range, with no check of Python's."""
    import inspect

    assert "2**63" not in inspect.getsource(rtw.scan)
    with pytest.raises(ValueError) as e:
        rtw.scan(_config("random", 8), progress=False, **{key: bad})
    shown = repr(bad) if not isinstance(bad, int) or isinstance(bad, bool) else str(bad)
    assert str(e.value) == f"{key}: {shown} is invalid: must be an integer in [0, 9223372036854775807]"
