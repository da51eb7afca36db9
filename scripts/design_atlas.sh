#!/usr/bin/env bash
# The design atlas (docs/design.md): the searches of configs/design/ into
# runs/design/search/NAME/ (search.parquet, designs.parquet, search.md),
# the Sobol designs of the widest config (what sets the winners apart), the
# gait families (each of widest, shallowest, fastest and robust searched
# again for one gait, GAIT-ROLE: the config with gait = "GAIT"; the widest
# walk is widest-walk), then scripts/design_atlas.py: every winner's fine
# profile and figure, the Fig. 7(a) design on the same axes,
# results/design/designs-NAME.parquet (each search's reported designs: rho,
# alpha, fn, zeta, phi_lo, phi_hi, gait, each interval checked by direct
# simulation for its gait), atlas.png, families.png, atlas.md and the
# animations.
#   ./scripts/design_atlas.sh [--analyse-only]     # ~15 min on two idle cores
. "$(dirname "$0")/lib.sh"
OUT=results/design
GAITS=(walk skip crawl)
ROLES=(widest shallowest fastest robust)
if [[ "${1:-}" != "--analyse-only" ]]; then
  rtw_build
  mkdir -p runs/design/families
  sed -e 's/^seed = 1/seed = 1\nmethod = "sobol"/' -e 's/^name = "widest"/name = "widest-sobol"/' \
    configs/design/widest.toml > runs/design/widest-sobol.toml
  searches=(configs/design/widest configs/design/widest-walk configs/design/shallowest configs/design/front
            configs/design/fig7a configs/design/robust runs/design/widest-sobol)
  for g in "${GAITS[@]}"; do
    for r in "${ROLES[@]}"; do
      [[ $g-$r == walk-widest ]] && continue
      sed -e "s/^name = .*/name = \"$g-$r\"/" -e "s/^budget = \(.*\)/budget = \1\ngait = \"$g\"/" \
        "configs/design/$r.toml" > "runs/design/families/$g-$r.toml"
      searches+=("runs/design/families/$g-$r")
    done
  done
  # robust.toml's [simulation] table sets the MFPT's roughness (5 cm).
  for c in "${searches[@]}"; do
    "$RTW_BIN" design "$c.toml" --out "runs/design/search/$(basename "$c")" --quiet --force > /dev/null
    echo "design_atlas: $(basename "$c") done" >&2
  done
fi
rtw_install
"$RTW_PY" scripts/design_atlas.py runs/design/search "$OUT"
