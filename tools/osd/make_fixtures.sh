#!/bin/bash
# Regenerates the OpenSubdiv reference fixtures (see DEVELOPERS.md, "Reference fixtures"):
#
#   tests/meshes/osd/*.obj         copies of the 2-manifold OpenSubdiv regression shapes used
#   tests/meshes/own_*.obj         our procedural meshes (tools/osd/make_meshes.py tests)
#   tests/fixtures/osd/            untagged: tags ignored, boundary edge-and-corner and edge-only,
#                                  levels 1-3; catmark_*, bilinear_*, own_* with Catmull-Clark,
#                                  loop_* with Loop
#   tests/fixtures/osd_tagged/     tagged: creases, corners, holes, creasemethod, smoothtriangles and
#                                  interpolateboundary from the file (edge-only when the file has no
#                                  interpolateboundary tag, as OpenSubdiv's regression suite),
#                                  levels 1-3; catmark_* with Catmull-Clark, loop_* with Loop
#   tests/meshes/osd_nonmanifold/  copies of the non-manifold shapes (SOURCES.md says NON-manifold,
#                                  or the name has 'nonman'; no hedit)
#   tests/fixtures/osd_nonmanifold/  those shapes, tagged as above, levels 1-3
#
# Each directory gets a MANIFEST.tsv (fixture, scheme, boundary, level, input, ...) that the Rust
# tests read, so adding fixtures needs no code change. A shape whose level-3 output would be over
# max_bytes (2,000,000 bytes of OBJ) gets levels 1-2 only in that directory. When the edge-only
# result is byte-identical to the edge-and-corner one (closed meshes, meshes without corners of
# one face), no second file is written: the edge-only manifest row names the edge-and-corner
# file. Re-running gives byte-identical files.
#
# Usage: tools/osd/make_fixtures.sh            (needs g++, libosd-dev, python3)
# Environment: OSD_SHAPES   the regression shapes (default: ../shared/meshes/osd next to the repo)
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
shapes=${OSD_SHAPES:-"$root/../shared/meshes/osd"}
sources="$shapes/../SOURCES.md"
max_bytes=2000000
levels="1 2 3"

[ -d "$shapes" ] || { echo "make_fixtures.sh: no shapes at $shapes (set OSD_SHAPES)" >&2; exit 1; }
[ -f "$sources" ] || { echo "make_fixtures.sh: $sources not found" >&2; exit 1; }

refine=$("$here/build.sh" "$root/target/osd/osd_refine")
osd_version=$(dpkg-query -W -f='${Version}' libosd-dev 2>/dev/null || echo unknown)
export LC_ALL=C

cd "$root"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The 2-manifold shapes, from the SOURCES.md table (column 6 says manifold), without hedit ones.
manifold_shapes() {
    awk -F'|' '$2 ~ /\.obj/ { name = $2; m = $7; gsub(/ /, "", name); gsub(/ /, "", m);
                               if (m == "manifold") print name }' "$sources" |
        grep -v hedit | sed 's/\.obj$//' | sort
}

# The non-manifold shapes: NON-manifold in SOURCES.md, or 'nonman' in the name; without hedit ones.
nonmanifold_shapes() {
    awk -F'|' '$2 ~ /\.obj/ { name = $2; m = $7; gsub(/ /, "", name);
                               if (m ~ /NON/ || name ~ /nonman/) print name }' "$sources" |
        grep -v hedit | sed 's/\.obj$//' | sort
}

# Inputs.
rm -rf tests/meshes/osd tests/meshes/osd_nonmanifold
mkdir -p tests/meshes/osd tests/meshes/osd_nonmanifold
for s in $(manifold_shapes); do
    case $s in catmark_*|bilinear_*|loop_*) cp "$shapes/$s.obj" tests/meshes/osd/ ;; esac
done
for s in $(nonmanifold_shapes); do
    case $s in catmark_*|loop_*) cp "$shapes/$s.obj" tests/meshes/osd_nonmanifold/ ;; esac
