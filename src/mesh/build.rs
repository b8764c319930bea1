//! Building a [`HalfEdgeMesh`] from flat arrays: validation first, then connectivity by counting
//! sorts and per-vertex sorted runs, with no hash map.

use super::HalfEdgeMesh;
use crate::error::{Error, Result};

/// The largest half-edge count a base mesh may have, so that four refinement levels of index
/// arithmetic (`4h + 3`, `2E + h`) still fit in `u32` without checks in the hot loops.
pub(crate) const MAX_HALF_EDGES: usize = (u32::MAX / 8) as usize;

pub(super) fn from_faces(
    positions: &[f32],
    indices: &[u32],
    face_sizes: &[u32],
) -> Result<HalfEdgeMesh> {
    validate(positions, indices, face_sizes)?;
    let num_vertices = positions.len() / 3;
    let num_half_edges = indices.len();

    let mut cell_offsets = Vec::with_capacity(face_sizes.len() + 1);
    let mut he_cell = Vec::with_capacity(num_half_edges);
    let mut he_to = Vec::with_capacity(num_half_edges);
    let mut total = 0usize;
    cell_offsets.push(0);
    for (c, &n) in face_sizes.iter().enumerate() {
        let corners = &indices[total..total + n as usize];
        he_to.extend_from_slice(&corners[1..]);
        he_to.push(corners[0]);
        he_cell.extend(std::iter::repeat_n(c as u32, n as usize));
        total += n as usize;
        cell_offsets.push(total as u32);
    }

    let mut mesh = HalfEdgeMesh {
        positions: positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect(),
        cell_offsets,
        he_from: indices.to_vec(),
        he_cell,
        ..HalfEdgeMesh::default()
    };
    let out_to = build_vertex_half_edges(&mut mesh, &he_to, num_vertices);
    drop(he_to);
    build_edges(&mut mesh, &out_to);
    put_boundary_half_edges_first(&mut mesh);
    mesh.multi_fan_vertices =
        !mesh.non_manifold_edges && (0..mesh.num_vertices() as u32).any(|v| !mesh.is_single_fan(v));
    Ok(mesh)
}

fn validate(positions: &[f32], indices: &[u32], face_sizes: &[u32]) -> Result<()> {
    if !positions.len().is_multiple_of(3) {
        return Err(Error::mesh(format!(
            "positions has {} numbers, which is not a multiple of 3; give x, y, z for every vertex",
            positions.len()
        )));
    }
    if positions.is_empty() {
        return Err(Error::mesh("positions is empty; a mesh needs at least one vertex"));
    }
    if let Some(i) = positions.iter().position(|x| !x.is_finite()) {
        return Err(Error::mesh(format!(
            "vertex {} has coordinate {} = {}; every coordinate must be a finite number",
            i / 3,
            ["x", "y", "z"][i % 3],
            positions[i]
        )));
    }
    let num_vertices = positions.len() / 3;
    if num_vertices > u32::MAX as usize / 4 {
        return Err(Error::mesh(format!(
            "{num_vertices} vertices is more than subsurf can index ({})",
            u32::MAX / 4
        )));
    }
    let sum: u64 = face_sizes.iter().map(|&n| n as u64).sum();
    if sum != indices.len() as u64 {
        return Err(Error::mesh(format!(
            "faceSizes sum to {sum} but indices has {} entries; each face uses faceSizes[f] consecutive indices",
            indices.len()
        )));
    }
    if indices.len() > MAX_HALF_EDGES {
        return Err(Error::mesh(format!(
            "{} face corners is more than subsurf can refine ({MAX_HALF_EDGES})",
            indices.len()
        )));
    }
    // The face in which each vertex was last seen: a linear repeated-vertex check, so that one
    // face with a million corners costs a million steps, not half a trillion.
    let mut last_face = vec![u32::MAX; num_vertices];
    let mut start = 0usize;
    for (f, &n) in face_sizes.iter().enumerate() {
        let n = n as usize;
        if n < 3 {
            return Err(Error::mesh(format!("face {f} has {n} vertices; a face needs at least 3")));
        }
        let face = &indices[start..start + n];
        for (k, &v) in face.iter().enumerate() {
            if v as usize >= num_vertices {
                return Err(Error::mesh(format!(
                    "face {f} (indices[{}]) refers to vertex {v}, but there are only {num_vertices} vertices (0..{})",
                    start + k,
                    num_vertices - 1
                )));
            }
            if std::mem::replace(&mut last_face[v as usize], f as u32) == f as u32 {
                return Err(Error::mesh(format!(
                    "face {f} uses vertex {v} twice; a face must not repeat a vertex"
                )));
            }
        }
        start += n;
    }
    Ok(())
}

