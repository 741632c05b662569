# Sourced by benches/instructions.sh and benches/frame_ratio.sh: `per_row BIN N ARGS...` prints the
# instructions per `snapback sweep` row (CSV included), counted by callgrind (noise-free) as the
# difference between sweeps of 2N and N rows over N, so start-up does not count. One thread, as the rows
# would run on each core.
count() {
  local bin=$1
  shift
  RAYON_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" sweep "$@" \
    2>&1 >/dev/null | sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
per_row() {
  local bin=$1 n=$2 one two
  shift 2
  one=$(count "$bin" --steps "$n" "$@")
  two=$(count "$bin" --steps $((2 * n)) "$@")
  echo $(((two - one) / n))
}
