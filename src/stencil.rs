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
//! [`Weights`] sink as for positions, and `StencilSum` composes their stencils (the base level
//! is the identity), so every path of the driver (every scheme, tags, holes, boundary modes)
//! gives its stencils without code of its own. [`crate::scheme::stencil_table`] is the entry point.

use crate::error::{Error, Result};
use crate::mesh::HalfEdgeMesh;
use crate::primvar::Primvar;
use crate::rules::{Source, Stencil, Weights};
use crate::shared_weights::SharedWeights;

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
        let limit = limit.min(u32::MAX as usize);
        if count > limit {
            return Stencils { num_control: count, limit, overflowed: true, ..Stencils::default() };
        }
        Stencils {
            spans: (0..count as u32).map(|i| [i, 1]).collect(),
            indices: (0..count as u32).collect(),
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
        self.weights.extend(touched.iter().map(|&c| {
            let w = sums[c as usize].0;
            zero |= w == 0.0;
            w
        }));
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
        self.count = 0;
        self.scale = 1.0;
        if self.stamp == u32::MAX {
            self.sums.iter_mut().for_each(|e| e.1 = 0);
            self.stamp = 0;
        }
        self.stamp += 1;
        rule(self);
        out.overflowed |= self.overflowed;
        out.append_row(&self.touched[..self.count], &self.sums)
    }
}

impl Weights for StencilSum<'_> {
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

    /// The three rows of a vertex in one pass: the masks are merged per parent vertex first, so
    /// that each parent row is read once and feeds three sums; the rows share their control
    /// vertices (a weight is kept as 0 where one mask does not reach a vertex the others do),
    /// which [`StencilTable::with_tangents`] then takes as they are.
    fn limit_rows(
        &self,
        mesh: &HalfEdgeMesh,
        masks: &mut dyn FnMut(u32, &mut [Stencil; 3]),
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
        let mut recorded: [Stencil; 3] = Default::default();
        let mut sum = LimitSum {
            sources: Vec::with_capacity(32),
            listed: vec![(0, 0); n],
            sums: vec![Slot::default(); self.num_control],
            touched: vec![0; self.num_control],
            stamp: 0,
        };
        for v in 0..n as u32 {
            recorded.iter_mut().for_each(|s| s.sources.clear());
            masks(v, &mut recorded);
            sum.next_row();
            sum.merge(mesh, &recorded);
            let count = sum.gather(self);
            let touched = &sum.touched[..count];
            let [a, b, c] = &mut out;
            let start = a.indices.len();
            if a.overflowed || self.overflowed || start + touched.len() > a.limit {
                for rows in [&mut *a, &mut *b, &mut *c] {
                    rows.overflowed = true;
                    rows.spans.push([start as u32, 0]);
                }
                continue;
            }
            emit(touched, &sum.sums, [a, b, c]);
        }
        let [positions, first, second] = out;
        (positions, [first, second])
    }
}

