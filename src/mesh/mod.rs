//! The half-edge mesh: struct-of-arrays connectivity with `u32` indices.
//!
//! Every cell (face) owns a contiguous run of half-edges, one per corner, in the order the face
//! lists its vertices. Half-edge `h` runs from corner `k` to corner `k + 1` of its cell. Half-edges
//! that share an unordered vertex pair share an edge; the half-edges of one edge form a cycle
//! (`next_around_edge`), so an edge used by three or more cells, or by two cells in the same
//! direction, is represented as it is (non-manifold), as the seed `002` allows. A boundary edge
//! has a cycle of one.
//!
//! A cell may list a vertex more than once (OpenSubdiv accepts such faces). Then, as OpenSubdiv's
//! `Vtr` does, a half-edge from a vertex to itself (adjacent corners with one vertex) is an edge
//! of its own, and a cell never has two half-edges on one edge: a later use of a vertex pair
//! within the cell that already uses it gets an edge of its own. Both kinds are non-manifold
//! edges although their half-edges do not show it (a flag per edge says so), and so is the edge
//! that the cell's first use of such a pair is on. In refined meshes two edges may join the same
//! two vertices too (a host keeps the halves of a parent edge apart, as OpenSubdiv does).
//!
//! The query API follows the seed's names in Rust style; see [`VertexRef`], [`HalfEdgeRef`] and
//! [`CellRef`]. Entry points that take an index return `Option`, so a bad index is never a panic.

mod build;
#[cfg(target_arch = "wasm32")]
pub(crate) use build::positions_not_in_threes;
mod handles;
mod poly;

pub use handles::{CellRef, HalfEdgeRef, VertexRef};
pub use poly::{area_vector, PolyMesh};
pub(crate) use poly::{chunked, quad_and_fan_chunks};

use crate::error::Result;

/// The largest coordinate (and attribute value) accepted, in magnitude. The rules and the
/// stencils sum many values before they scale them, and past this such sums could overflow
/// f32 (about 3.4e38) into infinities: a fuzzed OBJ file with a coordinate of 1.9e38 gave
/// Catmull-Clark edge points of infinity. Even so, a valence of millions stays in range.
pub const MAX_COORDINATE: f32 = 1e30;

/// Whether `x` is finite and within [`MAX_COORDINATE`] (NaN is not).
#[inline(always)]
pub(crate) fn usable(x: f32) -> bool {
    x.abs() <= MAX_COORDINATE
}

/// The first value of `values` that is not [`usable`]. A pass without an early exit first (it
/// vectorizes): the place is looked for only on failure.
pub(crate) fn first_unusable(values: &[f32]) -> Option<usize> {
    let all_usable = values.iter().fold(true, |ok, &x| ok & usable(x));
    if all_usable {
        return None;
    }
    values.iter().position(|&x| !usable(x))
}

/// What every `what` (a coordinate, a value) must be, for an `x` that is not [`usable`].
pub(crate) fn unusable_because(x: f32, what: &str) -> String {
    if x.is_finite() {
        format!(
            "every {what} must be within ±1e30, as larger ones overflow f32 in the \
             subdivision's sums; scale them down"
        )
    } else {
        format!("every {what} must be a finite number")
    }
}

