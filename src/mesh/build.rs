//! Building a [`HalfEdgeMesh`] from flat arrays: validation first, then connectivity by a counting
//! sort on the from-vertex and valence-sized scans, with no hash map and no comparison sort.

use super::{uniform_cell_size, HalfEdgeMesh};
use crate::error::{Error, Result};

/// The largest half-edge count a base mesh may have, so that four refinement levels of index
/// arithmetic (`4h + 3`, `2E + h`) still fit in `u32` without checks in the hot loops.
pub(crate) const MAX_HALF_EDGES: usize = (u32::MAX / 8) as usize;

pub(super) fn from_faces(
    positions: &[f32],
    indices: &[u32],
    face_sizes: &[u32],
) -> Result<HalfEdgeMesh> {
    let repeated_corners = validate(positions, indices, face_sizes)?;
    let positions = positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
    Ok(connect(positions, indices.to_vec(), face_sizes, repeated_corners))
}

/// [`from_faces`] taking the arrays it keeps: no copy of the positions or the index list.
pub(super) fn from_vertices(
    positions: Vec<[f32; 3]>,
    indices: Vec<u32>,
    face_sizes: &[u32],
) -> Result<HalfEdgeMesh> {
    let repeated_corners = validate(positions.as_flattened(), &indices, face_sizes)?;
    Ok(connect(positions, indices, face_sizes, repeated_corners))
}

/// The connectivity of valid cells; `repeated_corners` says whether some cell lists a vertex
/// more than once (only then are edges split as the module docs of [`super`] say).
fn connect(
    positions: Vec<[f32; 3]>,
    indices: Vec<u32>,
    face_sizes: &[u32],
    repeated_corners: bool,
) -> HalfEdgeMesh {
    let num_vertices = positions.len();

    let mut cell_offsets = Vec::with_capacity(face_sizes.len() + 1);
    cell_offsets.push(0u32);
    let mut total = 0u32;
    cell_offsets.extend(face_sizes.iter().map(|&n| {
        total += n;
        total
    }));
    let cell_size = uniform_cell_size(&cell_offsets);
    let he_to = match cell_size {
        3 => uniform_to_vertices::<3>(&indices),
        4 => uniform_to_vertices::<4>(&indices),
        _ => mixed_to_vertices(&indices, &cell_offsets),
    };
    // The to-vertex of each outgoing-list entry too, so that the edge scans read one array.
    let (vertex_offsets, vertex_half_edges, out_to) =
        counting_sort_with(&indices, num_vertices, &he_to);
    let mut mesh = HalfEdgeMesh::from_cells(positions, cell_offsets, indices, Some(cell_size));
    mesh.repeated_corners = repeated_corners;
    mesh.vertex_offsets = vertex_offsets;
    mesh.vertex_half_edges = vertex_half_edges;
    let has_boundary = build_edges(&mut mesh, &he_to, &out_to);
    drop((he_to, out_to));
    if has_boundary {
        put_boundary_half_edges_first(&mut mesh);
    }
    mesh.multi_fan_vertices =
        !mesh.non_manifold_edges && (0..mesh.num_vertices() as u32).any(|v| !mesh.is_single_fan(v));
    mesh
}

/// The to-vertex of every half-edge when every cell has `N` corners: each cell's corners rotated
/// by one, collected in place.
fn uniform_to_vertices<const N: usize>(indices: &[u32]) -> Vec<u32> {
    let cells = indices.as_chunks::<N>().0.iter();
    // `from_fn` on a constant N unrolls; `rotate_left` would be a call per cell.
    let to: Vec<[u32; N]> =
        cells.map(|corners| std::array::from_fn(|k| corners[(k + 1) % N])).collect();
    to.into_flattened()
}

/// The to-vertex of every half-edge, for cells of any sizes. Each half-edge ends where the next
/// one of its cell starts: the list shifted by one, with the last corner of every cell wrapping
/// round to its first.
fn mixed_to_vertices(indices: &[u32], cell_offsets: &[u32]) -> Vec<u32> {
    let mut he_to = vec![0u32; indices.len()];
    if let Some(last) = indices.len().checked_sub(1) {
        he_to[..last].copy_from_slice(&indices[1..]);
    }
    for range in cell_offsets.windows(2) {
        he_to[range[1] as usize - 1] = indices[range[0] as usize];
    }
    he_to
}

