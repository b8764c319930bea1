//! The rows of a stencil table while the levels run: `Stencils` is the vertex-varying data the
//! hosts refine, and `StencilSum` the [`Weights`] sink that composes a new row from its
//! parents' rows (see the parent module).

use super::StencilTable;
use crate::error::{Error, Result};
use crate::mesh::HalfEdgeMesh;
use crate::primvar::{LimitSources, Primvar};
use crate::rules::Weights;

/// The stencils of one level's vertices while the levels run: for vertex `i`, the control
/// vertices `indices[s..s + n]` and their `weights`, where `[s, n] = spans[i]`. Rows are
/// appended in the order the hosts make them; a host that places rows out of order
/// ([`Primvar::set`], √3) leaves the data out of row order, which [`Stencils::into_table`]
/// puts right.
///
/// `limit` is the most entries (index and weight pairs) one level may hold; a row that would
/// pass it is left empty and marks the stencils `overflowed` (which propagates to every level
/// made from them), so that the call can refuse the table instead of exhausting memory.
#[derive(Clone, Debug, Default)]
pub(crate) struct Stencils {
    spans: Vec<[u32; 2]>,
    indices: Vec<u32>,
    weights: Vec<f32>,
    /// Number of control vertices (the base level's vertices).
    num_control: usize,
    limit: usize,
    overflowed: bool,
}

/// No stencils: the face points of a host whose rules weight none.
static NO_STENCILS: Stencils = Stencils {
    spans: Vec::new(),
    indices: Vec::new(),
    weights: Vec::new(),
    num_control: 0,
    limit: 0,
    overflowed: false,
};

impl Stencils {
    /// The control vertices themselves: vertex `i` is control vertex `i` with weight 1. At most
    /// `limit` entries per level (see [`Stencils`]).
    pub(crate) fn identity(count: usize, limit: usize) -> Self {
        Self::one_each((0..count as u32).collect(), limit)
    }

    /// The control vertices of a base mesh whose vertex `i` is control vertex `controls[i]`
    /// (a permutation), with weight 1: rows made from these name the control vertices.
    pub(crate) fn named(controls: &[u32], limit: usize) -> Self {
        Self::one_each(controls.to_vec(), limit)
    }

    /// Row `i` control vertex `controls[i]` with weight 1.
    fn one_each(controls: Vec<u32>, limit: usize) -> Self {
        let count = controls.len();
        let limit = limit.min(u32::MAX as usize);
        if count > limit {
            return Stencils { num_control: count, limit, overflowed: true, ..Stencils::default() };
        }
        Stencils {
            spans: (0..count as u32).map(|i| [i, 1]).collect(),
            indices: controls,
            weights: vec![1.0; count],
            num_control: count,
            limit,
            overflowed: false,
        }
    }

    /// `capacity` rows after these, at most `limit` entries.
    fn with_capacity_within(&self, capacity: usize, limit: usize) -> Self {
        // A child row combines a few parent rows and is longer than they are, by fewer
        // entries at each level (the supports converge): 1.5 times the parent's average and 6
        // more is above what Catmull-Clark and Loop make at levels 1-3 (6.25 per row at level
        // 1, 10.6 at level 2), so the arrays are not moved while they grow; `into_table` gives
        // back what is left.
        let average = self.indices.len().checked_div(self.spans.len()).unwrap_or(1);
        let entries = capacity.saturating_mul(average + average / 2 + 6).min(limit);
        Stencils {
            spans: Vec::with_capacity(capacity),
            indices: Vec::with_capacity(entries),
            weights: Vec::with_capacity(entries),
            num_control: self.num_control,
            limit,
            overflowed: self.overflowed,
        }
    }

    /// The stencil of vertex `i`.
    fn row(&self, i: usize) -> (&[u32], &[f32]) {
        let [start, len] = self.spans[i];
        let range = start as usize..start as usize + len as usize;
        // Every span of rows with entries lies within both arrays; shared-weight rows (whose
        // entries are another's, see `emit`) are never read, and read as empty.
        match (self.indices.get(range.clone()), self.weights.get(range)) {
            (Some(controls), Some(weights)) => (controls, weights),
            _ => (&[], &[]),
        }
    }

