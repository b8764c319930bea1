//! The linear rules: old vertices stay, new points are midpoints and centroids. Bilinear runs on
//! the quad split (as OpenSubdiv's bilinear scheme), midpoint on the triangle split.

use super::{centroid, edge_midpoint, vec3, QuadSplitRules, TriSplitRules};
use crate::mesh::HalfEdgeMesh;
use glam::Vec3;

/// Bilinear subdivision: face centroids, edge midpoints, vertices unchanged.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Bilinear;

/// Midpoint subdivision of triangles: edge midpoints, vertices unchanged.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Midpoint;

impl QuadSplitRules for Bilinear {
    fn face_point(&self, mesh: &HalfEdgeMesh, cell: u32) -> Vec3 {
        centroid(mesh, cell)
    }

    fn edge_point(&self, mesh: &HalfEdgeMesh, _: &[[f32; 3]], edge: u32) -> Vec3 {
        edge_midpoint(mesh, edge)
    }

    fn vertex_point(&self, mesh: &HalfEdgeMesh, _: &[[f32; 3]], vertex: u32) -> Vec3 {
        vec3(mesh.positions[vertex as usize])
    }
}

impl TriSplitRules for Midpoint {
    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32) -> Vec3 {
        edge_midpoint(mesh, edge)
    }

    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32) -> Vec3 {
        vec3(mesh.positions[vertex as usize])
    }
}
