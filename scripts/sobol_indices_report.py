"""results/sensitivity/indices.parquet (rtw-scan sensitivity of the Saltelli scan) -> results/sensitivity/indices.md.

The paper's sensitivity claim ("failure seemed rather independent of rho and
zeta ... alpha, f_n and phi showed a clear influence") as Sobol indices: one
table of total indices, one of first-order indices, each index with its 95 %
bootstrap half-width. docs/reproduction.md quotes the tables
(scripts/readme_tables.py).

    .venv/bin/python scripts/sobol_indices_report.py [results/sensitivity]
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import pyarrow.compute as pc
import pyarrow.parquet as pq

from rtwscripts.labels import FAILED, STABLE

PARAMS = [("rho", "ρ"), ("alpha", "α"), ("fn", "f_n"), ("zeta", "ζ"), ("phi", "φ")]
OUTPUTS = ["failure", *STABLE, *FAILED, "speed", "f_w"]
CLASSES = OUTPUTS[:6]


def table(d: dict[tuple[str, str], dict[str, float]], key: str) -> list[str]:
    head = "| output | " + " | ".join(sym for _, sym in PARAMS) + " |"
    rows = [head, "|---|" + "---:|" * len(PARAMS)]
    for out in OUTPUTS:
        if (out, "rho") not in d:
            continue
        cells = [f"{d[out, p][key]:.3f} ± {d[out, p][key + '_conf']:.3f}" for p, _ in PARAMS]
        rows.append(f"| {out} | " + " | ".join(cells) + " |")
    return rows


def main(root: Path) -> None:
    f = pq.read_table(root / "indices.parquet")
    about = json.loads(pq.read_metadata(root / "indices.parquet").metadata[b"rtw.sensitivity"])
    d = {(r["output"], r["parameter"]): r for r in f.to_pylist()}
    wide = sorted({o for (o, _), r in d.items() if o in OUTPUTS and max(r["S1_conf"], r["ST_conf"]) > 0.05})
    widest = max(max(r["S1_conf"], r["ST_conf"]) for (o, _), r in d.items() if o in OUTPUTS)
    within = "every half-width is at most 0.05" + (f" except those of {', '.join(wide)}" if wide else "")
    base = about["rows"] // 7
    for out in wide:
        hw = max(max(r["S1_conf"], r["ST_conf"]) for (o, _), r in d.items() if o == out)
        if out in CLASSES:
            # An indicator's half-width shrinks as 1/sqrt(base rows): the base
            # rows (a power of two, as Sobol points balance) that bring it to 0.05.
            needed = 2 ** math.ceil(math.log2(base * (hw / 0.05) ** 2))
            within += (f"; {out}'s widest ({hw:.3f}) would need about {needed} base rows "
                       f"({needed * 7} runs) to reach 0.05")
        else:
            top = pq.read_table(root / "saltelli/samples.parquet", columns=[out]).column(out)
            within += (f"; {out}'s widest ({hw:.3f}) comes from one run's {out} of "
                       f"{pc.max(top).as_py():.6g} (median {pc.approximate_median(top).as_py():.3g}), "
                       "which dominates its variance")
    if not wide:
        within += f" (the widest {widest:.3f})"
    lines = [
        "# Sobol indices of the paper's box",
        "",
        f"Made by `./scripts/sobol_indices.sh`: `rtw-scan sensitivity` of the Saltelli scan "
        f"`results/sensitivity/saltelli/` (configs/sensitivity-saltelli.toml: {about['rows']} runs, "
        f"{base} base rows × (5 + 2), the default model), {about['resamples']} bootstrap "
        f"resamples (seed {about['seed']}). Each outcome is a 0/1 indicator over all runs, failures "
        "included; failure = collapse or stall. ± is the 95 % half-width: "
        f"{within}.",
        "",
        "## Total indices",
        "",
        "ST: the share of the output's variance due to the input, its interactions included.",
        "",
        *table(d, "ST"),
        "",
        "## First-order indices",
        "",
        "S1: the share due to the input alone.",
        "",
        *table(d, "S1"),
        "",
    ]
    (root / "indices.md").write_text("\n".join(lines))
    print("\n".join(lines))


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "results/sensitivity"))
