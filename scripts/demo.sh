#!/usr/bin/env bash
# Builds the package and serves the demo page:
#   scripts/demo.sh                 → http://127.0.0.1:8080/
#   PORT=9000 scripts/demo.sh       → another port
# Set SKIP_BUILD=1 to serve the last build. Stop with Ctrl-C.
set -euo pipefail
cd "$(dirname "$0")/.."
PORT=${PORT:-8080}

scripts/setup.sh
[ "${SKIP_BUILD:-0}" = 1 ] || scripts/build-pkg.sh

# www/ imports ./pkg/subsurf.js; a copy (not a link) so any static server can serve www/ alone.
rm -rf www/pkg
cp -r pkg www/pkg

echo
echo "subsurf demo: http://127.0.0.1:$PORT/   (Ctrl-C to stop)"
# python's http.server sends .wasm as application/wasm, which WebAssembly.instantiateStreaming needs.
exec python3 -m http.server "$PORT" --bind 127.0.0.1 --directory www
