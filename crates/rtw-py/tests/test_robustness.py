"""The terrain and robustness options from Python: the same keys, values and
errors as `rtw-scan simulate --set` (docs/robustness.md)."""

from __future__ import annotations

import pytest

import rtw

FIG7A = (0.8, 2.5, 0.125, 3.269, 0.0514, 0.15)


def test_step_down_max_only_when_asked_for() -> None:
    flat = rtw.simulate(*FIG7A)
    assert "step_down_max" not in flat.to_dict()
    out = rtw.simulate(*FIG7A, options={"robustness.step_down": True})
    assert out.step_down_max is not None and out.step_down_max > 0.0
    # Asking for it changes nothing else in the row.
    for key, value in flat.to_dict().items():
        if key != "wall_time_s":
            assert out.to_dict()[key] == value, key


def test_a_bad_step_raises_naming_the_key() -> None:
    with pytest.raises(ValueError, match=r"terrain\.step_height: -1 is invalid"):
        rtw.simulate(*FIG7A, options={"terrain.step_height": -1})
    step = rtw.simulate(*FIG7A, options={"terrain.step_height": 0.05, "terrain.step_at": 3.0})
    assert step.t_end != rtw.simulate(*FIG7A).t_end


def test_a_point_of_the_survival_curve_and_its_errors() -> None:
    # The same keys and values as `rtw-scan simulate --set
    # robustness.step_down_at=H --json`, and its error naming the key.
    keys = ["step_down_survival", "step_down_collapse", "step_down_stall", "step_down_other_gait",
            "step_down_diverged"]
    assert not set(keys) & set(rtw.simulate(*FIG7A).to_dict())
    out = rtw.simulate(*FIG7A, options={"robustness.step_down_at": 3.0}).to_dict()
    shares = [out[k] for k in keys]
    assert sum(shares) == pytest.approx(1.0, abs=1e-12)
    assert all(round(20 * s) == 20 * s for s in shares)
    assert out["step_down_survival"] < 1.0
    with pytest.raises(ValueError, match=r"robustness\.step_down_at: -1 is invalid: must be in \[0, 1000\]"):
        rtw.simulate(*FIG7A, options={"robustness.step_down_at": -1})


SMALL_SCAN = """seed = 3
samples = 6
[params]
length = 0.8
rho = { uniform = [1, 5] }
alpha = { uniform = [0, 0.4] }
fn = { uniform = [1.5, 5] }
zeta = { uniform = [0.05, 0.1] }
phi = { uniform = [0.05, 0.3] }
"""


def test_a_scan_has_the_step_down_column_only_when_asked_for() -> None:
    plain = rtw.scan(SMALL_SCAN, progress=False)
    assert "step_down_max" not in plain.column_names
    step = rtw.scan(SMALL_SCAN, options={"robustness.step_down": True}, progress=False)
    assert step.column_names == plain.column_names + ["step_down_max"]
    stable = {"skip", "walk", "crawl"}
    for label, h in zip(step.column("outcome").to_pylist(), step.column("step_down_max").to_pylist()):
        assert (h is not None) == (label in stable), (label, h)


def test_gsn_only_when_asked_for() -> None:
    # The gait sensitivity norm (docs/robustness-gsn.md): the same key and value
    # as `rtw-scan simulate --set robustness.gsn=true --json`.
    flat = rtw.simulate(*FIG7A)
    assert "gsn" not in flat.to_dict()
    out = rtw.simulate(*FIG7A, options={"robustness.gsn": True})
    assert out.gsn == pytest.approx(4.6349, abs=1e-3)
    assert "step_down_max" not in out.to_dict()
    for key, value in flat.to_dict().items():
        if key != "wall_time_s":
            assert out.to_dict()[key] == value, key
    with pytest.raises(ValueError, match=r"robustness\.gsn"):
        rtw.simulate(*FIG7A, options={"robustness.gsn": 2})


def test_a_scan_has_the_gsn_column_only_when_asked_for() -> None:
    plain = rtw.scan(SMALL_SCAN, progress=False)
    both = rtw.scan(SMALL_SCAN, options={"robustness.step_down": True, "robustness.gsn": True}, progress=False)
    assert both.column_names == plain.column_names + ["step_down_max", "gsn"]
    stable = {"skip", "walk", "crawl"}
    for label, g in zip(both.column("outcome").to_pylist(), both.column("gsn").to_pylist()):
        assert label in stable or g is None, (label, g)
