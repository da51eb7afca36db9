"""rtw.design is `rtw-scan design`: the same library entry point, the same
evaluations and reported designs, the same refusals in the same words."""

from __future__ import annotations

import subprocess

import pyarrow.parquet as pq
import pytest
from test_same_checks import BINARY, cli_error, python_error

import rtw

CONFIG = """name = "small"
seed = 2
budget = 300
batch = 4
objectives = ["slope_range"]
report = 2
[box]
rho = [1.0, 5.0]
alpha = [0.0, 0.4]
fn = [1.5, 5.0]
zeta = [0.05, 0.1]
[slopes]
from = 0.05
to = 0.3
grid = 0.05
tol = 0.01
verify_grid = 0.025
"""


def _config(tmp_path, text: str = CONFIG) -> str:
    path = tmp_path / "search.toml"
    path.write_text(text)
    return str(path)


def _rows(table) -> list[dict]:
    return table.to_pylist()


def test_design_equals_the_cli_search_in_memory_and_in_a_folder(tmp_path) -> None:
    cfg = _config(tmp_path)
    cli = tmp_path / "cli"
    subprocess.run([str(BINARY), "design", cfg, "--out", str(cli), "--quiet"], check=True, capture_output=True)
    calls: list[tuple[int, int]] = []
    d = rtw.design(cfg, progress=lambda done, total: calls.append((done, total)))
    assert isinstance(d, rtw.DesignSearch)
    assert _rows(d.evaluations) == _rows(pq.read_table(cli / "search.parquet"))
    assert _rows(d.designs) == _rows(pq.read_table(cli / "designs.parquet"))
    assert _rows(d.archive) == _rows(pq.read_table(cli / "archive.parquet"))
    assert d.summary == (cli / "search.md").read_text()
    assert d.runs == sum(d.evaluations.column("runs").to_pylist()) >= 300
    assert calls, "no progress reported"
    # Into a folder: the files the CLI writes, the same bytes of rows.
    py = tmp_path / "py"
    d2 = rtw.design(cfg, out=py, progress=False)
    assert _rows(pq.read_table(py / "search.parquet")) == _rows(pq.read_table(cli / "search.parquet"))
    assert d2.summary == d.summary


def test_design_refuses_what_the_cli_refuses_in_its_words(tmp_path) -> None:
    bad = _config(tmp_path, CONFIG.replace("budget = 300", "budget = 0"))
    cli = cli_error("design", bad, "--quiet")
    py = python_error(lambda: rtw.design(bad, progress=False))
    assert "budget: 0 is invalid: must be an integer in [1, 10000000]" in cli
    assert py == cli
    cfg = _config(tmp_path)
    out = tmp_path / "out"
    rtw.design(cfg, out=out, progress=False)
    other = tmp_path / "other.toml"
    other.write_text(CONFIG.replace("seed = 2", "seed = 3"))
    with pytest.raises(ValueError, match="holds the search \"small\" of other settings"):
        rtw.design(other, out=out, progress=False)
    with pytest.raises(ValueError, match="threads: 0 is invalid"):
        rtw.design(cfg, threads=0, progress=False)


def test_the_committed_atlas_designs_fail_inside_their_intervals_no_more_often_than_their_check_found() -> None:
    # results/design/designs-*.parquet (scripts/design_atlas.sh). The library
    # checked each reported interval by direct simulation (search::check) and
    # found isolated failing slopes at a small rate (`checked_failures` of
    # `checked_slopes`; for an interval checked for one gait, `gait`, a
    # slope in another gait fails): a failing window can be narrower than 1e-6 rad
    # (docs/design.md), so no finite check makes an interval stable at every
    # φ. Seven more slopes per design, drawn from a fixed seed between the
    # check's own, must fail no more often than that rate allows: a binomial
    # tail probability above 1e-3 (scipy.stats.binom).
    import random
    from pathlib import Path

    from scipy.stats import binom

    files = sorted((Path(__file__).resolve().parents[3] / "results/design").glob("designs-*.parquet"))
    assert len(files) >= 5, files
    rng = random.Random(41)
    tries = fails = checked = checked_fails = 0
    for path in files:
        for r in pq.read_table(path).to_pylist():
            assert r["phi_hi"] >= r["phi_lo"] and r["checked_slopes"] > 200
            checked += r["checked_slopes"]
            checked_fails += r["checked_failures"]
            for _ in range(7):
                phi = rng.uniform(r["phi_lo"], r["phi_hi"])
                out = rtw.simulate(length=r["length"], rho=r["rho"], alpha=r["alpha"], fn=r["fn"], zeta=r["zeta"],
                                   phi=phi)
                tries += 1
                # An interval checked for one gait holds only that gait.
                fails += out.outcome not in rtw.STABLE_LABELS or r["gait"] not in ("any", out.outcome)
    rate = max(checked_fails, 1) / checked
    assert binom.sf(fails - 1, tries, rate) > 1e-3, (fails, tries, checked_fails, checked)


def test_design_takes_the_configs_simulation_table_as_the_cli_does(tmp_path) -> None:
    # The model of a search is in its config's [simulation] table, for both faces.
    cfg = _config(tmp_path, CONFIG + "[simulation.contact]\nmu = 0.3\n")
    cli = tmp_path / "cli"
    subprocess.run([str(BINARY), "design", cfg, "--out", str(cli), "--quiet"], check=True, capture_output=True)
    d = rtw.design(cfg, progress=False)
    assert _rows(d.evaluations) == _rows(pq.read_table(cli / "search.parquet"))
    assert b"mu=0.3" in pq.read_metadata(cli / "search.parquet").metadata[b"rtw.variant"]
    (tmp_path / "plain").mkdir()
    plain = rtw.design(_config(tmp_path / "plain"), progress=False)
    assert _rows(plain.evaluations) != _rows(d.evaluations), "mu = 0.3 changed no design's profile"
