"""The paper's targets (docs/model.md §8) and how a 1000-sample scan is
scored against them: the variant study, the sensitivity runs and the
reproduction table use the same distance and the same names for the
failure clusters."""

from __future__ import annotations

import math

from rtwscripts.labels import STABLE

# docs/model.md §8: supplementary Section 2 (percent of all samples).
PAPER = {"stable": 73.7, "skip": 35.9, "walk": 32.0, "crawl": 5.8}
# The paper box's midpoints: a failure cluster "sits at small x" when its
# centre lies below the midpoint of x's sampled range.
MID = {"alpha": 0.2, "fn": 3.25, "phi": 0.175}


def distance_pp(stable: float, percent: dict) -> float:
    """The distance of a 1000-sample statistic to the paper's: sum of the
    absolute differences of stable, skip, walk and crawl (percentage points)."""
    return abs(stable - PAPER["stable"]) + sum(abs(percent[k] - PAPER[k]) for k in STABLE)


def cluster_regions(clusters: list[dict]) -> dict:
    """Names each k-means cluster by where its centre sits (Fig. S4's two
    groups): 'collapse region' = small alpha and low f_n, 'barrier region' =
    small phi (and not the former)."""
    regions = []
    for c in clusters:
        if c["alpha"] < MID["alpha"] and c["fn"] < MID["fn"]:
            regions.append("collapse region")
        elif c["phi"] < MID["phi"]:
            regions.append("barrier region")
        else:
            regions.append("elsewhere")
    both = "collapse region" in regions and "barrier region" in regions
    return {"regions": regions, "both": both}


def fmt(x, nd=1):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "–"
    return f"{x:.{nd}f}"
