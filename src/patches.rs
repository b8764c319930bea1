//! Regular patches: where Catmull-Clark's limit surface over a base face is a uniform bicubic
//! B-spline patch, the limit points of the output vertices on that face are evaluated from its
//! sixteen control points directly, instead of from their stencils.
//!
//! A face is regular when it is a quad whose four corners are smooth interior vertices with four
//! quads around them: the surface over it is then the tensor-product cubic B-spline of the 4×4
//! control points around it (Catmull and Clark 1978; OpenSubdiv's `Far::PatchTable` uses the
//! same patches for its regular faces). A vertex of level `L` on such a face sits at parameters
//! `(i, j) / 2^L`, and its limit point is the patch's value there.
//!
//! Why: a limit row reads about 14 entries per point (8 bytes each, more than 110 per point
//! with the output), so a frame of limit points from the table is bound by memory bandwidth. A
//! patch reads 64 bytes of control indices for all its points, and the B-spline weights at the
//! sample parameters are shared by every patch. The points of the other faces (extraordinary
//! vertices, creases, boundaries) keep their stencil rows.
//!
//! With normals the tangents are `∂u` and `∂v` of the patch, summed over the control points'
//! differences from one of them (`Σ w (x - x0)`, as the table's rows sum theirs, see
//! `StencilTable::points_and_normals`): the tangent weights sum to 0, and summed on the points
//! themselves f32 rounded the patches' and the rows' normals up to 1e-4 rad apart, where the
//! GPU evaluator (which runs the rows) must give the CPU evaluator's normals to 1e-5.

use crate::mesh::{HalfEdgeMesh, PolyMesh};
use crate::stencil::{ClosedForms, Lanes, Normals, StencilTable};

/// An output vertex's patch and its sample `(i, j)` there ([`RegularPatches::owners`]).
pub(crate) type Owner = (u32, [u8; 2]);

/// The patch of an output vertex that no patch gives.
pub(crate) const NO_PATCH: u32 = u32::MAX;

/// The regular faces of a base mesh refined `levels` times, and for each the output vertices
/// its patch gives (each output vertex belongs to at most one patch).
#[derive(Clone, Debug, Default)]
pub(crate) struct RegularPatches {
    /// Each patch's 16 control vertices, row by row (`v`), each row along `u`.
    controls: Vec<[u32; 16]>,
    /// `offsets[p]..offsets[p + 1]` are patch `p`'s entries in `points` and `params`.
    offsets: Vec<u32>,
    /// Output vertex of each entry.
    points: Vec<u32>,
    /// `(i, j)` of each entry: parameters `(i, j) / 2^levels`.
    params: Vec<[u8; 2]>,
    /// The output vertices no patch gives, ascending: their stencil rows give them.
    rest: Vec<u32>,
    /// The cubic B-spline basis and its derivative at each sample `k / 2^levels`.
    basis: Vec<[[f32; 4]; 2]>,
}

