#!/usr/bin/env bash
# Builds the npm package into pkg/: release wasm, wasm-bindgen (--target web), wasm-opt -O3 from
# the npm binaryen package, then the package's own files from js/ (a Node entry point, package.json
# and README templates).
# Usage: scripts/build-pkg.sh            (needs what scripts/setup.sh installs)
set -euo pipefail
cd "$(dirname "$0")/.."

CRATE=subsurf
OUT=pkg
WASM_OPT=node_modules/.bin/wasm-opt   # npm binaryen; Debian's wasm-opt 108 breaks the module

[ -x "$WASM_OPT" ] || { echo "build-pkg: $WASM_OPT missing; run scripts/setup.sh (npm ci)" >&2; exit 1; }

size() { wc -c <"$1" | tr -d ' '; }

echo "== build-pkg: cargo build --release --target wasm32-unknown-unknown --lib"
# --lib: the CLI binary would also be named subsurf.wasm and collide with the library.
cargo build --release --target wasm32-unknown-unknown --lib

rm -rf "$OUT"
echo "== build-pkg: wasm-bindgen --target web --out-dir $OUT"
wasm-bindgen --target web --out-dir "$OUT" "${CARGO_TARGET_DIR:-target}/wasm32-unknown-unknown/release/$CRATE.wasm"

BG="$OUT/${CRATE}_bg.wasm"
BEFORE=$(size "$BG")
echo "== build-pkg: wasm-opt -O3 -ocimfs 10 ($("$WASM_OPT" --version))"
# -ocimfs 10: no inlining of a function of more than 10 instructions into its only caller. By
# default wasm-opt inlines every such function, which folded the whole stencil build into the
# exported shim; V8 compiled that one huge function worse: the limit table's build took 1.27 s
# against 1.02 s with the flag, a subdivide with a UV and a colour channel 16 % longer.
"$WASM_OPT" -O3 -ocimfs 10 --strip-debug --strip-producers "$BG" -o "$BG.opt"
mv "$BG.opt" "$BG"
AFTER=$(size "$BG")

# The same library without SIMD, for engines that do not run it (Safari 15, the last on some
# iPhones): the loaders take it where js/support.js's probe fails. Same glue: wasm-bindgen's
# output for it must equal the SIMD build's, byte for byte, or one glue could not load both.
# Its own target directory keeps both builds incremental; the env key overrides the
# target.wasm32-unknown-unknown.rustflags of .cargo/config.toml (+simd128).
SCALAR="$OUT/${CRATE}_nosimd.wasm"
SCALAR_TARGET="${CARGO_TARGET_DIR:-target}/nosimd"
echo "== build-pkg: the same without simd128 (-> $SCALAR)"
CARGO_TARGET_DIR="$SCALAR_TARGET" CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUSTFLAGS="-C target-feature=-simd128" \
  cargo build --release --target wasm32-unknown-unknown --lib
SCALAR_GLUE=$(mktemp -d)
wasm-bindgen --target web --out-dir "$SCALAR_GLUE" "$SCALAR_TARGET/wasm32-unknown-unknown/release/$CRATE.wasm"
if ! cmp -s "$SCALAR_GLUE/$CRATE.js" "$OUT/$CRATE.js"; then
  echo "build-pkg: wasm-bindgen's glue for the build without SIMD differs from the SIMD build's; one glue cannot load both" >&2
  exit 1
fi
"$WASM_OPT" -O3 -ocimfs 10 --strip-debug --strip-producers "$SCALAR_GLUE/${CRATE}_bg.wasm" -o "$SCALAR"
# No v128 in it: its target_features section alone would not say (a validator trusts that).
"$WASM_OPT" "$SCALAR" --print >"$SCALAR_GLUE/text.wat"
if grep -q -E 'v128|[if](8x16|16x8|32x4|64x2)' "$SCALAR_GLUE/text.wat"; then
  echo "build-pkg: $SCALAR uses SIMD instructions" >&2
  exit 1
fi
rm -rf "$SCALAR_GLUE"

# The package's own files are checked-in sources in js/: init.js (the './init' entry: the glue
# with freed.js, which makes calls on freed objects say so, and support.js, which picks
# subsurf_nosimd.wasm where the engine lacks SIMD and makes a failed load say why), auto.js and three-auto.js (the browser
# and bundler entries of '.' and './three': a top-level `await init()`, so no init call is
# needed), node.js (Node has no fetch() for file:
# URLs, so the plain `await init()` of a --target web build cannot find its .wasm there; this
# entry loads it synchronously: import { subdivide } from 'subsurf/node'), node.d.ts, webgpu.js and
# webgpu.d.ts (subsurf/webgpu: stencil tables evaluated by a WebGPU compute shader), three.js,
# three-node.js and three.d.ts (subsurf/three: subdivideGeometry for three.js; three-node.js is
# its Node entry, which loads the .wasm through node.js first), geometry.js (subsurf/three's
# array-level core, typed arrays in and out, which three.js imports), the worker-*.js and .d.ts
# files (subsurf/worker: subdivide in a Web Worker or a worker_threads thread; worker.js and
# worker-node.js call, worker-thread.js answers, worker-script*.js are the threads' scripts),
# and the package.json and README.md templates, which get the crate's version and description here.
cp js/auto.js js/init.js js/freed.js js/support.js js/three-auto.js js/node.js js/node.d.ts js/webgpu.js js/webgpu.d.ts js/three.js js/three-node.js js/three.d.ts js/geometry.js "$OUT/"
cp js/worker.js js/worker-node.js js/worker.d.ts js/worker-client.js js/worker-thread.js js/worker-thread.d.ts \
  js/worker-script.js js/worker-script-node.js "$OUT/"

VERSION=$(cargo metadata --no-deps --format-version 1 |
  node -e 'let s="";process.stdin.on("data",d=>s+=d).on("end",()=>{const p=JSON.parse(s).packages.find(p=>p.name==="subsurf");process.stdout.write(p.version)})')
DESCRIPTION=$(cargo metadata --no-deps --format-version 1 |
  node -e 'let s="";process.stdin.on("data",d=>s+=d).on("end",()=>{const p=JSON.parse(s).packages.find(p=>p.name==="subsurf");process.stdout.write(p.description||"")})')

VERSION="$VERSION" DESCRIPTION="$DESCRIPTION" node -e '
const fs = require("fs");
const pkg = JSON.parse(fs.readFileSync("js/package.json", "utf8"));
pkg.version = process.env.VERSION;
pkg.description = process.env.DESCRIPTION;
fs.writeFileSync(process.argv[1], JSON.stringify(pkg, null, 2) + "\n");
' "$OUT/package.json"
sed "s/{{VERSION}}/$VERSION/" js/README.md >"$OUT/README.md"

echo "== build-pkg: $OUT/ (version $VERSION)"
printf '   %-24s %9s bytes before wasm-opt, %9s after (%s%%)\n' "${CRATE}_bg.wasm" "$BEFORE" "$AFTER" \
  "$(( (AFTER - BEFORE) * 100 / BEFORE ))"
for f in "$OUT"/*; do printf '   %-24s %9s bytes\n' "$(basename "$f")" "$(size "$f")"; done