/// The composition of [`Primvar::limit_rows`]: one vertex's three masks (limit position, two
/// tangents) merged per source vertex of the level, then the sources' rows gathered into three
/// sums per control vertex at once.
struct LimitSum {
    /// The level's vertices the masks weight, with the three masks' weights of each.
    sources: Vec<(u32, [f32; 3])>,
    /// Per level vertex, the stamp of the row that last listed it in `sources`, and where.
    listed: Vec<(u32, u32)>,
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
            self.listed.iter_mut().for_each(|l| l.0 = 0);
            self.stamp = 0;
        }
        self.stamp += 1;
        self.sources.clear();
    }

    /// Lists the level vertices `masks` weight in `sources`, each once with its three weights.
    fn merge(&mut self, mesh: &HalfEdgeMesh, masks: &[Stencil; 3]) {
        let stamp = self.stamp;
        for (k, mask) in masks.iter().enumerate() {
            for &(source, weight) in &mask.sources {
                let parent = match source {
                    Source::Vertex(p) => p,
                    Source::Corner(h) => mesh.he_from[h as usize],
                    // Limit masks weight no face point.
                    Source::FacePoint(_) => continue,
                };
                let entry = &mut self.listed[parent as usize];
                if entry.0 == stamp {
                    self.sources[entry.1 as usize].1[k] += weight;
                } else {
                    *entry = (stamp, self.sources.len() as u32);
                    let mut w = [0.0; 3];
                    w[k] = weight;
                    self.sources.push((parent, w));
                }
            }
        }
    }

    /// Adds up the rows of `level` that `sources` name, weighted; returns how many control
    /// vertices the row has (`touched[..count]`, in the order first reached, as `append_row`).
    fn gather(&mut self, level: &Stencils) -> usize {
        let stamp = self.stamp;
        let sums = &mut self.sums[..];
        let touched = &mut self.touched[..];
        let mut count = 0;
        for &(parent, w) in &self.sources {
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
    // Whole slices, so that the copies run without a capacity check per entry (as
    // `Stencils::append_row`); an entry whose sums all cancelled (rare) is taken out after.
    a.indices.extend_from_slice(touched);
    for (k, rows) in [&mut *a, &mut *b, &mut *c].into_iter().enumerate() {
        rows.weights.extend(touched.iter().map(|&control| sums[control as usize].sums[k]));
    }
    if touched.iter().any(|&control| sums[control as usize].sums == [0.0; 3]) {
        let mut kept = start;
        for i in start..a.indices.len() {
            let w = [a.weights[i], b.weights[i], c.weights[i]];
            if w != [0.0; 3] {
                a.indices[kept] = a.indices[i];
                for (rows, w) in [&mut *a, &mut *b, &mut *c].into_iter().zip(w) {
                    rows.weights[kept] = w;
                }
                kept += 1;
            }
        }
        a.indices.truncate(kept);
        for rows in [&mut *a, &mut *b, &mut *c] {
            rows.weights.truncate(kept);
        }
    }
    let span = [start as u32, (a.indices.len() - start) as u32];
    for rows in [a, b, c] {
        rows.spans.push(span);
    }
}

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

impl StencilTable {
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
                positions[i] = p.xyz();
                normals[i] = crate::limit::normal(a.xyz(), b.xyz());
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
            |i, sum| out[i] = sum.xyz(),
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

/// Points of three floats as four (the fourth 0), for 128-bit loads.
pub(crate) fn pad(points: &[f32]) -> Vec<[f32; 4]> {
    points.as_chunks::<3>().0.iter().map(|&[x, y, z]| [x, y, z, 0.0]).collect()
}

/// Four f32 sums in one 128-bit register: a padded point times a weight, added, is one load,
/// one multiply and one add. In wasm they are spelled out with `simd128` intrinsics: written
/// as a loop over `[f32; 4]`, LLVM saw that the fourth lane is never stored and split the other
/// three into scalar multiply-adds, which V8 ran as such (three times the arithmetic of a point).
/// Multiply then add, lane by lane, as the scalar loop: the sums are bit-identical.
#[derive(Clone, Copy)]
pub(crate) struct Lanes(
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))] core::arch::wasm32::v128,
    #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))] [f32; 4],
);

impl Lanes {
    /// `self + x * w`.
    #[inline(always)]
    pub(crate) fn add_scaled(self, x: &[f32; 4], w: f32) -> Lanes {
        self.add_lanes(Lanes::load(x), w)
    }
}

#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
impl Lanes {
    pub(crate) const ZERO: Lanes = Lanes(core::arch::wasm32::f32x4(0.0, 0.0, 0.0, 0.0));

    /// A padded point in lanes.
    #[inline(always)]
    pub(crate) fn load(x: &[f32; 4]) -> Lanes {
        use core::arch::wasm32::{v128, v128_load};
        // SAFETY: `x` is 16 readable bytes; wasm loads need no alignment.
        Lanes(unsafe { v128_load(x.as_ptr().cast::<v128>()) })
    }

    /// `self - x`, lane by lane.
    #[inline(always)]
    pub(crate) fn sub(self, x: Lanes) -> Lanes {
        Lanes(core::arch::wasm32::f32x4_sub(self.0, x.0))
    }

    /// `self + x * w`, `x` in registers.
    #[inline(always)]
    pub(crate) fn add_lanes(self, x: Lanes, w: f32) -> Lanes {
        use core::arch::wasm32::{f32x4_add, f32x4_mul, f32x4_splat};
        Lanes(f32x4_add(self.0, f32x4_mul(x.0, f32x4_splat(w))))
    }

    /// The first three lanes.
    #[inline(always)]
    pub(crate) fn xyz(self) -> [f32; 3] {
        use core::arch::wasm32::f32x4_extract_lane;
        [
            f32x4_extract_lane::<0>(self.0),
            f32x4_extract_lane::<1>(self.0),
            f32x4_extract_lane::<2>(self.0),
        ]
    }
}

