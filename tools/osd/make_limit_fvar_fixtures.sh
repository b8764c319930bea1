#!/bin/bash
# Writes tests/fixtures/osd_limit_fvar/: OpenSubdiv's face-varying (UV) values at the limit, with
# Debian's OpenSubdiv (see DEVELOPERS.md, "Reference fixtures (OpenSubdiv)"). Each fixture is
#
#   osd_refine --limit --no-normals --fvar-linear MODE --scheme SCHEME --levels LEVEL
#              [--ignore-tags --boundary edge-and-corner] INPUT -o FIXTURE
#
# i.e. RefineUniform (full topology in the last level) + Interpolate and InterpolateFaceVarying
# level by level in double precision, then on the last level PrimvarRefinerReal<double>::Limit
# (positions, tangents) and LimitFaceVarying (channel 0, the input's vt). The file has `v` (the
# limit positions, %.9g), `vt` (the limit UVs in OpenSubdiv's value order, %.10g) and `f v/vt`
# (OpenSubdiv's face order, holes left out); no `vn` (tests/fixtures/osd_limit/ has the normals).
# Cases:
#
#   inputs   every catmark_* (Catmull-Clark) and loop_* (Loop) shape of tests/meshes/osd/ whose
#            faces all have vt indices (copied there by tools/osd/make_fixtures.sh);
#   modes    the six face-varying linear-interpolation modes: none corners-only corners-plus1
#            corners-plus2 boundaries all;
#   levels   1-3. A level is left out for a shape and kind, with all six modes and the deeper
#            levels, once one of its six files would pass 90,000 bytes (levels 1-2) or 25,000
#            bytes (level 3): catmark_bishop, car, lefthanded, pawn, righthanded and rook have
#            no fixture; most shapes have levels 1-2, the small ones level 3 too;
#   tags     untagged: --ignore-tags --boundary edge-and-corner; tagged: the file's creases,
#            corners, holes, creasemethod, smoothtriangles and interpolateboundary (edge-only
#            without one), only for shapes that have such tags (the same rule as
#            make_fvar_fixtures.sh).
#
# A file byte-identical to one already written for the same shape and level (modes a shape does
# not tell apart; tagged = untagged) is not written twice: the rows name the first. Cases where
# osd_refine fails (an OpenSubdiv crash) are left out, with the deeper levels, and reported on
# stderr. MANIFEST.tsv columns, as tests/fixtures/osd_fvar/: fixture, scheme, boundary, level,
# input, mode, tagged (yes/no). Needs g++ and libosd-dev only. Deterministic: a second run writes
# byte-identical files.
set -euo pipefail
. "$(dirname "$0")/fixture_common.sh"

# Per-file caps, which keep the directory near 14 MB (levels 1-2; level 3).
max_bytes_l12=90000
max_bytes_l3=25000
modes="none corners-only corners-plus1 corners-plus2 boundaries all"

dir=tests/fixtures/osd_limit_fvar
manifest=$dir/MANIFEST.tsv
start_manifest "$dir" \
    "# Face-varying limit fixtures from OpenSubdiv $osd_version (libosd-dev), made by tools/osd/make_limit_fvar_fixtures.sh:" \
    "# osd_refine --limit --no-normals --fvar-linear MODE --scheme SCHEME --levels LEVEL [--ignore-tags --boundary edge-and-corner] INPUT -o FIXTURE" \
    "$(printf '# fixture\tscheme\tboundary\tlevel\tinput\tmode\ttagged')"

skipped=0
for input in $(ls tests/meshes/osd/catmark_*.obj tests/meshes/osd/loop_*.obj | sort); do
    all_corners_have_uvs "$input" || continue
    name=$(basename "$input" .obj)
    case $name in
        loop_*) scheme=loop ;;
        *) scheme=catmark ;;
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
            cap=$max_bytes_l12
            [ "$level" = 3 ] && cap=$max_bytes_l3
            # All six modes first, so that a level is written with every mode or not at all.
            for mode in $modes; do
                # shellcheck disable=SC2086
                if ! "$refine" --quiet --limit --no-normals --fvar-linear $mode --scheme $scheme --levels $level \
                        $flags "$input" -o "$tmp/$mode.obj" 2>"$tmp/err"; then
                    echo "  $name ($kind, $mode): osd_refine failed at level $level ($(tail -c 200 "$tmp/err" | tr '\n' ' ')): level $level and deeper left out" >&2
                    skipped=$((skipped + 1))
                    break 2
                fi
                size=$(wc -c <"$tmp/$mode.obj")
                if [ "$size" -gt "$cap" ]; then
                    [ "$level" != 3 ] && echo "  $name ($kind): level $level is $size bytes: levels below it only" >&2
                    break 2
                fi
            done
            for mode in $modes; do
                fixture=$(same_fixture "$dir" "$name" "$level" "$tmp/$mode.obj")
                if [ -z "$fixture" ]; then
                    fixture=$name.$kind.$mode.L$level.obj
                    cp "$tmp/$mode.obj" "$dir/$fixture"
                fi
                printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$fixture" "$scheme" "$boundary" "$level" \
                    "$input" "$mode" "$tagged" >>"$manifest"
            done
        done
    done
done
echo "make_limit_fvar_fixtures.sh: $(grep -vc '^#' "$manifest") rows in $(ls "$dir" | grep -c '\.obj$') files, $(du -sh "$dir" | cut -f1); $skipped cases failed in osd_refine" >&2
