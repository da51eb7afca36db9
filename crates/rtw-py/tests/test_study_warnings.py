"""A study's warnings reach Python as the command prints them, even with no
progress shown: a profile or a design search whose cost passes the library's
bounds (hours of computing) warns with ``UserWarning`` at its start, in the
words of ``rtw-scan profile`` and ``rtw-scan design``, and its notes (what it
will cost) go to the ``rtw`` logger."""

from __future__ import annotations

import logging
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

import rtw

if TYPE_CHECKING:
    from conftest import Press

DESIGN = dict(length=0.8, rho=2.5, alpha=0.125, fn=3.269, zeta=0.0514)
# Its most batches on 26 slopes: about 2e8 walker-steps, past the 1e8 bound.
COSTLY = {"robustness.mfpt": True, "robustness.sigma": 0.05, "robustness.mfpt_batches": 3000}


def test_a_costly_profile_warns_at_its_start(ctrl_c: Press, caplog: pytest.LogCaptureFixture) -> None:
    caplog.set_level(logging.INFO, logger="rtw")
    with pytest.warns(UserWarning, match=r"the profile will cost about .*walker-steps of the MFPT"):
        ctrl_c(1.5, lambda: rtw.profile(**DESIGN, phi_from=0.05, phi_to=0.3, options=COSTLY))
    assert any("walker-steps" in r.getMessage() for r in caplog.records if r.name == "rtw"), caplog.records


def test_a_costly_design_search_warns_at_its_start(ctrl_c: Press, tmp_path: Path) -> None:
    cfg = tmp_path / "big.toml"
    cfg.write_text(
        'name = "big"\nseed = 1\nbudget = 5000000\nbatch = 4\nobjectives = ["slope_range"]\n'
        "[box]\nrho = [1.0, 5.0]\nalpha = [0.0, 0.4]\nfn = [1.5, 5.0]\nzeta = [0.05, 0.1]\n"
        "[slopes]\nfrom = 0.05\nto = 0.3\ngrid = 0.05\ntol = 0.01\n"
    )
    with pytest.warns(UserWarning, match=r"will cost about .*simulations \(more than 1000000\)"):
        ctrl_c(1.5, lambda: rtw.design(cfg, progress=False))
