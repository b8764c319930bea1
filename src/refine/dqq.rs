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

use crate::error::{Error, Result};
use crate::mesh::{HalfEdgeMesh, NonManifold, PolyMesh};
use crate::rules::{vec3, CornerRules};

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
    match mesh.first_non_manifold() {
        None => Ok(()),
        Some(NonManifold::Edge { from, to, .. }) => Err(Error::Unsupported(format!(
            "{scheme} needs a manifold mesh, but the edge between vertices {from} and {to} has more than two faces (or two facing the same way); use catmull-clark or loop, which treat such edges as creases"
        ))),
        Some(NonManifold::Vertex { vertex }) => Err(Error::Unsupported(format!(
            "{scheme} needs a manifold mesh, but the faces around vertex {vertex} form more than one fan; use catmull-clark or loop"
        ))),
    }
}

/// The rank of each boundary half-edge among boundary half-edges (`u32::MAX` elsewhere).
fn boundary_ranks(mesh: &HalfEdgeMesh) -> (Vec<u32>, u32) {
    let mut count = 0u32;
    let ranks = (0..mesh.num_half_edges())
        .map(|h| {
            if mesh.he_next_around_edge[h] == h as u32 {
                count += 1;
                count - 1
            } else {
                u32::MAX
            }
        })
        .collect();
    (ranks, count)
}

/// One dual level: the child mesh as flat arrays. `check` must have passed.
pub fn refine<R: CornerRules>(mesh: &HalfEdgeMesh, rules: &R, boundary: DualBoundary) -> PolyMesh {
    let nh = mesh.num_half_edges();
    let (ranks, boundary_count) = match boundary {
        DualBoundary::Chaikin => boundary_ranks(mesh),
        DualBoundary::Retract => (Vec::new(), 0),
    };
    let mut positions = vec![0.0f32; 3 * (nh + 2 * boundary_count as usize)];
    let (corners, chaikin) = positions.as_chunks_mut::<3>().0.split_at_mut(nh);
    for (h, p) in corners.iter_mut().enumerate() {
        *p = rules.corner_point(mesh, h as u32).to_array();
    }
    for h in 0..nh {
        if let Some(&r) = ranks.get(h).filter(|&&r| r != u32::MAX) {
            let a = vec3(mesh.positions[mesh.he_from[h] as usize]);
            let b = vec3(mesh.positions[mesh.to_vertex(h as u32) as usize]);
            chaikin[2 * r as usize] = (a * 0.75 + b * 0.25).to_array();
            chaikin[2 * r as usize + 1] = (a * 0.25 + b * 0.75).to_array();
        }
    }

    let near_from = |h: u32| nh as u32 + 2 * ranks[h as usize];
    let mut indices: Vec<u32> = (0..nh as u32).collect();
    let mut face_sizes: Vec<u32> = mesh.cell_offsets.windows(2).map(|w| w[1] - w[0]).collect();
    for e in 0..mesh.num_edges() {
        match mesh.edge_half_edges[mesh.edge_range(e)] {
            [h, g] => {
                indices.extend_from_slice(&[mesh.next_in_cell(h), h, mesh.next_in_cell(g), g]);
            }
            [h] if boundary == DualBoundary::Chaikin => {
                indices.extend_from_slice(&[
                    mesh.next_in_cell(h),
                    h,
                    near_from(h),
                    near_from(h) + 1,
                ]);
            }
            _ => continue,
        }
        face_sizes.push(4);
    }
    for v in 0..mesh.num_vertices() as u32 {
        let Some(&start) = mesh.out_half_edges(v).first() else {
            continue;
        };
        let on_boundary = mesh.he_next_around_edge[start as usize] == start;
        if on_boundary && boundary == DualBoundary::Retract {
            continue;
        }
        let first = indices.len();
        let mut h = start;
        loop {
            indices.push(h);
            let incoming = mesh.prev_in_cell(h);
            let across = mesh.he_next_around_edge[incoming as usize];
            if across == incoming {
                // The incoming boundary half-edge ends at v: its point near v, then start's.
                indices.extend_from_slice(&[near_from(incoming) + 1, near_from(start)]);
                break;
            }
            if across == start {
                break;
            }
            h = across;
        }
        if indices.len() - first < 3 {
            // An interior vertex of valence 2: its face would have two sides. Leaving it out
            // lets the two edge faces beside it share the edge between its two corners.
            indices.truncate(first);
            continue;
        }
        face_sizes.push((indices.len() - first) as u32);
    }
    PolyMesh { positions, indices, face_sizes }
}
