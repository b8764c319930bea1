//! Applying the rules' weights to data (OpenSubdiv's `Far::PrimvarRefiner`): the sinks that turn
//! a new point's [`Weights`] into a value, for positions and for rows of any width.

use crate::mesh::HalfEdgeMesh;
use crate::rules::Weights;
use std::borrow::Cow;

/// The groups of a sink that multiplies each weight by the product of the open groups' scales
/// as it comes (`self.scale`), rather than setting a sum aside: a row is wider than a register.
macro_rules! scaled_groups {
    () => {
        /// The scale outside the group.
        type Group = f32;

        #[inline(always)]
        fn begin_group(&mut self, scale: f32) -> f32 {
            let outer = self.scale;
            self.scale = outer * scale;
            outer
        }

        #[inline(always)]
        fn end_group(&mut self, outer: f32) {
            self.scale = outer;
        }
    };
}

/// Sums weighted points of `W` floats (positions, or every vertex-numbered channel of a level
/// packed side by side, see [`pack_points`]): the parent level's `points` by vertex, corners
/// through `he_from`, and the child level's `face_points` by cell. The sum stays in registers;
/// a group sets it aside and scales its own sum at the end, lane by lane, so that each lane sums
/// exactly as it would alone (positions packed with other channels stay bit for bit those
/// refined alone).
pub struct PointSum<'a, const W: usize = 3> {
    pub points: &'a [[f32; W]],
    pub he_from: &'a [u32],
    pub face_points: &'a [[f32; W]],
    pub sum: [f32; W],
}

impl<'a, const W: usize> PointSum<'a, W> {
    #[inline(always)]
    pub fn new(points: &'a [[f32; W]], he_from: &'a [u32], face_points: &'a [[f32; W]]) -> Self {
        PointSum { points, he_from, face_points, sum: [0.0; W] }
    }

    /// The point whose weights `rule` gives.
    #[inline(always)]
    pub fn eval(&mut self, rule: impl FnOnce(&mut Self)) -> [f32; W] {
        self.sum = [0.0; W];
        rule(self);
        self.sum
    }

    #[inline(always)]
    fn add(&mut self, point: &[f32; W], weight: f32) {
        for (s, &x) in self.sum.iter_mut().zip(point) {
            *s += x * weight;
        }
    }
}

impl<const W: usize> Weights for PointSum<'_, W> {
    #[inline(always)]
    fn vertex(&mut self, v: u32, weight: f32) {
        let points = self.points;
        self.add(&points[v as usize], weight);
    }

    #[inline(always)]
    fn corner(&mut self, h: u32, weight: f32) {
        self.vertex(self.he_from[h as usize], weight);
    }

    #[inline(always)]
    fn face_point(&mut self, c: u32, weight: f32) {
        let face_points = self.face_points;
        self.add(&face_points[c as usize], weight);
    }

    /// The sum before the group, and the group's scale.
    type Group = ([f32; W], f32);

    #[inline(always)]
    fn begin_group(&mut self, scale: f32) -> ([f32; W], f32) {
        (std::mem::replace(&mut self.sum, [0.0; W]), scale)
    }

    #[inline(always)]
    fn end_group(&mut self, (outer, scale): ([f32; W], f32)) {
        for (s, o) in self.sum.iter_mut().zip(outer) {
            *s = o + *s * scale;
        }
    }
}

/// Sums weighted rows of `width` floats per vertex (every vertex-varying channel side by side):
/// the parent level's `rows` by vertex, corners through `he_from`, and the child level's
/// `face_rows` by cell, into `sum`. A group multiplies the weights inside it as they come (no
/// sum is set aside: a row is wider than a register).
pub struct RowSum<'a> {
    pub rows: &'a [f32],
    pub width: usize,
    pub he_from: &'a [u32],
    pub face_rows: &'a [f32],
    pub sum: Vec<f32>,
    /// The product of the scales of the open groups.
    scale: f32,
}

impl<'a> RowSum<'a> {
    pub fn new(rows: &'a [f32], width: usize, he_from: &'a [u32], face_rows: &'a [f32]) -> Self {
        RowSum { rows, width, he_from, face_rows, sum: vec![0.0; width], scale: 1.0 }
    }

