"""rtw.sensitivity, rtw.basin, rtw.profile and rtw.design go through the checks of their `rtw-scan` subcommands.

Both faces call one library entry point each: the same bad file, table or
value gets the same refusal, in the same words (the CLI's flag `--name` is
Python's keyword `name`), and both stop on Ctrl-C.
"""

from __future__ import annotations

import os
import re
import subprocess
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

import rtw

if TYPE_CHECKING:
    from conftest import Press

ROOT = Path(__file__).resolve().parents[3]
BINARY = Path(os.environ.get("RTW_SCAN", Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "release/rtw-scan"))
FIG7A = (0.8, 2.5, 0.125, 3.269, 0.0514, 0.15)
DESIGN = ["--length", "0.8", "--rho", "2.5", "--alpha", "0.125", "--fn", "3.269", "--zeta", "0.0514", "--phi", "0.15"]
X, Y = "omega_a:-30:30:3", "theta_b:-0.3:0.3:3"
NAMES = ["rho", "alpha", "fn", "zeta", "phi"]
BOUNDS = [[1.0, 5.0], [0.0, 0.4], [1.5, 5.0], [0.05, 0.1], [0.05, 0.3]]


def _config(sampling: str, n: int) -> str:
    axes = "\n".join(f"{k} = {{ uniform = [{lo}, {hi}] }}" for k, (lo, hi) in zip(NAMES, BOUNDS))
    return (
        f'name = "checks"\nseed = 5\nsamples = {n}\nsampling = "{sampling}"\n[params]\nlength = 0.8\n{axes}\n'
        "[simulation]\nt_max = 3.0\n"
    )


def cli_error(*args: str) -> str:
    """The CLI's refusal (exit 1), without its `error: ` prefix."""
    assert BINARY.is_file(), f"{BINARY} is missing: cargo build --release -p rtw-scan (or set RTW_SCAN)"
    o = subprocess.run([str(BINARY), *args], capture_output=True, text=True)
    assert o.returncode != 0, (args, o.stdout)
    lines = [line for line in o.stderr.splitlines() if line.startswith("error: ")]
    assert lines, o.stderr
    return lines[-1].removeprefix("error: ")


def python_error(call) -> str:
    with pytest.raises(ValueError) as e:
        call()
    return str(e.value)


def as_python(cli: str) -> str:
    """A CLI message in Python's spelling: flags (`--resamples`) are keywords (`resamples`)."""
    return cli.replace("--", "")


def as_python_profile(cli: str) -> str:
    """A profile's CLI message in `rtw.profile`'s spelling: its `--from` and `--to` are
    `phi_from` and `phi_to`, its other flags keywords of their own names."""
    return as_python(re.sub(r"--to\b", "phi_to", re.sub(r"--from\b", "phi_from", cli)))


@pytest.fixture(scope="module")
def scan(tmp_path_factory) -> Path:
    """A real scan file written by `rtw-scan run` (Saltelli, 16 base rows × 7)."""
    d = tmp_path_factory.mktemp("scan")
    cfg = d / "s.toml"
    cfg.write_text(_config("saltelli", 16))
    subprocess.run([str(BINARY), "run", str(cfg), "--out", str(d / "s")], check=True, capture_output=True)
    return d / "s" / "samples.parquet"


def _rewrite(src: Path, dest: Path, table: pa.Table, drop_hash: bool = False) -> Path:
    """`table` written with `src`'s key-value metadata (the hostile repro), optionally without its hashes."""
    meta = dict(pq.read_metadata(src).metadata)
    if drop_hash:
        meta.pop(b"rtw.content_hash")
        meta.pop(b"rtw.metadata_hash", None)
    pq.write_table(table.replace_schema_metadata(meta), dest)
    return dest


