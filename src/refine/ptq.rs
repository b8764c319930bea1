//! Primal triangle quadrisection (PTQ): each triangle splits into four at its edge points.
//!
//! Child vertices are `[old vertices | edge points]`. Triangle `t` with corners `(a, b, c)` and
//! half-edges `h0 = a→b`, `h1 = b→c`, `h2 = c→a` becomes child cells `4t .. 4t + 3`:
//! `(a, e0, e2)`, `(e0, b, e1)`, `(e2, e1, c)` and the middle `(e1, e2, e0)`, where `ek` is the
//! edge point of `hk`'s edge: child `k` has its parent's corner `k` in position `k`, as in
//! OpenSubdiv, so each child keeps its parent's parametric orientation. Every loop writes only
//! its own entries.
//!
//! Child edges, as in [`super::pqq`]: the half of parent edge `e` at its first vertex is `2e`,
//! at its second `2e + 1` (for an edge from a vertex to itself: at its half-edge's from-end and
//! to-end); triangle `t`'s inner edges are `2E + 3t` (`e0`–`e1`), `2E + 3t + 1`
//! (`e1`–`e2`) and `2E + 3t + 2` (`e2`–`e0`). [`child_mesh`] numbers them so, by index
//! arithmetic, and so keeps apart two child edges that join the same two vertices (as
//! OpenSubdiv does; merging them by vertex pair would change the topology of some
//! non-manifold inputs).

use crate::mesh::HalfEdgeMesh;
use crate::primvar::{Points, Primvar};
use crate::rules::crease::decay;
use crate::rules::{LevelTags, TriSplitRules};

/// Child `[vertices, edges, half-edges, cells]` of one PTQ level of a triangle mesh.
pub fn child_counts(vertices: u64, edges: u64, half_edges: u64, cells: u64) -> [u64; 4] {
    [vertices + edges, 2 * edges + 3 * cells, 4 * half_edges, 4 * cells]
}

/// Number of child vertices: `V + E`.
pub fn num_child_vertices(mesh: &HalfEdgeMesh) -> usize {
    mesh.num_vertices() + mesh.num_edges()
}

/// The new positions in child vertex order: [`refine_values`] of the mesh's positions.
pub fn refine_points<R: TriSplitRules>(mesh: &HalfEdgeMesh, rules: &R) -> Vec<[f32; 3]> {
    refine_values(mesh, rules, &mesh.positions)
}

/// The new values in child vertex order (`V + E` of them), computed by `rules` from `parent`
/// (as [`super::pqq::refine_values`]), built by pushes rather than zeroed and overwritten.
pub fn refine_values<R: TriSplitRules, P: Primvar>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    parent: &P,
) -> P {
    <super::Ptq as super::PrimalSplit<R>>::points(mesh, rules, parent)
}

/// [`refine_values`], appended to `points` (as [`super::pqq::refine_values_into`]).
pub fn refine_values_into<R: TriSplitRules, P: Primvar>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    parent: &P,
    points: &mut impl Points<P>,
) {
    let (v, e) = (mesh.num_vertices() as u32, mesh.num_edges() as u32);
    let mut sum = parent.sum(&mesh.he_from, None);
    points.extend_with(v, &mut sum, |i, w| rules.vertex_point(mesh, i, w));
    points.extend_with(e, &mut sum, |i, w| rules.edge_point(mesh, i, w));
}

/// The child triangles' vertex indices, 12 per parent triangle. The mesh must be all triangles.
pub fn child_face_indices(mesh: &HalfEdgeMesh) -> Vec<u32> {
    let base = mesh.num_vertices() as u32;
    let corners = mesh.he_from.as_chunks::<3>().0;
    let children: Vec<[u32; 12]> = corners
        .iter()
        .zip(mesh.he_edge.as_chunks::<3>().0)
        .map(|(&triangle, edges)| triangle_children(triangle, edges.map(|e| base + e)))
        .collect();
    children.into_flattened()
}

/// The four children of triangle `(a, b, c)` whose edges `ab`, `bc`, `ca` have the edge points
/// `[e0, e1, e2]`, in the order of the module docs.
#[inline]
pub fn triangle_children([a, b, c]: [u32; 3], [e0, e1, e2]: [u32; 3]) -> [u32; 12] {
    [a, e0, e2, e0, b, e1, e2, e1, c, e1, e2, e0]
}

