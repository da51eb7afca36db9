"""The scan report in a real browser: headless Chromium from Debian's packages
(`chromium`, `chromium-driver`; scripts/test.sh installs them when missing),
driven by Selenium through the system's chromedriver (never a driver or a
browser that Selenium Manager would download: SE_OFFLINE and the driver's path).

It opens the report of results/paper made by `python -m rtw report`, and fails
on any console error; checks the samples plotted per outcome against the
Parquet file; brushes the α axis and checks the count the page shows; clicks
a sample and checks its columns and its animated gait; and saves a screenshot
to $CARGO_TARGET_DIR/report-test/screenshot.png (target/report-test/ by
default) for a person to look at.
"""

from __future__ import annotations

import importlib.util
import json
import os
import shutil
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

import numpy as np
import pyarrow.parquet as pq
import pytest

ROOT = Path(__file__).resolve().parents[3]
SCAN = ROOT / "results/paper"
OUT = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "report-test"
CHROMIUM = shutil.which("chromium")
DRIVER = shutil.which("chromedriver")

pytestmark = pytest.mark.skipif(
    CHROMIUM is None or DRIVER is None,
    reason="needs chromium and chromium-driver (Debian packages; scripts/test.sh installs them as root: "
           "apt-get install -y chromium chromium-driver)",
)


