"""What rtw.report refuses to read, and what it reads as given: the scan goes
through rtw-scan's verified reader (rtw.read_scan), so a file rtw-scan
refuses gives no report; the sensitivity indices beside it must be its own;
the scan's own text is never taken for the page's placeholders; the options
are type-checked."""

from __future__ import annotations

import base64
import gzip
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pyarrow as pa
import pyarrow.compute as pc
import pyarrow.parquet as pq
import pytest

import rtw
from rtw import _rtw

ROOT = Path(__file__).resolve().parents[3]
SCAN = ROOT / "results/paper"
BINARY = Path(os.environ.get("RTW_SCAN", Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "release/rtw-scan"))
SMALL = ("seed = {seed}\nsamples = {n}\n{name}[params]\nlength = 0.8\nrho = 2.5\n"
         "alpha = {{ uniform = [0.0, 0.4] }}\nfn = 3.269\nzeta = 0.0514\n"
         "phi = {{ uniform = [0.05, 0.3] }}\n[simulation]\nt_max = 2.0\n")


def blob(page: str, name: str) -> str:
    b64 = re.search(rf'<script type="application/octet-stream" id="{name}">([^<]*)</script>', page).group(1)
    return gzip.decompress(base64.b64decode(b64)).decode()


def run_scan(tmp: Path, folder: str, seed: int = 3, n: int = 30, name: str | None = None, extra: str = "") -> Path:
    assert BINARY.is_file(), f"{BINARY} is missing: cargo build --release -p rtw-scan (or set RTW_SCAN)"
    cfg = tmp / f"{folder}.toml"
    cfg.write_text(SMALL.format(seed=seed, n=n, name=f"name = {json.dumps(name)}\n" if name else "") + extra)
    out = tmp / folder
    subprocess.run([str(BINARY), "run", str(cfg), "--out", str(out), "--quiet"], check=True, capture_output=True)
    return out


def rewrite(src: Path, dst: Path, change, keep_hash: bool) -> None:
    """`src`'s rows changed by `change`, written by pyarrow with `src`'s
    metadata, its content hash kept or dropped (as a hostile user would)."""
    meta = dict(pq.read_metadata(src).metadata)
    if not keep_hash:
        meta.pop(b"rtw.content_hash")
    dst.parent.mkdir(parents=True, exist_ok=True)
    pq.write_table(change(pq.read_table(src)).replace_schema_metadata(meta), dst)


def _nan_speed(t: pa.Table) -> pa.Table:
    i = t.schema.get_field_index("speed")
    speed = t["speed"].to_pylist()
    speed[next(k for k, v in enumerate(speed) if v is not None)] = float("nan")
    return t.set_column(i, t.schema.field(i), pa.array(speed, pa.float64()))


def _perm(t: pa.Table) -> list[int]:
    n = t.num_rows
    return [1, 0, *range(2, n)]


