#!/bin/bash
# OpenSubdiv's own cost for the channels of subsurf's uv + colour target (benches/table.rs,
# `cargo bench --bench table`): Catmull-Clark on the 1M-quad torus at level 1, positions only,
# then with a face-varying uv (the torus's (u, v) grid, seams along both closing loops; mode
# corners-plus1) and a vertex-varying colour of three floats, in alternating processes.
# tools/osd/osd_refine built with float positions and weights (as subsurf's), its
# `create + refine + interpolate` line: TopologyRefinerFactory::Create, RefineUniform and the
# PrimvarRefiner calls (Interpolate for positions and colour, InterpolateFaceVarying for the uv),
# the same steps as one subsurf call except that OpenSubdiv writes no face lists out.
# Prints each process's best of REPEATS runs, then the ratio of the medians of those bests.
#   tools/osd/attribute_cost.sh [PROCESSES] [REPEATS]     (default 5 and 3)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
processes=${1:-5}
repeats=${2:-3}
refine=$(FLOAT=1 "$here/build.sh" "$root/target/osd/osd_refine_float")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
torus="$tmp/torus_uv_1000x1000.obj"
python3 "$here/make_meshes.py" torus --major 1000 --minor 1000 --uv "$torus"
best() { "$refine" --levels 1 --time "$repeats" --no-output --quiet "$@" "$torus" 2>&1 \
  | awk '/create \+ refine \+ interpolate/ { print $6 }'; }
plain=() channels=()
for _ in $(seq "$processes"); do
  plain+=("$(best)")
  channels+=("$(best --fvar-linear corners-plus1 --color)")
done
median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
p=$(median "${plain[@]}") c=$(median "${channels[@]}")
echo "OpenSubdiv $(dpkg-query -W -f='${Version}' libosd-dev 2>/dev/null || echo '?'), Catmull-Clark torus 1M quads L1, best of $repeats per process, s"
echo "positions only:   ${plain[*]}"
echo "+ uv and colour:  ${channels[*]}"
awk -v p="$p" -v c="$c" 'BEGIN { printf "medians %.3f and %.3f s: ratio %.2f\n", p, c, c / p }'