def timing():
    """scripts/report_timing.py: how the page is opened and its marks read."""
    spec = importlib.util.spec_from_file_location("report_timing", ROOT / "scripts" / "report_timing.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def page():
    t = timing()
    OUT.mkdir(parents=True, exist_ok=True)
    html = OUT / "paper.html"
    made = subprocess.run([sys.executable, "-m", "rtw", "report", "results/paper", "--out", str(html), "--force"],
                          capture_output=True, text=True, cwd=ROOT, timeout=600)
    assert made.returncode == 0, made.stderr
    driver = t.open_chromium()
    try:
        driver.get(html.as_uri())
        marks = t.wait_ready(driver)
        (OUT / "timing.json").write_text(json.dumps(marks, indent=1))
        print(f"report opened: first view {marks['first-view']:.0f} ms, everything drawn {marks['ready']:.0f} ms "
              f"(written to {OUT / 'timing.json'})")
        yield driver
    finally:
        driver.quit()


def rows():
    return pq.read_table(SCAN / "samples.parquet").to_pydict()


def no_console_errors(driver):
    severe = [e for e in driver.get_log("browser") if e["level"] == "SEVERE"]
    assert not severe, f"console errors: {severe}"


def test_the_page_opens_without_console_errors(page):
    no_console_errors(page)
    title = page.execute_script("return document.querySelector('h1').textContent")
    assert title == "rtw scan report: paper"


def test_plotted_samples_per_outcome_match_the_parquet_file(page):
    want = Counter(rows()["outcome"])
    plotted = page.execute_script(
        "return Object.fromEntries(document.getElementById('gaitmap').data.map(t => [t.name, t.x.length]))")
    assert plotted == {o: c for o, c in want.items() if c}
    # The parallel coordinates carry every sample, coloured by its outcome.
    codes = page.execute_script(
        "const d = document.getElementById('parcoords').data[0]; return d.line.color")
    names = page.execute_script("return Array.from(document.getElementById('gaitmap').data.map(t => t.name))")
    assert Counter(names[c] for c in codes) == want
    # The cluster views carry every failure.
    failures = page.execute_script(
        "return document.getElementById('clusters3d').data.filter(t => t.customdata)"
        ".reduce((n, t) => n + t.x.length, 0)")
    assert failures == want["collapse"] + want["stall"]
    no_console_errors(page)


def test_brushing_alpha_shows_the_count_of_the_parquet_file(page):
    r = rows()
    lo, hi = 0.1, 0.2
    want = Counter(o for a, o in zip(r["alpha"], r["outcome"]) if lo <= a <= hi)
    labels = page.execute_script(
        "return document.getElementById('parcoords').data[0].dimensions.map(d => d.label)")
    i = labels.index("α")
    page.execute_script(
        f"Plotly.restyle('parcoords', {{'dimensions[{i}].constraintrange': [[{lo}, {hi}]]}})")
    time.sleep(0.3)
    shown = page.execute_script("return document.getElementById('count').dataset.selected")
    text = page.execute_script("return document.getElementById('count').textContent")
    assert int(shown) == sum(want.values()), text
    assert text.startswith(f"{sum(want.values()):,} of {len(r['alpha']):,} samples selected")
    for o, c in want.items():
        assert f"{o} {c:,}" in text
    # The gait map shows the same samples brushed, per outcome.
    marked = page.execute_script(
        "return Object.fromEntries(document.getElementById('gaitmap').data.map(t => [t.name, (t.selectedpoints || []).length]))")
    assert {o: c for o, c in marked.items() if c} == dict(want)
    page.execute_script(f"Plotly.restyle('parcoords', {{'dimensions[{i}].constraintrange': [null]}})")
    time.sleep(0.3)
    assert int(page.execute_script("return document.getElementById('count').dataset.selected")) == len(r["alpha"])
    assert page.execute_script("return document.getElementById('gaitmap').data.every(t => t.selectedpoints == null)")
    no_console_errors(page)


def test_a_click_shows_the_sample_and_its_gait_animated(page):
    r = rows()
    gaits = page.execute_script(
        "return Array.from(document.querySelectorAll('#gaits button')).map(b => b.textContent)")
    assert gaits, "no sample with a gait"
    # A stable sample's gait: its run lasts the whole t_max, so the animation has frames.
    walk = next(g for g in gaits if " walk: " in g)
    sid = int(walk.split()[0].lstrip("#"))
    row = r["sample_id"].index(sid)
    page.execute_script(
        f"document.getElementById('gaitmap').emit('plotly_click', {{points: [{{customdata: {row}}}]}})")
    time.sleep(0.2)
    table = page.execute_script(
        "const t = document.getElementById('sample-table');"
        "return {id: t.dataset.sampleId, cells: Array.from(t.rows).map(x => [x.cells[0].textContent, x.cells[1].textContent])}")
    assert int(table["id"]) == sid
    cells = dict(table["cells"])
    assert list(cells) == list(r)  # every column of the row, in the file's order
    assert cells["outcome"] == "walk" and float(cells["alpha"]) == pytest.approx(r["alpha"][row], rel=1e-5)
    first = int(page.execute_script("return document.getElementById('frame').dataset.frame"))
    time.sleep(1.0)
    later = int(page.execute_script("return document.getElementById('frame').dataset.frame"))
    assert later != first, "the gait's animation does not advance"
    frame = page.execute_script("return document.getElementById('frame').textContent")
    assert frame.startswith("frame ") and " s · " in frame
    # A sample without a precomputed gait says so.
    without = next(i for i, s in enumerate(r["sample_id"]) if f"#{s} " not in " ".join(gaits))
    page.execute_script(
        f"document.getElementById('gaitmap').emit('plotly_click', {{points: [{{customdata: {without}}}]}})")
    note = page.execute_script("return document.getElementById('gait-note').textContent")
    assert note.startswith(f"No gait was computed for sample {r['sample_id'][without]}")
    # Back to the walk for the screenshot.
    page.execute_script(
        f"document.getElementById('gaitmap').emit('plotly_click', {{points: [{{customdata: {row}}}]}})")
    time.sleep(0.5)
    no_console_errors(page)
    shot = OUT / "screenshot.png"
    page.save_screenshot(str(shot))
    print(f"screenshot of the report: {shot}")
    assert shot.stat().st_size > 10_000


def test_the_first_view_is_drawn_before_the_webgl_views(page):
    # The header, the summary and the gait map come first, and the gait map of
    # 1 000 samples is SVG: no software-rendered WebGL context delays it.
    marks = json.loads((OUT / "timing.json").read_text())
    assert marks["first-view"] <= marks["parallel coordinates"] < marks["ready"]
    types = page.execute_script("return document.getElementById('gaitmap').data.map(t => t.type)")
    assert set(types) == {"scatter"}
    no_console_errors(page)


@pytest.fixture(scope="module")
def large_page(tmp_path_factory):
    """The report of a scan of more than PLOT_ROWS rows (large_scan.py), open."""
    from large_scan import make_scan

    folder = tmp_path_factory.mktemp("large")
    scan = make_scan(folder)
    html = folder / "large.html"
    made = subprocess.run([sys.executable, "-m", "rtw", "report", str(scan), "--out", str(html), "--per-outcome", "1"],
                          capture_output=True, text=True, cwd=ROOT, timeout=600)
    assert made.returncode == 0, made.stderr
    t = timing()
    driver = t.open_chromium()
    try:
        driver.get(html.as_uri())
        t.wait_ready(driver)
        yield driver, pq.read_table(scan / "samples.parquet")
    finally:
        driver.quit()


def test_a_large_scan_is_brushed_over_every_row(large_page):
    page, table = large_page
    no_console_errors(page)
    # The gait map and the failure projections are densities (a layout image each).
    for view in ("gaitmap", "proj0", "proj1", "proj2"):
        assert page.execute_script(f"return document.getElementById('{view}').layout.images.length") == 1, view
    alpha = table["alpha"].to_numpy()
    outcome = table["outcome"].to_pylist()
    lo, hi = float(alpha.min()), float(alpha.max())
    a, b = lo + 0.3 * (hi - lo), lo + 0.6 * (hi - lo)
    # A row counts when its bin (1/255 of the axis, numpy's own floor here)
    # meets the brushed range.
    k = np.clip(np.floor((alpha - lo) / (hi - lo) * 255), 0, 254)
    w = (hi - lo) / 255
    keep = (lo + k * w <= b) & (lo + (k + 1) * w >= a)
    want = Counter(o for o, y in zip(outcome, keep) if y)
    labels = page.execute_script("return document.getElementById('parcoords').data[0].dimensions.map(d => d.label)")
    i = labels.index("α")
    page.execute_script(f"Plotly.restyle('parcoords', {{'dimensions[{i}].constraintrange': [[{a}, {b}]]}})")
    time.sleep(0.5)
    text = page.execute_script("return document.getElementById('count').textContent")
    assert int(page.execute_script("return document.getElementById('count').dataset.selected")) == sum(want.values()), text
    assert text.startswith(f"{sum(want.values()):,} of {len(alpha):,} samples selected")
    for o, c in want.items():
        assert f"{o} {c:,}" in text
    # Cleared, every row again.
    page.execute_script(f"Plotly.restyle('parcoords', {{'dimensions[{i}].constraintrange': [null]}})")
    time.sleep(0.5)
    assert int(page.execute_script("return document.getElementById('count').dataset.selected")) == len(alpha)
    no_console_errors(page)
