"""A design search, or an atlas of them, as one HTML page: ``rtw.report(DIR)``
/ ``python -m rtw report DIR`` where DIR is a search's folder
(``rtw-scan design --out DIR``) or an atlas (``results/design/``).

The files come from rtw-scan's verified design reader (``_rtw.read_design``:
footers, content hashes, and which file is what from the metadata rtw-scan
wrote), so the page never shows rows rtw-scan would refuse. The page shows:

- every reported design on the atlas's axes: its widest checked interval of
  stable slopes against its speed and against its shallowest stable slope,
  one colour per search (the Fig. 7(a) design is the one-point search
  ``configs/design/fig7a.toml``);
- each reported design's checked interval [phi_lo, phi_hi] beside the
  profile's own, with the failures its direct-simulation check found;
- each search's evaluations: its objective against the simulations spent,
  the designs that fell (infeasible, never scored) apart, and for two
  objectives the evaluated designs and the front;
- each profile in the folder: the gait and speed against φ, with its located
  label changes;
- the folder's figures and gait animations (PNG, GIF), inlined.

Nothing here simulates: the numbers are the files'.
"""

from __future__ import annotations

import html
import json
import math
from pathlib import Path
from typing import Any

from ._page import clean, images, page, style, text_metadata

# Figures and animations inlined up to this size each (the atlas's GIFs are
# about 0.3 MB); a larger one is named on the page, not carried.
IMAGE_BYTES = 3_000_000
# The columns of a reported design the page's tables show, in order.
TABLE = ("rho", "alpha", "fn", "zeta", "phi_lo", "phi_hi", "slope_range", "phi_min", "label_at_speed_phi",
         "speed", "mfpt", "checked_failures", "checked_slopes")
HEAD = {"rho": "ρ", "alpha": "α", "fn": "f_n", "zeta": "ζ", "phi_lo": "phi_lo", "phi_hi": "phi_hi",
        "slope_range": "slope range", "phi_min": "phi_min", "label_at_speed_phi": "gait at speed φ",
        "speed": "speed (m/s)", "mfpt": "MFPT (steps)", "checked_failures": "failures", "checked_slopes": "checked"}


def _columns(table) -> dict[str, list]:
    return {c: clean(v) for c, v in table.to_pydict().items()}


def _searches(files: list[tuple[Path, str, Any]]) -> tuple[list[dict], list[dict]]:
    """The searches (their settings, evaluations and reported designs, one
    entry per search identity) and the profiles, in file order."""
    searches: dict[str, dict] = {}
    profiles = []
    for path, role, table in files:
        meta = text_metadata(table.schema.metadata)
        if role == "profile":
            about = json.loads(meta["rtw.profile"])
            cols = _columns(table.select(["phi", "outcome", "speed", "f_w"]))
            order = sorted(range(len(cols["phi"])), key=lambda i: cols["phi"][i])
            profiles.append({"file": path.name, "design": about.get("design", {}), "tol": about.get("tol"),
                             "changes": about.get("changes", []), "phi_lo": about.get("phi_lo"),
                             "phi_hi": about.get("phi_hi"), "phi_min": about.get("phi_min"),
                             "variant": meta.get("rtw.variant", "?"),
                             **{c: [cols[c][i] for i in order] for c in cols}})
            continue
        identity = meta["rtw.design"]
        settings = json.loads(identity)["settings"]
        s = searches.setdefault(identity, {"name": settings.get("name", "?"), "settings": settings,
                                           "variant": meta.get("rtw.variant", "?"),
                                           "version": meta.get("rtw.version", "?"), "files": []})
        s["files"].append(f"{path.name} ({role}, {table.num_rows} rows)")
        s[role] = _columns(table)
    return list(searches.values()), profiles


def _num(v: Any, digits: int = 4) -> str:
    if v is None:
        return "–"
    if isinstance(v, float):
        if not math.isfinite(v):
            return "∞" if v > 0 else "–"
        return f"{v:.{digits}g}" if abs(v) >= 1e4 else f"{v:.{digits}f}".rstrip("0").rstrip(".")
    return str(v)


def _tables(searches: list[dict]) -> str:
    """Each search's header and its reported designs, as HTML."""
    e = html.escape
    out = []
    for s in searches:
        st = s["settings"]
        box = ", ".join(f"{k} ∈ [{_num(lo)}, {_num(hi)}]" for k, (lo, hi) in zip(("ρ", "α", "f_n", "ζ"), st["bounds"]))
        about = [("objectives", ", ".join(st["objectives"]) + (f" (gait: {st['gait']})" if st.get("gait") else "")),
                 ("method", f"{st['method']}, budget {st['budget']:,} simulations, seed {st['seed']}"),
                 ("box", f"{box}; L = {st['length']} m"),
                 ("slopes", f"φ ∈ [{st['from']}, {st['to']}] rad, grid {st['grid']}, changes to {st['tol']}; "
                            f"reported designs profiled again on a grid of {st['verify_grid']}"),
                 ("model", s["variant"]), ("files", "; ".join(s["files"]))]
        if st.get("speed_phi") is not None:
            about.insert(1, ("speed at", f"φ = {st['speed_phi']}"))
        if st.get("mfpt_phi") is not None:
            about.insert(1, ("MFPT at", f"φ = {st['mfpt_phi']}"))
        head = "".join(f"<tr><th>{e(k)}</th><td>{e(str(v))}</td></tr>" for k, v in about)
        body = ""
        rep = s.get("reported")
        if rep:
            cols = [c for c in TABLE if c in rep]
            body = ("<table class='designs'><thead><tr><th>rank</th>" + "".join(f"<th>{e(HEAD[c])}</th>" for c in cols)
                    + "</tr></thead><tbody>"
                    + "".join("<tr><td>" + str(i + 1) + "</td>" + "".join(f"<td>{e(_num(rep[c][i]))}</td>" for c in cols)
                              + "</tr>" for i in range(len(rep["rho"])))
                    + "</tbody></table>")
        else:
            body = "<p class='note'>No reported designs in this folder (the search has not finished).</p>"
        out.append(f"<h3>Search {e(s['name'])}</h3><table class='meta'>{head}</table>{body}")
    return "".join(out)


def design_page(directory: Path, files: list[tuple[Path, str, Any]], plotly_js: str) -> str:
    """The design page's HTML for the design files `files` read from
    `directory`. It simulates nothing, so it takes no progress bar."""
    from . import __version__

    searches, profiles = _searches(files)
    shown, skipped = images(directory if directory.is_dir() else directory.parent, ("png", "gif"), IMAGE_BYTES)
    e = html.escape
    names = ", ".join(s["name"] for s in searches)
    title = f"rtw design report: {names}"
    header = (f"<h1>{e(title)}</h1><p class='note'>{e(str(directory))}: {len(searches)} search(es), "
              f"{len(profiles)} profile(s), read by rtw-scan's verified reader; report made by rtw {e(__version__)}. "
              "A design's interval [phi_lo, phi_hi] is the widest run of slopes its direct-simulation check "
              "found stable (docs/design.md).</p>")
    if skipped:
        header += f"<p class='note'>Not inlined (over {IMAGE_BYTES / 1e6:.0f} MB): {e(', '.join(skipped))}.</p>"
    data = {"searches": searches, "profiles": profiles, "images": shown, "style": style()}
    return page("design", title, header, data, plotly_js, {"TABLES": _tables(searches)})
