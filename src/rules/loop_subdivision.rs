//! Loop subdivision with Loop's original weights (as OpenSubdiv and CGAL use, not Warren's):
//!
//! - interior edge point `3/8 (a + b) + 1/8 (c + d)`, with `c`, `d` the opposite corners;
//! - boundary or non-manifold edge point: the midpoint;
//! - interior vertex of valence `n`: `(1 - nβ) v + β Σ neighbours`,
//!   `β = (5/8 - (3/8 + cos(2π/n)/4)²) / n` (1/16 at `n = 6`);
//! - boundary vertex: see [`Boundary`].

use super::{boundary_vertex_rule, edge_midpoint, ring, smooth_edge, vec3, TriSplitRules};
use crate::mesh::HalfEdgeMesh;
use crate::scheme::Boundary;
use glam::Vec3;

/// Loop subdivision rules; triangles only.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Loop {
    pub boundary: Boundary,
}

/// Loop's β for valence `n`.
pub fn loop_beta(n: u32) -> f32 {
    let n = n as f64;
    let c = 0.375 + 0.25 * (std::f64::consts::TAU / n).cos();
    ((0.625 - c * c) / n) as f32
}

impl TriSplitRules for Loop {
    #[inline]
    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32) -> Vec3 {
        match smooth_edge(mesh, edge) {
            Some([h0, h1]) => {
                let opposite = |h: u32| {
                    vec3(mesh.positions[mesh.he_from[mesh.prev_in_cell(h) as usize] as usize])
                };
                edge_midpoint(mesh, edge) * 0.75 + (opposite(h0) + opposite(h1)) * 0.125
            }
            None => edge_midpoint(mesh, edge),
        }
    }

    #[inline]
    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32) -> Vec3 {
        let v = vec3(mesh.positions[vertex as usize]);
        let ring = ring(mesh, vertex, |_| {});
        if ring.faces == 0 {
            return v;
        }
        if let Some(p) = boundary_vertex_rule(self.boundary, v, &ring) {
            return p;
        }
        let beta = loop_beta(ring.valence);
        v * (1.0 - ring.valence as f32 * beta) + ring.neighbours * beta
    }
}
