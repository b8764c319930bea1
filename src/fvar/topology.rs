//! The value topology of one level: which values each vertex has, which corner sees which,
//! how each value is tagged, and which edges are seams (OpenSubdiv's `Vtr::FVarLevel`), analysed
//! for a first level and inherited by refined ones (`Vtr::FVarRefinement`).

use super::siblings::Distinct;
use super::{edge_tag, tag, ModeRules};
use crate::mesh::HalfEdgeMesh;
use crate::rules::crease::decay;
use crate::rules::LevelTags;
use crate::tags::SHARPNESS_INFINITE;

/// The sharpness of one level as the face-varying rules read it: the level's tags when it has
/// any (boundary and non-manifold edges are infinitely sharp there already), otherwise sharp
/// boundary edges only; and under `edge-and-corner`, a vertex with one face is infinitely sharp
/// (OpenSubdiv's factory writes that into the vertex sharpness; our crease rules recognise it).
#[derive(Clone, Copy, Debug)]
pub struct LevelSharpness<'a> {
    pub tags: Option<&'a LevelTags>,
    pub sharp_corners: bool,
}

/// The primal split that made a level: it fixes the child vertex order (`[vertices | face
/// points | edge points]`, face points for the cells the split gives one) and which parent
/// value each child corner sees. Every split gives parent cell `c` the child corners
/// `4 s .. 4 (s + n)`, `s` its first half-edge and `n` its size: `n` quads around a face point
/// (corner `4h` at the old vertex of parent half-edge `h`), or for a triangle four triangles in
/// OpenSubdiv's order (see [`crate::refine::ptq`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Split {
    /// Catmull-Clark's and bilinear's: every cell into quads.
    Quad,
    /// Loop's and midpoint's: every triangle into four.
    Triangle,
    /// Quad/Triangle's: triangles as [`Split::Triangle`], other cells as [`Split::Quad`].
    Mixed,
}

impl Split {
    /// True when the child cells of parent cell `c` are triangles.
    fn splits_into_triangles(self, mesh: &HalfEdgeMesh, c: u32) -> bool {
        match self {
            Split::Quad => false,
            Split::Triangle => true,
            Split::Mixed => mesh.cell_range(c as usize).len() == 3,
        }
    }

    /// The next (`forward`) or previous corner of child corner `h` in its child cell.
    fn child_step(self, mesh: &HalfEdgeMesh, h: u32, forward: bool) -> u32 {
        let parent = mesh.cell_of(h / 4);
        let n = if self.splits_into_triangles(mesh, parent) { 3 } else { 4 };
        let base = 4 * mesh.cell_range(parent as usize).start as u32;
        let k = (h - base) % n;
        let step = if forward { 1 } else { n - 1 };
        h - k + (k + step) % n
    }

    /// Which cells get a face point and where it goes among the face points; and how many
    /// there are.
    pub(crate) fn face_points(self, mesh: &HalfEdgeMesh) -> (FacePoints, usize) {
        match self {
            Split::Quad => (FacePoints::Every, mesh.num_cells()),
            Split::Triangle => (FacePoints::None, 0),
            Split::Mixed => {
                let mut count = 0u32;
                let map = (0..mesh.num_cells() as u32)
                    .map(|c| {
                        if self.splits_into_triangles(mesh, c) {
                            u32::MAX
                        } else {
                            count += 1;
                            count - 1
                        }
                    })
                    .collect();
                (FacePoints::Map(map), count as usize)
            }
        }
    }
}

/// The face points of a split ([`Split::face_points`]): cell `c`'s is the `c`-th when every
/// cell has one (no map to build or read), none has one, or a map says (`u32::MAX` for none).
pub(crate) enum FacePoints {
    Every,
    None,
    Map(Vec<u32>),
}

impl FacePoints {
    /// Cell `c`'s face point's place among the face points, if it has one.
    #[inline]
    pub(crate) fn of(&self, c: u32) -> Option<u32> {
        match self {
            FacePoints::Every => Some(c),
            FacePoints::None => None,
            FacePoints::Map(map) => map.get(c as usize).copied().filter(|&k| k != u32::MAX),
        }
    }
}

impl LevelSharpness<'_> {
    pub(crate) fn edge(&self, mesh: &HalfEdgeMesh, e: u32) -> f32 {
        match self.tags {
            Some(t) => t.edges[e as usize],
            None if mesh.edge_range(e as usize).len() != 2 || mesh.is_non_manifold_edge(e) => {
                SHARPNESS_INFINITE
            }
            None => 0.0,
        }
    }

    pub(crate) fn vertex(&self, mesh: &HalfEdgeMesh, v: u32) -> f32 {
        if self.sharp_corners && mesh.out_half_edges(v).len() == 1 {
            return SHARPNESS_INFINITE;
        }
        self.tags.map_or(0.0, |t| t.vertices[v as usize])
    }

    /// The sharpness at the next level of edge `e`'s half at `v`.
    pub(crate) fn child_edge(&self, mesh: &HalfEdgeMesh, e: u32, v: u32) -> f32 {
        match self.tags {
            Some(t) => t.decay_at(t.edges[e as usize], v),
            None => decay(self.edge(mesh, e)),
        }
    }
}

fn is_semi_sharp(s: f32) -> bool {
    s > 0.0 && s < SHARPNESS_INFINITE
}

