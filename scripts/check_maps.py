"""Keeps the maps of rtw-scan's subcommands in step with the binary: reads the
subcommands from the built binary's help (`rtw-scan --help`, its "Commands:"
list, `help` left out) and checks that each file of MAPS names every one of
them in its passage, and names nothing there that is not one.

A map is (file, passage, name): `passage` a regular expression whose first
match (its group 1 if it has one) is the part of the file that lists the
subcommands (None: the whole file), `name` one whose group 1 is a subcommand
named there. A file moves, or
a new map is kept in step, by changing MAPS alone.

Usage: python3 scripts/check_maps.py [--bin PATH]   (default target/release/rtw-scan;
build it first: cargo build --release -p rtw-scan). Exits 1 on any map out of step.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

MAPS = [
    # The README's list: its "What rtw does" names every subcommand, each line in docs/commands.md.
    ("README.md", r"^## What rtw does\n.*?(?=^## )", r"`rtw-scan ([a-z][a-z-]*)`"),
    # The one-line-each list the README points to: its first block of commands.
    ("docs/commands.md", r"^## The commands\n.*?^```sh\n.*?^```", r"^rtw-scan ([a-z][a-z-]*)"),
    # The reference: one heading per subcommand.
    ("docs/cli.md", None, r"^### `rtw-scan ([a-z][a-z-]*)`"),
    # The layers' tour: the command's table, each subcommand and the entry it calls.
    ("docs/architecture.md", r"^  \| subcommand \|.*?\n((?:  \|[^\n]*\n)+)", r"^  \| `rtw-scan ([a-z][a-z-]*)` \|"),
    # The command crate's table of subcommands: one row each, its first cell the name.
    ("crates/rtw-scan/src/lib.rs", r"^//! \| subcommand \|.*?\n((?://! \|[^\n]*\n)+)", r"^//! \| `([a-z][a-z-]*)` \|"),
]


def subcommands(binary: str) -> list[str]:
    """The subcommands the binary's --help lists under "Commands:"."""
    try:
        out = subprocess.run([binary, "--help"], check=True, capture_output=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        sys.exit(f"check_maps: cannot run {binary} --help ({e}): build it first (cargo build --release -p rtw-scan)")
    block = re.search(r"^Commands:\n(.*?)(?:\n\n|\Z)", out, re.M | re.S)
    if not block:
        sys.exit(f"check_maps: {binary} --help has no 'Commands:' list")
    names = [line.split()[0] for line in block.group(1).splitlines() if line.strip()]
    return [n for n in names if n != "help"]


def named(path: Path, passage: str | None, name: str) -> tuple[list[str], str | None]:
    """The subcommands a map names, in order, and why none could be read."""
    if not path.is_file():
        return [], f"{path.relative_to(ROOT)} does not exist"
    text = path.read_text()
    if passage is not None:
        m = re.search(passage, text, re.M | re.S)
        if not m:
            return [], f"{path.relative_to(ROOT)} has no passage matching {passage!r}"
        text = m.group(1) if m.re.groups else m.group(0)
    return re.findall(name, text, re.M), None


def check(commands: list[str]) -> list[str]:
    bad = []
    for file, passage, name in MAPS:
        found, why = named(ROOT / file, passage, name)
        if why:
            bad.append(f"{file}: {why}")
            continue
        missing = [c for c in commands if c not in found]
        extra = sorted(set(found) - set(commands))
        if missing:
            bad.append(f"{file}: names {len(set(found) & set(commands))} of the {len(commands)} subcommands; "
                       f"missing: {', '.join(missing)}")
        if extra:
            bad.append(f"{file}: names as subcommands what rtw-scan --help does not list: {', '.join(extra)}")
    return bad


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    default = os.path.join(os.environ.get("CARGO_TARGET_DIR", "target"), "release", "rtw-scan")
    ap.add_argument("--bin", default=str(ROOT / default), help="the rtw-scan binary [default: %(default)s]")
    args = ap.parse_args()
    commands = subcommands(args.bin)
    bad = check(commands)
    for b in bad:
        print(f"check_maps: {b}", file=sys.stderr)
    print(f"check_maps: {len(commands)} subcommands ({', '.join(commands)}); "
          f"{len(MAPS) - len({b.split(':')[0] for b in bad})} of {len(MAPS)} maps in step")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
