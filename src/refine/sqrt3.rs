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
//!
//! [`child_mesh`] gives the next level as a half-edge mesh without the general builder: each
//! child vertex's outgoing half-edges and each child half-edge's twin follow from the parent's
//! connectivity by the rules above, and the result is exactly the mesh
//! `HalfEdgeMesh::from_poly(&refine(..))` would build (`tests/child_mesh.rs` checks this), so the
//! next level's points, whose vertex sums depend on the child's vertex lists, are unchanged.

use super::dqq;
use crate::error::Result;
use crate::mesh::{HalfEdgeMesh, PolyMesh};
use crate::primvar::{Primvar, Rows};
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
pub(crate) fn split_half_edges(mesh: &HalfEdgeMesh, refine_boundary: bool) -> Vec<u32> {
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
pub(crate) fn first_child_vertices(mesh: &HalfEdgeMesh, split: &[u32]) -> (Vec<u32>, usize) {
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

/// The child values from `parent`, in child vertex order.
fn child_points<R: Sqrt3Rules, P: Primvar>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    refine_boundary: bool,
    (split, first, count): (&[u32], &[u32], usize),
    parent: &P,
) -> P {
    let mut points = parent.with_capacity(count);
    let mut sum = parent.sum(&mesh.he_from, None);
    let vertices = mesh.num_vertices() as u32;
    points.extend_with(vertices, &mut sum, |v, w| rules.vertex_point(mesh, v, refine_boundary, w));
    points.extend_zeroed(count - mesh.num_vertices());
    // Each cell writes its own one or two slots.
    for (c, (&b, &slot)) in split.iter().zip(first).enumerate() {
        let at = slot as usize;
        if at >= count {
            continue;
        }
        if b == NONE {
            points.set(at, &mut sum, |w| rules.face_point(mesh, c as u32, w));
        } else {
            for near in 0..2 {
                points.set(at + near, &mut sum, |w| rules.boundary_point(mesh, b, near, w));
            }
        }
    }
    points
}

/// One √3 level: the child mesh as flat arrays. `refine_boundary` splits boundary edges (every
/// second level of a run, as Kobbelt and CGAL do).
pub fn refine<R: Sqrt3Rules>(mesh: &HalfEdgeMesh, rules: &R, refine_boundary: bool) -> PolyMesh {
    refine_with(mesh, rules, refine_boundary, &Rows::default()).0
}

/// [`refine`], and the child values of the vertex-varying `rows` (or of any [`Primvar`]).
pub fn refine_with<R: Sqrt3Rules, P: Primvar>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    refine_boundary: bool,
    rows: &P,
) -> (PolyMesh, P) {
    let split = split_half_edges(mesh, refine_boundary);
    let (positions, indices, rows) = points_and_faces(mesh, rules, refine_boundary, &split, rows);
    let face_sizes = vec![3; mesh.num_half_edges()];
    (PolyMesh { positions: positions.into_flattened(), indices, face_sizes }, rows)
}

/// The child positions, face list and rows of one √3 level, shared by both outputs.
fn points_and_faces<R: Sqrt3Rules, P: Primvar>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    refine_boundary: bool,
    split: &[u32],
    rows: &P,
) -> (Vec<[f32; 3]>, Vec<u32>, P) {
    let (first, num_child_vertices) = first_child_vertices(mesh, split);
    let layout = (split, &first[..], num_child_vertices);
    let positions = child_points(mesh, rules, refine_boundary, layout, &mesh.positions);
    let rows = if rows.is_empty() {
        rows.with_capacity(0)
    } else {
        child_points(mesh, rules, refine_boundary, layout, rows)
    };
    let indices = child_face_indices(mesh, split, &first);
    (positions, indices, rows)
}