def _bad_files(scan: Path, d: Path) -> dict[str, Path]:
    t = pq.read_table(scan)
    perm = np.random.default_rng(1).permutation(t.num_rows)
    dup = np.arange(t.num_rows)
    dup[1] = 0
    speed = t.column("speed").to_numpy(zero_copy_only=False).copy()
    speed[:] = np.nan
    nan_speed = t.set_column(t.schema.get_field_index("speed"), "speed", pa.array(speed))
    return {
        "shuffled, hash kept": _rewrite(scan, d / "shuffled.parquet", t.take(perm)),
        "shuffled, no hash": _rewrite(scan, d / "shuffled-nohash.parquet", t.take(perm), drop_hash=True),
        "duplicated id": _rewrite(scan, d / "dup.parquet", t.take(dup)),
        "NaN speeds": _rewrite(scan, d / "nan.parquet", nan_speed),
    }


def test_python_refuses_every_file_the_cli_refuses_with_its_words(scan: Path, tmp_path: Path) -> None:
    for what, f in _bad_files(scan, tmp_path).items():
        cli = cli_error("sensitivity", str(f), "--out", str(tmp_path / "i.parquet"))
        py = python_error(lambda: rtw.sensitivity(f))
        assert py == cli, what
    assert not (tmp_path / "i.parquet").exists()


def _table_of(scan: Path) -> pa.Table:
    """A scan file's rows as a table carrying its config (as rtw.scan returns one), no hash."""
    t = pq.read_table(scan)
    meta = {k: v for k, v in pq.read_metadata(scan).metadata.items() if not k.endswith(b"_hash")}
    return t.replace_schema_metadata(meta)


def test_a_shuffled_or_corrupt_table_is_refused(scan: Path) -> None:
    t = _table_of(scan)
    # The untouched table gives the file's indices.
    assert rtw.sensitivity(t, resamples=10).equals(rtw.sensitivity(scan, resamples=10))
    perm = np.random.default_rng(1).permutation(t.num_rows)
    # Saltelli's estimator pairs rows by their position: a shuffled table would give wrong indices.
    assert "sample_id" in python_error(lambda: rtw.sensitivity(t.take(perm)))
    dup = np.arange(t.num_rows)
    dup[1] = 0
    assert "column `sample_id`, row 1: 0 is invalid" in python_error(lambda: rtw.sensitivity(t.take(dup)))
    for column in ["speed", "phi"]:
        i = t.schema.get_field_index(column)
        bad = t.set_column(i, t.schema.field(i), pa.array(np.full(t.num_rows, np.nan)))
        assert f"column `{column}`, row 0: " in python_error(lambda: rtw.sensitivity(bad)), column


def test_a_refined_table_is_refused_as_biased(scan: Path) -> None:
    t = _table_of(scan)
    refined = t.replace_schema_metadata({**t.schema.metadata, b"rtw.refine": b"{}"})
    assert "refined" in python_error(lambda: rtw.sensitivity(refined))


@pytest.mark.parametrize(
    ("flag", "value"),
    [
        ("resamples", "1"),
        ("resamples", "0"),
        ("resamples", str(10**12)),
        ("resamples", str(10**40)),
        ("seed", str(2**64)),
        ("seed", "-1"),
    ],
)
def test_sensitivity_settings_get_the_same_refusal(scan: Path, tmp_path: Path, flag: str, value: str) -> None:
    cli = cli_error("sensitivity", str(scan), f"--{flag}", value, "--out", str(tmp_path / "i.parquet"))
    py = python_error(lambda: rtw.sensitivity(scan, **{flag: int(value)}))
    assert py == as_python(cli)
    assert "in [" in py, py


@pytest.mark.parametrize(
    ("flag", "value"),
    [
        ("threads", "0"),
        ("threads", "1000"),
        ("threads", str(10**6)),
        ("steps", "0"),
        ("steps", str(10**30)),
        ("tol", "5"),
    ],
)
def test_basin_settings_get_the_same_refusal(tmp_path: Path, flag: str, value: str) -> None:
    cli = cli_error("basin", *DESIGN, "--x", X, "--y", Y, f"--{flag}", value, "--out", str(tmp_path / "b.parquet"))
    number = float(value) if flag == "tol" else int(value)
    py = python_error(lambda: rtw.basin(*FIG7A, x=X, y=Y, **{flag: number}))
    assert py == as_python(cli)
    assert "in [" in py or "in (" in py, py