/// Refuses a NaN, infinite or too large coordinate ([`super::MAX_COORDINATE`]), naming the
/// first.
pub(crate) fn check_usable(positions: &[f32]) -> Result<()> {
    let Some(i) = super::first_unusable(positions) else { return Ok(()) };
    Err(Error::mesh(format!(
        "vertex {} has coordinate {} = {}; {}",
        i / 3,
        ["x", "y", "z"][i % 3],
        positions[i],
        super::unusable_because(positions[i], "coordinate")
    )))
}

/// Checks the flat arrays; returns whether some face repeats a vertex (valid input: OpenSubdiv
/// accepts such faces, see the module docs of [`super`]).
fn validate(positions: &[f32], indices: &[u32], face_sizes: &[u32]) -> Result<bool> {
    if !positions.len().is_multiple_of(3) {
        return Err(positions_not_in_threes(positions.len()));
    }
    if positions.is_empty() {
        return Err(Error::mesh("positions is empty; a mesh needs at least one vertex"));
    }
    // Whole-array checks that vectorise (no early exit) come first; only a failure pays for
    // finding the culprit.
    check_usable(positions)?;
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
    if indices.iter().fold(0, |m, &v| m.max(v)) < num_vertices as u32
        && uniform_faces_have_distinct_corners(indices, face_sizes)
    {
        return Ok(false);
    }
    // Face by face, reporting the first face at fault, and noting whether a face repeats a
    // vertex (see [`repeated_corner`]).
    let mut last_face = Vec::new();
    let mut repeats = false;
    let mut start = 0usize;
    for (f, &n) in face_sizes.iter().enumerate() {
        let n = n as usize;
        if n < 3 {
            return Err(Error::mesh(format!("face {f} has {n} vertices; a face needs at least 3")));
        }
        let face = &indices[start..start + n];
        if let Some(k) = face.iter().position(|&v| v as usize >= num_vertices) {
            return Err(Error::mesh(format!(
                "face {f} (indices[{}]) refers to vertex {}, but there are only {num_vertices} vertices (0..{})",
                start + k,
                face[k],
                num_vertices - 1
            )));
        }
        if !repeats {
            repeats = repeated_corner(face, f as u32, num_vertices, &mut last_face).is_some();
        }
        start += n;
    }
    Ok(repeats)
}

/// The first vertex that `face` (face number `f`, every index below `num_vertices`) lists a
/// second time. Pairwise within a small face (no memory traffic); for larger faces through
/// `last_face`, the face in which each vertex was last seen (allocated on first use, shared by
/// the calls for one mesh, faces in ascending order), so that one face with a million corners
/// costs a million steps, not half a trillion.
pub(crate) fn repeated_corner(
    face: &[u32],
    f: u32,
    num_vertices: usize,
    last_face: &mut Vec<u32>,
) -> Option<u32> {
    const PAIRWISE: usize = 8;
    if face.len() <= PAIRWISE {
        return (1..face.len()).find_map(|k| face[..k].contains(&face[k]).then_some(face[k]));
    }
    if last_face.is_empty() {
        *last_face = vec![u32::MAX; num_vertices];
    }
    face.iter().copied().find(|&v| std::mem::replace(&mut last_face[v as usize], f) == f)
}

/// The error for a position array whose length is not a multiple of 3.
pub(crate) fn positions_not_in_threes(len: usize) -> Error {
    Error::mesh(format!(
        "positions has {len} numbers, which is not a multiple of 3; give x, y, z for every vertex"
    ))
}

