//! Stencil tables: refine once, evaluate every frame (OpenSubdiv's `Far::StencilTable`).
//!
//! Every output vertex of a call is an affine combination of the control (base) vertices, with
//! weights that depend on the topology, tags and options only. A [`StencilTable`] stores them as
//! one sparse matrix in compressed rows (`offsets`, `indices`, `weights`); evaluating it for new
//! control positions, or for any vertex-varying channel, is one sparse product
//! ([`StencilTable::evaluate`]) instead of a subdivision.
//!
//! The table is built by running the call's levels with `Stencils` as the vertex-varying data
//! ([`crate::primvar::Primvar`]): the rules name a new point's parents through the same
//! [`crate::rules::Weights`] sink as for positions, and `StencilSum` composes their stencils
//! (the base level is the identity), so every path of the driver (every scheme, tags, holes,
//! boundary modes) gives its stencils without code of its own. [`crate::scheme::stencil_table`]
//! is the entry point.
//!
//! `build` composes the rows while the levels run; `lanes` holds the 128-bit sums and the
//! batched normals that the evaluation loops here and the patches share.

mod build;
mod lanes;

pub(crate) use build::Stencils;
pub(crate) use lanes::{pad, Lanes, Normals, PointSink, Written};

use crate::error::{Error, Result};
use crate::shared_weights::SharedWeights;

/// For every output vertex of a call, the control vertices and weights whose weighted sum gives
/// it, in compressed rows: output vertex `i` is `Σ weights[k] · control[indices[k]]` over `k` in
/// `offsets[i]..offsets[i + 1]`. A row names each of its control vertices once (in no particular
/// order, as in OpenSubdiv's tables) and its weights sum to 1.
/// OpenSubdiv's `Far::StencilTable` (sizes, offsets, indices, weights) with the sizes left out
/// (they are the differences of the offsets).
///
/// A table for normals also holds, on the same entries, the weights of the two limit tangents
/// (OpenSubdiv's `Far::LimitStencilTable` and its `du`/`dv` weights): a row's control vertices
/// are then those any of the three sums reads, with zero weights where one does not.
#[derive(Clone, Debug, PartialEq)]
pub struct StencilTable {
    num_control: u32,
    offsets: Vec<u32>,
    indices: Vec<u32>,
    weights: Vec<f32>,
    tangent_weights: Option<Box<[Vec<f32>; 2]>>,
}

/// A table written row by row, each row from weighted control vertices that may repeat (a
/// repeat adds to the entry it repeats): for rows of a few entries each, a level's own rules
/// written straight from its topology (`crate::smooth_levels`).
pub(crate) struct TableWriter {
    table: StencilTable,
    row_start: usize,
}

impl TableWriter {
    /// No rows yet, on `num_control` control vertices, with room for `rows` rows of `entries`
    /// entries in all.
    pub(crate) fn new(num_control: usize, rows: usize, entries: usize) -> Self {
        let mut offsets = Vec::with_capacity(rows + 1);
        offsets.push(0);
        let table = StencilTable {
            num_control: num_control as u32,
            offsets,
            indices: Vec::with_capacity(entries),
            weights: Vec::with_capacity(entries),
            tangent_weights: None,
        };
        TableWriter { table, row_start: 0 }
    }

    /// Adds `weight` times control vertex `v` to the current row.
    #[inline]
    pub(crate) fn add(&mut self, v: u32, weight: f32) {
        let row = &self.table.indices[self.row_start..];
        match row.iter().position(|&i| i == v) {
            Some(k) => self.table.weights[self.row_start + k] += weight,
            None => {
                self.table.indices.push(v);
                self.table.weights.push(weight);
            }
        }
    }

    /// Ends the current row; the next `add` starts a new one.
    pub(crate) fn end_row(&mut self) {
        self.row_start = self.table.indices.len();
        self.table.offsets.push(self.row_start as u32);
    }

    pub(crate) fn finish(self) -> StencilTable {
        self.table
    }
}