impl RegularPatches {
    /// The patches of `base` refined `levels` times by Catmull-Clark into the quads `faces`
    /// (OpenSubdiv's child order, no face left out), with `outputs` output vertices; `None` when
    /// no face is regular or the level count is out of the parameters' range.
    pub(crate) fn new(
        base: &HalfEdgeMesh,
        faces: &PolyMesh,
        levels: u32,
        outputs: usize,
    ) -> Option<Self> {
        if levels == 0 || levels > 7 || !base.has_simple_edges() || base.is_non_manifold() {
            return None;
        }
        let cells = base.num_cells();
        let mut controls = Vec::new();
        let patch_of: Vec<u32> = (0..cells)
            .map(|c| match regular_controls(base, c) {
                Some(points) => {
                    controls.push(points);
                    controls.len() as u32 - 1
                }
                None => u32::MAX,
            })
            .collect();
        if controls.is_empty() || faces.face_sizes.iter().any(|&n| n != 4) {
            return None;
        }
        let steps = 1usize << levels;
        let expected = base.num_half_edges() << (2 * (levels - 1));
        if faces.face_sizes.len() != expected {
            return None;
        }
        // Each output quad goes back to its base face through the child corner it was at each
        // level (a quad's children are numbered by its half-edges); its corners' parameters
        // follow. A vertex goes to the first patch that has it.
        let mut owner = vec![(u32::MAX, [0u8; 2]); outputs];
        for (f, quad) in faces.indices.chunks_exact(4).enumerate() {
            let mut path = [0usize; 8];
            let mut at = f;
            for step in path.iter_mut().take(levels as usize - 1) {
                *step = at % 4;
                at /= 4;
            }
            let cell = base.cell_of(at as u32) as usize;
            let patch = patch_of[cell];
            if patch == u32::MAX {
                continue;
            }
            let n = steps as i32;
            let mut corners = [[0, 0], [n, 0], [n, n], [0, n]];
            let first = at - base.cell_range(cell).start;
            corners = child_square(corners, first);
            for &k in path[..levels as usize - 1].iter().rev() {
                corners = child_square(corners, k);
            }
            for (&v, [i, j]) in quad.iter().zip(corners) {
                let slot = owner.get_mut(v as usize)?;
                if slot.0 == u32::MAX {
                    *slot = (patch, [i as u8, j as u8]);
                }
            }
        }
        let mut counts = vec![0u32; controls.len() + 1];
        for &(p, _) in &owner {
            if p != u32::MAX {
                counts[p as usize + 1] += 1;
            }
        }
        for p in 1..counts.len() {
            counts[p] += counts[p - 1];
        }
        let offsets = counts.clone();
        let given = offsets[controls.len()] as usize;
        let (mut points, mut params) = (vec![0u32; given], vec![[0u8; 2]; given]);
        let mut rest = Vec::new();
        for (v, &(p, ij)) in owner.iter().enumerate() {
            if p == u32::MAX {
                rest.push(v as u32);
                continue;
            }
            let slot = &mut counts[p as usize];
            points[*slot as usize] = v as u32;
            params[*slot as usize] = ij;
            *slot += 1;
        }
        // In `i` order within a patch, so that each sample's row sums are made once.
        let mut entries = Vec::new();
        for p in 0..controls.len() {
            let range = offsets[p] as usize..offsets[p + 1] as usize;
            entries.clear();
            entries.extend(
                points[range.clone()].iter().copied().zip(params[range.clone()].iter().copied()),
            );
            entries.sort_unstable_by_key(|&(v, [i, j])| (i, j, v));
            for (&(v, ij), (point, param)) in
                entries.iter().zip(points[range.clone()].iter_mut().zip(&mut params[range]))
            {
                *point = v;
                *param = ij;
            }
        }
        let basis = (0..=steps).map(|k| bspline(k as f32 / steps as f32)).collect();
        Some(RegularPatches { controls, offsets, points, params, rest, basis })
    }

    /// Number of output vertices the patches give.
    pub(crate) fn num_points(&self) -> usize {
        self.points.len()
    }

    /// Bytes a frame reads besides its input: the control indices, each point's output vertex
    /// and sample, the rest's list.
    pub(crate) fn bytes(&self) -> u64 {
        let lists = std::mem::size_of_val(&self.controls[..])
            + std::mem::size_of_val(&self.offsets[..])
            + std::mem::size_of_val(&self.points[..])
            + std::mem::size_of_val(&self.params[..])
            + std::mem::size_of_val(&self.rest[..]);
        lists as u64
    }

    /// Per output vertex (of `outputs`), its patch and sample `(i, j)`; [`NO_PATCH`] for the
    /// vertices no patch gives. A stencil build leaves the rows of the others empty, and
    /// [`Self::rows_into`] writes them.
    pub(crate) fn owners(&self, outputs: usize) -> Vec<Owner> {
        let mut owners = vec![(NO_PATCH, [0u8; 2]); outputs];
        for p in 0..self.controls.len() {
            let range = self.offsets[p] as usize..self.offsets[p + 1] as usize;
            for (&v, &ij) in self.points[range.clone()].iter().zip(&self.params[range]) {
                if let Some(o) = owners.get_mut(v as usize) {
                    *o = (p as u32, ij);
                }
            }
        }
        owners
    }

    /// Bytes that the rows of the patches' points take in a table (see [`Self::rows_into`]):
    /// 4 per entry and 4 per weight (three weights with `tangents`, else one).
    pub(crate) fn row_bytes(&self, tangents: bool) -> u64 {
        let per_entry = if tangents { 16 } else { 8 };
        let nonzero = |k: u8| self.basis[k as usize][0].iter().filter(|&&b| b != 0.0).count();
        let entries: usize = self.params.iter().map(|&[i, j]| nonzero(i) * nonzero(j)).sum();
        per_entry * entries as u64
    }

