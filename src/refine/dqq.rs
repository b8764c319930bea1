//! Dual quad quadrisection (DQQ, the Doo-Sabin split): every face corner becomes a vertex, and
//! the new faces are one per old face (its corners), one per interior edge (a quad) and one per
//! interior vertex (its corners around it).
//!
//! Child vertex `h` is the corner of parent half-edge `h` (its cell at its from-vertex). Child
//! faces are `[face faces | edge faces in edge order | vertex faces in vertex order]`. With
//! [`DualBoundary::Chaikin`] every boundary half-edge `h = a→b` also gets two boundary points,
//! child vertices `H + 2r` (near `a`) and `H + 2r + 1` (near `b`), `r` being `h`'s rank among
//! boundary half-edges; boundary edges and vertices then get faces too, and the new boundary
//! polygon is the Chaikin refinement of the old one.
//!
//! The faces, for parent half-edge `h` with `g` the other half-edge of its edge:
//!
//! - face face of cell `c`: its corners in order, so child half-edge `h` runs from corner `h`
//!   to the next corner of `h`'s cell;
//! - edge face: `(next(h), h, next(g), g)` for an interior edge listed as `[h, g]`, and
//!   `(next(h), h, near_from(h), near_from(h) + 1)` for a boundary edge (Chaikin);
//! - vertex face: the corners around the vertex, starting at its first outgoing half-edge and
//!   going across the edge before each corner; a boundary vertex (Chaikin) ends with the point
//!   near it on its incoming boundary edge, then the one on its outgoing boundary edge.
//!
//! [`child_mesh`] writes the child's connectivity by index arithmetic from this layout, in the
//! conventions of the general builder, so that it is exactly the mesh
//! `HalfEdgeMesh::from_poly(&refine(..))` would build (`tests/child_mesh.rs` checks this); the
//! next level's faces and points, which depend on the child's edge numbering and vertex lists,
//! are then unchanged.

use crate::error::{Error, Result};
use crate::mesh::{HalfEdgeMesh, NonManifold, PolyMesh};
use crate::primvar::{Primvar, Rows};
use crate::rules::CornerRules;

/// No such child element: no face for this edge, no vertex face for this corner.
const NONE: u32 = u32::MAX;

/// What the dual split does at the boundary.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DualBoundary {
    /// Faces of boundary edges and vertices are left out, so the surface retracts (CGAL).
    Retract,
    /// Boundary edges and vertices get faces that end on the Chaikin points of the boundary.
    Chaikin,
}

/// Upper bounds of the child `[vertices, edges, half-edges, cells]`, exact on closed meshes
/// but for the edges. Face faces have `H` half-edges, edge faces `4E`, vertex faces `H` plus two
/// Chaikin corners per boundary vertex (at most `2V`); every edge has at least one half-edge.
pub fn child_counts(vertices: u64, edges: u64, half_edges: u64, cells: u64) -> [u64; 4] {
    let child_half_edges = 2 * half_edges + 4 * edges + 2 * vertices;
    [3 * half_edges, child_half_edges, child_half_edges, cells + edges + vertices]
}

/// Refuses meshes the dual split cannot take.
pub fn check(mesh: &HalfEdgeMesh, scheme: &str) -> Result<()> {
    super::check_distinct_corners(mesh, scheme)?;
    match mesh.first_non_manifold() {
        None => Ok(()),
        Some(NonManifold::Edge { edge, from, to })
            if mesh.marked_non_manifold.get(edge as usize) == Some(&true) =>
        {
            Err(Error::Unsupported(format!(
                "{scheme} needs a manifold mesh, but the edge between vertices {from} and {to} descends from a face that repeats a vertex (a non-manifold edge); use catmull-clark or loop, which treat such edges as creases"
            )))
        }
        Some(NonManifold::Edge { from, to, .. }) => Err(Error::Unsupported(format!(
            "{scheme} needs a manifold mesh, but the edge between vertices {from} and {to} has more than two faces (or two facing the same way); use catmull-clark or loop, which treat such edges as creases"
        ))),
        Some(NonManifold::Vertex { vertex }) => Err(Error::Unsupported(format!(
            "{scheme} needs a manifold mesh, but the faces around vertex {vertex} form more than one fan; use catmull-clark or loop"
        ))),
    }
}

