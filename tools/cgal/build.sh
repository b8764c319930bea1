#!/bin/sh
# Builds tools/cgal/cgal_subdivide against the header-only CGAL (Debian: apt-get install libcgal-dev,
# which brings Boost, GMP and MPFR headers).
# Usage: tools/cgal/build.sh [OUTPUT]   (default: target/cgal/cgal_subdivide under the repository root)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
out=${1:-"$root/target/cgal/cgal_subdivide"}
mkdir -p "$(dirname "$out")"
if [ ! -f /usr/include/CGAL/subdivision_method_3.h ]; then
    echo "build.sh: CGAL headers not found; run: apt-get install libcgal-dev" >&2
    exit 1
fi
# Rebuild only when the source is newer than the binary.
if [ ! -x "$out" ] || [ "$here/cgal_subdivide.cpp" -nt "$out" ]; then
    ${CXX:-g++} -O2 -std=c++17 -Wall -Wextra -o "$out" "$here/cgal_subdivide.cpp" -lgmp -lmpfr
fi
echo "$out"