/// True for an all-triangle or all-quad mesh whose faces never repeat a vertex; false for
/// anything else, which the face-by-face check then examines.
fn uniform_faces_have_distinct_corners(indices: &[u32], face_sizes: &[u32]) -> bool {
    // Branch-free folds, so that valid input (the common case) runs vectorised.
    let all_sized = |n: u32| face_sizes.iter().fold(true, |ok, &s| ok & (s == n));
    if indices.len() == 4 * face_sizes.len() && all_sized(4) {
        let quads = indices.as_chunks::<4>().0.iter();
        return quads.fold(true, |ok, &[a, b, c, d]| {
            ok & (a != b) & (a != c) & (a != d) & (b != c) & (b != d) & (c != d)
        });
    }
    if indices.len() == 3 * face_sizes.len() && all_sized(3) {
        let triangles = indices.as_chunks::<3>().0.iter();
        return triangles.fold(true, |ok, &[a, b, c]| ok & (a != b) & (a != c) & (b != c));
    }
    false
}

/// The edge arrays of a mesh, as [`build_edges`] makes them.
struct Edges {
    he_edge: Vec<u32>,
    he_next_around_edge: Vec<u32>,
    edge_vertices: Vec<[u32; 2]>,
    edge_offsets: Vec<u32>,
    edge_half_edges: Vec<u32>,
    /// [`HalfEdgeMesh::marked_non_manifold`]: empty unless some edge is marked.
    marked: Vec<bool>,
    non_manifold: bool,
    boundary: bool,
}

impl Edges {
    /// Ends edge `e`, whose half-edges are those listed from `start`: links them around the
    /// edge, notes a boundary or non-manifold edge (`marked`: known non-manifold already).
    fn close_edge(&mut self, mesh: &HalfEdgeMesh, e: u32, start: usize, marked: bool) {
        let list = &self.edge_half_edges[start..];
        self.non_manifold |= marked
            || list.len() > 2
            || (list.len() == 2
                && mesh.he_from[list[0] as usize] == mesh.he_from[list[1] as usize]);
        self.boundary |= list.len() == 1;
        for (i, &g) in list.iter().enumerate() {
            self.he_edge[g as usize] = e;
            self.he_next_around_edge[g as usize] = list[(i + 1) % list.len()];
        }
        self.edge_offsets.push(self.edge_half_edges.len() as u32);
    }

    fn with_capacity(num_half_edges: usize) -> Self {
        let mut edge_offsets = Vec::with_capacity(num_half_edges / 2 + 2);
        edge_offsets.push(0);
        Edges {
            he_edge: vec![u32::MAX; num_half_edges],
            he_next_around_edge: vec![0; num_half_edges],
            edge_vertices: Vec::with_capacity(num_half_edges / 2 + 1),
            edge_offsets,
            edge_half_edges: Vec::with_capacity(num_half_edges),
            marked: Vec::new(),
            non_manifold: false,
            boundary: false,
        }
    }
}

/// Numbers the edges in the order of their lowest half-edge (the order in which a walk over the
/// faces first meets them), lists each edge's half-edges in ascending order and links them into
/// the cycle around the edge. Each edge is found from its lowest half-edge `h = a → b` by
/// scanning the outgoing lists of `b` (and `a`) for the other half-edges between the two
/// vertices; every later half-edge of the edge is then already numbered and skipped. Returns
/// whether any edge is a boundary edge.
fn build_edges(mesh: &mut HalfEdgeMesh, he_to: &[u32], out_to: &[u32]) -> bool {
    let long = LongLists::new(mesh, out_to);
    let edges = if long.starts.is_empty() {
        edges_of(&Outgoing::<false> { mesh, out_to, long: &long }, he_to)
    } else {
        edges_of(&Outgoing::<true> { mesh, out_to, long: &long }, he_to)
    };
    mesh.marked_non_manifold = edges.marked;
    mesh.he_edge = edges.he_edge;
    mesh.he_next_around_edge = edges.he_next_around_edge;
    mesh.edge_vertices = edges.edge_vertices;
    mesh.edge_offsets = edges.edge_offsets;
    mesh.edge_half_edges = edges.edge_half_edges;
    mesh.non_manifold_edges = edges.non_manifold;
    edges.boundary
}

/// The edges, by the path that fits the mesh.
fn edges_of<const SEARCH: bool>(outgoing: &Outgoing<'_, SEARCH>, he_to: &[u32]) -> Edges {
    let mesh = outgoing.mesh;
    if mesh.repeated_corners {
        edges_of_repeating_cells(mesh, he_to, outgoing)
    } else {
        manifold_edges(mesh, he_to, outgoing)
            .unwrap_or_else(|| general_edges(mesh, he_to, outgoing))
    }
}

