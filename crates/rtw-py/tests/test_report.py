"""rtw.report / `python -m rtw report`: what the page carries, and what it refuses.

The page's data is read back from the written file (its gzipped, base64 blob),
so these tests check what a browser gets; test_report_browser.py checks what
it shows.
"""

from __future__ import annotations

import base64
import gzip
import json
import math
import os
import re
import subprocess
import sys
from collections import Counter
from pathlib import Path

import pyarrow.parquet as pq
import pytest

import rtw
from rtw.report import GENERATOR

ROOT = Path(__file__).resolve().parents[3]
SCAN = ROOT / "results/paper"
# The module (rtw.report, the attribute, is its function).
report_module = sys.modules["rtw.report"]
BINARY = Path(os.environ.get("RTW_SCAN", Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "release/rtw-scan"))


def blob(page: str, name: str) -> str:
    b64 = re.search(rf'<script type="application/octet-stream" id="{name}">([^<]*)</script>', page).group(1)
    return gzip.decompress(base64.b64decode(b64)).decode()


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    out = tmp_path_factory.mktemp("report") / "paper.html"
    assert rtw.report(SCAN, out=out) == out
    page = out.read_text()
    return out, page, json.loads(blob(page, "data-gz"))


def test_the_page_is_self_contained(made):
    out, page, data = made
    assert GENERATOR in page
    # No file, server or CDN is fetched: no src= or href= to anything but inline data.
    assert not re.search(r'\b(src|href)="(?!#|data:)', page)
    # Plotly.js: the bundle shipped with rtw (scripts/plotly_bundle.sh), byte for byte.
    assert blob(page, "plotly-gz") == (report_module.ASSETS / report_module.PLOTLY_JS).read_text()
    assert data["n"] == pq.read_metadata(SCAN / "samples.parquet").num_rows


def test_a_changed_plotly_bundle_is_refused(tmp_path, monkeypatch):
    assets = tmp_path / "report_assets"
    assets.mkdir()
    for f in report_module.ASSETS.iterdir():
        (assets / f.name).write_bytes(f.read_bytes())
    js = assets / report_module.PLOTLY_JS
    js.write_bytes(js.read_bytes().replace(b"plotly.js v", b"plotly.js w", 1))
    monkeypatch.setattr(sys.modules["rtw._page"], "ASSETS", assets)
    with pytest.raises(ImportError, match="sha256"):
        rtw.report(SCAN, out=tmp_path / "report.html")
    assert not (tmp_path / "report.html").exists()


def test_the_page_carries_every_row_and_the_summary(made):
    _, page, data = made
    rows = pq.read_table(SCAN / "samples.parquet").to_pydict()
    assert Counter(data["outcomes"][c] for c in data["outcome"]) == Counter(rows["outcome"])
    assert data["all_columns"] == list(rows)
    assert data["columns"]["alpha"] == rows["alpha"]
    summary = json.loads((SCAN / "summary.json").read_text())
    for o in summary["outcomes"]:
        if o["paper_percent"] is not None:  # the paper's numbers beside the scan's
            assert re.search(rf"<td>{o['outcome']}</td><td>{o['count']:,}</td><td>{o['percent']:.1f}</td>"
                             rf"<td>[^<]*</td><td>{o['paper_percent']:.1f}</td>", page)


def test_failure_clusters_are_rtw_scans(made, tmp_path):
    """The page's cluster of each failure is the one `rtw-scan cluster --assignments` writes."""
    _, _, data = made
    assert BINARY.is_file(), f"{BINARY} is missing: cargo build --release -p rtw-scan (or set RTW_SCAN)"
    f = tmp_path / "clusters.parquet"
    subprocess.run([str(BINARY), "cluster", str(SCAN / "samples.parquet"), "--assignments", str(f)],
                   check=True, capture_output=True)
    want = pq.read_table(f, columns=["sample_id", "cluster"]).to_pydict()
    want = {s: c - 1 for s, c in zip(want["sample_id"], want["cluster"])}
    ids = data["columns"]["sample_id"]
    got = {ids[i]: c for i, c in zip(data["clusters"]["index"], data["clusters"]["cluster"])}
    assert got == want