impl StencilTable {
    /// Moves row `l` of the first `order.len()` rows to row `order[l]` (`order` a permutation of
    /// those rows); the rows after them stay where they are.
    pub(crate) fn reorder_first(&mut self, order: &[u32]) {
        let n = order.len().min(self.num_stencils());
        let mut from = vec![0u32; n];
        for (l, &p) in order.iter().enumerate().take(n) {
            if let Some(f) = from.get_mut(p as usize) {
                *f = l as u32;
            }
        }
        let end = self.offsets[n] as usize;
        let mut offsets = Vec::with_capacity(n + 1);
        offsets.push(0u32);
        let mut indices = Vec::with_capacity(end);
        let tangents = if self.tangent_weights.is_some() { end } else { 0 };
        let mut weights =
            [Vec::with_capacity(end), Vec::with_capacity(tangents), Vec::with_capacity(tangents)];
        for &l in &from {
            let range = self.offsets[l as usize] as usize..self.offsets[l as usize + 1] as usize;
            indices.extend_from_slice(&self.indices[range.clone()]);
            weights[0].extend_from_slice(&self.weights[range.clone()]);
            if let Some(tangents) = &self.tangent_weights {
                weights[1].extend_from_slice(&tangents[0][range.clone()]);
                weights[2].extend_from_slice(&tangents[1][range]);
            }
            offsets.push(indices.len() as u32);
        }
        self.offsets[..=n].copy_from_slice(&offsets);
        self.indices[..end].copy_from_slice(&indices);
        self.weights[..end].copy_from_slice(&weights[0]);
        if let Some(tangents) = &mut self.tangent_weights {
            tangents[0][..end].copy_from_slice(&weights[1]);
            tangents[1][..end].copy_from_slice(&weights[2]);
        }
    }

