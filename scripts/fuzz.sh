#!/usr/bin/env bash
# Fuzzes subsurf with cargo-fuzz: the OBJ reader, mesh building from arbitrary arrays, and every
# scheme at levels 1-2 on small fuzzed meshes (fuzz/fuzz_targets/). Installs what it needs on a
# fresh machine (nightly with rust-src, cargo-fuzz) and skips what is already there.
#
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]     (default 20 s, every target)
#   FUZZ_RUNS=1000000 scripts/fuzz.sh 0 subdivide        (a fixed number of executions instead)
#   FUZZ_SANITIZER=address scripts/fuzz.sh 600          (under AddressSanitizer)
#
# The committed corpus (fuzz/corpus/TARGET) is read, never written: new inputs go to a scratch
# directory. A crash stops the run with the input in fuzz/artifacts/TARGET/; reproduce it with
# `cargo +nightly fuzz run -s none -a TARGET fuzz/artifacts/TARGET/crash-...` and turn it into a
# regression test in tests/bad_inputs.rs or tests/properties.rs. To refresh the corpus after a
# long run: `cargo +nightly fuzz cmin -s none -a TARGET -- -use_counters=0` (edges only: small).
set -euo pipefail
cd "$(dirname "$0")/.."

SECONDS_PER_TARGET=${1:-20}
shift || true
TARGETS=("$@")
[ "${#TARGETS[@]}" -gt 0 ] || TARGETS=(obj_reader mesh_build subdivide)
CARGO_FUZZ_VERSION=0.13.2

step() { printf '== fuzz: %s\n' "$*"; }

if ! rustup toolchain list | grep -q '^nightly-'; then
  step "rustup toolchain install nightly (about 20 s, once)"
  # --no-self-update: installing a toolchain must not replace the rustup binary itself.
  rustup toolchain install nightly --profile minimal --component rust-src --no-self-update
elif ! rustup component list --toolchain nightly --installed | grep -q '^rust-src'; then
  step "rustup component add rust-src --toolchain nightly"
  rustup component add rust-src --toolchain nightly
fi

if ! command -v cargo-fuzz >/dev/null 2>&1 \
   || [ "$(cargo-fuzz --version | awk '{print $2}')" != "$CARGO_FUZZ_VERSION" ]; then
  step "cargo install cargo-fuzz $CARGO_FUZZ_VERSION (about 1-2 minutes, once)"
  cargo install cargo-fuzz --version "$CARGO_FUZZ_VERSION" --locked
fi

# No sanitizer by default: ASan halves the executions. Debug assertions (-a) turn on overflow
# checks, so arithmetic that would wrap is a crash, and the asserts beside the crate's unsafe
# indexing (the stencil build and evaluation). The unsafe blocks (unchecked indexing, writes
# into reserved room, SIMD loads) want an ASan run now and then:
# `FUZZ_SANITIZER=address scripts/fuzz.sh 600`.
FLAGS=(-s "${FUZZ_SANITIZER:-none}" -a)
step "cargo +nightly fuzz build ${FLAGS[*]}"
cargo +nightly fuzz build "${FLAGS[@]}"

SCRATCH=$(mktemp -d)
trap 'rm -rf "$SCRATCH"' EXIT
TOTAL=0
for target in "${TARGETS[@]}"; do
  mkdir -p "$SCRATCH/$target" "fuzz/corpus/$target"
  if [ -n "${FUZZ_RUNS:-}" ]; then LIMIT=(-runs="$FUZZ_RUNS"); else LIMIT=(-max_total_time="$SECONDS_PER_TARGET"); fi
  step "$target: ${LIMIT[*]} (corpus: $(ls "fuzz/corpus/$target" | wc -l) inputs)"
  log="$SCRATCH/$target.log"
  if ! cargo +nightly fuzz run "${FLAGS[@]}" "$target" "$SCRATCH/$target" "fuzz/corpus/$target" -- \
      "${LIMIT[@]}" -max_len=4096 -print_final_stats=1 >"$log" 2>&1; then
    tail -n 60 "$log"
    echo "fuzz: $target FAILED; the input is in fuzz/artifacts/$target/" >&2
    exit 1
  fi
  runs=$(awk '/stat::number_of_executed_units/ {print $2}' "$log")
  rate=$(awk '/stat::average_exec_per_sec/ {print $2}' "$log")
  printf '   %-11s %10s executions, %7s exec/s, %s new inputs, no crash\n' \
    "$target" "$runs" "$rate" "$(ls "$SCRATCH/$target" | wc -l)"
  TOTAL=$((TOTAL + runs))
done
echo "fuzz: ${#TARGETS[@]} targets, $TOTAL executions, no crash"