    /// Appends to `out` the row whose weights `rule` gives.
    #[inline]
    pub fn eval_into(&mut self, out: &mut Vec<f32>, rule: impl FnOnce(&mut Self)) {
        match &mut self.sum[..] {
            [x] => *x = 0.0,
            [x, y] => [*x, *y] = [0.0; 2],
            [x, y, z] => [*x, *y, *z] = [0.0; 3],
            sum => sum.fill(0.0),
        }
        rule(self);
        // Constant lengths for the common widths: no memcpy call per row.
        match self.sum[..] {
            [x] => out.push(x),
            [x, y] => out.extend_from_slice(&[x, y]),
            [x, y, z] => out.extend_from_slice(&[x, y, z]),
            [x, y, z, w] => out.extend_from_slice(&[x, y, z, w]),
            _ => out.extend_from_slice(&self.sum),
        }
    }

    /// `sum += weight * row`. The common widths (a scalar, UVs, a colour, four skin weights)
    /// get unrolled bodies: a loop over three floats cost more than the sums themselves.
    #[inline(always)]
    pub(crate) fn add(sum: &mut [f32], row: &[f32], weight: f32) {
        match sum.len() {
            1 => add_n::<1>(sum, row, weight),
            2 => add_n::<2>(sum, row, weight),
            3 => add_n::<3>(sum, row, weight),
            4 => add_n::<4>(sum, row, weight),
            _ => {
                for (s, &x) in sum.iter_mut().zip(row) {
                    *s += x * weight;
                }
            }
        }
    }
}

#[inline(always)]
fn add_n<const N: usize>(sum: &mut [f32], row: &[f32], weight: f32) {
    if let (Some(sum), Some(row)) = (sum.first_chunk_mut::<N>(), row.first_chunk::<N>()) {
        for k in 0..N {
            sum[k] += row[k] * weight;
        }
    }
}

impl Weights for RowSum<'_> {
    #[inline]
    fn vertex(&mut self, v: u32, weight: f32) {
        let start = v as usize * self.width;
        let row = &self.rows[start..start + self.width];
        Self::add(&mut self.sum, row, weight * self.scale);
    }

    #[inline]
    fn corner(&mut self, h: u32, weight: f32) {
        self.vertex(self.he_from[h as usize], weight);
    }

    #[inline]
    fn face_point(&mut self, c: u32, weight: f32) {
        let start = c as usize * self.width;
        let row = &self.face_rows[start..start + self.width];
        Self::add(&mut self.sum, row, weight * self.scale);
    }

    scaled_groups!();
}

/// The widest row a [`FVarSum`] sums (face-varying channels are grouped up to it; no channel
/// is wider, see `attributes::MAX_ITEM_SIZE`).
pub const FVAR_MAX_WIDTH: usize = 16;

/// Sums weighted rows of a face-varying channel (`width` floats per value, at most
/// [`FVAR_MAX_WIDTH`], summed in a fixed array: no allocation per value) for one new value whose vertex topology matches the
/// surface's: corners resolve through `corner_values` (the value each parent face corner
/// sees), face points are the child level's `face_values` by cell, and a rule's `vertex(v)` is
/// the value `ends` gives for `v` (the moving vertex's value, or an edge's end values as one of
/// its faces sees them).
pub struct FVarSum<'a> {
    values: &'a [f32],
    width: usize,
    corner_values: &'a [u32],
    face_values: &'a [f32],
    ends: [(u32, u32); 2],
    sum: [f32; FVAR_MAX_WIDTH],
    scale: f32,
}

impl<'a> FVarSum<'a> {
    pub fn new(
        values: &'a [f32],
        width: usize,
        corner_values: &'a [u32],
        face_values: &'a [f32],
    ) -> Self {
        let width = width.min(FVAR_MAX_WIDTH);
        let sum = [0.0; FVAR_MAX_WIDTH];
        FVarSum { values, width, corner_values, face_values, ends: [(0, 0); 2], sum, scale: 1.0 }
    }

