"""Checks a built documentation site (scripts/docs_site.sh): every local
link (href, src) of every page points to a file of the site, and every
`#anchor` to an id on that page; then the first page is opened in Debian's
headless Chromium, which must render its title and the tutorial's link, and
a screenshot is kept beside the site (SITE.png). External links are not
fetched (these machines reach no web site); they are counted. Last, no
page of docs/ or results/ is over PAGE_MAX_LINES lines (the CHANGELOG, the
project's history, is read by search, not page by page).

Without chromium on PATH the render check is skipped, saying so (the test
command installs it as root for the report's browser test).

Usage: .venv/bin/python scripts/check_site.py SITE_DIR
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

FIRST_PAGE = Path("docs/index.html")
# A page a reader takes in one sitting; a longer one is split by topic
# (docs/index.md keeps the spine).
PAGE_MAX_LINES = 400


def long_pages(root: Path) -> list[str]:
    """The Markdown pages of docs/ and results/ under `root` over PAGE_MAX_LINES lines."""
    pages = sorted((root / "docs").glob("*.md")) + sorted((root / "results").rglob("*.md"))
    return [f"{p.relative_to(root)}: {n} lines (at most {PAGE_MAX_LINES})"
            for p in pages if (n := len(p.read_text().splitlines())) > PAGE_MAX_LINES]


class Page(HTMLParser):
    """The links and the ids of one HTML page."""

    def __init__(self) -> None:
        super().__init__()
        self.links: list[str] = []
        self.ids: set[str] = set()

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        for name, value in attrs:
            if value is None:
                continue
            if name in ("href", "src"):
                self.links.append(value)
            elif name == "id" or (name == "name" and tag == "a"):
                self.ids.add(value)


def parse(path: Path) -> Page:
    page = Page()
    page.feed(path.read_text(errors="replace"))
    return page


def broken_links(site: Path) -> tuple[list[str], int, int]:
    """(each broken link, local links checked, external links counted)."""
    pages = {p: parse(p) for p in site.rglob("*.html")}
    broken, local, external = [], 0, 0
    for path, page in pages.items():
        for link in page.links:
            parts = urlsplit(link)
            if parts.scheme or link.startswith("//"):
                external += parts.scheme in ("http", "https")
                continue
            local += 1
            target = (path.parent / unquote(parts.path)).resolve() if parts.path else path
            if target.is_dir():
                target = target / "index.html"
            where = f"{path.relative_to(site)}: {link}"
            if not target.exists():
                broken.append(f"{where} (no file {target})")
                continue
            anchor = unquote(parts.fragment)
            if anchor and target.suffix == ".html":
                ids = pages[target].ids if target in pages else parse(target).ids
                if anchor not in ids:
                    broken.append(f"{where} (no id '{anchor}' on that page)")
    return broken, local, external


def render(site: Path) -> str | None:
    """The first page's DOM after Chromium has rendered it; None without chromium."""
    chromium = shutil.which("chromium")
    if chromium is None:
        return None
    page = (site / FIRST_PAGE).resolve().as_uri()
    flags = ["--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run",
             "--disable-background-networking", "--disable-component-update", "--disable-sync"]
    with tempfile.TemporaryDirectory() as profile:
        base = [chromium, *flags, f"--user-data-dir={profile}"]
        subprocess.run([*base, f"--screenshot={site}.png", "--window-size=1200,1600", page],
                       check=True, capture_output=True, timeout=120)
        done = subprocess.run([*base, "--dump-dom", page], check=True, capture_output=True, text=True, timeout=120)
    return done.stdout


def main() -> int:
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    site = Path(sys.argv[1]).resolve()
    if not (site / FIRST_PAGE).exists():
        sys.exit(f"check_site: {site / FIRST_PAGE} is missing: build the site first (scripts/docs_site.sh)")
    broken, local, external = broken_links(site)
    for b in broken:
        print(f"check_site: broken link: {b}", file=sys.stderr)
    print(f"check_site: {local} local links checked, {len(broken)} broken; {external} external links not fetched")
    dom = render(site)
    if dom is None:
        print("check_site: render check SKIPPED: no chromium on PATH (sudo apt-get install -y chromium)")
    else:
        wanted = ["<title>rtw", "Your first hour with rtw", "Python API reference"]
        missing = [w for w in wanted if w not in dom]
        if missing:
            print(f"check_site: the first page rendered without {missing}", file=sys.stderr)
            return 1
        print(f"check_site: the first page renders in headless Chromium (screenshot {site}.png)")
    long = long_pages(Path(__file__).resolve().parent.parent)
    for p in long:
        print(f"check_site: page too long: {p}", file=sys.stderr)
    print(f"check_site: {len(long)} pages of docs/ and results/ over {PAGE_MAX_LINES} lines")
    return 1 if broken or long else 0


if __name__ == "__main__":
    sys.exit(main())
