//! The weights of a limit table, each distinct row of them stored once.
//!
//! A limit row (position and two tangents) depends only on the topology and tags around its
//! vertex, and a cage has few distinct neighbourhoods: the horse's level-2 Catmull-Clark table
//! has 1.16M rows but 40,780 distinct weight lists (514k entries of 13M), its level-2 Loop
//! table 14,206. A frame reads 16 bytes per entry from a table (an index and three weights),
//! and is bound by that memory traffic; with the weights shared it reads the index and, per
//! row, where its weights start, while the shared lists stay in cache. The table itself is
//! unchanged (its arrays are what users and the GPU read); this is the CPU evaluator's view of
//! it, the same weights in the same order, so the sums are bit-identical.

/// The rows' weights of a table with tangents, shared: row `r`'s entry `j` (in the table's
/// order) has the weights `weights[starts[r] + j]` (position, first tangent, second tangent).
#[derive(Clone, Debug)]
pub(crate) struct SharedWeights {
    /// Per row of the table, where its weights start; rows that were not shared are never read.
    starts: Vec<u32>,
    /// The distinct weight lists, one after another.
    weights: Vec<[f32; 3]>,
}

/// A distinct weight list while sharing, as the hash table holds it (no indirection: a probe
/// is one cache miss): its hash, where it starts and how long it is.
#[derive(Clone, Copy)]
struct List {
    hash: u64,
    start: u32,
    len: u32,
}

/// The length of an empty slot (no row has that many entries).
const EMPTY: u32 = u32::MAX;

impl List {
    const EMPTY: List = List { hash: 0, start: 0, len: EMPTY };

    /// The list's weights.
    fn weights(self, weights: &[[f32; 3]]) -> &[[f32; 3]] {
        weights.get(self.start as usize..).and_then(|w| w.get(..self.len as usize)).unwrap_or(&[])
    }
}

impl SharedWeights {
    /// The shared weights of `rows` of a table of limit rows in compressed rows (`offsets`,
    /// and per entry the position's and the two tangents' weights); `None` when sharing would
    /// keep more than half the weights (a cage of few repeated neighbourhoods, where the shared
    /// lists would not stay in cache either).
    pub(crate) fn new(
        offsets: &[u32],
        [position, first, second]: [&[f32]; 3],
        rows: &[usize],
    ) -> Option<Self> {
        let mut starts = vec![0; offsets.len().saturating_sub(1)];
        let mut weights: Vec<[f32; 3]> = Vec::new();
        let mut slots = vec![List::EMPTY; 1 << 12];
        let mut count = 0;
        let budget =
            rows.iter().map(|&r| (offsets[r + 1] - offsets[r]) as usize).sum::<usize>() / 2;
        for &r in rows {
            let range = offsets[r] as usize..offsets[r + 1] as usize;
            let row = (&position[range.clone()], &first[range.clone()], &second[range]);
            let hash = hash(row);
            let mask = slots.len() - 1;
            let mut slot = home(hash) & mask;
            // Linear probing: the row's list, or the empty slot where it goes.
            let list = loop {
                let list = slots[slot];
                if list.len == EMPTY || (list.hash == hash && same(list.weights(&weights), row)) {
                    break list;
                }
                slot = (slot + 1) & mask;
            };
            starts[r] = if list.len != EMPTY {
                list.start
            } else {
                let start = u32::try_from(weights.len()).ok()?;
                let (a, b, c) = row;
                weights.extend(a.iter().zip(b).zip(c).map(|((&a, &b), &c)| [a, b, c]));
                if weights.len() > budget {
                    return None;
                }
                slots[slot] = List { hash, start, len: a.len() as u32 };
                count += 1;
                if 2 * count > slots.len() {
                    slots = rehash(&slots, 2 * slots.len());
                }
                start
            };
        }
        weights.shrink_to_fit();
        Some(SharedWeights { starts, weights })
    }

    /// Where row `r`'s weights start in [`SharedWeights::weights`].
    #[inline(always)]
    pub(crate) fn start(&self, r: usize) -> usize {
        self.starts[r] as usize
    }