    /// Writes into `out` the value whose weights `rule` gives, with `ends` resolving
    /// [`Weights::vertex`].
    #[inline(always)]
    pub fn eval_into(
        &mut self,
        out: &mut [f32],
        ends: [(u32, u32); 2],
        rule: impl FnOnce(&mut Self),
    ) {
        self.ends = ends;
        let width = self.width;
        self.sum[..width].fill(0.0);
        rule(self);
        out[..width].copy_from_slice(&self.sum[..width]);
    }

    #[inline(always)]
    fn add_row(&mut self, source: &[f32], index: usize, weight: f32) {
        let width = self.width;
        let row = &source[index * width..(index + 1) * width];
        let weight = weight * self.scale;
        for (s, &x) in self.sum[..width].iter_mut().zip(row) {
            *s += x * weight;
        }
    }
}

impl Weights for FVarSum<'_> {
    #[inline(always)]
    fn vertex(&mut self, v: u32, weight: f32) {
        let value = if self.ends[0].0 == v { self.ends[0].1 } else { self.ends[1].1 };
        self.add_row(self.values, value as usize, weight);
    }

    #[inline(always)]
    fn corner(&mut self, h: u32, weight: f32) {
        self.add_row(self.values, self.corner_values[h as usize] as usize, weight);
    }

    #[inline(always)]
    fn face_point(&mut self, c: u32, weight: f32) {
        self.add_row(self.face_values, c as usize, weight);
    }

    scaled_groups!();
}

/// One vertex-numbered channel: `width` floats per vertex (see [`pack_points`]).
#[derive(Clone, Debug, Default)]
pub struct Channel<'p> {
    pub width: usize,
    pub values: Cow<'p, [f32]>,
}

/// The widest packed point [`pack_points`] makes: positions and up to five more floats per
/// vertex (a colour and a UV, or four skin weights). Wider levels walk the rules per kind.
pub const MAX_PACKED: usize = 8;

/// Calls `$f::<W, A, B>($args)` for the layout of one channel of `A` floats (`B` = 0) or two of
/// `A` and `B` that `$widths` lists, when it fits beside the positions in [`MAX_PACKED`] floats
/// (the common layouts: a colour, a UV, both, skin weights); `None` for any other.
macro_rules! by_layout {
    ($widths:expr, $f:ident $args:tt) => {
        by_layout!(@ $widths, $f $args;
            1 0, 2 0, 3 0, 4 0, 5 0, 1 1, 1 2, 1 3, 1 4, 2 1, 2 2, 2 3, 3 1, 3 2, 4 1)
    };
    (@ $widths:expr, $f:ident $args:tt; $($a:literal $b:literal),*) => {
        match $widths {
            $([$a] if $b == 0 => Some($f::<W, $a, $b> $args),
              [$a, $b] => Some($f::<W, $a, $b> $args),)*
            _ => None,
        }
    };
}

