//! Primal quad quadrisection (PQQ): an n-gon splits into n quads around its face point.
//!
//! The child mesh is written by index arithmetic from the parent's arrays (seed `000`'s
//! `RefineHalfEdges`, generalised to edges with any number of half-edges). For parent half-edge
//! `h` in cell `c`, from vertex `a`, on edge `e`, with previous half-edge `p` on edge `d`:
//!
//! | child half-edge | from            | to              | on child edge        |
//! |-----------------|-----------------|-----------------|----------------------|
//! | `4h + 0`        | `a`             | `V + F + e`     | half of `e` at `a`   |
//! | `4h + 1`        | `V + F + e`     | `V + c`         | `2E + h`             |
//! | `4h + 2`        | `V + c`         | `V + F + d`     | `2E + p`             |
//! | `4h + 3`        | `V + F + d`     | `a`             | half of `d` at `a`   |
//!
//! so child cell `h` is the quad `(a, edge point of e, face point, edge point of d)`, child vertex
//! order is `[old vertices | face points | edge points]`, and the half of parent edge `e` that
//! touches its first vertex is child edge `2e`, the other `2e + 1` (for an edge from a vertex to
//! itself, the half at its half-edge's from-end is `2e`, at its to-end `2e + 1`). Every loop
//! writes only the entries of its own iteration.

use crate::mesh::{quad_and_fan_chunks, HalfEdgeMesh};
use crate::primvar::{Points, Primvar};
use crate::rules::crease::decay;
use crate::rules::{LevelTags, QuadSplitRules};

/// Child vertex, edge, half-edge and cell counts of one PQQ level, in `u64` so that a guard can
/// compare them before anything is allocated.
pub fn child_counts(vertices: u64, edges: u64, half_edges: u64, cells: u64) -> [u64; 4] {
    [vertices + cells + edges, 2 * edges + half_edges, 4 * half_edges, half_edges]
}

/// Number of child vertices: `V + F + E`.
pub fn num_child_vertices(mesh: &HalfEdgeMesh) -> usize {
    mesh.num_vertices() + mesh.num_cells() + mesh.num_edges()
}

/// The new positions in child vertex order: [`refine_values`] of the mesh's positions.
pub fn refine_points<R: QuadSplitRules>(mesh: &HalfEdgeMesh, rules: &R) -> Vec<[f32; 3]> {
    refine_values(mesh, rules, &mesh.positions)
}

/// The new values in child vertex order (`V + F + E` of them), computed by the host's stencil
/// policy `rules` from `parent` (the mesh's positions, or [`crate::primvar::Rows`] of other
/// vertex-varying data). Built by pushes rather than zeroed and overwritten, which on wasm saves
/// a pass over the largest array.
pub fn refine_values<R: QuadSplitRules, P: Primvar>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    parent: &P,
) -> P {
    <super::Pqq as super::PrimalSplit<R>>::points(mesh, rules, parent)
}

/// [`refine_values`], appended to `points` (the values themselves, or a sink that unpacks them
/// as they come, see [`Points`]).
pub fn refine_values_into<R: QuadSplitRules, P: Primvar>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    parent: &P,
    points: &mut impl Points<P>,
) {
    let (v, f, e) = (mesh.num_vertices() as u32, mesh.num_cells() as u32, mesh.num_edges() as u32);
    let mut face_points = parent.with_capacity(f as usize);
    let mut sum = parent.sum(&mesh.he_from, None);
    face_points.extend_with(f, &mut sum, |c, w| rules.face_point(mesh, c, w));
    let mut sum = parent.sum(&mesh.he_from, Some(&face_points));
    points.extend_with(v, &mut sum, |i, w| rules.vertex_point(mesh, i, w));
    points.extend_from(&face_points);
    points.extend_with(e, &mut sum, |i, w| rules.edge_point(mesh, i, w));
}

/// Child cell `h`: the quad (old vertex, edge point, face point, edge point) at the corner where
/// parent half-edge `h` starts.
#[inline(always)]
fn child_quad(mesh: &HalfEdgeMesh, h: u32) -> [u32; 4] {
    let (v, f) = (mesh.num_vertices() as u32, mesh.num_cells() as u32);
    let edge_base = v + f;
    let prev = mesh.prev_in_cell(h);
    [
        mesh.he_from[h as usize],
        edge_base + mesh.he_edge[h as usize],
        v + mesh.cell_of(h),
        edge_base + mesh.he_edge[prev as usize],
    ]
}