    /// The shared weight lists.
    #[inline(always)]
    pub(crate) fn weights(&self) -> &[[f32; 3]] {
        &self.weights
    }
}

/// One row's weights: the position's, the first tangent's and the second's.
type Row<'a> = (&'a [f32], &'a [f32], &'a [f32]);

/// `shared` holds `row`'s weights, bit for bit (0 and -0 are different weights to a sum that
/// starts at -0).
fn same(shared: &[[f32; 3]], (a, b, c): Row) -> bool {
    shared.len() == a.len()
        && shared.iter().zip(a.iter().zip(b).zip(c)).all(|(w, ((&a, &b), &c))| {
            (w[0].to_bits() ^ a.to_bits())
                | (w[1].to_bits() ^ b.to_bits())
                | (w[2].to_bits() ^ c.to_bits())
                == 0
        })
}

/// A hash of a row's weights: one multiply per entry.
fn hash((a, b, c): Row) -> u64 {
    const K: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut h = a.len() as u64;
    for ((&a, &b), &c) in a.iter().zip(b).zip(c) {
        let x = u64::from(a.to_bits()) | u64::from(b.to_bits()) << 32;
        h = (h.rotate_left(5) ^ x ^ u64::from(c.to_bits()).rotate_left(19)).wrapping_mul(K);
    }
    h
}

/// The first slot to try for `hash`: its high bits (a product's low bits mix only the
/// factors' low bits).
fn home(hash: u64) -> usize {
    hash.rotate_left(32) as usize
}

/// The lists of `slots` in a hash table of `size` slots (a power of two).
fn rehash(slots: &[List], size: usize) -> Vec<List> {
    let mut table = vec![List::EMPTY; size];
    let mask = size - 1;
    for &list in slots.iter().filter(|l| l.len != EMPTY) {
        let mut slot = home(list.hash) & mask;
        while table[slot].len != EMPTY {
            slot = (slot + 1) & mask;
        }
        table[slot] = list;
    }
    table
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows with the same weights, bit for bit, share one list; any other difference (a weight,
    /// a length, the sign of a zero) does not.
    #[test]
    fn equal_rows_share_their_weights() {
        // Five rows: 0 and 2 are equal, 3 differs in a tangent, 4 has -0 where 0 has 0. Each
        // entry's three weights are (position, first, second).
        let rows: [&[[f32; 3]]; 5] = [
            &[[0.5, 1.0, 0.0], [0.5, -1.0, 0.0]],
            &[[1.0, 0.0, 0.0]],
            &[[0.5, 1.0, 0.0], [0.5, -1.0, 0.0]],
            &[[0.5, 1.0, 0.0], [0.5, -1.0, 0.5]],
            &[[0.5, 1.0, -0.0], [0.5, -1.0, 0.0]],
        ];
        let mut offsets = vec![0u32];
        let mut columns: [Vec<f32>; 3] = Default::default();
        for row in rows.iter().cycle().take(50) {
            for w in row.iter() {
                columns.iter_mut().zip(w).for_each(|(c, &w)| c.push(w));
            }
            offsets.push(columns[0].len() as u32);
        }
        let weights = [&columns[0][..], &columns[1][..], &columns[2][..]];
        let all: Vec<usize> = (0..50).collect();
        let shared = SharedWeights::new(&offsets, weights, &all).unwrap();
        // Four distinct lists of seven entries in all, each row reading its own.
        assert_eq!(shared.weights().len(), 7);
        for (r, row) in rows.iter().cycle().take(50).enumerate() {
            let start = shared.start(r);
            let got = &shared.weights()[start..start + row.len()];
            assert!(got
                .iter()
                .zip(row.iter())
                .all(|(a, b)| a.map(f32::to_bits) == b.map(f32::to_bits)));
        }
        assert_eq!(shared.start(0), shared.start(2));
        assert_ne!(shared.start(0), shared.start(3));
        assert_ne!(shared.start(0), shared.start(4));
        // Rows all different keep more than half the weights: not shared.
        assert!(SharedWeights::new(&offsets, weights, &[0, 1, 3, 4]).is_none());
    }
}