/// `positions` and `channels` side by side, `W` floats per vertex (`W` the sum of their widths;
/// a channel shorter than the positions reads as zeros), so that one walk of the rules refines
/// them all with its sum in registers. One or two channels go in one pass.
pub fn pack_points<const W: usize>(
    positions: &[[f32; 3]],
    channels: &[Channel<'_>],
) -> Vec<[f32; W]> {
    let widths: Vec<_> = channels.iter().map(|c| c.width).collect();
    let values = |k: usize| channels.get(k).map_or(&[][..], |c| &c.values[..]);
    if let Some(packed) = by_layout!(&widths[..], join(positions, values(0), values(1))) {
        return packed;
    }
    let mut packed: Vec<[f32; W]> = join::<W, 0, 0>(positions, &[], &[]);
    let mut at = 3;
    for channel in channels {
        let values = &channel.values[..];
        match channel.width {
            1 => put::<W, 1>(&mut packed, values, at),
            2 => put::<W, 2>(&mut packed, values, at),
            3 => put::<W, 3>(&mut packed, values, at),
            4 => put::<W, 4>(&mut packed, values, at),
            _ => put::<W, 5>(&mut packed, values, at),
        }
        at += channel.width;
    }
    packed
}

/// Writes the values of a channel of `N` floats into floats `at..at + N` of the packed points
/// (loops of constant width: no copy call per point).
fn put<const W: usize, const N: usize>(packed: &mut [[f32; W]], values: &[f32], at: usize) {
    for (point, value) in packed.iter_mut().zip(values.chunks_exact(N)) {
        if let Some(to) = point.get_mut(at..at + N) {
            to.copy_from_slice(value);
        }
    }
}

/// The packed points of `positions` with channels of `A` and `B` floats, in one pass.
fn join<const W: usize, const A: usize, const B: usize>(
    positions: &[[f32; 3]],
    first: &[f32],
    second: &[f32],
) -> Vec<[f32; W]> {
    let n = positions.len();
    if A > 0 && first.len() == n * A && B > 0 && second.len() == n * B {
        // Every value there (the common case): one zipped pass, no index checks per point.
        let rows = positions.iter().zip(first.chunks_exact(A)).zip(second.chunks_exact(B));
        return rows.map(|((p, a), b)| packed_point::<W, A, B>(p, a, b)).collect();
    }
    if A > 0 && first.len() == n * A && B == 0 {
        let rows = positions.iter().zip(first.chunks_exact(A));
        return rows.map(|(p, a)| packed_point::<W, A, 0>(p, a, &[])).collect();
    }
    let point = |(i, p): (usize, &[f32; 3])| {
        let (a, b) = (first.get(i * A..(i + 1) * A), second.get(i * B..(i + 1) * B));
        packed_point::<W, A, B>(p, a.unwrap_or(&[]), b.unwrap_or(&[]))
    };
    positions.iter().enumerate().map(point).collect()
}

/// One packed point: `p`, then `a` and `b` when they hold `A` and `B` floats (zeros otherwise).
/// Made float by float in registers: built in a zeroed array with slice copies, each point went
/// through the stack before its store.
#[inline(always)]
fn packed_point<const W: usize, const A: usize, const B: usize>(
    p: &[f32; 3],
    a: &[f32],
    b: &[f32],
) -> [f32; W] {
    let (a, b) = (a.first_chunk::<A>(), b.first_chunk::<B>());
    std::array::from_fn(|i| match i {
        0..3 => p[i],
        _ if i < 3 + A => a.map_or(0.0, |a| a[i - 3]),
        _ if i < 3 + A + B => b.map_or(0.0, |b| b[i - 3 - A]),
        _ => 0.0,
    })
}

/// Where a host appends a level's new values: the values themselves (every kind of
/// [`Primvar`]), or [`Unpacking`], which takes packed points apart as they come.
pub trait Points<P: Primvar> {
    /// Appends `count` values, value `i` the one whose weights `rule(i, _)` gives.
    fn extend_with<'a>(
        &mut self,
        count: u32,
        sum: &mut P::Sum<'a>,
        rule: impl FnMut(u32, &mut P::Sum<'a>),
    );
    /// Appends every value of `other`.
    fn extend_from(&mut self, other: &P);
}

impl<P: Primvar> Points<P> for P {
    #[inline(always)]
    fn extend_with<'a>(
        &mut self,
        count: u32,
        sum: &mut P::Sum<'a>,
        rule: impl FnMut(u32, &mut P::Sum<'a>),
    ) {
        Primvar::extend_with(self, count, sum, rule);
    }

    fn extend_from(&mut self, other: &P) {
        Primvar::extend_from(self, other);
    }
}

/// The child of packed points ([`pack_points`]) taken apart as the host appends them: the
/// positions, and each channel at its own width. (Kept packed and unpacked after, the child
/// cost a second pass over it and twice its memory.)
pub struct Unpacking {
    positions: Vec<[f32; 3]>,
    /// Each channel's first float in a packed point, its width and its values.
    channels: Vec<(usize, usize, Vec<f32>)>,
}

impl Unpacking {
    /// Room for `count` points of channels of `widths` (packed after the positions, in order),
    /// and for channel `k`'s values, `room[k]` values when that is more (a face-varying
    /// channel's values after the vertices' own, which would otherwise move them all).
    pub fn new(count: usize, widths: &[usize], room: &[usize]) -> Self {
        let mut at = 3;
        let channels = widths.iter().enumerate().map(|(k, &width)| {
            at += width;
            let values = room.get(k).map_or(count, |&r| r.max(count));
            (at - width, width, Vec::with_capacity(values * width))
        });
        Unpacking { positions: Vec::with_capacity(count), channels: channels.collect() }
    }

    /// Appends `points`, column by column: each column a loop of constant width.
    #[inline(always)]
    fn extend_from_points<const W: usize>(&mut self, points: &[[f32; W]]) {
        self.positions.extend(points.iter().map(|point| take::<W, 3>(point, 0)));
        for channel in &mut self.channels {
            extend_values(channel, points);
        }
    }

    /// The positions and the channels' values.
    pub fn into_parts(self) -> (Vec<[f32; 3]>, Vec<Vec<f32>>) {
        (self.positions, self.channels.into_iter().map(|(.., values)| values).collect())
    }
}

impl<const W: usize> Points<Vec<[f32; W]>> for Unpacking {
    #[inline(always)]
    fn extend_with<'a>(
        &mut self,
        count: u32,
        sum: &mut PointSum<'a, W>,
        mut rule: impl FnMut(u32, &mut PointSum<'a, W>),
    ) {
        // A run of points is summed into a buffer that stays in the L1 cache, then taken
        // apart column by column: a point at a time cost a width dispatch, a capacity check and
        // a store per channel and point (about 100 M instructions of a textured 1M-quad split).
        let mut buffer = [[0.0f32; W]; RUN];
        let mut start = 0;
        while start < count {
            let run = &mut buffer[..(count - start).min(RUN as u32) as usize];
            for (i, point) in (start..).zip(run.iter_mut()) {
                *point = sum.eval(|w| rule(i, w));
            }
            self.extend_from_points(run);
            start += RUN as u32;
        }
    }

    fn extend_from(&mut self, other: &Vec<[f32; W]>) {
        for run in other.chunks(RUN) {
            self.extend_from_points(run);
        }
    }
}

/// The points [`Unpacking`] sums before it takes them apart: few enough to stay in the L1 cache.
const RUN: usize = 64;

/// Appends a channel's values (`(at, width, values)` of [`Unpacking`]) from every packed point
/// of `points`, a loop of constant width for each width a packed point holds.
fn extend_values<const W: usize>(
    (at, width, values): &mut (usize, usize, Vec<f32>),
    points: &[[f32; W]],
) {
    fn columns<const W: usize, const N: usize>(
        values: &mut Vec<f32>,
        points: &[[f32; W]],
        at: usize,
    ) {
        // Written into reserved room, so that the copy loop has no capacity check per point
        // and the floats are not zeroed first (that was 1 % of a uv + colour call natively).
        let start = values.len();
        let count = points.len() * N;
        values.reserve(count);
        let (to, _) = values.spare_capacity_mut()[..count].as_chunks_mut::<N>();
        for (to, point) in to.iter_mut().zip(points) {
            for (to, x) in to.iter_mut().zip(take::<W, N>(point, at)) {
                to.write(x);
            }
        }
        // SAFETY: the loop wrote all `count` floats after `start`: `to` has `points.len()`
        // chunks of `N`.
        unsafe { values.set_len(start + count) };
    }
    match *width {
        1 => columns::<W, 1>(values, points, *at),
        2 => columns::<W, 2>(values, points, *at),
        3 => columns::<W, 3>(values, points, *at),
        4 => columns::<W, 4>(values, points, *at),
        _ => columns::<W, 5>(values, points, *at),
    }
}

/// Floats `at..at + N` of a packed point (zeros if they pass its end, which a layout that
/// [`pack_points`] made never does): one bounds check, not one per float.
#[inline(always)]
fn take<const W: usize, const N: usize>(point: &[f32; W], at: usize) -> [f32; N] {
    point.get(at..).and_then(|rest| rest.first_chunk::<N>()).copied().unwrap_or([0.0; N])
}

/// Every vertex-varying channel side by side: `width` floats per vertex, in vertex order.
/// Width 0 (no channel) costs nothing at any level. A lone channel's base values are the
/// caller's, borrowed (`attributes::pack`); every refined level owns its values.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Rows<'a> {
    pub width: usize,
    pub values: Cow<'a, [f32]>,
}