    /// Appends one row's data: the control vertices `touched`, in the order the row first
    /// reached them, with their weights in `sums`; returns the row's span, or an empty one (and
    /// marks the overflow) when the row would pass the limit. Rows are not sorted: a sort per
    /// row was 13 % of the build in wasm, and only the merge of `StencilTable::with_tangents`
    /// needs order (it sorts the rows it merges).
    fn append_row(&mut self, touched: &[u32], sums: &[(f32, u32)]) -> [u32; 2] {
        let start = self.indices.len();
        if start + touched.len() > self.limit {
            self.overflowed = true;
            return [start as u32, 0];
        }
        // Whole slices, so that the copies run without a capacity check per entry; a weight
        // that cancelled to zero (rare) is taken out after.
        self.indices.extend_from_slice(touched);
        let mut zero = false;
        let written = self.weights.len() + touched.len();
        self.weights.reserve(touched.len());
        let room = &mut self.weights.spare_capacity_mut()[..touched.len()];
        for (to, &c) in room.iter_mut().zip(touched) {
            debug_assert!((c as usize) < sums.len());
            // SAFETY: a row names control vertices only (below `num_control`, the length of
            // `sums`; see `StencilSum::gather`).
            let w = unsafe { sums.get_unchecked(c as usize).0 };
            zero |= w == 0.0;
            to.write(w);
        }
        // SAFETY: the loop wrote the `touched.len()` floats after the old length.
        unsafe { self.weights.set_len(written) };
        if zero {
            let mut kept = start;
            for k in start..self.weights.len() {
                if self.weights[k] != 0.0 {
                    self.indices[kept] = self.indices[k];
                    self.weights[kept] = self.weights[k];
                    kept += 1;
                }
            }
            self.indices.truncate(kept);
            self.weights.truncate(kept);
        }
        [start as u32, (self.indices.len() - start) as u32]
    }

    /// The weights of rows that share another's entries (the tangent rows of
    /// [`Primvar::limit_rows`]), in row order; the stencils themselves when they have entries of their own.
    pub(crate) fn into_shared_weights(self) -> std::result::Result<Vec<f32>, Self> {
        if self.indices.is_empty() && !self.weights.is_empty() && !self.overflowed {
            Ok(self.weights)
        } else {
            Err(self)
        }
    }

    /// The table of these stencils in row order; an [`Error::TooLarge`] when a limit was
    /// reached (`what` names the call for the message).
    pub(crate) fn into_table(self, what: impl FnOnce() -> String) -> Result<StencilTable> {
        if self.overflowed {
            return Err(Error::TooLarge(what()));
        }
        let mut offsets = Vec::with_capacity(self.spans.len() + 1);
        offsets.push(0u32);
        let mut end = 0u32;
        let in_order = self.spans.iter().all(|&[start, len]| {
            let next = start == end;
            end = start + len;
            next
        });
        let (indices, weights) = if in_order && end as usize == self.indices.len() {
            offsets.extend(self.spans.iter().map(|&[start, len]| start + len));
            let (mut indices, mut weights) = (self.indices, self.weights);
            indices.shrink_to_fit();
            weights.shrink_to_fit();
            (indices, weights)
        } else {
            let mut indices = Vec::with_capacity(self.indices.len());
            let mut weights = Vec::with_capacity(self.weights.len());
            for i in 0..self.spans.len() {
                let (c, w) = self.row(i);
                indices.extend_from_slice(c);
                weights.extend_from_slice(w);
                offsets.push(indices.len() as u32);
            }
            (indices, weights)
        };
        let num_control = self.num_control as u32;
        Ok(StencilTable { num_control, offsets, indices, weights, tangent_weights: None })
    }
}

