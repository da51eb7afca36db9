"""The survival curve of a step down over every phase, for four gaits of
docs/robustness-step-down.md: the Fig. 7(a) walk and a walk, a skip and a crawl of
the paper scan (samples 44, 515 and 560 of results/robustness/paper).

For each gait, `rtw-scan simulate --set robustness.step_down=true
--set robustness.step_down_h50=true --json` gives its `step_down_max` (the
best phase) and `step_down_h50`; then, at stated heights (0.01 m, 0.2 m and
0.25 to 2 times `step_down_max`), `--set robustness.step_down_at=H` gives
the share of the 20 edge positions over one step that survive, and the
shares that fail by kind. Writes results/robustness/step_down_curve.md
(docs/robustness-step-down.md copies its tables).

    .venv/bin/python scripts/step_down_curve.py [OUT.md]
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pyarrow.parquet as pq

from rtwscripts.labels import STABLE

ROOT = Path(__file__).resolve().parent.parent
BIN = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "release" / "rtw-scan"
INPUTS = ["length", "rho", "alpha", "fn", "zeta", "phi"]
SAMPLES = {44: "walk (paper scan sample 44)", 515: "skip (paper scan sample 515)",
           560: "crawl (paper scan sample 560)"}
ABSOLUTE = (0.01, 0.2)
OF_MAX = (0.25, 0.5, 0.8, 1.0, 1.25, 1.5, 2.0)
KINDS = ["survival", "collapse", "stall", "other_gait", "diverged"]


def simulate(d: dict, *sets: str) -> dict:
    args = [str(BIN), "simulate", *(x for k in INPUTS for x in (f"--{k}", repr(float(d[k])))), "--json"]
    for s in sets:
        args += ["--set", s]
    return json.loads(subprocess.run(args, check=True, capture_output=True, text=True).stdout)


def curve(name: str, d: dict) -> list[str]:
    v = simulate(d, "robustness.step_down=true", "robustness.step_down_h50=true")
    if v["outcome"] not in STABLE:
        return [f"### {name}\n", f"Not a stable gait at the default model ({v['outcome']}).\n"]
    top, h50 = v["step_down_max"], v["step_down_h50"]
    md = [f"### {name}\n",
          f"`step_down_max` {top:.4f} m (the best phase), `step_down_h50` {h50:.4f} m; the shares of the 20 "
          "edge positions.\n",
          "| h (m) | h / step_down_max | survive | collapse | stall | another gait | diverged |",
          "|---:|---:|---:|---:|---:|---:|---:|"]
    heights = [(h, h / top if top > 0 else float("nan")) for h in ABSOLUTE] + [(k * top, k) for k in OF_MAX if top > 0]
    for h, k in sorted(heights):
        r = simulate(d, f"robustness.step_down_at={h!r}")
        shares = " | ".join(f"{r['step_down_' + kind]:.2f}" for kind in KINDS)
        md.append(f"| {h:.4f} | {k:.2f} | {shares} |")
    return md + [""]


def main() -> None:
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "results/robustness/step_down_curve.md"
    paper = {r["sample_id"]: r for r in pq.read_table(ROOT / "results/robustness/paper/samples.parquet",
                                                       columns=["sample_id", *INPUTS]).to_pylist()}
    fig7a = {"length": 0.8, "rho": 2.5, "alpha": 0.125, "fn": 3.269, "zeta": 0.0514, "phi": 0.15}
    md = ["# The step down over every phase: survival curves (default model)\n",
          "`.venv/bin/python scripts/step_down_curve.py`: each height by `rtw-scan simulate … "
          "--set robustness.step_down_at=H --json`, the step's edge at 20 positions spread over one step of "
          "the gait (docs/robustness.md, \"The step down over every phase\").\n"]
    md += curve("Fig. 7(a) walk", fig7a)
    for sid, name in SAMPLES.items():
        md += curve(name, paper[sid])
    out.write_text("\n".join(md))
    print("\n".join(md))


if __name__ == "__main__":
    main()
