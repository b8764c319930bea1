//! Stencil policies: where the new points go. A rule set knows geometry and nothing of how the
//! child mesh is connected; a refinement host in [`crate::refine`] calls it once per new point
//! (the split of seed `004`: host × policy).
//!
//! A user can write a rule set of their own and run it on an existing host: implement the trait
//! of the host's topology split and pass it to the host's `refine` function.

mod catmull_clark;

pub use catmull_clark::CatmullClark;

use crate::mesh::HalfEdgeMesh;
use glam::Vec3;

/// The geometry policy of a primal quad split (PQQ): every face gets a face point, every edge an
/// edge point, every vertex a new position. The host computes all face points first, then all
/// edge points, then all vertex points; each call may read the face points of the child level.
///
/// Implementations must be pure functions of their arguments: the host may call them in any
/// order or from several threads.
pub trait QuadSplitRules {
    /// The point for cell `cell`.
    fn face_point(&self, mesh: &HalfEdgeMesh, cell: u32) -> Vec3;
    /// The point for edge `edge`; `face_points[c]` is the face point of cell `c`.
    fn edge_point(&self, mesh: &HalfEdgeMesh, face_points: &[[f32; 3]], edge: u32) -> Vec3;
    /// The new position of vertex `vertex`.
    fn vertex_point(&self, mesh: &HalfEdgeMesh, face_points: &[[f32; 3]], vertex: u32) -> Vec3;
}

#[inline]
pub(crate) fn vec3(p: [f32; 3]) -> Vec3 {
    Vec3::from_array(p)
}

/// The centroid of a cell: the face point of every primal scheme.
#[inline]
pub(crate) fn centroid(mesh: &HalfEdgeMesh, cell: u32) -> Vec3 {
    let c = cell as usize;
    let corners = &mesh.he_from[mesh.cell_offsets[c] as usize..mesh.cell_offsets[c + 1] as usize];
    let sum = corners
        .iter()
        .fold(Vec3::ZERO, |s, &v| s + vec3(mesh.positions[v as usize]));
    sum / corners.len() as f32
}