/// A polygon mesh with half-edge connectivity, stored as flat arrays.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct HalfEdgeMesh {
    pub(crate) positions: Vec<[f32; 3]>,
    /// `cell_offsets[c]..cell_offsets[c + 1]` are the half-edges of cell `c`; length `F + 1`.
    pub(crate) cell_offsets: Vec<u32>,
    /// From-vertex of each half-edge; also the flat face index list.
    pub(crate) he_from: Vec<u32>,
    /// The cell of each half-edge when cells differ in size; empty when `cell_size` is set, as
    /// [`HalfEdgeMesh::cell_of`] then computes it (one array less to write per level).
    pub(crate) he_cell: Vec<u32>,
    pub(crate) he_edge: Vec<u32>,
    pub(crate) he_next_around_edge: Vec<u32>,
    /// `[from, to]` of the first half-edge of each edge.
    pub(crate) edge_vertices: Vec<[u32; 2]>,
    /// `edge_offsets[e]..edge_offsets[e + 1]` index `edge_half_edges`; length `E + 1`.
    pub(crate) edge_offsets: Vec<u32>,
    pub(crate) edge_half_edges: Vec<u32>,
    /// `vertex_offsets[v]..vertex_offsets[v + 1]` index `vertex_half_edges`, the half-edges leaving
    /// `v`, a boundary one first when there is one; length `V + 1`.
    pub(crate) vertex_offsets: Vec<u32>,
    pub(crate) vertex_half_edges: Vec<u32>,
    /// True when some edge has more than two half-edges or two running the same way. Set by the
    /// builder (for free, while it pairs half-edges) and inherited by refined meshes, so a scheme
    /// can choose its general path without scanning the mesh.
    pub(crate) non_manifold_edges: bool,
    /// True when the mesh has no non-manifold edge but some vertex's faces form several fans.
    /// Set by the builder (one walk around every vertex, about 3% of the build) and inherited by
    /// refined meshes (the children of such a vertex are such vertices; no others appear), so
    /// the plain Catmull-Clark and Loop rules never need to check.
    pub(crate) multi_fan_vertices: bool,
    /// Edges that are non-manifold although their half-edges do not show it (see the module
    /// docs): an edge from a vertex to itself, the edges of a vertex pair that one cell uses
    /// more than once, and in refined meshes the halves of such edges (as OpenSubdiv tags them).
    /// One flag per edge, or empty when there is none: only meshes with a cell that repeats a
    /// vertex, and their refinements, pay for it.
    pub(crate) marked_non_manifold: Vec<bool>,
    /// True when some cell lists a vertex more than once. Set by the builder; refined meshes
    /// never have such cells.
    pub(crate) repeated_corners: bool,
    /// 3 or 4 when every cell has that many corners, else 0 (see [`uniform_cell_size`]).
    pub(crate) cell_size: u32,
}

/// 3 when every cell is a triangle, 4 when every cell is a quad, else 0 (also for no cells).
/// With it, the cell walks of such meshes (every level the quad and triangle splits make, and
/// most input) are index arithmetic instead of two dependent loads (`he_cell`, then
/// `cell_offsets`), and `he_cell` need not be stored.
pub(crate) fn uniform_cell_size(cell_offsets: &[u32]) -> u32 {
    let Some(&end) = cell_offsets.get(1) else {
        return 0;
    };
    let n = end - cell_offsets[0];
    let uniform = (n == 3 || n == 4) && cell_offsets.windows(2).all(|w| w[1] - w[0] == n);
    if uniform {
        n
    } else {
        0
    }
}

impl HalfEdgeMesh {
    /// A mesh of these cells (corners `he_from`, cell `c` the half-edges
    /// `cell_offsets[c]..cell_offsets[c + 1]`) without connectivity yet: what every builder starts
    /// from (the general one, the dual split's, the quad and triangle splits'), so that the
    /// mesh's own arrays and what follows from its cells (`cell_size`, the stored `he_cell`) are
    /// set in this one place; each builder then fills in the edges and vertex lists it computes
    /// its own way. `cell_size` is the uniform size when the caller knows it, else it is found.
    pub(crate) fn from_cells(
        positions: Vec<[f32; 3]>,
        cell_offsets: Vec<u32>,
        he_from: Vec<u32>,
        cell_size: Option<u32>,
    ) -> Self {
        let cell_size = cell_size.unwrap_or_else(|| uniform_cell_size(&cell_offsets));
        let he_cell = stored_half_edge_cells(&cell_offsets, cell_size);
        HalfEdgeMesh { positions, cell_offsets, he_from, he_cell, cell_size, ..Default::default() }
    }
}

