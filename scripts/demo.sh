#!/usr/bin/env bash
# Builds the package and serves the demo page on 127.0.0.1:
#   scripts/demo.sh                 → http://127.0.0.1:8080/ (or the next free port)
#   PORT=9000 scripts/demo.sh       → exactly that port
# Set SKIP_BUILD=1 to serve the last build. Stop with Ctrl-C.
# Check a running demo with: DEMO_URL=http://127.0.0.1:8080/ node tests/e2e/demo.mjs
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
[ "${SKIP_BUILD:-0}" = 1 ] || scripts/build-pkg.sh
[ -f pkg/subsurf_bg.wasm ] || { echo "demo: pkg/ is not built; run without SKIP_BUILD=1" >&2; exit 1; }

# www/ imports ./pkg/subsurf.js; a copy (not a link) so any static server can serve www/ alone.
rm -rf www/pkg
cp -r pkg www/pkg

# The glTF page (gltf.html) imports three.js through its import map from www/vendor/three/, laid
# out as the three package is (build/, examples/jsm/), so that the addons' relative imports
# resolve. Copied from node_modules (scripts/setup.sh's npm ci installs the pinned three).
THREE=node_modules/three
[ -f "$THREE/build/three.module.js" ] || { echo "demo: $THREE is missing; run scripts/setup.sh" >&2; exit 1; }
rm -rf www/vendor/three
for file in LICENSE package.json build/three.module.js build/three.core.js \
    examples/jsm/loaders/GLTFLoader.js examples/jsm/controls/OrbitControls.js \
    examples/jsm/utils/BufferGeometryUtils.js examples/jsm/utils/SkeletonUtils.js \
    examples/jsm/environments/RoomEnvironment.js; do
  # three.module.js imports three.core.js in the pinned three; older builds are one file.
  [ -f "$THREE/$file" ] || [ "$file" = build/three.core.js ] || { echo "demo: $THREE/$file is missing" >&2; exit 1; }
  [ -f "$THREE/$file" ] || continue
  mkdir -p "www/vendor/three/$(dirname "$file")"
  cp "$THREE/$file" "www/vendor/three/$file"
done

# Python's http.server, with two additions: no caching (a rebuilt package is picked up on reload)
# and, unless PORT is given, the next free port when 8080 is taken. The URL is printed once the
# socket is bound, so it is always the right one. .wasm goes out as application/wasm and .js as
# text/javascript, which WebAssembly.compileStreaming and module workers need.
exec python3 - "${PORT:-}" <<'PY'
import errno, functools, http.server, socketserver, sys

class Handler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map,
                      '.wasm': 'application/wasm', '.js': 'text/javascript', '.mjs': 'text/javascript'}

    def end_headers(self):
        self.send_header('Cache-Control', 'no-store')
        super().end_headers()

    def log_message(self, format, *args):
        pass  # quiet: one line per request drowns the URL

class Server(socketserver.ThreadingMixIn, http.server.HTTPServer):
    daemon_threads = True

wanted = sys.argv[1]
ports = [int(wanted)] if wanted else range(8080, 8100)
handler = functools.partial(Handler, directory='www')
for port in ports:
    try:
        server = Server(('127.0.0.1', port), handler)
        break
    except OSError as error:
        if error.errno != errno.EADDRINUSE or port == ports[-1]:
            sys.exit(f'demo: cannot listen on 127.0.0.1:{port}: {error.strerror}')
print(f'\nsubsurf demo: http://127.0.0.1:{port}/   (Ctrl-C to stop)', flush=True)
try:
    server.serve_forever()
except KeyboardInterrupt:
    print()
PY
