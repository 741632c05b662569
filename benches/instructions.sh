#!/usr/bin/env bash
# Instructions per `snapback sweep` row (CSV included), counted by callgrind (noise-free): the difference
# between sweeps of 2N and N rows over N, so start-up does not count. One thread, as the rows would run
# on each core. Usage: bash benches/instructions.sh [path/to/snapback] [N]
set -euo pipefail
bin=${1:-target/release/snapback}
n=${2:-500}
count() {
  RAYON_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" sweep "$@" \
    2>&1 >/dev/null | sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
row() {
  local name=$1
  shift
  local one two
  one=$(count --steps "$n" "$@")
  two=$(count --steps $((2 * n)) "$@")
  printf '%-34s %8d instructions per row\n' "$name" $(((two - one) / n))
}
# A sweep over the speed by a millionth keeps every bounce the same as at its start.
sweep=(--vary speed --from 10 --to 10.000001)
row "Fig. 3(c)" "${sweep[@]}"
row "chain of 8" "${sweep[@]}" --chain 8
row "compliant ball (100 kN/m, 0.3)" "${sweep[@]}" --ball-stiffness 100kN/m --ball-damping 0.3
row "chain of 8 + that ball" "${sweep[@]}" --chain 8 --ball-stiffness 100kN/m --ball-damping 0.3