/// One level of a face-varying channel: its values (`width` floats each), the value each face
/// corner (half-edge) sees, each value's tag (`tag`) and crease ends, and each edge's tag
/// (`edge_tag`). A vertex's first value is numbered as the vertex; a vertex with several
/// values (only along seams) has the others after all vertices' first ones. So wherever a level
/// has no seam, its value indices are its vertex indices, and refined corner values follow the
/// child faces' own indices.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FVarLevel {
    pub width: usize,
    pub values: Vec<f32>,
    pub corner_values: Vec<u32>,
    pub(crate) tags: Vec<u8>,
    /// The vertices with more than one value, in vertex order: `[vertex, its second value,
    /// number of values]`.
    pub(crate) several: Vec<[u32; 3]>,
    /// For each crease or semi-sharp value, in value order: the value, and the vertex's
    /// outgoing half-edges in the first and last face of its span, whose next and previous
    /// corners hold the crease's end values. Sparse: such values lie along seams only.
    pub(crate) ends: Vec<(u32, [u32; 2])>,
    pub(crate) edge_tags: Vec<u8>,
    /// For a last level whose faces stay implicit ([`crate::refined::Refined`]): the corners
    /// that do not see their vertex, and `corner_values` is empty.
    pub(crate) seam_corners: Option<SeamCorners>,
}

/// The corner values of a level whose faces are the implicit quads of a split: everywhere the
/// child faces' own indices ([`crate::refine::pqq::child_face_indices`]), but for the child
/// corners of the parent cells near seams, listed here. The 64 MB corner list of a textured
/// 1M-quad split is then never written whole to memory and read back: the bindings patch the
/// face indices piece by piece as they copy them out.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SeamCorners {
    /// Ascending, disjoint ranges of child corners `[start, end)`, each with where its values
    /// start in `values`.
    spans: Vec<[u32; 3]>,
    values: Vec<u32>,
}

impl SeamCorners {
    /// The spans from the first that ends after child corner `at`.
    fn spans_from(&self, at: usize) -> &[[u32; 3]] {
        &self.spans[self.spans.partition_point(|s| (s[1] as usize) <= at)..]
    }

    /// Whether any of the `len` child corners from `at` on is near a seam: a piece that is
    /// not can be copied out as the faces' own indices, without a patched copy.
    pub fn touches(&self, at: usize, len: usize) -> bool {
        self.spans_from(at).first().is_some_and(|s| (s[0] as usize) < at + len)
    }

    /// Writes over `corners`, the child corners from `at` on, the values of the spans there.
    pub fn patch(&self, at: usize, corners: &mut [u32]) {
        let end = at + corners.len();
        for &[s, e, from] in self.spans_from(at) {
            let (s, e, from) = (s as usize, e as usize, from as usize);
            if s >= end {
                break;
            }
            let (lo, hi) = (s.max(at), e.min(end));
            let from = from + lo - s;
            corners[lo - at..hi - at].copy_from_slice(&self.values[from..from + hi - lo]);
        }
    }
}

/// Calls `f(i)` for each `i` whose `bytes[i]` has a bit of `mask`, in ascending order, reading
/// eight bytes at a time: the tags it scans are zero away from seams, which are sparse, so most
/// words are passed over whole (a byte at a time, the scans of a 1M-quad level cost tens of
/// millions of instructions).
pub(crate) fn for_each_marked(bytes: &[u8], mask: u8, mut f: impl FnMut(usize)) {
    let (words, rest) = bytes.as_chunks::<8>();
    let wide = u64::from_ne_bytes([mask; 8]);
    for (w, word) in words.iter().enumerate() {
        if u64::from_ne_bytes(*word) & wide == 0 {
            continue;
        }
        for (k, &b) in word.iter().enumerate() {
            if b & mask != 0 {
                f(8 * w + k);
            }
        }
    }
    let done = 8 * words.len();
    for (k, &b) in rest.iter().enumerate() {
        if b & mask != 0 {
            f(done + k);
        }
    }
}

/// Builds a level's value numbering vertex by vertex (see [`FVarLevel`]).
struct Numbering {
    tags: Vec<u8>,
    several: Vec<[u32; 3]>,
    ends: Vec<(u32, [u32; 2])>,
}

impl Numbering {
    fn new(vertices: usize) -> Self {
        Numbering { tags: vec![0; vertices], several: Vec::new(), ends: Vec::new() }
    }

    /// Gives vertex `v` `count` values and returns the index of its second (if any).
    fn add(&mut self, v: u32, count: u32) -> u32 {
        let second = self.tags.len() as u32;
        if count > 1 {
            self.several.push([v, second, count]);
            self.tags.resize(self.tags.len() + count as usize - 1, 0);
        }
        second
    }

    /// Sets value `i`'s tag and crease ends.
    fn tag(&mut self, i: u32, tag: u8, ends: Option<[u32; 2]>) {
        self.tags[i as usize] = tag;
        if let Some(ends) = ends {
            self.ends.push((i, ends));
        }
    }

    fn finish(
        mut self,
        width: usize,
        values: Vec<f32>,
        corner_values: Vec<u32>,
        edge_tags: Vec<u8>,
    ) -> FVarLevel {
        self.ends.sort_unstable_by_key(|&(i, _)| i);
        FVarLevel {
            width,
            values,
            corner_values,
            tags: self.tags,
            several: self.several,
            ends: self.ends,
            edge_tags,
            seam_corners: None,
        }
    }
}

