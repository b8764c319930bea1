//! Stencil policies: where the new points go. A rule set knows geometry and nothing of how the
//! child mesh is connected; a refinement host in [`crate::refine`] calls it once per new point
//! (the split of seed `004`: host × policy).
//!
//! A user can write a rule set of their own and run it on an existing host: implement the trait
//! of the host's topology split and pass it to the host's `refine` function.

mod catmull_clark;
pub mod crease;
mod doo_sabin;
mod linear;
mod loop_subdivision;
mod quad_triangle;
mod sqrt3;

pub use catmull_clark::{CatmullClark, CreasedCatmullClark};
pub use crease::LevelTags;
pub use doo_sabin::{doo_sabin_weight, DooSabin};
pub use linear::{Bilinear, Midpoint};
pub use loop_subdivision::{loop_beta, CreasedLoop, Loop};
pub use quad_triangle::{triangle_vertex_weight, QuadTriangle};
pub use sqrt3::{sqrt3_alpha, Sqrt3, Sqrt3Rules};

use crate::mesh::HalfEdgeMesh;
use crate::scheme::Boundary;
use glam::Vec3;

/// The geometry policy of a primal quad split (PQQ): every face gets a face point, every edge an
/// edge point, every vertex a new position. The host computes all face points first, then all
/// edge points, then all vertex points; each call may read the face points of the child level.
///
/// Implementations must be pure functions of their arguments: the host may call them in any
/// order or from several threads.
pub trait QuadSplitRules {
    /// The point for cell `cell`.
    fn face_point(&self, mesh: &HalfEdgeMesh, cell: u32) -> Vec3;
    /// The point for edge `edge`; `face_points[c]` is the face point of cell `c`.
    fn edge_point(&self, mesh: &HalfEdgeMesh, face_points: &[[f32; 3]], edge: u32) -> Vec3;
    /// The new position of vertex `vertex`.
    fn vertex_point(&self, mesh: &HalfEdgeMesh, face_points: &[[f32; 3]], vertex: u32) -> Vec3;
}

#[inline]
pub(crate) fn vec3(p: [f32; 3]) -> Vec3 {
    Vec3::from_array(p)
}

/// The centroid of a cell: the face point of every primal scheme.
#[inline(always)]
pub fn centroid(mesh: &HalfEdgeMesh, cell: u32) -> Vec3 {
    let corners = &mesh.he_from[mesh.cell_range(cell as usize)];
    let sum = corners.iter().fold(Vec3::ZERO, |s, &v| s + vec3(mesh.positions[v as usize]));
    sum / corners.len() as f32
}

/// The geometry policy of a primal triangle split (PTQ): every edge gets an edge point, every
/// vertex a new position; each triangle becomes four.
pub trait TriSplitRules {
    /// The point for edge `edge`.
    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32) -> Vec3;
    /// The new position of vertex `vertex`.
    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32) -> Vec3;
}

/// The geometry policy of the mixed split (Quad/Triangle): triangles split as PTQ, other faces
/// as PQQ. Every cell gets a face point (used by the rules; output only for non-triangles),
/// every edge an edge point, every vertex a new position.
pub trait MixedSplitRules {
    /// The point for cell `cell`.
    fn face_point(&self, mesh: &HalfEdgeMesh, cell: u32) -> Vec3;
    /// The point for edge `edge`; `face_points[c]` is the face point of cell `c`.
    fn edge_point(&self, mesh: &HalfEdgeMesh, face_points: &[[f32; 3]], edge: u32) -> Vec3;
    /// The new position of vertex `vertex`.
    fn vertex_point(&self, mesh: &HalfEdgeMesh, face_points: &[[f32; 3]], vertex: u32) -> Vec3;
}

/// The geometry policy of a dual split (DQQ): every face corner (half-edge) gets a new point,
/// and the new faces join them.
pub trait CornerRules {
    /// The point for the corner of half-edge `half_edge`'s cell at its from-vertex.
    fn corner_point(&self, mesh: &HalfEdgeMesh, half_edge: u32) -> Vec3;
}

/// What a vertex's one-ring looks like, gathered once and shared by the primal vertex rules.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Ring {
    /// Number of incident edges.
    pub valence: u32,
    /// Number of incident faces.
    pub faces: u32,
    /// Sum of the other ends of all incident edges.
    pub neighbours: Vec3,
    /// Sum of the other ends of incident boundary (single-face) edges, and their number.
    pub boundary: Vec3,
    pub boundary_edges: u32,
}

