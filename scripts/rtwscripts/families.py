"""The design atlas's gait families (docs/design-atlas.md): for walk, skip and
crawl, the winner of each of four searches run for that gait alone
(GAIT-ROLE, scripts/design_atlas.sh), each re-simulated directly, with the
Fig. 7(a) design on the same axes.

- widest: the widest interval of the gait (configs/design/widest.toml; the
  walk's is widest-walk);
- shallowest: the shallowest slope of the gait, the lowest cost of
  transport (sin φ);
- fastest: the largest speed at φ = 0.15 in the gait;
- robust: the largest MFPT at φ = 0.15 in the gait on a 5 cm rough slope.

Each winner is one of its search's reported designs (each interval checked
by the library for the gait, search::check), picked by simulating it
again: its gait and speed at φ = 0.15, its MFPT there on the searches' draw
of the ground and on fresh draws, and its profile over the whole slope
axis. What sets the families apart is read from the paper scan's samples
(results/paper/samples.parquet), which no search chose."""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Callable

import matplotlib.pyplot as plt
import numpy as np
import pyarrow.parquet as pq

from .labels import COLOURS

GAITS = ("walk", "skip", "crawl")
ROLES = ("widest", "shallowest", "fastest", "robust")
# The profile behind each winner's strip: the whole slope axis of the
# searches, from level ground, on the atlas's fine grid.
SPAN = (0.0, 0.8, 0.002, 1e-4)


def search_name(gait: str, role: str) -> str:
    return "widest-walk" if (gait, role) == ("walk", "widest") else f"{gait}-{role}"


# The roles judged at φ = 0.15 by direct simulation need no interval of the
# gait, so the designs a search of any gait reported for the same goal are
# candidates too: a search of the gait alone, with a small budget (robust:
# a few dozen designs), can miss a design the other found.
POOLED = {"fastest": "front", "robust": "robust"}


def winners(search: Path, out: Path, at_speed_phi: Callable, label_at: Callable, mfpt: Callable,
            fresh: tuple[int, ...]) -> list[dict]:
    """Each family's winner of each role (None where the search reported
    no design of that gait), its reported designs copied to
    OUT/designs-NAME.parquet. Each winner is simulated again at its
    shallowest slope of the gait (`label_at_phi_min`), at φ = 0.15 and, on
    the rough slope, there."""
    rows = []
    for g in GAITS:
        for role in ROLES:
            name = search_name(g, role)
            shutil.copyfile(search / name / "designs.parquet", out / f"designs-{name}.parquet")
            cands = []
            for source in [name, *([POOLED[role]] if role in POOLED else [])]:
                for i, r in enumerate(pq.read_table(search / source / "designs.parquet").to_pylist()):
                    label, speed = at_speed_phi(r)
                    cands.append({**r, "from": f"{source}-{i + 1}", "label_at_0.15": label,
                                  "speed_at_0.15": speed})
            found = sum(c["from"].rsplit("-", 1)[0] == name for c in cands)
            # A winner at φ = 0.15 must be in its gait there.
            at = [c for c in cands if c["label_at_0.15"] == g]
            if role == "widest":
                best = max(cands, key=lambda c: c["slope_range"], default=None)
            elif role == "shallowest":
                best = min(cands, key=lambda c: c["phi_min"], default=None)
            elif role == "fastest":
                best = max(at, key=lambda c: c["speed_at_0.15"], default=None)
            else:
                for c in at:
                    c["mfpt_at_0.15"] = mfpt(c)
                best = max(at, key=lambda c: c["mfpt_at_0.15"] or 0.0, default=None)
            if best is not None:
                best["label_at_phi_min"] = label_at(best, best["phi_min"])
                if "mfpt_at_0.15" not in best:
                    best["mfpt_at_0.15"] = mfpt(best)
                best["mfpt_fresh"] = [mfpt(best, s) if best["mfpt_at_0.15"] is not None else None for s in fresh]
            rows.append({"family": g, "role": role, "search": name, "found": found, "design": best})
    return rows


