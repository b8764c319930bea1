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
//! boundaries included, which the tests check against OpenSubdiv. On a mesh of triangles
//! [`crate::scheme`] runs Loop itself (its host and rules, with the crease rules for
//! non-manifold edges and vertices, and child edges kept apart), so that the two agree result
//! for result there, non-manifold meshes included; these rules serve the triangles of mixed
//! meshes, and `tests/schemes.rs` checks them against Loop's on meshes of triangles.
//!
//! # Evaluation on the parent mesh
//!
//! The refined mesh is never built: each rule gathers the refined one-ring from the parent.
//! A face point is the centroid (the quad rule returns it unchanged: `Σ e_i = Σ corners`). An
//! old vertex's refined neighbours are the midpoints of its edges and its diagonals the face
//! points of its non-triangle faces. An edge point's refined neighbours are the edge's ends, plus
//! per adjacent triangle the midpoints of its two other edges (three child triangles), or per
//! other face its face point (two child quads, whose diagonals are the midpoints of the face's
//! edges next to the edge). On the boundary the refined crease rule and seed 003's mean equal
//! the parent-mesh forms of [`boundary_vertex_rule`], and boundary edge points stay midpoints.

use super::{edge_midpoint, interior_ring, smooth_edge, MixedSplitRules, Weights};
use crate::mesh::HalfEdgeMesh;
use crate::options::Boundary;

/// Stam & Loop's Quad/Triangle rules.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QuadTriangle {
    pub boundary: Boundary,
}

/// The vertex weight `a(n)` for a vertex surrounded by `n` triangles.
pub fn triangle_vertex_weight(n: u32) -> f32 {
    let c = 0.375 + 0.25 * (std::f64::consts::TAU / n as f64).cos();
    (2.0 * c * c - 0.25) as f32
}

/// The refined one-ring of a vertex of the refined mesh, counted: its valence, how many of its
/// faces are quads and how many are not.
#[derive(Default)]
struct RefinedRing {
    valence: u32,
    quads: u32,
    triangles: u32,
}

impl RefinedRing {
    /// The averaging step of the derivation above for an interior vertex: the weights on the
    /// vertex itself, on the sum of its refined neighbours and on the sum of its quad diagonals.
    fn mask(&self) -> [f32; 3] {
        let n = self.valence as f32;
        if self.triangles == 0 {
            [(n - 3.0) / n, 2.0 / (n * n), 1.0 / (n * n)]
        } else if self.quads == 0 {
            let a = triangle_vertex_weight(self.valence);
            [a, (1.0 - a) / n, 0.0]
        } else {
            let alpha = 1.0 / (1.0 + 0.5 * n + 0.25 * self.quads as f32);
            [alpha, 0.5 * alpha, 0.25 * alpha]
        }
    }
}

fn is_triangle(mesh: &HalfEdgeMesh, c: u32) -> bool {
    mesh.cell_range(c as usize).len() == 3
}

impl MixedSplitRules for QuadTriangle {
    fn face_point(&self, mesh: &HalfEdgeMesh, cell: u32, w: &mut impl Weights) {
        super::centroid(mesh, cell, w)
    }

    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights) {
        let Some(halves) = smooth_edge(mesh, edge) else {
            return edge_midpoint(mesh, edge, w);
        };
        // The edge point sits at the midpoint `m` of the linear split; its refined neighbours
        // are the edge's ends, and per side the face's point or the triangle's two other
        // midpoints and far corner.
        let mut r = RefinedRing { valence: 2, ..RefinedRing::default() };
        for h in halves {
            if is_triangle(mesh, mesh.cell_of(h)) {
                r.valence += 2;
                r.triangles += 3;
            } else {
                r.valence += 1;
                r.quads += 2;
            }
        }
        let [center, neighbour, diagonal] = r.mask();
        let [a, b] = mesh.edge_vertices[edge as usize];
        // `m` and the two ends.
        w.vertex(a, 0.5 * center + neighbour);
        w.vertex(b, 0.5 * center + neighbour);
        for h in halves {
            let c = mesh.cell_of(h);
            let (prev, next) = (mesh.prev_in_cell(h), mesh.next_in_cell(h));
            if is_triangle(mesh, c) {
                // The midpoints of the triangle's two other edges, `(from + to)/2 + before`
                // between them (`before` is the opposite corner).
                w.corner(h, 0.5 * neighbour);
                w.corner(next, 0.5 * neighbour);
                w.corner(prev, neighbour);
            } else {
                // The face point, and the diagonals of the two child quads at the edge point:
                // the midpoints of the face's edges next to the edge, `(before + from + to +
                // after)/2` between them.
                w.face_point(c, neighbour);
                let half = 0.5 * diagonal;
                w.corner(prev, half);
                w.corner(h, half);
                w.corner(next, half);
                w.corner(mesh.next_in_cell(next), half);
            }
        }
    }

    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32, w: &mut impl Weights) {
        let Some(ring) = interior_ring(self.boundary, mesh, vertex, w) else { return };
        let mut r = RefinedRing { valence: ring.valence, ..RefinedRing::default() };
        let out = mesh.out_half_edges(vertex);
        for &h in out {
            if is_triangle(mesh, mesh.cell_of(h)) {
                r.triangles += 1;
            } else {
                r.quads += 1;
            }
        }
        // The refined neighbours are the midpoints `(v + p_i)/2` of the vertex's edges, the
        // diagonals the face points of its quads.
        let [center, neighbour, diagonal] = r.mask();
        for &h in out {
            w.corner(mesh.next_in_cell(h), 0.5 * neighbour);
            let c = mesh.cell_of(h);
            if !is_triangle(mesh, c) {
                w.face_point(c, diagonal);
            }
        }
        w.vertex(vertex, center + 0.5 * neighbour * ring.valence as f32);
    }
}