/// Each vertex's row of `values` (`width` floats) as `known` gives it on a manifold mesh: the
/// value its first corner sees (`firsts`) for the vertices that no seam or boundary rule marked
/// (`mismatch`), zeros for the others (written when visited); all `nv` rows zeros without
/// `known`. Room for `room` floats. Made row by row, not zeroed first and written over, with
/// the common widths at constant width.
fn first_values(
    values: &[f32],
    width: usize,
    known: Option<(&[u32], &[u8])>,
    nv: usize,
    room: usize,
) -> Vec<f32> {
    fn rows<const N: usize>(
        values: &[f32],
        (firsts, mismatch): (&[u32], &[u8]),
        room: usize,
    ) -> Vec<f32> {
        let (rows, _) = values.as_chunks::<N>();
        let mut out: Vec<[f32; N]> = Vec::with_capacity(room.div_ceil(N));
        out.extend(firsts.iter().zip(mismatch).map(|(&first, &mismatched)| {
            match rows.get(first as usize) {
                Some(row) if mismatched == 0 => *row,
                _ => [0.0; N],
            }
        }));
        out.into_flattened()
    }
    let mut out = Vec::with_capacity(room);
    match (known, width) {
        (Some(known), 2) => return rows::<2>(values, known, room),
        (Some(known), 3) => return rows::<3>(values, known, room),
        (Some(known), 4) => return rows::<4>(values, known, room),
        (Some((firsts, mismatch)), _) => {
            for (&first, &mismatched) in firsts.iter().zip(mismatch) {
                // `u32::MAX` (no corner) would overflow the product on 32-bit targets.
                let row = (mismatched == 0 && first != u32::MAX).then(|| first as usize * width);
                match row.and_then(|at| values.get(at..at + width)) {
                    Some(row) => out.extend_from_slice(row),
                    None => out.resize(out.len() + width, 0.0),
                }
            }
        }
        (None, _) => out.resize(nv * width, 0.0),
    }
    out
}

/// The seams of a first level: each edge's tag, and per vertex whether a seam or the boundary
/// touches it (`early`: a seam marked it before OpenSubdiv's vertex-order visit reached it) and
/// the value its first corner sees (`firsts`, `u32::MAX` for a vertex without corners).
struct Seams {
    edge_tags: Vec<u8>,
    /// 1 where a seam or the boundary touches the vertex (bytes, for [`for_each_marked`]).
    mismatch: Vec<u8>,
    early: Vec<bool>,
    boundary: Vec<bool>,
    firsts: Vec<u32>,
}

impl Seams {
    fn find(mesh: &HalfEdgeMesh, indices: &[u32], mode: ModeRules) -> Self {
        let (nv, ne) = (mesh.num_vertices(), mesh.num_edges());
        let value_at = |x: u32, v: u32| {
            let corner = if mesh.he_from[x as usize] == v { x } else { mesh.next_in_cell(x) };
            indices[corner as usize]
        };
        let mut edge_tags = vec![0u8; ne];
        let mut mismatch = vec![0u8; nv];
        // OpenSubdiv visits the vertices in order and marks both ends of a seam when it meets
        // the seam at one of them; a boundary vertex is tested for the mode's own sharpening
        // only if no seam marked it before its turn.
        let mut early = vec![false; nv];
        let mut boundary = vec![false; nv];
        let seam_tag =
            edge_tag::MISMATCH | if mode.linear_boundaries { edge_tag::LINEAR } else { 0 };
        let mut mark_seam = |e: u32, [a, b]: [u32; 2], at_a: bool, at_b: bool| {
            edge_tags[e as usize] = seam_tag;
            mismatch[a as usize] = 1;
            mismatch[b as usize] = 1;
            if at_a {
                early[a as usize] = true;
                early[b as usize] |= b > a;
            }
            if at_b {
                early[b as usize] = true;
                early[a as usize] |= a > b;
            }
        };
        let firsts = if mesh.has_simple_edges() {
            simple_seams(mesh, indices, &mut boundary, mark_seam)
        } else {
            for e in 0..ne {
                let hs = &mesh.edge_half_edges[mesh.edge_range(e)];
                let [a, b] = mesh.edge_vertices[e];
                if hs.len() == 1 {
                    boundary[a as usize] = true;
                    boundary[b as usize] = true;
                    continue;
                }
                let (va, vb) = (value_at(hs[0], a), value_at(hs[0], b));
                let (mut at_a, mut at_b) = (false, false);
                for &x in &hs[1..] {
                    at_a |= value_at(x, a) != va;
                    at_b |= value_at(x, b) != vb;
                }
                if at_a || at_b {
                    mark_seam(e as u32, [a, b], at_a, at_b);
                }
            }
            let first = |v: usize| {
                let first = mesh.out_half_edges(v as u32).first();
                first.map_or(u32::MAX, |&h| indices[h as usize])
            };
            (0..nv).map(first).collect()
        };
        Seams { edge_tags, mismatch, early, boundary, firsts }
    }
}