/// Where every child face and corner goes: one pass over the edges and one walk around each
/// vertex, shared by the flat face list of the last level and the child mesh of the others.
struct Layout {
    /// The boundary half-edges in order (Chaikin only): `boundary[r]` has rank `r`.
    boundary: Vec<u32>,
    /// The first child half-edge of each edge's face, `NONE` for an edge without one.
    edge_face: Vec<u32>,
    num_edge_faces: usize,
    /// The child half-edge that leaves corner `h` in its vertex's face, `NONE` without one.
    vertex_face_out: Vec<u32>,
    /// The size of each vertex face, in vertex order.
    vertex_face_sizes: Vec<u32>,
    /// For the boundary half-edge of rank `r`: the child half-edge leaving its point near its
    /// from-vertex in that vertex's face (towards the corner), and the one leaving its point
    /// near its to-vertex in that vertex's face (towards the next boundary point).
    chaikin_tails: Vec<[u32; 2]>,
    num_child_half_edges: usize,
}

impl Layout {
    fn new(mesh: &HalfEdgeMesh, mode: DualBoundary) -> Self {
        let (nh, ne, nv) = (mesh.num_half_edges(), mesh.num_edges(), mesh.num_vertices());
        let chaikin = mode == DualBoundary::Chaikin;
        let is_boundary = |h: u32| mesh.he_next_around_edge[h as usize] == h;
        let boundary: Vec<u32> =
            if chaikin { (0..nh as u32).filter(|&h| is_boundary(h)).collect() } else { Vec::new() };
        let mut ranks = Vec::new();
        if chaikin {
            ranks = vec![NONE; nh];
            for (r, &h) in boundary.iter().enumerate() {
                ranks[h as usize] = r as u32;
            }
        }

        let mut edge_face = vec![NONE; ne];
        let mut at = nh as u32;
        for (e, slot) in edge_face.iter_mut().enumerate() {
            // Edges of three or more half-edges (non-manifold, refused by `check`) get none.
            let count = mesh.edge_offsets[e + 1] - mesh.edge_offsets[e];
            if count == 2 || (count == 1 && chaikin) {
                *slot = at;
                at += 4;
            }
        }
        let num_edge_faces = (at as usize - nh) / 4;

        let mut vertex_face_out = vec![NONE; nh];
        let mut vertex_face_sizes = Vec::with_capacity(nv);
        let mut chaikin_tails = vec![[NONE; 2]; boundary.len()];
        for v in 0..nv as u32 {
            let out = mesh.out_half_edges(v);
            let Some(&start) = out.first() else {
                continue;
            };
            let starts_on_boundary = is_boundary(start);
            if starts_on_boundary && !chaikin {
                continue;
            }
            let (mut h, mut n, mut incoming_boundary) = (start, 0u32, NONE);
            loop {
                vertex_face_out[h as usize] = at + n;
                n += 1;
                let incoming = mesh.prev_in_cell(h);
                let across = mesh.he_next_around_edge[incoming as usize];
                if across == incoming {
                    incoming_boundary = incoming;
                    break;
                }
                // The length bound only matters on meshes `check` refuses: there a walk need
                // not come back to its start.
                if across == start || n as usize >= out.len() {
                    break;
                }
                h = across;
            }
            let closes = incoming_boundary == NONE;
            // An interior vertex of valence 2 would make a face with two sides; leaving it out
            // lets the two edge faces beside it share the edge between its two corners. An open
            // walk from an interior start happens only at non-manifold vertices.
            if (closes && n < 3) || (!closes && !starts_on_boundary) {
                let mut h = start;
                for _ in 0..n {
                    vertex_face_out[h as usize] = NONE;
                    h = mesh.he_next_around_edge[mesh.prev_in_cell(h) as usize];
                }
                continue;
            }
            let size = if closes { n } else { n + 2 };
            if !closes {
                chaikin_tails[ranks[start as usize] as usize][0] = at + n + 1;
                chaikin_tails[ranks[incoming_boundary as usize] as usize][1] = at + n;
            }
            vertex_face_sizes.push(size);
            at += size;
        }
        Layout {
            boundary,
            edge_face,
            num_edge_faces,
            vertex_face_out,
            vertex_face_sizes,
            chaikin_tails,
            num_child_half_edges: at as usize,
        }
    }

