"""Sphinx configuration of rtw's documentation site (scripts/docs_site.sh).

The site is built from the repository's root, so that the pages link to one
another, to the README and to the generated results pages under results/
exactly as they do on the forge: the Markdown is the source, read through
MyST, and nothing is copied. Sphinx with MyST rather than mdBook: it installs
from the Python package index in seconds (no compile in a new user's first
hour), and its autodoc writes the Python API page from the installed
package's own docstrings, which the Rust side's rustdoc cannot.
"""

project = "rtw"
author = "the rtw developers"
# napoleon: the package's docstrings are in Google style (Args:, Returns:, Raises:).
extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.napoleon"]
source_suffix = {".md": "markdown"}
root_doc = "docs/index"
include_patterns = [
    "README.md",
    "CHANGELOG.md",
    "docs/*.md",
    "results/*.md",
    "results/**/*.md",
    "crates/hybrid-ode/README.md",
]
exclude_patterns = ["target/**", ".venv/**", "v/**", "runs/**"]
# GitHub-style anchors for the pages' `#section` links, to the fourth level.
myst_heading_anchors = 4
myst_enable_extensions = ["dollarmath"]
# Generated results pages start at a level-3 heading or have no title: they
# are listed by path, and a skipped heading level is no error of the reader's.
suppress_warnings = ["myst.header", "toc.no_title"]
html_theme = "alabaster"
html_title = "rtw"
html_theme_options = {"description": "passive gaits of the rimless wheel-like tensegrity", "fixed_sidebar": True}
autodoc_member_order = "bysource"
# A class's "Attributes:" as fields of its description: the getters the
# compiled classes expose are listed by autodoc as members already.
napoleon_use_ivar = True
