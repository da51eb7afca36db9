"""The PNG of a basin slice written by `rtw-scan basin` (scripts/basin.sh).

Reads FILE.parquet (one row per grid point) and draws the grid in the two
coordinates' start values: each cell coloured by what became of the point
(returns to the gait, takes every step without returning, fails, or starts
with a tip in the ground), the returning cells shaded by the step at which
they came back, and the gait's fixed point marked. Nothing is recomputed:
every number drawn is read from the file.

    python scripts/basin.py results/robustness/basin_fig7a.parquet [--out X.png] [--title TEXT]
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pyarrow.parquet as pq  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

OUTCOMES = ["returns", "survives", "fails", "infeasible"]
COLORS = ["#2ca02c", "#ff7f0e", "#d62728", "#d9d9d9"]
UNIT = {"omega": "rad/s", "theta": "rad"}
DPI = 130


def axis_label(coord: str) -> str:
    kind, rod = coord.split("_")
    symbol = {"omega": "ω", "theta": "θ"}[kind]
    return f"{symbol}_{rod} at the start [{UNIT[kind]}]"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("file", type=Path)
    ap.add_argument("--out", type=Path)
    ap.add_argument("--title", default="Basin slice")
    a = ap.parse_args()
    table = pq.read_table(a.file)
    meta = json.loads(pq.read_metadata(a.file).metadata[b"rtw.basin"])
    t = table.to_pydict()
    nx, ny = meta["x"]["points"], meta["y"]["points"]
    xs = np.array(t["x_value"]).reshape(ny, nx)[0]
    ys = np.array(t["y_value"]).reshape(ny, nx)[:, 0]
    code = np.array([OUTCOMES.index(o) for o in t["outcome"]]).reshape(ny, nx)
    steps = np.array(t["steps"], dtype=float).reshape(ny, nx)

    def edges(v: np.ndarray) -> np.ndarray:
        if len(v) == 1:
            return np.array([v[0] - 0.5, v[0] + 0.5])
        d = np.diff(v)
        return np.concatenate([[v[0] - d[0] / 2], v[:-1] + d / 2, [v[-1] + d[-1] / 2]])

    fig, ax = plt.subplots(figsize=(7.5, 5.6))
    ax.pcolormesh(edges(xs), edges(ys), code, cmap=ListedColormap(COLORS), vmin=-0.5, vmax=3.5)
    # The returning cells, darker the longer they took to come back.
    back = np.where(code == 0, steps, np.nan)
    if np.isfinite(back).any():
        m = ax.pcolormesh(edges(xs), edges(ys), back, cmap="Greens", alpha=0.55,
                          vmin=0, vmax=np.nanmax(back))
        fig.colorbar(m, ax=ax, label="steps to return (within tol)")
    ax.plot(meta["x"]["centre"], meta["y"]["centre"], "k*", ms=12, label="the gait's fixed point")
    counts = {o: int(np.sum(code == k)) for k, o in enumerate(OUTCOMES)}
    handles = [Patch(color=c, label=f"{o} ({counts[o]})") for o, c in zip(OUTCOMES, COLORS)]
    handles.append(ax.lines[0])
    ax.legend(handles=handles, loc="upper left", fontsize=8, framealpha=0.9)
    ax.set_xlabel(axis_label(meta["x"]["coord"]))
    ax.set_ylabel(axis_label(meta["y"]["coord"]))
    ax.set_title(
        f"{a.title}\n{meta['gait']} (period {meta['period']}, max |μ| {meta['floquet_max']:.3f}); "
        f"{nx}×{ny} points, ≤ {meta['steps']} steps, tol {meta['tol']:g}",
        fontsize=9,
    )
    out = a.out or a.file.with_suffix(".png")
    fig.tight_layout()
    fig.savefig(out, dpi=DPI)
    print(f"basin.py: wrote {out}")


if __name__ == "__main__":
    main()