impl Rows<'_> {
    /// Number of rows.
    pub fn len(&self) -> usize {
        self.values.len().checked_div(self.width).unwrap_or(0)
    }

    pub fn is_empty(&self) -> bool {
        self.width == 0 || self.values.is_empty()
    }
}

/// One vertex's three limit masks merged per vertex of the level: each weighted vertex once,
/// with its position's, first tangent's and second tangent's weights.
pub type LimitSources = Vec<(u32, [f32; 3])>;

/// One level's values of one kind (positions, or [`Rows`]), as the hosts refine them: the same
/// loop over new points serves every kind. A host asks for a sum over the parent values (and
/// the child level's face points, where its rules weight them), then appends or places each new
/// value.
pub trait Primvar: Sized {
    /// The sink that sums one new value.
    type Sum<'a>: Weights
    where
        Self: 'a;
    /// A sum over these (parent) values, with `face_points` the child level's face points when
    /// the rules weight them.
    fn sum<'a>(&'a self, he_from: &'a [u32], face_points: Option<&'a Self>) -> Self::Sum<'a>;
    /// No values of this kind's shape, with room for `capacity`.
    fn with_capacity(&self, capacity: usize) -> Self;
    /// Appends the value whose weights `rule` gives.
    fn push<'a>(&mut self, sum: &mut Self::Sum<'a>, rule: impl FnOnce(&mut Self::Sum<'a>));
    /// Appends `count` values, value `i` the one whose weights `rule(i, _)` gives. (One call
    /// per run of values lets positions be collected from an exact-size iterator, without a
    /// capacity check per value.)
    fn extend_with<'a>(
        &mut self,
        count: u32,
        sum: &mut Self::Sum<'a>,
        mut rule: impl FnMut(u32, &mut Self::Sum<'a>),
    ) {
        for i in 0..count {
            self.push(sum, |w| rule(i, w));
        }
    }
    /// Appends every value of `other`.
    fn extend_from(&mut self, other: &Self);
    /// Appends `count` zero values, to be placed later with [`Primvar::set`].
    fn extend_zeroed(&mut self, count: usize);
    /// Overwrites value `i` with the one whose weights `rule` gives.
    fn set<'a>(&mut self, i: usize, sum: &mut Self::Sum<'a>, rule: impl FnOnce(&mut Self::Sum<'a>));
    /// True when these are stencils that passed their size limit (the build is then refused;
    /// see `Stencils::into_table`): other data never is.
    fn overflowed(&self) -> bool {
        false
    }

    /// Values that stand for `count` vertices of the level just made, each itself, so that
    /// the next level's values are made on this level's (level by level stencils, see
    /// `scheme::build_level_stencils`); `None` for kinds that have no such values.
    fn restart(&self, _count: usize) -> Option<Self> {
        None
    }
    /// True when there is nothing to refine (a [`Rows`] without channels): the hosts then
    /// return `with_capacity(0)` without running the rules.
    fn is_empty(&self) -> bool;
    /// These values as one vertex-numbered channel, when they are plain floats (so that a host
    /// may refine them in one walk of the rules with the positions, see [`pack_points`]).
    fn as_channel(&self) -> Option<Channel<'_>> {
        None
    }
    /// Values of this kind from the refined channel that [`Primvar::as_channel`] gave.
    fn with_channel(&self, _values: Vec<f32>) -> Option<Self> {
        None
    }
    /// The values of three masks per vertex of `mesh` (the limit position and two tangents),
    /// which `masks(v, sources)` gives merged per vertex of the level (each weighted vertex
    /// once, with its three weights): the position rows, and the two tangent rows. A kind whose
    /// three sums share their work overrides this.
    fn limit_rows(
        &self,
        mesh: &HalfEdgeMesh,
        masks: &mut dyn FnMut(u32, &mut LimitSources),
    ) -> (Self, [Self; 2]) {
        let n = mesh.num_vertices();
        let mut out = [self.with_capacity(n), self.with_capacity(n), self.with_capacity(n)];
        let mut sum = self.sum(&mesh.he_from, None);
        let mut sources = Vec::new();
        for v in 0..n as u32 {
            sources.clear();
            masks(v, &mut sources);
            for (k, rows) in out.iter_mut().enumerate() {
                rows.push(&mut sum, |w| {
                    for &(source, weights) in &sources {
                        if weights[k] != 0.0 {
                            w.vertex(source, weights[k]);
                        }
                    }
                });
            }
        }
        let [positions, first, second] = out;
        (positions, [first, second])
    }
}