CORRUPT = {
    "truncated, hash kept": (lambda t: t.slice(0, t.num_rows // 2), True),
    "shuffled, hash kept": (lambda t: t.take(_perm(t)), True),
    "truncated, no hash": (lambda t: t.slice(0, t.num_rows // 2), False),
    "middle deleted, no hash": (lambda t: pa.concat_tables([t.slice(0, 100), t.slice(200)]), False),
    "duplicated, no hash": (lambda t: pa.concat_tables([t, t.slice(0, 10)]).sort_by("sample_id"), False),
    "shuffled, no hash": (lambda t: t.take(_perm(t)), False),
    "NaN speed, no hash": (_nan_speed, False),
}


@pytest.mark.parametrize("case", list(CORRUPT))
def test_a_scan_file_rtw_scan_refuses_gives_no_report(case, tmp_path):
    change, keep = CORRUPT[case]
    bad = tmp_path / "scan" / "samples.parquet"
    rewrite(SCAN / "samples.parquet", bad, change, keep)
    # rtw-scan itself refuses it...
    r = subprocess.run([str(BINARY), "summary", str(bad)], capture_output=True, text=True)
    assert r.returncode != 0, r.stdout
    # ...and so does the report, naming the file, from Python and from the command line.
    with pytest.raises(ValueError, match=re.escape(str(bad))):
        rtw.report(bad.parent, out=tmp_path / "r.html", per_outcome=0)
    r = subprocess.run([sys.executable, "-m", "rtw", "report", str(bad.parent), "--out", str(tmp_path / "r.html")],
                       capture_output=True, text=True)
    assert r.returncode == 2 and str(bad) in r.stderr, r.stderr
    assert not (tmp_path / "r.html").exists()


def test_a_corrupt_page_is_an_error_naming_the_file(tmp_path):
    bad = tmp_path / "scan" / "samples.parquet"
    bad.parent.mkdir()
    raw = bytearray((SCAN / "samples.parquet").read_bytes())
    for k in range(len(raw) // 3, len(raw) // 3 + 64):  # a data page's bytes, not the footer
        raw[k] ^= 0x5A
    bad.write_bytes(bytes(raw))
    r = subprocess.run([sys.executable, "-m", "rtw", "report", str(bad.parent), "--out", str(tmp_path / "r.html")],
                       capture_output=True, text=True)
    assert r.returncode == 2, r.stderr
    assert "Traceback" not in r.stderr and str(bad) in r.stderr and "corrupt" in r.stderr, r.stderr


def test_an_incomplete_shard_set_is_refused(tmp_path):
    cfg = ROOT / "configs/smoke.toml"
    subprocess.run([str(BINARY), "run", str(cfg), "--shard", "0/2", "--out", str(tmp_path)], check=True,
                   capture_output=True)
    with pytest.raises(ValueError, match=r"1 of 2 shards missing.*part-1\.parquet"):
        rtw.report(tmp_path, per_outcome=0)
    assert not (tmp_path / "report.html").exists()
    # A part named alone is read as that part (its own ids), not as the scan.
    t, files = _rtw.read_scan(tmp_path / "part-0.parquet")
    assert files == [tmp_path / "part-0.parquet"] and t.schema.metadata[b"rtw.shard"] == b"0/2"


def test_read_scan_is_the_verified_scan_with_its_metadata(tmp_path):
    t = rtw.read_scan(SCAN)
    assert _rtw.read_scan(SCAN)[1] == [SCAN / "samples.parquet"]
    assert t.equals(pq.read_table(SCAN / "samples.parquet").replace_schema_metadata(t.schema.metadata))
    on_disk = pq.read_metadata(SCAN / "samples.parquet").metadata
    assert {k: v for k, v in t.schema.metadata.items() if k.startswith(b"rtw.")} == {
        k: v for k, v in on_disk.items() if k.startswith(b"rtw.")}
    # A complete shard set reads as its merged file would: the same rows, the same content hash.
    sharded = tmp_path / "sharded"
    for k in (0, 1):
        subprocess.run([str(BINARY), "run", str(ROOT / "configs/smoke.toml"), "--shard", f"{k}/2",
                        "--out", str(sharded)], check=True, capture_output=True)
    parts, files = _rtw.read_scan(sharded)
    assert files == [sharded / "part-0.parquet", sharded / "part-1.parquet"]
    subprocess.run([str(BINARY), "merge", str(sharded)], check=True, capture_output=True)
    # (Values compared: each part has its own dictionary of labels.)
    assert parts.to_pylist() == pq.read_table(sharded / "samples.parquet").to_pylist()
    merged = pq.read_metadata(sharded / "samples.parquet").metadata
    assert parts.schema.metadata[b"rtw.content_hash"] == merged[b"rtw.content_hash"]
    assert b"rtw.shard" not in parts.schema.metadata and parts.schema.metadata[b"rtw.shards"] == b"2"


def test_another_scans_sensitivity_indices_are_refused(tmp_path):
    a = run_scan(tmp_path, "a", seed=3, n=64)
    b = run_scan(tmp_path, "b", seed=4, n=64)
    for s in (a, b):
        subprocess.run([str(BINARY), "sensitivity", str(s)], check=True, capture_output=True)
    own = pq.read_table(a / "indices.parquet").select(["output", "parameter", "S1", "S1_conf", "ST", "ST_conf"])
    data = json.loads(blob(rtw.report(a, per_outcome=0).read_text(), "data-gz"))
    assert data["sensitivity"]["file"] == "indices.parquet"
    assert len(data["sensitivity"]["rows"]) == own.num_rows > 0
    shutil.copy(b / "indices.parquet", a / "indices.parquet")
    with pytest.raises(ValueError, match=r"indices.parquet holds another scan's sensitivity indices"):
        rtw.report(a, per_outcome=0)
    # Indices written by hand, with no record of their scan, are not taken either.
    pq.write_table(own, a / "indices.parquet")
    with pytest.raises(ValueError, match=r"indices.parquet: not sensitivity indices written by `rtw-scan sensitivity`"):
        rtw.report(a, per_outcome=0)


def test_the_scans_own_text_is_not_expanded_as_placeholders(tmp_path):
    name = "x{{SCRIPT}}y{{PLOTLY}}z{{DATA}}"
    scan = run_scan(tmp_path, "s", name=name)
    plain = run_scan(tmp_path, "p", name="xyz")
    page = rtw.report(scan, per_outcome=0).read_text()
    size = len(rtw.report(plain, per_outcome=0).read_text())
    assert f"<title>rtw report: {name}</title>" in page
    assert f"<h1>rtw scan report: {name}</h1>" in page
    # The page is its plain twin's size (the name's length apart), not twice or five times it.
    assert abs(len(page) - size) < 2_000, (len(page), size)


def test_a_scan_with_fewer_failures_than_clusters_is_reported(tmp_path):
    """Every sample at Fig. 7(a)'s walking design: no failure, so
    summary.json's clusters are null."""
    cfg = tmp_path / "walk.toml"
    cfg.write_text("seed = 1\nsamples = 4\n[params]\nlength = 0.8\nrho = 2.5\nalpha = 0.125\nfn = 3.269\n"
                   "zeta = 0.0514\nphi = 0.15\n[simulation]\nt_max = 2.0\n")
    scan = tmp_path / "walk"
    subprocess.run([str(BINARY), "run", str(cfg), "--out", str(scan), "--quiet"], check=True, capture_output=True)
    assert json.loads((scan / "summary.json").read_text())["clusters"] is None
    data = json.loads(blob(rtw.report(scan, per_outcome=1).read_text(), "data-gz"))
    assert data["n"] == 4 and data["clusters"]["centres"] == [] and data["gaits"]


@pytest.mark.parametrize("kwargs, error, message", [
    ({"samples": [5.5]}, TypeError, r"samples: 5\.5 is not a sample id"),
    ({"samples": [True]}, TypeError, r"samples: True is not a sample id"),
    ({"samples": 5}, TypeError, r"samples: 5 is not a list of sample ids"),
    ({"samples": [-1]}, ValueError, r"samples: -1 is invalid: must be a sample id >= 0"),
    ({"outputs": "speed"}, TypeError, r"outputs: 'speed' is not a list of column names"),
    ({"outputs": [1]}, TypeError, r"outputs: 1 is not a column name"),
])
def test_options_of_the_wrong_type_are_refused_by_name(kwargs, error, message, tmp_path):
    with pytest.raises(error, match=message):
        rtw.report(SCAN, out=tmp_path / "r.html", per_outcome=0, **kwargs)
    assert not (tmp_path / "r.html").exists()


def _cluster(scan: Path, dest: Path) -> None:
    """`rtw-scan cluster --assignments`: each failure of `scan` and its cluster, written to `dest`."""
    subprocess.run([str(BINARY), "cluster", str(scan / "samples.parquet"), "--assignments", str(dest)],
                   check=True, capture_output=True)


def test_the_scans_own_assignments_are_read_and_an_altered_file_is_refused(tmp_path):
    """rtw-scan's reader of an assignments file checks its rows against the
    content hash written with them: a file whose clusters were changed after
    (its metadata kept, as a hostile user would) is refused, naming it."""
    a = run_scan(tmp_path, "a", seed=3, n=64)
    _cluster(a, a / "clusters.parquet")
    data = json.loads(blob(rtw.report(a, per_outcome=0).read_text(), "data-gz"))
    assert data["clusters"]["how"].startswith("from clusters.parquet"), data["clusters"]["how"]
    want = pq.read_table(a / "clusters.parquet", columns=["sample_id", "cluster"]).to_pydict()
    ids = [data["columns"]["sample_id"][i] for i in data["clusters"]["index"]]
    assert dict(zip(ids, data["clusters"]["cluster"])) == {s: c - 1 for s, c in zip(want["sample_id"], want["cluster"])}
    rewrite(a / "clusters.parquet", a / "clusters.parquet",
            lambda t: t.set_column(1, t.schema.field(1), pc.add(t["cluster"], 1)), keep_hash=True)
    with pytest.raises(ValueError, match=r"clusters\.parquet is corrupt: its rows hash to"):
        rtw.report(a, per_outcome=0)


def test_another_scans_assignments_are_refused(tmp_path):
    """An assignments file beside a scan must record that scan's content hash:
    the failures of another scan (same sample ids, other rows) are refused."""
    a = run_scan(tmp_path, "a", seed=3, n=64)
    b = run_scan(tmp_path, "b", seed=4, n=64)
    _cluster(b, a / "clusters.parquet")
    with pytest.raises(ValueError, match=r"clusters\.parquet holds another scan's failure clusters"):
        rtw.report(a, per_outcome=0)


def test_another_scans_summary_is_refused(tmp_path):
    """summary.json beside a scan must count that scan's rows: another scan's
    (same size, other seed and outcomes) is refused, naming it."""
    a = run_scan(tmp_path, "a", seed=3, n=64)
    b = run_scan(tmp_path, "b", seed=4, n=64)
    shutil.copy(b / "summary.json", a / "summary.json")
    with pytest.raises(ValueError, match=r"summary\.json is not the summary of this scan"):
        rtw.report(a, per_outcome=0)