/// One √3 level as a half-edge mesh, equal to `HalfEdgeMesh::from_poly(&refine(..))` but
/// written by index arithmetic: the outgoing half-edges of each child vertex (below) and the
/// twin of each child half-edge (`child_twins`), from which `dqq::manifold_mesh` numbers
/// the edges; no sort or search over the child mesh. Three kinds of parent take the general
/// path, which is the only error: meshes `check` refuses, meshes with a face that is not a
/// triangle, and the rare two-triangle "pillow" (an interior vertex of valence 2; only a closed
/// pair of triangles has one), whose flipped edges all join the same two centroids, so that the
/// builder merges them into one non-manifold edge.
pub fn child_mesh<R: Sqrt3Rules>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    refine_boundary: bool,
) -> Result<HalfEdgeMesh> {
    child_mesh_with(mesh, rules, refine_boundary, &Rows::default()).map(|(child, _)| child)
}

/// [`child_mesh`], and the child values of the vertex-varying `rows` (or of any [`Primvar`]).
pub fn child_mesh_with<R: Sqrt3Rules, P: Primvar>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    refine_boundary: bool,
    rows: &P,
) -> Result<(HalfEdgeMesh, P)> {
    let nh = mesh.num_half_edges();
    let triangles = nh == 3 * mesh.num_cells();
    if mesh.is_non_manifold() || !triangles || nh == 0 || has_pillow(mesh) {
        let (poly, rows) = refine_with(mesh, rules, refine_boundary, rows);
        return Ok((HalfEdgeMesh::from_poly(&poly)?, rows));
    }
    let split = split_half_edges(mesh, refine_boundary);
    let (positions, he_from, rows) = points_and_faces(mesh, rules, refine_boundary, &split, rows);
    let num_child_vertices = positions.len();
    let cell_offsets = (0..=nh as u32).map(|c| 3 * c).collect();

    let twin = |h: u32| mesh.he_next_around_edge[h as usize];
    let mut vertex_offsets = Vec::with_capacity(num_child_vertices + 1);
    let mut out = Vec::with_capacity(3 * nh);
    vertex_offsets.push(0u32);
    // An old vertex leaves each child face it is in: the face of each of its parent
    // half-edges `k` but a split one (the middle triangle); that of the boundary half-edge
    // before `k`, unsplit, `(w, y, a)`; and the middle triangle when `k` leads to the split
    // half-edge of its cell (`y` is the split triangle's third vertex).
    for y in 0..mesh.num_vertices() as u32 {
        let start = out.len();
        for &k in mesh.out_half_edges(y) {
            let b = split[k as usize / 3];
            let p = prev(k);
            if b != k {
                out.push(3 * k);
            }
            if twin(p) == p && b != p {
                out.push(3 * p + 1);
            }
            if b == next(k) {
                out.push(3 * b + 2);
            }
        }
        dqq::insertion_sort(&mut out[start..]);
        vertex_offsets.push(out.len() as u32);
    }
    // A centroid leaves the face of each of its cell's half-edges (towards their from-vertex)
    // and of each twin of them (towards the point across).
    for (c, _) in split.iter().enumerate().filter(|(_, &b)| b == NONE) {
        let start = out.len();
        for k in 3 * c as u32..3 * c as u32 + 3 {
            out.push(3 * k + 2);
            if twin(k) != k {
                out.push(3 * twin(k) + 1);
            }
        }
        dqq::insertion_sort(&mut out[start..]);
        vertex_offsets.push(out.len() as u32);
    }
    // The points near `t` and `s` on a split `t → s` of triangle `(t, s, x)`: each leaves the
    // middle triangle, the face of the half-edge it is the point of, and that half-edge's twin.
    for &b in split.iter().filter(|&&b| b != NONE) {
        for (own, k) in [(3 * b, prev(b)), (3 * b + 1, next(b))] {
            let start = out.len();
            out.extend_from_slice(&[own, 3 * k + 2]);
            if twin(k) != k {
                out.push(3 * twin(k) + 1);
            }
            dqq::insertion_sort(&mut out[start..]);
            vertex_offsets.push(out.len() as u32);
        }
    }
    debug_assert_eq!(out.len(), 3 * nh);
    let he_twin = child_twins(mesh, &split);
    let child = dqq::manifold_mesh(dqq::ManifoldParts {
        positions,
        cell_offsets,
        he_from,
        he_twin,
        vertex_offsets,
        vertex_half_edges: out,
    });
    Ok((child, rows))
}

