//! Topology hosts: how the child mesh is connected. A host asks a stencil policy from
//! [`crate::rules`] for every new point and never chooses a weight itself.
//!
//! - [`pqq`]: primal quad split (Catmull-Clark, bilinear);
//! - [`ptq`]: primal triangle split (Loop, midpoint);
//! - [`dqq`]: dual split (Doo-Sabin);
//! - [`quad_tri`]: triangles as PTQ, other faces as PQQ (Quad/Triangle);
//! - [`sqrt3`]: centroid split and edge flips (√3).

pub mod dqq;
pub mod pqq;
pub mod ptq;
pub mod quad_tri;
pub mod sqrt3;

use crate::error::{Error, Result};
use crate::mesh::HalfEdgeMesh;
use crate::primvar::{Points, Primvar};
use crate::rules::{LevelTags, QuadSplitRules, TriSplitRules, Weights};

/// Refuses a mesh with a cell that repeats a vertex, naming the first, for `scheme`, which
/// cannot take one (Doo-Sabin, √3, Quad/Triangle).
pub(crate) fn check_distinct_corners(mesh: &HalfEdgeMesh, scheme: &str) -> Result<()> {
    match mesh.first_repeated_corner() {
        None => Ok(()),
        Some((face, vertex)) => Err(Error::Unsupported(format!(
            "face {face} repeats vertex {vertex}; {scheme} needs faces with distinct vertices; use catmull-clark, loop or bilinear"
        ))),
    }
}

/// The marks of a primal split's child edges ([`HalfEdgeMesh::marked_non_manifold`]): the
/// halves `2e`, `2e + 1` of a marked parent edge `e` are marked, the other `num_child_edges - 2E`
/// (inside the parent cells) are not; empty when the parent has no mark.
pub(crate) fn child_marks(mesh: &HalfEdgeMesh, num_child_edges: usize) -> Vec<bool> {
    if mesh.marked_non_manifold.is_empty() {
        return Vec::new();
    }
    let mut marks = Vec::with_capacity(num_child_edges);
    marks.extend(mesh.marked_non_manifold.iter().flat_map(|&m| [m, m]));
    marks.resize(num_child_edges, false);
    marks
}

/// What a level driver needs of a primal split whatever its rule set `R`: the per-level plumbing
/// (new values, child faces, the parent of each child face for leaving out holes, the child mesh
/// and its tags), written once in the driver for both splits.
pub trait PrimalSplit<R> {
    /// Corners of every child face.
    const FACE_SIZE: usize;
    /// True when a last level's faces can stay implicit in the parent ([`crate::refined::Refined`]).
    const IMPLICIT_FACES: bool;
    /// True when every cell gets a face point: child vertices are `[vertices | face points |
    /// edge points]`, otherwise `[vertices | edge points]`.
    const FACE_POINTS: bool;
    /// The rule of edge `edge`'s point.
    fn edge_rule(rules: &R, mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights);
    /// The rule of vertex `vertex`'s new value.
    fn vertex_rule(rules: &R, mesh: &HalfEdgeMesh, vertex: u32, w: &mut impl Weights);
    /// Number of child vertices.
    fn num_points(mesh: &HalfEdgeMesh) -> usize;
    /// The new values of `parent` (positions or other vertex-varying data) in child vertex
    /// order, appended to `out`.
    fn points_into<P: Primvar>(
        mesh: &HalfEdgeMesh,
        rules: &R,
        parent: &P,
        out: &mut impl Points<P>,
    );
    /// The new values of `parent` in child vertex order.
    fn points<P: Primvar>(mesh: &HalfEdgeMesh, rules: &R, parent: &P) -> P {
        let mut points = parent.with_capacity(Self::num_points(mesh));
        Self::points_into(mesh, rules, parent, &mut points);
        points
    }
    /// The child faces' vertex indices.
    fn child_face_indices(mesh: &HalfEdgeMesh) -> Vec<u32>;
    /// The parent cell of child face `f`.
    fn parent_cell(mesh: &HalfEdgeMesh, f: usize) -> u32;
    /// The child mesh, with `positions` from [`PrimalSplit::points`].
    fn child_mesh(mesh: &HalfEdgeMesh, positions: Vec<[f32; 3]>) -> HalfEdgeMesh;
    /// The child level's sharpness and holes.
    fn child_tags(mesh: &HalfEdgeMesh, child: &HalfEdgeMesh, tags: &LevelTags) -> LevelTags;
}

