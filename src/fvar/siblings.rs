//! What the non-primal levels ([`super::doo_sabin`], [`super::sqrt3`]) read of a level's value
//! topology: they analyse nothing beforehand (a level made by them is not analysed, see
//! [`super::FVarChannel::analysed`]), so they compare the value indices the corners see, as
//! OpenSubdiv compares face-varying indices: two corners at a vertex with different indices see
//! different values ("siblings"), and an edge whose two faces see different indices at either
//! end is a seam.

use crate::mesh::HalfEdgeMesh;

/// No such child value.
pub(crate) const NONE: u32 = u32::MAX;

/// Per corner (parent half-edge), the rank of its value among the distinct values seen at its
/// vertex, in the order of the vertex's outgoing half-edges; per vertex, how many there are.
pub(crate) struct Siblings {
    pub rank: Vec<u32>,
    pub count: Vec<u32>,
}

impl Siblings {
    /// The siblings of every vertex of `mesh` whose corners see `corner_values`. One loop per
    /// vertex, each writing only the ranks of its own corners.
    pub fn new(mesh: &HalfEdgeMesh, corner_values: &[u32]) -> Self {
        let nv = mesh.num_vertices();
        let mut rank = vec![0u32; mesh.num_half_edges()];
        let mut count = Vec::with_capacity(nv);
        let mut seen: Vec<u32> = Vec::new();
        for v in 0..nv as u32 {
            seen.clear();
            for &h in mesh.out_half_edges(v) {
                let x = corner_values[h as usize];
                rank[h as usize] = match seen.iter().position(|&s| s == x) {
                    Some(r) => r as u32,
                    None => {
                        seen.push(x);
                        seen.len() as u32 - 1
                    }
                };
            }
            count.push(seen.len() as u32);
        }
        Siblings { rank, count }
    }
}

/// True when the edge of interior half-edge `h` is a seam: the faces on its two sides see
/// different values at either end. False for a boundary half-edge.
#[inline]
pub(crate) fn is_seam(mesh: &HalfEdgeMesh, corner_values: &[u32], h: u32) -> bool {
    let g = mesh.he_next_around_edge[h as usize];
    if g == h {
        return false;
    }
    let value = |x: u32| corner_values[x as usize];
    value(h) != value(mesh.next_in_cell(g)) || value(mesh.next_in_cell(h)) != value(g)
}
