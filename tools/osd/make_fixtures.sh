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
#                                  or the name has 'nonman'; no hedit), and our own meshes with
#                                  faces that repeat a vertex (make_meshes.py repeated: own_*)
#   tests/fixtures/osd_nonmanifold/  those shapes, tagged as above, levels 1-3
#   tests/fixtures/osd_nonmanifold_untagged/  those shapes untagged as tests/fixtures/osd/, and
#                                  with the linear schemes: every shape with OpenSubdiv's
#                                  bilinear scheme (scheme column 'bilinear'), the loop_* shapes
#                                  with Loop's topology and positions interpolated as varying
#                                  data, i.e. midpoint subdivision (osd_refine --varying; scheme
#                                  column 'midpoint'), both edge-and-corner, levels 1-3; a
#                                  result byte-identical to the tagged one (a shape whose only
#                                  tag is its boundary mode) names ../osd_nonmanifold/'s file
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
#              OSD_SETS     the fixture sets to write (default: all four: untagged tagged
#                           nonmanifold nonmanifold-untagged); the inputs are copied every time
set -euo pipefail

# A relative OSD_SHAPES is the caller's: made absolute before fixture_common.sh changes folder.
[ -z "${OSD_SHAPES:-}" ] || OSD_SHAPES=$(realpath -m "$OSD_SHAPES")
. "$(dirname "$0")/fixture_common.sh"
shapes=${OSD_SHAPES:-"$root/../shared/meshes/osd"}
sources="$shapes/../SOURCES.md"
max_bytes=2000000
levels="1 2 3"

[ -d "$shapes" ] || { echo "make_fixtures.sh: no shapes at $shapes (set OSD_SHAPES)" >&2; exit 1; }
[ -f "$sources" ] || { echo "make_fixtures.sh: $sources not found" >&2; exit 1; }

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
python3 "$here/make_meshes.py" repeated tests/meshes/osd_nonmanifold >/dev/null

# The levels written for a shape. own_repeat_sphere lists vertex 0 twice in one face, far apart,
# and OpenSubdiv 3.5 refines it wrongly from level 2 on: Vtr::Level::populateLocalIndices gives
# the face's second corner at vertex 0 the first corner's local index once the vertex's faces
# have been put in order around it (it only looks past the first corner when the face comes
# twice in a row), so the child faces around vertex 0 at level 2 are the wrong ones (refining
# OpenSubdiv's own level 1 once more gives another level 2: ours). Level 1 only.
levels_of() {
    case $1 in
        own_repeat_sphere) echo 1 ;;
        *) echo "$levels" ;;
    esac
}