/// [`Seams::find`] on a mesh with simple edges (at most two half-edges each, running opposite
/// ways), vertex by vertex; returns each vertex's first value. A seam passes through a vertex
/// only where its corners see different values, which few do: every vertex's corners are
/// compared with its first (their indices are read next to each other, and the first is the
/// vertex's value when nothing differs), and only the edges of the vertices where one differs
/// are tested as an edge-by-edge scan would (a vertex whose faces form several fans may differ
/// between fans without a seam). The boundary is read from each vertex's first half-edge,
/// which is a boundary one when the vertex has one. The first values come out of the same
/// reads: with their copy, about 10 ms against 13 natively and 10 against 16 in wasm on the
/// 1M-quad torus, where the edge-by-edge scan read every half-edge's twin and the values
/// across it, and the copy then found each vertex's first corner again.
fn simple_seams(
    mesh: &HalfEdgeMesh,
    indices: &[u32],
    boundary: &mut [bool],
    mut mark_seam: impl FnMut(u32, [u32; 2], bool, bool),
) -> Vec<u32> {
    let (offsets, out) = (&mesh.vertex_offsets, &mesh.vertex_half_edges);
    let twins = &mesh.he_next_around_edge;
    let mut differing = Vec::new();
    let mut firsts = vec![u32::MAX; mesh.num_vertices()];
    let vertices = firsts.iter_mut().zip(boundary.iter_mut()).zip(offsets.windows(2));
    for (v, ((first, boundary), range)) in vertices.enumerate() {
        let Some(corners) = out.get(range[0] as usize..range[1] as usize) else { continue };
        let Some((&h0, rest)) = corners.split_first() else { continue };
        let value = indices[h0 as usize];
        *first = value;
        *boundary = twins[h0 as usize] == h0;
        if rest.iter().any(|&h| indices[h as usize] != value) {
            differing.push(v as u32);
        }
    }
    // An edge between two such vertices is tested from both: marking a seam twice changes
    // nothing.
    for v in differing {
        for &h in mesh.out_half_edges(v) {
            let t = twins[h as usize];
            if t == h {
                continue;
            }
            let next = mesh.next_in_cell(h);
            let at_a = indices[h as usize] != indices[mesh.next_in_cell(t) as usize];
            let at_b = indices[next as usize] != indices[t as usize];
            if at_a || at_b {
                mark_seam(mesh.he_edge[h as usize], [v, mesh.he_from[next as usize]], at_a, at_b);
            }
        }
    }
    firsts
}

/// What gathering a value's span finds (OpenSubdiv's `FVarLevel::ValueSpan`).
#[derive(Clone, Copy, Debug, Default)]
struct Span {
    size: usize,
    start: usize,
    /// Seams inside the span, or more than one run of faces: the value is a corner.
    discts: i32,
    semi_sharp: u32,
    inf_sharp: u32,
}

enum EdgeClass {
    Seam,
    Infinite,
    SemiSharp,
    Smooth,
}

impl FVarLevel {
    /// Number of values.
    pub fn num_values(&self) -> usize {
        self.tags.len()
    }

    /// `[second value, count]` of vertex `v` when it has several values.
    #[inline]
    fn several_of(&self, v: u32) -> Option<[u32; 2]> {
        if self.tags[v as usize] & tag::MISMATCH == 0 {
            return None;
        }
        let i = self.several.binary_search_by_key(&v, |x| x[0]).ok()?;
        Some([self.several[i][1], self.several[i][2]])
    }

    /// Number of values of vertex `v`.
    #[inline]
    pub(crate) fn count(&self, v: u32) -> u32 {
        self.several_of(v).map_or(1, |[_, n]| n)
    }

    /// Value `s` of vertex `v` (its first is `v`).
    #[inline]
    pub(crate) fn value(&self, v: u32, s: u32) -> u32 {
        match (s, self.several_of(v)) {
            (0, _) | (_, None) => v,
            (s, Some([second, _])) => second + s - 1,
        }
    }

    /// Which of vertex `v`'s values `value` is.
    #[inline]
    fn sibling(&self, v: u32, value: u32) -> u32 {
        match self.several_of(v) {
            Some([second, _]) if value != v => value - second + 1,
            _ => 0,
        }
    }

