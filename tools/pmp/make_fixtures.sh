#!/bin/bash
# Regenerates the pmp-library reference fixtures (see DEVELOPERS.md, "Reference fixtures
# (pmp-library)"):
#
#   tests/fixtures/pmp/meshes/*.obj   the inputs: our mixed meshes (tools/pmp/make_meshes.py) and
#                                     copies of mixed OpenSubdiv regression shapes (first line
#                                     names the source)
#   tests/fixtures/pmp/MESH.LN.obj    pmp's quad_tri_subdivision applied N = 1, 2 times to one
#                                     SurfaceMesh (BoundaryHandling::Interpolate), written by
#                                     tools/pmp/pmp_quadtri.cpp in pmp's vertex and face order
#
# pmp-library is MIT, but none of its code is in this repository: the script compiles it from a
# copy outside the repository, $PMP_SRC (default /tmp/pmp-src), laid out as pmp's own tree
# (src/pmp/...). The copy used for the committed fixtures was fetched file by file from
# pmp-library/pmp-library at ONE commit:
#
#   373fa5d6bf52e8504dda92aacc153741bd5f7042
#
#   src/pmp/surface_mesh.h, src/pmp/surface_mesh.cpp, src/pmp/properties.h, src/pmp/types.h,
#   src/pmp/mat_vec.h, src/pmp/exceptions.h, src/pmp/algorithms/subdivision.h,
#   src/pmp/algorithms/subdivision.cpp, src/pmp/algorithms/differential_geometry.h,
#   src/pmp/algorithms/differential_geometry.cpp
#
# with the code kept verbatim and only unused parts left out (doc comments; in surface_mesh.cpp
# split/flip/collapse/delete/garbage_collection; in subdivision.cpp the other three schemes; in
# differential_geometry.* everything but centroid(mesh, f); in mat_vec.h the Eigen conversions
# and the OpenGL/linear-algebra helpers, so Eigen is not needed). A full checkout of that commit
# works too if Eigen's headers are on the include path (EXTRA_CXXFLAGS=-I/usr/include/eigen3,
# Debian libeigen3-dev). Build (g++ 12.2, C++20 for pmp's <numbers> and operator<=>):
#
#   g++ -O2 -std=c++20 -I$PMP_SRC/src tools/pmp/pmp_quadtri.cpp $PMP_SRC/src/pmp/surface_mesh.cpp \
#       $PMP_SRC/src/pmp/algorithms/subdivision.cpp \
#       $PMP_SRC/src/pmp/algorithms/differential_geometry.cpp -o target/pmp/pmp_quadtri
#
# pmp's Scalar is float (PMP_SCALAR_TYPE_64 not defined), its default. Re-running gives
# byte-identical files.
#
# Usage: tools/pmp/make_fixtures.sh     (needs g++, python3)
# Environment: PMP_SRC      pmp-library source tree (default /tmp/pmp-src)
#              OSD_SHAPES   the OpenSubdiv regression shapes (default: ../shared/meshes/osd)
#              PMP_BIN      where to build pmp_quadtri (default: target/pmp/pmp_quadtri)
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
src=${PMP_SRC:-/tmp/pmp-src}
shapes=${OSD_SHAPES:-"$root/../shared/meshes/osd"}
bin=${PMP_BIN:-"$root/target/pmp/pmp_quadtri"}
export LC_ALL=C

for f in surface_mesh.cpp algorithms/subdivision.cpp algorithms/differential_geometry.cpp; do
    [ -f "$src/src/pmp/$f" ] || { echo "make_fixtures.sh: no $src/src/pmp/$f (set PMP_SRC)" >&2; exit 1; }
done
mkdir -p "$(dirname "$bin")"
${CXX:-g++} -O2 -std=c++20 -Wall -Wextra ${EXTRA_CXXFLAGS:-} -I"$src/src" -o "$bin" \
    "$here/pmp_quadtri.cpp" "$src/src/pmp/surface_mesh.cpp" \
    "$src/src/pmp/algorithms/subdivision.cpp" "$src/src/pmp/algorithms/differential_geometry.cpp"

cd "$root"
fixtures=tests/fixtures/pmp
meshes=$fixtures/meshes
rm -rf "$fixtures"
mkdir -p "$meshes"

# Mixed 2-manifold OpenSubdiv shapes: closed (pyramid), open with a pole (pole8), open with
# hexagons and pentagons (nonquads).
osd="catmark_pyramid catmark_pole8 bilinear_nonquads1 catmark_nonquads"
for s in $osd; do
    [ -f "$shapes/$s.obj" ] || { echo "make_fixtures.sh: no $shapes/$s.obj (set OSD_SHAPES)" >&2; exit 1; }
    cp "$shapes/$s.obj" "$meshes/"
done
chmod 644 "$meshes"/*.obj
python3 "$here/make_meshes.py" "$meshes"

count=0
for input in "$meshes"/*.obj; do
    mesh=$(basename "$input" .obj)
    for level in 1 2; do
        "$bin" --levels "$level" "$input" -o "$fixtures/$mesh.L$level.obj"
        count=$((count + 1))
    done
done
echo "make_fixtures.sh: $count fixtures in $fixtures ($(du -sh "$fixtures" | cut -f1)), pmp-library 373fa5d (from $src)"
