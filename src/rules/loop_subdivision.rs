//! Loop subdivision with Loop's original weights (as OpenSubdiv and CGAL use, not Warren's):
//!
//! - interior edge point `3/8 (a + b) + 1/8 (c + d)`, with `c`, `d` the opposite corners;
//! - boundary or non-manifold edge point: the midpoint;
//! - interior vertex of valence `n`: `(1 - nβ) v + β Σ neighbours`,
//!   `β = (5/8 - (3/8 + cos(2π/n)/4)²) / n` (1/16 at `n = 6`);
//! - boundary vertex: see [`Boundary`].
//!
//! [`Loop`] is meant for 2-manifold meshes; [`CreasedLoop`] adds creases, corners and
//! non-manifold edges and vertices (see [`super::crease`]).

use super::crease::{creased_edge_point, creased_vertex_point, sharp_or_smooth, LevelTags};
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

/// The corner of `h`'s triangle opposite its edge.
#[inline]
fn opposite(mesh: &HalfEdgeMesh, h: u32) -> Vec3 {
    vec3(mesh.positions[mesh.he_from[mesh.prev_in_cell(h) as usize] as usize])
}

impl TriSplitRules for Loop {
    #[inline]
    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32) -> Vec3 {
        match smooth_edge(mesh, edge) {
            Some([h0, h1]) => {
                edge_midpoint(mesh, edge) * 0.75 + (opposite(mesh, h0) + opposite(mesh, h1)) * 0.125
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

/// Loop with creases, corners and non-manifold features: the rules of [`super::crease`] on one
/// level's [`LevelTags`], with the smooth rules of [`Loop`].
#[derive(Clone, Copy, Debug)]
pub struct CreasedLoop<'a> {
    pub boundary: Boundary,
    pub tags: &'a LevelTags,
}

impl TriSplitRules for CreasedLoop<'_> {
    #[inline]
    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32) -> Vec3 {
        let Some([h0, h1]) = sharp_or_smooth(mesh, self.tags, edge) else {
            return edge_midpoint(mesh, edge);
        };
        let [a, b] = mesh.edge_vertices[edge as usize];
        let ends = [vec3(mesh.positions[a as usize]), vec3(mesh.positions[b as usize])];
        let far = opposite(mesh, h0) + opposite(mesh, h1);
        creased_edge_point(mesh, self.tags, edge, ends, far, 0.375, 0.125)
    }

    #[inline]
    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32) -> Vec3 {
        creased_vertex_point(
            mesh,
            self.tags,
            self.boundary,
            vertex,
            |_| Vec3::ZERO,
            |nb| {
                let beta = loop_beta(nb.faces);
                nb.v * (1.0 - nb.faces as f32 * beta) + nb.neighbours * beta
            },
        )
    }
}