/// Keeps, in order, the faces of `corners` (faces of `size` corners each, as a split's index
/// list or a channel's corner values) that `keep` takes by face index.
pub(crate) fn retain_faces(corners: &mut Vec<u32>, size: usize, keep: impl Fn(usize) -> bool) {
    let mut kept = 0usize;
    for f in 0..corners.len() / size {
        if keep(f) {
            corners.copy_within(f * size..(f + 1) * size, kept * size);
            kept += 1;
        }
    }
    corners.truncate(kept * size);
}

/// The `he_cell` a mesh with these cells stores: each half-edge's cell, or nothing when
/// [`uniform_cell_size`] is not 0 (then [`HalfEdgeMesh::cell_of`] is arithmetic).
pub(crate) fn stored_half_edge_cells(cell_offsets: &[u32], cell_size: u32) -> Vec<u32> {
    if cell_size != 0 {
        return Vec::new();
    }
    let mut he_cell = vec![0u32; cell_offsets.last().map_or(0, |&n| n as usize)];
    for (c, range) in cell_offsets.windows(2).enumerate() {
        he_cell[range[0] as usize..range[1] as usize].fill(c as u32);
    }
    he_cell
}

/// Where a mesh stops being a 2-manifold, for schemes that need to say so.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NonManifold {
    /// An edge with more than two half-edges, or two running the same way.
    Edge { edge: u32, from: u32, to: u32 },
    /// A vertex whose faces form more than one fan.
    Vertex { vertex: u32 },
}

impl HalfEdgeMesh {
    /// Builds a mesh from flat arrays, validating all of them. See [`PolyMesh`] for the layout.
    pub fn from_faces(positions: &[f32], indices: &[u32], face_sizes: &[u32]) -> Result<Self> {
        build::from_faces(positions, indices, face_sizes)
    }

    /// [`HalfEdgeMesh::from_faces`] on arrays it keeps (positions as `[x, y, z]` per vertex):
    /// neither is copied, which saves a pass and the memory of a second copy on large meshes.
    pub fn from_vertices(
        positions: Vec<[f32; 3]>,
        indices: Vec<u32>,
        face_sizes: &[u32],
    ) -> Result<Self> {
        build::from_vertices(positions, indices, face_sizes)
    }

    /// Builds a mesh from cells whose edges are already numbered (see
    /// [`build::from_cells_and_edges`]); for refinement hosts, which pass on whether the parent
    /// had vertices with several fans, and which edges are marked non-manifold.
    pub(crate) fn from_cells_and_edges(
        positions: Vec<[f32; 3]>,
        cell_offsets: Vec<u32>,
        he_from: Vec<u32>,
        he_edge: Vec<u32>,
        num_edges: usize,
        marked_non_manifold: Vec<bool>,
        multi_fan_vertices: bool,
    ) -> Self {
        let mut mesh = build::from_cells_and_edges(
            positions,
            cell_offsets,
            he_from,
            he_edge,
            num_edges,
            marked_non_manifold,
        );
        mesh.multi_fan_vertices = multi_fan_vertices && !mesh.non_manifold_edges;
        mesh
    }

    /// Builds a mesh from a [`PolyMesh`].
    pub fn from_poly(poly: &PolyMesh) -> Result<Self> {
        Self::from_faces(&poly.positions, &poly.indices, &poly.face_sizes)
    }