/// The [`Weights`] sink that composes stencils: a source's weight times the source's stencil
/// (a parent vertex's, or a child face point's), summed per control vertex in a dense array
/// (`sums`, one slot per control vertex, in f32 as OpenSubdiv's stencil builder sums them: f64
/// was 5 % slower in wasm and changed no test's outcome) whose slots a row has touched are
/// listed in `touched`; `stamp` marks a slot as
/// belonging to the current row, so nothing is cleared between rows. No sort of the gathered
/// products and no hashing: only the row's distinct control vertices are sorted.
pub(crate) struct StencilSum<'a> {
    parent: &'a Stencils,
    he_from: &'a [u32],
    face_points: &'a Stencils,
    /// Per control vertex, the row's sum and the stamp of the row that last wrote it (side by
    /// side: one cache line per touch).
    sums: Vec<(f32, u32)>,
    stamp: u32,
    /// The row's control vertices, `touched[..count]`: one slot per control vertex, so that
    /// listing one needs no capacity check.
    touched: Vec<u32>,
    count: usize,
    /// The product of the scales of the open groups.
    scale: f32,
    /// The parents' overflow, passed on to every row made from them.
    overflowed: bool,
}

impl StencilSum<'_> {
    /// Adds `weight` times row `i` of `source`. The sums, the touched list and the stamp are
    /// taken into locals first: as fields of `self` they were read again after every store
    /// (the stores might have changed them, as far as LLVM could tell), in wasm twice the work.
    #[inline]
    fn gather(&mut self, source: &Stencils, i: usize, weight: f32) {
        let weight = weight * self.scale;
        let (controls, weights) = source.row(i);
        let stamp = self.stamp;
        let sums = &mut self.sums[..];
        let touched = &mut self.touched[..];
        let mut count = self.count;
        for (&c, &w) in controls.iter().zip(weights) {
            let product = w * weight;
            debug_assert!((c as usize) < sums.len());
            // SAFETY: a row names control vertices only (below `num_control`, the length of
            // `sums` and of `touched`), and lists each at most once, so `count` is below
            // `touched.len()` when a control vertex is listed. Without these two bounds checks
            // per entry, the build of the horse's level-2 Catmull-Clark table took 14 % less
            // time in wasm.
            let entry = unsafe { sums.get_unchecked_mut(c as usize) };
            if entry.1 == stamp {
                entry.0 += product;
            } else {
                *entry = (product, stamp);
                debug_assert!(count < touched.len());
                unsafe { *touched.get_unchecked_mut(count) = c };
                count += 1;
            }
        }
        self.count = count;
    }

    /// Runs `rule` and appends the row it gives to `out`; returns the row's span.
    fn row_into(&mut self, out: &mut Stencils, rule: impl FnOnce(&mut Self)) -> [u32; 2] {
        out.overflowed |= self.overflowed;
        if out.overflowed {
            // Refused already: the rule is not run (see `limit_rows`).
            return [out.indices.len() as u32, 0];
        }
        self.count = 0;
        self.scale = 1.0;
        if self.stamp == u32::MAX {
            self.sums.iter_mut().for_each(|e| e.1 = 0);
            self.stamp = 0;
        }
        self.stamp += 1;
        rule(self);
        out.append_row(&self.touched[..self.count], &self.sums)
    }
}

impl Weights for StencilSum<'_> {
    const FACE_POINTS_COST_MORE: bool = true;

    #[inline]
    fn vertex(&mut self, v: u32, weight: f32) {
        self.gather(self.parent, v as usize, weight);
    }

    #[inline]
    fn corner(&mut self, h: u32, weight: f32) {
        self.vertex(self.he_from[h as usize], weight);
    }

    #[inline]
    fn face_point(&mut self, c: u32, weight: f32) {
        self.gather(self.face_points, c as usize, weight);
    }

    /// The scale outside the group.
    type Group = f32;

    #[inline]
    fn begin_group(&mut self, scale: f32) -> f32 {
        let outer = self.scale;
        self.scale = outer * scale;
        outer
    }

    #[inline]
    fn end_group(&mut self, outer: f32) {
        self.scale = outer;
    }
}

impl Primvar for Stencils {
    type Sum<'a> = StencilSum<'a>;

    fn restart(&self, count: usize) -> Option<Self> {
        Some(Stencils::identity(count, self.limit))
    }

