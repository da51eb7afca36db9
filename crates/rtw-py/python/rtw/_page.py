"""What the two pages of ``rtw.report`` share (a scan's page,
``scan_page.py``; a design search's, ``design_report.py``): the templates
and the Plotly.js bundle in report_assets/, the data inlined gzip'd, the
marker by which rtw knows its own pages, the images inlined, the colours.
Each page imports this module and neither imports the other; ``report.py``
reads the folder, picks the page and writes it.

Only the standard library (and ``_rtw``) is imported here.
"""

from __future__ import annotations

import base64
import gzip
import hashlib
import html
import json
import math
import re
from pathlib import Path
from typing import Any, Sequence

from . import _rtw

# The marker every page carries, by which the native layer that writes it
# (``_rtw.write_page``) tells a page rtw made from a file it must not replace.
GENERATOR: str = _rtw.PAGE_GENERATOR
ASSETS = Path(__file__).with_name("report_assets")
PLOTLY_JS = "plotly-rtw.min.js"


class ReportError(ValueError):
    """The directory cannot be reported on (no scan, bad options); the message says why."""


def plotly_bundle() -> str:
    """Plotly.js with only the trace types the page draws, built by
    scripts/plotly_bundle.sh from pinned npm packages and shipped with rtw;
    its sha256 is checked, so a page never carries a changed bundle."""
    path = ASSETS / PLOTLY_JS
    try:
        raw = path.read_bytes()
        want = (ASSETS / f"{PLOTLY_JS}.sha256").read_text(encoding="ascii").split()[0]
    except FileNotFoundError as e:
        raise ImportError(f"rtw's Plotly.js bundle is missing ({e.filename}): reinstall rtw") from None
    if hashlib.sha256(raw).hexdigest() != want:
        raise ImportError(f"{path}: its sha256 is not the one in {PLOTLY_JS}.sha256: reinstall rtw "
                          "(or rebuild it with scripts/plotly_bundle.sh --write)")
    return raw.decode("utf-8")


def b64gz(text: str) -> str:
    """`text` gzip'd then base64'd, as the page inflates it in the browser."""
    # mtime=0: the same report gives the same bytes.
    return base64.b64encode(gzip.compress(text.encode("utf-8"), compresslevel=9, mtime=0)).decode("ascii")


def text_metadata(md: dict | None) -> dict[str, str]:
    """A schema's metadata (bytes keys and values) as text."""
    return {(k.decode() if isinstance(k, bytes) else k): (v.decode() if isinstance(v, bytes) else v)
            for k, v in (md or {}).items()}


def clean(v):
    """JSON-safe: non-finite floats as null."""
    if isinstance(v, float):
        return v if math.isfinite(v) else None
    if isinstance(v, dict):
        return {k: clean(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [clean(x) for x in v]
    return v


def style() -> dict[str, Any]:
    """The colours of rtw.draw and the figures, so the page looks like them."""
    from . import draw

    return {"outcome": draw.OUTCOME_COLOR, "rod": list(draw.ROD_COLOR), "string": draw.STRING_COLOR,
            "ground": draw.GROUND_COLOR, "earth": draw.EARTH_COLOR, "state": draw.STATE_COLOR,
            "cluster": ["#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#17becf"]}


def images(directory: Path, kinds: Sequence[str], max_bytes: int) -> tuple[list[dict[str, str]], list[str]]:
    """The images of `kinds` (``"png"``, ``"gif"``) in DIR, inlined as data
    URLs, in name order; and the names of those over `max_bytes`, left out."""
    if not directory.is_dir():
        return [], []
    shown, skipped = [], []
    for f in sorted(f for kind in kinds for f in directory.glob(f"*.{kind}")):
        if f.stat().st_size > max_bytes:
            skipped.append(f.name)
            continue
        src = f"data:image/{f.suffix[1:]};base64," + base64.b64encode(f.read_bytes()).decode()
        shown.append({"name": f.name, "src": src})
    return shown, skipped


def page_assets(name: str) -> tuple[str, dict[str, str]]:
    """The template NAME.html, and its STYLE and SCRIPT: the style and the
    loader both pages share (page.css, boot.js), the script its own (NAME.js)."""
    read = lambda f: (ASSETS / f).read_text(encoding="utf-8")  # noqa: E731
    return read(f"{name}.html"), {"STYLE": read("page.css"), "SCRIPT": read("boot.js") + read(f"{name}.js")}


def fill(page: str, parts: dict[str, str]) -> str:
    """The page template with its {{NAME}} placeholders filled in one pass:
    what is put in (a scan's name, its config) is never read again for them."""
    return re.sub(r"\{\{(" + "|".join(parts) + r")\}\}", lambda m: parts[m.group(1)], page)


def page(name: str, title: str, header: str, data: dict[str, Any], plotly_js: str,
         more: dict[str, str] | None = None) -> str:
    """The page of the template NAME.html: its `title` (text, escaped here),
    its `header` (HTML), `more` placeholders (HTML), the Plotly.js bundle and
    `data` (JSON, non-finite floats as null), both inlined gzip'd."""
    template, shared = page_assets(name)
    parts = {
        **shared,
        "GENERATOR": GENERATOR,
        "TITLE": html.escape(title),
        "HEADER": header,
        **(more or {}),
        "PLOTLY": b64gz(plotly_js),
        "DATA": b64gz(json.dumps(clean(data), separators=(",", ":"), allow_nan=False)),
    }
    return fill(template, parts)