    fn num_child_vertices(&self, mesh: &HalfEdgeMesh) -> usize {
        mesh.num_half_edges() + 2 * self.boundary.len()
    }

    fn num_child_cells(&self, mesh: &HalfEdgeMesh) -> usize {
        mesh.num_cells() + self.num_edge_faces + self.vertex_face_sizes.len()
    }

    /// The child face list: the from-vertex of every child half-edge.
    fn face_indices(&self, mesh: &HalfEdgeMesh) -> Vec<u32> {
        let nh = mesh.num_half_edges();
        let mut indices = vec![0u32; self.num_child_half_edges];
        for (h, slot) in indices[..nh].iter_mut().enumerate() {
            *slot = h as u32;
        }
        for (e, &at) in self.edge_face.iter().enumerate() {
            if let [h, g] = mesh.edge_half_edges[mesh.edge_range(e)] {
                let face = [mesh.next_in_cell(h), h, mesh.next_in_cell(g), g];
                indices[at as usize..at as usize + 4].copy_from_slice(&face);
            }
        }
        for (h, &at) in self.vertex_face_out.iter().enumerate() {
            if at != NONE {
                indices[at as usize] = h as u32;
            }
        }
        // Boundary edges (Chaikin): each edge face ends on the edge's two points, which also
        // end the faces of the edge's two vertices.
        for (r, (&h, &tails)) in self.boundary.iter().zip(&self.chaikin_tails).enumerate() {
            let near_from = nh as u32 + 2 * r as u32;
            let at = self.edge_face[mesh.he_edge[h as usize] as usize] as usize;
            let face = [mesh.next_in_cell(h), h, near_from, near_from + 1];
            indices[at..at + 4].copy_from_slice(&face);
            // Every tail is set on a mesh that `check` accepts; elsewhere a vertex's other fans
            // are not walked, and their points end no face.
            for (k, out) in tails.into_iter().enumerate() {
                if let Some(slot) = indices.get_mut(out as usize) {
                    *slot = near_from + k as u32;
                }
            }
        }
        indices
    }

    fn face_sizes(&self, mesh: &HalfEdgeMesh) -> Vec<u32> {
        let mut sizes = Vec::with_capacity(self.num_child_cells(mesh));
        sizes.extend(mesh.cell_offsets.windows(2).map(|w| w[1] - w[0]));
        sizes.resize(mesh.num_cells() + self.num_edge_faces, 4);
        sizes.extend_from_slice(&self.vertex_face_sizes);
        sizes
    }

    /// For each parent half-edge `h`, the child half-edge of its edge face that runs against
    /// it, from `next(h)` to `h` (`NONE` without an edge face). The one after it leaves corner
    /// `h` along its vertex, to the corner across `h`'s edge (or to `h`'s Chaikin point near
    /// it); the one of `prev(h)` leaves corner `h` towards corner `prev(h)`.
    fn edge_face_sides(&self, mesh: &HalfEdgeMesh) -> Vec<u32> {
        let mut sides = vec![NONE; mesh.num_half_edges()];
        for (e, &at) in self.edge_face.iter().enumerate() {
            if at != NONE {
                for (k, &h) in mesh.edge_half_edges[mesh.edge_range(e)].iter().enumerate() {
                    sides[h as usize] = at + 2 * k as u32;
                }
            }
        }
        sides
    }
}

/// The corner points, then the Chaikin points, in child vertex order, from `parent`.
fn child_points<R: CornerRules, P: Primvar>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    layout: &Layout,
    parent: &P,
) -> P {
    let mut points = parent.with_capacity(layout.num_child_vertices(mesh));
    let mut sum = parent.sum(&mesh.he_from, None);
    let corners = mesh.num_half_edges() as u32;
    points.extend_with(corners, &mut sum, |h, w| rules.corner_point(mesh, h, w));
    let cut = 2 * layout.boundary.len() as u32;
    points.extend_with(cut, &mut sum, |k, w| {
        rules.boundary_point(mesh, layout.boundary[k as usize / 2], k as usize % 2, w)
    });
    points
}