#[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
impl Lanes {
    pub(crate) const ZERO: Lanes = Lanes([0.0; 4]);

    /// A padded point in lanes.
    #[inline(always)]
    pub(crate) fn load(x: &[f32; 4]) -> Lanes {
        Lanes(*x)
    }

    /// `self - x`, lane by lane.
    #[inline(always)]
    pub(crate) fn sub(self, x: Lanes) -> Lanes {
        Lanes(std::array::from_fn(|k| self.0[k] - x.0[k]))
    }

    /// `self + x * w`, `x` in registers.
    #[inline(always)]
    pub(crate) fn add_lanes(self, x: Lanes, w: f32) -> Lanes {
        let mut sum = self.0;
        for (s, x) in sum.iter_mut().zip(x.0) {
            *s += x * w;
        }
        Lanes(sum)
    }

    /// The first three lanes.
    #[inline(always)]
    pub(crate) fn xyz(self) -> [f32; 3] {
        [self.0[0], self.0[1], self.0[2]]
    }
}

/// Unit normals of tangent pairs ([`crate::limit::normal`]), gathered in batches of [`BATCH`]
/// and made four at a time: in wasm the four cross products, lengths and divisions run side by
/// side in lanes, with exactly that function's f32 operations (the same results), and where
/// its test sends one of them to f64 all four go through it. The last ones are written when the
/// batch is dropped.
///
/// For the patches ([`crate::patches`]): 1.1 times faster per point there than one normal at a
/// time. A table's rows keep one normal at a time: this measured 1.05 times slower in their
/// loop with batches of four, and no faster with batches of 64.
pub(crate) struct Normals<'o> {
    out: &'o mut [[f32; 3]],
    rows: [usize; BATCH],
    tangents: [[Lanes; 2]; BATCH],
    len: usize,
}

/// Tangent pairs a [`Normals`] holds before it makes their normals, out of line: V8 compiles
/// the patches' loop worse with the normals' code inlined into it, and worse around a call
/// every fourth point than once per `BATCH` (the torus's limit frame with normals in
/// `bench/stencil_ab.mjs`: B/A 0.924 for the call out of line, then 0.936 for batches of 64
/// rather than four).
const BATCH: usize = 64;

impl<'o> Normals<'o> {
    pub(crate) fn new(out: &'o mut [[f32; 3]]) -> Self {
        Normals { out, rows: [0; BATCH], tangents: [[Lanes::ZERO; 2]; BATCH], len: 0 }
    }

    /// The normal of `first × second` goes to `row`.
    #[inline(always)]
    pub(crate) fn push(&mut self, row: usize, first: Lanes, second: Lanes) {
        // `len` is below `BATCH` here (a full batch is flushed at once); the remainder says so
        // to the compiler, which then checks no index.
        let at = self.len % BATCH;
        self.rows[at] = row;
        self.tangents[at] = [first, second];
        self.len = at + 1;
        if self.len == BATCH {
            self.flush();
        }
    }

    // Out of line: see `BATCH`.
    #[inline(never)]
    fn flush(&mut self) {
        let len = self.len;
        let (tangents, _) = self.tangents[..].as_chunks::<4>();
        let (rows, _) = self.rows[..].as_chunks::<4>();
        for (k, (tangents, rows)) in tangents.iter().zip(rows).enumerate().take(len.div_ceil(4)) {
            let normals = four_normals(tangents);
            for (&row, normal) in rows.iter().zip(normals).take(len - 4 * k) {
                if let Some(out) = self.out.get_mut(row) {
                    *out = normal;
                }
            }
        }
        self.len = 0;
    }
}

impl Drop for Normals<'_> {
    fn drop(&mut self) {
        self.flush();
    }
}

