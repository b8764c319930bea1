#!/bin/bash
# Regenerates the face-varying (UV) reference fixtures, tests/fixtures/osd_fvar/, with Debian's
# OpenSubdiv (see DEVELOPERS.md, "Reference fixtures (OpenSubdiv)"):
#
#   inputs   every shape of tests/meshes/osd/ and tests/meshes/osd_nonmanifold/ whose faces all
#            have vt indices (tools/osd/make_fixtures.sh copies them from ../shared/meshes/osd):
#            catmark_* with Catmull-Clark, loop_* with Loop, bilinear_* with bilinear;
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

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
# Per-file caps: a level is left out for a shape once its file would be larger.
max_bytes_l2=500000
max_bytes_l3=200000
modes="none corners-only corners-plus1 corners-plus2 boundaries all"

refine=$("$here/build.sh" "$root/target/osd/osd_refine")
osd_version=$(dpkg-query -W -f='${Version}' libosd-dev 2>/dev/null || echo unknown)
export LC_ALL=C
cd "$root"

dir=tests/fixtures/osd_fvar
rm -rf "$dir"
mkdir -p "$dir"
manifest=$dir/MANIFEST.tsv
{
    echo "# Face-varying reference fixtures from OpenSubdiv $osd_version (libosd-dev), made by tools/osd/make_fvar_fixtures.sh:"
    echo "# osd_refine --scheme SCHEME --levels LEVEL --fvar-linear MODE --no-positions [--ignore-tags --boundary edge-and-corner] INPUT"
    printf '# fixture\tscheme\tboundary\tlevel\tinput\tmode\ttagged\n'
} >"$manifest"

# True when every face corner of the OBJ file $1 has a vt index (and there are vt lines).
all_corners_have_uvs() {
    awk '$1 == "vt" { vt = 1 } $1 == "f" { for (i = 2; i <= NF; i++) if ($i !~ /^-?[0-9]+\/-?[0-9]+/) bad = 1 }
         END { exit !(vt && !bad) }' "$1"
}

# True when the file has tags that change the result.
has_tags() {
    awk '$1 == "t" && $2 ~ /^(crease|corner|hole|interpolateboundary|creasemethod|smoothtriangles)$/ { t = 1 }
         END { exit !t }' "$1"
}

tagged_boundary() {
    local value
    value=$(awk '$1 == "t" && $2 == "interpolateboundary" { v = $4 } END { print v }' "$1")
    case $value in
        0) echo none ;;
        1) echo edge-and-corner ;;
        *) echo edge-only ;;
    esac
}

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for input in $(ls tests/meshes/osd/*.obj tests/meshes/osd_nonmanifold/*.obj | sort); do
    all_corners_have_uvs "$input" || continue
    name=$(basename "$input" .obj)
    case $name in
        catmark_*) scheme=catmark ;;
        loop_*) scheme=loop ;;
        bilinear_*) scheme=bilinear ;;
        *) continue ;;
    esac
    kinds=untagged
    has_tags "$input" && kinds="untagged tagged"
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
