//! Catmull-Clark stencils, with the boundary rules of [`Boundary`], and with semi-sharp creases,
//! corners and holes ([`CreasedCatmullClark`]).
//!
//! Derived from seed `000` (whose pseudocode scatters `+=` per half-edge; here every point is a
//! gather over its own neighbourhood, so no two computations write the same place) and checked
//! against OpenSubdiv 3.5:
//!
//! - face point: the centroid;
//! - interior edge point: `(a + b + f0 + f1) / 4`;
//! - boundary or non-manifold edge point: the midpoint (the edge is a sharp crease);
//! - interior vertex of valence `n`: `(n - 2)/n · v + 1/n² · Σ neighbours + 1/n² · Σ face points`,
//!   the same as seed `003`'s `(n-3)/n · v + 1/n · F + 2/n · R`;
//! - boundary vertex: see [`Boundary`].
//!
//! [`CatmullClark`] is the untagged rule set: it needs no sharpness data and is meant for
//! 2-manifold meshes. [`CreasedCatmullClark`] adds the crease rules of [`super::crease`] (sharp
//! and semi-sharp edges and vertices, non-manifold edges and vertices, OpenSubdiv's
//! smooth-triangle edge rule); [`crate::scheme`] picks it when there are tags, when the boundary
//! is `none`, or when the mesh is not a 2-manifold.

use super::crease::{creased_edge_point, creased_vertex_point, sharp_or_smooth, LevelTags};
use super::{
    centroid, edge_midpoint, interior_ring, one_ring, smooth_edge, QuadSplitRules, Weights,
};
use crate::mesh::HalfEdgeMesh;
use crate::options::Boundary;

/// Catmull-Clark subdivision rules.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CatmullClark {
    pub boundary: Boundary,
}

/// The smooth vertex mask of valence `n`: the weight on the vertex, and the weight on each
/// neighbour and on each face point (the same).
#[inline]
fn smooth_vertex_mask(n: u32) -> [f32; 2] {
    let n = n as f32;
    [(n - 2.0) / n, 1.0 / (n * n)]
}

impl QuadSplitRules for CatmullClark {
    #[inline]
    fn face_point(&self, mesh: &HalfEdgeMesh, cell: u32, w: &mut impl Weights) {
        centroid(mesh, cell, w)
    }

    #[inline]
    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights) {
        match smooth_edge(mesh, edge) {
            Some([h0, h1]) => {
                let [a, b] = mesh.edge_vertices[edge as usize];
                w.scaled(0.25, |w| {
                    w.vertex(a, 1.0);
                    w.vertex(b, 1.0);
                    w.face_point(mesh.cell_of(h0), 1.0);
                    w.face_point(mesh.cell_of(h1), 1.0);
                });
            }
            None => edge_midpoint(mesh, edge, w),
        }
    }

    #[inline]
    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32, w: &mut impl Weights) {
        let Some(ring) = interior_ring(self.boundary, mesh, vertex, w) else { return };
        if face_points_cost_more(w) && ring.interior && mesh.cell_size == 4 {
            return quad_vertex_point(mesh, vertex, ring.faces, w);
        }
        let [center, ring_weight] = smooth_vertex_mask(ring.faces);
        // The small weights first: summed before the large one, their rounding stays small
        // at high valence (catmark_pole360).
        one_ring(mesh, vertex, &ring, ring_weight, true, w);
        w.vertex(vertex, center);
    }
}

/// [`Weights::FACE_POINTS_COST_MORE`] of `w`'s type.
#[inline(always)]
fn face_points_cost_more<W: Weights>(_: &W) -> bool {
    W::FACE_POINTS_COST_MORE
}

/// The smooth vertex rule at an interior vertex of valence `n` whose faces are all quads, on
/// the vertex, its neighbours and its faces' opposite corners instead of the face points: each
/// face point `(v + e_i + d_i + e_(i+1)) / 4` expanded, `(4n - 7)/(4n) · v + 3/(2n²) · Σ e_i +
/// 1/(4n²) · Σ d_i` (Catmull and Clark's 1978 vertex rule written on a quad mesh's one-ring).
/// The same point as [`CatmullClark`]'s rule; for sinks to which a face point costs more than
/// its corners (a stencil build: 8 % fewer products at the horse's level 2, and no
/// reads of the level's own face-point rows).
fn quad_vertex_point(mesh: &HalfEdgeMesh, vertex: u32, n: u32, w: &mut impl Weights) {
    let n = n as f32;
    let out = mesh.out_half_edges(vertex);
    let next = HalfEdgeMesh::next_in_quad;
    // The small weights first, as in `vertex_point`.
    w.scaled(1.0 / (4.0 * n * n), |w| out.iter().for_each(|&h| w.corner(next(next(h)), 1.0)));
    w.scaled(1.5 / (n * n), |w| out.iter().for_each(|&h| w.corner(next(h), 1.0)));
    w.vertex(vertex, (4.0 * n - 7.0) / (4.0 * n));
}

/// OpenSubdiv's smooth-triangle edge weight (`TRI_SUB_SMOOTH`) for a triangle next to the edge.
const SMOOTH_TRIANGLE_EDGE_WEIGHT: f32 = 0.470;

/// Catmull-Clark with creases, corners and non-manifold features: the rules of
/// [`super::crease`] on one level's [`LevelTags`], with the smooth rules of [`CatmullClark`].
///
/// With `tags.smooth_triangles` (OpenSubdiv's `TRI_SUB_SMOOTH`), a smooth edge next to a
/// triangle weights each face point `w = (w0 + w1) / 2` and each end `(1 - 2w) / 2`, where `wi` is
/// 0.47 for a triangle and 0.25 otherwise.
#[derive(Clone, Copy, Debug)]
pub struct CreasedCatmullClark<'a> {
    pub boundary: Boundary,
    pub tags: &'a LevelTags,
}

impl QuadSplitRules for CreasedCatmullClark<'_> {
    #[inline]
    fn face_point(&self, mesh: &HalfEdgeMesh, cell: u32, w: &mut impl Weights) {
        centroid(mesh, cell, w)
    }

    #[inline]
    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights) {
        // Boundary and non-manifold edges are infinitely sharp: the midpoint.
        let Some([h0, h1]) = sharp_or_smooth(mesh, self.tags, edge) else {
            return edge_midpoint(mesh, edge, w);
        };
        let (c0, c1) = (mesh.cell_of(h0), mesh.cell_of(h1));
        let (vertex_weight, face_weight) = if self.tags.smooth_triangles {
            let size = |c: u32| mesh.cell_range(c as usize).len();
            let w = |c: u32| if size(c) == 3 { SMOOTH_TRIANGLE_EDGE_WEIGHT } else { 0.25 };
            let face_weight = 0.5 * (w(c0) + w(c1));
            (0.5 * (1.0 - 2.0 * face_weight), face_weight)
        } else {
            (0.25, 0.25)
        };
        let face_weight = creased_edge_point(mesh, self.tags, edge, vertex_weight, face_weight, w);
        if face_weight != 0.0 {
            w.scaled(face_weight, |w| {
                w.face_point(c0, 1.0);
                w.face_point(c1, 1.0);
            });
        }
    }

    #[inline]
    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32, w: &mut impl Weights) {
        creased_vertex_point(mesh, self.tags, self.boundary, vertex, (smooth_vertex_mask, true), w)
    }
}
