"""What the scripts of scripts/ share, so that no script imports another.

A script run as `python scripts/NAME.py` has scripts/ first on sys.path, so
`import rtwscripts` finds this package with no path set by hand. The parts:

- here: the repository's root, the figures' resolution, the default model's
  variant name and `model`, the model part of a file's `rtw.variant`
  (plain Python: the checks that run before the package rtw is installed use
  them too);
- `rtwscripts.labels`: the gait and failure labels, from the package rtw;
- `rtwscripts.stats`: Wilson intervals over arrays and the permutation test;
- `rtwscripts.paper`: the paper's targets and how a scan is scored on them;
- `rtwscripts.reference`: the SciPy port of the model (scripts/scipy_side_by_side.py);
- `rtwscripts.structure`: the structural rules and layers of the crates
  (scripts/check_structure.py, scripts/code_counts.py).
"""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent

# The figures' resolution (dots per inch), for every PNG the scripts draw.
DPI = 130

# rtw's default model as a variant file (configs/variants/): the one the gallery's walk is run
# with, and the one the variant study's selection rule picks (results/variants/summary.json
# "chosen"; scripts/variants_report.py writes this name as "default" beside it, and
# crates/rtw-scan-test/tests/it/default_variant.rs fails unless the two agree and the file gives
# rtw-model's Options::default()).
DEFAULT_VARIANT = "prestress-0.8875-settled-mu0.8-slack-steps"


def model(variant: str) -> str:
    """The model part of an `rtw.variant`: everything before the run's
    integrator settings."""
    return variant.split(" method=", 1)[0].strip()
