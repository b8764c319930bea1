//! A limit table's rows regrouped for the CPU frame: the rows of the points on one base face,
//! four at a time in the lanes of 128-bit sums, over the few control points that face reaches,
//! with dense weights (a zero where a row does not read a point).
//!
//! A row of a limit table with normals is about 11 entries, each a control index and three
//! weights. Summed a row at a time ([`super::StencilTable::points_and_normals`]), every entry
//! costs a gather, three splatted weights and three multiply-adds on a padded point whose
//! fourth lane idles, and the horse's level-2 Loop frame took 25 ns per point in wasm. The
//! points of one base face all lie on the surface over that face, which only the face's
//! neighbourhood shapes (the 12 control points of a box-spline patch for a regular Loop
//! triangle; 12.2 on average over the horse). So a block here loads each of those points once,
//! splits it into x, y and z, and multiplies them by four rows' weights at once: no idle lane,
//! a quarter of the gathers and splits, and the normals made four at a time in lanes. The
//! horse's level-2 frames with normals (wasm, `evaluate` through the JS API): Loop 25.2 → 20.6
//! ns per point, Catmull-Clark 26.2 → 19.9.
//!
//! The blocks run in base-face order and write their points where the output numbers them.
//! That order matters as much as the arithmetic: in a standalone prototype on the horse (wasm,
//! level-2 Loop) the same blocks ran at 11 ns per point writing nowhere, 12.5 writing
//! sequentially, 15 writing in face order (the output's runs of vertex, edge and face children
//! each advance with the faces) and 21 in the order of the rows' lowest output index.
//!
//! The cost is memory and a first frame: dense weights of 48 bytes per control point of a
//! face per block (174 MB for the horse's level-2 Catmull-Clark table, against its 214 MB of
//! rows), made from the table in about 0.2 s (wasm), on the first frame (see
//! `crate::evaluator::RowSums`).
//!
//! The sums are those of the rows, in another order: positions as `x0 + Σ w (x - x0)` and
//! tangents as `Σ w (x - x0)`, with `x0` the face's first control point (the rows take their
//! own first one), so they agree with the rows' to f32 rounding, not bit for bit.

use super::lanes::{normals_in_lanes, one_by_one, store_four, Aligned, Lanes};
use super::StencilTable;

/// One block: four output rows over one face's control points.
#[derive(Clone, Copy, Debug)]
struct Block {
    /// Where the face's control points start in [`Blocks::controls`], and how many there are.
    controls: u32,
    len: u32,
    /// Where the block's weights start in [`Blocks::weights`] (`len` of them).
    weights: u32,
    /// The output row of each lane. A face whose row count is not a multiple of four fills the
    /// last block's idle lanes with a copy of its first lane (same row, same weights): the copy
    /// writes what the lane writes.
    rows: [u32; 4],
}

/// The rows of a limit table with tangents, grouped by base face into blocks of four (see the
/// module documentation).
#[derive(Clone, Debug, Default)]
pub(crate) struct Blocks {
    blocks: Vec<Block>,
    /// Each face's control points, face after face.
    controls: Vec<u32>,
    /// Per block and control point of its face: the position's, the first tangent's and the
    /// second tangent's weights, one lane per row.
    weights: Vec<[Aligned; 3]>,
}