/// The outgoing half-edges of each vertex by to-vertex, for finding the half-edges between two
/// vertices. A short outgoing list is scanned; a long one (the hub of a fan, with a valence in
/// the thousands) is searched in a copy sorted by to-vertex, since scanning it once for each of
/// its edges would make a hub of valence `n` cost `n²` steps (a 100k-triangle fan took 3 s).
/// `SEARCH` says whether there are long lists: without, the edge scans compile as plain scans
/// (with the test for a long list in them, the common case took 8 % longer).
struct Outgoing<'a, const SEARCH: bool> {
    mesh: &'a HalfEdgeMesh,
    /// The to-vertex of each outgoing-list entry, parallel to the mesh's outgoing lists.
    out_to: &'a [u32],
    long: &'a LongLists,
}

/// The outgoing lists longer than [`LongLists::LONG`], each sorted by to-vertex (and, within
/// one to-vertex, ascending as the list was): for each, in order of vertex, its vertex and
/// where its entries start in `to` / `out`.
#[derive(Default)]
struct LongLists {
    starts: Vec<(u32, u32)>,
    to: Vec<u32>,
    out: Vec<u32>,
}

impl LongLists {
    /// Lists longer than this are sorted: above it, a binary search beats the scan.
    const LONG: u32 = 64;

    fn new(mesh: &HalfEdgeMesh, out_to: &[u32]) -> Self {
        let mut long = LongLists::default();
        let offsets = &mesh.vertex_offsets;
        // A fold that vectorises first: almost every mesh has no long list.
        let ends = offsets.iter().skip(1);
        if ends.zip(offsets).fold(0, |m, (&end, &start)| m.max(end - start)) <= Self::LONG {
            return long;
        }
        for (v, range) in offsets.windows(2).enumerate() {
            if range[1] - range[0] <= Self::LONG {
                continue;
            }
            let range = range[0] as usize..range[1] as usize;
            let mut pairs: Vec<(u32, u32)> = out_to[range.clone()]
                .iter()
                .copied()
                .zip(mesh.vertex_half_edges[range].iter().copied())
                .collect();
            pairs.sort_unstable();
            long.starts.push((v as u32, long.to.len() as u32));
            long.to.extend(pairs.iter().map(|p| p.0));
            long.out.extend(pairs.iter().map(|p| p.1));
        }
        long
    }

    /// The entries of long list `a` (`len` of them) that go to `b`: to-vertices and half-edges.
    #[cold]
    fn between(&self, a: u32, b: u32, len: usize) -> (&[u32], &[u32]) {
        let k = self.starts.partition_point(|&(v, _)| v < a);
        let first = self.starts[k].1 as usize;
        let to = &self.to[first..first + len];
        let lo = to.partition_point(|&t| t < b);
        let hi = lo + to[lo..].partition_point(|&t| t == b);
        (&self.to[first + lo..first + hi], &self.out[first + lo..first + hi])
    }
}

impl<const SEARCH: bool> Outgoing<'_, SEARCH> {
    /// Outgoing half-edges of `a` with their to-vertices, among which are all those to `b`, in
    /// ascending order: `a`'s whole list when it is short.
    #[inline(always)]
    fn candidates(&self, a: u32, b: u32) -> impl Iterator<Item = (u32, u32)> + '_ {
        let offsets = &self.mesh.vertex_offsets;
        let (start, end) = (offsets[a as usize] as usize, offsets[a as usize + 1] as usize);
        let (to, out) = if SEARCH && end - start > LongLists::LONG as usize {
            self.long.between(a, b, end - start)
        } else {
            (&self.out_to[start..end], &self.mesh.vertex_half_edges[start..end])
        };
        to.iter().copied().zip(out.iter().copied())
    }

    /// The half-edges from `a` to `b`, ascending.
    fn between(&self, a: u32, b: u32) -> impl Iterator<Item = u32> + '_ {
        self.candidates(a, b).filter(move |&(t, _)| t == b).map(|(_, h)| h)
    }
}

