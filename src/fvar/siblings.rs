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
        let mut seen = Distinct::default();
        for v in 0..nv as u32 {
            seen.clear();
            for &h in mesh.out_half_edges(v) {
                let x = corner_values[h as usize];
                rank[h as usize] = seen.find(x).unwrap_or_else(|| seen.push(x)) as u32;
            }
            count.push(seen.list.len() as u32);
        }
        Siblings { rank, count }
    }
}

/// The values met around one vertex, in the order met, and where each was first met. A few are
/// searched; past [`Distinct::SEARCHED`] they are looked up by value, since a vertex with a value
/// per face (the apex of a cone as three.js makes it, a UV per segment) made the search cost
/// `n²` steps: 3 s for a cone of 100k segments.
#[derive(Default)]
pub(crate) struct Distinct {
    /// The values in the order met (a value may be listed again: see [`Distinct::push`]).
    pub list: Vec<u32>,
    /// Per value, the stamp of the vertex that last indexed it and its first place in `list`;
    /// only used past `SEARCHED` values, and grown to the largest value met.
    lookup: Vec<(u32, u32)>,
    stamp: u32,
}

impl Distinct {
    const SEARCHED: usize = 16;

    /// Starts another vertex.
    pub fn clear(&mut self) {
        self.list.clear();
        if self.stamp == u32::MAX {
            self.lookup.iter_mut().for_each(|l| l.0 = 0);
            self.stamp = 0;
        }
        self.stamp += 1;
    }

    /// Where `x` was first listed.
    #[inline]
    pub fn find(&self, x: u32) -> Option<usize> {
        if self.list.len() <= Self::SEARCHED {
            return self.list.iter().position(|&u| u == x);
        }
        match self.lookup.get(x as usize) {
            Some(&(stamp, at)) if stamp == self.stamp => Some(at as usize),
            _ => None,
        }
    }

    /// Lists `x` (even when listed already: a caller may list a value twice on purpose, and
    /// [`Distinct::find`] still gives its first place); returns its place.
    #[inline]
    pub fn push(&mut self, x: u32) -> usize {
        self.list.push(x);
        let n = self.list.len();
        if n == Self::SEARCHED + 1 {
            for i in 0..n {
                self.index(i);
            }
        } else if n > Self::SEARCHED + 1 {
            self.index(n - 1);
        }
        n - 1
    }

    /// Indexes `list[i]` unless an earlier place is indexed.
    #[cold]
    fn index(&mut self, i: usize) {
        let x = self.list[i] as usize;
        if self.lookup.len() <= x {
            self.lookup.resize(x + 1, (0, 0));
        }
        if self.lookup[x].0 != self.stamp {
            self.lookup[x] = (self.stamp, i as u32);
        }
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

#[cfg(test)]
mod tests {
    use super::Distinct;

    /// Past the searched few, the lookup must give what a search of the list gives: the first
    /// place of a value, none for a value not listed at this vertex (though listed at an earlier
    /// one), also for a value listed twice on purpose.
    #[test]
    fn the_lookup_finds_what_a_search_finds() {
        let mut distinct = Distinct::default();
        let mut state = 7u32;
        for vertex in 0..50 {
            distinct.clear();
            let count = [3, 16, 17, 40, 300][vertex % 5];
            for k in 0..count {
                state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                let x = (state >> 8) % 500;
                let searched = distinct.list.iter().position(|&u| u == x);
                assert_eq!(distinct.find(x), searched, "vertex {vertex}, value {k}: {x}");
                if searched.is_none() || k % 7 == 0 {
                    distinct.push(x);
                }
            }
        }
    }
}
