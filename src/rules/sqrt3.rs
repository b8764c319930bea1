//! Kobbelt's √3 subdivision rules (seed `001`; Kobbelt 2000), with the boundary rule as CGAL's
//! `Sqrt3_mask_3` has it:
//!
//! - face point: the centroid;
//! - interior vertex of valence `n`: `(1 - α) v + α/n Σ neighbours`,
//!   `α = (4 - 2 cos(2π/n)) / 9` (1/3 at `n = 6`);
//! - on a level that refines the boundary, boundary half-edge `t → s` of the boundary run
//!   `q → t → s → r` gets the two points `(q + 16t + 10s)/27` (near `t`) and `(10t + 16s + r)/27`
//!   (near `s`), and a boundary vertex `s` between boundary neighbours `t` and `r` moves to
//!   `(4t + 19s + 4r)/27`;
//! - on the other levels boundary vertices keep their position (boundary edges are not split).
//!
//! [`Boundary::Fixed`] keeps boundary vertices in place on every level and puts the boundary
//! points at the thirds of their edge, so the boundary polygon never changes. Every other
//! boundary option gives Kobbelt's rule: √3 has one boundary rule, which moves corners (vertices
//! of one face) too, as CGAL does; seed 003's midpoint average has no √3 counterpart.

use super::{boundary_ring, centroid, one_ring, ring, Weights};
use crate::mesh::HalfEdgeMesh;
use crate::options::Boundary;

/// The geometry policy of the √3 split ([`crate::refine::sqrt3`]): every face without a refined
/// boundary edge gets a face point, every refined boundary half-edge two points, every vertex a
/// new position. All are weights of parent values only (no rule weights face points).
///
/// Implementations must be pure functions of their arguments: the host may call them in any
/// order or from several threads.
pub trait Sqrt3Rules {
    /// The weights of the point for cell `cell`.
    fn face_point(&self, mesh: &HalfEdgeMesh, cell: u32, w: &mut impl Weights);
    /// The weights of the new position of vertex `vertex`; `refine_boundary` says whether this
    /// level splits boundary edges.
    fn vertex_point(
        &self,
        mesh: &HalfEdgeMesh,
        vertex: u32,
        refine_boundary: bool,
        w: &mut impl Weights,
    );
    /// The weights of one of the two points on boundary half-edge `half_edge` (from `t` to `s`):
    /// the one near `t` (`near == 0`) or the one near `s` (`near == 1`). Called only on levels
    /// that refine the boundary.
    fn boundary_point(
        &self,
        mesh: &HalfEdgeMesh,
        half_edge: u32,
        near: usize,
        w: &mut impl Weights,
    );
}

/// √3 subdivision rules; triangles only.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Sqrt3 {
    pub boundary: Boundary,
}

/// Kobbelt's α for valence `n`: `(4 - 2 cos(2π/n)) / 9`.
pub fn sqrt3_alpha(n: u32) -> f32 {
    let c = (std::f64::consts::TAU / n as f64).cos();
    ((4.0 - 2.0 * c) / 9.0) as f32
}

/// The boundary neighbours of boundary half-edge `t → s`, as corners (see [`Weights::corner`]):
/// `q` before `t` and `r` after `s` along the boundary (`t` and `s` themselves where the mesh
/// does not say, which a manifold boundary never leaves open).
fn boundary_neighbours(mesh: &HalfEdgeMesh, half_edge: u32) -> (u32, u32) {
    let (t, s) = (half_edge, mesh.next_in_cell(half_edge));
    let is_boundary = |h: u32| mesh.he_next_around_edge[h as usize] == h;
    // A boundary vertex lists its outgoing boundary half-edge first.
    let r = match mesh.out_half_edges(mesh.he_from[s as usize]).first() {
        Some(&h) if is_boundary(h) => mesh.next_in_cell(h),
        _ => s,
    };
    let q = mesh
        .out_half_edges(mesh.he_from[t as usize])
        .iter()
        .map(|&h| mesh.prev_in_cell(h))
        .find(|&h| is_boundary(h))
        .unwrap_or(t);
    (q, r)
}

impl Sqrt3Rules for Sqrt3 {
    #[inline]
    fn face_point(&self, mesh: &HalfEdgeMesh, cell: u32, w: &mut impl Weights) {
        centroid(mesh, cell, w)
    }

    #[inline]
    fn vertex_point(
        &self,
        mesh: &HalfEdgeMesh,
        vertex: u32,
        refine_boundary: bool,
        w: &mut impl Weights,
    ) {
        let ring = ring(mesh, vertex);
        if ring.faces == 0 {
            return w.vertex(vertex, 1.0);
        }
        if ring.boundary_edges > 0 {
            // Two boundary edges: a boundary vertex; more: several fans meet, no direction.
            let moves =
                refine_boundary && ring.boundary_edges == 2 && self.boundary != Boundary::Fixed;
            if moves {
                w.vertex(vertex, 19.0 / 27.0);
                boundary_ring(mesh, vertex, 4.0 / 27.0, w);
            } else {
                w.vertex(vertex, 1.0);
            }
            return;
        }
        let alpha = sqrt3_alpha(ring.valence);
        one_ring(mesh, vertex, &ring, alpha / ring.valence as f32, false, w);
        w.vertex(vertex, 1.0 - alpha);
    }

    #[inline]
    fn boundary_point(
        &self,
        mesh: &HalfEdgeMesh,
        half_edge: u32,
        near: usize,
        w: &mut impl Weights,
    ) {
        let (t, s) = (half_edge, mesh.next_in_cell(half_edge));
        let (near_end, far_end) = if near == 0 { (t, s) } else { (s, t) };
        if self.boundary == Boundary::Fixed {
            w.corner(near_end, 2.0 / 3.0);
            w.corner(far_end, 1.0 / 3.0);
            return;
        }
        let (q, r) = boundary_neighbours(mesh, half_edge);
        // (q + 16t + 10s)/27 near t, (10t + 16s + r)/27 near s.
        let beyond = if near == 0 { q } else { r };
        w.corner(beyond, 1.0 / 27.0);
        w.corner(near_end, 16.0 / 27.0);
        w.corner(far_end, 10.0 / 27.0);
    }
}
