//! Borrowing handles with the seed `002` query vocabulary. They hold a valid index, so none of
//! their methods can fail.

use super::HalfEdgeMesh;

/// A vertex of a [`HalfEdgeMesh`].
#[derive(Clone, Copy, Debug)]
pub struct VertexRef<'a> {
    pub(super) mesh: &'a HalfEdgeMesh,
    pub(super) index: u32,
}

/// A half-edge of a [`HalfEdgeMesh`].
#[derive(Clone, Copy, Debug)]
pub struct HalfEdgeRef<'a> {
    pub(super) mesh: &'a HalfEdgeMesh,
    pub(super) index: u32,
}

/// A cell (face) of a [`HalfEdgeMesh`].
#[derive(Clone, Copy, Debug)]
pub struct CellRef<'a> {
    pub(super) mesh: &'a HalfEdgeMesh,
    pub(super) index: u32,
}

impl<'a> VertexRef<'a> {
    pub fn index(&self) -> u32 {
        self.index
    }

    /// Number of coordinates per vertex: always 3.
    pub fn dimension(&self) -> usize {
        3
    }

    /// Coordinate `ic` (0, 1 or 2); `None` for any other.
    pub fn coord(&self, ic: usize) -> Option<f32> {
        self.position().get(ic).copied()
    }

    pub fn position(&self) -> [f32; 3] {
        self.mesh.positions[self.index as usize]
    }

    /// Half-edges leaving this vertex. On a boundary this is one less than the number of edges.
    pub fn num_half_edges_from(&self) -> usize {
        self.mesh.out_half_edges(self.index).len()
    }

    /// The `k`-th half-edge leaving this vertex; `k = 0` is a boundary half-edge when there is one.
    pub fn kth_half_edge_from(&self, k: usize) -> Option<HalfEdgeRef<'a>> {
        let h = *self.mesh.out_half_edges(self.index).get(k)?;
        Some(HalfEdgeRef { mesh: self.mesh, index: h })
    }

    /// The half-edge from this vertex to `to`, if a cell has one.
    pub fn find_half_edge_to(&self, to: u32) -> Option<HalfEdgeRef<'a>> {
        let mesh = self.mesh;
        mesh.out_half_edges(self.index)
            .iter()
            .find(|&&h| mesh.to_vertex(h) == to)
            .map(|&h| HalfEdgeRef { mesh, index: h })
    }

    /// Half-edges leaving this vertex.
    pub fn half_edges_from(&self) -> impl Iterator<Item = HalfEdgeRef<'a>> + 'a {
        let mesh = self.mesh;
        mesh.out_half_edges(self.index).iter().map(move |&h| HalfEdgeRef { mesh, index: h })
    }

    /// True when a boundary edge touches this vertex.
    pub fn is_boundary(&self) -> bool {
        self.half_edges_from().any(|h| h.is_boundary() || h.prev_in_cell().is_boundary())
    }
}

impl<'a> HalfEdgeRef<'a> {
    fn at(&self, index: u32) -> HalfEdgeRef<'a> {
        HalfEdgeRef { mesh: self.mesh, index }
    }

    pub fn index(&self) -> u32 {
        self.index
    }

    pub fn from_vertex_index(&self) -> u32 {
        self.mesh.he_from[self.index as usize]
    }

    pub fn to_vertex_index(&self) -> u32 {
        self.mesh.to_vertex(self.index)
    }

    pub fn from_vertex(&self) -> VertexRef<'a> {
        VertexRef { mesh: self.mesh, index: self.from_vertex_index() }
    }

    pub fn to_vertex(&self) -> VertexRef<'a> {
        VertexRef { mesh: self.mesh, index: self.to_vertex_index() }
    }

    pub fn cell_index(&self) -> u32 {
        self.mesh.cell_of(self.index)
    }

    pub fn cell(&self) -> CellRef<'a> {
        CellRef { mesh: self.mesh, index: self.cell_index() }
    }

    /// The edge this half-edge lies on, an index into the mesh's edge arrays.
    pub fn edge_index(&self) -> u32 {
        self.mesh.he_edge[self.index as usize]
    }

    pub fn next_in_cell(&self) -> HalfEdgeRef<'a> {
        self.at(self.mesh.next_in_cell(self.index))
    }

    pub fn prev_in_cell(&self) -> HalfEdgeRef<'a> {
        self.at(self.mesh.prev_in_cell(self.index))
    }

    /// The next half-edge in the cycle around this edge: the opposite half-edge on a manifold
    /// interior edge, this half-edge itself on a boundary edge.
    pub fn next_around_edge(&self) -> HalfEdgeRef<'a> {
        self.at(self.mesh.he_next_around_edge[self.index as usize])
    }

    /// The previous half-edge around the from-vertex: `prev_in_cell().next_around_edge()`. On a
    /// boundary this returns the incoming boundary half-edge itself, as the seed's mesh does.
    pub fn prev_around_from_vertex(&self) -> HalfEdgeRef<'a> {
        self.prev_in_cell().next_around_edge()
    }

    /// True when no other cell shares this half-edge's edge.
    pub fn is_boundary(&self) -> bool {
        self.mesh.he_next_around_edge[self.index as usize] == self.index
    }
}

impl<'a> CellRef<'a> {
    pub fn index(&self) -> u32 {
        self.index
    }

    /// The cell's first half-edge, from its first listed vertex.
    pub fn half_edge(&self) -> HalfEdgeRef<'a> {
        HalfEdgeRef { mesh: self.mesh, index: self.mesh.cell_offsets[self.index as usize] }
    }

    pub fn num_vertices(&self) -> usize {
        self.mesh.cell_range(self.index as usize).len()
    }

    /// The cell's vertices in order around it.
    pub fn vertex_indices(&self) -> &'a [u32] {
        &self.mesh.he_from[self.mesh.cell_range(self.index as usize)]
    }
}