    fn sum<'a>(&'a self, he_from: &'a [u32], face_points: Option<&'a Self>) -> StencilSum<'a> {
        let face_points = face_points.unwrap_or(&NO_STENCILS);
        StencilSum {
            parent: self,
            he_from,
            face_points,
            sums: vec![(0.0, 0); self.num_control],
            stamp: 0,
            touched: vec![0; self.num_control],
            count: 0,
            scale: 1.0,
            overflowed: self.overflowed || face_points.overflowed,
        }
    }

    fn with_capacity(&self, capacity: usize) -> Self {
        self.with_capacity_within(capacity, self.limit)
    }

    fn push<'a>(&mut self, sum: &mut StencilSum<'a>, rule: impl FnOnce(&mut StencilSum<'a>)) {
        let span = sum.row_into(self, rule);
        self.spans.push(span);
    }

    fn extend_from(&mut self, other: &Self) {
        self.overflowed |= other.overflowed;
        if self.indices.len() + other.indices.len() > self.limit {
            self.overflowed = true;
            self.spans.extend(std::iter::repeat_n([0, 0], other.spans.len()));
            return;
        }
        let shift = self.indices.len() as u32;
        self.spans.extend(other.spans.iter().map(|&[start, len]| [start + shift, len]));
        self.indices.extend_from_slice(&other.indices);
        self.weights.extend_from_slice(&other.weights);
    }

    fn extend_zeroed(&mut self, count: usize) {
        self.spans.extend(std::iter::repeat_n([0, 0], count));
    }

    fn set<'a>(
        &mut self,
        i: usize,
        sum: &mut StencilSum<'a>,
        rule: impl FnOnce(&mut StencilSum<'a>),
    ) {
        let span = sum.row_into(self, rule);
        self.spans[i] = span;
    }

    fn is_empty(&self) -> bool {
        self.spans.is_empty()
    }

    fn overflowed(&self) -> bool {
        self.overflowed
    }

    /// The three rows of a vertex in one pass: the masks come merged per parent vertex, so
    /// that each parent row is read once and feeds three sums; the rows share their control
    /// vertices (a weight is kept as 0 where one mask does not reach a vertex the others do),
    /// which [`StencilTable::with_tangents`] then takes as they are.
    fn limit_rows(
        &self,
        mesh: &HalfEdgeMesh,
        masks: &mut dyn FnMut(u32, &mut LimitSources),
    ) -> (Self, [Self; 2]) {
        let n = mesh.num_vertices();
        // The tangent rows share the position rows' entries: they keep weights only (see
        // `Stencils::into_shared_weights`). An entry is then an index and three weights, 16
        // bytes where the limit counts 8: half as many fit.
        let positions = self.with_capacity_within(n, self.limit / 2);
        let weights_only = || Stencils {
            indices: Vec::new(),
            weights: Vec::with_capacity(positions.weights.capacity()),
            ..self.with_capacity(0)
        };
        let mut out = [weights_only(), weights_only(), positions];
        out.rotate_right(1);
        let mut sources = Vec::with_capacity(32);
        let mut sum = LimitSum {
            sums: vec![Slot::default(); self.num_control],
            touched: vec![0; self.num_control],
            stamp: 0,
        };
        for v in 0..n as u32 {
            let [a, b, c] = &mut out;
            let start = a.indices.len();
            // Once refused, the rest is not gathered: near a fan's hub every row is as long as
            // the hub's valence, and gathering them all took minutes.
            let count = (!a.overflowed && !self.overflowed)
                .then(|| {
                    sources.clear();
                    masks(v, &mut sources);
                    sum.next_row();
                    sum.gather(self, &sources)
                })
                .filter(|&count| start + count <= a.limit);
            match count {
                Some(count) => emit(&sum.touched[..count], &sum.sums, [a, b, c]),
                None => {
                    for rows in [&mut *a, &mut *b, &mut *c] {
                        rows.overflowed = true;
                        rows.spans.push([start as u32, 0]);
                    }
                }
            }
        }
        let [positions, first, second] = out;
        (positions, [first, second])
    }
}

