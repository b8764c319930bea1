#!/bin/bash
# OpenSubdiv's stencil evaluation as a reference for subsurf's: builds tools/osd/osd_stencil_bench
# (g++ -O2, libosdCPU from libosd-dev) into target/osd/, makes the meshes and prints one line per
# stencil table (see the header of osd_stencil_bench.cpp for the fields and what is timed).
#
#   tools/osd/stencil_bench.sh [REPEATS]       (default 30 timed runs after a warm-up)
#
# Cases:
#   horse (48,485 vertices, 96,966 triangles): Loop levels 2 and 3, Catmull-Clark levels 2 and 3,
#     refined and limit stencils, except the limit at Catmull-Clark level 3 (its adaptive
#     refinement and Gregory patches take ~4x the 3.7 GB of level 2: left out);
#   torus_400x250 (tools/osd/make_meshes.py torus --major 400 --minor 250: 100,000 quads):
#     Catmull-Clark level 2, refined and limit stencils.
#
# The horse is read from bench/meshes/horse.obj if it exists, otherwise from $HORSE (a .ply, .off
# or .obj file; the first two are converted with tools/osd/mesh_to_obj.py); without either its
# cases are skipped. bench/meshes/SOURCES.md says where the horse comes from.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
repeats=${1:-30}
bench=$root/target/osd/osd_stencil_bench
mkdir -p "$(dirname "$bench")"
if [ ! -f /usr/include/opensubdiv/far/stencilTableFactory.h ]; then
    echo "stencil_bench.sh: OpenSubdiv headers not found; run: apt-get install libosd-dev" >&2
    exit 1
fi
${CXX:-g++} -O2 -std=c++14 -Wall -Wextra -o "$bench" "$here/osd_stencil_bench.cpp" -losdCPU

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 "$here/make_meshes.py" torus --major 400 --minor 250 "$tmp/torus_400x250.obj"

horse=""
if [ -f "$root/bench/meshes/horse.obj" ]; then
    horse=$root/bench/meshes/horse.obj
elif [ -n "${HORSE:-}" ]; then
    case $HORSE in
        *.obj) horse=$HORSE ;;
        *) python3 "$here/mesh_to_obj.py" "$HORSE" "$tmp/horse.obj"; horse=$tmp/horse.obj ;;
    esac
else
    echo "stencil_bench.sh: no bench/meshes/horse.obj and no \$HORSE: the horse cases are skipped" >&2
fi

echo "# osd_stencil_bench, OpenSubdiv $(dpkg-query -W -f='${Version}' libosd-dev 2>/dev/null || echo unknown), $repeats runs, $(nproc) cores"
if [ -n "$horse" ]; then
    "$bench" --scheme loop --level 2 --repeats "$repeats" "$horse"
    "$bench" --scheme loop --level 3 --repeats "$repeats" "$horse"
    "$bench" --scheme catmark --level 2 --repeats "$repeats" "$horse"
    "$bench" --scheme catmark --level 3 --repeats "$repeats" --no-limit "$horse"
fi
"$bench" --scheme catmark --level 2 --repeats "$repeats" "$tmp/torus_400x250.obj"
