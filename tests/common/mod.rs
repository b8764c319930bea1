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
    he.half_edge_indices()
        .filter(|&h| he.half_edge(h).unwrap().is_boundary())
        .count()
}

pub fn position(mesh: &PolyMesh, v: usize) -> [f32; 3] {
    [
        mesh.positions[3 * v],
        mesh.positions[3 * v + 1],
        mesh.positions[3 * v + 2],
    ]
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
        ("prism7-triangulated", triangulate_quads(&prism(7))),
        ("torus-triangles", torus_triangles(6, 5, 2.0, 0.7)),
    ]
}