/// The common case, where every edge has one half-edge or two running opposite ways: one scan
/// of `b`'s outgoing list finds the twin of `a → b`. `None` at the first sign of a non-manifold
/// edge (a second twin, a twin already taken, two boundary half-edges the same way), for
/// [`general_edges`] to number the same edges again.
fn manifold_edges<const SEARCH: bool>(
    mesh: &HalfEdgeMesh,
    he_to: &[u32],
    outgoing: &Outgoing<'_, SEARCH>,
) -> Option<Edges> {
    let mut edges = Edges::with_capacity(he_to.len());
    for (h, (&a, &b)) in mesh.he_from.iter().zip(he_to).enumerate() {
        if edges.he_edge[h] != u32::MAX {
            continue;
        }
        let h = h as u32;
        let e = edges.edge_vertices.len() as u32;
        edges.edge_vertices.push([a, b]);
        edges.he_edge[h as usize] = e;
        edges.edge_half_edges.push(h);
        let mut twin = None;
        for (to, g) in outgoing.candidates(b, a) {
            if to == a {
                if twin.is_some() {
                    return None;
                }
                twin = Some(g);
            }
        }
        match twin {
            Some(g) => {
                // A lower twin would have numbered `h` already; a numbered one is shared.
                if g < h || edges.he_edge[g as usize] != u32::MAX {
                    return None;
                }
                edges.he_edge[g as usize] = e;
                edges.he_next_around_edge[h as usize] = g;
                edges.he_next_around_edge[g as usize] = h;
                edges.edge_half_edges.push(g);
            }
            None => {
                if outgoing.between(a, b).nth(1).is_some() {
                    return None;
                }
                edges.he_next_around_edge[h as usize] = h;
                edges.boundary = true;
            }
        }
        edges.edge_offsets.push(edges.edge_half_edges.len() as u32);
    }
    Some(edges)
}

/// Any edge: all half-edges `a → b` from `a`'s list, then all `b → a` from `b`'s.
fn general_edges<const SEARCH: bool>(
    mesh: &HalfEdgeMesh,
    he_to: &[u32],
    outgoing: &Outgoing<'_, SEARCH>,
) -> Edges {
    let mut edges = Edges::with_capacity(he_to.len());
    for (h, (&a, &b)) in mesh.he_from.iter().zip(he_to).enumerate() {
        if edges.he_edge[h] != u32::MAX {
            continue;
        }
        let e = edges.edge_vertices.len() as u32;
        edges.edge_vertices.push([a, b]);
        let start = edges.edge_half_edges.len();
        // The counting sort left each outgoing list ascending, so `h` (the lowest) comes first.
        for (from, to) in [(a, b), (b, a)] {
            edges.edge_half_edges.extend(outgoing.between(from, to));
        }
        edges.edge_half_edges[start..].sort_unstable();
        edges.close_edge(mesh, e, start, false);
    }
    edges
}

