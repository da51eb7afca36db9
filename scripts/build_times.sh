#!/usr/bin/env bash
# The first hour of a fresh clone, as the cold build time of each build step
# of the three commands a new user runs first (docs/testing.md, "Build
# times"), in the order a user runs them, in a fresh clone of each revision
# with an empty target directory:
#   1. the main command's build (README): cargo build --release -p rtw-scan
#   2. the Python package as the README installs it, into a venv `v`
#      (pip install ./crates/rtw-py; maturin builds it in target/)
#   3. the test command's builds (scripts/test.sh): clippy, rustdoc, every
#      test binary (cargo test --no-run), and its install of the package
#      into .venv
# Only the builds are timed: maturin, which pip downloads, is fetched into
# both venvs before the clock starts. Writes to stdout the Markdown of
# results/bench/build-times.md: a summary (seconds per step and revision)
# and, per revision, its steps with the crates each compiled or checked (a
# crate compiled again by a later step was not reused).
#   ./scripts/build_times.sh REV:LABEL...   # e.g. HEAD:now; ~10 min per revision on two idle cores
. "$(dirname "$0")/lib.sh"
[ $# -ge 1 ] || { echo "usage: build_times.sh REV:LABEL..." >&2; exit 2; }
root=$(pwd)
work=$(mktemp -d /tmp/rtw-build-times.XXXXXX)
trap 'rm -rf "$work"' EXIT
started=$(date -u '+%Y-%m-%d, %H:%M')
k=0
for spec in "$@"; do
  rev=${spec%%:*} label=${spec#*:}
  k=$((k + 1))
  clone="$work/rtw-$k"
  git clone -q "$root" "$clone"
  (
    cd "$clone"
    git checkout -q "$rev"
    export CARGO_TARGET_DIR="$clone/target"
    python3 -m venv v && v/bin/pip install --quiet --disable-pip-version-check maturin==1.16.0
    python3 -m venv .venv && .venv/bin/pip install --quiet --disable-pip-version-check maturin==1.16.0
    n=0
    step() {
      local name=$1; shift
      n=$((n + 1))
      local log="$work/rev-$k-step-$n.log" t0 t1 compiled
      t0=$(date +%s.%N)
      "$@" > "$log" 2>&1 || { echo "build_times: $rev: $name failed:" >&2; tail -20 "$log" >&2; exit 1; }
      t1=$(date +%s.%N)
      compiled=$(grep -cE '^\s*(Compiling|Checking|Documenting)' "$log" || true)
      printf '| %s | %s | %s |\n' "$name" "$(awk "BEGIN { printf \"%.0f\", $t1 - $t0 }")" "$compiled"
    }
    load=$(cut -d' ' -f1-3 /proc/loadavg)
    {
      echo "| step | seconds | crates compiled (or checked) |"
      echo "|---|---:|---:|"
      step "main: cargo build --release -p rtw-scan" cargo build --release -p rtw-scan
      step "python: pip install ./crates/rtw-py (README venv v)" \
        env PATH="$PWD/v/bin:$PATH" v/bin/pip install -v --no-build-isolation --no-deps ./crates/rtw-py
      step "test: cargo clippy --workspace --all-targets" cargo clippy --workspace --all-targets --release -- -D warnings
      step "test: cargo doc --workspace" env RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --release
      step "test: cargo test --workspace --no-run" cargo test --workspace --release --no-run
      step "test: pip install into .venv" \
        env PATH="$PWD/.venv/bin:$PATH" .venv/bin/pip install -v --no-build-isolation --no-deps ./crates/rtw-py
      echo
      echo "(rev $(git rev-parse --short HEAD), $(nproc) cores, load average before: $load)"
    } > "$work/rev-$k.md"
  )
  echo "build_times: $rev done" >&2
  rm -rf "$clone"
done
python3 - "$work" "$started" "$@" <<'PY'
import shlex
import sys
work, started, specs = sys.argv[1], sys.argv[2], sys.argv[3:]
runs = []
for k, spec in enumerate(specs, 1):
    rev, label = spec.split(":", 1)
    text = open(f"{work}/rev-{k}.md").read().strip()
    rows = [l.split("|") for l in text.splitlines() if l.startswith("| ") and not l.startswith("| step")]
    runs.append((text.rsplit("rev ", 1)[1].split(",")[0], label, text, [(r[1].strip(), int(r[2])) for r in rows]))
out = ["# Build times of a fresh clone", "",
       f"`./scripts/build_times.sh {' '.join(shlex.quote(x) for x in specs)}` on a machine with 2 cores ({started} UTC): for each "
       "revision a fresh clone and an empty `target/`, then each build step of the three first commands (the "
       "main command, the Python package as the README installs it, the test command), timed, and the crates "
       "each step compiled or checked. One run each: these machines drift by ±30 % between runs.",
       "", "## Summary", "",
       "| step | " + " | ".join(f"{r} ({l})" for r, l, _, _ in runs) + " |", "|---|" + "---:|" * len(runs)]
for i, (step, _) in enumerate(runs[0][3]):
    out.append(f"| {step} | " + " | ".join(str(r[3][i][1]) for r in runs) + " |")
totals = [sum(v for _, v in r[3]) for r in runs]
tests = [sum(v for s, v in r[3] if s.startswith("test:")) for r in runs]
out += ["| **the test command's four steps, after the main command** | "
        + " | ".join(f"**{t}**" for t in tests) + " |",
        "| **all six steps** | " + " | ".join(f"**{t}**" for t in totals) + " |", "",
        f"Seconds. The test command's builds after the main command went from {tests[0]} s to "
        f"{tests[-1]} s ({tests[-1] / tests[0]:.2f} of before), the Python package's from "
        f"{runs[0][3][1][1]} s to {runs[-1][3][1][1]} s."]
for rev, label, text, _ in runs:
    out += ["", f"## {rev}: {label}", "", text]
print("\n".join(out))
PY
