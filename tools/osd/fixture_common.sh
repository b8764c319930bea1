# Sourced by the fixture scripts of tools/osd/ (make_fixtures.sh, make_limit_fixtures.sh,
# make_fvar_fixtures.sh, make_limit_fvar_fixtures.sh): what they share. Sets `here` (this
# folder), `root` (the repository, now the working directory), `script` (the caller's name, for
# messages), `refine` (tools/osd/osd_refine built against the system OpenSubdiv), `osd_version`
# (libosd-dev's) and `tmp` (a scratch folder, removed on exit).

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
script=$(basename "$0")
refine=$("$here/build.sh" "$root/target/osd/osd_refine")
osd_version=$(dpkg-query -W -f='${Version}' libosd-dev 2>/dev/null || echo unknown)
export LC_ALL=C
cd "$root"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# start_manifest DIR LINE...: empties DIR and writes DIR/MANIFEST.tsv with the header LINEs, each
# as one line (a LINE holds its own "# " and tabs).
start_manifest() {
    local dir=$1
    shift
    rm -rf "$dir"
    mkdir -p "$dir"
    printf '%s\n' "$@" >"$dir/MANIFEST.tsv"
}

# The boundary mode that OpenSubdiv uses for the OBJ file $1's own tags (edge-only without an
# interpolateboundary tag, as OpenSubdiv's regression suite).
tagged_boundary() {
    local value
    value=$(awk '$1 == "t" && $2 == "interpolateboundary" { v = $4 } END { print v }' "$1")
    case $value in
        0) echo none ;;
        1) echo edge-and-corner ;;
        2 | "") echo edge-only ;;
        *) echo "$script: $1: interpolateboundary $value" >&2; exit 1 ;;
    esac
}

# has_tags FILE [interpolateboundary]: true when the OBJ file has tags that change the result:
# creases, corners, holes, creasemethod, smoothtriangles, and interpolateboundary when asked.
has_tags() {
    local names="crease|corner|hole|creasemethod|smoothtriangles"
    [ "${2:-}" = interpolateboundary ] && names="$names|interpolateboundary"
    awk -v names="^($names)\$" '$1 == "t" && $2 ~ names { t = 1 } END { exit !t }' "$1"
}

# True when every face corner of the OBJ file $1 has a vt index (and there are vt lines).
all_corners_have_uvs() {
    awk '$1 == "vt" { vt = 1 } $1 == "f" { for (i = 2; i <= NF; i++) if ($i !~ /^-?[0-9]+\/-?[0-9]+/) bad = 1 }
         END { exit !(vt && !bad) }' "$1"
}

# same_fixture DIR NAME LEVEL FILE: the name of a fixture already in DIR for shape NAME at level
# LEVEL whose bytes are FILE's, or nothing.
same_fixture() {
    local other
    for other in "$1/$2".*.L"$3".obj; do
        if [ -f "$other" ] && cmp -s "$4" "$other"; then
            basename "$other"
            return
        fi
    done
}
