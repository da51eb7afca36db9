"""rtw.sensitivity against SALib on the same rows: Saltelli scans and given data."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pyarrow.parquet as pq
import pytest

import rtw

salib_sobol = pytest.importorskip("SALib.analyze.sobol")
salib_delta = pytest.importorskip("SALib.analyze.delta")

ROOT = Path(__file__).resolve().parents[3]
NAMES = ["rho", "alpha", "fn", "zeta", "phi"]
BOUNDS = [[1.0, 5.0], [0.0, 0.4], [1.5, 5.0], [0.05, 0.1], [0.05, 0.3]]
PROBLEM = {"num_vars": 5, "names": NAMES, "bounds": BOUNDS}
LABELS = ["skip", "walk", "crawl", "collapse", "stall", "diverged"]


def _config(sampling: str, n: int) -> str:
    axes = "\n".join(f"{k} = {{ uniform = [{lo}, {hi}] }}" for k, (lo, hi) in zip(NAMES, BOUNDS))
    return (
        f'seed = 5\nsamples = {n}\nsampling = "{sampling}"\n[params]\nlength = 0.8\n{axes}\n'
        "[simulation]\nt_max = 3.0\n"
    )


def _outputs(table) -> dict[str, np.ndarray]:
    """The outputs rtw analyses, computed here from the rows: labels as 0/1 indicators, failure, speed."""
    outcome = np.asarray(table.column("outcome").to_pylist())
    out = {label: (outcome == label).astype(float) for label in LABELS}
    out["failure"] = np.isin(outcome, ["collapse", "stall", "diverged"]).astype(float)
    out["speed"] = np.asarray(table.column("speed"), dtype=float)
    return out


def _index(indices, output: str, column: str) -> np.ndarray:
    d = indices.to_pydict()
    return np.array([d[column][i] for i, o in enumerate(d["output"]) if o == output])


def _check_saltelli(table, indices) -> None:
    assert np.array_equal(np.asarray(table.column("sample_id")), np.arange(table.num_rows))
    for output, y in _outputs(table).items():
        si = salib_sobol.analyze(PROBLEM, y, calc_second_order=False, num_resamples=1000, seed=3)
        for ours, theirs in (("S1", "S1"), ("ST", "ST")):
            np.testing.assert_allclose(_index(indices, output, ours), si[theirs], rtol=1e-9, atol=1e-12)
        if y.std() > 0:
            # Different bootstrap draws: the half-widths agree to their own sampling error.
            for conf in ("S1_conf", "ST_conf"):
                ours, theirs = _index(indices, output, conf), np.asarray(si[conf])
                # An input without any effect on the output (AB = A row for row) has 0 both ways.
                zero = theirs == 0
                assert np.all(ours[zero] == 0), (output, conf, ours, theirs)
                ratio = ours[~zero] / theirs[~zero]
                assert np.all((ratio > 0.75) & (ratio < 1.33)), (output, conf, ratio)
    # Complements: the same indices (to rounding of the standardisation).
    np.testing.assert_allclose(_index(indices, "stable", "ST"), _index(indices, "failure", "ST"), atol=1e-12)


def test_salib_reads_an_in_memory_saltelli_scan_like_rtw() -> None:
    """SALib's sobol.analyze on the rows of rtw.scan gives rtw.sensitivity's S1 and ST."""
    table = rtw.scan(_config("saltelli", 128), progress=False)
    assert table.num_rows == 128 * 7
    indices = rtw.sensitivity(table, resamples=1000)
    assert indices.column_names == ["output", "parameter", "S1", "S1_conf", "ST", "ST_conf"]
    assert set(indices.column("output").to_pylist()) >= {*LABELS, "stable", "failure", "speed", "f_w"}
    _check_saltelli(table, indices)


def test_salib_reads_the_committed_saltelli_scan_file() -> None:
    """results/sensitivity/saltelli/samples.parquet, read by SALib as it is, gives the committed indices."""
    scan = ROOT / "results/sensitivity/saltelli/samples.parquet"
    table = pq.read_table(scan)
    committed = pq.read_table(ROOT / "results/sensitivity/indices.parquet")
    for output, y in _outputs(table).items():
        si = salib_sobol.analyze(PROBLEM, y, calc_second_order=False, seed=3)
        np.testing.assert_allclose(_index(committed, output, "S1"), si["S1"], rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose(_index(committed, output, "ST"), si["ST"], rtol=1e-9, atol=1e-12)
    # The paper's claims, as committed: the indices of failure and of every gait to within ± 0.05
    # (crawl, 2.1 % of the runs, is why the scan has 32768 base rows: docs/reproduction.md).
    for output in ["failure", "stable", "skip", "walk", "crawl", "collapse", "stall"]:
        assert np.all(_index(committed, output, "S1_conf") <= 0.05), output
        assert np.all(_index(committed, output, "ST_conf") <= 0.05), output
    # And rtw.sensitivity on the file reproduces the committed indices exactly.
    again = rtw.sensitivity(scan)
    assert again.select(["output", "parameter", "S1", "ST", "S1_conf", "ST_conf"]).equals(
        committed.select(["output", "parameter", "S1", "ST", "S1_conf", "ST_conf"])
    )


def test_given_data_indices_of_a_random_scan_are_salibs_binned_first_order() -> None:
    """On a scan that is not a Saltelli design, S1 is SALib delta's sobol_first on the same rows; ST is NaN."""
    n = 600
    table = rtw.scan(_config("random", n), progress=False)
    indices = rtw.sensitivity(table, resamples=200)
    exp = 2.0 / (7.0 + np.tanh((1500.0 - n) / 500.0))
    m = np.linspace(0, n, int(np.round(min(int(np.ceil(n**exp)), 48))) + 1)
    x = np.column_stack([np.asarray(table.column(k)) for k in NAMES])
    for output, y in _outputs(table).items():
        theirs = [salib_delta.sobol_first(y, x[:, i], m) for i in range(5)]
        np.testing.assert_allclose(_index(indices, output, "S1"), theirs, rtol=1e-9, atol=1e-12)
        assert np.isnan(_index(indices, output, "ST")).all()
        assert (_index(indices, output, "S1_conf") >= 0).all()


