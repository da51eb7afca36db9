"""The five-line example of docs/python.md and of the README runs and prints what it says."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]


@pytest.mark.parametrize("page", ["docs/python.md", "README.md"])
def test_the_python_page_example_runs(
    page: str, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """The five-line example (the first Python block that imports rtw)."""
    pytest.importorskip("polars")
    text = (ROOT / page).read_text()
    example = next((m for m in re.finditer(r"```python\n(.*?)```", text, re.S) if "import rtw" in m.group(1)), None)
    assert example is not None
    code = example.group(1)
    assert len(code.strip().splitlines()) == 5
    monkeypatch.chdir(ROOT)
    exec(compile(code, page, "exec"), {})
    out = capsys.readouterr().out
    assert out.startswith("walk 1.72"), out
    # The outcome counts of the smoke scan: 6 rows.
    counts = [int(n) for n in re.findall(r"│ \w+\s+┆ (\d+)\s+│", out)]
    assert sum(counts) == 6, out