impl<const W: usize> Primvar for Vec<[f32; W]> {
    type Sum<'a> = PointSum<'a, W>;

    #[inline]
    fn sum<'a>(&'a self, he_from: &'a [u32], face_points: Option<&'a Self>) -> PointSum<'a, W> {
        PointSum::new(self, he_from, face_points.map_or(&[], |f| f))
    }

    fn with_capacity(&self, capacity: usize) -> Self {
        Vec::with_capacity(capacity)
    }

    #[inline(always)]
    fn push<'a>(&mut self, sum: &mut PointSum<'a, W>, rule: impl FnOnce(&mut PointSum<'a, W>)) {
        self.push(sum.eval(rule));
    }

    #[inline(always)]
    fn extend_with<'a>(
        &mut self,
        count: u32,
        sum: &mut PointSum<'a, W>,
        mut rule: impl FnMut(u32, &mut PointSum<'a, W>),
    ) {
        self.extend((0..count).map(|i| sum.eval(|w| rule(i, w))));
    }

    fn extend_from(&mut self, other: &Self) {
        self.extend_from_slice(other);
    }

    fn extend_zeroed(&mut self, count: usize) {
        self.resize(self.len() + count, [0.0; W]);
    }

    fn is_empty(&self) -> bool {
        <[[f32; W]]>::is_empty(self)
    }

    #[inline(always)]
    fn set<'a>(
        &mut self,
        i: usize,
        sum: &mut PointSum<'a, W>,
        rule: impl FnOnce(&mut PointSum<'a, W>),
    ) {
        self[i] = sum.eval(rule);
    }
}