    /// `table` with the rows of the patches' points made from the patches: the B-spline
    /// weights of each point's sample on its patch's 16 control points (the tensor products of
    /// the basis, and of the basis with its derivative for the tangents `∂u` and `∂v`), those
    /// that are not 0. These are the limit stencils in closed form, as OpenSubdiv's
    /// `Far::LimitStencilTableFactory` takes them from its regular patches; composed through
    /// the levels they took most of the build (a limit row gathers about 95 parent entries).
    /// `owners` is [`Self::owners`] of the table's rows.
    pub(crate) fn rows_into(&self, table: StencilTable, owners: &[Owner]) -> StencilTable {
        // Each patch's control points in ascending order, as every row of a table lists them.
        let ascending: Vec<[u8; 16]> = (self.controls.iter())
            .map(|controls| {
                let mut order: [u8; 16] = std::array::from_fn(|k| k as u8);
                order.sort_unstable_by_key(|&k| controls[k as usize]);
                order
            })
            .collect();
        table.with_rows(|v, entries| {
            let Some(&(p, [i, j])) = owners.get(v as usize).filter(|o| o.0 != NO_PATCH) else {
                return false;
            };
            let ([bi, di], [bj, dj]) = (self.basis[i as usize], self.basis[j as usize]);
            let controls = &self.controls[p as usize];
            for k in ascending[p as usize].map(usize::from) {
                let (r, c) = (k / 4, k % 4);
                let w = bj[r] * bi[c];
                if w != 0.0 {
                    entries.push((controls[k], [w, bj[r] * di[c], dj[r] * bi[c]]));
                }
            }
            true
        })
    }

    /// Patch `p`'s 16 control points, from the padded control points.
    fn control_points(&self, control: &[[f32; 4]], p: usize) -> [Lanes; 16] {
        self.controls[p].map(|i| control.get(i as usize).map_or(Lanes::ZERO, Lanes::load))
    }

    /// Patch `p`'s output vertices with their samples `(i, j)`, in `i` order.
    fn entries(&self, p: usize) -> impl Iterator<Item = (usize, [usize; 2])> + '_ {
        let range = self.offsets[p] as usize..self.offsets[p + 1] as usize;
        let params = self.params[range.clone()].iter().map(|&[i, j]| [i as usize, j as usize]);
        self.points[range].iter().map(|&v| v as usize).zip(params)
    }
}

impl ClosedForms for RegularPatches {
    fn rest(&self) -> &[u32] {
        &self.rest
    }

    /// Writes each patch's points from the padded control points.
    fn points(&self, control: &[[f32; 4]], positions: &mut [[f32; 3]]) {
        for p in 0..self.controls.len() {
            let points = self.control_points(control, p);
            // Each control row's value at the current sample `i`: the patch's points come in
            // `i` order, so each is made once for all its `j`.
            let (mut at, mut sums) = (usize::MAX, [Lanes::ZERO; 4]);
            for (v, [i, j]) in self.entries(p) {
                if i != at {
                    at = i;
                    let [b, _] = &self.basis[at];
                    for (sum, row) in sums.iter_mut().zip(points.chunks_exact(4)) {
                        *sum = row.iter().zip(b).fold(Lanes::ZERO, |s, (&x, &w)| s.add_lanes(x, w));
                    }
                }
                let [b, _] = &self.basis[j];
                let point = sums.iter().zip(b).fold(Lanes::ZERO, |s, (&x, &w)| s.add_lanes(x, w));
                point.store_xyz(&mut positions[v]);
            }
        }
    }

    /// Writes each patch's points and unit normals (`∂u × ∂v`, which point as the faces are
    /// wound; [`crate::limit::normal`], four at a time) from the padded control points. The
    /// sums run on the points' differences from the patch's control point (1, 1) (see the
    /// module's notes), and the positions add it back (the basis sums to 1).
    fn points_and_normals(
        &self,
        control: &[[f32; 4]],
        positions: &mut [[f32; 3]],
        normals: &mut [[f32; 3]],
    ) {
        // (A patch's points are not numbered in runs: no runs of four to look for.)
        let mut normals = Normals::<false>::new(normals);
        for p in 0..self.controls.len() {
            let points = self.control_points(control, p);
            let origin = points[5];
            let points = points.map(|x| x.sub(origin));
            // Each control row's value and `u`-derivative at the current sample `i`, made once
            // for all its `j` (the points come in `i` order).
            let (mut at, mut sums) = (usize::MAX, [Lanes::ZERO; 8]);
            for (v, [i, j]) in self.entries(p) {
                if i != at {
                    at = i;
                    let [b, d] = &self.basis[at];
                    for (r, row) in points.chunks_exact(4).enumerate() {
                        let (mut value, mut slope) = (Lanes::ZERO, Lanes::ZERO);
                        for (c, &x) in row.iter().enumerate() {
                            value = value.add_lanes(x, b[c]);
                            slope = slope.add_lanes(x, d[c]);
                        }
                        sums[r] = value;
                        sums[4 + r] = slope;
                    }
                }
                let [b, d] = &self.basis[j];
                let (mut point, mut du, mut dv) = (origin, Lanes::ZERO, Lanes::ZERO);
                for r in 0..4 {
                    point = point.add_lanes(sums[r], b[r]);
                    du = du.add_lanes(sums[4 + r], b[r]);
                    dv = dv.add_lanes(sums[r], d[r]);
                }
                if let Some(position) = positions.get_mut(v) {
                    point.store_xyz(position);
                }
                normals.push(v, du, dv);
            }
        }
    }
}

