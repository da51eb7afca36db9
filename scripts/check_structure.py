#!/usr/bin/env python3
"""The structural rules of the library crates (docs/architecture.md): no file
over 600 lines outside its tests, no import cycle, imports down the layers.
The rules and the layers (`LAYERS`) are in scripts/rtwscripts/structure.py.

Usage: python3 scripts/check_structure.py [crate dir ...]
(default: every crate under crates/). Exits 1 on a violation.
"""

from rtwscripts.structure import main

if __name__ == "__main__":
    main()
