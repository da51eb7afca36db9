"""scripts/time_budget.py recovers the costs it fits from samples whose
times are made from known costs (the reference is the construction itself)."""

import importlib.util
from pathlib import Path

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

ROOT = Path(__file__).resolve().parents[3]


def load_script():
    spec = importlib.util.spec_from_file_location("time_budget", ROOT / "scripts" / "time_budget.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_recovers_known_costs(tmp_path):
    rng = np.random.default_rng(7)
    n = 1000
    rhs = rng.integers(200, 20000, n).astype(np.uint64)
    events = (rhs / rng.uniform(15.0, 60.0, n)).astype(np.uint64)
    # 120 ns per RHS evaluation, 2.4 µs per event, 100 µs per sample, 1 % noise.
    exact = 120e-9 * rhs + 2.4e-6 * events + 100e-6
    wall = exact * (1.0 + 0.01 * rng.standard_normal(n))
    path = tmp_path / "samples.parquet"
    pq.write_table(pa.table({"rhs_evals": rhs, "events": events, "wall_time_s": wall}), path)

    coef, share, r2, total, count = load_script().fit(path)

    assert count == n
    assert abs(total - wall.sum()) < 1e-12 * wall.sum()
    assert abs(coef[0] / 120e-9 - 1) < 0.02
    assert abs(coef[1] / 2.4e-6 - 1) < 0.05
    assert abs(coef[2] / 100e-6 - 1) < 0.2
    assert abs(share.sum() - 1) < 1e-9  # least squares with a constant: residuals sum to 0
    assert r2 > 0.99