/// Fills `vertex_offsets`/`vertex_half_edges` by a counting sort on the from-vertex, each
/// vertex's run sorted by to-vertex so that the half-edges of one vertex pair are adjacent.
/// Returns the to-vertex of every list entry, a parallel array that keeps the edge search
/// below on contiguous memory.
fn build_vertex_half_edges(
    mesh: &mut HalfEdgeMesh,
    he_to: &[u32],
    num_vertices: usize,
) -> Vec<u32> {
    let offsets = bucket_offsets(&mesh.he_from, num_vertices);
    let mut fill = offsets.clone();
    let mut keys = vec![0u64; mesh.he_from.len()];
    for (h, &v) in mesh.he_from.iter().enumerate() {
        keys[fill[v as usize] as usize] = ((he_to[h] as u64) << 32) | h as u64;
        fill[v as usize] += 1;
    }
    drop(fill);
    for v in 0..num_vertices {
        keys[offsets[v] as usize..offsets[v + 1] as usize].sort_unstable();
    }
    mesh.vertex_offsets = offsets;
    mesh.vertex_half_edges = keys.iter().map(|&k| k as u32).collect();
    keys.iter().map(|&k| (k >> 32) as u32).collect()
}

/// For each run of half-edges `a → b` in `a`'s list: the run `b → a` in `b`'s list (as a range
/// of list positions), found by binary search on the parallel to-vertex array.
fn opposite_run(mesh: &HalfEdgeMesh, out_to: &[u32], a: u32, b: u32) -> std::ops::Range<usize> {
    let start = mesh.vertex_offsets[b as usize] as usize;
    let end = mesh.vertex_offsets[b as usize + 1] as usize;
    let tos = &out_to[start..end];
    let first = tos.partition_point(|&t| t < a);
    let len = tos[first..].partition_point(|&t| t == a);
    start + first..start + first + len
}

/// Calls `visit(a, b, run_ab, run_ba)` for every maximal run of half-edges `a → b`, with both
/// runs as ranges into `vertex_half_edges`, when the run holds the edge's lowest half-edge.
/// Each edge is visited exactly once, by the vertex that owns it.
fn for_each_owned_edge(
    mesh: &HalfEdgeMesh,
    out_to: &[u32],
    mut visit: impl FnMut(u32, u32, std::ops::Range<usize>, std::ops::Range<usize>),
) {
    for a in 0..mesh.num_vertices() {
        let end = mesh.vertex_offsets[a + 1] as usize;
        let mut i = mesh.vertex_offsets[a] as usize;
        while i < end {
            let b = out_to[i];
            let run_end = i + out_to[i..end].partition_point(|&t| t == b);
            let opposite = opposite_run(mesh, out_to, a as u32, b);
            let lowest_here = mesh.vertex_half_edges[i];
            let owned = opposite.is_empty() || mesh.vertex_half_edges[opposite.start] > lowest_here;
            if owned {
                visit(a as u32, b, i..run_end, opposite);
            }
            i = run_end;
        }
    }
}

/// Numbers edges in the order their owning vertices are visited (by owner vertex, then by the
/// other vertex) and lists each edge's half-edges in ascending order, so the first is the lowest.
fn build_edges(mesh: &mut HalfEdgeMesh, out_to: &[u32]) {
    let num_half_edges = mesh.he_from.len();
    let mut edge_vertices = Vec::with_capacity(num_half_edges / 2 + 1);
    let mut edge_offsets = Vec::with_capacity(num_half_edges / 2 + 2);
    edge_offsets.push(0u32);
    let mut edge_half_edges = vec![0u32; num_half_edges];
    let mut he_edge = vec![0u32; num_half_edges];
    let mut he_next_around_edge = vec![0u32; num_half_edges];
    let mut filled = 0usize;
    let mut non_manifold = false;
    for_each_owned_edge(mesh, out_to, |a, b, run, opposite| {
        // Two half-edges the same way, or more than two in all (then one run has two or more).
        non_manifold |= run.len() > 1 || opposite.len() > 1;
        let e = edge_vertices.len() as u32;
        edge_vertices.push([a, b]);
        let list = &mut edge_half_edges[filled..filled + run.len() + opposite.len()];
        filled += list.len();
        edge_offsets.push(filled as u32);
        merge_sorted(&mesh.vertex_half_edges[run], &mesh.vertex_half_edges[opposite], list);
        for (i, &h) in list.iter().enumerate() {
            he_edge[h as usize] = e;
            he_next_around_edge[h as usize] = list[(i + 1) % list.len()];
        }
    });
    mesh.he_edge = he_edge;
    mesh.he_next_around_edge = he_next_around_edge;
    mesh.edge_vertices = edge_vertices;
    mesh.edge_offsets = edge_offsets;
    mesh.edge_half_edges = edge_half_edges;
    mesh.non_manifold_edges = non_manifold;
}

