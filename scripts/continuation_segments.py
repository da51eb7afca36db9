#!/usr/bin/env python3
"""The Fig. S3 story from `rtw-scan continuation --through N`: a gait's branch
continued through the changes of its mode sequence (FILE.segments.json).

  diagram A.segments.json [B.segments.json ...] --out FIG.png [--sweep SWEEP.parquet] [--title T]
      one panel per file (one rod length L each): step frequency against the
      input, each point coloured by its gait label, stable filled and unstable
      hollow, each segment's end marked and named (grazing, corner, gait lost,
      fold, range end); with --sweep, the attractor sweep's stable gaits over it
      (rtw-scan bifurcation: NAME.parquet and NAME.steps.parquet) for the file
      whose L is the sweep's.
  check A.segments.json SWEEP.parquet [--rel-tol 1e-3]
      on every segment point that is stable where the sweep shows a stable gait
      of the same period at a grid value inside the segment: the same label,
      and the step frequency (the segment's, interpolated to the sweep's value)
      within --rel-tol. Prints a Markdown table per segment; exits 1 on a
      disagreement.
"""

import argparse
import json
import sys

import numpy as np

COLOURS = {"walk": "tab:blue", "skip": "tab:orange", "crawl": "tab:green"}


def load(path):
    with open(path) as f:
        return json.load(f)


def sweep_table(path):
    import pyarrow.parquet as pq

    per = pq.read_table(path).to_pandas()
    steps = pq.read_table(path.replace(".parquet", ".steps.parquet")).to_pandas()
    freq = 1.0 / steps.groupby("value")["step_time"].mean()
    per = per.set_index("value")
    per["step_frequency"] = freq
    return per.reset_index()


def segments(doc):
    for d in doc["directions"]:
        for i, s in enumerate(d["segments"]):
            yield d["direction"], i, s


def way(doc):
    """Each direction's segments with the direction's name in the tables
    (`way` in the segments file: up / down from the start, or the period-2
    branch it continues)."""
    for d in doc["directions"]:
        for i, s in enumerate(d["segments"]):
            yield d["way"], i, s


def model_of(path):
    """The model a file was made at (rtwscripts.model of its `rtw.variant`):
    for FILE.segments.json that of FILE.parquet, which the same run wrote."""
    import pyarrow.parquet as pq

    from rtwscripts import model

    path = str(path)
    data = path[: -len(".segments.json")] + ".parquet" if path.endswith(".segments.json") else path
    variant = (pq.read_metadata(data).metadata or {}).get(b"rtw.variant")
    if variant is None:
        sys.exit(f"continuation_segments: {data} has no rtw.variant: its model cannot be named")
    return model(variant.decode())