impl Blocks {
    /// The blocks of the rows `covered` marks (all rows when it is empty) of `table`, which
    /// must have tangent weights, grouped by base face: the output faces `indices` /
    /// `face_sizes` come `runs[k]` at a time from base face `k`, in order (each level's children
    /// follow their parents), and a row goes with a face that has its vertex (see `by_face`). `None`
    /// when the table has no tangents, when the blocks would take more than `max_bytes`, or when
    /// their memory cannot be had (the rows then do the work).
    // Out of line: inlined into its caller, V8 compiled the whole of it slower.
    #[inline(never)]
    pub(crate) fn new(
        table: &StencilTable,
        indices: &[u32],
        face_sizes: &[u32],
        runs: &[u32],
        covered: &[bool],
        max_bytes: u64,
    ) -> Option<Blocks> {
        table.tangent_weights()?;
        let (starts, order) = by_face(table.num_stencils(), indices, face_sizes, runs, covered)?;
        let groups = runs.len() + 1;
        let (offsets, indices) = (table.offsets(), table.indices());
        let faces = || starts.windows(2).map(|f| &order[f[0] as usize..f[1] as usize]);
        // Each face's control points, in the order its rows first name them: where they start
        // in `controls`, and how many. Each point's slot in the current face is valid where its
        // stamp is the face's.
        // About one point per row (1.02 on the horse): room for 1.5, so that it rarely grows.
        let mut controls = Vec::with_capacity(order.len() + order.len() / 2);
        let mut spans = Vec::with_capacity(groups);
        let mut stamp = vec![u32::MAX; table.num_control_vertices()];
        let mut slot = vec![0u32; table.num_control_vertices()];
        for (g, face) in faces().enumerate() {
            let start = controls.len();
            for &r in face {
                let r = r as usize;
                for &c in &indices[offsets[r] as usize..offsets[r + 1] as usize] {
                    if stamp[c as usize] != g as u32 {
                        stamp[c as usize] = g as u32;
                        controls.push(c);
                    }
                }
            }
            spans.push([u32::try_from(start).ok()?, (controls.len() - start) as u32]);
        }
        // All the memory at once: grown block by block, the weights were copied as they grew.
        let count = |face: &[u32]| face.len().div_ceil(4) as u64;
        let num_blocks: u64 = faces().map(count).sum();
        let num_weights: u64 = faces().zip(&spans).map(|(f, s)| count(f) * u64::from(s[1])).sum();
        let bytes = 28 * num_blocks + 4 * controls.len() as u64 + 48 * num_weights;
        if bytes > max_bytes || u32::try_from(num_weights).is_err() {
            return None;
        }
        let mut blocks = Blocks { controls, ..Blocks::default() };
        blocks.blocks.try_reserve_exact(num_blocks as usize).ok()?;
        blocks.weights.try_reserve_exact(num_weights as usize).ok()?;
        fill(&mut blocks, &spans, faces, table, &mut slot);
        Some(blocks)
    }

    /// The positions and unit normals of the rows the blocks hold, from padded control points
    /// (`control` holds the table's control points: every index of the blocks is below their
    /// count).
    pub(crate) fn evaluate(
        &self,
        control: &[[f32; 4]],
        positions: &mut [[f32; 3]],
        normals: &mut [[f32; 3]],
    ) {
        debug_assert!(self.controls.iter().all(|&c| (c as usize) < control.len()));
        // Blocks with a normal that needs f64 (see `limit::normal`), made after the loop: a
        // call in the loop, even one never made, had V8 keep the loop's values on the stack.
        let mut redo = vec![0u64; self.blocks.len().div_ceil(64)];
        for (i, block) in self.blocks.iter().enumerate() {
            let [p, a, b] = self.sums(block, control);
            store_four(positions, block.rows, p);
            match normals_in_lanes(a, b) {
                Some(n) => store_four(normals, block.rows, n),
                None => redo[i / 64] |= 1 << (i % 64),
            }
        }
        for (i, block) in self.blocks.iter().enumerate() {
            if redo[i / 64] & 1 << (i % 64) != 0 {
                let [_, a, b] = self.sums(block, control);
                store_four(normals, block.rows, one_by_one(a, b));
            }
        }
    }

    /// A block's position (`x0 + Σ w (x - x0)`) and two tangents (`Σ w (x - x0)`), their x, y
    /// and z each in lanes, one row per lane.
    #[inline(always)]
    fn sums(&self, block: &Block, control: &[[f32; 4]]) -> [[Lanes; 3]; 3] {
        let start = block.controls as usize;
        let controls = &self.controls[start..start + block.len as usize];
        let weights = &self.weights[block.weights as usize..][..controls.len()];
        // SAFETY (both loads): every control index of the blocks is one of the table's, below
        // its number of control points, which `control` holds (see `evaluate`).
        let load = |c: u32| Lanes::load(unsafe { control.get_unchecked(c as usize) });
        let anchor = controls.first().map_or(Lanes::ZERO, |&c| load(c));
        let mut sums = [[Lanes::ZERO; 3]; 3];
        for (&c, w) in controls.iter().zip(weights) {
            let d = load(c).sub(anchor);
            let xyz = [d.splat::<0>(), d.splat::<1>(), d.splat::<2>()];
            for (sum, w) in sums.iter_mut().zip(w) {
                let w = Lanes::load(&w.0);
                for (s, &x) in sum.iter_mut().zip(&xyz) {
                    *s = s.add_product(w, x);
                }
            }
        }
        let [p, a, b] = sums;
        let p = [
            p[0].add(anchor.splat::<0>()),
            p[1].add(anchor.splat::<1>()),
            p[2].add(anchor.splat::<2>()),
        ];
        [p, a, b]
    }
}