/// Gathers the one-ring of `vertex`, calling `per_face(h)` for each half-edge `h` leaving it
/// (one per incident face).
#[inline]
pub(crate) fn ring(mesh: &HalfEdgeMesh, vertex: u32, mut per_face: impl FnMut(u32)) -> Ring {
    let mut r = Ring::default();
    let out = mesh.out_half_edges(vertex);
    // With manifold edges, every open fan at a vertex starts with an outgoing boundary
    // half-edge, which the mesh lists first: when the first one has a twin, the vertex is
    // interior, and the boundary loads below (two per face) are not needed.
    let interior = out.first().is_some_and(|&h| mesh.he_next_around_edge[h as usize] != h);
    if interior && !mesh.non_manifold_edges {
        for &h in out {
            per_face(h);
            r.neighbours += vec3(mesh.positions[mesh.to_vertex(h) as usize]);
        }
        r.faces = out.len() as u32;
        r.valence = r.faces;
        return r;
    }
    for &h in out {
        per_face(h);
        r.faces += 1;
        let to = vec3(mesh.positions[mesh.to_vertex(h) as usize]);
        r.neighbours += to;
        r.valence += 1;
        if mesh.he_next_around_edge[h as usize] == h {
            r.boundary += to;
            r.boundary_edges += 1;
        }
        // An incoming boundary half-edge is the only trace of its edge among the outgoing ones.
        let incoming = mesh.prev_in_cell(h);
        if mesh.he_next_around_edge[incoming as usize] == incoming {
            let from = vec3(mesh.positions[mesh.he_from[incoming as usize] as usize]);
            r.neighbours += from;
            r.valence += 1;
            r.boundary += from;
            r.boundary_edges += 1;
        }
    }
    r
}

/// The one-ring of `vertex`, gathered by walking once around it (across each edge from a
/// face's incoming half-edge to the next face's outgoing one), calling `per_face(h)` for each
/// half-edge `h` leaving it. `None` when the walk does not visit every face at the vertex exactly
/// once in one fan: the faces form several fans (a non-manifold vertex, which the primal schemes
/// keep in place as OpenSubdiv does), or a non-manifold edge sends the walk astray. For a vertex
/// without faces, an empty ring. It relies on the mesh convention that a boundary half-edge
/// leaves a vertex first in its list. The crease rules use it; the plain rules use [`ring`],
/// whose loads do not wait on each other, on meshes known to be 2-manifold.
#[inline]
pub(crate) fn fan(mesh: &HalfEdgeMesh, vertex: u32, mut per_face: impl FnMut(u32)) -> Option<Ring> {
    let out = mesh.out_half_edges(vertex);
    let mut r = Ring::default();
    let Some(&start) = out.first() else {
        return Some(r);
    };
    let open = mesh.he_next_around_edge[start as usize] == start;
    let mut h = start;
    for _ in 0..out.len() {
        per_face(h);
        r.faces += 1;
        let to = vec3(mesh.positions[mesh.to_vertex(h) as usize]);
        r.neighbours += to;
        let incoming = mesh.prev_in_cell(h);
        let across = mesh.he_next_around_edge[incoming as usize];
        if across == incoming {
            // The far end of an open fan: its incoming boundary edge.
            let from = vec3(mesh.positions[mesh.he_from[incoming as usize] as usize]);
            r.neighbours += from;
            r.valence = r.faces + 1;
            r.boundary = from + vec3(mesh.positions[mesh.to_vertex(start) as usize]);
            r.boundary_edges = 2;
            return (open && r.faces as usize == out.len()).then_some(r);
        }
        if across == start {
            r.valence = r.faces;
            return (!open && r.faces as usize == out.len()).then_some(r);
        }
        if mesh.he_from[across as usize] != vertex {
            return None;
        }
        h = across;
    }
    None
}

/// The new position of a vertex with boundary edges under `boundary`, or `None` for an interior
/// vertex, which the scheme's own smooth rule moves. Shared by every primal scheme.
#[inline]
pub(crate) fn boundary_vertex_rule(boundary: Boundary, v: Vec3, ring: &Ring) -> Option<Vec3> {
    if ring.boundary_edges == 0 {
        return None;
    }
    Some(match boundary {
        // `None` never reaches a primal scheme (refused up front); fixed is the safe reading.
        Boundary::Fixed | Boundary::None => v,
        Boundary::Average => {
            // Seed 003: the mean of v and the midpoints of its boundary edges.
            let k = ring.boundary_edges as f32;
            (v + (ring.boundary + k * v) * 0.5) / (k + 1.0)
        }
        Boundary::EdgeAndCorner if ring.faces == 1 && ring.boundary_edges == 2 => v,
        Boundary::EdgeOnly | Boundary::EdgeAndCorner if ring.boundary_edges == 2 => {
            (v * 6.0 + ring.boundary) * 0.125
        }
        // More than two boundary edges: the vertex joins several fans and has no crease
        // direction, so it stays put as a corner.
        Boundary::EdgeOnly | Boundary::EdgeAndCorner => v,
    })
}

/// True when `edge` has exactly two half-edges running opposite ways: the only kind of edge a
/// smooth edge rule applies to. Boundary and non-manifold edges are sharp creases.
#[inline(always)]
pub(crate) fn smooth_edge(mesh: &HalfEdgeMesh, edge: u32) -> Option<[u32; 2]> {
    match mesh.edge_half_edges[mesh.edge_range(edge as usize)] {
        // Without non-manifold edges, two half-edges always run opposite ways.
        [h0, h1]
            if !mesh.non_manifold_edges
                || mesh.he_from[h0 as usize] != mesh.he_from[h1 as usize] =>
        {
            Some([h0, h1])
        }
        _ => None,
    }
}

#[inline]
pub fn edge_midpoint(mesh: &HalfEdgeMesh, edge: u32) -> Vec3 {
    let [a, b] = mesh.edge_vertices[edge as usize];
    (vec3(mesh.positions[a as usize]) + vec3(mesh.positions[b as usize])) * 0.5
}
