#!/usr/bin/env python3
"""Checks that an rtw-scan samples.parquet reads correctly in pandas, polars
and pyarrow: `outcome` is categorical in both data-frame libraries, the
parameters are float64, the row count matches the stored config, and the file
metadata holds the config (TOML), the seed, the version and the variant.

Usage:
    python scripts/check_parquet.py SAMPLES.parquet [--rows N]

Without --rows, the expected row count is computed from the config stored in
the file (product of grid sizes x samples). Exits 0 when every check passes,
1 otherwise; the last line reads "check_parquet: N passed, M failed".
"""

import argparse
import math
import re
import sys
import tomllib
from pathlib import Path

import pandas as pd
import polars as pl
import pyarrow as pa
import pyarrow.parquet as pq

PARAMS = ["length", "rho", "alpha", "fn", "zeta", "phi"]
DERIVED = ["m", "l_c", "inertia", "r", "k", "c"]


def documented_labels() -> set[str]:
    """The labels docs/data-dictionary.md gives `outcome` ("gait (skip, walk,
    crawl) or failure (collapse, stall, diverged)"): this check runs before the
    package rtw (whose LABELS the other scripts use) is installed, and holds
    the data to what the dictionary promises."""
    doc = (Path(__file__).resolve().parent.parent / "docs/data-dictionary.md").read_text()
    row = next((line for line in doc.splitlines() if line.startswith("| `outcome` | string (dictionary) |")), None)
    # The row's last cell, its meaning: `| name | type | unit | meaning |`.
    groups = re.findall(r"\(([a-z, ]+)\)", row.rstrip(" |").rsplit(" | ", 1)[-1] if row else "")
    if not groups:
        sys.exit("check_parquet: docs/data-dictionary.md has no `outcome` row naming its labels in parentheses")
    return {label.strip() for g in groups for label in g.split(",")}


LABELS = documented_labels()


class Checks:
    def __init__(self):
        self.passed = 0
        self.failed = 0

    def check(self, ok, what):
        if ok:
            self.passed += 1
            print(f"ok:   {what}")
        else:
            self.failed += 1
            print(f"FAIL: {what}")
        return ok


def grid_size(axis):
    """Number of grid points of one [params] entry."""
    if isinstance(axis, list):
        return len(axis)
    if isinstance(axis, dict) and "linspace" in axis:
        return int(axis["linspace"][2])
    return 1


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("samples", help="samples.parquet written by `rtw-scan run`")
    ap.add_argument("--rows", type=int, help="expected row count (default: from the stored config)")
    args = ap.parse_args()
    c = Checks()

    # pyarrow: metadata and schema.
    meta = pq.read_metadata(args.samples)
    kv = {k.decode(): v.decode() for k, v in (meta.metadata or {}).items()}
    for key in ["rtw.config", "rtw.seed", "rtw.version", "rtw.variant"]:
        c.check(key in kv, f"pyarrow: metadata has {key}")
    config = tomllib.loads(kv.get("rtw.config", ""))
    c.check(str(config.get("seed")) == kv.get("rtw.seed"), "metadata: rtw.config parses as TOML and its seed is rtw.seed")
    c.check(set(config.get("params", {})) == set(PARAMS), "metadata: the config names the six parameters")
    expected = args.rows
    if expected is None:
        expected = config.get("samples", 0) * math.prod(grid_size(a) for a in config.get("params", {}).values())
    c.check(meta.num_rows == expected, f"pyarrow: {meta.num_rows} rows, expected {expected}")
    schema = pq.read_schema(args.samples)
    outcome_type = schema.field("outcome").type
    c.check(
        pa.types.is_dictionary(outcome_type)
        and outcome_type.index_type == pa.int32()
        and pa.types.is_string(outcome_type.value_type),
        f"pyarrow: outcome is dictionary<int32, string> ({outcome_type})",
    )
    c.check(schema.field("sample_id").type == pa.int64(), "pyarrow: sample_id is int64")

    # pandas.
    df = pd.read_parquet(args.samples)
    c.check(len(df) == expected, f"pandas: {len(df)} rows, expected {expected}")
    c.check(isinstance(df["outcome"].dtype, pd.CategoricalDtype), f"pandas: outcome is categorical ({df['outcome'].dtype})")
    c.check(set(df["outcome"].astype(str)) <= LABELS, "pandas: outcome values are rtw labels")
    bad = [col for col in PARAMS + DERIVED if df[col].dtype != "float64"]
    c.check(not bad, f"pandas: parameters are float64 {bad or ''}")
    c.check(list(df["sample_id"]) == list(range(expected)), "pandas: sample_id runs 0..rows in order")

    # polars.
    pf = pl.read_parquet(args.samples)
    c.check(pf.height == expected, f"polars: {pf.height} rows, expected {expected}")
    dtype = pf.schema["outcome"]
    c.check(dtype == pl.Categorical or isinstance(dtype, (pl.Categorical, pl.Enum)), f"polars: outcome is categorical ({dtype})")
    bad = [col for col in PARAMS + DERIVED if pf.schema[col] != pl.Float64]
    c.check(not bad, f"polars: parameters are Float64 {bad or ''}")
    c.check(
        pf["outcome"].cast(pl.Utf8).to_list() == df["outcome"].astype(str).tolist(),
        "polars and pandas read the same outcomes",
    )

    print(f"check_parquet: {c.passed} passed, {c.failed} failed")
    return 0 if c.failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