    /// The first level's topology from a channel's `indices` (one per face corner) into
    /// `values` (`width` floats each), under `mode`: its values become one per vertex and
    /// sibling. OpenSubdiv's `FVarLevel::completeTopologyFromFaceValues`, including the order in
    /// which it visits vertices where that changes a result (which boundary edges are linear).
    pub(crate) fn base(
        mesh: &HalfEdgeMesh,
        values: &[f32],
        width: usize,
        indices: &[u32],
        sharp: &LevelSharpness,
        mode: ModeRules,
    ) -> Self {
        let nv = mesh.num_vertices();
        let Seams { mut edge_tags, mut mismatch, early, boundary, firsts } =
            Seams::find(mesh, indices, mode);
        let smooth_corners_sharp = !sharp.sharp_corners && mode.corners_sharp;
        for v in 0..nv as u32 {
            if !boundary[v as usize] || early[v as usize] {
                continue;
            }
            let out = mesh.out_half_edges(v);
            if mode.linear_boundaries && !out.is_empty() {
                mismatch[v as usize] = 1;
                for &h in out {
                    for x in [h, mesh.prev_in_cell(h)] {
                        if mesh.he_next_around_edge[x as usize] == x {
                            edge_tags[mesh.he_edge[x as usize] as usize] |= edge_tag::LINEAR;
                        }
                    }
                }
            } else if out.len() == 1 && smooth_corners_sharp {
                mismatch[v as usize] = 1;
            }
        }

        let mut numbering = Numbering::new(nv);
        // Room for a second value at each mismatched vertex (a seam's, most often), so that the
        // values after the vertices' first ones seldom move the whole array.
        let mut mismatched = Vec::new();
        for_each_marked(&mismatch, 1, |v| mismatched.push(v as u32));
        let room = (nv + 2 * mismatched.len()) * width;
        let mut extra_values = Vec::new();
        // A vertex with one value numbers it as itself, so its corners see the vertex: start
        // from that (a copy), and let the vertices with several values write theirs.
        let mut corner_values = mesh.he_from.clone();
        let row = |i: u32| &values[i as usize * width..(i as usize + 1) * width];
        let maybe_non_manifold =
            mesh.is_non_manifold() || sharp.tags.is_some_and(|t| !t.non_manifold.is_empty());
        // On a manifold mesh, a vertex that no seam or boundary rule touches has the one value
        // its first corner sees: made in one tight pass, the mismatched ones visited after.
        let manifold_firsts = (!maybe_non_manifold).then_some((&firsts[..], &mismatch[..]));
        let mut values_out = first_values(values, width, manifold_firsts, nv, room);
        let visit = if maybe_non_manifold { (0..nv as u32).collect() } else { mismatched };
        let (mut fan, mut siblings) = (Vec::new(), Vec::new());
        let mut uniques = Distinct::default();
        for v in visit {
            let out = mesh.out_half_edges(v);
            // A vertex without faces keeps one value (zero) that no corner sees.
            let Some(&first_corner) = out.first() else { continue };
            let manifold = !maybe_non_manifold
                || (!sharp.tags.is_some_and(|t| t.is_non_manifold_vertex(v))
                    && fan_order(mesh, v, &mut fan).is_some());
            if mismatch[v as usize] == 0 {
                let value = indices[first_corner as usize];
                // Faces around a non-manifold vertex may disagree without any seam.
                if manifold || out.iter().all(|&h| indices[h as usize] == value) {
                    let target = &mut values_out[v as usize * width..(v as usize + 1) * width];
                    for (t, &x) in target.iter_mut().zip(row(value)) {
                        *t = x;
                    }
                    continue;
                }
            }
            let open = if manifold {
                fan_order(mesh, v, &mut fan).unwrap_or(false)
            } else {
                fan.clear();
                fan.extend_from_slice(out);
                false
            };
            uniques.clear();
            siblings.clear();
            for (i, &h) in fan.iter().enumerate() {
                let x = indices[h as usize];
                let s = if i > 0 && indices[fan[i - 1] as usize] == x {
                    siblings[i - 1]
                } else if i > 0
                    && (uniques.list.len() == 1
                        || (uniques.list.len() == 2 && uniques.list[0] != x))
                {
                    // OpenSubdiv compares a third run's value with the first value only, so
                    // a value met again after another one becomes a sibling of its own (with
                    // a span of its own); results depend on it.
                    uniques.push(x)
                } else {
                    uniques.find(x).unwrap_or_else(|| uniques.push(x))
                };
                siblings.push(s);
            }
            let uniques = &uniques.list;
            let second = numbering.add(v, uniques.len() as u32);
            let value_of = |s: usize| if s == 0 { v } else { second + s as u32 - 1 };
            for (&h, &s) in fan.iter().zip(&siblings) {
                corner_values[h as usize] = value_of(s);
            }
            let spans = if manifold {
                let class = |e: u32| {
                    if edge_tags[e as usize] & edge_tag::MISMATCH != 0 {
                        return EdgeClass::Seam;
                    }
                    match sharp.edge(mesh, e) {
                        s if s >= SHARPNESS_INFINITE => EdgeClass::Infinite,
                        s if s > 0.0 => EdgeClass::SemiSharp,
                        _ => EdgeClass::Smooth,
                    }
                };
                gather_spans(mesh, &fan, open, &siblings, uniques.len(), class)
            } else {
                vec![Span { discts: 1, ..Span::default() }; uniques.len()]
            };
            let vertex_sharpness = sharp.vertex(mesh, v);
            let n = uniques.len();
            let mut all_corners = mode.linear_boundaries
                || vertex_sharpness >= SHARPNESS_INFINITE
                || !manifold
                || (mode.dependent_sharpness && n > 2)
                || (mode.sharpen_darts && n == 1 && !boundary[v as usize]);
            let mut dependent = false;
            if !all_corners && mode.dependent_sharpness && n == 2 {
                let [s0, s1] = [spans[0], spans[1]];
                all_corners =
                    s0.inf_sharp > 0 || s1.inf_sharp > 0 || s0.discts > 0 || s1.discts > 0;
                if mode.sharpen_both_if_one_corner {
                    all_corners |= s0.size == 1 || s1.size == 1;
                }
                dependent = (s0.semi_sharp > 0) != (s1.semi_sharp > 0);
            }
            for (s, span) in spans.iter().enumerate() {
                let mut t = tag::MISMATCH;
                let mut ends = None;
                let corner = span.discts > 0
                    || all_corners
                    || span.inf_sharp > 0
                    || (span.size == 1 && mode.corners_sharp);
                if !corner {
                    t |= if span.semi_sharp > 0 || is_semi_sharp(vertex_sharpness) {
                        tag::SEMI_SHARP
                    } else if dependent {
                        tag::SEMI_SHARP | tag::DEP_SHARP
                    } else {
                        tag::CREASE
                    };
                    let last = (span.start + span.size - 1) % fan.len();
                    ends = Some([fan[span.start], fan[last]]);
                }
                numbering.tag(value_of(s), t, ends);
                if s == 0 {
                    values_out[v as usize * width..(v as usize + 1) * width]
                        .copy_from_slice(row(uniques[0]));
                } else {
                    extra_values.extend_from_slice(row(uniques[s]));
                }
            }
        }
        values_out.extend_from_slice(&extra_values);
        numbering.finish(width, values_out, corner_values, edge_tags)
    }

