#!/usr/bin/env bash
# Issue 23's speed goal: instructions per `snapback sweep` row on a free 188 g frame against the same bounce
# clamped, counted by callgrind (noise-free) as benches/instructions.sh counts them (the difference between
# sweeps of 2N and N rows over N). Usage: bash benches/frame_ratio.sh [path/to/snapback] [N]
set -euo pipefail
bin=${1:-target/release/snapback}
n=${2:-300}
count() {
  RAYON_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" sweep "$@" \
    2>&1 >/dev/null | sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
row() {
  local one two
  one=$(count --steps "$n" --vary speed --from 10 --to 10.000001 "$@")
  two=$(count --steps $((2 * n)) --vary speed --from 10 --to 10.000001 "$@")
  echo $(((two - one) / n))
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
