"""The report of a design search's folder and of the atlas (results/design):
the page carries exactly the rows of the files rtw-scan wrote, read through
rtw-scan's verified design reader, and refuses what that reader refuses.

The page's data is read back from the written file (its gzipped, base64
blob), as test_report.py does for a scan; the browser test at the end opens
the atlas's page in headless Chromium.
"""

from __future__ import annotations

import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

import pyarrow as pa
import pyarrow.parquet as pq
import pytest
from test_design_search import CONFIG
from test_report import blob
from test_same_checks import BINARY

import rtw
from rtw.report import GENERATOR, ReportError

ROOT = Path(__file__).resolve().parents[3]
ATLAS = ROOT / "results/design"


def _data(page: str) -> dict:
    return json.loads(blob(page, "data-gz"))


def _as_carried(values: list) -> list:
    """The values as the page carries them: non-finite floats become null."""
    return [None if isinstance(v, float) and not math.isfinite(v) else v for v in values]


@pytest.fixture(scope="module")
def atlas_page(tmp_path_factory):
    out = tmp_path_factory.mktemp("design-report") / "atlas.html"
    assert rtw.report(ATLAS, out=out, progress=False) == out
    page = out.read_text()
    return out, page, _data(page)


def test_the_atlas_page_carries_every_reported_design_and_profile(atlas_page) -> None:
    _, page, data = atlas_page
    assert GENERATOR in page
    files = sorted(ATLAS.glob("designs-*.parquet"))
    assert len(data["searches"]) == len(files) >= 6
    by_name = {s["name"]: s for s in data["searches"]}
    for f in files:
        table = pq.read_table(f)
        name = json.loads(pq.read_metadata(f).metadata[b"rtw.design"])["settings"]["name"]
        shown = by_name[name]["reported"]
        for col in ("rho", "alpha", "fn", "zeta", "phi_lo", "phi_hi", "speed", "checked_failures"):
            assert shown[col] == _as_carried(table.column(col).to_pylist()), (f.name, col)
        assert "evaluations" not in by_name[name], "the atlas holds no search.parquet"
    profiles = sorted(ATLAS.glob("profile-*.parquet"))
    assert sorted(p["file"] for p in data["profiles"]) == [p.name for p in profiles]
    for p in data["profiles"]:
        rows = pq.read_table(ATLAS / p["file"], columns=["phi"]).num_rows
        assert len(p["phi"]) == rows and p["phi"] == sorted(p["phi"])
    gifs = sorted(f.name for f in ATLAS.glob("*.gif"))
    assert gifs and {im["name"] for im in data["images"]} >= set(gifs)
    # Each search's reported designs appear in its table on the page.
    for s in data["searches"]:
        assert f"Search {s['name']}" in page