/// The composition of [`Primvar::limit_rows`]: the rows of the level's vertices that one
/// vertex's three masks weight (merged per vertex) gathered into three sums per control vertex
/// at once.
struct LimitSum {
    /// Per control vertex, the row's sums and stamp.
    sums: Vec<Slot>,
    /// The row's control vertices, `touched[..count]`: one slot per control vertex, as in
    /// `StencilSum`.
    touched: Vec<u32>,
    stamp: u32,
}

impl LimitSum {
    /// Starts a row: a new stamp (clearing the stamps when they run out).
    fn next_row(&mut self) {
        if self.stamp == u32::MAX {
            self.sums.iter_mut().for_each(|s| *s = Slot::default());
            self.stamp = 0;
        }
        self.stamp += 1;
    }

    /// Adds up the rows of `level` that `sources` name, with their three weights; returns how
    /// many control vertices the row has (`touched[..count]`, in the order first reached, as
    /// `append_row`).
    fn gather(&mut self, level: &Stencils, sources: &[(u32, [f32; 3])]) -> usize {
        let stamp = self.stamp;
        let sums = &mut self.sums[..];
        let touched = &mut self.touched[..];
        let mut count = 0;
        for &(parent, w) in sources {
            let (controls, weights) = level.row(parent as usize);
            let w = Slot::masks(w);
            for (&c, &cw) in controls.iter().zip(weights) {
                debug_assert!((c as usize) < sums.len());
                // SAFETY: as in `StencilSum::gather`: rows name control vertices (below the
                // length of `sums` and `touched`), each listed once per row.
                if unsafe { sums.get_unchecked_mut(c as usize) }.add(w, cw, stamp) {
                    debug_assert!(count < touched.len());
                    unsafe { *touched.get_unchecked_mut(count) = c };
                    count += 1;
                }
            }
        }
        count
    }
}

/// Appends one limit row of `touched` with the three sums of each to `a` (entries
/// and the position's weights) and to `b`, `c` (the tangents' weights on the same entries); a
/// control vertex whose three sums cancelled is left out.
fn emit(touched: &[u32], sums: &[Slot], [a, b, c]: [&mut Stencils; 3]) {
    let start = a.indices.len();
    let count = touched.len();
    let lengths = [a.weights.len(), b.weights.len(), c.weights.len()];
    // One pass that reads each slot once and writes the four arrays in reserved room, through
    // local slices: in wasm, a pass per array took 12 ns per entry (a sixth of a limit table's
    // build), and a pass that wrote through the vectors reloaded their pointers per entry.
    a.indices.reserve(count);
    let indices = &mut a.indices.spare_capacity_mut()[..count];
    let [x, y, z] = [&mut a.weights, &mut b.weights, &mut c.weights].map(|w| {
        w.reserve(count);
        &mut w.spare_capacity_mut()[..count]
    });
    let mut kept = 0;
    for &control in touched {
        let w = sums.get(control as usize).map_or([0.0; 3], |slot| slot.sums);
        // `kept` counts the entries before this one that were kept: below `count`.
        if let (Some(i), Some(x), Some(y), Some(z)) =
            (indices.get_mut(kept), x.get_mut(kept), y.get_mut(kept), z.get_mut(kept))
        {
            i.write(control);
            x.write(w[0]);
            y.write(w[1]);
            z.write(w[2]);
        }
        kept += usize::from(w != [0.0; 3]);
    }
    // SAFETY: the loop wrote the first `kept` of the `count` entries reserved after `start`.
    unsafe { a.indices.set_len(start + kept) };
    for (rows, length) in [&mut *a, &mut *b, &mut *c].into_iter().zip(lengths) {
        // SAFETY: as above, the first `kept` of the `count` floats reserved after `length`.
        unsafe { rows.weights.set_len(length + kept) };
    }
    let span = [start as u32, kept as u32];
    for rows in [a, b, c] {
        rows.spans.push(span);
    }
}

