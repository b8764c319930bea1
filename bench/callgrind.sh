#!/usr/bin/env bash
# Instructions of one attribute call (examples/attribute_call.rs: Catmull-Clark, 1M-quad torus,
# level 1), positions only and with a uv and a colour, counted by callgrind: deterministic for
# the same binary, unlike timings on this shared machine, so a change to the attribute path can
# be judged by it (it counts no page faults or cache misses: confirm with bench/attributes.mjs).
# Prints each case's instructions in all (the input made too), in the level loop
# (`refine_with_attributes`) and in building the mesh (`from_faces`), then the functions with the
# most of their own. Needs valgrind (apt-get install valgrind). Built with line tables in a
# target directory of its own, so that the tests' release builds are not redone.
#   bench/callgrind.sh [TOP]
set -euo pipefail
cd "$(dirname "$0")/.."
command -v valgrind >/dev/null || { echo "callgrind.sh: valgrind missing (apt-get install valgrind)" >&2; exit 1; }
TOP=${1:-12}
TARGET=target/callgrind
# Line tables, so that callgrind names the functions (the release profile has none).
CARGO_PROFILE_RELEASE_DEBUG=1 CARGO_TARGET_DIR=$TARGET cargo build -q --release --example attribute_call
for case in plain uv-color; do
  valgrind --tool=callgrind --callgrind-out-file="$TARGET/$case.out" \
    "$TARGET/release/examples/attribute_call" "$case" >/dev/null 2>&1
  inclusive() {
    callgrind_annotate --inclusive=yes "$TARGET/$case.out" 2>/dev/null \
      | awk -v f="$1" 'index($0, f) && /^ *[0-9,]+ \(/ { print $1; exit }'
  }
  echo "== $case: $(inclusive 'PROGRAM TOTALS') instructions; level loop $(inclusive 'scheme::refine_with_attributes ['), mesh build $(inclusive 'build::from_faces ')"
  callgrind_annotate --inclusive=no "$TARGET/$case.out" 2>/dev/null \
    | grep -E '^ *[0-9,]+ \(' | sed -n "2,$((TOP + 1))p" | cut -c1-150
done
