"""The five-line example at the top of docs/python.md runs and prints what it says."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]


def test_the_python_page_example_runs(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("polars")
    page = (ROOT / "docs" / "python.md").read_text()
    example = re.search(r"```python\n(.*?)```", page, re.S)
    assert example is not None
    code = example.group(1)
    assert len(code.strip().splitlines()) == 5
    monkeypatch.chdir(ROOT)
    exec(compile(code, "docs/python.md", "exec"), {})
    out = capsys.readouterr().out
    assert out.startswith("walk 1.78"), out
    # The outcome counts of the smoke scan: 6 rows.
    counts = [int(n) for n in re.findall(r"│ \w+\s+┆ (\d+)\s+│", out)]
    assert sum(counts) == 6, out
