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

use super::{centroid, vec3, QuadSplitRules};
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
        let e = edge as usize;
        let [a, b] = mesh.edge_vertices[e];
        let mid = vec3(mesh.positions[a as usize]) + vec3(mesh.positions[b as usize]);
        let hs = &mesh.edge_half_edges[mesh.edge_range(e)];
        if let [h0, h1] = *hs {
            if mesh.he_from[h0 as usize] != mesh.he_from[h1 as usize] {
                let f0 = vec3(face_points[mesh.he_cell[h0 as usize] as usize]);
                let f1 = vec3(face_points[mesh.he_cell[h1 as usize] as usize]);
                return (mid + f0 + f1) * 0.25;
            }
        }
        mid * 0.5
    }

    #[inline]
    fn vertex_point(&self, mesh: &HalfEdgeMesh, face_points: &[[f32; 3]], vertex: u32) -> Vec3 {
        let v = vec3(mesh.positions[vertex as usize]);
        let out = mesh.out_half_edges(vertex);
        let mut neighbours = Vec3::ZERO;
        let mut faces = Vec3::ZERO;
        let mut boundary = Vec3::ZERO;
        let mut boundary_edges = 0u32;
        for &h in out {
            faces += vec3(face_points[mesh.he_cell[h as usize] as usize]);
            let to = vec3(mesh.positions[mesh.to_vertex(h) as usize]);
            neighbours += to;
            if mesh.he_next_around_edge[h as usize] == h {
                boundary += to;
                boundary_edges += 1;
            }
            let incoming = mesh.prev_in_cell(h);
            if mesh.he_next_around_edge[incoming as usize] == incoming {
                let from = vec3(mesh.positions[mesh.he_from[incoming as usize] as usize]);
                neighbours += from;
                boundary += from;
                boundary_edges += 1;
            }
        }
        if out.is_empty() {
            return v;
        }
        if boundary_edges == 0 {
            let n = out.len() as f32;
            return v * ((n - 2.0) / n) + (neighbours + faces) / (n * n);
        }
        match self.boundary {
            Boundary::Fixed => v,
            Boundary::Average => {
                // Seed 003: the mean of v and the midpoints of its boundary edges.
                let k = boundary_edges as f32;
                (v + (boundary + k * v) * 0.5) / (k + 1.0)
            }
            Boundary::EdgeAndCorner if out.len() == 1 && boundary_edges == 2 => v,
            Boundary::EdgeOnly | Boundary::EdgeAndCorner if boundary_edges == 2 => {
                (v * 6.0 + boundary) * 0.125
            }
            // More than two boundary edges: the vertex joins several fans and has no crease
            // direction, so it stays put as a corner.
            Boundary::EdgeOnly | Boundary::EdgeAndCorner => v,
        }
    }
}
