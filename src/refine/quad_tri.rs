//! The mixed split of Quad/Triangle subdivision: triangles split into four as in
//! [`super::ptq`], every other face into quads around a face point as in [`super::pqq`]. The
//! positions come from a [`MixedSplitRules`] policy.
//!
//! Child vertices are `[old vertices | centroids of non-triangles, in cell order | edge
//! midpoints]`; child faces follow the parent cells, four triangles per triangle (in the PTQ
//! order) or `n` quads per `n`-gon (in the PQQ order).

use super::ptq;
use crate::mesh::{HalfEdgeMesh, PolyMesh};
use crate::primvar::{Primvar, Rows};
use crate::rules::{MixedSplitRules, Weights};

/// Child `[vertices, faces]` of one level, from the parent counts and the number of triangles
/// `tris` (whose half-edges number `3 tris`).
pub fn child_counts(vertices: u64, edges: u64, half_edges: u64, cells: u64, tris: u64) -> [u64; 2] {
    [vertices + (cells - tris) + edges, 4 * tris + (half_edges - 3 * tris)]
}

/// The new values from `parent` in child vertex order; `centroid_of[c]` is `u32::MAX` for
/// triangles, whose face points the rules read but the child mesh does not have.
fn points<R: MixedSplitRules, P: Primvar>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    parent: &P,
    centroid_of: &[u32],
) -> P {
    // Face points of every cell first (the rules read them), then the child values.
    let mut face_points = parent.with_capacity(mesh.num_cells());
    let mut sum = parent.sum(&mesh.he_from, None);
    let cells = mesh.num_cells() as u32;
    face_points.extend_with(cells, &mut sum, |c, w| rules.face_point(mesh, c, w));
    let mut points =
        parent.with_capacity(mesh.num_vertices() + mesh.num_cells() + mesh.num_edges());
    let mut sum = parent.sum(&mesh.he_from, Some(&face_points));
    let vertices = mesh.num_vertices() as u32;
    points.extend_with(vertices, &mut sum, |v, w| rules.vertex_point(mesh, v, w));
    for (c, &k) in centroid_of.iter().enumerate() {
        if k != u32::MAX {
            points.push(&mut sum, |w| w.face_point(c as u32, 1.0));
        }
    }
    let edges = mesh.num_edges() as u32;
    points.extend_with(edges, &mut sum, |e, w| rules.edge_point(mesh, e, w));
    points
}

/// One level: the child mesh as flat arrays, with positions from `rules`.
pub fn refine<R: MixedSplitRules>(mesh: &HalfEdgeMesh, rules: &R) -> PolyMesh {
    refine_with(mesh, rules, &Rows::default()).0
}

/// [`refine`], and the child values of the vertex-varying `rows` (or of any [`Primvar`]).
pub fn refine_with<R: MixedSplitRules, P: Primvar>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    rows: &P,
) -> (PolyMesh, P) {
    let (nv, nf) = (mesh.num_vertices(), mesh.num_cells());
    let size = |c: usize| mesh.cell_range(c).len();
    // Index of each cell's centroid among the centroids (u32::MAX for triangles).
    let mut centroid_of = vec![u32::MAX; nf];
    let mut centroids = 0u32;
    let (mut num_indices, mut num_faces) = (0usize, 0usize);
    for (c, slot) in centroid_of.iter_mut().enumerate() {
        if size(c) == 3 {
            (num_indices, num_faces) = (num_indices + 12, num_faces + 4);
        } else {
            *slot = centroids;
            centroids += 1;
            (num_indices, num_faces) = (num_indices + 4 * size(c), num_faces + size(c));
        }
    }
    let edge_base = (nv as u32) + centroids;
    let positions = points(mesh, rules, &mesh.positions, &centroid_of).into_flattened();
    let rows = if rows.is_empty() {
        rows.with_capacity(0)
    } else {
        points(mesh, rules, rows, &centroid_of)
    };
    let mut indices = Vec::with_capacity(num_indices);
    let mut face_sizes = Vec::with_capacity(num_faces);
    for (c, &k) in centroid_of.iter().enumerate() {
        let cell = mesh.cell_range(c);
        let (start, n) = (cell.start, cell.len());
        let edge_point = |i: usize| edge_base + mesh.he_edge[start + (i % n)];
        let corner = |i: usize| mesh.he_from[start + i];
        if k == u32::MAX {
            let corners = [corner(0), corner(1), corner(2)];
            indices.extend_from_slice(&ptq::triangle_children(corners, [0, 1, 2].map(edge_point)));
            face_sizes.extend_from_slice(&[3; 4]);
        } else {
            let center = nv as u32 + k;
            for i in 0..n {
                indices.extend_from_slice(&[
                    corner(i),
                    edge_point(i),
                    center,
                    edge_point(i + n - 1),
                ]);
            }
            face_sizes.extend(std::iter::repeat_n(4, n));
        }
    }
    (PolyMesh { positions, indices, face_sizes }, rows)
}