/// The child values of the vertex-varying `rows` (none when it is empty).
fn child_rows<R: CornerRules, P: Primvar>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    layout: &Layout,
    rows: &P,
) -> P {
    if rows.is_empty() {
        return rows.with_capacity(0);
    }
    child_points(mesh, rules, layout, rows)
}

/// One dual level: the child mesh as flat arrays. `check` must have passed.
pub fn refine<R: CornerRules>(mesh: &HalfEdgeMesh, rules: &R, boundary: DualBoundary) -> PolyMesh {
    refine_with(mesh, rules, boundary, &Rows::default()).0
}

/// [`refine`], and the child values of the vertex-varying `rows` (or of any [`Primvar`]).
pub fn refine_with<R: CornerRules, P: Primvar>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    boundary: DualBoundary,
    rows: &P,
) -> (PolyMesh, P) {
    let layout = Layout::new(mesh, boundary);
    let positions = child_points(mesh, rules, &layout, &mesh.positions);
    let indices = layout.face_indices(mesh);
    let face_sizes = layout.face_sizes(mesh);
    let rows = child_rows(mesh, rules, &layout, rows);
    (PolyMesh { positions: positions.into_flattened(), indices, face_sizes }, rows)
}

/// One dual level as a half-edge mesh, equal to `HalfEdgeMesh::from_poly(&refine(..))` but
/// written by index arithmetic (see the module docs). Meshes that `check` refuses, and meshes
/// without faces (whose child has no vertex, which a mesh cannot be built from), take that
/// general path; it is the only error.
pub fn child_mesh<R: CornerRules>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    boundary: DualBoundary,
) -> Result<HalfEdgeMesh> {
    child_mesh_with(mesh, rules, boundary, &Rows::default()).map(|(child, _)| child)
}

/// [`child_mesh`], and the child values of the vertex-varying `rows` (or of any [`Primvar`]).
pub fn child_mesh_with<R: CornerRules, P: Primvar>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    boundary: DualBoundary,
    rows: &P,
) -> Result<(HalfEdgeMesh, P)> {
    if mesh.is_non_manifold() || mesh.num_half_edges() == 0 {
        let (poly, rows) = refine_with(mesh, rules, boundary, rows);
        return Ok((HalfEdgeMesh::from_poly(&poly)?, rows));
    }
    let layout = Layout::new(mesh, boundary);
    let positions = child_points(mesh, rules, &layout, &mesh.positions);
    let he_from = layout.face_indices(mesh);
    let rows = child_rows(mesh, rules, &layout, rows);

    let nh = mesh.num_half_edges();
    let mut cell_offsets = Vec::with_capacity(layout.num_child_cells(mesh) + 1);
    cell_offsets.extend_from_slice(&mesh.cell_offsets);
    let mut at = nh as u32;
    cell_offsets.extend((0..layout.num_edge_faces).map(|_| {
        at += 4;
        at
    }));
    cell_offsets.extend(layout.vertex_face_sizes.iter().map(|&n| {
        at += n;
        at
    }));
    let sides = layout.edge_face_sides(mesh);
    let he_twin = dual_twins(mesh, &layout, &sides, he_from.len());

    // A corner leaves along its face face, its two edge faces and its vertex face, when it has
    // them: in ascending order but for the two edge faces. A Chaikin point leaves along its
    // edge face, then its vertex face.
    let mut vertex_offsets = Vec::with_capacity(positions.len() + 1);
    let mut vertex_half_edges = Vec::with_capacity(he_from.len());
    vertex_offsets.push(0u32);
    for range in mesh.cell_offsets.windows(2) {
        let mut p = range[1] - 1;
        for x in range[0]..range[1] {
            let along = match sides[x as usize] {
                NONE => NONE,
                side => side + 1,
            };
            let back = sides[p as usize];
            vertex_half_edges.push(x);
            for h in [along.min(back), along.max(back), layout.vertex_face_out[x as usize]] {
                if h != NONE {
                    vertex_half_edges.push(h);
                }
            }
            vertex_offsets.push(vertex_half_edges.len() as u32);
            p = x;
        }
    }
    for (&h, &[near_from_out, near_to_out]) in layout.boundary.iter().zip(&layout.chaikin_tails) {
        let at = sides[h as usize];
        vertex_half_edges.extend_from_slice(&[at + 2, near_from_out]);
        vertex_offsets.push(vertex_half_edges.len() as u32);
        vertex_half_edges.extend_from_slice(&[at + 3, near_to_out]);
        vertex_offsets.push(vertex_half_edges.len() as u32);
    }
    let child = manifold_mesh(ManifoldParts {
        positions,
        cell_offsets,
        he_from,
        he_twin,
        vertex_offsets,
        vertex_half_edges,
    });
    Ok((child, rows))
}

