#!/usr/bin/env bash
# Sobol indices of the paper's sensitivity claims ("failure seemed rather
# independent of rho and zeta ... alpha, f_n and phi showed a clear
# influence", docs/reproduction.md): the Saltelli scan of the paper's box
#   configs/sensitivity-saltelli.toml -> results/sensitivity/saltelli/
# its first-order and total indices with 95 % bootstrap half-widths
#   -> results/sensitivity/indices.parquet
# and their tables (scripts/sobol_indices_report.py) -> results/sensitivity/indices.md
# (229376 runs: about 6 minutes on 2 idle cores). results/sensitivity/ also holds the
# per-modelling-choice runs of scripts/sensitivity.sh; neither script touches
# the other's files.
. "$(dirname "$0")/lib.sh"
rtw_build
rm -rf results/sensitivity/saltelli
"$RTW_BIN" run configs/sensitivity-saltelli.toml --out results/sensitivity/saltelli >/dev/null
"$RTW_BIN" sensitivity results/sensitivity/saltelli --out results/sensitivity/indices.parquet >/dev/null
rtw_install
"$RTW_PY" scripts/sobol_indices_report.py results/sensitivity
