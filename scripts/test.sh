#!/usr/bin/env bash
# Runs every test of subsurf, in order, and prints a summary. Exits non-zero if any step fails.
#
#   scripts/test.sh
#
# Steps: setup (installs what is missing), cargo fmt --check, cargo clippy, the API docs (cargo
# doc, natively and for wasm32, warnings as errors: a broken link fails), native cargo test
# (profile test-release: release without LTO, see Cargo.toml),
# wasm-bindgen tests in Node and headless Chromium, the npm package build, a Node smoke test of
# the built package, its entries on an engine without WebAssembly SIMD (support: Node and
# headless Chromium, their WebAssembly changed to refuse it: subsurf_nosimd.wasm loaded and
# giving the SIMD build's results, clear errors), the package as users install it (consumers: npm pack, installed from the
# tarball into fresh Node, Vite, webpack 5 and plain-page projects, the pages run in headless
# Chromium), subsurf/three with real three.js in Node (tests/js/three.mjs, with the
# pinned three and again with 0.150.1, the oldest of its peer range), glTF files of
# OpenSubdiv's shapes read by three's GLTFLoader against OpenSubdiv's results (tests/js/gltf.mjs), native vs
# wasm agreement on seeded random meshes (the fixture comes from the native tests), the demo
# page end-to-end test (when tests/e2e/demo.mjs exists), subsurf/webgpu's compute shader against
# a JS reference in headless Chromium on SwiftShader (e2e-webgpu), subsurf/three drawn by a real
# three.js WebGLRenderer in headless Chromium, pixels read back (e2e-three), the glTF page
# (www/gltf.html: glTF files opened, subdivided beside the original, textures, skinning, morphs,
# dense cages drawn faint on both demo pages) end to end (e2e-gltf), a real textured glTF
# model from npm (@pmndrs/assets) subdivided and drawn there too (e2e-gltf-model),
# every ```js example of README.md and js/README.md run as pasted, with checks of what it claims
# (readme: Node, and Chromium for the WebGPU and worker-script ones),
# subsurf/worker in Node's worker_threads (worker-node) and in headless Chromium (e2e-worker:
# byte for byte with the main thread, transfers, progress, abort, errors), and a short fuzz run
# of every cargo-fuzz target (scripts/fuzz.sh; installs nightly and cargo-fuzz once).
# A step whose input failed to build is skipped and counted as a failure.
set -uo pipefail
cd "$(dirname "$0")/.."

LOGS=artifacts/test-logs
mkdir -p "$LOGS"
NAMES=()
RESULTS=()
TIMES=()
FAILED=0

# run NAME COMMAND...: runs a step, tees its output to $LOGS/NAME.log, records status and time.
run() {
  local name=$1
  shift
  printf '\n==== %s: %s\n' "$name" "$*"
  local start=$SECONDS
  "$@" 2>&1 | tee "$LOGS/$name.log"
  local status=${PIPESTATUS[0]}
  record "$name" "$([ "$status" -eq 0 ] && echo ok || echo "FAILED (exit $status)")" $((SECONDS - start))
  return "$status"
}

record() {
  NAMES+=("$1")
  RESULTS+=("$2")
  TIMES+=("$3")
  [ "$2" = ok ] || FAILED=1
}

skip() {
  printf '\n==== %s: skipped (%s)\n' "$1" "$2"
  record "$1" "SKIPPED ($2)" 0
}

summary() {
  printf '\n==== summary\n'
  for i in "${!NAMES[@]}"; do
    printf '  %-16s %5ss  %s\n' "${NAMES[$i]}" "${TIMES[$i]}" "${RESULTS[$i]}"
  done
  if [ "$FAILED" -eq 0 ]; then
    printf 'all tests passed (%ss)\n' "$SECONDS"
  else
    printf 'SOME STEPS FAILED; logs in %s/\n' "$LOGS"
  fi
}
trap summary EXIT

# The wasm test runner picks the first WebDriver it finds; name Chromium's explicitly.
if [ -z "${CHROMEDRIVER:-}" ] && command -v chromedriver >/dev/null 2>&1; then
  export CHROMEDRIVER=$(command -v chromedriver)
fi

# Checks the closing `test result:` lines of the wasm tests: Node and Chromium must each have
# run every shared case (a silently skipped browser run would otherwise look like a pass).
check_wasm_counts() {
  local log=$LOGS/wasm-tests.log
  local expected
  expected=$(cat tests/common/wasm_*.rs | grep -c '^#\[wasm_bindgen_test\]')
  local ok=0
  for target in wasm_node wasm_browser; do
    local line
    line=$(awk -v t="tests/$target.rs" 'index($0, "Running " t) { on = 1 } on && /^test result:/ { print; exit }' "$log")
    printf '  %-13s %s\n' "$target:" "${line:-no test result line}"
    if ! [[ "$line" =~ ^test\ result:\ ok\.\ ([0-9]+)\ passed\;\ 0\ failed ]] || [ "${BASH_REMATCH[1]}" -ne "$expected" ]; then
      echo "  expected 'test result: ok. $expected passed; 0 failed' for $target" >&2
      ok=1
    fi
  done
  if ! grep -q 'Running headless tests in Chrome' "$log"; then
    echo "  the browser tests did not run in Chrome" >&2
    ok=1
  fi
  return $ok
}

run setup scripts/setup.sh || { echo "setup failed; nothing else can run" >&2; exit 1; }
run fmt cargo fmt --check
run clippy cargo clippy --all-targets -- -D warnings
run docs env RUSTDOCFLAGS='-D warnings' sh -c \
  'cargo doc --no-deps && cargo doc --no-deps --target wasm32-unknown-unknown'
# Written by the native test native_vs_wasm_fixture; removed first so a stale one never passes.
rm -f artifacts/native-vs-wasm.json
run native-tests cargo test --profile test-release
if run wasm-tests cargo test --target wasm32-unknown-unknown; then
  run wasm-counts check_wasm_counts
else
  skip wasm-counts "wasm tests failed"
fi
if run build-pkg scripts/build-pkg.sh; then
  run pkg-smoke node tests/js/pkg_smoke.mjs
  run support node tests/js/support.mjs
  run consumers node tests/js/consumers.mjs
  run three node tests/js/three.mjs
  run gltf node tests/js/gltf.mjs
  run three-r150 node tests/js/three.mjs --three node_modules/three-r150
  run worker-node node tests/js/worker_node.mjs
  run readme node tests/js/readme.mjs
  run native-vs-wasm node tests/js/native_vs_wasm.mjs
  if [ -f tests/e2e/demo.mjs ]; then
    run e2e-demo node tests/e2e/demo.mjs
  else
    skip e2e-demo "tests/e2e/demo.mjs does not exist"
  fi
  run e2e-webgpu node tests/e2e/webgpu.mjs
  run e2e-three node tests/e2e/three.mjs
  run e2e-gltf node tests/e2e/gltf.mjs
  run e2e-gltf-model node tests/e2e/gltf_model.mjs
  run e2e-worker node tests/e2e/worker.mjs
else
  skip pkg-smoke "package build failed"
  skip consumers "package build failed"
  skip three "package build failed"
  skip gltf "package build failed"
  skip three-r150 "package build failed"
  skip readme "package build failed"
  skip native-vs-wasm "package build failed"
  skip e2e-demo "package build failed"
  skip e2e-webgpu "package build failed"
  skip e2e-three "package build failed"
  skip e2e-gltf "package build failed"
  skip e2e-gltf-model "package build failed"
  skip worker-node "package build failed"
  skip e2e-worker "package build failed"
fi
run fuzz scripts/fuzz.sh 20

exit "$FAILED"
