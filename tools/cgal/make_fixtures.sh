#!/bin/bash
# Regenerates the CGAL reference fixtures (see DEVELOPERS.md, "Reference fixtures (CGAL)"):
#
#   tests/meshes/cgal/*.obj     the inputs: copies of small OpenSubdiv regression shapes (from
#                               ../shared/meshes/osd, first line names the source) and our
#                               procedural meshes (tools/cgal/make_meshes.py)
#   tests/fixtures/cgal/        SCHEME.MESH.LN.obj: CGAL's Subdivision_method_3 result of N levels
#                               in one call (tools/cgal/cgal_subdivide): levels 1 and 2 always,
#                               3 (and for sqrt3 also 4, its second border-refining step) when the
#                               result has at most $max_deep_faces faces
#
# Triangle meshes get all four CGAL schemes (sqrt3, loop, catmull-clark, doo-sabin); other meshes
# catmull-clark and doo-sabin. The test discovers the fixtures from the file names. Re-running
# gives byte-identical files.
#
# Usage: tools/cgal/make_fixtures.sh        (needs g++, libcgal-dev, python3)
# Environment: OSD_SHAPES   the OpenSubdiv regression shapes (default: ../shared/meshes/osd)
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
shapes=${OSD_SHAPES:-"$root/../shared/meshes/osd"}
max_deep_faces=3000
export LC_ALL=C

subdivide=$("$here/build.sh" "$root/target/cgal/cgal_subdivide")
cd "$root"
meshes=tests/meshes/cgal
fixtures=tests/fixtures/cgal

# Inputs: OpenSubdiv shapes (2-manifold, no unreferenced vertices) and our own meshes.
osd_triangles="loop_tetrahedron loop_icosahedron loop_cube loop_saddle_edgeonly loop_pole8
               loop_triangle_edgeonly loop_xord_boundary"
osd_polygons="catmark_cube catmark_torus catmark_tent bilinear_nonquads1"
rm -rf "$meshes" "$fixtures"
mkdir -p "$meshes" "$fixtures"
for s in $osd_triangles $osd_polygons; do
    [ -f "$shapes/$s.obj" ] || { echo "make_fixtures.sh: no $shapes/$s.obj (set OSD_SHAPES)" >&2; exit 1; }
    cp "$shapes/$s.obj" "$meshes/"
done
chmod 644 "$meshes"/*.obj
python3 "$here/make_meshes.py" "$meshes" >/dev/null

is_triangle_mesh() {
    awk '$1 == "f" && NF != 4 { bad = 1 } END { exit bad }' "$1"
}

count=0
for input in "$meshes"/*.obj; do
    mesh=$(basename "$input" .obj)
    if is_triangle_mesh "$input"; then
        schemes="sqrt3 loop catmull-clark doo-sabin"
    else
        schemes="catmull-clark doo-sabin"
    fi
    for scheme in $schemes; do
        levels="1 2 3"
        [ "$scheme" = sqrt3 ] && levels="1 2 3 4"
        for level in $levels; do
            out="$fixtures/$scheme.$mesh.L$level.obj"
            "$subdivide" --scheme "$scheme" --levels "$level" "$input" -o "$out"
            if [ "$level" -ge 3 ] && [ "$(grep -c '^f ' "$out")" -gt "$max_deep_faces" ]; then
                rm "$out"
                break
            fi
            count=$((count + 1))
        done
    done
done
echo "make_fixtures.sh: $count fixtures in $fixtures ($(du -sh "$fixtures" | cut -f1)), CGAL $(dpkg-query -W -f='${Version}' libcgal-dev 2>/dev/null || echo unknown)"
