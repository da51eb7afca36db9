#!/usr/bin/env python3
"""Checks that two rtw-scan outputs hold identical rows: every value of every
column, compared bit for bit (floats by their IEEE-754 bits, so NaN == NaN and
0.0 != -0.0; nulls only equal nulls), except `wall_time_s`.

`wall_time_s` is the one column that is not a function of (seed, sample_id):
it is the measured time one simulation took on whatever machine ran it. Every
other column (inputs, derived parameters, outcome, metrics, integrator work
counts) is deterministic and must match exactly.

Usage:
    python scripts/compare_scans.py A B

A and B are Parquet files, or globs such as 'DIR/part-*.parquet', read with
polars.scan_parquet (the parts of a sharded scan, read directly) and ordered by
sample_id. For plain files the `rtw.config_hash` metadata must match as well.
Exits 0 when identical, 1 otherwise; the last line reads
"compare_scans: N passed, M failed".
"""

import struct
import sys

import polars as pl
import pyarrow.parquet as pq

# The one non-deterministic column (see the module docstring).
TIMING = {"wall_time_s"}


def load(spec):
    if any(c in spec for c in "*?["):
        df = pl.scan_parquet(spec).collect().sort("sample_id")
    else:
        df = pl.read_parquet(spec)
    return df.to_arrow()


def canonical(value):
    """A value whose == is bit equality for floats."""
    if isinstance(value, float):
        return ("f64", struct.pack("<d", value))
    return (type(value).__name__, value)


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    a_spec, b_spec = argv[1], argv[2]
    a, b = load(a_spec), load(b_spec)
    passed = failed = 0

    def check(ok, what):
        nonlocal passed, failed
        if ok:
            passed += 1
        else:
            failed += 1
            print(f"FAIL: {what}")
        return ok

    check(a.num_rows > 0, f"{a_spec} has rows")
    check(a.num_rows == b.num_rows, f"row counts {a.num_rows} vs {b.num_rows}")
    check(a.column_names == b.column_names, f"columns {a.column_names} vs {b.column_names}")
    compared = 0
    for name in a.column_names:
        if name in TIMING or name not in b.column_names:
            continue
        va = [canonical(v) for v in a.column(name).to_pylist()]
        vb = [canonical(v) for v in b.column(name).to_pylist()]
        bad = [i for i, (x, y) in enumerate(zip(va, vb)) if x != y]
        if check(not bad and len(va) == len(vb), f"column {name} differs at rows {bad[:5]}"):
            compared += len(va)
    ids = a.column("sample_id").to_pylist()
    check(ids == list(range(len(ids))), f"{a_spec}: sample_id runs 0..{len(ids) - 1}")

    plain = [s for s in (a_spec, b_spec) if not any(c in s for c in "*?[")]
    if len(plain) == 2:
        ha, hb = (pq.read_metadata(s).metadata.get(b"rtw.config_hash") for s in plain)
        check(ha is not None and ha == hb, f"rtw.config_hash {ha} vs {hb}")
    print(
        f"compared {compared} values in {a.num_rows} rows x "
        f"{len([c for c in a.column_names if c not in TIMING])} columns ({', '.join(sorted(TIMING))} left out)"
    )
    print(f"compare_scans: {passed} passed, {failed} failed")
    return 0 if failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