/// The primal quad split ([`pqq`]).
pub struct Pqq;

/// The primal triangle split ([`ptq`]).
pub struct Ptq;

impl<R: QuadSplitRules> PrimalSplit<R> for Pqq {
    const FACE_SIZE: usize = 4;
    const IMPLICIT_FACES: bool = true;
    const FACE_POINTS: bool = true;

    #[inline]
    fn edge_rule(rules: &R, mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights) {
        rules.edge_point(mesh, edge, w)
    }

    #[inline]
    fn vertex_rule(rules: &R, mesh: &HalfEdgeMesh, vertex: u32, w: &mut impl Weights) {
        rules.vertex_point(mesh, vertex, w)
    }

    fn num_points(mesh: &HalfEdgeMesh) -> usize {
        pqq::num_child_vertices(mesh)
    }

    fn points_into<P: Primvar>(
        mesh: &HalfEdgeMesh,
        rules: &R,
        parent: &P,
        out: &mut impl Points<P>,
    ) {
        pqq::refine_values_into(mesh, rules, parent, out)
    }

    fn child_face_indices(mesh: &HalfEdgeMesh) -> Vec<u32> {
        pqq::child_face_indices(mesh)
    }

    /// Child cell `h` comes from parent half-edge `h`'s cell.
    fn parent_cell(mesh: &HalfEdgeMesh, f: usize) -> u32 {
        mesh.cell_of(f as u32)
    }

    fn child_mesh(mesh: &HalfEdgeMesh, positions: Vec<[f32; 3]>) -> HalfEdgeMesh {
        pqq::child_mesh(mesh, positions)
    }

    fn child_tags(mesh: &HalfEdgeMesh, child: &HalfEdgeMesh, tags: &LevelTags) -> LevelTags {
        pqq::child_tags(mesh, child, tags)
    }
}

impl<R: TriSplitRules> PrimalSplit<R> for Ptq {
    const FACE_SIZE: usize = 3;
    const IMPLICIT_FACES: bool = false;
    const FACE_POINTS: bool = false;

    #[inline]
    fn edge_rule(rules: &R, mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights) {
        rules.edge_point(mesh, edge, w)
    }

    #[inline]
    fn vertex_rule(rules: &R, mesh: &HalfEdgeMesh, vertex: u32, w: &mut impl Weights) {
        rules.vertex_point(mesh, vertex, w)
    }

    fn num_points(mesh: &HalfEdgeMesh) -> usize {
        ptq::num_child_vertices(mesh)
    }

    fn points_into<P: Primvar>(
        mesh: &HalfEdgeMesh,
        rules: &R,
        parent: &P,
        out: &mut impl Points<P>,
    ) {
        ptq::refine_values_into(mesh, rules, parent, out)
    }

    fn child_face_indices(mesh: &HalfEdgeMesh) -> Vec<u32> {
        ptq::child_face_indices(mesh)
    }

    /// Child triangle `f` comes from parent triangle `f / 4`.
    fn parent_cell(_: &HalfEdgeMesh, f: usize) -> u32 {
        (f / 4) as u32
    }

    fn child_mesh(mesh: &HalfEdgeMesh, positions: Vec<[f32; 3]>) -> HalfEdgeMesh {
        ptq::child_mesh(mesh, positions)
    }

    fn child_tags(mesh: &HalfEdgeMesh, child: &HalfEdgeMesh, tags: &LevelTags) -> LevelTags {
        ptq::child_tags(mesh, child, tags)
    }
}
