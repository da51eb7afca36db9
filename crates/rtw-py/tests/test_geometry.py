"""The star's geometry for drawings comes from rtw-model (`_rtw.star_points`,
`SPOKES`, `STRINGS`), and it is the model's: checked against closed forms
(docs/model.md §1–§2) and against the simulation's own string energy."""

from __future__ import annotations

import math

import numpy as np
import pytest

import rtw
from rtw import _rtw, draw

FIG7A = dict(length=0.8, rho=2.5, alpha=0.125, fn=3.269, zeta=0.0514, phi=0.15)


def test_tips_and_connection_points_are_the_closed_form_on_a_trace() -> None:
    """Reference: the closed form of docs/model.md §1, tips c ± (L/2) e and
    connection points c ± r e, e = (cos θ, sin θ), r = L(1 − 2α)/2, at every
    sample of a simulated trace (the trace's own centres and angles)."""
    table = rtw.trace(**FIG7A, t_max=2.0)
    L, r = FIG7A["length"], FIG7A["length"] * (1 - 2 * FIG7A["alpha"]) / 2
    cols = {c: np.asarray(table[c].to_numpy(), dtype=float) for c in table.column_names}
    x = np.stack([cols[f"x_{k}"] for k in "abc"])
    y = np.stack([cols[f"y_{k}"] for k in "abc"])
    th = np.stack([cols[f"theta_{k}"] for k in "abc"])
    tips, conns = draw.star_points(x, y, th, L, r)
    assert tips.shape == conns.shape == (6, table.num_rows, 2)
    e = np.stack([np.cos(th), np.sin(th)], axis=-1)
    c = np.stack([x, y], axis=-1)
    for j, (rod, sign) in enumerate(_rtw.SPOKES):
        np.testing.assert_allclose(tips[j], c[rod] + sign * (L / 2) * e[rod], rtol=0, atol=1e-12)
        np.testing.assert_allclose(conns[j], c[rod] + sign * r * e[rod], rtol=0, atol=1e-12)
    # Each rod is L long between its two tips.
    for rod in range(3):
        np.testing.assert_allclose(np.linalg.norm(tips[draw.PLUS[rod]] - tips[draw.MINUS[rod]], axis=-1), L, atol=1e-12)


def test_strings_join_neighbouring_spokes_round_the_star() -> None:
    """Reference: in the rest shape (docs/model.md §3: centres at one hub,
    rods 60° apart) the connection points are the corners of a regular
    hexagon of circumradius r, so each of the six strings, joining
    neighbouring spokes, is r long, and together they go once round."""
    r, theta_a = 0.3, 0.2
    tips, conns = draw.star_points([0.0] * 3, [0.0] * 3, [theta_a + i * math.pi / 3 for i in range(3)], 1.0, r)
    assert sorted(a for a, _ in _rtw.STRINGS) == list(range(6))
    assert sorted(b for _, b in _rtw.STRINGS) == list(range(6))
    sides = [np.linalg.norm(conns[a] - conns[b]) for a, b in _rtw.STRINGS]
    np.testing.assert_allclose(sides, r, rtol=0, atol=1e-12)
    # The spokes go round counter-clockwise, 60° apart, from θ_a.
    angles = [math.atan2(p[1], p[0]) for p in tips]
    for j, a in enumerate(angles):
        assert math.isclose((a - theta_a - j * math.pi / 3 + math.pi) % (2 * math.pi) - math.pi, 0, abs_tol=1e-12)


def test_the_drawn_strings_store_the_simulated_string_energy() -> None:
    """Reference: the simulation's own `string_potential` column, with the
    run's k; `check_geometry` holds the strings drawn from rtw-model's
    points to it at every sample (relative 1e-6)."""
    table = rtw.trace(**FIG7A, t_max=2.0)
    out = rtw.simulate(**FIG7A, t_max=2.0)
    trace = draw.Trace(table)  # its design (L, r, φ, the strings' rest length and slack) from its metadata
    assert draw.check_geometry(trace, k=out.k) == out.k
    # A string layout other than rtw-model's (each spoke joined to the one opposite) is caught.
    _, conns = trace.points()
    wrong = np.linalg.norm(conns[[0, 1, 2, 3, 4, 5]] - conns[[3, 4, 5, 0, 1, 2]], axis=-1)
    assert not np.allclose(wrong, draw.string_lengths(trace))


def test_bad_frames_are_refused_by_name() -> None:
    with pytest.raises(ValueError, match=r"x, y, theta: 2, 3 and 3 values are invalid"):
        _rtw.star_points([0.0, 0.0], [0.0] * 3, [0.0] * 3, 1.0, 0.3)
