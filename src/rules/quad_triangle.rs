//! Quad/Triangle subdivision (Stam & Loop, "Quad/Triangle Subdivision", Computer Graphics
//! Forum 22(1), 2003), as the smoothing step that follows the linear split of
//! [`crate::refine::quad_tri`].
//!
//! # Derivation
//!
//! The scheme factors into a linear split followed by one averaging step. Let `v` be a vertex of
//! the linearly refined mesh, `e_i` its `n` edge neighbours, and `d_j` the vertex diagonally
//! opposite `v` in each incident quad.
//!
//! - **Only quads around `v`**: `v' = (n-3)/n v + 2/n² Σ e_i + 1/n² Σ d_j`. For an old vertex,
//!   `e_i = (v + p_i)/2` are edge midpoints and `d_j` face centroids, which gives
//!   `(n-2)/n v + 1/n² Σ p_i + 1/n² Σ f_j`: Catmull-Clark's vertex rule. For a new edge point
//!   (valence 4, neighbours `a`, `b`, `F₁`, `F₂`, diagonals summing to `2F₁ + 2F₂`) it gives
//!   `(a + b + F₁ + F₂)/4`, and for a face centroid `F` it gives `F` again: Catmull-Clark
//!   exactly, on any all-quad region and on the quads that `n`-gons split into.
//! - **Only triangles around `v`**: `v' = a v + (1-a)/n Σ e_i` with
//!   `a(n) = 2 (3/8 + cos(2π/n)/4)² - 1/4`. For an old vertex, `e_i = (v + p_i)/2` gives
//!   `(1+a)/2 v + (1-a)/2 · avg p_i`, and `(1-a)/2 = nβ` with Loop's
//!   `β = (5/8 - (3/8 + cos(2π/n)/4)²)/n`: Loop's vertex rule. A new edge point has valence 6,
//!   `a = 1/4`, and `1/4 m + 1/8 Σ e_i = 3/8 (p + q) + 1/8 (r + s)`: Loop's edge rule.
//!   (pmp-library writes `2 (3/8 + (cos(2π/n) - 1)/4)²`, putting the `-1/4` inside the square:
//!   `a = 1/8` at valence 6, which is not Loop.)
//! - **Quads and triangles around `v`** (`n_q` quads): the paper's averaging of face centroids,
//!   `v' = α (v + 1/2 Σ e_i + 1/4 Σ_quads d_j)` with `α = 1 / (1 + n/2 + n_q/4)`. In the regular
//!   quad/triangle configuration (two quads and three triangles, `α = 1/4`) this is the rule the
//!   paper analyses as C¹ with bounded curvature.
//! - **Boundary vertices** (a boundary edge of the refined mesh touches them): the crease rule
//!   `1/2 v + 1/4 (b₁ + b₂)` along the two boundary neighbours `b₁`, `b₂`, which is `(a + 6v +
//!   b)/8` for old vertices and keeps new boundary points at the midpoints, exactly as
//!   Catmull-Clark and Loop do. The other [`Boundary`] modes apply as in every primal scheme.
//!
//! So on an all-quad mesh the scheme is Catmull-Clark and on an all-triangle mesh it is Loop,
//! boundaries included, which the tests check against OpenSubdiv.

use super::{boundary_vertex_rule, ring, vec3, AveragingRules};
use crate::mesh::HalfEdgeMesh;
use crate::scheme::Boundary;
use glam::Vec3;

/// Stam & Loop's Quad/Triangle smoothing rules.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QuadTriangle {
    pub boundary: Boundary,
}

/// The vertex weight `a(n)` for a vertex surrounded by `n` triangles.
pub fn triangle_vertex_weight(n: u32) -> f32 {
    let c = 0.375 + 0.25 * (std::f64::consts::TAU / n as f64).cos();
    (2.0 * c * c - 0.25) as f32
}

impl AveragingRules for QuadTriangle {
    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32) -> Vec3 {
        let v = vec3(mesh.positions[vertex as usize]);
        let (mut quads, mut others, mut diagonals) = (0u32, 0u32, Vec3::ZERO);
        let ring = ring(mesh, vertex, |h| {
            let c = mesh.he_cell[h as usize] as usize;
            if mesh.cell_offsets[c + 1] - mesh.cell_offsets[c] == 4 {
                quads += 1;
                let diagonal = mesh.to_vertex(mesh.next_in_cell(h));
                diagonals += vec3(mesh.positions[diagonal as usize]);
            } else {
                others += 1;
            }
        });
        if ring.faces == 0 {
            return v;
        }
        if let Some(p) = self.boundary_point(v, &ring) {
            return p;
        }
        let n = ring.valence as f32;
        if others == 0 {
            v * ((n - 3.0) / n) + (ring.neighbours * 2.0 + diagonals) / (n * n)
        } else if quads == 0 {
            let a = triangle_vertex_weight(ring.valence);
            v * a + ring.neighbours * ((1.0 - a) / n)
        } else {
            let alpha = 1.0 / (1.0 + 0.5 * n + 0.25 * quads as f32);
            (v + ring.neighbours * 0.5 + diagonals * 0.25) * alpha
        }
    }
}

impl QuadTriangle {
    /// Boundary vertices of the refined mesh. The primal boundary rules are stated on the
    /// parent mesh; here they act on the linearly refined one, where the crease rule is
    /// `1/2 v + 1/4 (b₁ + b₂)`, corners keep their place, and seed 003's mean keeps its form.
    fn boundary_point(&self, v: Vec3, ring: &super::Ring) -> Option<Vec3> {
        match self.boundary {
            Boundary::EdgeOnly | Boundary::EdgeAndCorner if ring.boundary_edges == 2 => {
                if self.boundary == Boundary::EdgeAndCorner && ring.faces == 1 {
                    return Some(v);
                }
                Some(v * 0.5 + ring.boundary * 0.25)
            }
            Boundary::Average if ring.boundary_edges > 0 => {
                Some((v + ring.boundary) / (1.0 + ring.boundary_edges as f32))
            }
            _ => boundary_vertex_rule(self.boundary, v, ring),
        }
    }
}