fn merge_sorted(a: &[u32], b: &[u32], out: &mut [u32]) {
    let (mut i, mut j) = (0, 0);
    for slot in out.iter_mut() {
        if j >= b.len() || (i < a.len() && a[i] < b[j]) {
            *slot = a[i];
            i += 1;
        } else {
            *slot = b[j];
            j += 1;
        }
    }
}

/// The seed's contract: `kth_half_edge_from(0)` is a boundary half-edge when the vertex has one.
fn put_boundary_half_edges_first(mesh: &mut HalfEdgeMesh) {
    for v in 0..mesh.num_vertices() {
        let start = mesh.vertex_offsets[v] as usize;
        let end = mesh.vertex_offsets[v + 1] as usize;
        let boundary = (start..end).find(|&i| {
            let h = mesh.vertex_half_edges[i] as usize;
            mesh.he_next_around_edge[h] == h as u32
        });
        if let Some(i) = boundary {
            mesh.vertex_half_edges.swap(start, i);
        }
    }
}

/// Builds a mesh whose edges are already known: `he_edge[h]` is the edge of half-edge `h`
/// (`0..num_edges`, every edge used). A refinement host that derives its child edges by index
/// arithmetic uses this instead of [`from_faces`], which would merge two child edges that happen
/// to join the same two vertices (as OpenSubdiv keeps them apart). Only counting sorts: each
/// edge lists its half-edges in ascending order, each vertex its outgoing ones, a boundary one
/// first. The input must describe valid cells (at least 3 distinct vertices each).
pub(crate) fn from_cells_and_edges(
    positions: Vec<[f32; 3]>,
    cell_offsets: Vec<u32>,
    he_from: Vec<u32>,
    he_edge: Vec<u32>,
    num_edges: usize,
) -> HalfEdgeMesh {
    let nh = he_from.len();
    let mut he_cell = vec![0u32; nh];
    for (c, range) in cell_offsets.windows(2).enumerate() {
        he_cell[range[0] as usize..range[1] as usize].fill(c as u32);
    }
    let mut mesh = HalfEdgeMesh { positions, cell_offsets, he_from, he_cell, ..Default::default() };

    let (edge_offsets, edge_half_edges) = counting_sort(&he_edge, num_edges);
    let mut he_next_around_edge = vec![0u32; nh];
    let mut edge_vertices = vec![[0u32; 2]; num_edges];
    let mut non_manifold = false;
    for e in 0..num_edges {
        let list = &edge_half_edges[edge_offsets[e] as usize..edge_offsets[e + 1] as usize];
        for (i, &h) in list.iter().enumerate() {
            he_next_around_edge[h as usize] = list[(i + 1) % list.len()];
        }
        let first = list[0];
        edge_vertices[e] = [mesh.he_from[first as usize], mesh.to_vertex(first)];
        non_manifold |= list.len() > 2
            || (list.len() == 2
                && mesh.he_from[list[0] as usize] == mesh.he_from[list[1] as usize]);
    }
    mesh.he_edge = he_edge;
    mesh.he_next_around_edge = he_next_around_edge;
    mesh.edge_vertices = edge_vertices;
    mesh.edge_offsets = edge_offsets;
    mesh.edge_half_edges = edge_half_edges;
    mesh.non_manifold_edges = non_manifold;

    let num_vertices = mesh.positions.len();
    let (vertex_offsets, vertex_half_edges) = counting_sort(&mesh.he_from, num_vertices);
    mesh.vertex_offsets = vertex_offsets;
    mesh.vertex_half_edges = vertex_half_edges;
    put_boundary_half_edges_first(&mut mesh);
    mesh
}

/// Offsets of a counting sort: `offsets[k]..offsets[k + 1]` is where the items whose key is `k`
/// go; every key must be below `buckets`.
fn bucket_offsets(keys: &[u32], buckets: usize) -> Vec<u32> {
    let mut offsets = vec![0u32; buckets + 1];
    for &k in keys {
        offsets[k as usize + 1] += 1;
    }
    for k in 0..buckets {
        offsets[k + 1] += offsets[k];
    }
    offsets
}

/// A stable counting sort of the item indices `0..keys.len()` by key: the offsets and the
/// sorted indices (each bucket in ascending order).
fn counting_sort(keys: &[u32], buckets: usize) -> (Vec<u32>, Vec<u32>) {
    let offsets = bucket_offsets(keys, buckets);
    let mut fill = offsets.clone();
    let mut sorted = vec![0u32; keys.len()];
    for (i, &k) in keys.iter().enumerate() {
        sorted[fill[k as usize] as usize] = i as u32;
        fill[k as usize] += 1;
    }
    (offsets, sorted)
}
