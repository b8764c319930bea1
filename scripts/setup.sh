#!/usr/bin/env bash
# Installs what building and testing subsurf needs on a fresh Debian machine of this kind.
# Every step checks first and skips itself when already done, so a second run costs seconds.
set -euo pipefail
cd "$(dirname "$0")/.."

WASM_BINDGEN_VERSION=0.2.130   # must equal the wasm-bindgen pin in Cargo.toml

step() { printf '\n== setup: %s\n' "$*"; }

# A first run (toolchain, npm packages, the native and wasm builds, the test projects) fills
# about 4 GB in this folder; when the disk is nearly full, every later step fails with ENOSPC
# somewhere inside npm or cargo, so say it here, plainly.
FREE_KB=$(df -Pk . | awk 'NR == 2 {print $4}')
if [ -n "$FREE_KB" ] && [ "$FREE_KB" -lt $((5 * 1024 * 1024)) ]; then
  echo "setup: only $((FREE_KB / 1024)) MB free on the disk of $(pwd); building and testing subsurf needs about 5 GB. Free some space (old clones, target/ folders) and run again" >&2
  exit 1
fi

if ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
  step "rustup target add wasm32-unknown-unknown"
  rustup target add wasm32-unknown-unknown
fi

for component in rustfmt clippy; do
  if ! rustup component list --installed | grep -q "^$component"; then
    step "rustup component add $component"
    rustup component add "$component"
  fi
done

if ! command -v wasm-bindgen >/dev/null 2>&1 \
   || [ "$(wasm-bindgen --version | awk '{print $2}')" != "$WASM_BINDGEN_VERSION" ]; then
  step "cargo install wasm-bindgen-cli $WASM_BINDGEN_VERSION (about 5 minutes, once)"
  # No --locked: the CLI's lock file names an index entry this registry mirror lacks.
  cargo install wasm-bindgen-cli --version "$WASM_BINDGEN_VERSION"
fi

# Debian packages for the commands we need: chromium + chromedriver (wasm browser tests, demo
# end-to-end test), node + npm (package smoke test, Playwright, the consumer projects: Vite 8 needs
# Node 20.19 or newer, though the published package itself runs on Node 18),
# python3 (scripts/demo.sh serves www/ with http.server).
APT_PACKAGES=()
command -v chromium >/dev/null 2>&1 || APT_PACKAGES+=(chromium)
command -v chromedriver >/dev/null 2>&1 || APT_PACKAGES+=(chromium-driver)
command -v node >/dev/null 2>&1 || APT_PACKAGES+=(nodejs)
command -v npm >/dev/null 2>&1 || APT_PACKAGES+=(npm)
command -v python3 >/dev/null 2>&1 || APT_PACKAGES+=(python3)
if [ "${#APT_PACKAGES[@]}" -gt 0 ]; then
  step "apt-get install ${APT_PACKAGES[*]}"
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  # This image deletes downloaded .debs between dpkg calls, so the install fails now and then;
  # a retry picks up where the last one stopped.
  $SUDO apt-get update -qq || true
  for try in 1 2 3 4 5 6; do
    if DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${APT_PACKAGES[@]}"; then break; fi
    [ "$try" -lt 6 ] || { echo "setup: apt-get install ${APT_PACKAGES[*]} failed 6 times" >&2; exit 1; }
    sleep 2
  done
fi

# The tests' tools (Vite 8 in the consumer projects) need Node 20.19; the package needs only 18.
if ! node -e 'const [a, b] = process.versions.node.split(".").map(Number); process.exit(a > 20 || (a === 20 && b >= 19) ? 0 : 1)'; then
  echo "setup: Node $(node --version) is too old for the tests and the demo build (Vite 8 needs Node 20.19 or newer); install a newer Node (https://nodejs.org) and run again" >&2
  exit 1
fi

if [ ! -d node_modules ] || [ package-lock.json -nt node_modules/.package-lock.json ]; then
  step "npm ci"
  npm ci --no-audit --no-fund
fi
echo "setup: ok"
