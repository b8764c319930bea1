//! Catmull-Clark stencils, with the boundary rules of [`Boundary`], and with semi-sharp creases,
//! corners and holes ([`CreasedCatmullClark`]).
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
//!
//! [`CatmullClark`] is the untagged rule set: it needs no sharpness data and is meant for
//! 2-manifold meshes. [`CreasedCatmullClark`] adds the crease rules of [`super::crease`] (sharp
//! and semi-sharp edges and vertices, non-manifold edges and vertices, OpenSubdiv's
//! smooth-triangle edge rule); [`crate::scheme`] picks it when there are tags, when the boundary
//! is `none`, or when the mesh is not a 2-manifold.

use super::crease::{creased_edge_point, creased_vertex_point, sharp_or_smooth, LevelTags};
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
                let f0 = vec3(face_points[mesh.cell_of(h0) as usize]);
                let f1 = vec3(face_points[mesh.cell_of(h1) as usize]);
                edge_midpoint(mesh, edge) * 0.5 + (f0 + f1) * 0.25
            }
            None => edge_midpoint(mesh, edge),
        }
    }

    #[inline]
    fn vertex_point(&self, mesh: &HalfEdgeMesh, face_points: &[[f32; 3]], vertex: u32) -> Vec3 {
        let v = vec3(mesh.positions[vertex as usize]);
        let mut faces = Vec3::ZERO;
        let ring = ring(mesh, vertex, |h| faces += vec3(face_points[mesh.cell_of(h) as usize]));
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

/// OpenSubdiv's smooth-triangle edge weight (`TRI_SUB_SMOOTH`) for a triangle next to the edge.
const SMOOTH_TRIANGLE_EDGE_WEIGHT: f32 = 0.470;

/// Catmull-Clark with creases, corners and non-manifold features: the rules of
/// [`super::crease`] on one level's [`LevelTags`], with the smooth rules of [`CatmullClark`].
///
/// With `tags.smooth_triangles` (OpenSubdiv's `TRI_SUB_SMOOTH`), a smooth edge next to a
/// triangle weights each face point `w = (w0 + w1) / 2` and each end `(1 - 2w) / 2`, where `wi` is
/// 0.47 for a triangle and 0.25 otherwise.
#[derive(Clone, Copy, Debug)]
pub struct CreasedCatmullClark<'a> {
    pub boundary: Boundary,
    pub tags: &'a LevelTags,
}

impl QuadSplitRules for CreasedCatmullClark<'_> {
    #[inline]
    fn face_point(&self, mesh: &HalfEdgeMesh, cell: u32) -> Vec3 {
        centroid(mesh, cell)
    }

    #[inline]
    fn edge_point(&self, mesh: &HalfEdgeMesh, face_points: &[[f32; 3]], edge: u32) -> Vec3 {
        // Boundary and non-manifold edges are infinitely sharp: the midpoint.
        let Some([h0, h1]) = sharp_or_smooth(mesh, self.tags, edge) else {
            return edge_midpoint(mesh, edge);
        };
        let (c0, c1) = (mesh.cell_of(h0), mesh.cell_of(h1));
        let [a, b] = mesh.edge_vertices[edge as usize];
        let ends = [vec3(mesh.positions[a as usize]), vec3(mesh.positions[b as usize])];
        let faces = vec3(face_points[c0 as usize]) + vec3(face_points[c1 as usize]);
        let (vertex_weight, face_weight) = if self.tags.smooth_triangles {
            let size = |c: u32| mesh.cell_range(c as usize).len();
            let w = |c: u32| if size(c) == 3 { SMOOTH_TRIANGLE_EDGE_WEIGHT } else { 0.25 };
            let face_weight = 0.5 * (w(c0) + w(c1));
            (0.5 * (1.0 - 2.0 * face_weight), face_weight)
        } else {
            (0.25, 0.25)
        };
        creased_edge_point(mesh, self.tags, edge, ends, faces, vertex_weight, face_weight)
    }

    #[inline]
    fn vertex_point(&self, mesh: &HalfEdgeMesh, face_points: &[[f32; 3]], vertex: u32) -> Vec3 {
        creased_vertex_point(
            mesh,
            self.tags,
            self.boundary,
            vertex,
            |c| vec3(face_points[c as usize]),
            |nb| {
                let n = nb.faces as f32;
                nb.v * ((n - 2.0) / n) + (nb.neighbours + nb.face_points) / (n * n)
            },
        )
    }
}
