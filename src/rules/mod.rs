//! Stencil policies: where the new points go, as weights. A rule set reads the parent level's
//! topology (and its tags) and nothing else: for each new point it names the parent values the
//! point combines and with what weight, through a [`Weights`] sink, as OpenSubdiv's `Sdc` masks
//! do. The evaluation applies the same weights to positions and to any other data, vertex- or
//! face-varying; a refinement host in [`crate::refine`] says which new points a level has (the
//! split of seed `004`: host × policy).
//!
//! A user can write a rule set of their own and run it on an existing host: implement the trait
//! of the host's topology split and pass it to the host's `refine` function.

mod catmull_clark;
pub mod crease;
mod doo_sabin;
pub mod limit;
mod linear;
mod loop_subdivision;
mod quad_triangle;
mod sqrt3;
mod weights;

pub use catmull_clark::{CatmullClark, CreasedCatmullClark};
pub use crease::LevelTags;
pub use doo_sabin::{doo_sabin_weight, DooSabin};
pub use linear::{Bilinear, Midpoint};
pub use loop_subdivision::{loop_beta, CreasedLoop, Loop};
pub use quad_triangle::{triangle_vertex_weight, QuadTriangle};
pub use sqrt3::{sqrt3_alpha, Sqrt3, Sqrt3Rules};
pub use weights::{Scaled, Source, Stencil, Weights};

use crate::mesh::HalfEdgeMesh;
use crate::options::Boundary;

/// The geometry policy of a primal quad split (PQQ): every face gets a face point, every edge an
/// edge point, every vertex a new position. The host computes all face points first, then all
/// edge points, then all vertex points; edge and vertex rules may weight the face points of the
/// child level ([`Weights::face_point`]).
///
/// Implementations must be pure functions of their arguments: the host may call them in any
/// order or from several threads.
pub trait QuadSplitRules {
    /// The weights of the face point of cell `cell`.
    fn face_point(&self, mesh: &HalfEdgeMesh, cell: u32, w: &mut impl Weights);
    /// The weights of the edge point of edge `edge`.
    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights);
    /// The weights of the new position of vertex `vertex`.
    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32, w: &mut impl Weights);
}

/// The geometry policy of a primal triangle split (PTQ): every edge gets an edge point, every
/// vertex a new position; each triangle becomes four. No rule may weight face points.
pub trait TriSplitRules {
    /// The weights of the edge point of edge `edge`.
    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights);
    /// The weights of the new position of vertex `vertex`.
    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32, w: &mut impl Weights);
}

/// The geometry policy of the mixed split (Quad/Triangle): triangles split as PTQ, other faces
/// as PQQ. Every cell gets a face point (which edge and vertex rules may weight; output only for
/// non-triangles), every edge an edge point, every vertex a new position.
pub trait MixedSplitRules {
    /// The weights of the face point of cell `cell`.
    fn face_point(&self, mesh: &HalfEdgeMesh, cell: u32, w: &mut impl Weights);
    /// The weights of the edge point of edge `edge`.
    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights);
    /// The weights of the new position of vertex `vertex`.
    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32, w: &mut impl Weights);
}

/// The geometry policy of a dual split (DQQ): every face corner (half-edge) gets a new point,
/// and so does each end of a boundary edge when the boundary is kept (Chaikin's corner cutting).
pub trait CornerRules {
    /// The weights of the point for the corner of half-edge `half_edge`'s cell at its
    /// from-vertex.
    fn corner_point(&self, mesh: &HalfEdgeMesh, half_edge: u32, w: &mut impl Weights);
    /// The weights of the point on boundary half-edge `half_edge` near its from-vertex (`near
    /// == 0`) or near its to-vertex (`near == 1`).
    fn boundary_point(
        &self,
        mesh: &HalfEdgeMesh,
        half_edge: u32,
        near: usize,
        w: &mut impl Weights,
    );
}

/// The centroid of a cell: the face point of every primal scheme.
#[inline(always)]
pub fn centroid(mesh: &HalfEdgeMesh, cell: u32, w: &mut impl Weights) {
    let range = mesh.cell_range(cell as usize);
    let scale = 1.0 / range.len() as f32;
    let group = w.begin_group(scale);
    for h in range {
        w.corner(h as u32, 1.0);
    }
    w.end_group(group);
}

/// `weight` on each end of an edge.
#[inline(always)]
pub fn edge_ends(mesh: &HalfEdgeMesh, edge: u32, weight: f32, w: &mut impl Weights) {
    let [a, b] = mesh.edge_vertices[edge as usize];
    w.scaled(weight, |w| {
        w.vertex(a, 1.0);
        w.vertex(b, 1.0);
    });
}