    /// The flat arrays again: positions, the face index list and face sizes.
    pub fn to_poly(&self) -> PolyMesh {
        PolyMesh {
            positions: self.positions.as_flattened().to_vec(),
            indices: self.he_from.clone(),
            face_sizes: self.cell_offsets.windows(2).map(|w| w[1] - w[0]).collect(),
        }
    }

    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }

    pub fn num_half_edges(&self) -> usize {
        self.he_from.len()
    }

    pub fn num_cells(&self) -> usize {
        self.cell_offsets.len().saturating_sub(1)
    }

    pub fn num_edges(&self) -> usize {
        self.edge_vertices.len()
    }

    pub fn vertex(&self, v: u32) -> Option<VertexRef<'_>> {
        ((v as usize) < self.num_vertices()).then_some(VertexRef { mesh: self, index: v })
    }

    pub fn half_edge(&self, h: u32) -> Option<HalfEdgeRef<'_>> {
        ((h as usize) < self.num_half_edges()).then_some(HalfEdgeRef { mesh: self, index: h })
    }

    pub fn cell(&self, c: u32) -> Option<CellRef<'_>> {
        ((c as usize) < self.num_cells()).then_some(CellRef { mesh: self, index: c })
    }

    pub fn vertex_indices(&self) -> std::ops::Range<u32> {
        0..self.num_vertices() as u32
    }

    pub fn half_edge_indices(&self) -> std::ops::Range<u32> {
        0..self.num_half_edges() as u32
    }

    pub fn cell_indices(&self) -> std::ops::Range<u32> {
        0..self.num_cells() as u32
    }

    /// The largest vertex index, or `None` for a mesh without vertices; the next free index is
    /// one more.
    pub fn max_vertex_index(&self) -> Option<u32> {
        self.num_vertices().checked_sub(1).map(|v| v as u32)
    }

    pub fn max_half_edge_index(&self) -> Option<u32> {
        self.num_half_edges().checked_sub(1).map(|h| h as u32)
    }

    pub fn max_cell_index(&self) -> Option<u32> {
        self.num_cells().checked_sub(1).map(|c| c as u32)
    }

    /// The two vertices of edge `e`, in the direction of its first half-edge.
    pub fn edge_vertices(&self, e: u32) -> Option<[u32; 2]> {
        self.edge_vertices.get(e as usize).copied()
    }

    /// The half-edges of edge `e`: one for a boundary edge, two for an interior manifold edge.
    pub fn edge_half_edges(&self, e: u32) -> Option<&[u32]> {
        let start = *self.edge_offsets.get(e as usize)? as usize;
        let end = *self.edge_offsets.get(e as usize + 1)? as usize;
        self.edge_half_edges.get(start..end)
    }

    /// Positions as `[x, y, z]` per vertex.
    pub fn positions(&self) -> &[[f32; 3]] {
        &self.positions
    }

    /// The flat face index list (the from-vertex of every half-edge, cell by cell).
    pub fn face_indices(&self) -> &[u32] {
        &self.he_from
    }

    /// Adds `count` vertices at the origin and returns the index of the first.
    pub fn add_vertices(&mut self, count: u32) -> u32 {
        let first = self.num_vertices() as u32;
        self.positions.resize(first as usize + count as usize, [0.0; 3]);
        let total = *self.vertex_offsets.last().unwrap_or(&0);
        if self.vertex_offsets.is_empty() {
            self.vertex_offsets.push(0);
        }
        self.vertex_offsets.resize(self.positions.len() + 1, total);
        first
    }

    /// Makes sure vertex `v` exists, adding vertices at the origin up to it.
    pub fn add_vertex(&mut self, v: u32) {
        let have = self.num_vertices() as u32;
        if v >= have {
            self.add_vertices(v - have + 1);
        }
    }

    /// Replaces every position (`[x, y, z]` per vertex, as many vertices as the mesh has) and
    /// keeps the connectivity: for meshes that move but keep their faces, subdivided again with
    /// [`crate::scheme::subdivide_mesh_borrowed`] without a rebuild. On an error (another count,
    /// a non-finite value) the mesh is unchanged.
    pub fn set_positions(&mut self, positions: Vec<[f32; 3]>) -> Result<()> {
        if positions.len() != self.positions.len() {
            return Err(crate::Error::mesh(format!(
                "the new positions have {} vertices ({} numbers), but the mesh has {}; give \
                 3 numbers per vertex, or build a new mesh for another vertex count",
                positions.len(),
                3 * positions.len(),
                self.positions.len()
            )));
        }
        build::check_usable(positions.as_flattened())?;
        self.positions = positions;
        Ok(())
    }

    /// Sets the coordinates of vertex `v`. Fails on a missing vertex or a non-finite or too
    /// large value ([`MAX_COORDINATE`]).
    pub fn set_coord(&mut self, v: u32, coord: [f32; 3]) -> Result<()> {
        if let Some(&bad) = coord.iter().find(|&&c| !usable(c)) {
            return Err(crate::Error::mesh(format!(
                "vertex {v}: coordinates {coord:?}; {}",
                unusable_because(bad, "coordinate")
            )));
        }
        let n = self.num_vertices();
        let slot = self.positions.get_mut(v as usize).ok_or_else(|| {
            crate::Error::mesh(format!("vertex {v} does not exist; the mesh has {n} vertices"))
        })?;
        *slot = coord;
        Ok(())
    }

    /// Adds a cell with the given vertices in order around it, creating missing vertices, and
    /// returns its index. This rebuilds the connectivity, O(mesh size) per call: build large
    /// meshes with [`HalfEdgeMesh::from_faces`] instead.
    pub fn add_cell(&mut self, cell_vertices: &[u32]) -> Result<u32> {
        if let Some(&max) = cell_vertices.iter().max() {
            self.add_vertex(max);
        }
        let mut indices = self.he_from.clone();
        indices.extend_from_slice(cell_vertices);
        let mut sizes: Vec<u32> = self.cell_offsets.windows(2).map(|w| w[1] - w[0]).collect();
        sizes.push(cell_vertices.len() as u32);
        let rebuilt = build::from_faces(self.positions.as_flattened(), &indices, &sizes)?;
        *self = rebuilt;
        Ok(self.num_cells() as u32 - 1)
    }

    /// True when some edge has more than two half-edges, or two running the same way (a
    /// non-manifold edge). Vertices whose faces form several fans around manifold edges do not
    /// count here; [`HalfEdgeMesh::first_non_manifold`] finds those too.
    pub fn has_non_manifold_edges(&self) -> bool {
        self.non_manifold_edges
    }

    /// True when the mesh has non-manifold edges or vertices: what the plain rules of the primal
    /// schemes do not handle.
    #[inline]
    pub(crate) fn is_non_manifold(&self) -> bool {
        self.non_manifold_edges || self.multi_fan_vertices
    }

    /// True when edge `e` has more than two half-edges, or two running the same way, or is marked
    /// non-manifold (an edge from a vertex to itself, or one of a pair a cell uses twice, or a
    /// half of one; see the module docs).
    #[inline]
    pub(crate) fn is_non_manifold_edge(&self, e: u32) -> bool {
        let hs = &self.edge_half_edges[self.edge_range(e as usize)];
        hs.len() > 2
            || (hs.len() == 2 && self.he_from[hs[0] as usize] == self.he_from[hs[1] as usize])
            || self.marked_non_manifold.get(e as usize).copied().unwrap_or(false)
    }

    /// True when every edge has one half-edge or two running opposite ways and none is marked
    /// non-manifold: each half-edge's twin is then its next around the edge (itself on a
    /// boundary), and edges can be visited as pairs of half-edges.
    #[inline]
    pub(crate) fn has_simple_edges(&self) -> bool {
        !self.non_manifold_edges && !self.repeated_corners && self.marked_non_manifold.is_empty()
    }

    /// True when some cell lists a vertex more than once (OpenSubdiv accepts such faces, and
    /// so do Catmull-Clark, Loop, bilinear and midpoint here; see the module docs).
    pub fn has_repeated_corners(&self) -> bool {
        self.repeated_corners
    }

    /// The first cell that lists a vertex more than once, with that vertex.
    pub fn first_repeated_corner(&self) -> Option<(u32, u32)> {
        if !self.repeated_corners {
            return None;
        }
        let mut last_cell = Vec::new();
        self.cell_indices().find_map(|c| {
            let corners = &self.he_from[self.cell_range(c as usize)];
            build::repeated_corner(corners, c, self.num_vertices(), &mut last_cell).map(|v| (c, v))
        })
    }

    /// The first place the mesh is not a 2-manifold, if any.
    pub fn first_non_manifold(&self) -> Option<NonManifold> {
        if !self.is_non_manifold() {
            return None; // known from the builder (and inherited by refined meshes)
        }
        if self.non_manifold_edges {
            if let Some(e) = (0..self.num_edges() as u32).find(|&e| self.is_non_manifold_edge(e)) {
                let [from, to] = self.edge_vertices[e as usize];
                return Some(NonManifold::Edge { edge: e, from, to });
            }
        }
        (0..self.num_vertices() as u32)
            .find(|&v| !self.is_single_fan(v))
            .map(|vertex| NonManifold::Vertex { vertex })
    }

    /// True when the faces around `v` form one fan (assuming manifold edges); true for a vertex
    /// without faces.
    pub(crate) fn is_single_fan(&self, v: u32) -> bool {
        let out = self.out_half_edges(v);
        let Some(&start) = out.first() else {
            return true;
        };
        let mut h = start;
        let mut visited = 1usize;
        loop {
            let incoming = self.prev_in_cell(h);
            let across = self.he_next_around_edge[incoming as usize];
            if across == incoming || across == start {
                break;
            }
            h = across;
            visited += 1;
            if visited > out.len() {
                return false;
            }
        }
        visited == out.len()
    }

    /// This mesh with vertex `v` renamed `labels[v]`, where `controls` lists the vertex of each
    /// label (the two are inverse permutations). Cells, half-edges and edges keep their numbers
    /// and every list its order, so that a walk of the relabelled mesh meets the same elements
    /// in the same order as a walk of this one, only under the vertices' new names.
    pub(crate) fn relabelled(&self, labels: &[u32], controls: &[u32]) -> HalfEdgeMesh {
        let name = |v: u32| labels.get(v as usize).copied().unwrap_or(v);
        let mut vertex_offsets = Vec::with_capacity(controls.len() + 1);
        let mut vertex_half_edges = Vec::with_capacity(self.vertex_half_edges.len());
        vertex_offsets.push(0);
        for &v in controls {
            if (v as usize) < self.num_vertices() {
                vertex_half_edges.extend_from_slice(self.out_half_edges(v));
            }
            vertex_offsets.push(vertex_half_edges.len() as u32);
        }
        let positions = controls.iter().map(|&v| self.positions.get(v as usize).copied());
        HalfEdgeMesh {
            positions: positions.map(|p| p.unwrap_or_default()).collect(),
            cell_offsets: self.cell_offsets.clone(),
            he_from: self.he_from.iter().map(|&v| name(v)).collect(),
            he_cell: self.he_cell.clone(),
            he_edge: self.he_edge.clone(),
            he_next_around_edge: self.he_next_around_edge.clone(),
            edge_vertices: self.edge_vertices.iter().map(|&[a, b]| [name(a), name(b)]).collect(),
            edge_offsets: self.edge_offsets.clone(),
            edge_half_edges: self.edge_half_edges.clone(),
            vertex_offsets,
            vertex_half_edges,
            non_manifold_edges: self.non_manifold_edges,
            multi_fan_vertices: self.multi_fan_vertices,
            marked_non_manifold: self.marked_non_manifold.clone(),
            repeated_corners: self.repeated_corners,
            cell_size: self.cell_size,
        }
    }

    // Index arithmetic shared by the handles and the refinement hosts.

    #[inline]
    pub(crate) fn out_half_edges(&self, v: u32) -> &[u32] {
        let v = v as usize;
        &self.vertex_half_edges
            [self.vertex_offsets[v] as usize..self.vertex_offsets[v + 1] as usize]
    }

    /// The next corner of half-edge `h` in a mesh of quads only (`cell_size` 4), without
    /// looking at the mesh: for loops that test the cell size once, not on every call.
    #[inline(always)]
    pub(crate) const fn next_in_quad(h: u32) -> u32 {
        (h & !3) | ((h + 1) & 3)
    }

    #[inline]
    pub(crate) fn next_in_cell(&self, h: u32) -> u32 {
        match self.cell_size {
            4 => return Self::next_in_quad(h),
            3 => return if h % 3 == 2 { h - 2 } else { h + 1 },
            _ => {}
        }
        let c = self.he_cell[h as usize] as usize;
        if h + 1 == self.cell_offsets[c + 1] {
            self.cell_offsets[c]
        } else {
            h + 1
        }
    }

    #[inline]
    pub(crate) fn prev_in_cell(&self, h: u32) -> u32 {
        match self.cell_size {
            4 => return (h & !3) | (h.wrapping_sub(1) & 3),
            3 => return if h.is_multiple_of(3) { h + 2 } else { h - 1 },
            _ => {}
        }
        let c = self.he_cell[h as usize] as usize;
        if h == self.cell_offsets[c] {
            self.cell_offsets[c + 1] - 1
        } else {
            h - 1
        }
    }

    /// The cell of half-edge `h`.
    #[inline]
    pub(crate) fn cell_of(&self, h: u32) -> u32 {
        match self.cell_size {
            4 => h >> 2,
            3 => h / 3,
            _ => self.he_cell[h as usize],
        }
    }

    #[inline]
    pub(crate) fn to_vertex(&self, h: u32) -> u32 {
        self.he_from[self.next_in_cell(h) as usize]
    }

    /// The half-edges of cell `c`: arithmetic on uniform cells, else two loads from
    /// `cell_offsets`.
    #[inline]
    pub(crate) fn cell_range(&self, c: usize) -> std::ops::Range<usize> {
        match self.cell_size as usize {
            0 => self.cell_offsets[c] as usize..self.cell_offsets[c + 1] as usize,
            n => n * c..n * c + n,
        }
    }

    #[inline]
    pub(crate) fn edge_range(&self, e: usize) -> std::ops::Range<usize> {
        self.edge_offsets[e] as usize..self.edge_offsets[e + 1] as usize
    }
}

