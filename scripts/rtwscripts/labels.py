"""The gait and failure labels, as the library names and orders them: the
package rtw's LABELS, STABLE_LABELS and FAILURE_LABELS (rtw-model's Outcome,
docs/data-dictionary.md's `outcome`), never a list typed in a script."""

from __future__ import annotations

from rtw import FAILURE_LABELS, LABELS, STABLE_LABELS

# Every label a sample can have, in the library's order.
OUTCOMES = list(LABELS)
# The stable gaits (skip, walk, crawl).
STABLE = list(STABLE_LABELS)
# The failures (collapse, stall; a diverged sample is neither a gait nor a failure).
FAILED = list(FAILURE_LABELS)

# Each label's colour in the figures of a design's gait along φ.
COLOURS = {
    "walk": "tab:green",
    "skip": "tab:blue",
    "crawl": "tab:purple",
    "collapse": "tab:red",
    "stall": "tab:orange",
    "diverged": "black",
}

__all__ = ["COLOURS", "FAILED", "OUTCOMES", "STABLE"]