# make_set DIR KIND: writes DIR/*.obj and DIR/MANIFEST.tsv; KIND is untagged, tagged,
# nonmanifold (tagged, on the non-manifold shapes) or nonmanifold-untagged (untagged, on the
# non-manifold shapes, with the linear schemes too).
make_set() {
    local dir=$1 kind=$2
    rm -rf "$dir"
    mkdir -p "$dir"
    local manifest="$dir/MANIFEST.tsv"
    {
        echo "# Reference fixtures from OpenSubdiv $osd_version (libosd-dev), made by tools/osd/make_fixtures.sh."
        if [ "$kind" = untagged ]; then
            echo "# osd_refine --scheme SCHEME --levels LEVEL --boundary BOUNDARY --ignore-tags INPUT -o FIXTURE"
        elif [ "$kind" = nonmanifold-untagged ]; then
            echo "# osd_refine --scheme SCHEME --levels LEVEL --boundary BOUNDARY --ignore-tags INPUT -o FIXTURE;"
            echo "# scheme midpoint: osd_refine --scheme loop --varying ... (Loop's topology, linear positions)"
        else
            echo "# osd_refine --scheme SCHEME --levels LEVEL INPUT -o FIXTURE (tags used; BOUNDARY is what the"
            echo "# file's interpolateboundary says, boundary_from=default means no tag, so edge-only)"
        fi
        printf '# fixture\tscheme\tboundary\tlevel\tinput'
        [ "$kind" = tagged ] || [ "$kind" = nonmanifold ] && printf '\tboundary_from'
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
    local untagged=no
    [ "$kind" = untagged ] || [ "$kind" = nonmanifold-untagged ] && untagged=yes

    local input name scheme schemes modes mode from level out flags keep3 size stem
    for input in $inputs; do
        name=$(basename "$input" .obj)
        case $name in loop_*) scheme=loop ;; *) scheme=catmark ;; esac
        schemes=$scheme
        if [ "$kind" = nonmanifold-untagged ]; then
            schemes="$scheme bilinear"
            [ "$scheme" = loop ] && schemes="$schemes midpoint"
        fi
        for scheme in $schemes; do
            if [ $untagged = yes ]; then
                case $scheme in
                    bilinear | midpoint) modes=edge-and-corner ;;
                    *) modes="edge-and-corner edge-only" ;;
                esac
            else
                modes=$(tagged_boundary "$input")
                if grep -q '^t interpolateboundary' "$input"; then from=tag; else from=default; fi
            fi
            keep3=yes
            for mode in $modes; do
                for level in $(levels_of "$name"); do
                    [ "$level" = 3 ] && [ $keep3 = no ] && continue
                    case $scheme in bilinear | midpoint) stem="$name.$scheme" ;; *) stem="$name.$mode" ;; esac
                    out="$stem.L$level.obj"
                    if [ $untagged = yes ]; then
                        flags=(--boundary "$mode" --ignore-tags)
                    else
                        flags=()
                    fi
                    case $scheme in
                        midpoint) flags+=(--scheme loop --varying) ;;
                        *) flags+=(--scheme "$scheme") ;;
                    esac
                    "$refine" --quiet --levels "$level" "${flags[@]}" "$input" -o "$tmp/out.obj"
                    size=$(stat -c %s "$tmp/out.obj")
                    if [ "$level" = 3 ] && [ "$size" -gt $max_bytes ]; then
                        keep3=no
                        echo "  $dir: $name: level 3 ($scheme) is $size bytes, over $max_bytes: levels 1-2 only" >&2
                        continue
                    fi
                    if [ $untagged = yes ] && [ "$mode" = edge-only ] &&
                        cmp -s "$tmp/out.obj" "$dir/$name.edge-and-corner.L$level.obj"; then
                        out="$name.edge-and-corner.L$level.obj"
                    elif [ "$kind" = nonmanifold-untagged ] &&
                        cmp -s "$tmp/out.obj" "tests/fixtures/osd_nonmanifold/$out"; then
                        # The shape's only tag is this boundary mode: the tagged file is the same.
                        out="../osd_nonmanifold/$out"
                    else
                        mv "$tmp/out.obj" "$dir/$out"
                    fi
                    if [ $untagged = yes ]; then
                        printf '%s\t%s\t%s\t%s\t%s\n' "$out" "$scheme" "$mode" "$level" "$input" >>"$manifest"
                    else
                        printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$out" "$scheme" "$mode" "$level" "$input" "$from" >>"$manifest"
                    fi
                done
            done
        done
    done
    echo "$dir: $(grep -vc '^#' "$manifest") fixtures, $(du -sh "$dir" | cut -f1)" >&2
}

for set in ${OSD_SETS:-untagged tagged nonmanifold nonmanifold-untagged}; do
    case $set in
        untagged) make_set tests/fixtures/osd untagged ;;
        tagged) make_set tests/fixtures/osd_tagged tagged ;;
        nonmanifold) make_set tests/fixtures/osd_nonmanifold nonmanifold ;;
        nonmanifold-untagged) make_set tests/fixtures/osd_nonmanifold_untagged nonmanifold-untagged ;;
        *) echo "make_fixtures.sh: unknown set '$set' in OSD_SETS" >&2; exit 1 ;;
    esac
done
