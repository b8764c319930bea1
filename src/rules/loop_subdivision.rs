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
use super::Weights;
use super::{edge_ends, edge_midpoint, interior_ring, one_ring, smooth_edge, TriSplitRules};
use crate::mesh::HalfEdgeMesh;
use crate::options::Boundary;

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

/// The smooth vertex mask of valence `n`: weights on the vertex and on each neighbour (the
/// triangle split has no face points).
#[inline]
fn smooth_vertex_mask(n: u32) -> [f32; 2] {
    let beta = loop_beta(n);
    [1.0 - n as f32 * beta, beta]
}

/// The corner of `h`'s triangle opposite its edge, as a corner (see [`Weights::corner`]).
#[inline]
fn opposite(mesh: &HalfEdgeMesh, h: u32) -> u32 {
    mesh.prev_in_cell(h)
}

impl TriSplitRules for Loop {
    #[inline]
    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights) {
        match smooth_edge(mesh, edge) {
            Some([h0, h1]) => {
                w.scaled(0.125, |w| {
                    w.corner(opposite(mesh, h0), 1.0);
                    w.corner(opposite(mesh, h1), 1.0);
                });
                edge_ends(mesh, edge, 0.375, w);
            }
            None => edge_midpoint(mesh, edge, w),
        }
    }

    #[inline]
    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32, w: &mut impl Weights) {
        let Some(ring) = interior_ring(self.boundary, mesh, vertex, w) else { return };
        let [center, edge] = smooth_vertex_mask(ring.valence);
        one_ring(mesh, vertex, &ring, edge, false, w);
        w.vertex(vertex, center);
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
    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights) {
        let Some([h0, h1]) = sharp_or_smooth(mesh, self.tags, edge) else {
            return edge_midpoint(mesh, edge, w);
        };
        let far = creased_edge_point(mesh, self.tags, edge, 0.375, 0.125, w);
        if far != 0.0 {
            w.scaled(far, |w| {
                w.corner(opposite(mesh, h0), 1.0);
                w.corner(opposite(mesh, h1), 1.0);
            });
        }
    }

    #[inline]
    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32, w: &mut impl Weights) {
        creased_vertex_point(mesh, self.tags, self.boundary, vertex, (smooth_vertex_mask, false), w)
    }
}
