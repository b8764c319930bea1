#!/bin/bash
# OpenSubdiv against the wasm package, round after round in one process tree, so that both see
# the same moment of a noisy machine (on the shared VMs the same command can take 1.6 times as
# long an hour later). Each round runs osd_refine (see far_perf.sh) on the two benchmark tori
# and then `node bench/node_bench.mjs catmull-clark` on the same tori.
#
# Usage: tools/osd/versus.sh [ROUNDS]    (default 3; needs pkg/ from scripts/build-pkg.sh)
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
rounds=${1:-3}
[ -f "$root/pkg/node.js" ] || { echo "versus.sh: pkg/ missing; run scripts/build-pkg.sh" >&2; exit 1; }
refine=$("$here/build.sh" "$root/target/osd/osd_refine")

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 "$here/make_meshes.py" torus --major 1000 --minor 1000 "$tmp/quads.obj"
python3 "$here/make_meshes.py" torus --major 250 --minor 200 --triangles "$tmp/tris.obj"

echo "OpenSubdiv $(dpkg-query -W -f='${Version}' libosd-dev 2>/dev/null || echo '?'), node $(node --version), $(nproc) cores, $(date -u +%Y-%m-%dT%H:%M:%SZ)"
for round in $(seq "$rounds"); do
    echo
    echo "== round $round"
    for mesh in "quads 1" "tris 3"; do
        set -- $mesh
        echo "osd_refine $1 level $2 (seconds, best (median) of 5):"
        "$refine" --levels "$2" --time 5 --no-output "$tmp/$1.obj" 2>&1 | grep -E "create|refine \+ interpolate"
    done
    node "$root/bench/node_bench.mjs" catmull-clark | grep -E "scheme|1M quads|tris \| 3"
done