@pytest.fixture(scope="module")
def search_dir(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("design-search")
    cfg = tmp / "search.toml"
    cfg.write_text(CONFIG)
    out = tmp / "small"
    subprocess.run([str(BINARY), "design", str(cfg), "--out", str(out), "--quiet"], check=True, capture_output=True)
    return out


def test_a_search_folder_shows_its_evaluations_and_designs(search_dir, tmp_path) -> None:
    out = tmp_path / "search.html"
    made = subprocess.run([sys.executable, "-m", "rtw", "report", str(search_dir), "--out", str(out), "--quiet"],
                          capture_output=True, text=True)
    assert made.returncode == 0, made.stderr
    data = _data(out.read_text())
    (s,) = data["searches"]
    assert s["name"] == "small"
    ev = pq.read_table(search_dir / "search.parquet").to_pydict()
    assert s["evaluations"]["index"] == ev["index"]
    assert s["evaluations"]["feasible"] == ev["feasible"]
    assert s["evaluations"]["runs"] == ev["runs"]
    rep = pq.read_table(search_dir / "designs.parquet").to_pydict()
    assert s["reported"]["phi_lo"] == rep["phi_lo"] and s["reported"]["rho"] == rep["rho"]
    assert data["profiles"] == []
    # --quiet: nothing but the closing line on stderr.
    assert made.stderr.strip().startswith("rtw: report written to"), made.stderr


def test_an_altered_design_file_gives_no_report(search_dir, tmp_path) -> None:
    bad = tmp_path / "altered"
    shutil.copytree(search_dir, bad)
    f = bad / "designs.parquet"
    t, kv = pq.read_table(f), pq.read_metadata(f).metadata
    rho = [v * 1.01 for v in t.column("rho").to_pylist()]
    changed = t.set_column(t.schema.get_field_index("rho"), "rho", pa.array(rho))
    # With rtw-scan's metadata kept, the rows no longer match its content hash.
    pq.write_table(changed.replace_schema_metadata(kv), f)
    with pytest.raises(ReportError, match=r"designs.parquet is corrupt"):
        rtw.report(bad, out=tmp_path / "r.html", progress=False)
    # Without it, the file is not a search's: refused, not left out.
    pq.write_table(changed, f)
    with pytest.raises(ReportError, match=r"designs.parquet: not a design search's file"):
        rtw.report(bad, out=tmp_path / "r.html", progress=False)
    assert not (tmp_path / "r.html").exists()


def test_designs_of_another_search_beside_the_evaluations_are_refused(search_dir, tmp_path) -> None:
    other_cfg = tmp_path / "other.toml"
    other_cfg.write_text(CONFIG.replace("seed = 2", "seed = 5"))
    other = tmp_path / "other"
    subprocess.run([str(BINARY), "design", str(other_cfg), "--out", str(other), "--quiet"], check=True,
                   capture_output=True)
    mixed = tmp_path / "mixed"
    shutil.copytree(search_dir, mixed)
    shutil.copy(other / "designs.parquet", mixed / "designs.parquet")
    with pytest.raises(ReportError, match="other settings or options"):
        rtw.report(mixed, out=tmp_path / "r.html", progress=False)


def test_a_folder_with_neither_scan_nor_search_keeps_the_scan_error(tmp_path) -> None:
    (tmp_path / "notes.txt").write_text("nothing here")
    with pytest.raises(ReportError, match="not a scan directory"):
        rtw.report(tmp_path, out=tmp_path / "r.html", progress=False)


def test_report_progress_counts_the_gaits_to_a_callable(tmp_path) -> None:
    calls: list[tuple[int, int]] = []
    rtw.report(ROOT / "results/paper", out=tmp_path / "p.html", per_outcome=1,
               progress=lambda done, total: calls.append((done, total)))
    assert calls and calls[-1][0] == calls[-1][1] > 0
    assert [d for d, _ in calls] == sorted(d for d, _ in calls)
    with pytest.raises(ValueError, match="progress: 'yes' is invalid"):
        rtw.report(ROOT / "results/paper", out=tmp_path / "q.html", progress="yes")


CHROMIUM = shutil.which("chromium")
DRIVER = shutil.which("chromedriver")


@pytest.mark.skipif(CHROMIUM is None or DRIVER is None, reason="needs chromium and chromium-driver "
                    "(scripts/test.sh installs them as root)")
def test_the_atlas_page_draws_in_chromium_without_errors(atlas_page) -> None:
    from test_report_browser import no_console_errors, timing

    out, _, data = atlas_page
    t = timing()
    driver = t.open_chromium()
    try:
        driver.get(out.as_uri())
        t.wait_ready(driver)
        no_console_errors(driver)
        assert driver.execute_script("return document.getElementById('status').textContent") == ""
        # One trace per search with reported designs on each atlas plot.
        n = driver.execute_script("return document.getElementById('atlas-speed').data.length")
        assert n == sum(1 for s in data["searches"] if s.get("reported"))
        shown = driver.execute_script("return document.querySelectorAll('#images img').length")
        assert shown == len(data["images"])
    finally:
        driver.quit()


@pytest.mark.skipif(CHROMIUM is None or DRIVER is None, reason="needs chromium and chromium-driver "
                    "(scripts/test.sh installs them as root)")
def test_a_search_without_speed_phi_draws_no_speed_chart_and_says_why(search_dir, tmp_path) -> None:
    """A search whose config has no speed_phi measured no speed: the page
    must not draw an empty "speed at φ = ?" chart, and says what to set."""
    from test_report_browser import no_console_errors, timing

    out = tmp_path / "search.html"
    assert rtw.report(search_dir, out=out, progress=False) == out
    assert all(s["settings"].get("speed_phi") is None for s in _data(out.read_text())["searches"])
    t = timing()
    driver = t.open_chromium()
    try:
        driver.get(out.as_uri())
        t.wait_ready(driver)
        no_console_errors(driver)
        drawn = driver.execute_script("const el = document.getElementById('atlas-speed'); return !!(el && el.data)")
        assert not drawn, "a speed chart was drawn for a search that measured no speed"
        note = driver.execute_script("return document.getElementById('atlas-speed-note').textContent")
        assert "speed_phi" in note
    finally:
        driver.quit()