def test_bad_tables_and_arguments_raise() -> None:
    import pyarrow as pa

    with pytest.raises(ValueError, match="no `rtw.config`"):
        rtw.sensitivity(pa.table({"x": [1.0]}))
    with pytest.raises(ValueError, match="resamples: 1 is invalid"):
        rtw.sensitivity(pa.table({"x": [1.0]}), resamples=1)


def test_wide_half_widths_warn_in_python_as_on_the_cli(tmp_path) -> None:
    # configs/sensitivity-saltelli-small.toml: 256 base rows, whose rare
    # classes' half-widths are far above 0.1. The library makes the warning;
    # the CLI prints it, Python raises it as a UserWarning, word for word.
    import subprocess

    from test_same_checks import BINARY

    root = Path(__file__).resolve().parents[3]
    scan = tmp_path / "small"
    subprocess.run([str(BINARY), "run", str(root / "configs/sensitivity-saltelli-small.toml"), "--out", str(scan),
                    "--quiet"], check=True, capture_output=True)
    cli = subprocess.run([str(BINARY), "sensitivity", str(scan), "--quiet", "--out", str(tmp_path / "i.parquet")],
                         check=True, capture_output=True, text=True)
    line = next(l for l in cli.stderr.splitlines() if l.startswith("warning: "))
    with pytest.warns(UserWarning) as caught:
        rtw.sensitivity(str(scan), progress=False)
    messages = [str(w.message) for w in caught]
    assert line.removeprefix("warning: ") in messages, (line, messages)
    assert "half-widths are above 0.1" in line
