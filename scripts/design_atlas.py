"""The design atlas (docs/design.md), from the searches in SEARCH/NAME/
(`rtw-scan design configs/design/NAME.toml --out SEARCH/NAME`):

- the winners: the widest stable slope range (`widest`), the widest walk
  (`widest-walk`), the shallowest stable slope (`shallowest`), the largest
  mean first-passage time at φ = 0.15 on a 5 cm rough slope (`robust`) and the
  Pareto front of slope range against speed at φ = 0.15 (`front`), each as
  its search reported it (profiled again on the fine grid);
- the article's Fig. 7(a) design on the same axes, judged by the same
  search code (configs/design/fig7a.toml, a box of one point);
- the winners' and Fig. 7(a)'s MFPT at φ = 0.15 and σ = 5 cm on the draw
  of the ground the searches used (terrain.seed 0) and on fresh draws
  (FRESH_SEEDS), where the `robust` search's pick of its largest estimate
  cannot have favoured them;
- each winner's fine profile (`rtw-scan profile --out`, grid 0.002, tol
  1e-4) and its figure (scripts/profile_figure.py), and an animation of its
  gait (`python -m rtw animate`);
- OUT/designs-NAME.parquet: each search's reported designs as rtw-scan
  wrote them (`rho`, `alpha`, `fn`, `zeta`, `phi_lo`, `phi_hi`: the fine
  profile's widest interval, checked by direct simulation and cut to its
  widest run of checked slopes with no failure, docs/design.md), the
  Fig. 7(a) design's too (`designs-fig7a.parquet`, configs/design/fig7a.toml);
- OUT/atlas.png and OUT/atlas.md: the front with Fig. 7(a), the winners'
  designs in the box, and the rank correlations of each input with the
  slope range and the shallowest slope over the Sobol designs of the widest
  config (`widest-sobol`, a sample of the box that no search biased);
- OUT/families.png and OUT/families.md: the gait families
  (rtwscripts/families.py), each family's winners along φ with Fig. 7(a).

Usage: .venv/bin/python scripts/design_atlas.py SEARCH OUT
"""

from __future__ import annotations

import functools
import json
import shutil
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pyarrow.parquet as pq  # noqa: E402
from scipy.stats import spearmanr  # noqa: E402

from rtwscripts import families  # noqa: E402
from rtwscripts.labels import STABLE  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
BIN = ROOT / "target/release/rtw-scan"
FIG7A = {"rho": 2.5, "alpha": 0.125, "fn": 3.269, "zeta": 0.0514}
INPUTS = ["rho", "alpha", "fn", "zeta"]
BOX = {"rho": (1.0, 5.0), "alpha": (0.0, 0.4), "fn": (1.5, 5.0), "zeta": (0.05, 0.1)}
SPEED_PHI = 0.15
FROM, TO = 0.01, 0.8


def flags(d: dict) -> list[str]:
    out = ["--length", "0.8"]
    for k in INPUTS:
        out += [f"--{k}", repr(float(d[k]))]
    return out


def cli(*args: str) -> str:
    return subprocess.run([str(BIN), *args], check=True, capture_output=True, text=True).stdout


@functools.cache
def _simulated(design: tuple[float, ...], *args: str) -> dict:
    """`rtw-scan simulate --json` of the design (its INPUTS in order) with
    `args`, once: the winners of the atlas and of its gait families are
    judged on the same designs (the `front` and `robust` searches' among
    them), and a run is deterministic."""
    return json.loads(cli("simulate", *flags(dict(zip(INPUTS, design))), *args, "--json"))


def simulated(d: dict, *args: str) -> dict:
    return _simulated(tuple(float(d[k]) for k in INPUTS), *args)


def at_speed_phi(d: dict) -> tuple[str, float | None]:
    """The gait at φ = 0.15 and its speed (none unless the gait is stable)."""
    v = simulated(d, "--phi", str(SPEED_PHI))
    stable = v["outcome"] in STABLE
    return v["outcome"], v.get("speed") if stable else None