/// The midpoint of an edge.
#[inline(always)]
pub fn edge_midpoint(mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights) {
    edge_ends(mesh, edge, 0.5, w)
}

/// What a vertex's one-ring looks like: counts only, gathered once and shared by the primal
/// vertex rules, which then weight its members through [`one_ring`] and [`boundary_ring`].
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Ring {
    /// Number of incident edges.
    pub valence: u32,
    /// Number of incident faces.
    pub faces: u32,
    /// Number of incident boundary (single-face) edges.
    pub boundary_edges: u32,
    /// True when the vertex has no boundary edge and its edges are known to be manifold: its
    /// outgoing half-edges then reach every edge once.
    pub interior: bool,
}

/// True when the incoming half-edge before outgoing `h` in its cell is a boundary half-edge:
/// then it is the only trace of its edge among the vertex's outgoing half-edges.
#[inline(always)]
fn incoming_boundary(mesh: &HalfEdgeMesh, h: u32) -> Option<u32> {
    let incoming = mesh.prev_in_cell(h);
    (mesh.he_next_around_edge[incoming as usize] == incoming).then_some(incoming)
}

/// Counts the one-ring of `vertex`.
#[inline(always)]
pub(crate) fn ring(mesh: &HalfEdgeMesh, vertex: u32) -> Ring {
    let out = mesh.out_half_edges(vertex);
    // With manifold edges, every open fan at a vertex starts with an outgoing boundary
    // half-edge, which the mesh lists first: when the first one has a twin, the vertex is
    // interior, and the boundary loads below (two per face) are not needed.
    let interior = out.first().is_some_and(|&h| mesh.he_next_around_edge[h as usize] != h);
    let faces = out.len() as u32;
    if interior && !mesh.non_manifold_edges {
        return Ring { valence: faces, faces, boundary_edges: 0, interior: true };
    }
    let mut r = Ring { valence: faces, faces, ..Ring::default() };
    for &h in out {
        if mesh.he_next_around_edge[h as usize] == h {
            r.boundary_edges += 1;
        }
        if incoming_boundary(mesh, h).is_some() {
            r.valence += 1;
            r.boundary_edges += 1;
        }
    }
    r
}

/// Weights every member of `vertex`'s one-ring by `weight`: the other end of each incident
/// edge (the to-vertex of each outgoing half-edge, and the from-vertex of each incoming boundary
/// half-edge), and with `faces` (Catmull-Clark's smooth rule, which weights neighbours and face
/// points alike) the face point of each incident face too. One group, so a summing sink scales
/// the ring's sum once.
#[inline(always)]
pub(crate) fn one_ring(
    mesh: &HalfEdgeMesh,
    vertex: u32,
    ring: &Ring,
    weight: f32,
    faces: bool,
    w: &mut impl Weights,
) {
    let out = mesh.out_half_edges(vertex);
    let group = w.begin_group(weight);
    // One loop per case, so that the common ones (interior) test nothing per face.
    match (ring.interior, faces) {
        (true, true) => ring_members::<true, true>(mesh, out, w),
        (true, false) => ring_members::<true, false>(mesh, out, w),
        (false, true) => ring_members::<false, true>(mesh, out, w),
        (false, false) => ring_members::<false, false>(mesh, out, w),
    }
    w.end_group(group);
}

/// Weight 1 on the other end of each edge at the vertex whose outgoing half-edges are `out`
/// (only outgoing ones when `INTERIOR`), and with `FACES` on each face point too.
#[inline(always)]
fn ring_members<const INTERIOR: bool, const FACES: bool>(
    mesh: &HalfEdgeMesh,
    out: &[u32],
    w: &mut impl Weights,
) {
    for &h in out {
        if FACES {
            w.face_point(mesh.cell_of(h), 1.0);
        }
        w.corner(mesh.next_in_cell(h), 1.0);
        if !INTERIOR {
            if let Some(incoming) = incoming_boundary(mesh, h) {
                w.corner(incoming, 1.0);
            }
        }
    }
}

/// Weights the other end of each boundary edge at `vertex` by `weight`.
#[inline(always)]
pub(crate) fn boundary_ring(mesh: &HalfEdgeMesh, vertex: u32, weight: f32, w: &mut impl Weights) {
    let group = w.begin_group(weight);
    for &h in mesh.out_half_edges(vertex) {
        if mesh.he_next_around_edge[h as usize] == h {
            w.corner(mesh.next_in_cell(h), 1.0);
        }
        if let Some(incoming) = incoming_boundary(mesh, h) {
            w.corner(incoming, 1.0);
        }
    }
    w.end_group(group);
}

