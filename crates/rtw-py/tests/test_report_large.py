"""The report of a scan too large to carry row by row (large_scan.py: more
than PLOT_ROWS rows). The page then carries every row coded a byte per
plotted column, the gait map's densities per outcome, and the rows of a
stratified sample; each is checked here against the Parquet file with numpy,
an independent computation of every code, count and share. The browser test
brushes such a page."""

from __future__ import annotations

import base64
import gzip
import json
import re
from collections import Counter

import numpy as np
import pyarrow.parquet as pq
import pytest

import rtw
from large_scan import SAMPLES, make_scan
from rtw.report import INPUTS, PLOT_ROWS, ReportError

BINS, NONE = 255, 255


@pytest.fixture(scope="module")
def big(tmp_path_factory):
    folder = tmp_path_factory.mktemp("large")
    scan = make_scan(folder)
    table = pq.read_table(scan / "samples.parquet")
    asked = int(table["sample_id"][123].as_py())
    out = rtw.report(scan, out=folder / "large.html", per_outcome=1, samples=[asked], progress=False)
    page = out.read_text()
    b64 = re.search(r'<script type="application/octet-stream" id="data-gz">([^<]*)</script>', page).group(1)
    return scan, table, json.loads(gzip.decompress(base64.b64decode(b64))), asked


def coded(values: np.ndarray) -> tuple[list[float], np.ndarray]:
    """The range and the bin of every value, computed here with numpy."""
    ok = np.isfinite(values)
    lo, hi = float(values[ok].min()), float(values[ok].max())
    codes = np.full(len(values), NONE, dtype=np.uint8)
    # A column of one value: every row in the middle bin.
    codes[ok] = np.clip(np.floor((values[ok] - lo) / (hi - lo) * BINS), 0, BINS - 1) if hi > lo else BINS // 2
    return [lo, hi], codes


def raw(b64: str) -> np.ndarray:
    return np.frombuffer(base64.b64decode(b64), dtype=np.uint8)


def test_the_page_carries_every_row_coded_not_every_row(big):
    scan, table, data, _ = big
    assert data["n"] == SAMPLES > PLOT_ROWS
    B = data["big"]
    assert (B["bins"], B["none"]) == (BINS, NONE)
    # Each plotted column of every row, as its bin on the column's range.
    for c in [*INPUTS, *data["outputs"]]:
        values = table[c].to_numpy(zero_copy_only=False).astype(float)
        want_range, want = coded(values)
        assert data["ranges"][c] == pytest.approx(want_range, rel=0, abs=0), c
        got = raw(B["codes"][c])
        assert len(got) == SAMPLES
        assert np.array_equal(got, want), f"{c}: {np.count_nonzero(got != want)} rows coded otherwise"
    # Every row's outcome.
    outcomes = table["outcome"].to_pylist()
    assert [data["outcomes"][k] for k in raw(B["outcome"])] == outcomes
    # Row by row, only the drawn rows.
    assert len(data["columns"]["alpha"]) == B["rows"] <= PLOT_ROWS + 1


def test_the_gait_map_counts_every_row_per_outcome(big):
    _, table, data, _ = big
    G = data["big"]["density"]
    assert (G["x"], G["y"]) == ("alpha", "fn")
    _, cx = coded(table["alpha"].to_numpy())
    _, cy = coded(table["fn"].to_numpy())
    outcome = np.array(table["outcome"].to_pylist())
    for k, o in enumerate(data["outcomes"]):
        rows = outcome == o
        want = np.bincount(cy[rows].astype(int) * BINS + cx[rows], minlength=BINS * BINS)
        assert np.array_equal(np.array(G["grids"][k]), want), o
    assert sum(map(sum, G["grids"])) == SAMPLES


