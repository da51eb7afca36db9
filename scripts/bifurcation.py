"""Bifurcation diagrams from `rtw-scan bifurcation` output: how the recorded
steps change as one parameter is swept.

Run through scripts/bifurcation.sh, which runs the sweeps. Reads
NAME.parquet (one row per parameter value) and NAME.steps.parquet (one row
per recorded step) as written by rtw-scan, and draws
  top:    the recorded post-impact angular velocity of the new stance rod
          (or the step time, --quantity step_time) against the parameter, as
          dots, with the gait-label bands beneath;
  bottom: the largest Floquet multiplier modulus of the solved limit cycle,
          with |mu| = 1.
Nothing is recomputed here: every number drawn is read from those files.

    python scripts/bifurcation.py results/bifurcation/phi-fig7a.parquet [--out X.png] [--title TEXT]
"""

from __future__ import annotations

import argparse
import textwrap
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import polars as pl  # noqa: E402
import pyarrow.parquet as pq  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

from rtw.draw import OUTCOME_COLOR as SCAN_COLOR  # noqa: E402  (the project's label colours)

from rtwscripts import DPI, model  # noqa: E402

# `failure`: the step map stopped (no new foot within its horizon), which the
# scan's labels have no name for.
OUTCOME_COLOR = {**SCAN_COLOR, "failure": "#c7c7c7"}

SYMBOL = {"phi": "φ [rad]", "length": "L [m]", "rho": "ρ [kg/m]", "alpha": "α", "fn": "f_n [Hz]",
          "zeta": "ζ", "s": "s = ℓ₀/r"}
QUANTITY = {"omega": "post-impact ω of the new stance rod [rad/s]", "step_time": "step time [s]"}
PERIOD_MARKER = {1: "o", 2: "s", 4: "D"}


def steps_path(points: Path) -> Path:
    return points.with_name(points.stem + ".steps.parquet")


def label_bands(ax, values: np.ndarray, labels: list[str]) -> None:
    """Each value's label as a coloured band reaching halfway to its neighbours."""
    edges = np.concatenate([[values[0] - (values[1] - values[0]) / 2],
                            (values[1:] + values[:-1]) / 2,
                            [values[-1] + (values[-1] - values[-2]) / 2]])
    for i, lab in enumerate(labels):
        ax.axvspan(edges[i], edges[i + 1], color=OUTCOME_COLOR[lab], lw=0)
    ax.set_yticks([])
    ax.set_ylabel("gait", rotation=0, ha="right", va="center")


def plot(points_file: Path, out: Path, quantity: str, title: str | None) -> Path:
    pts = pl.read_parquet(points_file).sort("value")
    steps = pl.read_parquet(steps_path(points_file))
    meta = {k.decode(): v.decode() for k, v in (pq.read_metadata(points_file).metadata or {}).items()}
    param = meta["rtw.bifurcation.param"]
    values = pts["value"].to_numpy()
    labels = [str(x) for x in pts["label"].to_list()]

    fig, (ax, axb, axm) = plt.subplots(3, 1, figsize=(8, 7.2), sharex=True,
                                       gridspec_kw=dict(height_ratios=[4, 0.35, 2.2], hspace=0.08))
    for lab in OUTCOME_COLOR:
        s = steps.filter(pl.col("label").cast(pl.Utf8) == lab)
        if s.height:
            ax.scatter(s["value"].to_numpy(), s[quantity].to_numpy(), s=2.5, color=OUTCOME_COLOR[lab],
                       lw=0, rasterized=True)
    ax.set_ylabel(QUANTITY[quantity])
    ax.grid(alpha=0.3)
    # The title's second line names the model of the data drawn, read from
    # its rtw.variant, so that it cannot drift from the data.
    title = "\n".join([title or f"bifurcation diagram in {param}",
                       *textwrap.wrap(f"model: {model(meta['rtw.variant'])}", 115)])
    ax.set_title(title, fontsize=8.5)

    label_bands(axb, values, labels)
    present = [lab for lab in OUTCOME_COLOR if lab in labels]
    ax.legend(handles=[Patch(color=OUTCOME_COLOR[lab], label=lab) for lab in present], loc="upper right",
              ncol=len(present), fontsize=8, title="gait (dots and band)", title_fontsize=8)

    solved = pts.filter(pl.col("floquet_max").is_not_null())
    for period in sorted(set(solved["period"].to_list())):
        marker = PERIOD_MARKER.get(period, "^")
        for stable in (True, False):
            s = solved.filter((pl.col("period") == period) & (pl.col("stable") == stable))
            if s.height:
                axm.scatter(s["value"].to_numpy(), s["floquet_max"].to_numpy(), s=14, marker=marker,
                            edgecolors="#333333", facecolors="#333333" if stable else "white",
                            label=f"period {period}" + ("" if stable else ", unstable"))
    axm.axhline(1.0, color="#d62728", lw=1, ls="--", label="|μ| = 1")
    axm.set_ylabel("max |μ| (Floquet)")
    axm.set_xlabel(SYMBOL.get(param, param))
    lo = min(0.0, float(solved["floquet_max"].min() or 0.0))
    hi = max(1.1, float(solved["floquet_max"].max() or 1.0) * 1.05)
    axm.set_ylim(lo, hi)
    axm.grid(alpha=0.3)
    axm.legend(fontsize=8, loc="lower left", ncol=4)
    axm.set_xlim(values[0] - (values[1] - values[0]) / 2, values[-1] + (values[-1] - values[-2]) / 2)
    foot = (f"rtw-scan bifurcation: {len(values)} values, transient {meta['rtw.bifurcation.transient']}, "
            f"record {meta['rtw.bifurcation.record']} steps; model: {meta['rtw.variant']}")
    fig.text(0.5, 0.005, foot, ha="center", fontsize=6.5, color="#444444", wrap=True)
    fig.subplots_adjust(left=0.11, right=0.98, top=0.91, bottom=0.09)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=DPI, metadata={"Title": title.replace("\n", " ")})
    plt.close(fig)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("points", type=Path, help="NAME.parquet written by rtw-scan bifurcation")
    ap.add_argument("--out", type=Path, help="PNG [default: NAME.png beside it]")
    ap.add_argument("--quantity", choices=sorted(QUANTITY), default="omega")
    ap.add_argument("--title")
    a = ap.parse_args()
    out = plot(a.points, a.out or a.points.with_suffix(".png"), a.quantity, a.title)
    print(out)


if __name__ == "__main__":
    main()
