#!/usr/bin/env bash
# Builds the npm package into pkg/: release wasm, wasm-bindgen (--target web), wasm-opt -O3 from
# the npm binaryen package, then package.json, a Node entry point and a README.
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
echo "== build-pkg: wasm-opt -O3 ($("$WASM_OPT" --version))"
"$WASM_OPT" -O3 --strip-debug --strip-producers "$BG" -o "$BG.opt"
mv "$BG.opt" "$BG"
AFTER=$(size "$BG")

# Node has no fetch() for file: URLs, so the plain `await init()` of a --target web build cannot
# find its .wasm there. This entry loads it synchronously: import { subdivide } from 'subsurf/node'.
cat >"$OUT/node.js" <<'JS'
import { readFileSync } from 'node:fs';
import { initSync } from './subsurf.js';

initSync({ module: readFileSync(new URL('./subsurf_bg.wasm', import.meta.url)) });

export * from './subsurf.js';
JS
cat >"$OUT/node.d.ts" <<'TS'
/* The subsurf API, already initialised: no init() call needed in Node. */
export * from './subsurf.js';
TS

VERSION=$(cargo metadata --no-deps --format-version 1 |
  node -e 'let s="";process.stdin.on("data",d=>s+=d).on("end",()=>{const p=JSON.parse(s).packages.find(p=>p.name==="subsurf");process.stdout.write(p.version)})')
DESCRIPTION=$(cargo metadata --no-deps --format-version 1 |
  node -e 'let s="";process.stdin.on("data",d=>s+=d).on("end",()=>{const p=JSON.parse(s).packages.find(p=>p.name==="subsurf");process.stdout.write(p.description||"")})')

VERSION="$VERSION" DESCRIPTION="$DESCRIPTION" node -e '
const fs = require("fs");
const pkg = {
  name: "subsurf",
  version: process.env.VERSION,
  description: process.env.DESCRIPTION,
  license: "MIT OR Apache-2.0",
  type: "module",
  main: "./subsurf.js",
  module: "./subsurf.js",
  types: "./subsurf.d.ts",
  files: ["subsurf.js", "subsurf.d.ts", "subsurf_bg.wasm", "subsurf_bg.wasm.d.ts", "node.js", "node.d.ts", "README.md"],
  exports: {
    ".": { types: "./subsurf.d.ts", default: "./subsurf.js" },
    "./node": { types: "./node.d.ts", default: "./node.js" },
    "./subsurf_bg.wasm": "./subsurf_bg.wasm",
    "./package.json": "./package.json"
  },
  sideEffects: ["./node.js"],
  engines: { node: ">=18" },
  keywords: ["subdivision", "catmull-clark", "mesh", "webassembly", "webgl"]
};
fs.writeFileSync(process.argv[1], JSON.stringify(pkg, null, 2) + "\n");
' "$OUT/package.json"

cat >"$OUT/README.md" <<MD
# subsurf $VERSION

Subdivision surfaces (Catmull-Clark, Loop, Doo-Sabin, Quad/Triangle, bilinear, midpoint) on flat
typed arrays, compiled from Rust to WebAssembly.

\`\`\`js
// Browser or bundler
import init, { subdivide } from 'subsurf';
await init();

// Node 18+: loads the .wasm synchronously, no init() needed
import { subdivide } from 'subsurf/node';

const out = subdivide(
  { positions: Float32Array, indices: Uint32Array, faceSizes: Uint32Array /* omit for triangles */ },
  { scheme: 'catmull-clark', levels: 2, boundary: 'edge-and-corner', maxFaces: 1e6 },
);
// out: { positions: Float32Array, indices: Uint32Array, faceSizes: Uint32Array, triangles: Uint32Array }
\`\`\`

\`scheme\` may also be an array, one name per level. \`schemeNames()\` and \`boundaryRules()\` list the
accepted names; \`readObj(text)\`, \`writeObj(mesh)\` and \`version()\` complete the API. Errors are
thrown as \`Error\` with a message that says what was wrong; the module stays usable afterwards.
MD

echo "== build-pkg: $OUT/ (version $VERSION)"
printf '   %-24s %9s bytes before wasm-opt, %9s after (%s%%)\n' "${CRATE}_bg.wasm" "$BEFORE" "$AFTER" \
  "$(( (AFTER - BEFORE) * 100 / BEFORE ))"
for f in "$OUT"/*; do printf '   %-24s %9s bytes\n' "$(basename "$f")" "$(size "$f")"; done
