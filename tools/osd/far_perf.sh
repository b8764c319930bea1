#!/bin/bash
# OpenSubdiv reference timings on two procedural tori (see DEVELOPERS.md, "Reference fixtures"):
#
#   (a) quad torus, 1000 x 1000 = 1,000,000 quads, Catmull-Clark level 1
#   (b) triangle torus, 250 x 200 x 2 = 100,000 triangles, Catmull-Clark levels 1, 2, 3
#
# For each it prints the raw output of /usr/bin/far_perf (uniform refinement, -u; float precision)
# and the "refine + interpolate" time of tools/osd/osd_refine (RefineUniform plus
# PrimvarRefiner::Interpolate of xyz positions in double precision, level by level; best and
# median of several runs). far_perf itself never interpolates data: its TopologyRefiner::Refine
# line is topology only, and StencilTableFactory::Create builds the weights that an evaluator
# would apply later.
#
# The meshes are written by tools/osd/make_meshes.py into a temporary directory (not kept); our
# own benchmarks can rebuild identical meshes with the same commands:
#   make_meshes.py torus --major 1000 --minor 1000 torus_quads_1000x1000.obj
#   make_meshes.py torus --major 250 --minor 200 --triangles torus_tris_250x200.obj
# (R = 1.0, r = 0.25; vertex (i, j) has index i*V + j; see make_meshes.py for the face order.)
#
# Usage: tools/osd/far_perf.sh [REPEATS]    (default 5 runs of osd_refine per case)
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
repeats=${1:-5}
far_perf=${FAR_PERF:-/usr/bin/far_perf}
[ -x "$far_perf" ] || { echo "far_perf.sh: $far_perf not found; apt-get install opensubdiv-tools" >&2; exit 1; }
refine=$("$here/build.sh" "$root/target/osd/osd_refine")

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
quads="$tmp/torus_quads_1000x1000.obj"
tris="$tmp/torus_tris_250x200.obj"
python3 "$here/make_meshes.py" torus --major 1000 --minor 1000 "$quads"
python3 "$here/make_meshes.py" torus --major 250 --minor 200 --triangles "$tris"

echo "OpenSubdiv $(dpkg-query -W -f='${Version}' libosd-dev 2>/dev/null || echo '?'), $(nproc) cores, $(date -u +%Y-%m-%dT%H:%M:%SZ)"
echo
echo "== (a) torus 1000 x 1000: 1,000,000 quads, Catmull-Clark, level 1"
echo "\$ far_perf -u -l 1 -catmark torus_quads_1000x1000.obj"
"$far_perf" -u -l 1 -catmark "$quads" | sed "s|$tmp/||"
echo "\$ osd_refine --levels 1 --time $repeats --no-output torus_quads_1000x1000.obj"
"$refine" --levels 1 --time "$repeats" --no-output "$quads" 2>&1 | sed "s|$tmp/||"
echo
echo "== (b) torus 250 x 200 x 2: 100,000 triangles, Catmull-Clark, levels 1-3"
echo "\$ far_perf -u -l 3 -catmark torus_tris_250x200.obj"
"$far_perf" -u -l 3 -catmark "$tris" | sed "s|$tmp/||"
for level in 1 2 3; do
    echo "\$ osd_refine --levels $level --time $repeats --no-output torus_tris_250x200.obj"
    "$refine" --levels "$level" --time "$repeats" --no-output "$tris" 2>&1 | sed "s|$tmp/||"
done