/// The one-ring of `vertex`, counted by walking once around it (across each edge from a face's
/// incoming half-edge to the next face's outgoing one). `None` when the walk does not visit
/// every face at the vertex exactly once in one fan: the faces form several fans (a non-manifold
/// vertex, which the primal schemes keep in place as OpenSubdiv does), or a non-manifold edge
/// sends the walk astray. For a vertex without faces, an empty ring. It relies on the mesh
/// convention that a boundary half-edge leaves a vertex first in its list. The crease rules use
/// it; the plain rules use [`ring`], whose loads do not wait on each other, on meshes known to
/// be 2-manifold. Once a fan is known, [`one_ring`] weights its members.
#[inline]
pub(crate) fn fan(mesh: &HalfEdgeMesh, vertex: u32) -> Option<Ring> {
    let out = mesh.out_half_edges(vertex);
    let Some(&start) = out.first() else {
        return Some(Ring::default());
    };
    let open = mesh.he_next_around_edge[start as usize] == start;
    let mut h = start;
    for faces in 1..=out.len() as u32 {
        let incoming = mesh.prev_in_cell(h);
        let across = mesh.he_next_around_edge[incoming as usize];
        if across == incoming {
            // The far end of an open fan: its incoming boundary edge.
            let ring = Ring { valence: faces + 1, faces, boundary_edges: 2, interior: false };
            return (open && faces as usize == out.len()).then_some(ring);
        }
        if across == start {
            let ring = Ring { valence: faces, faces, boundary_edges: 0, interior: true };
            return (!open && faces as usize == out.len()).then_some(ring);
        }
        if mesh.he_from[across as usize] != vertex {
            return None;
        }
        h = across;
    }
    None
}

/// The weights of a vertex with boundary edges under `boundary`; false (and nothing weighted)
/// for an interior vertex, which the scheme's own smooth rule moves. Shared by every primal
/// scheme.
#[inline(always)]
pub(crate) fn boundary_vertex_rule(
    boundary: Boundary,
    mesh: &HalfEdgeMesh,
    vertex: u32,
    ring: &Ring,
    w: &mut impl Weights,
) -> bool {
    if ring.boundary_edges == 0 {
        return false;
    }
    match boundary {
        Boundary::Average => {
            // Seed 003: the mean of v and the midpoints of its boundary edges.
            let k = ring.boundary_edges as f32;
            w.vertex(vertex, (1.0 + 0.5 * k) / (k + 1.0));
            boundary_ring(mesh, vertex, 0.5 / (k + 1.0), w);
        }
        Boundary::EdgeOnly | Boundary::EdgeAndCorner
            if ring.boundary_edges == 2
                && !(boundary == Boundary::EdgeAndCorner && ring.faces == 1) =>
        {
            w.vertex(vertex, 0.75);
            boundary_ring(mesh, vertex, 0.125, w);
        }
        // `None` never reaches a primal scheme (refused up front); fixed is the safe reading.
        // A corner of one face under edge-and-corner stays, and so does a vertex with more
        // than two boundary edges: it joins several fans and has no crease direction.
        _ => w.vertex(vertex, 1.0),
    }
    true
}

/// What every primal vertex rule does first: a vertex without faces stays, a vertex with
/// boundary edges follows `boundary` (both weighted here); `Some(ring)` for an interior vertex,
/// which the scheme's own smooth rule moves.
#[inline(always)]
pub(crate) fn interior_ring(
    boundary: Boundary,
    mesh: &HalfEdgeMesh,
    vertex: u32,
    w: &mut impl Weights,
) -> Option<Ring> {
    let ring = ring(mesh, vertex);
    if ring.faces == 0 {
        w.vertex(vertex, 1.0);
        return None;
    }
    (!boundary_vertex_rule(boundary, mesh, vertex, &ring, w)).then_some(ring)
}

/// True when `edge` has exactly two half-edges running opposite ways and is not marked
/// non-manifold: the only kind of edge a smooth edge rule applies to. Boundary and non-manifold
/// edges are sharp creases.
#[inline(always)]
pub(crate) fn smooth_edge(mesh: &HalfEdgeMesh, edge: u32) -> Option<[u32; 2]> {
    match mesh.edge_half_edges[mesh.edge_range(edge as usize)] {
        // Without non-manifold edges, two half-edges always run opposite ways.
        [h0, h1]
            if !mesh.non_manifold_edges
                || (mesh.he_from[h0 as usize] != mesh.he_from[h1 as usize]
                    && mesh.marked_non_manifold.get(edge as usize) != Some(&true)) =>
        {
            Some([h0, h1])
        }
        _ => None,
    }
}
