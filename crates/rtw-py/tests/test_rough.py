"""The rough slope and the Monte Carlo steps to fall from Python: the same
keys, values and errors as `rtw-scan simulate --set` (docs/robustness-rough.md)."""

from __future__ import annotations

import pytest

import rtw

FIG7A = (0.8, 2.5, 0.125, 3.269, 0.0514, 0.15)
MC = {"robustness.steps_to_fall": True, "robustness.trials": 4, "robustness.max_steps": 30}


def test_steps_to_fall_only_when_asked_for_and_censored_on_the_flat_slope() -> None:
    assert "steps_to_fall" not in rtw.simulate(*FIG7A).to_dict()
    out = rtw.simulate(*FIG7A, options=MC)
    assert out.steps_to_fall_lo <= out.steps_to_fall <= out.steps_to_fall_hi
    assert out.steps_to_fall == rtw.simulate(*FIG7A, options=MC).steps_to_fall
    flat = rtw.simulate(*FIG7A, options={**MC, "robustness.sigma": 0.0})
    assert (flat.steps_to_fall, flat.steps_to_fall_censored) == (30.0, 4.0)


def test_a_bad_roughness_raises_naming_the_key() -> None:
    with pytest.raises(ValueError, match=r"terrain\.roughness: -1 is invalid"):
        rtw.simulate(*FIG7A, options={"terrain.roughness": -1})
    with pytest.raises(ValueError, match=r"robustness\.trials: 1 is invalid"):
        rtw.simulate(*FIG7A, options={"robustness.trials": 1})
    with pytest.raises(ValueError, match=r"robustness\.mfpt_batches: 3001 is invalid: must be in \[2, 3000\]"):
        rtw.simulate(*FIG7A, options={"robustness.mfpt": True, "robustness.mfpt_batches": 3001})