    /// Number of stencils: output vertices.
    pub fn num_stencils(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Number of control vertices the table reads (the base mesh's vertices).
    pub fn num_control_vertices(&self) -> usize {
        self.num_control as usize
    }

    /// Where each stencil starts in [`StencilTable::indices`], and where the last ends: one more
    /// than there are stencils.
    pub fn offsets(&self) -> &[u32] {
        &self.offsets
    }

    /// The control vertex of every entry.
    pub fn indices(&self) -> &[u32] {
        &self.indices
    }

    /// The weight of every entry.
    pub fn weights(&self) -> &[f32] {
        &self.weights
    }

    /// The control vertices and weights of output vertex `i` (`None` beyond the last).
    pub fn stencil(&self, i: usize) -> Option<(&[u32], &[f32])> {
        let start = *self.offsets.get(i)? as usize;
        let end = *self.offsets.get(i + 1)? as usize;
        Some((&self.indices[start..end], &self.weights[start..end]))
    }

    /// The weights of the two limit tangents on the same entries, when the table has them.
    pub fn tangent_weights(&self) -> Option<[&[f32]; 2]> {
        self.tangent_weights.as_deref().map(|[a, b]| [&a[..], &b[..]])
    }

    /// Bytes of the arrays: 4 per offset, 8 per entry (16 with tangent weights).
    pub fn bytes(&self) -> u64 {
        let per_entry = if self.tangent_weights.is_some() { 16 } else { 8 };
        4 * self.offsets.len() as u64 + per_entry * self.indices.len() as u64
    }

    /// This table with the tangents' weights on its own entries (rows made together by
    /// [`Primvar::limit_rows`]); `None` unless both have one weight per entry.
    pub(crate) fn with_tangent_weights(self, first: Vec<f32>, second: Vec<f32>) -> Option<Self> {
        let entries = self.weights.len();
        (first.len() == entries && second.len() == entries)
            .then(|| StencilTable { tangent_weights: Some(Box::new([first, second])), ..self })
    }

    /// This table with the rows that `fill(row, entries)` makes: it appends a row's entries (a
    /// control vertex and its weights: the position's, then the two tangents', which a table
    /// without tangents drops) and says true, or false to keep the row as it is. For rows that
    /// a stencil build left empty (`scheme::build_stencils`' `made_elsewhere`).
    pub(crate) fn with_rows(
        self,
        mut fill: impl FnMut(u32, &mut Vec<(u32, [f32; 3])>) -> bool,
    ) -> StencilTable {
        let StencilTable { num_control, offsets, indices, weights, tangent_weights } = self;
        let mut entries = Vec::with_capacity(16);
        // Room for 16 entries (a patch's most) in each row left empty: the arrays are not moved
        // while they grow.
        let empty = offsets.windows(2).filter(|w| w[0] == w[1]).count();
        let room = indices.len() + 16 * empty;
        let mut table = StencilTable {
            num_control,
            offsets: Vec::with_capacity(offsets.len()),
            indices: Vec::with_capacity(room),
            weights: Vec::with_capacity(room),
            tangent_weights: tangent_weights
                .as_ref()
                .map(|_| Box::new([Vec::with_capacity(room), Vec::with_capacity(room)])),
        };
        table.offsets.push(0);
        for (r, range) in offsets.windows(2).enumerate() {
            entries.clear();
            if fill(r as u32, &mut entries) {
                table.indices.extend(entries.iter().map(|&(c, _)| c));
                table.weights.extend(entries.iter().map(|&(_, [w, ..])| w));
                if let Some([first, second]) = table.tangent_weights.as_deref_mut() {
                    first.extend(entries.iter().map(|&(_, [_, w, _])| w));
                    second.extend(entries.iter().map(|&(_, [.., w])| w));
                }
            } else {
                let range = range[0] as usize..range[1] as usize;
                table.indices.extend_from_slice(&indices[range.clone()]);
                table.weights.extend_from_slice(&weights[range.clone()]);
                if let (Some([first, second]), Some([a, b])) =
                    (table.tangent_weights.as_deref_mut(), tangent_weights.as_deref())
                {
                    first.extend_from_slice(&a[range.clone()]);
                    second.extend_from_slice(&b[range]);
                }
            }
            table.offsets.push(table.indices.len() as u32);
        }
        table
    }

    /// A table of this one's entries with other weights (one per entry), without tangents.
    pub(crate) fn with_weights(&self, weights: Vec<f32>) -> Option<Self> {
        (weights.len() == self.weights.len()).then(|| StencilTable {
            num_control: self.num_control,
            offsets: self.offsets.clone(),
            indices: self.indices.clone(),
            weights,
            tangent_weights: None,
        })
    }

    /// The rows of `positions` (the same outputs and control vertices) on this table's entries,
    /// which must hold each of their control vertices: a refined table on the entries of the
    /// limit's (the refined point with the limit's normals), whose tangents' weights then share
    /// them. Itself back when some row of `positions` names a control vertex its row here does
    /// not.
    /// Why: merging the refined rows with the limit's sorted all three tables' rows and took a
    /// fifth of such a build; a limit row holds its vertex's refined row, as every limit mask
    /// weights the vertex itself.
    pub(crate) fn with_positions_of(
        self,
        positions: &StencilTable,
    ) -> std::result::Result<Self, Self> {
        match self.positions_on_entries(positions) {
            Some(weights) => Ok(StencilTable { weights, tangent_weights: None, ..self }),
            None => Err(self),
        }
    }

    /// The weights of `positions`' rows on this table's entries (see `with_positions_of`).
    fn positions_on_entries(&self, positions: &StencilTable) -> Option<Vec<f32>> {
        let rows = self.num_stencils();
        if positions.num_stencils() != rows || positions.num_control != self.num_control {
            return None;
        }
        let mut weights = vec![0.0; self.indices.len()];
        // Per control vertex, its entry in the current row (`u32::MAX` outside it).
        let mut entry = vec![u32::MAX; self.num_control as usize];
        for i in 0..rows {
            let (start, end) = (self.offsets[i] as usize, self.offsets[i + 1] as usize);
            for (k, &c) in self.indices[start..end].iter().enumerate() {
                *entry.get_mut(c as usize)? = (start + k) as u32;
            }
            let (controls, row) = positions.stencil(i)?;
            for (&c, &w) in controls.iter().zip(row) {
                let at = *entry.get(c as usize)?;
                *weights.get_mut(at as usize)? = w;
            }
            for &c in &self.indices[start..end] {
                entry[c as usize] = u32::MAX;
            }
        }
        Some(weights)
    }

    /// This table of positions with the tables of the two tangents (same rows, same control
    /// vertices) merged into it: each row's entries become the union of the three rows'.
    pub(crate) fn with_tangents(self, first: StencilTable, second: StencilTable) -> StencilTable {
        let shared = |t: &StencilTable| t.offsets == self.offsets && t.indices == self.indices;
        if shared(&first) && shared(&second) {
            // Rows made together (`Stencils::limit_rows`) already share their entries.
            return StencilTable {
                tangent_weights: Some(Box::new([first.weights, second.weights])),
                ..self
            };
        }
        let (this, first, second) = (self.ascending(), first.ascending(), second.ascending());
        let rows = this.num_stencils();
        let capacity = this.indices.len() + this.indices.len() / 4;
        let mut offsets = Vec::with_capacity(rows + 1);
        let mut indices = Vec::with_capacity(capacity);
        let mut weights = [(); 3].map(|_| Vec::with_capacity(capacity));
        offsets.push(0);
        let tables = [&this, &first, &second];
        for i in 0..rows {
            let mut rows = tables.map(|t| t.stencil(i).unwrap_or((&[], &[])));
            // A merge of three ascending lists: take the smallest head, from each list that has it.
            while let Some(c) = rows.iter().filter_map(|(c, _)| c.first()).min().copied() {
                indices.push(c);
                for ((controls, w), out) in rows.iter_mut().zip(&mut weights) {
                    if controls.first() == Some(&c) {
                        out.push(w[0]);
                        *controls = &controls[1..];
                        *w = &w[1..];
                    } else {
                        out.push(0.0);
                    }
                }
            }
            offsets.push(indices.len() as u32);
        }
        let [weights, t1, t2] = weights;
        StencilTable {
            num_control: this.num_control,
            offsets,
            indices,
            weights,
            tangent_weights: Some(Box::new([t1, t2])),
        }
    }

    /// This table with each row's entries in ascending order of control vertex (for a table
    /// without tangent weights, which are the ones `with_tangents` merges).
    fn ascending(mut self) -> Self {
        debug_assert!(self.tangent_weights.is_none());
        let mut row = Vec::new();
        for i in 0..self.num_stencils() {
            let range = self.offsets[i] as usize..self.offsets[i + 1] as usize;
            if self.indices[range.clone()].is_sorted() {
                continue;
            }
            row.clear();
            let weights = self.weights[range.clone()].iter().copied();
            row.extend(self.indices[range.clone()].iter().copied().zip(weights));
            row.sort_unstable_by_key(|&(c, _)| c);
            let entries = self.indices[range.clone()].iter_mut().zip(&mut self.weights[range]);
            for ((c, w), &sorted) in entries.zip(&row) {
                (*c, *w) = sorted;
            }
        }
        self
    }

    /// Writes the output positions of `control` (3 floats per control vertex) into `positions`
    /// and, when the table has tangent weights, the unit normals (`tan1 × tan2` normalised,
    /// zero where that is zero or not finite, as [`crate::limit::normal`]) into `normals`, in one
    /// pass over the entries. Lengths as [`StencilTable::evaluate`]; `normals` must be 3 floats
    /// per stencil when the table has tangents, else it is left alone.
    pub fn evaluate_with_normals(
        &self,
        control: &[f32],
        positions: &mut [f32],
        normals: &mut [f32],
    ) -> Result<()> {
        if self.tangent_weights().is_none() {
            return self.evaluate(control, 3, positions);
        }
        if normals.len() != positions.len() {
            return Err(Error::InvalidAttribute(format!(
                "stencil table: normals has {} floats; expected 3 per output vertex ({} of them)",
                normals.len(),
                self.num_stencils()
            )));
        }
        self.check_lengths(control.len(), 3, positions.len())?;
        let control = pad(control);
        let (positions, _) = positions.as_chunks_mut::<3>();
        let (normals, _) = normals.as_chunks_mut::<3>();
        self.points_and_normals(&control, AllRows(self.num_stencils()), positions, normals, None);
        Ok(())
    }

    /// The positions and unit normals of `rows` from padded control points (a table with
    /// tangent weights; `control` holds `num_control` points, `positions` and `normals` one per
    /// stencil).
    ///
    /// A tangent's weights sum to 0, so its sum cancels: at level 6 of a unit torus the
    /// tangents are about 1/64 of the coordinates, and summed as they are, f32 loses the digits
    /// the normals need to agree across evaluators (the regular patches, the GPU's rows) to
    /// 1e-5. Summed as `Σ w (x - x0)`, with `x0` the row's first control point (equal, as the
    /// weights sum to 0), each term is a local difference and the sum keeps its digits. The
    /// shader in `js/webgpu.js` sums the same way; the patches take a control point of theirs.
    /// (Adding back `(Σ w) x0` for the weights' rounding brought the error back: that sum
    /// cancels as the original did.)
    pub(crate) fn points_and_normals(
        &self,
        control: &[[f32; 4]],
        rows: impl RowIds,
        positions: &mut [[f32; 3]],
        normals: &mut [[f32; 3]],
        shared: Option<&SharedWeights>,
    ) {
        let Some([t1, t2]) = self.tangent_weights() else {
            return self.points(control, rows, positions);
        };
        debug_assert!(t1.len() == self.indices.len() && t2.len() == self.indices.len());
        match shared {
            Some(shared) => {
                let weights = shared.weights();
                self.points_and_normals_from(
                    control,
                    rows,
                    positions,
                    normals,
                    |r| shared.start(r),
                    |w| {
                        debug_assert!(w < weights.len());
                        // SAFETY: `SharedWeights::new` gave each shared row a list of its own
                        // length, so `start(r) + j` for entry `j` of row `r` is within `weights`.
                        unsafe { *weights.get_unchecked(w) }
                    },
                );
            }
            None => {
                let offsets = &self.offsets;
                self.points_and_normals_from(
                    control,
                    rows,
                    positions,
                    normals,
                    |r| offsets[r] as usize,
                    |e| {
                        // SAFETY: `e` is an entry of the table (`sum_rows`), and the tangent weights
                        // have one per entry (`with_tangent_weights`).
                        unsafe {
                            [
                                *self.weights.get_unchecked(e),
                                *t1.get_unchecked(e),
                                *t2.get_unchecked(e),
                            ]
                        }
                    },
                );
            }
        }
    }

    /// [`StencilTable::points_and_normals`] with the weights of row `r`'s entry `j` at
    /// `weights(weight_start(r) + j)`.
    #[inline(always)]
    fn points_and_normals_from(
        &self,
        control: &[[f32; 4]],
        rows: impl RowIds,
        positions: &mut [[f32; 3]],
        normals: &mut [[f32; 3]],
        weight_start: impl Fn(usize) -> usize,
        weights: impl Fn(usize) -> [f32; 3],
    ) {
        // Natively the normals go four at a time (`Normals`): one by one they were a third of
        // the horse's tagged limit frame. In wasm one at a time measured 1.05 times faster in
        // this loop.
        #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
        let mut normals = Normals::<false>::new(normals);
        let first = |r: usize| {
            let (start, end) = (self.offsets[r] as usize, self.offsets[r + 1] as usize);
            let c = if start < end { self.indices[start] as usize } else { usize::MAX };
            [Lanes::ZERO, Lanes::ZERO, Lanes::ZERO, control.get(c).map_or(Lanes::ZERO, Lanes::load)]
        };
        self.sum_rows::<2, _>(
            rows,
            first,
            weight_start,
            |[p, a, b, x0], e, w| {
                // SAFETY: `e` is an entry of the table (`sum_rows`), and entries name control
                // vertices below `num_control`, which the callers made `control` hold.
                let x = unsafe { control.get_unchecked(*self.indices.get_unchecked(e) as usize) };
                let [w, w1, w2] = weights(w);
                let x = Lanes::load(x);
                *p = p.add_lanes(x, w);
                let d = x.sub(*x0);
                *a = a.add_lanes(d, w1);
                *b = b.add_lanes(d, w2);
            },
            |i, [p, a, b, _]| {
                p.store_xyz(&mut positions[i]);
                #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
                {
                    normals[i] = crate::limit::normal(a.xyz(), b.xyz());
                }
                #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
                normals.push(i, a, b);
            },
        );
    }

    /// Writes into `out` the output values of `control` (`width` floats per control vertex:
    /// 3 for positions, any width for other vertex-varying data), one row per stencil: one
    /// sparse product, without allocating. `control` must hold `width` floats per control vertex
    /// and `out` `width` per stencil, else an [`Error::InvalidAttribute`] and `out` is untouched.
    /// Rows do not depend on each other, so they can be split among threads as they are.
    pub fn evaluate(&self, control: &[f32], width: usize, out: &mut [f32]) -> Result<()> {
        self.check_lengths(control.len(), width, out.len())?;
        match width {
            0 => {}
            1 => self.evaluate_n::<1>(control, out),
            2 => self.evaluate_n::<2>(control, out),
            3 => self.evaluate_xyz(control, out),
            4 => self.evaluate_n::<4>(control, out),
            _ => self.evaluate_rows(control, width, out),
        }
        Ok(())
    }

    /// An error unless `control` holds `width` floats per control vertex and `out` `width` per
    /// stencil.
    fn check_lengths(&self, control: usize, width: usize, out: usize) -> Result<()> {
        let expect = |what: &str, count: usize, len: usize| {
            if Some(len) == count.checked_mul(width) {
                Ok(())
            } else {
                Err(Error::InvalidAttribute(format!(
                    "stencil table: {what} has {len} floats; expected {width} per {} ({count} of them)",
                    if what == "control" { "control vertex" } else { "output vertex" }
                )))
            }
        };
        expect("control", self.num_control_vertices(), control)?;
        expect("out", self.num_stencils(), out)
    }

    /// [`StencilTable::evaluate`] for a width known at compile time: each row summed in
    /// registers.
    fn evaluate_n<const N: usize>(&self, control: &[f32], out: &mut [f32]) {
        let (control, _) = control.as_chunks::<N>();
        let (out, _) = out.as_chunks_mut::<N>();
        self.sum_rows::<4, _>(
            AllRows(self.num_stencils()),
            |_| [0.0f32; N],
            |r| self.offsets[r] as usize,
            |sum, e, _| {
                // SAFETY: as in `evaluate_xyz`.
                let (x, w) = unsafe { self.entry(control, e) };
                for k in 0..N {
                    sum[k] += x[k] * w;
                }
            },
            |i, sum| out[i] = sum,
        );
    }

    /// [`StencilTable::evaluate`] of points: the control points padded to four floats first, so
    /// that each entry is one 128-bit load and one multiply-add (wasm `simd128`, SSE) instead
    /// of three scalar ones; the padding costs one pass over the (much smaller) control array.
    fn evaluate_xyz(&self, control: &[f32], out: &mut [f32]) {
        let (out, _) = out.as_chunks_mut::<3>();
        self.points(&pad(control), AllRows(self.num_stencils()), out);
    }

    /// The positions of the rows `rows` names from control points padded by [`pad`].
    pub(crate) fn points(&self, control: &[[f32; 4]], rows: impl RowIds, out: &mut [[f32; 3]]) {
        self.each_point(control, rows, |i, sum| sum.store_xyz(&mut out[i]));
    }

    /// Every row's point, padded as [`pad`] pads (for a table whose outputs are another sum's
    /// control points: `crate::regular_rings`). The rows come in order, so the points are
    /// pushed rather than written over zeros.
    pub(crate) fn points_padded(&self, control: &[[f32; 4]]) -> Vec<[f32; 4]> {
        let mut out = Vec::with_capacity(self.num_stencils());
        self.each_point(control, AllRows(self.num_stencils()), |_, sum| out.push(sum.xyzw()));
        out
    }

    /// The sum of each row `rows` names, handed to `store(row, sum)`.
    #[inline(always)]
    fn each_point(&self, control: &[[f32; 4]], rows: impl RowIds, store: impl FnMut(usize, Lanes)) {
        self.sum_rows::<4, _>(
            rows,
            |_| Lanes::ZERO,
            |r| self.offsets[r] as usize,
            |sum, e, _| {
                // SAFETY: `e` is an entry of the table (`sum_rows`), and every control index of
                // a table is below its `num_control` (the rows are built from the control
                // vertices' own stencils); the callers made `control` hold `num_control`
                // points.
                let (x, w) = unsafe { self.entry(control, e) };
                *sum = sum.add_scaled(x, w);
            },
            store,
        );
    }

    /// The control value and weight of entry `e`.
    ///
    /// # Safety
    /// `e` must be below the number of entries and `control` must hold `num_control` values.
    #[inline(always)]
    unsafe fn entry<'a, T>(&self, control: &'a [T], e: usize) -> (&'a T, f32) {
        debug_assert!(e < self.indices.len() && control.len() == self.num_control as usize);
        unsafe {
            let c = *self.indices.get_unchecked(e) as usize;
            (control.get_unchecked(c), *self.weights.get_unchecked(e))
        }
    }

    /// Sums the rows `ids` names, in its order: each from `start(row)`, `add(sum, e, w)` for
    /// each of its entries `e` in order, and hands each finished sum to `store(row, sum)`. `w`
    /// is where the entry's weights are when they are not the table's own: the row's
    /// `weight_start(row)` plus the entry's place in the row (see [`SharedWeights`]).
    ///
    /// `N` rows are summed side by side: each sum is a chain of dependent additions, whose
    /// latency (not memory) bounds one row at a time; several chains in flight keep the adder
    /// busy. Two rows gave 1.35× over one natively on the 100k-quad torus at level 2; four gave
    /// another 1.08× in wasm for one sum per row, but cost 5 % with the three sums of a row with
    /// tangents (twelve in flight are more than the registers). Each row still adds its own
    /// entries in their order, so the results are bit-identical to one row at a time.
    #[inline(always)]
    fn sum_rows<const N: usize, S: Copy>(
        &self,
        ids: impl RowIds,
        start: impl Fn(usize) -> S,
        weight_start: impl Fn(usize) -> usize,
        mut add: impl FnMut(&mut S, usize, usize),
        mut store: impl FnMut(usize, S),
    ) {
        let offsets = &self.offsets;
        let count = ids.count();
        let row = |k: usize| ids.row(k);
        let mut i = 0;
        while i + N <= count {
            let rows: [usize; N] = std::array::from_fn(|k| row(i + k));
            let starts = rows.map(|r| offsets[r] as usize);
            let ends = rows.map(|r| offsets[r + 1] as usize);
            let weights = rows.map(&weight_start);
            let common = (0..N).map(|k| ends[k] - starts[k]).min().unwrap_or(0);
            let mut sums = rows.map(&start);
            for j in 0..common {
                for k in 0..N {
                    add(&mut sums[k], starts[k] + j, weights[k] + j);
                }
            }
            for k in 0..N {
                let shift = weights[k].wrapping_sub(starts[k]);
                (starts[k] + common..ends[k])
                    .for_each(|e| add(&mut sums[k], e, e.wrapping_add(shift)));
            }
            for (k, sum) in sums.into_iter().enumerate() {
                store(rows[k], sum);
            }
            i += N;
        }
        for k in i..count {
            let r = row(k);
            let mut sum = start(r);
            let shift = weight_start(r).wrapping_sub(offsets[r] as usize);
            (offsets[r] as usize..offsets[r + 1] as usize)
                .for_each(|e| add(&mut sum, e, e.wrapping_add(shift)));
            store(r, sum);
        }
    }

    /// [`StencilTable::evaluate`] for any width.
    fn evaluate_rows(&self, control: &[f32], width: usize, out: &mut [f32]) {
        for (row, value) in self.offsets.windows(2).zip(out.chunks_exact_mut(width)) {
            let range = row[0] as usize..row[1] as usize;
            value.fill(0.0);
            for (&c, &w) in self.indices[range.clone()].iter().zip(&self.weights[range]) {
                let start = c as usize * width;
                for (s, &x) in value.iter_mut().zip(&control[start..start + width]) {
                    *s += x * w;
                }
            }
        }
    }
}

/// Points an evaluator makes in closed form from the padded control points rather than from
/// their rows: Catmull-Clark's regular patches (`crate::patches`), Loop's regular rings
/// (`crate::regular_rings`). The table's rows give the others.
pub(crate) trait ClosedForms {
    /// The output vertices left to the rows, ascending.
    fn rest(&self) -> &[u32];
    /// Writes the closed forms' points.
    fn points(&self, control: &[[f32; 4]], positions: &mut [[f32; 3]]);
    /// Writes the closed forms' points and unit normals ([`crate::limit::normal`]).
    fn points_and_normals(
        &self,
        control: &[[f32; 4]],
        positions: &mut [[f32; 3]],
        normals: &mut [[f32; 3]],
    );
}

/// Which rows of a table a sum runs over: all of them, or a list (those no patch gives, see
/// [`crate::patches`]). A type each, so that the loop over all rows has no list to read.
pub(crate) trait RowIds: Copy {
    fn count(self) -> usize;
    fn row(self, k: usize) -> usize;
}

/// The first `n` rows, in order.
#[derive(Clone, Copy)]
pub(crate) struct AllRows(pub usize);

impl RowIds for AllRows {
    #[inline(always)]
    fn count(self) -> usize {
        self.0
    }

