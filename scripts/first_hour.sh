#!/usr/bin/env bash
# A new user's first hour, walked (docs/testing.md, "A new user's first
# hour"): as root, makes a throwaway user without root, gives it the Rust
# toolchain that README.md's "Getting Rust" leads to (rustup with the stable
# toolchain in the user's own ~/.rustup and ~/.cargo/bin: fetched by rustup.rs
# where it can be reached, otherwise copied from this machine's rustup, which
# is the same thing rustup would install), clones REV into that user's home
# with nothing built and no crate fetched, and times, as that user, in
# README.md's order:
#   1. the main command:  cargo run --release -p rtw-scan -- run configs/paper.toml
#   2. the Python package: python3 -m venv v && v/bin/pip install './crates/rtw-py[plot]'
#   3. the test command:  ./scripts/test.sh
# Each step's output goes to the user's home (first-hour-N.log); a step
# that fails stops the walk and prints its log's end. Writes the Markdown of
# results/bench/first-hour.md to stdout. The user and its home are removed
# at the end.
#   sudo ./scripts/first_hour.sh [REV]   # REV defaults to HEAD; about 35 min on two idle cores
set -euo pipefail
cd "$(dirname "$0")/.."
[ "$(id -u)" -eq 0 ] || { echo "first_hour.sh: run as root (it makes a user)" >&2; exit 2; }
rev=$(git rev-parse --short "${1:-HEAD}")
root=$(pwd)
user=rtw-first-hour
home=/home/$user
id "$user" >/dev/null 2>&1 && userdel -r "$user" >/dev/null 2>&1 || true
useradd --create-home --shell /bin/bash "$user"
trap 'userdel -r "$user" >/dev/null 2>&1 || true; rm -f "${work_skipped:-}"' EXIT

# The toolchain, as rustup installs it for one user.
if curl -fsS --max-time 10 https://sh.rustup.rs -o "$home/rustup-init.sh" 2>/dev/null; then
  how="rustup-init from rustup.rs, then rustup default stable"
  su - "$user" -c 'sh ~/rustup-init.sh -y --profile default --default-toolchain none >/dev/null 2>&1'
else
  how="no network to rustup.rs here: this machine's rustup and its stable toolchain copied into the user's ~/.rustup and ~/.cargo/bin"
  src_rustup=${RUSTUP_HOME:-$HOME/.rustup} src_cargo=${CARGO_HOME:-$HOME/.cargo}
  mkdir -p "$home/.rustup/toolchains" "$home/.cargo/bin"
  stable=$(readlink -f "$src_rustup/toolchains/stable-$(uname -m)-unknown-linux-gnu")
  cp -a "$stable" "$home/.rustup/toolchains/"
  cp -a "$src_rustup/settings.toml" "$home/.rustup/" 2>/dev/null || true
  cp -a "$src_cargo/bin/." "$home/.cargo/bin/"
  # Tools installed beside rustup here that a new user would not have.
  rm -f "$home/.cargo/bin/"cargo-{nextest,hakari} 2>/dev/null || true
  chown -R "$user:$user" "$home/.rustup" "$home/.cargo"
fi
git clone -q "$root" "$home/rtw"
git -C "$home/rtw" checkout -q "$rev"
chown -R "$user:$user" "$home/rtw"
su - "$user" -c 'cd rtw && PATH=$HOME/.cargo/bin:$PATH rustup default stable >/dev/null 2>&1'

load=$(cut -d' ' -f1-3 /proc/loadavg)
started=$(date -u '+%Y-%m-%d %H:%M')
rows=()
n=0
step() { # NAME COMMAND: one timed step, as the user, from the clone's root
  local name=$1 cmd=$2 t0 t1
  n=$((n + 1))
  t0=$(date +%s)
  if ! su - "$user" -c "cd rtw && export PATH=\$HOME/.cargo/bin:/usr/local/bin:/usr/bin:/bin && $cmd" \
    >"$home/first-hour-$n.log" 2>&1; then
    echo "first_hour.sh: step $n ($name) failed; the end of its log:" >&2
    tail -30 "$home/first-hour-$n.log" >&2
    exit 1
  fi
  t1=$(date +%s)
  rows+=("| $n | \`$cmd\` | $(( (t1 - t0) / 60 )) min $(( (t1 - t0) % 60 )) s |")
  grep -E 'SKIPPED' "$home/first-hour-$n.log" | sed 's/^/    /' >>"$work_skipped" || true
}
work_skipped=$(mktemp)
step "main command" "cargo run --release -p rtw-scan -- run configs/paper.toml"
step "Python package" "python3 -m venv v && v/bin/pip install --quiet './crates/rtw-py[plot]'"
step "test command" "./scripts/test.sh"
grep -q "all checks passed" "$home/first-hour-3.log" || { echo "first_hour.sh: the test command did not say 'all checks passed'" >&2; exit 1; }

echo "# A new user's first hour: README.md's three commands as a user without root"
echo
echo "Walked by \`sudo ./scripts/first_hour.sh\` at $rev, $started UTC, as the user $user (uid $(id -u "$user"), no root); $(nproc) cores, load average before $load, after $(cut -d' ' -f1-3 /proc/loadavg). Toolchain: $how ($(su - "$user" -c 'PATH=$HOME/.cargo/bin:$PATH rustc --version'))."
echo
echo "## Steps"
echo
echo "| step | command (README.md) | wall time |"
echo "|---:|---|---:|"
printf '%s\n' "${rows[@]}"
echo
echo "The test command ended with \"all checks passed except the Slurm tier\"; what it skipped as a user without root:"
echo
echo '```'
if [ -s "$work_skipped" ]; then cat "$work_skipped"; else echo "    (nothing)"; fi
echo '```'
