#!/usr/bin/env python3
"""Count the public items of rtw's library crates from their rustdoc pages.

Usage: scripts/public_items.sh [--list]   (fresh rustdoc output, then this)
       python3 scripts/public_items.py [--list] [--doc DIR] [crate ...]

A public item is anything a user of the crate can name by a path, as
rustdoc documents it: each module, struct, enum, trait, function, constant,
static and type alias, one per path that names it (rustdoc's pages: an
item re-exported under a second path with a page of its own counts twice,
since a user can name it both ways; one re-exported as a link, once; two
items of one name in two modules, twice), plus each inherent method and associated constant
of those types (not trait implementations, not struct fields or enum
variants, which are parts of their type). `pub` items that rustdoc does not
reach (inside `pub(crate)` modules) are not public and are not counted.
"""

import os
import re
import sys

KINDS = ("struct", "enum", "trait", "fn", "constant", "static", "type", "macro", "union")


def members(html, kind):
    """Names of the inherent methods and associated constants on one page."""
    if kind == "trait":
        end = min(
            (i for i in (html.find('id="implementors"'), html.find('id="foreign-impls"')) if i >= 0),
            default=len(html),
        )
        part = html[:end]
        pat = r'id="((?:ty)?method|associatedconstant|associatedtype)\.([A-Za-z_0-9]+)"'
    else:
        start = html.find('id="implementations-list"')
        if start < 0:
            return set()
        ends = [
            i
            for i in (
                html.find('id="trait-implementations"', start),
                html.find('id="synthetic-implementations"', start),
                html.find('id="blanket-implementations"', start),
            )
            if i >= 0
        ]
        part = html[start : min(ends) if ends else len(html)]
        pat = r'id="(method|associatedconstant)\.([A-Za-z_0-9]+)"'
    return {m.group(2) for m in re.finditer(pat, part)}


def count(doc, crate, listing):
    root = os.path.join(doc, crate)
    items = {}
    for dirpath, _, files in os.walk(root):
        for f in files:
            if not f.endswith(".html") or f == "all.html":
                continue
            rel = os.path.relpath(os.path.join(dirpath, f), root)
            if f == "index.html":
                mod = os.path.dirname(rel).replace(os.sep, "::")
                items[("mod", mod or crate)] = set()
                continue
            kind, name = f[: -len(".html")].split(".", 1)
            if kind not in KINDS:
                continue
            # Keyed by the path that names it, not the bare name: a
            # `run_to_files` in five modules is five items.
            path = os.path.dirname(rel).replace(os.sep, "::")
            name = f"{path}::{name}" if path else name
            with open(os.path.join(dirpath, f), encoding="utf-8") as fh:
                html = fh.read()
            if "<title>Redirection" in html:
                continue
            items.setdefault((kind, name), set()).update(members(html, kind))
    total = sum(1 + len(m) for m in items.values())
    if listing:
        for (kind, name), m in sorted(items.items()):
            print(f"  {kind} {name}" + (f": {', '.join(sorted(m))}" if m else ""))
    print(f"{crate}: {total} public items ({len(items)} items with a page, "
          f"{total - len(items)} methods and associated constants)")


def main():
    args = sys.argv[1:]
    listing = "--list" in args
    args = [a for a in args if a != "--list"]
    doc = "target/doc"
    if "--doc" in args:
        i = args.index("--doc")
        doc = args[i + 1]
        del args[i : i + 2]
    for c in args or ["hybrid_ode", "rtw_model", "rtw_engine", "rtw_studies", "rtw_scan"]:
        count(doc, c.replace("-", "_"), listing)


if __name__ == "__main__":
    main()
