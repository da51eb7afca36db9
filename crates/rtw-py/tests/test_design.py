"""rtw-scan's sampling designs against scipy.stats.qmc."""

from __future__ import annotations

import numpy as np
import pytest

import rtw
from rtw import _rtw

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