#[cfg(test)]
mod tests {
    use super::HalfEdgeMesh;

    /// The index arithmetic for all-quad and all-triangle meshes gives the same neighbours and
    /// cell as the general lookup through `he_cell` and `cell_offsets` (filled in here from the
    /// cell sizes), and a mixed mesh keeps the general path.
    #[test]
    fn uniform_cell_walks_match_the_general_lookup() {
        let positions = vec![0.0; 3 * 9];
        let quads = [0, 1, 4, 3, 1, 2, 5, 4, 3, 4, 7, 6, 4, 5, 8, 7];
        let triangles = [0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4, 3, 4, 7, 3, 7, 6];
        let mixed = [0, 1, 4, 3, 1, 2, 5, 1, 5, 4];
        let pentagons = [0, 1, 2, 5, 4, 4, 5, 8, 7, 3];
        for (indices, sizes, size) in [
            (&quads[..], vec![4; 4], 4),
            (&triangles[..], vec![3; 6], 3),
            (&mixed[..], vec![4, 3, 3], 0),
            // Uniform, but neither triangles nor quads: the general path, with `he_cell`.
            (&pentagons[..], vec![5, 5], 0),
        ] {
            let mesh = HalfEdgeMesh::from_faces(&positions, indices, &sizes).expect("valid mesh");
            assert_eq!(mesh.cell_size, size);
            let he_cell = super::stored_half_edge_cells(&mesh.cell_offsets, 0);
            let general = HalfEdgeMesh { cell_size: 0, he_cell, ..mesh.clone() };
            for h in 0..mesh.num_half_edges() as u32 {
                assert_eq!(mesh.next_in_cell(h), general.next_in_cell(h), "next of {h}");
                assert_eq!(mesh.prev_in_cell(h), general.prev_in_cell(h), "prev of {h}");
                assert_eq!(mesh.cell_of(h), general.cell_of(h), "cell of {h}");
            }
        }
    }
}