/// The edges of a mesh in which some cell repeats a vertex, split as OpenSubdiv's `Vtr` splits
/// them (see the module docs of [`super`]) and numbered as the other paths number theirs, in the
/// order of their lowest half-edge. Each half-edge from a vertex to itself is an edge of its own;
/// of the half-edges on one vertex pair, the first of each cell share an edge, and each later
/// one of a cell gets an edge of its own when the walk reaches it. Those edges, and the shared
/// edge of a pair that some cell uses twice, are marked non-manifold.
fn edges_of_repeating_cells<const SEARCH: bool>(
    mesh: &HalfEdgeMesh,
    he_to: &[u32],
    outgoing: &Outgoing<'_, SEARCH>,
) -> Edges {
    /// Not numbered yet, and to get an edge of its own: a later use of a pair in one cell.
    const OWN_EDGE: u32 = u32::MAX - 1;
    let mut edges = Edges::with_capacity(he_to.len());
    let mut marked = Vec::with_capacity(he_to.len() / 2 + 1);
    let mut pair = Vec::new();
    for (h, (&a, &b)) in mesh.he_from.iter().zip(he_to).enumerate() {
        let state = edges.he_edge[h];
        if state != u32::MAX && state != OWN_EDGE {
            continue;
        }
        let e = edges.edge_vertices.len() as u32;
        edges.edge_vertices.push([a, b]);
        let start = edges.edge_half_edges.len();
        if a == b || state == OWN_EDGE {
            edges.edge_half_edges.push(h as u32);
            marked.push(true);
        } else {
            // Every half-edge between a and b; the counting sort left each outgoing list
            // ascending, so `h` (the lowest) comes first.
            pair.clear();
            for (from, to) in [(a, b), (b, a)] {
                pair.extend(outgoing.between(from, to));
            }
            pair.sort_unstable();
            // A cell's half-edges are contiguous, so its uses of the pair are neighbours here.
            let mut last_cell = u32::MAX;
            let mut split = false;
            for &g in &pair {
                let c = mesh.cell_of(g);
                if c == last_cell {
                    edges.he_edge[g as usize] = OWN_EDGE;
                    split = true;
                } else {
                    last_cell = c;
                    edges.edge_half_edges.push(g);
                }
            }
            marked.push(split);
        }
        edges.close_edge(mesh, e, start, marked[e as usize]);
    }
    if marked.contains(&true) {
        edges.marked = marked;
    }
    edges
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
/// first. The input must describe valid cells (at least 3 distinct vertices each, no two
/// half-edges of a cell on one edge). `marked_non_manifold` is
/// [`HalfEdgeMesh::marked_non_manifold`] (empty, or one flag per edge).
pub(crate) fn from_cells_and_edges(
    positions: Vec<[f32; 3]>,
    cell_offsets: Vec<u32>,
    he_from: Vec<u32>,
    he_edge: Vec<u32>,
    num_edges: usize,
    marked_non_manifold: Vec<bool>,
) -> HalfEdgeMesh {
    let nh = he_from.len();
    let mut mesh = HalfEdgeMesh::from_cells(positions, cell_offsets, he_from, None);

    let (edge_offsets, edge_half_edges) = counting_sort(&he_edge, num_edges);
    let mut he_next_around_edge = vec![0u32; nh];
    let mut edge_vertices = vec![[0u32; 2]; num_edges];
    let mut non_manifold = !marked_non_manifold.is_empty();
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
    mesh.marked_non_manifold = marked_non_manifold;

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

/// [`counting_sort`], also carrying `payload[i]` along with each item `i`.
fn counting_sort_with(
    keys: &[u32],
    buckets: usize,
    payload: &[u32],
) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    let offsets = bucket_offsets(keys, buckets);
    let mut fill = offsets.clone();
    let mut sorted = vec![0u32; keys.len()];
    let mut carried = vec![0u32; keys.len()];
    for (i, (&k, &p)) in keys.iter().zip(payload).enumerate() {
        let slot = fill[k as usize] as usize;
        sorted[slot] = i as u32;
        carried[slot] = p;
        fill[k as usize] += 1;
    }
    (offsets, sorted, carried)
}

#[cfg(test)]
mod tests {
    use super::{from_faces, LongLists, Outgoing};

    fn error(indices: &[u32], sizes: &[u32]) -> String {
        let positions = vec![0.0; 3 * 12];
        from_faces(&positions, indices, sizes).err().map(|e| e.to_string()).unwrap_or_default()
    }

    /// True when the mesh of these faces (over 12 vertices) has a cell that repeats a vertex.
    fn repeats(indices: &[u32], sizes: &[u32]) -> bool {
        let positions = vec![0.0; 3 * 12];
        from_faces(&positions, indices, sizes).is_ok_and(|m| m.repeated_corners)
    }

    /// Faces up to eight corners are checked pairwise, larger ones with the last-seen array;
    /// both must find the repeat, and neither may mistake a vertex shared by two faces for one.
    #[test]
    fn repeated_vertices_are_found_in_small_and_large_faces() {
        let ten: Vec<u32> = (0..10).collect();
        let mut twice = ten.clone();
        twice[7] = 3;
        assert!(repeats(&[ten.clone(), twice].concat(), &[10, 10]));
        assert!(repeats(&[0, 1, 2, 3, 4, 5, 6, 2], &[8]));
        let mut reversed = ten.clone();
        reversed.reverse();
        let shared = [ten, reversed, vec![0, 1, 2, 3, 4, 5, 6, 7]].concat();
        assert_eq!(error(&shared, &[10, 10, 8]), "");
        assert!(!repeats(&shared, &[10, 10, 8]));
    }

    /// All-quad and all-triangle meshes take the whole-array checks first; a fault in any corner
    /// position must still reach the face-by-face report, naming the first faulty face, and a
    /// repeated vertex in any corner must still be noticed.
    #[test]
    fn uniform_meshes_report_every_fault() {
        let quads = [0, 1, 2, 3, 4, 5, 6, 7];
        assert_eq!(error(&quads, &[4, 4]), "");
        assert!(!repeats(&quads, &[4, 4]));
        for k in 4..8 {
            let mut repeated = quads;
            repeated[k] = quads[4 + (k + 1) % 4];
            assert!(repeats(&repeated, &[4, 4]), "corner {k}");
            let mut outside = quads;
            outside[k] = 12;
            assert!(error(&outside, &[4, 4]).contains("face 1 (indices["), "corner {k}");
        }
        let triangles = [0, 1, 2, 3, 4, 5];
        assert_eq!(error(&triangles, &[3, 3]), "");
        assert!(!repeats(&triangles, &[3, 3]));
        for k in 3..6 {
            let mut repeated = triangles;
            repeated[k] = triangles[3 + (k + 1) % 3];
            assert!(repeats(&repeated, &[3, 3]), "corner {k}");
            let mut outside = triangles;
            outside[k] = 12;
            assert!(error(&outside, &[3, 3]).contains("face 1 (indices["), "corner {k}");
        }
        let mut positions = vec![0.0; 3 * 12];
        positions[7] = f32::NAN;
        let message = from_faces(&positions, &quads, &[4, 4]).err().map(|e| e.to_string());
        assert!(message.unwrap_or_default().contains("vertex 2 has coordinate y = NaN"));
    }

    /// A hub's outgoing list (longer than [`LongLists::LONG`]) is searched in its sorted copy;
    /// every lookup must give what a scan of the list gives: the half-edges between two
    /// vertices, ascending, none for two that share no edge. The fan around the hub has a fin
    /// (a third face on one of its edges) and a face the other way round on another.
    #[test]
    fn a_hubs_sorted_list_finds_what_a_scan_finds() {
        let ring = 150u32;
        let mut indices = Vec::new();
        for i in 0..ring {
            indices.extend([0, 1 + i, 1 + (i + 1) % ring]);
        }
        indices.extend([0, 1, ring + 1, 0, 3, 2]);
        let sizes = vec![3; indices.len() / 3];
        let positions = vec![0.0; 3 * (ring as usize + 2)];
        let mesh = from_faces(&positions, &indices, &sizes).unwrap();
        let out_to: Vec<u32> = mesh
            .vertex_half_edges
            .iter()
            .map(|&h| mesh.he_from[mesh.next_in_cell(h) as usize])
            .collect();
        let long = LongLists::new(&mesh, &out_to);
        assert_eq!(long.starts.len(), 1, "the hub's list is the one long list");
        let outgoing = Outgoing::<true> { mesh: &mesh, out_to: &out_to, long: &long };
        for a in 0..mesh.num_vertices() as u32 {
            for b in 0..mesh.num_vertices() as u32 {
                let found: Vec<u32> = outgoing.between(a, b).collect();
                let mut scanned: Vec<u32> = mesh
                    .out_half_edges(a)
                    .iter()
                    .copied()
                    .filter(|&h| mesh.he_from[mesh.next_in_cell(h) as usize] == b)
                    .collect();
                scanned.sort_unstable();
                assert_eq!(found, scanned, "half-edges {a} -> {b}");
            }
        }
        assert_eq!(outgoing.between(0, 3).count(), 2, "the reversed face's half-edge too");
        assert_eq!(outgoing.between(0, 1).count(), 2, "the fin's half-edge too");
    }
}
