#!/usr/bin/env bash
# Instructions per `snapback sweep` row (CSV included), counted by callgrind (benches/per_row.sh).
# Usage: bash benches/instructions.sh [path/to/snapback] [N] (by default the plain x86-64 build, benches/per_row.sh)
set -euo pipefail
n=${2:-500}
# shellcheck source=benches/per_row.sh
source "$(dirname "$0")/per_row.sh"
bin=${1:-$(portable)}
row() {
  local name=$1 count
  shift
  count=$(per_row "$bin" "$n" "$@")
  printf '%-34s %8d instructions per row\n' "$name" "$count"
}
# A sweep over the speed by a millionth keeps every bounce the same as at its start.
sweep=(--vary speed --from 10 --to 10.000001)
row "Fig. 3(c)" "${sweep[@]}"
row "chain of 8" "${sweep[@]}" --chain 8
row "compliant ball (100 kN/m, 0.3)" "${sweep[@]}" --ball-stiffness 100kN/m --ball-damping 0.3
row "chain of 8 + that ball" "${sweep[@]}" --chain 8 --ball-stiffness 100kN/m --ball-damping 0.3
