"""An unbounded MFPT (no fall counted: the interval open above) is not a
missing one: ``rtw.simulate`` gives ``inf`` for it, as the scan files do, and
``None`` only for an MFPT that was not computed (docs/data-dictionary.md)."""

from __future__ import annotations

import math

import rtw

FIG7A = (0.8, 2.5, 0.125, 3.269, 0.0514, 0.15)
SOFT = (0.8, 2.5, 0.125, 0.5, 0.0514, 0.15)
# Fig. 7(a)'s walk counts no fall in its batches on a slope of σ = 2 mm.
MFPT = {"robustness.mfpt": True, "robustness.sigma": 0.002}


def test_an_unbounded_mfpt_is_inf_and_a_missing_one_none() -> None:
    out = rtw.simulate(*FIG7A, options=MFPT)
    assert out.outcome == "walk"
    assert out.fall_rate == 0.0
    assert math.isinf(out.mfpt) and math.isinf(out.mfpt_hi), out.to_dict()
    assert math.isfinite(out.mfpt_lo)
    assert math.isinf(out.to_dict()["mfpt_hi"])
    none = rtw.simulate(*SOFT, options=MFPT)
    assert none.mfpt is None and none.mfpt_hi is None, none.to_dict()