/// The `N` child quads of cell `c` of a parent whose cells all have `N` corners, from the
/// parent's corner and edge lists cut into cells: [`child_quad`] for each of the cell's
/// half-edges, with the cell's loads made once and the cell walk a constant rotation.
#[inline(always)]
fn child_quads_of_cell<const N: usize>(
    corners: &[[u32; N]],
    edges: &[[u32; N]],
    [v, f]: [u32; 2],
    c: usize,
) -> [[u32; 4]; N] {
    let from = corners[c];
    let edge = edges[c].map(|e| v + f + e);
    let face = v + c as u32;
    std::array::from_fn(|k| [from[k], edge[k], face, edge[(k + N - 1) % N]])
}

/// The parent's corners and edges cut into cells of `N`, with its vertex and cell counts: what
/// [`child_quads_of_cell`] reads.
fn uniform_cells<const N: usize>(mesh: &HalfEdgeMesh) -> (&[[u32; N]], &[[u32; N]], [u32; 2]) {
    let counts = [mesh.num_vertices() as u32, mesh.num_cells() as u32];
    (mesh.he_from.as_chunks::<N>().0, mesh.he_edge.as_chunks::<N>().0, counts)
}

/// Every child quad of a parent whose cells all have `N` corners, cell by cell.
fn uniform_child_quads<const N: usize>(mesh: &HalfEdgeMesh) -> Vec<[u32; 4]> {
    let (corners, edges, counts) = uniform_cells::<N>(mesh);
    let cells = 0..corners.len();
    let quads: Vec<_> = cells.map(|c| child_quads_of_cell(corners, edges, counts, c)).collect();
    quads.into_flattened()
}

/// The child cells' vertex indices (four per parent half-edge); the face list of the last level.
pub fn child_face_indices(mesh: &HalfEdgeMesh) -> Vec<u32> {
    // Collected from an exact-size iterator: written in place, neither zeroed first nor
    // grown piece by piece (both cost a pass on wasm).
    let quads: Vec<[u32; 4]> = match mesh.cell_size {
        4 => uniform_child_quads::<4>(mesh),
        3 => uniform_child_quads::<3>(mesh),
        _ => (0..mesh.num_half_edges() as u32).map(|h| child_quad(mesh, h)).collect(),
    };
    quads.into_flattened()
}

/// [`child_face_indices`] to `faces` and its fan triangulation (two triangles per parent
/// half-edge, as [`crate::PolyMesh::triangles`] makes them) to `triangles`, in matching pieces
/// (see `mesh::quad_and_fan_chunks`); neither array is ever stored whole.
pub fn child_face_and_triangle_chunks(
    mesh: &HalfEdgeMesh,
    faces: impl FnMut(&[u32]),
    triangles: impl FnMut(&[u32]),
) {
    match mesh.cell_size {
        4 => uniform_child_chunks::<4>(mesh, faces, triangles),
        3 => uniform_child_chunks::<3>(mesh, faces, triangles),
        _ => {
            let quad = |h: usize| [child_quad(mesh, h as u32)];
            quad_and_fan_chunks(mesh.num_half_edges(), quad, faces, triangles)
        }
    }
}

/// [`child_face_and_triangle_chunks`] for a parent whose cells all have `N` corners, cell by
/// cell.
fn uniform_child_chunks<const N: usize>(
    mesh: &HalfEdgeMesh,
    faces: impl FnMut(&[u32]),
    triangles: impl FnMut(&[u32]),
) {
    let (corners, edges, counts) = uniform_cells::<N>(mesh);
    let cell = |c| child_quads_of_cell(corners, edges, counts, c);
    quad_and_fan_chunks(corners.len(), cell, faces, triangles)
}

