//! Building a [`HalfEdgeMesh`] from flat arrays: validation first, then connectivity by counting
//! sorts and per-vertex sorted runs, with no hash map.

use super::HalfEdgeMesh;
use crate::error::{Error, Result};

/// The largest half-edge count a base mesh may have, so that four refinement levels of index
/// arithmetic (`4h + 3`, `2E + h`) still fit in `u32` without checks in the hot loops.
pub(crate) const MAX_HALF_EDGES: usize = (u32::MAX / 8) as usize;

pub(super) fn from_faces(positions: &[f32], indices: &[u32], face_sizes: &[u32]) -> Result<HalfEdgeMesh> {
    validate(positions, indices, face_sizes)?;
    let num_vertices = positions.len() / 3;
    let num_half_edges = indices.len();

    let mut cell_offsets = Vec::with_capacity(face_sizes.len() + 1);
    let mut he_cell = Vec::with_capacity(num_half_edges);
    let mut total = 0u32;
    cell_offsets.push(0);
    for (c, &n) in face_sizes.iter().enumerate() {
        total += n;
        cell_offsets.push(total);
        he_cell.extend(std::iter::repeat_n(c as u32, n as usize));
    }

    let mut mesh = HalfEdgeMesh {
        positions: positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect(),
        cell_offsets,
        he_from: indices.to_vec(),
        he_cell,
        ..HalfEdgeMesh::default()
    };
    let he_to: Vec<u32> = (0..num_half_edges as u32).map(|h| mesh.to_vertex(h)).collect();
    build_vertex_half_edges(&mut mesh, &he_to, num_vertices);
    build_edges(&mut mesh, &he_to);
    put_boundary_half_edges_first(&mut mesh);
    Ok(mesh)
}

fn validate(positions: &[f32], indices: &[u32], face_sizes: &[u32]) -> Result<()> {
    if positions.len() % 3 != 0 {
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
    let mut start = 0usize;
    for (f, &n) in face_sizes.iter().enumerate() {
        let n = n as usize;
        if n < 3 {
            return Err(Error::mesh(format!(
                "face {f} has {n} vertices; a face needs at least 3"
            )));
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
            if face[..k].contains(&v) {
                return Err(Error::mesh(format!(
                    "face {f} uses vertex {v} twice; a face must not repeat a vertex"
                )));
            }
        }
        start += n;
    }
    Ok(())
}

/// Fills `vertex_offsets`/`vertex_half_edges` by a counting sort on the from-vertex, then sorts
/// each vertex's run by to-vertex so that the half-edges of one vertex pair are adjacent.
fn build_vertex_half_edges(mesh: &mut HalfEdgeMesh, he_to: &[u32], num_vertices: usize) {
    let mut offsets = vec![0u32; num_vertices + 1];
    for &v in &mesh.he_from {
        offsets[v as usize + 1] += 1;
    }
    for v in 0..num_vertices {
        offsets[v + 1] += offsets[v];
    }
    let mut fill = offsets.clone();
    let mut list = vec![0u32; mesh.he_from.len()];
    for (h, &v) in mesh.he_from.iter().enumerate() {
        list[fill[v as usize] as usize] = h as u32;
        fill[v as usize] += 1;
    }
    for v in 0..num_vertices {
        let run = &mut list[offsets[v] as usize..offsets[v + 1] as usize];
        run.sort_unstable_by_key(|&h| ((he_to[h as usize] as u64) << 32) | h as u64);
    }
    mesh.vertex_offsets = offsets;
    mesh.vertex_half_edges = list;
}

/// The half-edges from `a` to `b`, a contiguous run of `a`'s to-sorted list.
fn run_to<'a>(mesh: &'a HalfEdgeMesh, he_to: &[u32], a: u32, b: u32) -> &'a [u32] {
    let out = mesh.out_half_edges(a);
    let start = out.partition_point(|&h| he_to[h as usize] < b);
    let len = out[start..].partition_point(|&h| he_to[h as usize] == b);
    &out[start..start + len]
}

/// Numbers edges in order of their lowest half-edge and lists each edge's half-edges in
/// ascending order, so the first is the lowest.
fn build_edges(mesh: &mut HalfEdgeMesh, he_to: &[u32]) {
    let num_half_edges = mesh.he_from.len();
    // Pass 1: each half-edge finds the lowest half-edge on its vertex pair (the edge's owner).
    let mut owner = vec![0u32; num_half_edges];
    for (h, slot) in owner.iter_mut().enumerate() {
        let (a, b) = (mesh.he_from[h], he_to[h]);
        // The forward run contains `h` itself, so it is never empty.
        let forward = run_to(mesh, he_to, a, b)[0];
        let backward = run_to(mesh, he_to, b, a).first().copied().unwrap_or(u32::MAX);
        *slot = forward.min(backward);
    }
    // Pass 2: edge ids in owner order.
    let mut edge_of_owner = vec![u32::MAX; num_half_edges];
    let mut edge_vertices = Vec::new();
    for h in 0..num_half_edges {
        if owner[h] == h as u32 {
            edge_of_owner[h] = edge_vertices.len() as u32;
            edge_vertices.push([mesh.he_from[h], he_to[h]]);
        }
    }
    let num_edges = edge_vertices.len();
    let he_edge: Vec<u32> = owner.iter().map(|&o| edge_of_owner[o as usize]).collect();
    drop(edge_of_owner);
    drop(owner);

    // Pass 3: edge -> half-edges, a stable counting sort keeping ascending half-edge order.
    let mut offsets = vec![0u32; num_edges + 1];
    for &e in &he_edge {
        offsets[e as usize + 1] += 1;
    }
    for e in 0..num_edges {
        offsets[e + 1] += offsets[e];
    }
    let mut fill = offsets.clone();
    let mut list = vec![0u32; num_half_edges];
    for (h, &e) in he_edge.iter().enumerate() {
        list[fill[e as usize] as usize] = h as u32;
        fill[e as usize] += 1;
    }
    let mut next_around = vec![0u32; num_half_edges];
    for e in 0..num_edges {
        let run = &list[offsets[e] as usize..offsets[e + 1] as usize];
        for (i, &h) in run.iter().enumerate() {
            next_around[h as usize] = run[(i + 1) % run.len()];
        }
    }
    mesh.he_edge = he_edge;
    mesh.he_next_around_edge = next_around;
    mesh.edge_vertices = edge_vertices;
    mesh.edge_offsets = offsets;
    mesh.edge_half_edges = list;
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
