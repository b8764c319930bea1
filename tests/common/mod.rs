//! Helpers shared by the native integration tests.
#![allow(dead_code)]

use subsurf::{HalfEdgeMesh, PolyMesh};

/// V - E + F of a polygon mesh, counting edges through the half-edge mesh.
pub fn euler_characteristic(mesh: &PolyMesh) -> i64 {
    let he = HalfEdgeMesh::from_poly(mesh).expect("valid mesh");
    he.num_vertices() as i64 - he.num_edges() as i64 + he.num_cells() as i64
}

/// Number of boundary half-edges.
pub fn boundary_half_edges(mesh: &PolyMesh) -> usize {
    let he = HalfEdgeMesh::from_poly(mesh).expect("valid mesh");
    he.half_edge_indices().filter(|&h| he.half_edge(h).unwrap().is_boundary()).count()
}

pub fn position(mesh: &PolyMesh, v: usize) -> [f32; 3] {
    [mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]]
}

pub fn distance(a: [f32; 3], b: [f32; 3]) -> f32 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The meshes every scheme test runs on: closed, open, with an inner hole, with n-gons.
pub fn sample_meshes() -> Vec<(&'static str, PolyMesh)> {
    use subsurf::shapes::*;
    vec![
        ("cube", cube()),
        ("torus", torus(8, 6, 2.0, 0.5)),
        ("grid", grid(4, 3)),
        ("grid-with-hole", grid_with_hole(5, 5, 2..3, 1..3)),
        ("prism5", prism(5)),
        ("prism7-mixed", triangulate_quads(&prism(7))),
        ("icosahedron", icosahedron()),
        ("dodecahedron", dodecahedron()),
        ("torus-triangles", torus_triangles(6, 5, 2.0, 0.7)),
    ]
}

/// Asserts that two point sets are equal up to order, each point matching one within `tol`.
pub fn assert_same_points(a: &[[f32; 3]], b: &[[f32; 3]], tol: f32, what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: point counts differ");
    let mut order: Vec<usize> = (0..b.len()).collect();
    order.sort_by(|&i, &j| b[i][0].total_cmp(&b[j][0]));
    let xs: Vec<f32> = order.iter().map(|&i| b[i][0]).collect();
    let mut used = vec![false; b.len()];
    for p in a {
        let start = xs.partition_point(|&x| x < p[0] - tol);
        let found = (start..xs.len())
            .take_while(|&k| xs[k] <= p[0] + tol)
            .find(|&k| !used[k] && distance(*p, b[order[k]]) <= tol);
        match found {
            Some(k) => used[k] = true,
            None => panic!("{what}: no match for point {p:?}"),
        }
    }
}

/// The length of the diagonal of the bounding box of `positions` (at least 1e-3).
pub fn diagonal(positions: &[f32]) -> f32 {
    let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
    for p in positions.chunks_exact(3) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let d: f32 = (0..3).map(|k| (hi[k] - lo[k]).max(0.0).powi(2)).sum::<f32>().sqrt();
    d.max(1e-3)
}

/// Shapes whose normals at some vertices come from another span of faces than OpenSubdiv's:
/// where a vertex's faces have no canonical first one and our driver does not track
/// OpenSubdiv's (Catmull-Clark's interior vertex of two faces in `catmark_val2_back2back`), and
/// at non-manifold vertices, whose edges OpenSubdiv lists in its own order (every shape of
/// `tests/meshes/osd_nonmanifold/`). On these shapes the normals that differ are counted, not
/// required to agree (positions are). Loop's interior creases and corners agree: the driver
/// follows OpenSubdiv's first face through triangle splits (`subsurf::limit::FirstFaces`).
pub const OTHER_SPAN: &[&str] = &[
    "catmark_val2_back2back",
    "catmark_fan",
    "catmark_gregory_test4",
    "catmark_nonman_edges",
    "catmark_nonman_verts",
    "catmark_val2_nonman",
    "loop_nonman_edge100",
    "loop_nonman_edges",
    "loop_nonman_verts",
    "loop_val2_interior",
];