    #[inline(always)]
    fn row(self, k: usize) -> usize {
        k
    }
}

impl RowIds for &[u32] {
    #[inline(always)]
    fn count(self) -> usize {
        self.len()
    }

    #[inline(always)]
    fn row(self, k: usize) -> usize {
        self[k] as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(offsets: Vec<u32>, indices: Vec<u32>, weights: Vec<f32>) -> StencilTable {
        StencilTable { num_control: 5, offsets, indices, weights, tangent_weights: None }
    }

    /// Refined rows moved onto the entries of limit rows that hold them keep every weight at
    /// its control vertex and put 0 on the others; a refined row with a control vertex its
    /// limit row lacks gives the limit table back, unchanged.
    #[test]
    fn positions_go_onto_entries_that_hold_them() {
        let limit = table(vec![0, 3, 5], vec![4, 0, 2, 1, 3], vec![0.5, 0.25, 0.25, 0.6, 0.4]);
        let refined = table(vec![0, 2, 3], vec![0, 4, 3], vec![0.75, 0.25, 1.0]);
        let shared = limit.clone().with_positions_of(&refined).ok().unwrap();
        assert_eq!(shared.indices, limit.indices);
        assert_eq!(shared.offsets, limit.offsets);
        assert_eq!(shared.weights, [0.25, 0.75, 0.0, 0.0, 1.0]);
        let outside = StencilTable { indices: vec![0, 4, 2], ..refined };
        let back = limit.clone().with_positions_of(&outside).err().unwrap();
        assert_eq!(back, limit);
    }
}