def test_gaits_are_the_scans_runs_drawn_from_rtw_draw(made):
    _, _, data = made
    gaits = data["gaits"]
    outcomes = {g["outcome"] for g in gaits}
    assert {"skip", "walk", "crawl", "collapse", "stall"} <= outcomes
    assert sum("cluster" in g["why"] for g in gaits) == 2  # the failure nearest each centre
    ids = data["columns"]["sample_id"]
    for g in gaits:
        row = ids.index(g["sample_id"])
        assert g["note"] is None, g["note"]
        assert g["outcome"] == data["outcomes"][data["outcome"][row]]
        if not g["t"]:
            continue
        n = len(g["t"])
        # The last 8 s of the run (or all of a shorter one), one frame every 0.04 s.
        assert g["t"][-1] - g["t"][0] == pytest.approx(8.0, abs=0.05) or g["t"][0] == 0.0
        assert n == pytest.approx((g["t"][-1] - g["t"][0]) / 0.04 + 1, abs=1)
        length = data["columns"]["length"][row]
        for k in (0, n // 2, n - 1):
            for x0, y0, x1, y1 in g["rods"][k]:  # every rod drawn at its length
                assert math.hypot(x1 - x0, y1 - y0) == pytest.approx(length, abs=2e-4)
            for (x, y), mode in zip(g["feet"][k], g["mode"][k]):  # a foot in contact lies on the slope
                if mode:
                    gx, gy = g["ground"]
                    assert abs(-gy * x + gx * y) < 2e-4


def test_refuses_to_write_over_a_file_it_did_not_make(made, tmp_path):
    note = tmp_path / "notes.html"
    note.write_text("<p>my notes</p>")
    with pytest.raises(ValueError, match=r"out: .*notes.html exists and is not an rtw report"):
        rtw.report(SCAN, out=note, per_outcome=0)
    assert note.read_text() == "<p>my notes</p>"
    # Its own report it replaces.
    own = tmp_path / "own.html"
    own.write_text(made[1])
    rtw.report(SCAN, out=own, per_outcome=0)
    assert GENERATOR in own.read_text()


@pytest.mark.parametrize("kwargs, message", [
    ({"outputs": ["speedd"]}, r"outputs: 'speedd' is not a numeric column"),
    ({"outputs": ["failure"]}, r"outputs: 'failure' is not a numeric column"),
    ({"per_outcome": 11}, r"per_outcome: 11 is invalid: must be an integer in \[0, 10\]"),
    ({"samples": [10**9]}, r"--sample: sample_id 1000000000 is not in the scan"),
])
def test_bad_options_name_the_field(kwargs, message, tmp_path):
    with pytest.raises(ValueError, match=message):
        rtw.report(SCAN, out=tmp_path / "r.html", **kwargs)
    assert not (tmp_path / "r.html").exists()


def test_cli_errors_exit_2_with_the_reason(tmp_path):
    r = subprocess.run([sys.executable, "-m", "rtw", "report", str(tmp_path), "--out", str(tmp_path / "r.html")],
                       capture_output=True, text=True)
    assert r.returncode == 2
    assert "python -m rtw report: error: DIR:" in r.stderr and "no samples.parquet" in r.stderr


def test_sensitivity_indices_and_maps_are_shown_when_present(tmp_path):
    import shutil

    for f in ("samples.parquet", "summary.json"):
        shutil.copy(SCAN / f, tmp_path / f)
    # The scan's own indices, as `rtw-scan sensitivity` writes them beside it
    # (test_report_inputs.py: another scan's are refused).
    subprocess.run([str(BINARY), "sensitivity", str(tmp_path), "--resamples", "10"], check=True, capture_output=True)
    want = pq.read_table(tmp_path / "indices.parquet").to_pylist()
    png = ROOT / "results/figures/fig-s4.png"
    shutil.copy(png, tmp_path / "robustness.png")
    out = rtw.report(tmp_path, per_outcome=0)
    assert out == tmp_path / "report.html"
    data = json.loads(blob(out.read_text(), "data-gz"))
    clean = [{k: (v if not isinstance(v, float) or math.isfinite(v) else None) for k, v in r.items()} for r in want]
    assert data["sensitivity"] == {"file": "indices.parquet", "rows": clean} and clean
    assert [im["name"] for im in data["images"]] == ["robustness.png"]
    assert base64.b64decode(data["images"][0]["src"].split(",", 1)[1]) == png.read_bytes()


def test_an_unmerged_shard_set_is_reported_whole(tmp_path):
    """The part-*.parquet of a sharded scan, not yet merged: every row of every part."""
    assert BINARY.is_file(), f"{BINARY} is missing: cargo build --release -p rtw-scan (or set RTW_SCAN)"
    for k in (0, 1):
        subprocess.run([str(BINARY), "run", str(ROOT / "configs/smoke.toml"), "--shard", f"{k}/2",
                        "--out", str(tmp_path)], check=True, capture_output=True)
    assert not (tmp_path / "samples.parquet").exists()
    out = rtw.report(tmp_path, per_outcome=1)
    data = json.loads(blob(out.read_text(), "data-gz"))
    want = sorted(s for k in (0, 1) for s in pq.read_table(tmp_path / f"part-{k}.parquet")["sample_id"].to_pylist())
    assert data["columns"]["sample_id"] == want and data["n"] == len(want)
    assert data["gaits"], "no gait for the smoke scan's outcomes"


def test_a_refined_scan_says_its_shares_are_not_the_boxs(tmp_path):
    """A refine's combined file crowds its added samples where the labels
    change: the page says its shares are not the box's; a plain scan's
    does not."""
    cfg = tmp_path / "s.toml"
    cfg.write_text("seed = 3\nsamples = 30\n[params]\nlength = 0.8\nrho = 2.5\n"
                   "alpha = { uniform = [0.0, 0.4] }\nfn = 3.269\nzeta = 0.0514\n"
                   "phi = { uniform = [0.05, 0.3] }\n[simulation]\nt_max = 2.0\n")
    scan = tmp_path / "s"
    subprocess.run([str(BINARY), "run", str(cfg), "--out", str(scan), "--quiet"], check=True)
    subprocess.run([str(BINARY), "refine", str(scan), "--budget", "10", "--rounds", "1", "--seed", "1",
                    "--quiet"], check=True)
    refined = rtw.report(scan / "refine", out=tmp_path / "refined.html").read_text()
    assert "not the box's" in refined
    plain = rtw.report(scan, out=tmp_path / "plain.html").read_text()
    assert "not the box's" not in plain