def label_at(d: dict, phi: float) -> str:
    """The design's gait (or failure) at slope `phi`, simulated directly."""
    return simulated(d, "--phi", repr(float(phi)))["outcome"]


# The searches judge the MFPT on the rough slope of terrain.seed 0. The
# winners are judged again on these fresh draws: a search that keeps the
# largest of noisy estimates favours designs that were lucky on its draw.
FRESH_SEEDS = (100, 200)


def mfpt_at_speed_phi(d: dict, seed: int = 0) -> float | None:
    """The MFPT at φ = 0.15 on a rough slope of σ = 5 cm drawn from
    terrain.seed `seed` (none unless stable there)."""
    v = simulated(d, "--phi", str(SPEED_PHI), "--set", "robustness.mfpt=true", "--set", "robustness.sigma=0.05",
                  "--set", f"terrain.seed={seed}")
    return v.get("mfpt") if v["outcome"] in STABLE else None


def profile(d: dict, out: Path | None = None, span: tuple[float, float, float, float] | None = None) -> dict:
    """The design's profile over (from, to, grid, tol): by default the searches' slopes on their fine grid."""
    lo, hi, grid, tol = span or (FROM, TO, 0.002, 1e-4)
    args = ["profile", *flags(d), "--from", str(lo), "--to", str(hi), "--grid", str(grid), "--tol", str(tol),
            "--json", "--quiet"]
    if out is not None:
        args += ["--out", str(out), "--force"]
    return json.loads(cli(*args))


def ends(r: dict) -> str:
    """The gait an interval was checked for and how it ends at phi_lo and phi_hi."""
    if r.get("phi_lo_end") is None:
        return f"{r['gait']}; –"
    return f"{r['gait']}; {r['phi_lo_end']}, {r['phi_hi_end']}"