    /// The tag of edge `e`; edges past the stored ones (a refined level's inner edges) have
    /// none.
    #[inline]
    pub(crate) fn edge_tag(&self, e: u32) -> u8 {
        self.edge_tags.get(e as usize).copied().unwrap_or(0)
    }

    /// Renumbers the edge tags of a level that [`Split::Mixed`] made from a parent with
    /// `parent_vertices` vertices and its first edge point at `edge_base`, once `child` is
    /// built from its faces (which numbers edges its own way): a half of a parent edge joins an
    /// old vertex to the edge's point and keeps the edge's tag; inner edges have none.
    pub(crate) fn renumber_edge_tags(
        &mut self,
        child: &HalfEdgeMesh,
        parent_vertices: usize,
        edge_base: usize,
    ) {
        let by_parent_edge = std::mem::take(&mut self.edge_tags);
        self.edge_tags = child
            .edge_vertices
            .iter()
            .map(|&[a, b]| {
                let (low, high) = (a.min(b) as usize, a.max(b) as usize);
                if low < parent_vertices && high >= edge_base {
                    by_parent_edge.get(2 * (high - edge_base)).copied().unwrap_or(0)
                } else {
                    0
                }
            })
            .collect();
    }

    /// The crease ends of `value` (see [`FVarLevel::ends`]).
    pub(crate) fn crease_ends(&self, value: u32) -> [u32; 2] {
        match self.ends.binary_search_by_key(&value, |&(v, _)| v) {
            Ok(i) => self.ends[i].1,
            Err(_) => [0, 0],
        }
    }

    /// The values at the far ends of crease `value`'s span: the next corner after its first
    /// face's and the one before its last face's (see [`FVarLevel::ends`]).
    pub(crate) fn crease_end_values(&self, mesh: &HalfEdgeMesh, value: u32) -> [u32; 2] {
        let [start, end] = self.crease_ends(value);
        [
            self.corner_values[mesh.next_in_cell(start) as usize],
            self.corner_values[mesh.prev_in_cell(end) as usize],
        ]
    }

    /// The value of `v`'s end of edge-side half-edge `x` (the corner of `x`'s face at `v`).
    pub(crate) fn value_at(&self, mesh: &HalfEdgeMesh, x: u32, v: u32) -> u32 {
        let corner = if mesh.he_from[x as usize] == v { x } else { mesh.next_in_cell(x) };
        self.corner_values[corner as usize]
    }

    /// The cells next to a seam, in order: every cell around a vertex with several values
    /// (which holds each cell with a corner that sees a value other than its vertex's first),
    /// and those with a seam edge. Every other cell's corners see their vertices (numbered as
    /// the vertices), so its children and the rules that read it need no face-varying care
    /// ([`FVarLevel::child_topology`], `interpolate`). Found from the seams, which are sparse,
    /// rather than by reading every corner.
    pub(crate) fn cells_near_seams(&self, mesh: &HalfEdgeMesh) -> Vec<u32> {
        let mut cells = Vec::new();
        for &[v, ..] in &self.several {
            cells.extend(mesh.out_half_edges(v).iter().map(|&h| mesh.cell_of(h)));
        }
        for_each_marked(&self.edge_tags, edge_tag::MISMATCH, |e| {
            let sides = &mesh.edge_half_edges[mesh.edge_range(e)];
            cells.extend(sides.iter().map(|&h| mesh.cell_of(h)));
        });
        cells.sort_unstable();
        cells.dedup();
        cells
    }

