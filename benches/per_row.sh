# Sourced by benches/instructions.sh and benches/frame_ratio.sh: `per_row BIN N ARGS...` prints the
# instructions per `snapback sweep` row (CSV included), counted by callgrind (noise-free) as the
# difference between sweeps of 2N and N rows over N, so start-up does not count. One thread, as the rows
# would run on each core.
count() {
  local bin=$1 report
  shift
  report=$(RAYON_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" sweep "$@" \
    2>&1 >/dev/null)
  if grep -q 'Process terminating' <<<"$report"; then
    echo "per_row: valgrind could not run $bin to its end (a build for this CPU may use instructions" \
      "valgrind cannot decode: count the plain x86-64 build, the default)" >&2
    return 1
  fi
  sed -n 's/.*Collected : \([0-9]*\).*/\1/p' <<<"$report"
}
per_row() {
  local bin=$1 n=$2 one two
  shift 2
  one=$(count "$bin" --steps "$n" "$@") || return 1
  two=$(count "$bin" --steps $((2 * n)) "$@") || return 1
  echo $(((two - one) / n))
}
# The plain x86-64 build, in target/portable (`RUSTFLAGS=` overrides .cargo/config.toml's
# target-cpu=native), built if it is not up to date: the binary counted unless another is named. It is
# the build every round's counts were taken on, and valgrind runs it on any x86-64 machine.
portable() {
  local root
  root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  RUSTFLAGS= cargo build --release --quiet --manifest-path "$root/Cargo.toml" \
    --target-dir "$root/target/portable" >&2
  echo "$root/target/portable/release/snapback"
}