/// Whether any face of `base` is a regular patch (see [`RegularPatches::new`]).
pub(crate) fn any_regular(base: &HalfEdgeMesh) -> bool {
    regular_faces(base).is_some_and(|mut faces| faces.any(|regular| regular))
}

/// Whether every face of `base` is a regular patch: then every output vertex lies on one, and
/// the mesh is closed (a regular face's corners are interior).
pub(crate) fn all_regular(base: &HalfEdgeMesh) -> bool {
    regular_faces(base).is_some_and(|mut faces| faces.all(|regular| regular))
}

/// Per face of `base`, whether it is a regular patch; `None` for a mesh that has none (not a
/// simple 2-manifold, as [`RegularPatches::new`] requires).
fn regular_faces(base: &HalfEdgeMesh) -> Option<impl Iterator<Item = bool> + '_> {
    let manifold = base.has_simple_edges() && !base.is_non_manifold();
    manifold.then(|| (0..base.num_cells()).map(|c| regular_controls(base, c).is_some()))
}

/// The uniform cubic B-spline basis and its derivative at `t` in `[0, 1]`.
fn bspline(t: f32) -> [[f32; 4]; 2] {
    let s = 1.0 - t;
    let value = [
        s * s * s / 6.0,
        (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
        (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
        t * t * t / 6.0,
    ];
    let slope = [-0.5 * s * s, 1.5 * t * t - 2.0 * t, -1.5 * t * t + t + 0.5, 0.5 * t * t];
    [value, slope]
}

/// The parameters of child `k` of a square with corners `c` (as a quad's child at its corner
/// `k`: the corner, the midpoint of the side after it, the centre, the midpoint of the side
/// before it).
fn child_square(c: [[i32; 2]; 4], k: usize) -> [[i32; 2]; 4] {
    let mid = |a: [i32; 2], b: [i32; 2]| [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
    let centre = mid(c[0], c[2]);
    [c[k], mid(c[k], c[(k + 1) % 4]), centre, mid(c[k], c[(k + 3) % 4])]
}

/// The 16 control vertices of cell `c` when it is a regular face (see the module docs), row by
/// row from the side of its first half-edge: corners `v0..v3` at `(1, 1)`, `(1, 2)`, `(2, 2)`,
/// `(2, 1)` (row, column), so that `u` runs from `v0` to `v1` and `v` from `v0` to `v3`.
fn regular_controls(mesh: &HalfEdgeMesh, c: usize) -> Option<[u32; 16]> {
    let cell = mesh.cell_range(c);
    if cell.len() != 4 {
        return None;
    }
    let regular = |v: u32| {
        let out = mesh.out_half_edges(v);
        out.len() == 4
            && out.iter().all(|&h| {
                let twin = mesh.he_next_around_edge[h as usize];
                twin != h && mesh.cell_range(mesh.cell_of(h) as usize).len() == 4
            })
    };
    let from = |h: u32| mesh.he_from[h as usize];
    // Across half-edge `h` (from `a` to `b`), the quad on the other side: its vertices next to
    // `a` and next to `b`.
    let across = |h: u32| {
        let twin = mesh.he_next_around_edge[h as usize];
        let beyond = mesh.next_in_cell(twin);
        (beyond, from(mesh.next_in_cell(beyond)), from(mesh.prev_in_cell(twin)))
    };
    let hs = [0, 1, 2, 3].map(|k| (cell.start + k) as u32);
    if !hs.iter().all(|&h| regular(from(h))) {
        return None;
    }
    let v = hs.map(from);
    let sides = hs.map(|h| {
        let (beyond, x, y) = across(h);
        // The diagonal quad at `h`'s start: across the edge from it to `x`.
        let (_, _, diagonal) = across(beyond);
        (x, y, diagonal)
    });
    let [(x0, y0, d0), (x1, y1, d1), (x2, y2, d2), (x3, y3, d3)] = sides;
    Some([
        d0, x0, y0, d1, //
        y3, v[0], v[1], x1, //
        x3, v[3], v[2], y1, //
        d3, y2, x2, d2,
    ])
}
