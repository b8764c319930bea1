//! Four f32 sums in one 128-bit register, and unit normals made four at a time: what the
//! evaluation loops of the tables and of the regular patches share.

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

    /// `self + x`, lane by lane.
    #[inline(always)]
    pub(crate) fn add(self, x: Lanes) -> Lanes {
        Lanes(core::arch::wasm32::f32x4_add(self.0, x.0))
    }

    /// `self * w`.
    #[inline(always)]
    pub(crate) fn scale(self, w: f32) -> Lanes {
        use core::arch::wasm32::{f32x4_mul, f32x4_splat};
        Lanes(f32x4_mul(self.0, f32x4_splat(w)))
    }

    /// All four lanes.
    #[inline(always)]
    pub(crate) fn xyzw(self) -> [f32; 4] {
        let mut out = [0.0; 4];
        // SAFETY: `out` is 16 writable bytes; wasm stores need no alignment.
        unsafe { core::arch::wasm32::v128_store(out.as_mut_ptr().cast(), self.0) };
        out
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

    /// Writes the first three lanes to `out`: x and y as one 64-bit store, z as one 32-bit
    /// store, where `xyz` takes three of each.
    #[inline(always)]
    pub(crate) fn store_xyz(self, out: &mut [f32; 3]) {
        use core::arch::wasm32::{v128_store32_lane, v128_store64_lane};
        let at = out.as_mut_ptr();
        // SAFETY: `out` is 12 writable bytes: 8 at its start, 4 at byte 8; wasm stores need no
        // alignment.
        unsafe {
            v128_store64_lane::<0>(self.0, at.cast());
            v128_store32_lane::<2>(self.0, at.add(2).cast());
        }
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

    /// `self + x`, lane by lane.
    #[inline(always)]
    pub(crate) fn add(self, x: Lanes) -> Lanes {
        Lanes(std::array::from_fn(|k| self.0[k] + x.0[k]))
    }

    /// `self * w`.
    #[inline(always)]
    pub(crate) fn scale(self, w: f32) -> Lanes {
        Lanes(self.0.map(|x| x * w))
    }

    /// All four lanes.
    #[inline(always)]
    pub(crate) fn xyzw(self) -> [f32; 4] {
        self.0
    }

    /// The first three lanes.
    #[inline(always)]
    pub(crate) fn xyz(self) -> [f32; 3] {
        [self.0[0], self.0[1], self.0[2]]
    }

    /// Writes the first three lanes to `out`.
    #[inline(always)]
    pub(crate) fn store_xyz(self, out: &mut [f32; 3]) {
        *out = self.xyz();
    }
}

/// Where a level's points go as a step makes them, in output order: the padded points of the
/// next level (a `Vec`), or the caller's positions ([`Written`]) for the last level, which is
/// then not made twice.
pub(crate) trait PointSink {
    fn put_all(&mut self, points: impl Iterator<Item = Lanes>);
}

impl PointSink for Vec<[f32; 4]> {
    #[inline(always)]
    fn put_all(&mut self, points: impl Iterator<Item = Lanes>) {
        self.extend(points.map(Lanes::xyzw));
    }
}

/// Points written to `out` from its start, one after the other (points past its end are left
/// out).
pub(crate) struct Written<'o> {
    out: &'o mut [[f32; 3]],
    at: usize,
}

impl<'o> Written<'o> {
    pub(crate) fn new(out: &'o mut [[f32; 3]]) -> Self {
        Written { out, at: 0 }
    }
}

impl PointSink for Written<'_> {
    #[inline(always)]
    fn put_all(&mut self, points: impl Iterator<Item = Lanes>) {
        let rest = self.out.get_mut(self.at..).unwrap_or_default();
        let mut count = 0;
        for (out, point) in rest.iter_mut().zip(points) {
            point.store_xyz(out);
            count += 1;
        }
        self.at += count;
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
pub(crate) struct Normals<'o, const RUNS: bool> {
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

impl<'o, const RUNS: bool> Normals<'o, RUNS> {
    /// With `RUNS`, four normals pushed for four consecutive rows are written as one run (the
    /// callers whose rows mostly come in order).
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
            let count = (len - 4 * k).min(4);
            four_normals(tangents).store::<RUNS>(&rows[..count], self.out);
        }
        self.len = 0;
    }
}

impl<const RUNS: bool> Drop for Normals<'_, RUNS> {
    fn drop(&mut self) {
        self.flush();
    }
}

/// Four unit normals: in lanes, x, y and z each in one register (wasm), or one by one.
enum FourNormals {
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    Lanes([core::arch::wasm32::v128; 3]),
    Each([Lanes; 4]),
}

impl FourNormals {
    /// Writes the first `rows.len()` normals to their rows of `out` (rows past its end are left
    /// out); with `RUNS`, four consecutive rows as one run.
    #[inline(always)]
    fn store<const RUNS: bool>(self, rows: &[usize], out: &mut [[f32; 3]]) {
        // (Natively `Each` is the only variant.)
        #[allow(clippy::infallible_destructuring_match)]
        let each = match self {
            #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
            FourNormals::Lanes(xyz) => {
                if let (true, &[first, _, _, last]) = (RUNS, rows) {
                    // Four consecutive rows: three full stores, where one per row takes two.
                    let run = out.get_mut(first..first + 4).and_then(|run| run.try_into().ok());
                    if let (true, Some(run)) = (last == first + 3, run) {
                        store_twelve(xyz, run);
                        return;
                    }
                }
                per_register(xyz)
            }
            FourNormals::Each(each) => each,
        };
        for (&row, normal) in rows.iter().zip(each) {
            if let Some(out) = out.get_mut(row) {
                normal.store_xyz(out);
            }
        }
    }
}

