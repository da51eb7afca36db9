"""`rtw.scan` shows its progress as Python users expect, and is quiet with `progress=False`.

A terminal gets a bar redrawn in place on stderr (tqdm's look), a notebook
one line updated in place, a log (stderr not a terminal) plain lines; a
callable gets (done, total).
"""

from __future__ import annotations

import io
import os
import pty
import select
import subprocess
import sys
from pathlib import Path

import rtw

ROOT = Path(__file__).resolve().parents[3]
SMOKE = ROOT / "configs" / "smoke.toml"


def stderr_on_a_terminal(call: str) -> str:
    """What `call` writes to stderr when stderr is a terminal (a pseudo-terminal)."""
    main, child = pty.openpty()
    p = subprocess.Popen(
        [sys.executable, "-c", f"import rtw; {call}"],
        cwd=ROOT,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=child,
    )
    os.close(child)
    out = b""
    while True:
        ready, _, _ = select.select([main], [], [], 120)
        if not ready:
            break
        try:
            chunk = os.read(main, 4096)
        except OSError:  # the child closed the terminal
            break
        if not chunk:
            break
        out += chunk
    os.close(main)
    assert p.wait(timeout=120) == 0
    return out.decode()


def test_a_terminal_shows_a_bar_by_default() -> None:
    err = stderr_on_a_terminal(f"rtw.scan({str(SMOKE)!r})")
    assert "\r" in err, repr(err)
    last = err.rstrip().split("\r")[-1]
    assert "100%" in last and "6/6" in last and "samples/s" in last, repr(err)
    assert err.endswith("\n"), repr(err)  # the finished bar stays, the prompt goes below


def test_progress_false_is_quiet_on_a_terminal() -> None:
    assert stderr_on_a_terminal(f"rtw.scan({str(SMOKE)!r}, progress=False)") == ""


def test_a_log_gets_plain_lines_and_progress_false_nothing() -> None:
    for progress, expect_lines in [("True", True), ("False", False)]:
        p = subprocess.run(
            [sys.executable, "-c", f"import rtw; rtw.scan({str(SMOKE)!r}, progress={progress})"],
            cwd=ROOT,
            capture_output=True,
            text=True,
            timeout=120,
            check=True,
        )
        if expect_lines:
            assert "\r" not in p.stderr, repr(p.stderr)
            assert p.stderr.splitlines()[-1].startswith("rtw.scan: 6/6 (100%)"), p.stderr
        else:
            assert p.stderr == "", p.stderr


class _Notebook(io.StringIO):
    """Stands for a notebook's stderr (ipykernel's OutStream): not a terminal, draws `\\r`."""


_Notebook.__module__ = "ipykernel.iostream"


def test_a_notebook_gets_one_line_updated_in_place(monkeypatch) -> None:
    out = _Notebook()
    monkeypatch.setattr(sys, "stderr", out)
    rtw.scan(SMOKE)
    text = out.getvalue()
    assert text.startswith("\r") and text.count("\n") == 1 and text.endswith("\n"), repr(text)
    assert "6/6" in text.split("\r")[-1], repr(text)


def test_a_callable_gets_done_and_total() -> None:
    seen: list[tuple[int, int]] = []
    rtw.scan(SMOKE, progress=lambda done, total: seen.append((done, total)))
    assert seen and seen[-1] == (6, 6), seen
    assert all(t == 6 and 0 <= d <= 6 for d, t in seen), seen
    assert [d for d, _ in seen] == sorted(d for d, _ in seen), seen


FIG7A = (0.8, 2.5, 0.125, 3.269, 0.0514, 0.15)


def test_basin_and_sensitivity_report_their_progress_to_a_callable() -> None:
    """The studies that can take minutes count their units as a scan counts rows:
    a basin slice its grid points, a sensitivity analysis its bootstrap
    resamples (one per output, input and resample for the binned index)."""
    seen: list[tuple[int, int]] = []
    rtw.basin(*FIG7A, x="omega_a:-10:10:3", y="theta_b:-0.2:0.2:2", steps=4, threads=1, progress=lambda d, t: seen.append((d, t)))
    assert seen and seen[-1] == (6, 6), seen
    assert all(t == 6 and 0 <= d <= 6 for d, t in seen), seen
    table = rtw.scan(str(SMOKE), progress=False)
    seen.clear()
    indices = rtw.sensitivity(table, resamples=7, progress=lambda d, t: seen.append((d, t)))
    outputs = len(set(indices.column("output").to_pylist()))
    inputs = len(set(indices.column("parameter").to_pylist()))
    assert seen[-1] == (outputs * inputs * 7,) * 2, (seen[-1], outputs, inputs)


def test_a_study_in_a_log_gets_plain_lines_naming_it() -> None:
    err = io.StringIO()
    sys_err, sys.stderr = sys.stderr, err
    try:
        rtw.basin(*FIG7A, x="omega_a:-10:10:3", y="theta_b:-0.2:0.2:2", steps=4, threads=1)
        rtw.basin(*FIG7A, x="omega_a:-10:10:3", y="theta_b:-0.2:0.2:2", steps=4, threads=1, progress=False)
    finally:
        sys.stderr = sys_err
    lines = err.getvalue().splitlines()
    assert lines and all(l.startswith("rtw.basin: ") for l in lines), lines
    assert "6/6 (100%)" in lines[-1] and "points/s" in lines[-1], lines