/// The covered rows (see [`Blocks::new`]) grouped by base face: group `g`'s rows, in ascending
/// order, are `order[starts[g]..starts[g + 1]]` (group `runs.len()` holds the rows no face
/// names).
// Out of line, as `Blocks::new`.
#[inline(never)]
fn by_face(
    rows: usize,
    indices: &[u32],
    face_sizes: &[u32],
    runs: &[u32],
    covered: &[bool],
) -> Option<(Vec<u32>, Vec<u32>)> {
    let covers = |v: usize| covered.is_empty() || covered.get(v).copied().unwrap_or(false);
    // Each row's group: a base face that has its vertex (`runs.len()` for a row no face
    // names). A vertex inside a face's patch has one; one on its edges or corners is shared,
    // and goes to the first or the last face that has it, whichever has fewer rows so far:
    // the horse's level-2 Loop faces then hold 8 rows each (two full blocks) rather than 6
    // or 10 (four blocks with two idle lanes each), 18 % fewer blocks.
    const NONE: u32 = u32::MAX;
    let mut first_face = vec![NONE; rows];
    let mut last_face = vec![NONE; rows];
    // The face's group: base face `g`, its `left` faces still to come.
    let (mut g, mut left) = (0, runs.first().copied().unwrap_or(0));
    let mut corner = 0;
    for &size in face_sizes {
        while left == 0 && (g as usize) < runs.len() {
            g += 1;
            left = runs.get(g as usize).copied().unwrap_or(u32::MAX);
        }
        left = left.saturating_sub(1);
        for &v in indices.get(corner..corner + size as usize)? {
            let v = v as usize;
            if let (Some(first), Some(last)) = (first_face.get_mut(v), last_face.get_mut(v)) {
                if *first == NONE {
                    *first = g;
                }
                *last = g;
            }
        }
        corner += size as usize;
    }
    let mut count = vec![0u32; runs.len() + 1];
    for (&f, &l) in first_face.iter().zip(&last_face) {
        if f == l && f != NONE {
            count[f as usize] += 1;
        }
    }
    let group: Vec<u32> = first_face
        .iter()
        .zip(&last_face)
        .map(|(&f, &l)| {
            if f == l || f == NONE {
                return f;
            }
            let g = if count[l as usize] < count[f as usize] { l } else { f };
            count[g as usize] += 1;
            g
        })
        .collect();
    let groups = runs.len() + 1;
    let group_of = |g: u32| if g == NONE { groups - 1 } else { g as usize };
    let mut starts = vec![0u32; groups + 1];
    for (v, &g) in group.iter().enumerate() {
        if covers(v) {
            starts[group_of(g) + 1] += 1;
        }
    }
    for g in 0..groups {
        starts[g + 1] += starts[g];
    }
    let mut order = vec![0u32; starts[groups] as usize];
    let mut next = starts.clone();
    for (v, &g) in group.iter().enumerate() {
        if covers(v) {
            let g = group_of(g);
            order[next[g] as usize] = v as u32;
            next[g] += 1;
        }
    }
    Some((starts, order))
}

/// Appends the blocks of each face (`faces()`, with its control points at `spans`) to `blocks`,
/// whose memory is reserved; `slot` is scratch, one per control point.
// Out of line, as `Blocks::new`.
#[inline(never)]
fn fill<'a, F: Iterator<Item = &'a [u32]>>(
    blocks: &mut Blocks,
    spans: &[[u32; 2]],
    faces: impl Fn() -> F,
    table: &StencilTable,
    slot: &mut [u32],
) {
    let (offsets, indices, position) = (table.offsets(), table.indices(), table.weights());
    let Some([first, second]) = table.tangent_weights() else {
        return;
    };
    // A block is made in `dense` (in cache) and appended whole: scattered straight into the
    // table's memory, its weights needed that memory zeroed first, a pass over all of it.
    let mut dense = Vec::new();
    for (face, &[start, len]) in faces().zip(spans) {
        if face.is_empty() {
            continue;
        }
        let face_controls = &blocks.controls[start as usize..(start + len) as usize];
        for (j, &c) in face_controls.iter().enumerate() {
            slot[c as usize] = j as u32;
        }
        for four in face.chunks(4) {
            let rows: [u32; 4] = std::array::from_fn(|k| four.get(k).copied().unwrap_or(four[0]));
            dense.clear();
            dense.resize(len as usize, [Aligned::default(); 3]);
            for (lane, &r) in rows.iter().enumerate() {
                let range = offsets[r as usize] as usize..offsets[r as usize + 1] as usize;
                let entries = indices[range.clone()].iter().zip(&position[range.clone()]);
                let tangents = first[range.clone()].iter().zip(&second[range]);
                for ((&c, &w), (&a, &b)) in entries.zip(tangents) {
                    let at = &mut dense[slot[c as usize] as usize];
                    at[0].0[lane] = w;
                    at[1].0[lane] = a;
                    at[2].0[lane] = b;
                }
            }
            let weights = blocks.weights.len() as u32;
            blocks.weights.extend_from_slice(&dense);
            blocks.blocks.push(Block { controls: start, len, weights, rows });
        }
    }
}
