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

use super::{centroid, ring, vec3};
use crate::mesh::HalfEdgeMesh;
use crate::scheme::Boundary;
use glam::Vec3;

/// The geometry policy of the √3 split ([`crate::refine::sqrt3`]): every face without a refined
/// boundary edge gets a face point, every refined boundary half-edge two points, every vertex a
/// new position. All are functions of the parent mesh only.
///
/// Implementations must be pure functions of their arguments: the host may call them in any
/// order or from several threads.
pub trait Sqrt3Rules {
    /// The point for cell `cell`.
    fn face_point(&self, mesh: &HalfEdgeMesh, cell: u32) -> Vec3;
    /// The new position of vertex `vertex`; `refine_boundary` says whether this level splits
    /// boundary edges.
    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32, refine_boundary: bool) -> Vec3;
    /// The two points on boundary half-edge `half_edge` (from `t` to `s`): the one near `t`, then
    /// the one near `s`. Called only on levels that refine the boundary.
    fn boundary_points(&self, mesh: &HalfEdgeMesh, half_edge: u32) -> [Vec3; 2];
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

/// The boundary neighbours of boundary half-edge `t → s`: `q` before `t` and `r` after `s`
/// along the boundary (`t` and `s` themselves where the mesh does not say, which a manifold
/// boundary never leaves open).
fn boundary_neighbours(mesh: &HalfEdgeMesh, half_edge: u32) -> (u32, u32) {
    let t = mesh.he_from[half_edge as usize];
    let s = mesh.to_vertex(half_edge);
    let is_boundary = |h: u32| mesh.he_next_around_edge[h as usize] == h;
    // A boundary vertex lists its outgoing boundary half-edge first.
    let r = match mesh.out_half_edges(s).first() {
        Some(&h) if is_boundary(h) => mesh.to_vertex(h),
        _ => s,
    };
    let q = mesh
        .out_half_edges(t)
        .iter()
        .map(|&h| mesh.prev_in_cell(h))
        .find(|&h| is_boundary(h))
        .map_or(t, |h| mesh.he_from[h as usize]);
    (q, r)
}

impl Sqrt3Rules for Sqrt3 {
    #[inline]
    fn face_point(&self, mesh: &HalfEdgeMesh, cell: u32) -> Vec3 {
        centroid(mesh, cell)
    }

    #[inline]
    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32, refine_boundary: bool) -> Vec3 {
        let v = vec3(mesh.positions[vertex as usize]);
        let ring = ring(mesh, vertex, |_| {});
        if ring.faces == 0 {
            return v;
        }
        if ring.boundary_edges > 0 {
            // Two boundary edges: a boundary vertex; more: several fans meet, no direction.
            let moves =
                refine_boundary && ring.boundary_edges == 2 && self.boundary != Boundary::Fixed;
            return if moves { (v * 19.0 + ring.boundary * 4.0) / 27.0 } else { v };
        }
        let alpha = sqrt3_alpha(ring.valence);
        v * (1.0 - alpha) + ring.neighbours * (alpha / ring.valence as f32)
    }

    #[inline]
    fn boundary_points(&self, mesh: &HalfEdgeMesh, half_edge: u32) -> [Vec3; 2] {
        let t = mesh.he_from[half_edge as usize];
        let s = mesh.to_vertex(half_edge);
        let p = |v: u32| vec3(mesh.positions[v as usize]);
        if self.boundary == Boundary::Fixed {
            return [(p(t) * 2.0 + p(s)) / 3.0, (p(t) + p(s) * 2.0) / 3.0];
        }
        let (q, r) = boundary_neighbours(mesh, half_edge);
        [(p(q) + p(t) * 16.0 + p(s) * 10.0) / 27.0, (p(t) * 10.0 + p(s) * 16.0 + p(r)) / 27.0]
    }
}
