#!/bin/sh
# Builds tools/osd/osd_refine against the system OpenSubdiv (Debian: apt-get install libosd-dev).
# Usage: tools/osd/build.sh [OUTPUT]   (default: target/osd/osd_refine under the repository root)
# FLOAT=1 builds it with float positions and weights (-DOSD_REAL=float), for accuracy comparisons;
# the fixtures are made with the default, double.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
out=${1:-"$root/target/osd/osd_refine"}
mkdir -p "$(dirname "$out")"
if [ ! -f /usr/include/opensubdiv/far/topologyRefiner.h ]; then
    echo "build.sh: OpenSubdiv headers not found; run: apt-get install libosd-dev opensubdiv-tools" >&2
    exit 1
fi
${CXX:-g++} -O2 -std=c++14 -Wall -Wextra ${FLOAT:+-DOSD_REAL=float} -o "$out" "$here/osd_refine.cpp" -losdCPU
echo "$out"
