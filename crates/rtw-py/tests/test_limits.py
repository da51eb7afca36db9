"""Large requests from Python raise (ValueError, MemoryError); they never abort the interpreter.

Each call runs in a child interpreter, so an abort (SIGABRT, exit 134 from a
failed allocation) is seen as such instead of killing the test run.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
FIG7A = "length=0.8, rho=2.5, alpha=0.125, fn=3.269, zeta=0.0514, phi=0.15"
BIG_SCAN = """
seed = 1
samples = {n}
[params]
length = 0.8
rho = 2.5
alpha = 0.125
fn = 3.269
zeta = 0.0514
phi = 0.15
"""


def outcome_of(call: str) -> tuple[str, str]:
    """(the exception's type name or "ok", its message) of `call` in a child interpreter."""
    script = textwrap.dedent(
        f"""
        import rtw
        try:
            {call}
            print("ok")
        except Exception as e:
            print(type(e).__name__)
            print(e)
        """
    )
    p = subprocess.run(
        [sys.executable, "-c", script], cwd=ROOT, capture_output=True, text=True, timeout=120
    )
    assert p.returncode == 0, f"{call}: the interpreter died ({p.returncode}): {p.stderr[-2000:]}"
    kind, _, message = p.stdout.partition("\n")
    return kind, message


@pytest.mark.parametrize("n", [10**8, 10**12, 1_000_001])
def test_scan_beyond_memory_raises_naming_the_cli(n: int) -> None:
    kind, message = outcome_of(f"rtw.scan({BIG_SCAN.format(n=n)!r}, progress=False)")
    assert kind in ("ValueError", "MemoryError"), message
    assert f"{n} rows" in message and "rtw-scan run" in message, message


@pytest.mark.parametrize(
    "limit", ['"100TB"', '"10TB"', "10**15", '"1e18"']
)
def test_trace_beyond_memory_raises(limit: str) -> None:
    kind, message = outcome_of(f"rtw.trace({FIG7A}, dt=1e-9, limit={limit})")
    assert kind in ("ValueError", "MemoryError"), message
    assert "limit" in message, message


def test_trace_within_memory_but_beyond_its_limit_raises() -> None:
    # 2·10^10 samples of 196 bytes: far above the 2 GB default limit.
    kind, message = outcome_of(f"rtw.trace({FIG7A}, dt=1e-9)")
    assert kind == "ValueError", message
    assert "raise dt" in message or "dt" in message, message


def test_keyword_errors_name_the_key_and_range_with_numbers_as_written() -> None:
    import rtw

    fig7a = dict(length=0.8, rho=2.5, alpha=0.125, fn=3.269, zeta=0.0514, phi=0.15)
    for kwargs, needles in [
        ({"length": 1e300}, ["length: 1e300 is invalid: must be in"]),
        ({"phi": -1e-300}, []),
        ({"t_max": -1e300}, ["t_max: -1e300 is invalid: must be finite and > 0"]),
        ({"t_max": "fast"}, ["t_max", '"fast"', "must be finite and > 0"]),
        ({"trace_dt": 1e-300, "t_max": 0.5}, []),
    ]:
        args = {**fig7a, **kwargs}
        if not needles:
            rtw.simulate(**args)
            continue
        with pytest.raises(ValueError) as e:
            rtw.simulate(**args)
        for n in needles:
            assert n in str(e.value), str(e.value)
        assert "00000000" not in str(e.value), str(e.value)
    # Python's own names, not the command line's.
    with pytest.raises(ValueError) as e:
        rtw.scan(ROOT / "configs" / "smoke.toml", threads=10**6, progress=False)
    assert str(e.value).startswith("threads: 1000000 is invalid: must be an integer in [1, "), str(e.value)
    with pytest.raises(ValueError, match="progress: 'yes' is invalid"):
        rtw.scan(ROOT / "configs" / "smoke.toml", progress="yes")  # type: ignore[arg-type]