/// [`crate::limit::normal`] of four tangent pairs, in lanes (see [`Normals`]).
#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
#[inline(always)]
fn four_normals(tangents: &[[Lanes; 2]; 4]) -> [[f32; 3]; 4] {
    use core::arch::wasm32::*;
    // Four points' x, y and z, each in one register.
    let split = |v: [v128; 4]| {
        let low =
            [i32x4_shuffle::<0, 4, 1, 5>(v[0], v[1]), i32x4_shuffle::<0, 4, 1, 5>(v[2], v[3])];
        let high =
            [i32x4_shuffle::<2, 6, 3, 7>(v[0], v[1]), i32x4_shuffle::<2, 6, 3, 7>(v[2], v[3])];
        [
            i32x4_shuffle::<0, 1, 4, 5>(low[0], low[1]),
            i32x4_shuffle::<2, 3, 6, 7>(low[0], low[1]),
            i32x4_shuffle::<0, 1, 4, 5>(high[0], high[1]),
        ]
    };
    let [ax, ay, az] = split(tangents.map(|[a, _]| a.0));
    let [bx, by, bz] = split(tangents.map(|[_, b]| b.0));
    let (mul, sub, add) = (f32x4_mul, f32x4_sub, f32x4_add);
    let nx = sub(mul(ay, bz), mul(az, by));
    let ny = sub(mul(az, bx), mul(ax, bz));
    let nz = sub(mul(ax, by), mul(ay, bx));
    let length2 = add(add(mul(nx, nx), mul(ny, ny)), mul(nz, nz));
    let a2 = add(add(mul(ax, ax), mul(ay, ay)), mul(az, az));
    let b2 = add(add(mul(bx, bx), mul(by, by)), mul(bz, bz));
    let scale2 = mul(a2, b2);
    let good = v128_and(
        v128_and(
            f32x4_ge(length2, mul(f32x4_splat(0.01), scale2)),
            f32x4_gt(length2, f32x4_splat(1e-30)),
        ),
        f32x4_lt(scale2, f32x4_splat(1e30)),
    );
    if !i32x4_all_true(good) {
        return tangents.map(|[a, b]| crate::limit::normal(a.xyz(), b.xyz()));
    }
    let inverse = f32x4_div(f32x4_splat(1.0), f32x4_sqrt(length2));
    let [x, y, z] = [nx, ny, nz].map(|c| Lanes(mul(c, inverse)));
    let lanes = |v: Lanes| -> [f32; 4] {
        [
            f32x4_extract_lane::<0>(v.0),
            f32x4_extract_lane::<1>(v.0),
            f32x4_extract_lane::<2>(v.0),
            f32x4_extract_lane::<3>(v.0),
        ]
    };
    let [x, y, z] = [lanes(x), lanes(y), lanes(z)];
    std::array::from_fn(|k| [x[k], y[k], z[k]])
}

/// [`crate::limit::normal`] of four tangent pairs.
#[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
#[inline(always)]
fn four_normals(tangents: &[[Lanes; 2]; 4]) -> [[f32; 3]; 4] {
    tangents.map(|[a, b]| crate::limit::normal(a.xyz(), b.xyz()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A batch of normals writes each pushed pair's [`crate::limit::normal`] to its row, bit for
    /// bit, for counts below, at and past a batch and rows in any order; rows never pushed keep
    /// what they held. Also a wasm test: there the normals are made in lanes.
    #[cfg_attr(target_arch = "wasm32", wasm_bindgen_test::wasm_bindgen_test)]
    #[cfg_attr(not(target_arch = "wasm32"), test)]
    fn normals_in_batches_are_each_pairs_normal() {
        for count in [1, 3, 4, 5, BATCH - 1, BATCH, BATCH + 1, 2 * BATCH + 7] {
            let rows = count + 2;
            let mut out = vec![[9.0f32; 3]; rows];
            // Every third pair along one line (its normal is zero, through the f64 path), the
            // others at varied angles and lengths.
            let pair = |k: usize| {
                let t = k as f32 * 0.37;
                let a = [t.cos(), t.sin(), 0.25 * k as f32];
                let b =
                    if k.is_multiple_of(3) { a.map(|x| 2.0 * x) } else { [-t.sin(), t.cos(), 1.0] };
                (a, b)
            };
            // Pushed in reverse row order, skipping rows 0 and 1.
            let order: Vec<usize> = (2..rows).rev().collect();
            {
                let mut normals = Normals::new(&mut out);
                for (k, &row) in order.iter().enumerate() {
                    let (a, b) = pair(k);
                    let lanes = |v: [f32; 3]| Lanes::load(&[v[0], v[1], v[2], 0.0]);
                    normals.push(row, lanes(a), lanes(b));
                }
            }
            assert_eq!(out[0], [9.0; 3], "count {count}");
            assert_eq!(out[1], [9.0; 3], "count {count}");
            for (k, &row) in order.iter().enumerate() {
                let (a, b) = pair(k);
                let expected = crate::limit::normal(a, b);
                assert_eq!(
                    out[row].map(f32::to_bits),
                    expected.map(f32::to_bits),
                    "count {count}, pair {k}"
                );
            }
        }
    }

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