/// The twin of every child half-edge (itself on the boundary); each loop writes only the
/// half-edges of its own face or corner. `sides` is [`Layout::edge_face_sides`].
fn dual_twins(mesh: &HalfEdgeMesh, layout: &Layout, sides: &[u32], count: usize) -> Vec<u32> {
    let nh = mesh.num_half_edges();
    let parent_twin = |h: u32| mesh.he_next_around_edge[h as usize];
    let mut twins = vec![0u32; count];
    // Face faces: the side of the edge face against each half-edge.
    for (h, twin) in twins[..nh].iter_mut().enumerate() {
        *twin = if sides[h] == NONE { h as u32 } else { sides[h] };
    }
    // The half-edge that comes back to corner `z` from the corner before it around `z`'s
    // vertex, for the edge face half-edge `own` that goes there: in the vertex face; where an
    // interior vertex of valence 2 has none, in the other edge face at that vertex; at a
    // vertex that retracts, none.
    let around = |z: u32, own: u32| {
        let out = layout.vertex_face_out[z as usize];
        if out != NONE {
            return out;
        }
        let first = mesh.out_half_edges(mesh.he_from[z as usize])[0];
        if parent_twin(first) == first {
            own
        } else {
            sides[z as usize] + 1
        }
    };
    for (e, &at) in layout.edge_face.iter().enumerate() {
        if let [h, g] = mesh.edge_half_edges[mesh.edge_range(e)] {
            let face =
                [h, around(mesh.next_in_cell(g), at + 1), g, around(mesh.next_in_cell(h), at + 3)];
            twins[at as usize..at as usize + 4].copy_from_slice(&face);
        }
    }
    // Vertex faces: corner `x` goes to the corner across the edge before it, whose edge face
    // comes back; at the end of a boundary fan, to that edge's Chaikin point, whose edge face
    // comes back along the boundary.
    for (x, &out) in layout.vertex_face_out.iter().enumerate() {
        if out != NONE {
            let p = mesh.prev_in_cell(x as u32);
            let z = parent_twin(p);
            twins[out as usize] =
                if z == p { sides[p as usize] + 3 } else { sides[z as usize] + 1 };
        }
    }
    // Boundary edge faces, and the Chaikin ends of the vertex faces.
    for (&h, &[near_from_out, near_to_out]) in layout.boundary.iter().zip(&layout.chaikin_tails) {
        let at = sides[h as usize];
        let next_out = layout.vertex_face_out[mesh.next_in_cell(h) as usize];
        twins[at as usize..at as usize + 4].copy_from_slice(&[h, near_from_out, at + 2, next_out]);
        twins[near_from_out as usize] = at + 1;
        twins[near_to_out as usize] = near_to_out;
    }
    twins
}

/// The connectivity of a 2-manifold child mesh (every edge one half-edge or two running
/// opposite ways, every vertex one fan), as a host works it out by index arithmetic.
pub(crate) struct ManifoldParts {
    pub positions: Vec<[f32; 3]>,
    pub cell_offsets: Vec<u32>,
    pub he_from: Vec<u32>,
    /// The other half-edge of each half-edge's edge; a boundary half-edge's own index.
    pub he_twin: Vec<u32>,
    /// `vertex_offsets[v]..vertex_offsets[v + 1]` index `vertex_half_edges`: the half-edges
    /// leaving `v`, in ascending order.
    pub vertex_offsets: Vec<u32>,
    pub vertex_half_edges: Vec<u32>,
}

