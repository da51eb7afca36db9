"""Fails if any dependency needs a newer Rust than the workspace's
`rust-version` (Cargo.toml) says, from `cargo metadata`'s per-package
`rust_version`. (rtw's own code is held to the same version by clippy's
`incompatible_msrv` lint, which test.sh runs with -D warnings.)

Usage: python scripts/check_msrv.py   (runs `cargo metadata` itself)
"""

from __future__ import annotations

import json
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def version(v: str) -> tuple[int, ...]:
    parts = [int(x) for x in v.split(".")]
    return tuple(parts + [0] * (3 - len(parts)))


def main() -> int:
    declared = tomllib.loads((ROOT / "Cargo.toml").read_text())["workspace"]["package"]["rust-version"]
    meta = json.loads(
        subprocess.run(
            ["cargo", "metadata", "--format-version", "1", "--locked"],
            cwd=ROOT,
            check=True,
            capture_output=True,
            text=True,
        ).stdout
    )
    members = set(meta["workspace_members"])
    needs = sorted(
        ((p["rust_version"], p["name"], p["version"]) for p in meta["packages"]
         if p["id"] not in members and p.get("rust_version")),
        key=lambda r: version(r[0]),
        reverse=True,
    )
    too_new = [r for r in needs if version(r[0]) > version(declared)]
    if too_new:
        for rv, name, v in too_new:
            print(f"check_msrv: {name} {v} needs Rust {rv} > rust-version {declared} (Cargo.toml)", file=sys.stderr)
        return 1
    # The README tells a new user which Rust to get: it must name this minimum.
    readme = (ROOT / "README.md").read_text()
    if f"Rust {declared} or newer" not in readme:
        print(f"check_msrv: README.md does not say 'Rust {declared} or newer' (Cargo.toml rust-version)", file=sys.stderr)
        return 1
    top = needs[0] if needs else ("none", "-", "-")
    print(f"check_msrv: rust-version {declared} covers every dependency (highest: {top[1]} {top[2]} needs {top[0]})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