def test_the_drawn_rows_share_equally_and_keep_every_rare_outcome(big):
    _, table, data, asked = big
    counts = Counter(table["outcome"].to_pylist())
    # Water-filling, written out here: the smallest outcomes first, each at
    # most an equal share of what is left.
    want, left = {}, PLOT_ROWS
    for k, (o, c) in enumerate(sorted(counts.items(), key=lambda oc: oc[1])):
        want[o] = min(c, left // (len(counts) - k))
        left -= want[o]
    ids = data["columns"]["sample_id"]
    assert ids == sorted(set(ids)) and asked in ids
    drawn = Counter(data["outcomes"][k] for k in data["outcome"])
    extra = Counter([table["outcome"][int(np.searchsorted(table["sample_id"].to_numpy(), asked))].as_py()])
    for o in counts:
        assert drawn[o] - want[o] in (0, extra[o]), (o, drawn[o], want[o])
    # The rarest outcome is drawn whole (a uniform subset would thin it).
    rare = min(counts, key=counts.get)
    assert drawn[rare] == counts[rare]
    # The drawn rows are the file's rows (to 7 significant digits).
    at = np.searchsorted(table["sample_id"].to_numpy(), ids)
    assert data["columns"]["alpha"] == [float(f"{v:.7g}") for v in table["alpha"].to_numpy()[at]]
    # The parallel categories count every row.
    assert sum(data["parcats"]["counts"]) == SAMPLES
    # The failure views are the drawn failures.
    assert len(data["clusters"]["index"]) == drawn["collapse"] + drawn["stall"]


def test_a_sample_not_in_the_scan_is_refused(big, tmp_path):
    scan = big[0]
    with pytest.raises(ReportError, match="sample_id 99999999 is not in the scan"):
        rtw.report(scan, out=tmp_path / "r.html", per_outcome=0, samples=[99999999], progress=False)


def test_a_text_column_is_not_an_output(big, tmp_path):
    # The coded columns are numbers; a text column is refused, named, before any work.
    with pytest.raises(ReportError, match="outputs: 'message' is not a numeric column"):
        rtw.report(big[0], out=tmp_path / "r.html", per_outcome=0, outputs=["message"], progress=False)
    assert not (tmp_path / "r.html").exists()


def test_the_failure_projections_count_every_failure_per_cluster(big):
    scan, table, data, _ = big
    from rtw._rtw import failure_clusters

    cluster = dict(failure_clusters(scan / "samples.parquet"))
    P = data["big"]["clusters"]
    k = len(data["clusters"]["centres"])
    assert P["groups"] == k + 1
    outcome = table["outcome"].to_pylist()
    group = np.array([cluster.get(s, k) if o in ("collapse", "stall") else 255
                      for s, o in zip(table["sample_id"].to_pylist(), outcome)])
    assert data["big"]["failures"] == int(np.count_nonzero(group != 255))
    codes = {c: coded(table[c].to_numpy())[1].astype(int) for c in ("alpha", "fn", "phi")}
    for p, (x, y) in enumerate([("alpha", "fn"), ("alpha", "phi"), ("fn", "phi")]):
        for j in range(k + 1):
            rows = group == j
            want = np.bincount(codes[y][rows] * BINS + codes[x][rows], minlength=BINS * BINS)
            assert np.array_equal(np.array(P["grids"][p][j]), want), (x, y, j)
    # The drawn columns are the file's to 7 significant digits.
    at = np.searchsorted(table["sample_id"].to_numpy(), data["columns"]["sample_id"])
    assert data["columns"]["phi"] == [float(f"{v:.7g}") for v in table["phi"].to_numpy()[at]]


def test_a_column_the_scan_holds_fixed_is_in_the_middle_bin(tmp_path):
    # α fixed at 0.125: its range is one value, and every row sits in the
    # middle of the gait map's α axis (which the page widens around it).
    scan = make_scan(tmp_path, alpha=0.125)
    out = rtw.report(scan, out=tmp_path / "fixed.html", per_outcome=0, progress=False)
    b64 = re.search(r'<script type="application/octet-stream" id="data-gz">([^<]*)</script>', out.read_text()).group(1)
    data = json.loads(gzip.decompress(base64.b64decode(b64)))
    assert data["ranges"]["alpha"] == [0.125, 0.125]
    assert set(raw(data["big"]["codes"]["alpha"]).tolist()) == {BINS // 2}
    grids = np.array(data["big"]["density"]["grids"]).reshape(len(data["outcomes"]), BINS, BINS)
    assert grids[:, :, BINS // 2].sum() == grids.sum() == SAMPLES
