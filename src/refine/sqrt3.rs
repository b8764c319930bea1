//! The √3 split (Kobbelt; seed `001`): every face gets a centroid and splits into a fan, then
//! every old interior edge is flipped so that it joins the two points across it. Each triangle
//! becomes three, and the mesh turns by 30° per level.
//!
//! Boundaries follow Kobbelt's scheme as CGAL's `Sqrt3_subdivision` runs it: boundary edges are
//! split only on every second level (`refine_boundary`). On the other levels a boundary edge
//! keeps its fan triangle `(a, b, centroid)` and is not flipped. On a refining level a triangle
//! `(t, s, x)` with boundary half-edge `t → s` gets no centroid: the edge gets two points `p_t`
//! (near `t`) and `p_s` (near `s`), the triangle becomes `(t, p_t, x)`, `(p_t, p_s, x)`,
//! `(p_s, s, x)`, and the first and last are flipped with their neighbours like fan triangles,
//! so the edge `x → t` ends up joining `p_t` to the point across it, and `s → x` joins `p_s`.
//! Only the first boundary half-edge of a triangle is split; a triangle with two boundary edges
//! never reaches a refining level of a √3 run (the level before leaves at most one per
//! triangle), and cells that are not triangles are never split this way.
//!
//! Child vertices are `[old vertices | centroids | boundary points]`: centroids of the cells
//! without a split boundary edge, in cell order, then two points per split boundary half-edge
//! (near its from-vertex first), in half-edge order. Child face `h` (three indices at `3h`)
//! belongs to parent half-edge `h = u → v` of cell `c`, with `a(h)` the point of `c` across from
//! `h` after the fan split (the centroid of `c`, or `p_t` / `p_s` as above):
//!
//! - interior manifold edge with opposite half-edge `g`: the flipped triangle `(u, a(g), a(h))`;
//! - split boundary half-edge: the middle triangle `(p_t, p_s, x)`;
//! - any other edge (boundary, or non-manifold, which is never flipped): `(u, v, a(h))`.
//!
//! So on a triangle mesh the faces of cell `c`'s half-edges are the contiguous `3c .. 3c + 2`,
//! and every loop writes only its own entries.

use crate::mesh::{HalfEdgeMesh, PolyMesh};
use crate::rules::Sqrt3Rules;

const NONE: u32 = u32::MAX;

/// Child `[vertices, edges, half-edges, cells]` of one √3 level of a triangle mesh whose
/// triangles have at most one boundary edge each when `refine_boundary` (always so within a
/// run of √3 levels).
pub fn child_counts(
    vertices: u64,
    edges: u64,
    half_edges: u64,
    cells: u64,
    refine_boundary: bool,
) -> [u64; 4] {
    // Every half-edge is an interior one paired with another, or a boundary edge on its own.
    let boundary_edges = (2 * edges).saturating_sub(half_edges);
    if refine_boundary {
        [
            vertices + cells + boundary_edges,
            (3 * half_edges + 3 * boundary_edges) / 2,
            3 * half_edges,
            half_edges,
        ]
    } else {
        [vertices + cells, edges + half_edges, 3 * half_edges, half_edges]
    }
}

/// The split boundary half-edge of each cell (`u32::MAX` for none): its first boundary
/// half-edge when the level refines the boundary and the cell is a triangle.
fn split_half_edges(mesh: &HalfEdgeMesh, refine_boundary: bool) -> Vec<u32> {
    if !refine_boundary {
        return vec![NONE; mesh.num_cells()];
    }
    mesh.cell_offsets
        .windows(2)
        .map(|w| {
            if w[1] - w[0] != 3 {
                return NONE;
            }
            (w[0]..w[1]).find(|&h| mesh.he_next_around_edge[h as usize] == h).unwrap_or(NONE)
        })
        .collect()
}

/// The first child vertex of each cell: its centroid, or the first of its two boundary points.
/// A prefix count, and the number of child vertices.
fn first_child_vertices(mesh: &HalfEdgeMesh, split: &[u32]) -> (Vec<u32>, usize) {
    let centroids = split.iter().filter(|&&b| b == NONE).count() as u32;
    let base = mesh.num_vertices() as u32;
    let (mut next_centroid, mut next_pair) = (base, base + centroids);
    let first = split
        .iter()
        .map(|&b| {
            if b == NONE {
                next_centroid += 1;
                next_centroid - 1
            } else {
                next_pair += 2;
                next_pair - 2
            }
        })
        .collect();
    (first, next_pair as usize)
}

/// One √3 level: the child mesh as flat arrays. `refine_boundary` splits boundary edges (every
/// second level of a run, as Kobbelt and CGAL do).
pub fn refine<R: Sqrt3Rules>(mesh: &HalfEdgeMesh, rules: &R, refine_boundary: bool) -> PolyMesh {
    let split = split_half_edges(mesh, refine_boundary);
    let (first, num_child_vertices) = first_child_vertices(mesh, &split);

    let mut positions = vec![0.0f32; 3 * num_child_vertices];
    let points = positions.as_chunks_mut::<3>().0;
    let (old, new) = points.split_at_mut(mesh.num_vertices());
    for (v, p) in old.iter_mut().enumerate() {
        *p = rules.vertex_point(mesh, v as u32, refine_boundary).to_array();
    }
    // Each cell writes its own one or two slots.
    let base = mesh.num_vertices();
    for (c, (&b, &slot)) in split.iter().zip(&first).enumerate() {
        let at = slot as usize - base;
        if b == NONE {
            if let Some(p) = new.get_mut(at) {
                *p = rules.face_point(mesh, c as u32).to_array();
            }
        } else if let Some(pair) = new.get_mut(at..at + 2) {
            let [near_from, near_to] = rules.boundary_points(mesh, b);
            pair[0] = near_from.to_array();
            pair[1] = near_to.to_array();
        }
    }

    let indices = child_face_indices(mesh, &split, &first);
    let face_sizes = vec![3; mesh.num_half_edges()];
    PolyMesh { positions, indices, face_sizes }
}

/// The point of `h`'s cell across from `h` after the fan split (see the module notes).
#[inline]
fn across(mesh: &HalfEdgeMesh, split: &[u32], first: &[u32], h: u32) -> u32 {
    let c = mesh.he_cell[h as usize] as usize;
    let slot = first[c];
    let b = split[c];
    if b != NONE && h == mesh.next_in_cell(b) {
        slot + 1
    } else {
        slot
    }
}

/// Three child indices per parent half-edge.
fn child_face_indices(mesh: &HalfEdgeMesh, split: &[u32], first: &[u32]) -> Vec<u32> {
    let mut indices = vec![0u32; 3 * mesh.num_half_edges()];
    for (h, out) in indices.chunks_exact_mut(3).enumerate() {
        let h = h as u32;
        let c = mesh.he_cell[h as usize] as usize;
        let u = mesh.he_from[h as usize];
        let triangle = if split[c] == h {
            let x = mesh.he_from[mesh.prev_in_cell(h) as usize];
            [first[c], first[c] + 1, x]
        } else {
            let e = mesh.he_edge[h as usize] as usize;
            match mesh.edge_half_edges[mesh.edge_range(e)] {
                [h0, h1] if mesh.he_from[h0 as usize] != mesh.he_from[h1 as usize] => {
                    let g = if h0 == h { h1 } else { h0 };
                    [u, across(mesh, split, first, g), across(mesh, split, first, h)]
                }
                _ => [u, mesh.to_vertex(h), across(mesh, split, first, h)],
            }
        };
        out.copy_from_slice(&triangle);
    }
    indices
}
