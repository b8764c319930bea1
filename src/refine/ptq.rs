//! Primal triangle quadrisection (PTQ): each triangle splits into four at its edge points.
//!
//! Child vertices are `[old vertices | edge points]`. Triangle `t` with corners `(a, b, c)` and
//! half-edges `h0 = a→b`, `h1 = b→c`, `h2 = c→a` becomes child cells `4t .. 4t + 3`:
//! `(a, e0, e2)`, `(e0, b, e1)`, `(e2, e1, c)` and the middle `(e1, e2, e0)`, where `ek` is the
//! edge point of `hk`'s edge: child `k` has its parent's corner `k` in position `k`, as in
//! OpenSubdiv, so each child keeps its parent's parametric orientation. Every loop writes only
//! its own entries.

use crate::mesh::HalfEdgeMesh;
use crate::rules::TriSplitRules;

/// Child `[vertices, edges, half-edges, cells]` of one PTQ level of a triangle mesh.
pub fn child_counts(vertices: u64, edges: u64, half_edges: u64, cells: u64) -> [u64; 4] {
    [vertices + edges, 2 * edges + 3 * cells, 4 * half_edges, 4 * cells]
}

/// Number of child vertices: `V + E`.
pub fn num_child_vertices(mesh: &HalfEdgeMesh) -> usize {
    mesh.num_vertices() + mesh.num_edges()
}

/// Writes the new positions in child vertex order into `points`.
pub fn refine_points<R: TriSplitRules>(mesh: &HalfEdgeMesh, rules: &R, points: &mut [[f32; 3]]) {
    let (vertex_points, edge_points) = points.split_at_mut(mesh.num_vertices());
    for (e, p) in edge_points.iter_mut().enumerate() {
        *p = rules.edge_point(mesh, e as u32).to_array();
    }
    for (v, p) in vertex_points.iter_mut().enumerate() {
        *p = rules.vertex_point(mesh, v as u32).to_array();
    }
}

/// The child triangles' vertex indices, 12 per parent triangle. The mesh must be all triangles.
pub fn child_face_indices(mesh: &HalfEdgeMesh) -> Vec<u32> {
    let base = mesh.num_vertices() as u32;
    let mut indices = vec![0u32; 4 * mesh.num_half_edges()];
    for (t, out) in indices.chunks_exact_mut(12).enumerate() {
        let h = 3 * t;
        let [a, b, c] = [mesh.he_from[h], mesh.he_from[h + 1], mesh.he_from[h + 2]];
        let edges = [0, 1, 2].map(|k| base + mesh.he_edge[h + k]);
        out.copy_from_slice(&triangle_children([a, b, c], edges));
    }
    indices
}

/// The four children of triangle `(a, b, c)` whose edges `ab`, `bc`, `ca` have the edge points
/// `[e0, e1, e2]`, in the order of the module docs.
#[inline]
pub fn triangle_children([a, b, c]: [u32; 3], [e0, e1, e2]: [u32; 3]) -> [u32; 12] {
    [a, e0, e2, e0, b, e1, e2, e1, c, e1, e2, e0]
}
