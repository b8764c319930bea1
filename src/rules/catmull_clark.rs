//! Catmull-Clark stencils, with the boundary rules of [`Boundary`].
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

use super::{
    boundary_vertex_rule, centroid, edge_midpoint, ring, smooth_edge, vec3, QuadSplitRules,
};
use crate::mesh::HalfEdgeMesh;
use crate::scheme::Boundary;
use glam::Vec3;

/// Catmull-Clark subdivision rules.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CatmullClark {
    pub boundary: Boundary,
}

impl QuadSplitRules for CatmullClark {
    #[inline]
    fn face_point(&self, mesh: &HalfEdgeMesh, cell: u32) -> Vec3 {
        centroid(mesh, cell)
    }

    #[inline]
    fn edge_point(&self, mesh: &HalfEdgeMesh, face_points: &[[f32; 3]], edge: u32) -> Vec3 {
        match smooth_edge(mesh, edge) {
            Some([h0, h1]) => {
                let f0 = vec3(face_points[mesh.he_cell[h0 as usize] as usize]);
                let f1 = vec3(face_points[mesh.he_cell[h1 as usize] as usize]);
                edge_midpoint(mesh, edge) * 0.5 + (f0 + f1) * 0.25
            }
            None => edge_midpoint(mesh, edge),
        }
    }

    #[inline]
    fn vertex_point(&self, mesh: &HalfEdgeMesh, face_points: &[[f32; 3]], vertex: u32) -> Vec3 {
        let v = vec3(mesh.positions[vertex as usize]);
        let mut faces = Vec3::ZERO;
        let ring =
            ring(mesh, vertex, |h| faces += vec3(face_points[mesh.he_cell[h as usize] as usize]));
        if ring.faces == 0 {
            return v;
        }
        if let Some(p) = boundary_vertex_rule(self.boundary, v, &ring) {
            return p;
        }
        let n = ring.faces as f32;
        v * ((n - 2.0) / n) + (ring.neighbours + faces) / (n * n)
    }
}