/// Completes a child mesh from its parts in the general builder's conventions, so that the
/// result is the mesh `HalfEdgeMesh::from_faces` makes of the same faces: edges are numbered in
/// the order of their lowest half-edge, which comes first in the edge's list, and a vertex with
/// a boundary half-edge has the first one swapped to the front of its list. One pass over the
/// half-edges, one over the vertices when there is a boundary; no sort, no search.
pub(crate) fn manifold_mesh(parts: ManifoldParts) -> HalfEdgeMesh {
    let ManifoldParts {
        positions,
        cell_offsets,
        he_from,
        he_twin,
        vertex_offsets,
        mut vertex_half_edges,
    } = parts;
    let nh = he_from.len();
    debug_assert_eq!(vertex_offsets.len(), positions.len() + 1);
    debug_assert_eq!(vertex_half_edges.len(), nh);
    debug_assert!(vertex_offsets.windows(2).enumerate().all(|(v, w)| {
        let list = &vertex_half_edges[w[0] as usize..w[1] as usize];
        list.windows(2).all(|p| p[0] < p[1])
            && list.iter().all(|&h| he_from[h as usize] == v as u32)
    }));
    debug_assert!((0..nh).all(|h| {
        let twin = he_twin[h] as usize;
        he_twin[twin] as usize == h && (twin == h || he_from[twin] != he_from[h])
    }));

    let boundary_count = he_twin.iter().enumerate().filter(|&(h, &t)| t as usize == h).count();
    let num_edges = (nh + boundary_count) / 2;
    let mut mesh = HalfEdgeMesh {
        he_next_around_edge: he_twin,
        vertex_offsets,
        ..HalfEdgeMesh::from_cells(positions, cell_offsets, he_from, None)
    };
    let (he_from, he_twin) = (&mesh.he_from, &mesh.he_next_around_edge);
    let to_vertex = |h: usize| {
        let twin = he_twin[h] as usize;
        he_from[if twin != h { twin } else { mesh.next_in_cell(h as u32) as usize }]
    };
    let mut he_edge = vec![0u32; nh];
    let mut edge_vertices = Vec::with_capacity(num_edges);
    let mut edge_offsets = Vec::with_capacity(num_edges + 1);
    let mut edge_half_edges = Vec::with_capacity(nh);
    edge_offsets.push(0u32);
    for (h, &twin) in he_twin.iter().enumerate() {
        if twin as usize >= h {
            he_edge[h] = edge_vertices.len() as u32;
            edge_vertices.push([he_from[h], to_vertex(h)]);
            edge_half_edges.push(h as u32);
            if twin as usize != h {
                edge_half_edges.push(twin);
            }
            edge_offsets.push(edge_half_edges.len() as u32);
        }
    }
    for h in 0..nh {
        let twin = he_twin[h] as usize;
        if twin < h {
            he_edge[h] = he_edge[twin];
        }
    }
    if boundary_count > 0 {
        // The seed's contract: a vertex lists a boundary half-edge first when it has one.
        for range in mesh.vertex_offsets.windows(2) {
            let list = &mut vertex_half_edges[range[0] as usize..range[1] as usize];
            if let Some(i) = list.iter().position(|&h| he_twin[h as usize] == h) {
                list.swap(0, i);
            }
        }
    }
    mesh.he_edge = he_edge;
    mesh.edge_vertices = edge_vertices;
    mesh.edge_offsets = edge_offsets;
    mesh.edge_half_edges = edge_half_edges;
    mesh.vertex_half_edges = vertex_half_edges;
    mesh
}

/// Sorts a short list (a vertex's outgoing half-edges).
#[inline]
pub(crate) fn insertion_sort(list: &mut [u32]) {
    for i in 1..list.len() {
        let x = list[i];
        let mut j = i;
        while j > 0 && list[j - 1] > x {
            list[j] = list[j - 1];
            j -= 1;
        }
        list[j] = x;
    }
}