/// Per control vertex, one limit row's three sums (the position and the two tangents) and, in
/// the fourth lane, the stamp of the row that last wrote them: a product is one 16-byte load
/// and store. The sums are f32, as OpenSubdiv's stencil builder keeps them: a limit row adds
/// about a hundred products of level rows that are already rounded to f32.
#[derive(Clone, Copy, Default)]
#[repr(C, align(16))]
struct Slot {
    sums: [f32; 3],
    stamp: u32,
}

/// The three masks' weights of one source, as [`Slot::add`] takes them.
#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
type Masks = core::arch::wasm32::v128;
#[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
type Masks = [f32; 3];

impl Slot {
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    #[inline(always)]
    fn masks([a, b, c]: [f32; 3]) -> Masks {
        core::arch::wasm32::f32x4(a, b, c, 0.0)
    }

    #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
    #[inline(always)]
    fn masks(w: [f32; 3]) -> Masks {
        w
    }

    /// Adds `weight` times `masks` to the sums of row `stamp` (starting them when the slot
    /// holds another row's); true when it started them.
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    #[inline(always)]
    fn add(&mut self, masks: Masks, weight: f32, stamp: u32) -> bool {
        use core::arch::wasm32::*;
        let at = (self as *mut Slot).cast::<v128>();
        // SAFETY: a `Slot` is 16 bytes, readable and writable through `self`.
        let old = unsafe { v128_load(at) };
        let product = f32x4_mul(masks, f32x4_splat(weight));
        let first = u32x4_extract_lane::<3>(old) != stamp;
        let sum = if first { product } else { f32x4_add(old, product) };
        // SAFETY: as above.
        unsafe { v128_store(at, u32x4_replace_lane::<3>(sum, stamp)) };
        first
    }

    /// The scalar `add`, for targets without `simd128`.
    #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
    #[inline(always)]
    fn add(&mut self, masks: Masks, weight: f32, stamp: u32) -> bool {
        let first = self.stamp != stamp;
        for (sum, mask) in self.sums.iter_mut().zip(masks) {
            let product = mask * weight;
            *sum = if first { product } else { *sum + product };
        }
        self.stamp = stamp;
        first
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;
    use crate::rules::Weights;

    /// Rows placed out of order ([`Primvar::set`]) come out of the table in row order.
    #[test]
    fn rows_set_out_of_order() {
        let control = Stencils::identity(3, 100);
        let mut sum = control.sum(&[], None);
        let mut rows = control.with_capacity(3);
        rows.push(&mut sum, |w| w.vertex(2, 1.0));
        rows.extend_zeroed(2);
        rows.set(2, &mut sum, |w| {
            w.scaled(0.5, |w| {
                w.vertex(1, 1.0);
                w.vertex(0, 1.0);
            })
        });
        rows.set(1, &mut sum, |w| {
            w.vertex(0, 0.25);
            w.vertex(2, 0.5);
            w.vertex(0, 0.25);
        });
        let table = rows.into_table(String::new).unwrap();
        assert_eq!(table.offsets(), &[0, 1, 3, 5]);
        // Each row's controls in the order the row first reached them.
        assert_eq!(table.indices(), &[2, 0, 2, 1, 0]);
        assert_eq!(table.weights(), &[1.0, 0.5, 0.5, 0.5, 0.5]);
        let mut out = [0.0; 3];
        table.evaluate(&[1.0, 10.0, 100.0], 1, &mut out).unwrap();
        assert_eq!(out, [100.0, 50.5, 5.5]);
    }

    /// A row past the entry limit marks the stencils, and the table is refused.
    #[test]
    fn the_limit_refuses_the_table() {
        let control = Stencils::identity(3, 4);
        let mut sum = control.sum(&[], None);
        let mut rows = control.with_capacity(2);
        rows.push(&mut sum, |w| w.vertex(0, 1.0));
        rows.push(&mut sum, |w| (0..3).for_each(|v| w.vertex(v, 1.0 / 3.0)));
        assert!(!rows.overflowed);
        rows.push(&mut sum, |w| w.vertex(1, 1.0));
        assert!(rows.overflowed);
        let err = rows.into_table(|| "too big".into()).unwrap_err();
        assert_eq!(err, Error::TooLarge("too big".into()));
        assert!(Stencils::identity(5, 4).overflowed);
    }
}