/// The complete child mesh, with `positions` from [`refine_points`].
pub fn child_mesh(mesh: &HalfEdgeMesh, positions: Vec<[f32; 3]>) -> HalfEdgeMesh {
    let (nv, nf, ne, nh) = (
        mesh.num_vertices() as u32,
        mesh.num_cells() as u32,
        mesh.num_edges() as u32,
        mesh.num_half_edges() as u32,
    );
    let edge_base = nv + nf;
    // Which half of edge `e` touches vertex `a`: child edge 2e or 2e + 1. (An edge from a
    // vertex to itself, from a face that repeats a vertex, has both ends at `a`: its one
    // half-edge starts on half 2e and ends on half 2e + 1; the slots below that take the
    // to-end of a half-edge say so.)
    let half_at = |e: u32, a: u32| 2 * e + (mesh.edge_vertices[e as usize][0] != a) as u32;
    // The child half-edge that parent half-edge `x` leaves on the half of its edge at `a`.
    let child_at = |x: u32, a: u32| {
        if mesh.he_from[x as usize] == a {
            4 * x
        } else {
            4 * mesh.next_in_cell(x) + 3
        }
    };

    let he_from = child_face_indices(mesh);
    // Four entries per parent half-edge, collected in place rather than written into zeroed
    // arrays: no clearing pass over the two largest arrays.
    let corner = |h: u32| (mesh.he_from[h as usize], mesh.prev_in_cell(h));
    let he_edge: Vec<[u32; 4]> = (0..nh)
        .map(|h| {
            let (a, p) = corner(h);
            let (e, d) = (mesh.he_edge[h as usize], mesh.he_edge[p as usize]);
            // `half_at(d, a)`, but the to-end's half 2d + 1 on an edge from `a` to itself.
            let [d0, d1] = mesh.edge_vertices[d as usize];
            let p_end = 2 * d + ((d0 != a) | (d0 == d1)) as u32;
            [half_at(e, a), 2 * ne + h, 2 * ne + p, p_end]
        })
        .collect();
    let he_next_around_edge: Vec<[u32; 4]> = (0..nh)
        .map(|h| {
            let (a, p) = corner(h);
            // `child_at(x, a)`, but `p`'s own to-end child when `p` is alone on its edge.
            let x = mesh.he_next_around_edge[p as usize];
            let near_a = mesh.he_from[x as usize] == a && x != p;
            [
                child_at(mesh.he_next_around_edge[h as usize], a),
                4 * mesh.next_in_cell(h) + 2,
                4 * p + 1,
                if near_a { 4 * x } else { 4 * mesh.next_in_cell(x) + 3 },
            ]
        })
        .collect();

    let mut edge_vertices = vec![[0u32; 2]; (2 * ne + nh) as usize];
    let mut edge_offsets = vec![0u32; (2 * ne + nh + 1) as usize];
    let mut edge_half_edges = vec![0u32; 4 * nh as usize];
    let (split_vertices, inner_vertices) = edge_vertices.split_at_mut(2 * ne as usize);
    for (e, pair) in split_vertices.chunks_exact_mut(2).enumerate() {
        let [a, b] = mesh.edge_vertices[e];
        let mid = edge_base + e as u32;
        pair.copy_from_slice(&[[a, mid], [mid, b]]);
        let start = mesh.edge_offsets[e];
        let count = mesh.edge_offsets[e + 1] - start;
        edge_offsets[2 * e] = 2 * start;
        edge_offsets[2 * e + 1] = 2 * start + count;
    }
    for (h, pair) in inner_vertices.iter_mut().enumerate() {
        *pair = [edge_base + mesh.he_edge[h], nv + mesh.cell_of(h as u32)];
        edge_offsets[2 * ne as usize + h] = 2 * nh + 2 * h as u32;
    }
    edge_offsets[(2 * ne + nh) as usize] = 4 * nh;
    let (split_lists, inner_lists) = edge_half_edges.split_at_mut(2 * nh as usize);
    for e in 0..ne as usize {
        let [a, b] = mesh.edge_vertices[e];
        let parent = &mesh.edge_half_edges[mesh.edge_range(e)];
        let out = &mut split_lists[2 * mesh.edge_offsets[e] as usize..][..2 * parent.len()];
        let (near_a, near_b) = out.split_at_mut(parent.len());
        for (i, &x) in parent.iter().enumerate() {
            near_a[i] = child_at(x, a);
            // From a vertex to itself: the one half-edge's to-end.
            near_b[i] = if a == b { 4 * mesh.next_in_cell(x) + 3 } else { child_at(x, b) };
        }
    }
    for (h, pair) in inner_lists.chunks_exact_mut(2).enumerate() {
        pair.copy_from_slice(&[4 * h as u32 + 1, 4 * mesh.next_in_cell(h as u32) + 2]);
    }

    let mut vertex_offsets = vec![0u32; (nv + nf + ne + 1) as usize];
    let mut vertex_half_edges = vec![0u32; 4 * nh as usize];
    vertex_offsets[..=nv as usize].copy_from_slice(&mesh.vertex_offsets);
    for c in 0..nf as usize {
        vertex_offsets[nv as usize + c] = nh + mesh.cell_offsets[c];
    }
    for e in 0..ne as usize {
        vertex_offsets[edge_base as usize + e] = 2 * nh + 2 * mesh.edge_offsets[e];
    }
    vertex_offsets[(nv + nf + ne) as usize] = 4 * nh;
    let (old_lists, rest) = vertex_half_edges.split_at_mut(nh as usize);
    let (face_lists, edge_lists) = rest.split_at_mut(nh as usize);
    for (slot, &x) in old_lists.iter_mut().zip(&mesh.vertex_half_edges) {
        *slot = 4 * x;
    }
    for (h, slot) in face_lists.iter_mut().enumerate() {
        *slot = 4 * h as u32 + 2;
    }
    for e in 0..ne as usize {
        let parent = &mesh.edge_half_edges[mesh.edge_range(e)];
        let out = &mut edge_lists[2 * mesh.edge_offsets[e] as usize..][..2 * parent.len()];
        let (along, inward) = out.split_at_mut(parent.len());
        for (i, &x) in parent.iter().enumerate() {
            // Along the split edge first: it is a boundary half-edge when the parent edge was.
            along[i] = 4 * mesh.next_in_cell(x) + 3;
            inward[i] = 4 * x + 1;
        }
    }

    HalfEdgeMesh {
        he_edge: he_edge.into_flattened(),
        he_next_around_edge: he_next_around_edge.into_flattened(),
        edge_vertices,
        edge_offsets,
        edge_half_edges,
        vertex_offsets,
        vertex_half_edges,
        // The halves of a non-manifold edge are non-manifold; inner edges never are.
        non_manifold_edges: mesh.non_manifold_edges,
        multi_fan_vertices: mesh.multi_fan_vertices,
        marked_non_manifold: super::child_marks(mesh, (2 * ne + nh) as usize),
        repeated_corners: false,
        // Every child cell is a quad (none when the parent has no cells): child cell h is
        // 4h..4h + 4, and `cell_of` is a shift.
        ..HalfEdgeMesh::from_cells(
            positions,
            (0..=nh).map(|c| 4 * c).collect(),
            he_from,
            Some(if nh > 0 { 4 } else { 0 }),
        )
    }
}

