//! `triangles::join_quads` on quad meshes split into triangles: every OpenSubdiv regression
//! shape made only of quads, split along either diagonal of every quad, must be joined back
//! into exactly its own quads (the three.js issue: "when the triangles come from triangulating
//! a quad mesh, the result must equal Catmull-Clark on the quad mesh"), with Blender's fold
//! limits (40°) and with them opened to 180°. A quad the rule refuses on its own (folded past
//! the limits, not convex) must stay as its two triangles, never joined with a neighbour's.

use std::collections::BTreeSet;
use std::path::Path;
use subsurf::io::read_obj;
use subsurf::triangles::{join_quads, QuadLimits, TriangleEdges};

/// A quad as its sorted vertices.
fn key(v: &[u32]) -> [u32; 4] {
    let mut k = [v[0], v[1], v[2], v[3]];
    k.sort_unstable();
    k
}

#[test]
fn triangulated_quad_meshes_join_into_their_own_quads() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/meshes/osd");
    let mut names: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    names.sort();
    let open = QuadLimits { face_angle: std::f64::consts::PI, shape_angle: std::f64::consts::PI };
    let (mut shapes, mut quads_total, mut kept_split) = (0, 0, 0);
    for path in names.iter().filter(|p| p.extension().is_some_and(|e| e == "obj")) {
        let mesh = read_obj(&std::fs::read_to_string(path).unwrap()).unwrap();
        if mesh.face_sizes.iter().any(|&s| s != 4) {
            continue;
        }
        let quads: Vec<&[u32]> = mesh.indices.chunks_exact(4).collect();
        // A shape with a quad that repeats a vertex or two quads on the same four vertices
        // cannot be compared by vertex sets.
        let expected: BTreeSet<[u32; 4]> = quads.iter().map(|q| key(q)).collect();
        if expected.len() != quads.len()
            || expected.iter().any(|k| k.windows(2).any(|w| w[0] == w[1]))
        {
            continue;
        }
        shapes += 1;
        for (diagonal, limits) in
            [0, 1].into_iter().flat_map(|d| [(d, QuadLimits::default()), (d, open)])
        {
            let mut corners = Vec::with_capacity(6 * quads.len());
            for q in &quads {
                let [a, b, c, d] = [q[0], q[1], q[2], q[3]];
                corners.extend_from_slice(&if diagonal == 0 {
                    [a, b, c, a, c, d]
                } else {
                    [a, b, d, b, c, d]
                });
            }
            let edges = TriangleEdges::new(&corners).unwrap();
            let marks = vec![0; edges.len()];
            let join = |corners: &[u32]| {
                let edges = TriangleEdges::new(corners).unwrap();
                join_quads(
                    &mesh.positions,
                    corners,
                    &edges,
                    &vec![0; edges.len()],
                    &Default::default(),
                    limits,
                )
                .unwrap()
            };
            let polygons =
                join_quads(&mesh.positions, &corners, &edges, &marks, &Default::default(), limits)
                    .unwrap();
            let vertices = polygons.gather(&corners).unwrap();
            let mut at = 0;
            let mut triangles = 0;
            for &size in &polygons.face_sizes {
                let face = &vertices[at..at + size as usize];
                at += size as usize;
                if size == 4 {
                    assert!(
                        expected.contains(&key(face)),
                        "{}: diagonal {diagonal}, {limits:?}: joined {face:?}, not a quad of the shape",
                        path.display()
                    );
                } else {
                    triangles += 1;
                }
            }
            // A quad left split must be one the rule refuses on its own, not one a neighbour took.
            let split: usize = quads
                .iter()
                .enumerate()
                .filter(|&(q, _)| join(&corners[6 * q..6 * q + 6]).face_sizes != [4])
                .count();
            assert_eq!(
                triangles,
                2 * split,
                "{}: diagonal {diagonal}: triangles left over",
                path.display()
            );
            quads_total += quads.len();
            kept_split += split;
        }
    }
    assert!(shapes >= 20, "only {shapes} all-quad shapes found in {}", dir.display());
    eprintln!(
        "{shapes} all-quad shapes, both diagonals, both limits: {quads_total} quads, {kept_split} refused on their own"
    );
}