def test_resamples_that_are_not_integers_are_refused_by_range() -> None:
    for bad in (2.5, True, "10"):
        assert python_error(lambda: rtw.sensitivity(ROOT / "nowhere.parquet", resamples=bad)).startswith(
            f"resamples: {bad!r} is invalid: must be an integer in ["
        )


def test_ctrl_c_stops_basin_and_sensitivity(ctrl_c: Press) -> None:
    # Each would run for minutes: 201 × 201 points; 10^4 resamples of every
    # output of the committed Saltelli scan (229 376 rows).
    assert ctrl_c(0.5, lambda: rtw.basin(*FIG7A, x="omega_a:-30:30:201", y="theta_b:-0.3:0.3:201", steps=60)) < 5
    committed = ROOT / "results/sensitivity/saltelli/samples.parquet"
    assert ctrl_c(0.5, lambda: rtw.sensitivity(committed, resamples=10_000)) < 10
    # Python stays usable.
    assert rtw.basin(*FIG7A, x=X, y=Y, steps=8).num_rows == 9


DESIGN5 = dict(zip(["length", "rho", "alpha", "fn", "zeta"], FIG7A[:5]))


@pytest.mark.parametrize(
    ("flag", "value"),
    [
        ("tol", "0"),
        ("tol", "1e-12"),
        ("grid", "0"),
        ("grid", "1e-9"),
        ("threads", "0"),
        ("threads", str(10**6)),
    ],
)
def test_profile_settings_get_the_same_refusal(tmp_path: Path, flag: str, value: str) -> None:
    design = [a for pair in (("--" + k, str(v)) for k, v in DESIGN5.items()) for a in pair]
    cli = cli_error("profile", *design, "--from", "0.1", "--to", "0.2", f"--{flag}", value)
    number = int(value) if flag == "threads" else float(value)
    py = python_error(lambda: rtw.profile(**DESIGN5, phi_from=0.1, phi_to=0.2, **{flag: number}))
    assert py == as_python_profile(cli)
    assert "in [" in py or "in (" in py or "at least" in py, py


@pytest.mark.parametrize(
    ("key", "value"),
    [
        ("method", '"grid"'),
        ("batch", "1"),
        ("budget", "0"),
        ("objectives", '["fastest"]'),
        ("seed", "-1"),
    ],
)
def test_design_configs_get_the_same_refusal(tmp_path: Path, key: str, value: str) -> None:
    base = (ROOT / "configs/design/widest.toml").read_text()
    lines = [line for line in base.splitlines() if not line.startswith(f"{key} =")]
    # Top-level keys go before the first table.
    at = next(i for i, line in enumerate(lines) if line.startswith("["))
    cfg = tmp_path / "bad.toml"
    cfg.write_text("\n".join([*lines[:at], f"{key} = {value}", *lines[at:]]) + "\n")
    cli = cli_error("design", str(cfg), "--out", str(tmp_path / "out"), "--quiet")
    py = python_error(lambda: rtw.design(cfg, progress=False))
    assert py == cli
    assert key in py, py


def test_ctrl_c_stops_profile_and_design(ctrl_c: Press, tmp_path: Path) -> None:
    # Each would run for minutes: a profile on a 1e-5 grid (10^4 slopes);
    # the design search of the committed config (20 000 simulations).
    assert ctrl_c(0.5, lambda: rtw.profile(**DESIGN5, phi_from=0.1, phi_to=0.2, grid=1e-5, tol=1e-6)) < 5
    out = tmp_path / "search"
    assert ctrl_c(0.5, lambda: rtw.design(ROOT / "configs/design/widest.toml", out=out, progress=False)) < 10
    # Python stays usable.
    assert rtw.profile(**DESIGN5, phi_from=0.1, phi_to=0.12, grid=0.01).runs > 0