def diagram(args):
    import textwrap

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    docs = [load(p) for p in args.files]
    fig, axes = plt.subplots(len(docs), 1, figsize=(10, 3.4 * len(docs)), squeeze=False, sharex=True)
    sweep = sweep_table(args.sweep) if args.sweep else None
    for ax, doc in zip(axes[:, 0], docs):
        if sweep is not None and abs(doc["length"] - args.sweep_length) < 1e-9:
            st = sweep[sweep["stable"] == True]  # noqa: E712 (a nullable column)
            ax.scatter(st["value"], st["step_frequency"], s=30, facecolors="none", edgecolors="0.6",
                       label="attractor sweep (stable)", zorder=1)
        seen = set()
        for direction, i, s in segments(doc):
            pts = s["points"]
            p = np.array([q["p"] for q in pts])
            f = np.array([q["step_frequency"] for q in pts])
            stable = np.array([q["stable"] for q in pts])
            labels = [q["label"] or "?" for q in pts]
            ax.plot(p, f, color="0.3", lw=0.8, ls="-", zorder=2)
            for lab in sorted(set(labels)):
                m = np.array([x == lab for x in labels])
                c = COLOURS.get(lab, "tab:gray")
                for st, fc in ((True, c), (False, "none")):
                    k = m & (stable == st)
                    if k.any():
                        name = f"{lab}, {'stable' if st else 'unstable'}"
                        ax.scatter(p[k], f[k], s=14, color=c, facecolors=fc, zorder=3,
                                   label=name if name not in seen else None)
                        seen.add(name)
            end = s.get("end_at")
            if end and s["end"] not in ("end_parameter_range",):
                x = end["p_old"]
                y = f[-1] if len(f) else np.nan
                ax.axvline(x, color="tab:red", lw=0.6, ls=":", zorder=1)
                ax.annotate(s["end"].replace("_", " "), (x, y), textcoords="offset points",
                            xytext=(3, 6 if direction > 0 else -12), fontsize=7, color="tab:red")
        ax.set_ylabel("step frequency (steps/s)")
        ax.set_title(f"L = {doc['length']:g}", fontsize=9)
        ax.legend(fontsize=7, loc="best")
    axes[-1, 0].set_xlabel(docs[0]["param"])
    # The title names the model of the data drawn, read from the files, so it
    # cannot drift from them; every panel and the sweep must share it.
    models = {model_of(p) for p in args.files} | ({model_of(args.sweep)} if args.sweep else set())
    if len(models) != 1:
        sys.exit(f"continuation_segments: the files drawn together are at different models: {sorted(models)}")
    title = "\n".join([*([args.title] if args.title else []),
                       *textwrap.wrap(f"model: {models.pop()}", 130)])
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(args.out, dpi=130, metadata={"Title": title.replace("\n", " ")})
    print(f"wrote {args.out}")


def check(args):
    doc = load(args.segments)
    sweep = sweep_table(args.sweep)
    bad = 0
    print("| way | segment | gait | sweep values compared | labels agree | periods agree | max rel. Δ step frequency | agrees |")
    print("|---|---:|---|---:|---|---|---:|---|")
    for name, i, s in way(doc):
        pts = s["points"]
        p = np.array([q["p"] for q in pts])
        f = np.array([q["step_frequency"] for q in pts])
        stable = np.array([q["stable"] for q in pts])
        order = np.argsort(p)
        p, f, stable = p[order], f[order], stable[order]
        labels = [pts[k]["label"] for k in order]
        rows = sweep[(sweep["value"] >= p[0]) & (sweep["value"] <= p[-1]) & (sweep["stable"] == True)]  # noqa: E712
        n = 0
        lab_ok = per_ok = True
        worst = 0.0
        for _, r in rows.iterrows():
            k = np.searchsorted(p, r["value"])
            k = min(max(k, 1), len(p) - 1)
            # Both neighbours stable: the segment's gait is the attractor there.
            if not (stable[k - 1] and stable[k]):
                continue
            if r["period"] != s["period"]:
                per_ok = False
                continue
            n += 1
            w = (r["value"] - p[k - 1]) / (p[k] - p[k - 1])
            fi = (1 - w) * f[k - 1] + w * f[k]
            worst = max(worst, abs(fi - r["step_frequency"]) / r["step_frequency"])
            if r["label"] not in (labels[k - 1], labels[k]):
                lab_ok = False
        ok = lab_ok and per_ok and worst <= args.rel_tol
        bad += not ok
        print(f"| {name} | {i} | {s['label']} | {n} | {'yes' if lab_ok else 'no'} | {'yes' if per_ok else 'no'} "
              f"| {worst:.1e} | {'yes' if ok else 'NO'} |")
    sys.exit(1 if bad else 0)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    d = sub.add_parser("diagram")
    d.add_argument("files", nargs="+")
    d.add_argument("--out", required=True)
    d.add_argument("--sweep")
    d.add_argument("--sweep-length", type=float, default=0.8)
    d.add_argument("--title")
    c = sub.add_parser("check")
    c.add_argument("segments")
    c.add_argument("sweep")
    c.add_argument("--rel-tol", type=float, default=1e-3)
    a = ap.parse_args()
    diagram(a) if a.cmd == "diagram" else check(a)


if __name__ == "__main__":
    main()