/// Triangles only: the next and previous half-edges in a cell, by arithmetic.
#[inline]
fn next(h: u32) -> u32 {
    if h % 3 == 2 {
        h - 2
    } else {
        h + 1
    }
}

#[inline]
fn prev(h: u32) -> u32 {
    if h.is_multiple_of(3) {
        h + 2
    } else {
        h - 1
    }
}

/// The twin of every child half-edge (itself on the boundary), three per parent half-edge `k`,
/// for child face `k` in the notation of the module docs: `a(k)` is the point across from `k`,
/// `(t, s, x)` a triangle whose half-edge `b = t → s` is split into `t, p_t, p_s, s`.
fn child_twins(mesh: &HalfEdgeMesh, split: &[u32]) -> Vec<u32> {
    let twin = |h: u32| mesh.he_next_around_edge[h as usize];
    // The twin of `3k + 2`, from `a(k)` back to `k`'s from-vertex: in an unsplit cell, in the
    // face of the half-edge before `k` (across its edge when that edge was flipped); in a
    // split cell, the boundary piece `p_s → s`, or `x → p_t` in the middle triangle.
    let into_from = |k: u32| {
        let b = split[k as usize / 3];
        if b == NONE {
            let p = prev(k);
            if twin(p) != p {
                3 * twin(p)
            } else {
                3 * p + 1
            }
        } else if k == next(b) {
            3 * k + 2
        } else {
            3 * b + 2
        }
    };
    let mut twins = vec![0u32; 3 * mesh.num_half_edges()];
    for (k, face) in twins.chunks_exact_mut(3).enumerate() {
        let k = k as u32;
        let b = split[k as usize / 3];
        let j = twin(k);
        let twins_of_face = if b == k {
            // The middle triangle (p_t, p_s, x): the new boundary piece, then p_s → x, whose
            // twin is in the face across s → x (or that face itself at a boundary), and
            // x → p_t, whose twin is in the face of x → t.
            let n = next(k);
            let across_n = if twin(n) != n { 3 * twin(n) } else { 3 * n + 1 };
            [3 * k, across_n, 3 * prev(k) + 2]
        } else if j != k {
            // Flipped: (u, a(j), a(k)). u → a(j) comes back in `j`'s cell: from its point to
            // `j`'s to-vertex, in the face after `j` when that cell is unsplit; the middle
            // triangle's p_s → x, or the boundary piece t → p_t, when it is split.
            let bj = split[j as usize / 3];
            let back = if bj == NONE {
                3 * next(j) + 2
            } else if j == next(bj) {
                3 * bj + 1
            } else {
                3 * k
            };
            [back, 3 * j + 1, into_from(k)]
        } else {
            // A boundary edge kept: (u, v, a(k)); v → a(k) comes back in the face after `k`,
            // or, in a split cell, is x → p_s of the middle triangle or the boundary piece
            // t → p_t.
            let back = if b == NONE {
                3 * next(k) + 2
            } else if k == next(b) {
                3 * b + 1
            } else {
                3 * k + 1
            };
            [3 * k, back, into_from(k)]
        };
        face.copy_from_slice(&twins_of_face);
    }
    twins
}

/// True when some interior vertex has two faces: on a 2-manifold triangle mesh, a closed pair
/// of triangles on the same three vertices.
fn has_pillow(mesh: &HalfEdgeMesh) -> bool {
    mesh.vertex_offsets.windows(2).any(|w| {
        w[1] - w[0] == 2 && {
            let h = mesh.vertex_half_edges[w[0] as usize];
            mesh.he_next_around_edge[h as usize] != h
        }
    })
}

/// The point of `h`'s cell across from `h` after the fan split (see the module notes).
#[inline]
fn across(mesh: &HalfEdgeMesh, split: &[u32], first: &[u32], h: u32) -> u32 {
    let c = mesh.cell_of(h) as usize;
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
        let c = mesh.cell_of(h) as usize;
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
