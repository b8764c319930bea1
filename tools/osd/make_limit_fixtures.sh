#!/bin/bash
# Writes tests/fixtures/osd_limit/: OpenSubdiv's limit positions and normals (osd_refine --limit,
# i.e. RefineUniform + Interpolate to the last level, then PrimvarRefinerReal<double>::Limit with
# both tangents; `v` limit positions, `vn` the unit tan1 x tan2 or 0 0 0 where degenerate, `f`
# the last level's faces without holes) for every catmark_* and loop_* shape of tests/meshes/osd/
# and tests/meshes/osd_nonmanifold/ (catmark_* with Catmull-Clark, loop_* with Loop):
#
#   untagged   --ignore-tags, boundary edge-and-corner and edge-only
#   tagged     the file's tags and interpolateboundary (edge-only without one), only for shapes
#              that have tags other than interpolateboundary (otherwise it is an untagged case)
#
# levels 1-3; a level is left out once its file would pass 700,000 bytes (levels 1-2) or
# 120,000 bytes (level 3), and deeper levels with it. A file byte-identical to one already written (edge-only = edge-and-corner
# on closed meshes) is not written twice: the row names the first. Needs only libosd-dev and the
# shapes already copied into tests/meshes/ (tools/osd/make_fixtures.sh). Deterministic.
#
# Cases where osd_refine --limit fails (OpenSubdiv 3.5's Limit crashes on some non-manifold
# shapes) are left out and reported.
#
# MANIFEST.tsv columns: fixture, scheme, boundary, level, input, tagged (yes/no).
set -euo pipefail
. "$(dirname "$0")/fixture_common.sh"

max_bytes=700000      # levels 1-2
max_bytes_3=120000     # level 3
dir=tests/fixtures/osd_limit
manifest="$dir/MANIFEST.tsv"
start_manifest "$dir" \
    "# OpenSubdiv limit fixtures from OpenSubdiv $osd_version (libosd-dev), made by tools/osd/make_limit_fixtures.sh:" \
    "# osd_refine --limit --scheme SCHEME --levels LEVEL [--boundary BOUNDARY --ignore-tags] INPUT -o FIXTURE" \
    "$(printf '# fixture\tscheme\tboundary\tlevel\tinput\ttagged')"

# own_cone_uv (tools/osd/make_meshes.py): two vertices of valence 80, with Catmull-Clark.
for input in $(ls tests/meshes/osd/catmark_*.obj tests/meshes/osd/loop_*.obj \
                  tests/meshes/osd_nonmanifold/catmark_*.obj tests/meshes/osd_nonmanifold/loop_*.obj \
                  tests/meshes/own_cone_uv.obj | sort); do
    name=$(basename "$input" .obj)
    case $name in loop_*) scheme=loop ;; *) scheme=catmark ;; esac
    cases="edge-and-corner:no edge-only:no"
    has_tags "$input" && cases="$cases $(tagged_boundary "$input"):yes"
    for case in $cases; do
        mode=${case%:*}
        tagged=${case#*:}
        if [ "$tagged" = yes ]; then
            flags=()
            stem="$name.tagged-$mode"
        else
            flags=(--boundary "$mode" --ignore-tags)
            stem="$name.$mode"
        fi
        for level in 1 2 3; do
            if ! "$refine" --quiet --limit --scheme "$scheme" --levels "$level" "${flags[@]}" "$input" \
                    -o "$tmp/out.obj" 2>/dev/null; then
                # OpenSubdiv 3.5's Limit crashes on some non-manifold shapes (catmark_nonman_edge100).
                echo "  $name ($mode, tagged $tagged): osd_refine --limit failed at level $level: left out" >&2
                break
            fi
            size=$(stat -c %s "$tmp/out.obj")
            limit=$max_bytes
            [ "$level" = 3 ] && limit=$max_bytes_3
            if [ "$size" -gt $limit ]; then
                echo "  $name ($mode, tagged $tagged): level $level is $size bytes: levels below it only" >&2
                break
            fi
            out="$stem.L$level.obj"
            same=$(same_fixture "$dir" "$name" "$level" "$tmp/out.obj")
            if [ -n "$same" ]; then
                out=$same
            else
                mv "$tmp/out.obj" "$dir/$out"
            fi
            printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$out" "$scheme" "$mode" "$level" "$input" "$tagged" >>"$manifest"
        done
    done
done
echo "$dir: $(grep -vc '^#' "$manifest") rows, $(ls "$dir"/*.obj | wc -l) files, $(du -sh "$dir" | cut -f1)" >&2