done
chmod 644 tests/meshes/osd/*.obj tests/meshes/osd_nonmanifold/*.obj
rm -f tests/meshes/own_*.obj
python3 "$here/make_meshes.py" tests tests/meshes >/dev/null

# The boundary mode that OpenSubdiv uses for a shape's own tags.
tagged_boundary() {
    local value
    value=$(awk '$1 == "t" && $2 == "interpolateboundary" { v = $4 } END { print v }' "$1")
    case $value in
        0) echo none ;;
        1) echo edge-and-corner ;;
        2 | "") echo edge-only ;;
        *) echo "make_fixtures.sh: $1: interpolateboundary $value" >&2; exit 1 ;;
    esac
}

# make_set DIR KIND: writes DIR/*.obj and DIR/MANIFEST.tsv; KIND is untagged, tagged or
# nonmanifold (tagged, on the non-manifold shapes).
make_set() {
    local dir=$1 kind=$2
    rm -rf "$dir"
    mkdir -p "$dir"
    local manifest="$dir/MANIFEST.tsv"
    {
        echo "# Reference fixtures from OpenSubdiv $osd_version (libosd-dev), made by tools/osd/make_fixtures.sh."
        if [ "$kind" = untagged ]; then
            echo "# osd_refine --scheme SCHEME --levels LEVEL --boundary BOUNDARY --ignore-tags INPUT -o FIXTURE"
        else
            echo "# osd_refine --scheme SCHEME --levels LEVEL INPUT -o FIXTURE (tags used; BOUNDARY is what the"
            echo "# file's interpolateboundary says, boundary_from=default means no tag, so edge-only)"
        fi
        printf '# fixture\tscheme\tboundary\tlevel\tinput'
        [ "$kind" != untagged ] && printf '\tboundary_from'
        printf '\n'
    } >"$manifest"

    local inputs
    if [ "$kind" = untagged ]; then
        inputs=$(ls tests/meshes/osd/catmark_*.obj tests/meshes/osd/bilinear_*.obj \
                    tests/meshes/osd/loop_*.obj tests/meshes/own_*.obj | sort)
    elif [ "$kind" = tagged ]; then
        inputs=$(ls tests/meshes/osd/catmark_*.obj tests/meshes/osd/loop_*.obj | sort)
    else
        inputs=$(ls tests/meshes/osd_nonmanifold/*.obj | sort)
    fi

    local input name scheme modes mode from level out flags keep3 size
    for input in $inputs; do
        name=$(basename "$input" .obj)
        case $name in loop_*) scheme=loop ;; *) scheme=catmark ;; esac
        if [ "$kind" = untagged ]; then
            modes="edge-and-corner edge-only"
        else
            modes=$(tagged_boundary "$input")
            if grep -q '^t interpolateboundary' "$input"; then from=tag; else from=default; fi
        fi
        keep3=yes
        for mode in $modes; do
            for level in $levels; do
                [ "$level" = 3 ] && [ $keep3 = no ] && continue
                out="$name.$mode.L$level.obj"
                if [ "$kind" = untagged ]; then
                    flags=(--boundary "$mode" --ignore-tags)
                else
                    flags=()
                fi
                "$refine" --quiet --scheme "$scheme" --levels "$level" "${flags[@]}" "$input" -o "$tmp/out.obj"
                size=$(stat -c %s "$tmp/out.obj")
                if [ "$level" = 3 ] && [ "$size" -gt $max_bytes ]; then
                    keep3=no
                    echo "  $dir: $name: level 3 is $size bytes, over $max_bytes: levels 1-2 only" >&2
                    continue
                fi
                if [ "$kind" = untagged ] && [ "$mode" = edge-only ] &&
                    cmp -s "$tmp/out.obj" "$dir/$name.edge-and-corner.L$level.obj"; then
                    out="$name.edge-and-corner.L$level.obj"
                else
                    mv "$tmp/out.obj" "$dir/$out"
                fi
                if [ "$kind" = untagged ]; then
                    printf '%s\t%s\t%s\t%s\t%s\n' "$out" "$scheme" "$mode" "$level" "$input" >>"$manifest"
                else
                    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$out" "$scheme" "$mode" "$level" "$input" "$from" >>"$manifest"
                fi
            done
        done
    done
    echo "$dir: $(grep -vc '^#' "$manifest") fixtures, $(du -sh "$dir" | cut -f1)" >&2
}

make_set tests/fixtures/osd untagged
make_set tests/fixtures/osd_tagged tagged
make_set tests/fixtures/osd_nonmanifold nonmanifold
