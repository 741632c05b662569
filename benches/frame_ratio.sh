#!/usr/bin/env bash
# Issue 23's speed goal: instructions per `snapback sweep` row on a free 188 g frame against the same bounce
# clamped, counted by callgrind (benches/per_row.sh).
# Usage: bash benches/frame_ratio.sh [path/to/snapback] [N] (by default the plain x86-64 build, benches/per_row.sh)
set -euo pipefail
n=${2:-300}
# shellcheck source=benches/per_row.sh
source "$(dirname "$0")/per_row.sh"
bin=${1:-$(portable)}
row() {
  per_row "$bin" "$n" --vary speed --from 10 --to 10.000001 "$@"
}
printf '%-22s %9s %9s %6s\n' bounce clamped frame ratio
while read -r name args; do
  # shellcheck disable=SC2086 # the flags are words
  clamped=$(row $args)
  # shellcheck disable=SC2086
  framed=$(row $args --frame-mass 188g)
  printf '%-22s %9d %9d %6s\n' "$name" "$clamped" "$framed" \
    "$(awk -v f="$framed" -v c="$clamped" 'BEGIN { printf "%.2f", f / c }')"
done <<'CASES'
fig3c
string30 --cart-friction 30
compliant --ball-stiffness 100kN/m --ball-damping 0.3
compliant+string --ball-stiffness 100kN/m --ball-damping 0.3 --cart-friction 30
chain4 --chain 4
chain4+string --chain 4 --cart-friction 30
chain4+ball+string --chain 4 --ball-stiffness 100kN/m --ball-damping 0.3 --cart-friction 30
CASES