def strips(ax, entries: list[tuple[str, dict]]) -> None:
    """Each profile as a strip of its gait along φ, its checked interval
    outlined (dashed when checked for any stable gait); the first entry on
    top."""
    n = len(entries)
    for k, (name, prof) in enumerate(entries):
        y = n - 1 - k
        phi = np.array(prof["phi"])
        lab = prof["outcome"]
        edges = np.concatenate([[phi[0]], 0.5 * (phi[1:] + phi[:-1]), [phi[-1]]])
        for i, o in enumerate(lab):
            ax.broken_barh([(edges[i], edges[i + 1] - edges[i])], (y - 0.35, 0.7), color=COLOURS.get(o, "0.5"),
                           lw=0)
        lo, hi = prof["interval"]
        if lo is not None:
            # Dashed: an interval checked for any stable gait, not this one.
            ax.add_patch(plt.Rectangle((lo, y - 0.42), hi - lo, 0.84, fill=False, ec="k", lw=1.2,
                                       ls="--" if prof["gait"] == "any" else "-"))
    ax.set_yticks(range(n), [e[0] for e in entries][::-1], fontsize=8)
    ax.set_xlim(SPAN[0], SPAN[1])
    ax.set_ylim(-0.6, n - 0.4)
    ax.set_xlabel("slope φ [rad]")
    handles = [plt.Rectangle((0, 0), 1, 1, color=COLOURS[o]) for o in COLOURS if o != "diverged"]
    ax.legend(handles, [o for o in COLOURS if o != "diverged"], fontsize=7, loc="upper center",
              bbox_to_anchor=(0.5, -0.11), ncols=5, frameon=False)


def scatter(ax, samples: Path, rows: list[dict], fig7a: dict) -> None:
    """The winners on the two inputs that set the families apart (α, f_n),
    over the paper scan's samples of each gait."""
    t = pq.read_table(samples, columns=["alpha", "fn", "outcome"]).to_pydict()
    lab = np.array(t["outcome"], dtype=object)
    for g in GAITS:
        m = lab == g
        ax.scatter(np.array(t["alpha"])[m], np.array(t["fn"])[m], s=14 if g == "crawl" else 7, c=COLOURS[g],
                   alpha=0.6 if g == "crawl" else 0.3, lw=0)
    marks = {"widest": "s", "shallowest": "v", "fastest": ">", "robust": "o"}
    for row in rows:
        d = row["design"]
        if d is not None:
            ax.scatter([d["alpha"]], [d["fn"]], marker=marks[row["role"]], s=60, c=COLOURS[row["family"]],
                       edgecolors="k", zorder=4)
    ax.scatter([fig7a["alpha"]], [fig7a["fn"]], marker="*", s=220, c="tab:red", edgecolors="k", zorder=5,
               label="Fig. 7(a)")
    for role, m in marks.items():
        ax.scatter([], [], marker=m, c="w", edgecolors="k", label=role)
    ax.set_xlabel("connection ratio α")
    ax.set_ylabel("frequency f_n [Hz]")
    ax.legend(fontsize=7, loc="lower right")


def apart(samples: Path, inputs: list[str]) -> list[str]:
    """The median and interquartile range of each input and of φ among the
    paper scan's samples of each gait."""
    t = pq.read_table(samples, columns=[*inputs, "phi", "outcome"]).to_pydict()
    lab = np.array(t["outcome"], dtype=object)
    md = ["| gait | samples | " + " | ".join(f"{k}: median [IQR]" for k in [*inputs, "phi"]) + " |",
          "|---|---:|" + "---:|" * (len(inputs) + 1)]
    for g in GAITS:
        m = lab == g
        cells = []
        for k in [*inputs, "phi"]:
            q = np.percentile(np.array(t[k], dtype=float)[m], [25, 50, 75])
            cells.append(f"{q[1]:.3g} [{q[0]:.3g}, {q[2]:.3g}]")
        md.append(f"| {g} | {int(m.sum())} | " + " | ".join(cells) + " |")
    return md