impl Primvar for Rows<'_> {
    type Sum<'a>
        = RowSum<'a>
    where
        Self: 'a;

    fn sum<'a>(&'a self, he_from: &'a [u32], face_points: Option<&'a Self>) -> RowSum<'a> {
        RowSum::new(&self.values, self.width, he_from, face_points.map_or(&[], |f| &f.values))
    }

    fn with_capacity(&self, capacity: usize) -> Self {
        Rows { width: self.width, values: Cow::Owned(Vec::with_capacity(capacity * self.width)) }
    }

    #[inline]
    fn push<'a>(&mut self, sum: &mut RowSum<'a>, rule: impl FnOnce(&mut RowSum<'a>)) {
        sum.eval_into(self.values.to_mut(), rule);
    }

    fn extend_from(&mut self, other: &Self) {
        self.values.to_mut().extend_from_slice(&other.values);
    }

    fn extend_zeroed(&mut self, count: usize) {
        let values = self.values.to_mut();
        values.resize(values.len() + count * self.width, 0.0);
    }

    #[inline]
    fn set<'a>(&mut self, i: usize, sum: &mut RowSum<'a>, rule: impl FnOnce(&mut RowSum<'a>)) {
        sum.sum.fill(0.0);
        rule(sum);
        let row = i * self.width..(i + 1) * self.width;
        self.values.to_mut()[row].copy_from_slice(&sum.sum);
    }

    fn is_empty(&self) -> bool {
        Rows::is_empty(self)
    }

    fn as_channel(&self) -> Option<Channel<'_>> {
        let values = Cow::Borrowed(&self.values[..]);
        (!self.is_empty()).then_some(Channel { width: self.width, values })
    }

    fn with_channel(&self, values: Vec<f32>) -> Option<Self> {
        Some(Rows { width: self.width, values: Cow::Owned(values) })
    }
}
