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
                         "end": "end_parameter_range",
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


def check(cls, xs, band=None, open_=()):
    v, c = column(cls)
    return continuation.check_column(v, c, [(x, x in open_) for x in xs], 0.005, band)


def test_a_stable_period_one_walk_past_the_doubling_disagrees():
    cls = lambda phi: "walk1" if phi <= 0.18 else "walk2"  # noqa: E731
    assert check(cls, [0.1812])[0] == []
    bad, _ = check(cls, [0.1612])
    assert any("stable period-1 walk at 0.170" in b for b in bad), bad


def test_between_two_crossings_the_period_one_walk_is_unstable_and_stable_again_past_the_second():
    # Stable below 0.15, unstable on 0.15–0.20, stable again above 0.20.
    cls = lambda phi: "walk2" if 0.15 < phi < 0.20 else "walk1"  # noqa: E731
    assert check(cls, [0.1501, 0.2001])[0] == []
    # One crossing per column (the interpolated φ of the former check) would
    # put the walks above 0.20 on the unstable side:
    bad, _ = check(cls, [0.1501])
    assert any("stable period-1 walk at 0.210" in b for b in bad), bad


def test_past_an_open_crossing_the_scan_is_not_checked_and_says_so():
    cls = lambda phi: "walk1"  # noqa: E731
    bad, notes = check(cls, [0.1501], open_=(0.1501,))
    assert bad == []
    assert any("not checked" in n for n in notes), notes


def test_a_period_two_walk_where_the_period_one_walk_is_stable_is_a_coexisting_attractor():
    cls = lambda phi: "walk1" if phi < 0.17 else "walk2"  # noqa: E731
    bad, notes = check(cls, [0.1851], band=(0.178, 0.1851))
    assert bad == []
    # 0.170–0.185 are before the crossing; 0.180, 0.185 lie in the band.
    assert any("period-2 walk(s) where the period-1 walk is stable too (2 in the doubling's band)" in n
               for n in notes), notes


def test_the_column_of_the_diagram_must_see_a_walk_between_the_band_and_the_doubling():
    cls = lambda phi: "walk1" if phi < 0.15 else "skip0"  # noqa: E731
    bad, _ = check(cls, [0.1851], band=(0.168, 0.1851))
    assert any("neither walk" in b for b in bad), bad
    # Elsewhere (no band) the standing start may settle on a third attractor.
    assert check(cls, [0.1851])[0] == []
