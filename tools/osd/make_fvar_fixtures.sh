#!/bin/bash
# Regenerates the face-varying (UV) reference fixtures, tests/fixtures/osd_fvar/, with Debian's
# OpenSubdiv (see DEVELOPERS.md, "Reference fixtures (OpenSubdiv)"):
#
#   inputs   every shape of tests/meshes/osd/ and tests/meshes/osd_nonmanifold/ whose faces all
#            have vt indices (tools/osd/make_fixtures.sh copies them from ../shared/meshes/osd):
#            catmark_* with Catmull-Clark, loop_* with Loop, bilinear_* with bilinear; and our
#            own meshes with vt (tests/meshes/own_*, tools/osd/make_meshes.py: own_cone_uv) with
#            Catmull-Clark;
#   modes    the six face-varying linear-interpolation modes (osd_refine --fvar-linear MODE);
#   levels   1-3 (levels 2 and 3 only while the file stays under a cap: the big shapes,
#            catmark_car, the chess pieces, the poles, stop at level 1 or 2);
#   tags     untagged: --ignore-tags --boundary edge-and-corner; tagged: the file's creases,
#            corners, holes, creasemethod, smoothtriangles and interpolateboundary (edge-only
#            without one, as OpenSubdiv's regression suite), only for shapes that have such tags.
#
# Each fixture has only what the position fixtures lack (osd_refine --no-positions): `vt` lines,
# the last level's values in OpenSubdiv's order, and `f v/vt` corners in OpenSubdiv's face order,
# holes left out. When modes give byte-identical output for a shape, kind and level, the file is
# written once and the manifest rows name it. MANIFEST.tsv columns: fixture, scheme, boundary,
# level, input, mode, tagged (yes/no). Re-running gives byte-identical files.
#
# Usage: tools/osd/make_fvar_fixtures.sh       (needs g++, libosd-dev)
set -euo pipefail
. "$(dirname "$0")/fixture_common.sh"

# Per-file caps: a level is left out for a shape once its file would be larger.
max_bytes_l2=500000
max_bytes_l3=200000
modes="none corners-only corners-plus1 corners-plus2 boundaries all"

dir=tests/fixtures/osd_fvar
manifest=$dir/MANIFEST.tsv
start_manifest "$dir" \
    "# Face-varying reference fixtures from OpenSubdiv $osd_version (libosd-dev), made by tools/osd/make_fvar_fixtures.sh:" \
    "# osd_refine --scheme SCHEME --levels LEVEL --fvar-linear MODE --no-positions [--ignore-tags --boundary edge-and-corner] INPUT" \
    "$(printf '# fixture\tscheme\tboundary\tlevel\tinput\tmode\ttagged')"

for input in $(ls tests/meshes/osd/*.obj tests/meshes/osd_nonmanifold/*.obj tests/meshes/own_*.obj | sort); do
    all_corners_have_uvs "$input" || continue
    name=$(basename "$input" .obj)
    case $name in
        catmark_* | own_*) scheme=catmark ;;
        loop_*) scheme=loop ;;
        bilinear_*) scheme=bilinear ;;
        *) continue ;;
    esac
    kinds=untagged
    has_tags "$input" interpolateboundary && kinds="untagged tagged"
    for kind in $kinds; do
        if [ $kind = untagged ]; then
            flags="--ignore-tags --boundary edge-and-corner"; boundary=edge-and-corner; tagged=no
        else
            flags=""; boundary=$(tagged_boundary "$input"); tagged=yes
        fi
        for level in 1 2 3; do
            written=""
            for mode in $modes; do
                out=$tmp/$mode.obj
                # shellcheck disable=SC2086
                "$refine" --quiet --scheme $scheme --levels $level --fvar-linear $mode --no-positions \
                    $flags "$input" -o "$out"
                size=$(wc -c <"$out")
                if { [ "$level" = 2 ] && [ "$size" -gt "$max_bytes_l2" ]; } ||
                   { [ "$level" = 3 ] && [ "$size" -gt "$max_bytes_l3" ]; }; then
                    continue 2
                fi
                fixture=""
                for w in $written; do
                    if cmp -s "$out" "$dir/$w"; then fixture=$w; break; fi
                done
                if [ -z "$fixture" ]; then
                    fixture=$name.$kind.$mode.L$level.obj
                    cp "$out" "$dir/$fixture"
                    written="$written $fixture"
                fi
                printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$fixture" "$scheme" "$boundary" "$level" \
                    "$input" "$mode" "$tagged" >>"$manifest"
            done
        done
    done
done
echo "make_fvar_fixtures.sh: $(grep -vc '^#' "$manifest") cases in $(ls "$dir" | grep -c '\.obj$') files, $(du -sh "$dir" | cut -f1)"