/// The child level's tags (see [`crate::rules::crease`]): the halves `2e`, `2e + 1` of parent
/// edge `e` get its sharpness decayed at its first and second vertex, inner edges are smooth;
/// old vertices keep their decayed sharpness, new ones are smooth; child cell `h` is a hole when
/// its parent cell is. `child` is [`child_mesh`] of `mesh`.
pub fn child_tags(mesh: &HalfEdgeMesh, child: &HalfEdgeMesh, tags: &LevelTags) -> LevelTags {
    let (nv, nf, ne, nh) =
        (mesh.num_vertices(), mesh.num_cells(), mesh.num_edges(), mesh.num_half_edges());
    let mut edges = vec![0.0f32; 2 * ne + nh];
    for (e, &s) in tags.edges.iter().enumerate() {
        if s > 0.0 {
            let [a, b] = mesh.edge_vertices[e];
            edges[2 * e] = tags.decay_at(s, a);
            edges[2 * e + 1] = tags.decay_at(s, b);
        }
    }
    let mut vertices = vec![0.0f32; nv + nf + ne];
    for (child, &s) in vertices.iter_mut().zip(&tags.vertices) {
        *child = decay(s);
    }
    let holes = if tags.has_holes() {
        (0..nh as u32).map(|h| tags.holes[mesh.cell_of(h) as usize]).collect()
    } else {
        Vec::new()
    };
    let mut non_manifold = Vec::new();
    if !tags.non_manifold.is_empty() {
        non_manifold = Vec::with_capacity(nv + nf + ne);
        non_manifold.extend_from_slice(&tags.non_manifold);
        non_manifold.resize(nv + nf, false);
        non_manifold.extend((0..ne as u32).map(|e| mesh.is_non_manifold_edge(e)));
    }
    LevelTags::new(child, edges, vertices, holes, non_manifold, tags.method, tags.smooth_triangles)
}
