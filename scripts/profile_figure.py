"""The figure of a slope profile (`rtw-scan profile --out FILE.parquet`):
the gait against φ (a band per label, each simulated slope a tick), with the
speed and the step frequency f_w of every simulated slope below it, and the
located changes as vertical lines (dashed where a change is not sharp).

Reads only the profile's Parquet file (its rows and, from its metadata
`rtw.profile`, the changes), so the figure shows what the file holds.

Usage: .venv/bin/python scripts/profile_figure.py FILE.parquet [OUT.png]
(default OUT: FILE.png beside it).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pyarrow.parquet as pq  # noqa: E402

from rtwscripts.labels import COLOURS, FAILED, OUTCOMES, STABLE  # noqa: E402

# The gait axis from the bottom: the failures, the stable gaits from the
# slowest (crawl) up, then whatever else a run can end as (diverged).
LABELS = [*FAILED, *STABLE[::-1], *(o for o in OUTCOMES if o not in FAILED and o not in STABLE)]


def main() -> int:
    if len(sys.argv) not in (2, 3):
        print(__doc__, file=sys.stderr)
        return 2
    src = Path(sys.argv[1])
    out = Path(sys.argv[2]) if len(sys.argv) == 3 else src.with_suffix(".png")
    meta = pq.read_metadata(src).metadata or {}
    if b"rtw.profile" not in meta:
        sys.exit(f"profile_figure: {src} is not a slope profile (no rtw.profile in its metadata)")
    profile = json.loads(meta[b"rtw.profile"])
    t = pq.read_table(src, columns=["phi", "outcome", "speed", "f_w"]).to_pydict()
    phi, label, speed, f_w = t["phi"], [str(o) for o in t["outcome"]], t["speed"], t["f_w"]
    d = profile["design"]

    fig, (ax_gait, ax_speed, ax_fw) = plt.subplots(
        3, 1, figsize=(8, 6.5), sharex=True, gridspec_kw={"height_ratios": [1.1, 1, 1]}
    )
    shown = [l for l in LABELS if l in label]
    for seg in profile["segments"]:
        y = shown.index(seg["label"])
        ax_gait.plot([seg["lo"], seg["hi"]], [y, y], lw=8, solid_capstyle="butt", color=COLOURS[seg["label"]])
    ax_gait.scatter(phi, [shown.index(l) for l in label], marker="|", s=60, color="0.2", lw=0.6, zorder=3)
    ax_gait.set_yticks(range(len(shown)), shown)
    ax_gait.set_ylim(-0.6, len(shown) - 0.4)
    ax_gait.set_ylabel("gait")
    ax_gait.set_title(
        f"L = {d['length']} m, ρ = {d['rho']} kg/m, α = {d['alpha']}, f_n = {d['fn']} Hz, ζ = {d['zeta']}: "
        f"{profile['runs']} runs, changes to {profile['tol']:g} rad",
        fontsize=9,
    )
    stable = [i for i, l in enumerate(label) if l in STABLE]
    for ax, values, name in ((ax_speed, speed, "speed [m/s]"), (ax_fw, f_w, "step frequency f_w [Hz]")):
        for l in shown:
            idx = [i for i in stable if label[i] == l and values[i] is not None]
            if idx:
                ax.plot([phi[i] for i in idx], [values[i] for i in idx], ".", ms=3, color=COLOURS[l], label=l)
        ax.set_ylabel(name)
        ax.grid(alpha=0.3)
    ax_speed.legend(loc="upper left", fontsize=8, markerscale=3)
    for c in profile["changes"]:
        mid = 0.5 * (c["phi_left"] + c["phi_right"])
        for ax in (ax_gait, ax_speed, ax_fw):
            ax.axvline(mid, color="0.5", lw=0.5, ls="-" if c["sharp"] else ":")
    if profile["phi_lo"] is not None:
        ax_gait.axvspan(profile["phi_lo"], profile["phi_hi"], color="0.9", zorder=0)
    ax_fw.set_xlabel("slope φ [rad]")
    ax_fw.set_xlim(profile["from"], profile["to"])
    fig.tight_layout()
    fig.savefig(out, dpi=130)
    print(f"profile_figure: wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
