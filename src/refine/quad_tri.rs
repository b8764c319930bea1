//! The mixed split of Quad/Triangle subdivision: triangles split into four as in
//! [`super::ptq`], every other face into quads around a face point as in [`super::pqq`]. The
//! positions come from a [`MixedSplitRules`] policy.
//!
//! Child vertices are `[old vertices | centroids of non-triangles, in cell order | edge
//! midpoints]`; child faces follow the parent cells, four triangles per triangle (in the PTQ
//! order) or `n` quads per `n`-gon (in the PQQ order).

use super::ptq;
use crate::mesh::{HalfEdgeMesh, PolyMesh};
use crate::primvar::PointSum;
use crate::rules::MixedSplitRules;

/// Child `[vertices, faces]` of one level, from the parent counts and the number of triangles
/// `tris` (whose half-edges number `3 tris`).
pub fn child_counts(vertices: u64, edges: u64, half_edges: u64, cells: u64, tris: u64) -> [u64; 2] {
    [vertices + (cells - tris) + edges, 4 * tris + (half_edges - 3 * tris)]
}

/// One level: the child mesh as flat arrays, with positions from `rules`.
pub fn refine<R: MixedSplitRules>(mesh: &HalfEdgeMesh, rules: &R) -> PolyMesh {
    let (nv, nf, ne) = (mesh.num_vertices(), mesh.num_cells(), mesh.num_edges());
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
    // Face points of every cell first (the rules read them), then the child positions.
    let mut sum = PointSum::new(&mesh.positions, &mesh.he_from, &[]);
    let cell_points: Vec<[f32; 3]> =
        (0..nf as u32).map(|c| sum.eval(|w| rules.face_point(mesh, c, w))).collect();
    let mut sum = PointSum::new(&mesh.positions, &mesh.he_from, &cell_points);
    let mut positions = vec![0.0f32; 3 * (nv + centroids as usize + ne)];
    {
        let points = positions.as_chunks_mut::<3>().0;
        let (old, rest) = points.split_at_mut(nv);
        let (faces, edges) = rest.split_at_mut(centroids as usize);
        for (v, p) in old.iter_mut().enumerate() {
            *p = sum.eval(|w| rules.vertex_point(mesh, v as u32, w));
        }
        for (c, &k) in centroid_of.iter().enumerate() {
            if k != u32::MAX {
                faces[k as usize] = cell_points[c];
            }
        }
        for (e, p) in edges.iter_mut().enumerate() {
            *p = sum.eval(|w| rules.edge_point(mesh, e as u32, w));
        }
    }
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
    PolyMesh { positions, indices, face_sizes }
}