    /// The next level's topology (no values yet) after `split` of `mesh`: OpenSubdiv's
    /// `FVarRefinement::applyRefinement` for a uniform split.
    pub(crate) fn child_topology(
        &self,
        mesh: &HalfEdgeMesh,
        split: Split,
        sharp: &LevelSharpness,
        mode: ModeRules,
        near_seams: &[u32],
        implicit: bool,
    ) -> FVarLevel {
        let (nv, ne) = (mesh.num_vertices(), mesh.num_edges());
        let (face_point_of, face_points) = split.face_points(mesh);
        let edge_base = nv + face_points;
        let mut next = Numbering::new(edge_base + ne);
        // Children of old vertices: one value per parent value when the vertex mismatched.
        for_each_marked(&self.tags[..nv.min(self.tags.len())], tag::MISMATCH, |v| {
            let v = v as u32;
            let count = self.count(v);
            let second = next.add(v, count);
            for j in 0..count {
                let (p, c) = (self.value(v, j), if j == 0 { v } else { second + j - 1 });
                let t = self.tags[p as usize];
                // The child face at parent corner `h` leaves the child vertex on `4h`.
                let ends = (t & (tag::CREASE | tag::SEMI_SHARP) != 0)
                    .then(|| self.crease_ends(p).map(|h| 4 * h));
                next.tag(c, t, ends);
            }
        });
        let split_tag =
            if mode.smooth_boundaries() { tag::MISMATCH | tag::CREASE } else { tag::MISMATCH };
        // The inner edges that follow the halves of parent edges are never seams (see
        // `edge_tag`). A last level (`implicit`) needs no edge tags: only a next level reads
        // them.
        let edge_tags = if implicit {
            Vec::new()
        } else {
            let mut halves: Vec<u8> = self.edge_tags.iter().flat_map(|&t| [t, t]).collect();
            halves.resize(2 * ne, 0);
            halves
        };
        let parent_tags = &self.edge_tags[..ne.min(self.edge_tags.len())];
        for_each_marked(parent_tags, u8::MAX, |e| {
            let cv = (edge_base + e) as u32;
            if parent_tags[e] & edge_tag::MISMATCH == 0 {
                next.tag(cv, split_tag, None);
                return;
            }
            // A seam's edge point: one value per face, its span the children of that face at
            // the edge point, bounded by the edge's halves.
            let sides = &mesh.edge_half_edges[mesh.edge_range(e)];
            let second = next.add(cv, sides.len() as u32);
            for (j, &x) in sides.iter().enumerate() {
                let c = if j == 0 { cv } else { second + j as u32 - 1 };
                let ends = (split_tag & tag::CREASE != 0).then(|| {
                    let toward_end = split.child_step(mesh, 4 * mesh.next_in_cell(x), false);
                    [toward_end, split.child_step(mesh, 4 * x, true)]
                });
                next.tag(c, split_tag, ends);
            }
        });
        let mut next = next.finish(self.width, Vec::new(), Vec::new(), edge_tags);
        if mode.smooth_boundaries() && sharp.tags.is_some() {
            next.reclassify_semi_sharp(mesh, self, sharp, mode);
        }

        // The value each child corner sees: where nothing mismatches, the child vertex itself.
        let old = |h: u32| {
            let v = mesh.he_from[h as usize];
            let p = self.corner_values[h as usize];
            if p == v {
                v
            } else {
                next.value(v, self.sibling(v, p))
            }
        };
        let side = |x: u32| {
            let e = mesh.he_edge[x as usize];
            let cv = edge_base as u32 + e;
            if self.edge_tag(e) & edge_tag::MISMATCH == 0 {
                return cv;
            }
            let sides = &mesh.edge_half_edges[mesh.edge_range(e as usize)];
            next.value(cv, sides.iter().position(|&y| y == x).unwrap_or(0) as u32)
        };
        let face_point = |c: u32| nv as u32 + face_point_of.of(c).unwrap_or(0);
        // Cell `c`'s child corners (four per half-edge), each seeing its value.
        let cell_corners = |c: u32, out: &mut [u32]| {
            let cell = mesh.cell_range(c as usize);
            if split.splits_into_triangles(mesh, c) {
                let [h0, h1, h2] = [0, 1, 2].map(|k| (cell.start + k) as u32);
                let [e0, e1, e2] = [side(h0), side(h1), side(h2)];
                let children = [old(h0), e0, e2, e0, old(h1), e1, e2, e1, old(h2), e1, e2, e0];
                out.copy_from_slice(&children);
            } else {
                let face = face_point(c);
                for (h, out) in cell.zip(out.chunks_exact_mut(4)) {
                    let h = h as u32;
                    out.copy_from_slice(&[old(h), side(h), face, side(mesh.prev_in_cell(h))]);
                }
            }
        };
        // A cell away from seams has child corners that see the child vertices: the child
        // faces' own indices, which the uniform splits make whole (or leave implicit); the
        // cells near a seam are then written over.
        if implicit && split == Split::Quad {
            let mut seams = SeamCorners::default();
            for &c in near_seams {
                let cell = mesh.cell_range(c as usize);
                let from = seams.values.len();
                seams.values.resize(from + 4 * cell.len(), 0);
                cell_corners(c, &mut seams.values[from..]);
                seams.spans.push([4 * cell.start as u32, 4 * cell.end as u32, from as u32]);
            }
            next.seam_corners = Some(seams);
            return next;
        }
        let mut corners = match split {
            Split::Quad => crate::refine::pqq::child_face_indices(mesh),
            Split::Triangle => crate::refine::ptq::child_face_indices(mesh),
            Split::Mixed => vec![0; 4 * mesh.num_half_edges()],
        };
        let mut write = |c: u32| {
            let cell = mesh.cell_range(c as usize);
            cell_corners(c, &mut corners[4 * cell.start..4 * cell.end]);
        };
        match split {
            Split::Mixed => (0..mesh.num_cells() as u32).for_each(&mut write),
            _ => near_seams.iter().for_each(|&c| write(c)),
        }
        next.corner_values = corners;
        next
    }

