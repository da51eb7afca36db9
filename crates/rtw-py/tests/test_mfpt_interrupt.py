"""Ctrl-C stops the MFPT (docs/robustness.md, "Mean first-passage time"),
whose batches are thousands of one-step runs, within seconds, as it stops
every other measure: from ``rtw.simulate`` and from ``rtw.scan``."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import rtw

if TYPE_CHECKING:
    from conftest import Press

FIG7A = (0.8, 2.5, 0.125, 3.269, 0.0514, 0.15)
# Its most batches: minutes of runs at σ = 5 cm.
MFPT = {"robustness.mfpt": True, "robustness.sigma": 0.05, "robustness.mfpt_batches": 3000}
# Past the flat run (well under a second): inside the MFPT's batches.
PRESS_AFTER = 2.0
# 2 s promised; 5 s allowed on a loaded machine.
LIMIT = 5.0


def test_simulate_with_the_mfpt_stops_at_ctrl_c(ctrl_c: Press) -> None:
    took = ctrl_c(PRESS_AFTER, lambda: rtw.simulate(*FIG7A, options=MFPT)) - PRESS_AFTER
    print(f"rtw.simulate: Ctrl-C to KeyboardInterrupt {took:.3f} s")
    assert took < LIMIT, took
    # Python stays usable, the flag of the stopped run gone.
    assert rtw.simulate(*FIG7A).outcome == "walk"


def test_scan_with_the_mfpt_stops_at_ctrl_c(ctrl_c: Press, tmp_path: Path) -> None:
    cfg = tmp_path / "c.toml"
    cfg.write_text(
        "seed = 1\nsamples = 1\n[params]\nlength = 0.8\nrho = 2.5\nalpha = 0.125\n"
        "fn = 3.269\nzeta = 0.0514\nphi = 0.15\n[simulation]\n"
        + "".join(f"{k} = {str(v).lower()}\n" for k, v in MFPT.items())
    )
    took = ctrl_c(PRESS_AFTER, lambda: rtw.scan(cfg)) - PRESS_AFTER
    print(f"rtw.scan: Ctrl-C to KeyboardInterrupt {took:.3f} s")
    assert took < LIMIT, took