def main() -> None:
    search, out = Path(sys.argv[1]), Path(sys.argv[2])
    roles = {"widest": "widest stable slope range", "widest-walk": "widest walking slope range",
             "shallowest": "shallowest stable slope", "robust": "largest MFPT at 0.15, σ = 5 cm",
             "front": "Pareto front: slope range vs speed at 0.15"}
    rows = []
    for name in list(roles) + ["fig7a"]:
        t = pq.read_table(search / name / "designs.parquet").to_pylist()
        for i, r in enumerate(t):
            label, speed = at_speed_phi(r)
            rows.append({"role": f"{name}-{i + 1}" if name != "fig7a" else "Fig. 7(a)", "search": name,
                         "length": r["length"], **{k: r[k] for k in INPUTS}, "phi_lo": r["phi_lo"],
                         "phi_hi": r["phi_hi"], "slope_range": r["slope_range"], "phi_min": r["phi_min"],
                         "checked_slopes": r["checked_slopes"], "checked_failures": r["checked_failures"],
                         "ends": ends(r), "gait": r["gait"],
                         "label_at_0.15": label, "speed_at_0.15": speed})
        # The reported designs as rtw-scan wrote them (each interval checked
        # by direct simulation in the library, search::check).
        shutil.copyfile(search / name / "designs.parquet", out / f"designs-{name}.parquet")
    fig7a = rows.pop()
    speed7 = fig7a["speed_at_0.15"]

    # The winners: of each single-objective search's reported designs, the
    # widest checked interval (the shallowest phi_min for `shallowest`).
    def winner(name: str) -> dict:
        mine = [x for x in rows if x["search"] == name]
        if name == "shallowest":
            return min(mine, key=lambda x: x["phi_min"])
        if name == "robust":
            return max(mine, key=lambda x: x["mfpt_at_0.15"] or 0.0)
        return max(mine, key=lambda x: x["slope_range"])

    for r in rows + [fig7a]:
        r["mfpt_at_0.15"] = mfpt_at_speed_phi(r) if r["search"] in ("widest", "widest-walk", "shallowest", "robust", "fig7a") \
            else None
    winners = {name: winner(name) for name in ["widest", "widest-walk", "shallowest", "robust"]}
    for r in list(winners.values()) + [fig7a]:
        r["mfpt_fresh"] = [mfpt_at_speed_phi(r, s) if r["mfpt_at_0.15"] is not None else None for s in FRESH_SEEDS]

    # The winners' fine profiles, figures and animations.
    for name, r in winners.items():
        path = out / f"profile-{name}.parquet"
        # The shallowest from φ = 0, as its search profiled it, on a finer grid.
        profile(r, path, (0.0, 0.1, 0.0005, 1e-5) if name == "shallowest" else None)
        subprocess.run([sys.executable, str(ROOT / "scripts/profile_figure.py"), str(path)], check=True)
        phi = {"shallowest": r["phi_min"] + 0.002, "robust": SPEED_PHI}.get(name, 0.5 * (r["phi_lo"] + r["phi_hi"]))
        trace = ROOT / f"runs/design/trace-{name}.parquet"
        cli("simulate", *flags(r), "--phi", f"{phi:.4f}", "--set", "trace_dt=0.01", "--set", "t_max=8.0",
            "--trace", str(trace))
        subprocess.run([sys.executable, "-m", "rtw", "animate", str(trace), str(out / f"{name}.gif"),
                        "--start", "4", "--duration", "3.5", "--fps", "15", "--width", "320"], check=True)

    # What sets them apart: rank correlations over the unbiased Sobol designs.
    sob = pq.read_table(search / "widest-sobol" / "search.parquet").to_pydict()
    corr = []
    for k in INPUTS:
        x = np.array(sob[k])
        rng = np.array([np.nan if v is None else v for v in sob["slope_range"]], dtype=float)
        pm = np.array([np.nan if v is None else v for v in sob["phi_min"]], dtype=float)
        ok = ~np.isnan(rng)
        r1 = spearmanr(x[ok], rng[ok])
        r2 = spearmanr(x[ok], pm[ok])
        corr.append((k, r1.statistic, r1.pvalue, r2.statistic, r2.pvalue, int(ok.sum())))

    # The figure: the front's search with Fig. 7(a); the winners in the box.
    ev = pq.read_table(search / "front" / "search.parquet").to_pydict()
    feas = np.array(ev["feasible"])
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.8))
    sr = np.array([np.nan if v is None else v for v in ev["slope_range"]], dtype=float)
    sp = np.array([np.nan if v is None else v for v in ev["speed"]], dtype=float)
    a.scatter(sr[feas], sp[feas], s=8, c="0.75", label="designs evaluated (feasible)")
    front = [x for x in rows if x["search"] == "front"]
    pts = sorted((x["slope_range"], x["speed_at_0.15"]) for x in front if x["speed_at_0.15"] is not None)
    a.plot([p[0] for p in pts], [p[1] for p in pts], "o", c="tab:blue",
           label="front's reported designs (interval checked)")
    a.scatter([fig7a["slope_range"]], [speed7], marker="*", s=220, c="tab:red", label="Fig. 7(a) design", zorder=5)
    for name, m in [("widest", "s"), ("shallowest", "v"), ("widest-walk", "D")]:
        r = winners[name]
        if r["speed_at_0.15"] is not None:
            a.scatter([r["slope_range"]], [r["speed_at_0.15"]], marker=m, s=70, c="k", label=name, zorder=4)
    a.set_xlabel("widest stable slope range phi_hi − phi_lo [rad]")
    a.set_ylabel(f"speed at φ = {SPEED_PHI} [m/s]")
    a.set_title("Slope range against speed (default model, L = 0.8 m)")
    a.legend(fontsize=8)
    shown = [("widest", "k", "s"), ("widest-walk", "tab:green", "D"), ("shallowest", "tab:purple", "v")]
    xs = np.arange(len(INPUTS))
    for x in front:
        b.plot(xs, [(x[k] - BOX[k][0]) / (BOX[k][1] - BOX[k][0]) for k in INPUTS], c="tab:blue", alpha=0.4)
    for name, c, m in shown:
        r = winners[name]
        b.plot(xs, [(r[k] - BOX[k][0]) / (BOX[k][1] - BOX[k][0]) for k in INPUTS], marker=m, c=c, label=name)
    b.plot(xs, [(FIG7A[k] - BOX[k][0]) / (BOX[k][1] - BOX[k][0]) for k in INPUTS], marker="*", ms=12,
           c="tab:red", label="Fig. 7(a)")
    b.set_xticks(xs, [f"{k}\n[{BOX[k][0]}, {BOX[k][1]}]" for k in INPUTS])
    b.set_ylabel("place in the article's box (0 = low end)")
    b.set_title("The winners' designs (front in blue)")
    b.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "atlas.png", dpi=110)

    def f(v, d=4):
        return "–" if v is None else f"{v:.{d}f}"

    md = ["# Design atlas (default model, L = 0.8 m)\n",
          "`./scripts/design_atlas.sh`: the searches of `configs/design/` (budget and seed in each config), "
          "each reported design profiled again on a five times finer grid and its interval checked by direct "
          "simulation (`results/design/designs-NAME.parquet`); the speed and gait at φ = 0.15 by "
          "`rtw-scan simulate`. The Fig. 7(a) design judged as the searches judge theirs (`configs/design/fig7a.toml`).\n",
          "## Winners\n",
          "Of each single-objective search's reported designs (its best 20 by the search's own profile), the "
          "one with the widest checked interval (`widest`, `widest-walk`; the shallowest `phi_min` for "
          "`shallowest`, the largest MFPT for `robust`); the role names its rank in the search. The MFPT by "
          "`rtw-scan simulate --phi 0.15 --set robustness.mfpt=true --set robustness.sigma=0.05` on the rough "
          "slope of terrain.seed 0, which the `robust` search judged its designs on, and again on fresh draws "
          f"(`--set terrain.seed=S`, S = {', '.join(map(str, FRESH_SEEDS))}): the largest of noisy estimates "
          "is biased upwards, and a fresh draw is not.\n",
          "| role | ρ | α | f_n | ζ | phi_lo | phi_hi | slope range | phi_min | gait at 0.15 | speed at 0.15 | "
          f"MFPT at 0.15, σ 5 cm | on fresh draws (seeds {', '.join(map(str, FRESH_SEEDS))}) | "
          "failures in the profile's interval | checked for; ends |",
          "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|---|"]
    for r in list(winners.values()) + [fig7a]:
        md.append(f"| {r['role']} | {r['rho']:.3f} | {r['alpha']:.4f} | {r['fn']:.3f} | {r['zeta']:.4f} | "
                  f"{f(r['phi_lo'])} | {f(r['phi_hi'])} | {f(r['slope_range'])} | {f(r['phi_min'])} | "
                  f"{r['label_at_0.15']} | {f(r['speed_at_0.15'], 3)} | {f(r['mfpt_at_0.15'], 0)} | "
                  f"{', '.join(f(v, 0) for v in r['mfpt_fresh'])} | {r['checked_failures']} of {r['checked_slopes']} | "
                  f"{r['ends']} |")
    # The table rounds the designs, and a design's MFPT on a rough slope is
    # not smooth in its inputs: a star a little different takes another
    # path over the same ground. So each winner's numbers come with the
    # command of the exact design, and the robust winner's MFPT as rounded.
    robust = winners.get("robust")
    rounded = None
    if robust is not None and robust["mfpt_at_0.15"] is not None:
        rounded = mfpt_at_speed_phi({"rho": round(robust["rho"], 3), "alpha": round(robust["alpha"], 4),
                                     "fn": round(robust["fn"], 3), "zeta": round(robust["zeta"], 4)})
    md += ["\nThe table rounds the designs; the MFPTs are those of the exact designs "
           "(`results/design/designs-NAME.parquet`), each from the command below (add `--set terrain.seed=S` "
           "for a fresh draw). A design's MFPT on a rough slope is not smooth in its inputs: a star a little "
           "different takes another path over the same ground and meets other patches"
           + (f" (the robust winner as rounded in the table: {f(rounded, 0)} steps at seed 0, against "
              f"{f(robust['mfpt_at_0.15'], 0)})" if rounded is not None else "") + ".\n",
           "```sh"]
    for r in list(winners.values()) + [fig7a]:
        if r["mfpt_at_0.15"] is not None:
            md.append(f"rtw-scan simulate {' '.join(flags(r))} --phi {SPEED_PHI} --set robustness.mfpt=true "
                      f"--set robustness.sigma=0.05 --json  # {r['role']}")
    md += ["```"]
    md += ["\n## Pareto front: slope range against speed at φ = 0.15\n",
           "| role | ρ | α | f_n | ζ | phi_lo | phi_hi | slope range | speed at 0.15 | failures in the profile's interval | checked for; ends |",
           "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
    for r in front:
        md.append(f"| {r['role']} | {r['rho']:.3f} | {r['alpha']:.4f} | {r['fn']:.3f} | {r['zeta']:.4f} | "
                  f"{f(r['phi_lo'])} | {f(r['phi_hi'])} | {f(r['slope_range'])} | {f(r['speed_at_0.15'], 3)} | "
                  f"{r['checked_failures']} of {r['checked_slopes']} | {r['ends']} |")
    md += ["\nEach interval was checked for the gait named (`any`: any stable gait) at every checked slope; "
           "an end is *sharp* when no slope beyond it holds (checked or in the fine profile) and "
           "*interleaved* when some do, between failures: beyond an interleaved end the design still holds "
           "at some slopes, at others not (`gait`, `phi_lo_end`, `phi_hi_end` of designs.parquet).\n"]
    md += ["\n## What sets them apart\n",
           f"Spearman rank correlation of each input with the widest stable slope range and with the "
           f"shallowest stable slope, over the {corr[0][5]} Sobol designs of the widest config "
           "(`runs/design/search/widest-sobol`).\n",
           "| input | ρ_s with slope range | p | ρ_s with phi_min | p |", "|---|---:|---:|---:|---:|"]
    for k, r1, p1, r2, p2, _ in corr:
        md.append(f"| {k} | {r1:+.2f} | {p1:.1e} | {r2:+.2f} | {p2:.1e} |")
    (out / "atlas.md").write_text("\n".join(md) + "\n")
    print("\n".join(md))
    gait_families(search, out, fig7a)


def gait_families(search: Path, out: Path, fig7a: dict) -> None:
    """OUT/families.md and families.png: each gait family's winners
    (rtwscripts.families), their profiles on one slope axis with Fig. 7(a)'s."""
    fam = families.winners(search, out, at_speed_phi, label_at, mfpt_at_speed_phi, FRESH_SEEDS)
    strips = []
    for row in fam + [{"family": "Fig. 7(a)", "role": "", "search": "fig7a", "design": fig7a}]:
        d = row["design"]
        if d is None:
            continue
        path = ROOT / f"runs/design/families/profile-{row['search']}.parquet"
        profile(d, path, families.SPAN)
        t = pq.read_table(path, columns=["phi", "outcome"]).sort_by("phi").to_pydict()
        interval = (d["phi_lo"], d["phi_hi"])
        label = "Fig. 7(a)" if row["search"] == "fig7a" else f"{row['family']}: {row['role']}"
        strips.append((label, {"phi": t["phi"], "outcome": t["outcome"], "interval": interval, "gait": d["gait"]}))

    fig, (a, b) = plt.subplots(1, 2, figsize=(13, 5.6), gridspec_kw={"width_ratios": [1.6, 1]})
    families.strips(a, strips)
    a.set_title("Each family's winners along φ (box: the interval checked for the gait; dashed: for any gait)", fontsize=10)
    families.scatter(b, ROOT / "results/paper/samples.parquet", fam, fig7a)
    b.set_title("The winners on the paper scan's samples of each gait (dots)", fontsize=10)
    fig.tight_layout()
    fig.savefig(out / "families.png", dpi=110)

    def f(v, d=4):
        return "–" if v is None else f"{v:.{d}f}"

    fresh = ", ".join(map(str, FRESH_SEEDS))
    md = ["# Gait families (default model, L = 0.8 m)\n",
          "`./scripts/design_atlas.sh`: for each gait, the searches `widest`, `shallowest`, `fastest` and "
          "`robust` of `configs/design/` run again with `gait = \"GAIT\"` (`runs/design/families/GAIT-ROLE.toml`; "
          "the walk's widest is `widest-walk`), each reported design's interval checked by direct simulation "
          "for that gait (`results/design/designs-GAIT-ROLE.parquet`). Of each search's reported designs, the "
          "winner: the widest checked interval, the shallowest slope of the gait, and, of those in the gait at "
          "φ = 0.15 by `rtw-scan simulate`, the fastest there and the largest MFPT there (σ = 5 cm, the "
          f"searches' ground terrain.seed 0; again on fresh draws, seeds {fresh}). The robust design at the "
          "default roughness (σ = 1 cm) awaits an MFPT that reaches it (docs/robustness.md): at 1 cm most "
          "stable gaits have no fall counted.\n",
          "## Winners\n",
          "| family | role | design | ρ | α | f_n | ζ | phi_lo | phi_hi | slope range | phi_min | gait at phi_min | "
          "gait at 0.15 | "
          f"speed at 0.15 | MFPT at 0.15, σ 5 cm | on fresh draws (seeds {fresh}) | "
          "failures in the profile's interval | checked for; ends |",
          "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---:|---:|---:|---:|---|"]
    for row in fam:
        r = row["design"]
        if r is None:
            md.append(f"| {row['family']} | {row['role']} | – | " + "– | " * 9
                      + (f"none of {row['found']} reported in the gait at 0.15" if row["found"] else
                         "no design in the gait found") + " | – | – | – | – | – |")
            continue
        md.append(f"| {row['family']} | {row['role']} | {r['from']} | {r['rho']:.3f} | {r['alpha']:.4f} | "
                  f"{r['fn']:.3f} | {r['zeta']:.4f} | {f(r['phi_lo'])} | {f(r['phi_hi'])} | {f(r['slope_range'])} | "
                  f"{f(r['phi_min'])} | {r['label_at_phi_min']} | {r['label_at_0.15']} | "
                  f"{f(r['speed_at_0.15'], 3)} | "
                  f"{f(r['mfpt_at_0.15'], 0)} | {', '.join(f(v, 0) for v in r['mfpt_fresh'])} | "
                  f"{r['checked_failures']} of {r['checked_slopes']} | {ends(r)} |")
    md += ["\n*design*: the search that reported it and its place there (best first by the search's own "
           "profile); the fastest and the most robust are also sought among the designs of `front` and `robust` "
           "(any gait) that are in the gait at φ = 0.15. *slope range*, *phi_min*: of the gait, on the fine profile; *phi_lo*, *phi_hi*: the widest "
           "run of checked slopes in the gait.\n",
           "## What sets the families apart\n",
           "The paper scan's samples of each gait (`results/paper/samples.parquet`: designs drawn uniformly from "
           "the article's box, each at a slope drawn from its range), their inputs' and slopes' medians and "
           "interquartile ranges.\n",
           *families.apart(ROOT / "results/paper/samples.parquet", INPUTS)]
    (out / "families.md").write_text("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