/// The complete child mesh, with `positions` from [`refine_points`] and child edges numbered as
/// the module docs say. The mesh must be all triangles.
pub fn child_mesh(mesh: &HalfEdgeMesh, positions: Vec<[f32; 3]>) -> HalfEdgeMesh {
    let ne = mesh.num_edges() as u32;
    let he_from = child_face_indices(mesh);
    let mut he_edge = vec![0u32; 4 * mesh.num_half_edges()];
    for (t, out) in he_edge.chunks_exact_mut(12).enumerate() {
        let h = 3 * t;
        // The halves of each corner's edge at its from-end and at its to-end.
        let [[a0, a1], [b0, b1], [c0, c1]] = [h, h + 1, h + 2].map(|x| halves(mesh, x));
        let inner = 2 * ne + 3 * t as u32;
        let (i01, i12, i20) = (inner, inner + 1, inner + 2);
        // Child k's half-edges in order, as the module docs list the children: (a, e0, e2) is
        // a→e0, e0→e2, e2→a; (e0, b, e1) is e0→b, b→e1, e1→e0; (e2, e1, c) is e2→e1, e1→c,
        // c→e2; the middle (e1, e2, e0) is e1→e2, e2→e0, e0→e1.
        out.copy_from_slice(&[a0, i20, c1, a1, b0, i01, i12, b1, c0, i12, i20, i01]);
    }
    let cells = (0..=4 * mesh.num_cells() as u32).map(|c| 3 * c).collect();
    let num_edges = 2 * mesh.num_edges() + 3 * mesh.num_cells();
    let marked = super::child_marks(mesh, num_edges);
    let multi_fan = mesh.multi_fan_vertices;
    HalfEdgeMesh::from_cells_and_edges(
        positions, cells, he_from, he_edge, num_edges, marked, multi_fan,
    )
}

/// The child edges of parent half-edge `h`'s edge `e` at `h`'s from-end and at its to-end: `2e`
/// and `2e + 1` when `h` runs from the edge's first vertex, else the other way round. By
/// direction rather than by vertex, so that the two halves of an edge from a vertex to itself
/// are told apart.
#[inline(always)]
pub(crate) fn halves(mesh: &HalfEdgeMesh, h: usize) -> [u32; 2] {
    let e = mesh.he_edge[h];
    let backward = (mesh.edge_vertices[e as usize][0] != mesh.he_from[h]) as u32;
    [2 * e + backward, 2 * e + 1 - backward]
}

/// The child level's tags (see [`crate::rules::crease`]) for `child`, [`child_mesh`] of `mesh`:
/// the halves `2e`, `2e + 1` of parent edge `e` get its sharpness decayed at its first and
/// second vertex, inner edges are smooth; old vertices keep their decayed sharpness, edge points
/// are smooth; the four children of a hole are holes.
pub fn child_tags(mesh: &HalfEdgeMesh, child: &HalfEdgeMesh, tags: &LevelTags) -> LevelTags {
    let (nv, ne, nt) = (mesh.num_vertices(), mesh.num_edges(), mesh.num_cells());
    let mut edges = vec![0.0f32; 2 * ne + 3 * nt];
    for (e, &s) in tags.edges.iter().enumerate() {
        if s > 0.0 {
            let [a, b] = mesh.edge_vertices[e];
            edges[2 * e] = tags.decay_at(s, a);
            edges[2 * e + 1] = tags.decay_at(s, b);
        }
    }
    let mut vertices = vec![0.0f32; nv + ne];
    for (child, &s) in vertices.iter_mut().zip(&tags.vertices) {
        *child = decay(s);
    }
    let holes = if tags.has_holes() {
        (0..4 * nt).map(|c| tags.holes[c / 4]).collect()
    } else {
        Vec::new()
    };
    let mut non_manifold = Vec::new();
    if !tags.non_manifold.is_empty() {
        non_manifold = Vec::with_capacity(nv + ne);
        non_manifold.extend_from_slice(&tags.non_manifold);
        non_manifold.extend((0..ne as u32).map(|e| mesh.is_non_manifold_edge(e)));
    }
    LevelTags::new(child, edges, vertices, holes, non_manifold, tags.method, tags.smooth_triangles)
}
