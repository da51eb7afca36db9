"""The brute-force check of scripts/continuation.py plane --check on columns
made by hand, where the answer is known: a doubling curve that folds in f_n
crosses a column twice (its crossings against the closed form of the curve),
and a subcritical doubling's coexistence band admits a period-2 walk before
the doubling while a supercritical one does not."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import polars as pl

sys.path.insert(0, str(Path(__file__).resolve().parents[3] / "scripts"))
import continuation  # noqa: E402


def parabola(n: int = 401) -> pl.DataFrame:
    """A period-doubling curve f_n = 3 + 100 (φ − 0.2)² over φ ∈ [0.15, 0.25],
    continued both ways from its turning point (0.2, 3.0), as rtw-scan writes
    two directions of one curve."""
    rows = []
    for curve, phis in ((0, np.linspace(0.2, 0.25, n)), (1, np.linspace(0.2, 0.15, n))):
        for i, phi in enumerate(phis):
            rows.append({"curve": curve, "index": i, "kind": "period_doubling", "value": phi,
                         "value2": 3.0 + 100.0 * (phi - 0.2) ** 2})
    return pl.DataFrame(rows)


def test_a_curve_folded_in_fn_crosses_a_column_twice_at_its_closed_form():
    curve = parabola()
    for col in (3.01, 3.1, 3.2):
        xs = [x for x, _ in continuation.crossings(curve, col)]
        half = np.sqrt((col - 3.0) / 100.0)
        assert len(xs) == 2, xs
        # The polyline's chords lie within (Δφ)²·100/8 of the parabola in f_n.
        np.testing.assert_allclose(xs, [0.2 - half, 0.2 + half], atol=2e-5)
    assert continuation.crossings(curve, 2.99) == []
    # A column through the turning point touches the curve without crossing
    # it: no stability change, so no crossing (the shared first point of the
    # two directions is not counted twice either).
    assert continuation.crossings(curve, 3.0) == []


GRID = np.round(np.arange(0.10, 0.2501, 0.005), 3)


def column(cls_of) -> tuple[np.ndarray, list[str]]:
    return GRID, [cls_of(phi) for phi in GRID]


def test_a_stable_period_one_walk_past_the_doubling_disagrees():
    v, cls = column(lambda phi: "walk1" if phi <= 0.18 else "walk2")
    assert continuation.check_column(v, cls, [0.1812], 0.005, None) == []
    bad = continuation.check_column(v, cls, [0.1612], 0.005, None)
    assert any("stable period-1 walk at 0.170" in b for b in bad), bad


def test_between_two_crossings_the_period_one_walk_is_unstable_and_stable_again_past_the_second():
    # Stable below 0.15, unstable on 0.15–0.20, stable again above 0.20.
    v, cls = column(lambda phi: "walk2" if 0.15 < phi < 0.20 else "walk1")
    assert continuation.check_column(v, cls, [0.1501, 0.2001], 0.005, None) == []
    # One interpolated crossing per column (the old check) would put the
    # walks above 0.20 on the unstable side:
    bad = continuation.check_column(v, cls, [0.1501], 0.005, None)
    assert any("stable period-1 walk at 0.210" in b for b in bad), bad


def test_a_period_two_walk_before_the_doubling_needs_a_subcritical_band():
    # Period 2 from 0.17, the doubling at 0.1851: both walks between.
    v, cls = column(lambda phi: "walk1" if phi < 0.17 else "walk2")
    supercritical = continuation.check_column(v, cls, [0.1851], 0.005, None)
    assert any("supercritical" in b for b in supercritical), supercritical
    # Subcritical, the fold of the period-2 branch at 0.168: the band holds them.
    assert continuation.check_column(v, cls, [0.1851], 0.005, (0.168, 0.1851)) == []
    # A fold at 0.178 ends the band before 0.17, 0.175.
    bad = continuation.check_column(v, cls, [0.1851], 0.005, (0.178, 0.1851))
    assert any("below the period-2 branch's fold" in b for b in bad), bad
    # Where the fold is not known (another column), the band is not bounded.
    nan = float("nan")
    assert continuation.check_column(v, cls, [0.1851], 0.005, (nan, nan)) == []


def test_the_column_of_the_diagram_must_see_a_walk_between_fold_and_doubling():
    v, cls = column(lambda phi: "walk1" if phi < 0.15 else "skip0")
    bad = continuation.check_column(v, cls, [0.1851], 0.005, (0.168, 0.1851))
    assert any("neither walk" in b for b in bad), bad
