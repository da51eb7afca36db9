#!/usr/bin/env bash
# Says plainly when the Rust toolchain cannot build rtw, and how to get one
# that can, before a build fails with a compiler or manifest error. The
# minimum is Cargo.toml's rust-version (nalgebra 0.35 and edition 2024 need
# it); Debian 12's packaged rustc (1.63) is far older. Called by
# scripts/test.sh; README.md ("Getting Rust") gives the same advice.
. "$(dirname "$0")/lib.sh"
need=$(sed -n 's/^rust-version = "\([0-9.]*\)"/\1/p' Cargo.toml)
advice="install rustup (https://rustup.rs) as your own user and run 'rustup default stable'; \
a system package's older cargo earlier on PATH must come after ~/.cargo/bin (README.md, Getting Rust)"
if ! command -v cargo >/dev/null || ! command -v rustc >/dev/null; then
  echo "check_toolchain: cargo or rustc not found: rtw needs Rust $need or newer; $advice" >&2
  exit 1
fi
have=$(rustc --version | awk '{print $2}')
# sort -V orders versions: the lower of the two must be the minimum.
if [ "$(printf '%s\n%s\n' "$need" "${have%%-*}" | sort -V | head -1)" != "$need" ]; then
  echo "check_toolchain: rustc $have is older than rtw's minimum, Rust $need (Cargo.toml rust-version); $advice" >&2
  exit 1
fi
echo "check_toolchain: rustc $have (rtw needs $need or newer)"