/// [`crate::limit::normal`] of four tangent pairs, in lanes (see [`Normals`]).
#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
#[inline(always)]
fn four_normals(tangents: &[[Lanes; 2]; 4]) -> FourNormals {
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
        return FourNormals::Each(one_at_a_time(tangents));
    }
    let inverse = f32x4_div(f32x4_splat(1.0), f32x4_sqrt(length2));
    FourNormals::Lanes([nx, ny, nz].map(|c| mul(c, inverse)))
}

/// Four normals in lanes back to a point per register: six shuffles, where twelve lane
/// extracts took them out one float at a time.
#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
#[inline(always)]
fn per_register([x, y, z]: [core::arch::wasm32::v128; 3]) -> [Lanes; 4] {
    use core::arch::wasm32::i32x4_shuffle;
    let (low, high) = (i32x4_shuffle::<0, 4, 1, 5>(x, y), i32x4_shuffle::<2, 6, 3, 7>(x, y));
    [
        i32x4_shuffle::<0, 1, 4, 4>(low, z),
        i32x4_shuffle::<2, 3, 5, 5>(low, z),
        i32x4_shuffle::<0, 1, 6, 6>(high, z),
        i32x4_shuffle::<2, 3, 7, 7>(high, z),
    ]
    .map(Lanes)
}

/// Four normals in lanes written to four consecutive points, 48 bytes, as three 16-byte
/// stores of `x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3`.
#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
#[inline(always)]
fn store_twelve([x, y, z]: [core::arch::wasm32::v128; 3], out: &mut [[f32; 3]; 4]) {
    use core::arch::wasm32::{i32x4_shuffle, v128, v128_store};
    let (low, high) = (i32x4_shuffle::<0, 4, 1, 5>(x, y), i32x4_shuffle::<2, 6, 3, 7>(x, y));
    let first = i32x4_shuffle::<0, 1, 4, 2>(low, z);
    let second = i32x4_shuffle::<0, 1, 4, 5>(i32x4_shuffle::<3, 5, 3, 5>(low, z), high);
    let third = i32x4_shuffle::<2, 6, 7, 3>(z, high);
    let at = out.as_mut_ptr().cast::<v128>();
    // SAFETY: `out` is four points, 48 writable bytes; wasm stores need no alignment.
    unsafe {
        v128_store(at, first);
        v128_store(at.byte_add(16), second);
        v128_store(at.byte_add(32), third);
    }
}

/// [`crate::limit::normal`] of four tangent pairs one by one, each in the first three lanes of
/// its own register.
fn one_at_a_time(tangents: &[[Lanes; 2]; 4]) -> [Lanes; 4] {
    tangents.map(|[a, b]| {
        let [x, y, z] = crate::limit::normal(a.xyz(), b.xyz());
        Lanes::load(&[x, y, z, 0.0])
    })
}

/// [`crate::limit::normal`] of four tangent pairs, with x, y and z each in an array of four,
/// which LLVM's SLP vectorizer turns into SSE's four-wide operations: one pair at a time,
/// the scalar `sqrtss` and `divss` and the tangents' round trip through memory took about 40
/// ns a point natively on the horse's Catmull-Clark level 2, twice the rest of its frame.
#[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
#[inline(always)]
fn four_normals(tangents: &[[Lanes; 2]; 4]) -> FourNormals {
    use std::array::from_fn;
    let lane = |which: usize, k: usize| -> [f32; 4] { from_fn(|i| tangents[i][which].0[k]) };
    let ([ax, ay, az], [bx, by, bz]) = (from_fn(|k| lane(0, k)), from_fn(|k| lane(1, k)));
    fn each(f: impl Fn(usize) -> f32) -> [f32; 4] {
        from_fn(f)
    }
    // Exactly `limit::normal`'s operations, in its order, lane by lane (the same results).
    let nx = each(|i| ay[i] * bz[i] - az[i] * by[i]);
    let ny = each(|i| az[i] * bx[i] - ax[i] * bz[i]);
    let nz = each(|i| ax[i] * by[i] - ay[i] * bx[i]);
    let length2 = each(|i| nx[i] * nx[i] + ny[i] * ny[i] + nz[i] * nz[i]);
    let scale2 = each(|i| {
        (ax[i] * ax[i] + ay[i] * ay[i] + az[i] * az[i])
            * (bx[i] * bx[i] + by[i] * by[i] + bz[i] * bz[i])
    });
    let good =
        (0..4).all(|i| length2[i] >= 0.01 * scale2[i] && length2[i] > 1e-30 && scale2[i] < 1e30);
    if !good {
        return FourNormals::Each(one_at_a_time(tangents));
    }
    let inverse = each(|i| 1.0 / length2[i].sqrt());
    FourNormals::Each(from_fn(|i| {
        Lanes([nx[i] * inverse[i], ny[i] * inverse[i], nz[i] * inverse[i], 0.0])
    }))
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
            // Every ninth pair along one line (its normal is zero, through the f64 path, and so
            // are the three others of its four), the others at varied angles and lengths.
            let pair = |k: usize| {
                let t = k as f32 * 0.37;
                let a = [t.cos(), t.sin(), 0.25 * k as f32];
                let b =
                    if k.is_multiple_of(9) { a.map(|x| 2.0 * x) } else { [-t.sin(), t.cos(), 1.0] };
                (a, b)
            };
            // Pushed in reverse row order, skipping rows 0 and 1; and in order, where runs of
            // four rows are written whole.
            for order in [(2..rows).rev().collect::<Vec<usize>>(), (2..rows).collect()] {
                let mut out = vec![[9.0f32; 3]; rows];
                {
                    let mut normals = Normals::<true>::new(&mut out);
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
    }
}
