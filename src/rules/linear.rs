//! The linear rules: old vertices stay, new points are midpoints and centroids. Bilinear runs on
//! the quad split (as OpenSubdiv's bilinear scheme), midpoint on the triangle split.

use super::{centroid, edge_midpoint, QuadSplitRules, TriSplitRules, Weights};
use crate::mesh::HalfEdgeMesh;

/// Bilinear subdivision: face centroids, edge midpoints, vertices unchanged.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Bilinear;

/// Midpoint subdivision of triangles: edge midpoints, vertices unchanged.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Midpoint;

impl QuadSplitRules for Bilinear {
    fn face_point(&self, mesh: &HalfEdgeMesh, cell: u32, w: &mut impl Weights) {
        centroid(mesh, cell, w)
    }

    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights) {
        edge_midpoint(mesh, edge, w)
    }

    fn vertex_point(&self, _: &HalfEdgeMesh, vertex: u32, w: &mut impl Weights) {
        w.vertex(vertex, 1.0)
    }
}

impl TriSplitRules for Midpoint {
    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights) {
        edge_midpoint(mesh, edge, w)
    }

    fn vertex_point(&self, _: &HalfEdgeMesh, vertex: u32, w: &mut impl Weights) {
        w.vertex(vertex, 1.0)
    }
}