    /// Semi-sharp values whose sharpness has decayed at this child level become creases
    /// (OpenSubdiv's `FVarRefinement::reclassifySemisharpValues`); `parent` is the level this
    /// one refines, `sharp` its sharpness.
    fn reclassify_semi_sharp(
        &mut self,
        mesh: &HalfEdgeMesh,
        parent: &FVarLevel,
        sharp: &LevelSharpness,
        mode: ModeRules,
    ) {
        for v in 0..mesh.num_vertices() as u32 {
            if self.tags[v as usize] & tag::MISMATCH == 0 {
                continue;
            }
            let vertex_sharpness = sharp.vertex(mesh, v);
            let (mut semi_edges, mut child_semi_edges) = (false, false);
            for &h in mesh.out_half_edges(v) {
                for x in [h, mesh.prev_in_cell(h)] {
                    let e = mesh.he_edge[x as usize];
                    semi_edges |= is_semi_sharp(sharp.edge(mesh, e));
                    child_semi_edges |= is_semi_sharp(sharp.child_edge(mesh, e, v));
                }
            }
            if !is_semi_sharp(vertex_sharpness) && !semi_edges {
                continue;
            }
            if decay(vertex_sharpness) > 0.0 {
                continue;
            }
            let to_crease = |t: &mut u8| {
                *t = (*t & !(tag::SEMI_SHARP | tag::DEP_SHARP)) | tag::CREASE;
            };
            let count = self.count(v);
            let values: Vec<u32> = (0..count).map(|j| self.value(v, j)).collect();
            for (j, &c) in values.iter().enumerate() {
                let t = self.tags[c as usize];
                if t & tag::SEMI_SHARP == 0 || (child_semi_edges && t & tag::DEP_SHARP != 0) {
                    continue;
                }
                let mut still = false;
                if child_semi_edges {
                    let p = parent.value(v, j as u32);
                    span_inner_edges(mesh, parent.crease_ends(p), |e| {
                        still |= is_semi_sharp(sharp.child_edge(mesh, e, v));
                    });
                }
                if !still {
                    to_crease(&mut self.tags[c as usize]);
                }
            }
            if let ([a, b], true) = (&values[..], child_semi_edges && mode.dependent_sharpness) {
                let (a, b) = (*a, *b);
                let [t0, t1] = [self.tags[a as usize], self.tags[b as usize]];
                if t0 & tag::DEP_SHARP != 0 && t1 & tag::SEMI_SHARP == 0 {
                    self.tags[a as usize] &= !tag::DEP_SHARP;
                } else if t1 & tag::DEP_SHARP != 0 && t0 & tag::SEMI_SHARP == 0 {
                    self.tags[b as usize] &= !tag::DEP_SHARP;
                }
            }
        }
    }
}

/// Calls `visit(edge)` for each edge inside a span whose first and last faces leave its vertex
/// on `[start, end]`, walking across each face's incoming edge to the next face.
pub(crate) fn span_inner_edges(
    mesh: &HalfEdgeMesh,
    [start, end]: [u32; 2],
    mut visit: impl FnMut(u32),
) {
    let mut h = start;
    // A span never holds more faces than the vertex: the bound only guards a broken fan.
    for _ in 0..mesh.num_half_edges() {
        if h == end {
            return;
        }
        let incoming = mesh.prev_in_cell(h);
        visit(mesh.he_edge[incoming as usize]);
        let across = mesh.he_next_around_edge[incoming as usize];
        if across == incoming {
            return;
        }
        h = across;
    }
}

/// The outgoing half-edges of `v` in the order of its one fan (an open fan from its boundary
/// edge), into `fan`; `Some(open)`, or `None` when its faces do not form one fan.
fn fan_order(mesh: &HalfEdgeMesh, v: u32, fan: &mut Vec<u32>) -> Option<bool> {
    fan.clear();
    let out = mesh.out_half_edges(v);
    let start = *out.first()?;
    let open = mesh.he_next_around_edge[start as usize] == start;
    let mut h = start;
    while fan.len() < out.len() {
        fan.push(h);
        let incoming = mesh.prev_in_cell(h);
        let across = mesh.he_next_around_edge[incoming as usize];
        if across == incoming {
            return (open && fan.len() == out.len()).then_some(true);
        }
        if across == start {
            return (!open && fan.len() == out.len()).then_some(false);
        }
        if mesh.he_from[across as usize] != v {
            return None;
        }
        h = across;
    }
    None
}

/// The spans of the values around a manifold vertex whose faces (outgoing half-edges `fan`,
/// face `i` sharing the edge of `fan[i]` with face `i - 1`) see values `siblings`
/// (OpenSubdiv's `FVarLevel::gatherValueSpans`).
fn gather_spans(
    mesh: &HalfEdgeMesh,
    fan: &[u32],
    open: bool,
    siblings: &[usize],
    count: usize,
    class: impl Fn(u32) -> EdgeClass,
) -> Vec<Span> {
    let n = fan.len();
    let edge = |i: usize| mesh.he_edge[fan[i] as usize];
    let add = |span: &mut Span, e: u32| match class(e) {
        EdgeClass::Seam => span.discts += 1,
        EdgeClass::Infinite => span.inf_sharp += 1,
        EdgeClass::SemiSharp => span.semi_sharp += 1,
        EdgeClass::Smooth => {}
    };
    if count == 1 && !open {
        // An interior vertex with one value: its span starts at its seam, and a second seam
        // makes it a corner.
        let mut span = Span { size: n, ..Span::default() };
        let mut seam = false;
        for i in 0..n {
            if let EdgeClass::Seam = class(edge(i)) {
                if seam {
                    span.discts = 1;
                    break;
                }
                seam = true;
                span.start = i;
            } else {
                add(&mut span, edge(i));
            }
        }
        return vec![span];
    }
    let mut spans = vec![Span::default(); count];
    spans[0].size = 1;
    let wraps = !open && siblings[n - 1] == 0;
    if wraps {
        add(&mut spans[0], edge(0));
    }
    for i in 1..n {
        let s = siblings[i];
        if s == siblings[i - 1] {
            add(&mut spans[s], edge(i));
        } else {
            if spans[s].size > 0 {
                spans[s].discts += 1;
            }
            spans[s].start = i;
        }
        spans[s].size += 1;
    }
    if wraps {
        spans[0].discts -= 1;
    }
    spans
}
