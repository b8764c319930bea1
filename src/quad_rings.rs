//! Catmull-Clark's limit points and normals on a closed cage, from the last level's own points:
//! what [`crate::regular_rings`] does for Loop, for the cages the bicubic patches
//! ([`crate::patches`]) do not cover. A triangle cage (the horse, most glTF models) has no
//! regular face before level 2, so none of its limit points comes from a patch.
//!
//! Each frame makes every level's points by Catmull and Clark's smooth rules ([`QuadStep`],
//! numbered as `refine::pqq` numbers them: vertex points, face points, edge points), then
//! applies the limit masks of `rules::limit` (OpenSubdiv's `ComputeVertexLimitMask`) to each
//! vertex of the last level on its ring there. At valence 4, with `e_i` its neighbours and
//! `f_i` its faces' opposite corners counter-clockwise,
//!
//! ```text
//! P = (16v + 4 Σe + Σf) / 36,   t1 = 4(e0 - e2) + f0 - f1 - f2 + f3,   t2 = 4(e1 - e3) + f0 + f1 - f2 - f3,
//! ```
//!
//! OpenSubdiv's `tan1` and `tan2` there; at other valences the masks' weights are tabled per
//! valence. Why: a limit row of the horse at level 2 reads some 20 control points with three
//! weights each; a step reads about 5 points per point it makes, and a mask 9 at valence 4.
//! The table's rows stay whole, for `stencils()` and the GPU; as no frame reads them, the
//! evaluator makes the table only when asked for it (see `Evaluator::table`).

use crate::mesh::{HalfEdgeMesh, PolyMesh};
use crate::regular_rings::{Rings, MAX_VALENCE};
use crate::stencil::{ClosedForms, Lanes, Normals, PointSink, StencilTable, TableWriter};

/// Catmull-Clark's limit on a closed cage: the levels' steps, and the last level's rings.
#[derive(Clone, Debug)]
pub(crate) struct QuadRings {
    /// Level `k + 1`'s points from level `k`'s, for every level.
    steps: Vec<QuadStep>,
    /// The last level's vertices of valence 4: `[v, e0, f0, e1, f1, e2, f2, e3, f3]`, the
    /// ring as [`Rings::of_fans`] gives it here (per quad `i` counter-clockwise, the neighbour
    /// `e_i` it shares with the quad before and its corner `f_i` opposite the vertex), as byte
    /// offsets (16 bytes a padded point), which in wasm spare a shift per read.
    regular: Vec<[u32; 9]>,
    /// Its other vertices, `[v, start]`: the ring is `other_rings[start..]` up to the next
    /// one's start (or the end).
    others: Vec<[u32; 2]>,
    other_rings: Vec<u32>,
    /// Per valence (up to [`MAX_VALENCE`]), the limit masks' weights.
    masks: Vec<LimitMasks>,
    outputs: usize,
    /// False for refined points with limit normals (`normals` without `limit`): the points
    /// are the last level's own, the normals the limit's.
    limit: bool,
}

/// One level of Catmull and Clark's smooth rules on a closed cage whose every vertex has a
/// closed fan of 3 to [`MAX_VALENCE`] faces, in the order `refine::pqq` numbers the child level.
#[derive(Clone, Debug)]
pub(crate) struct QuadStep {
    /// `corners[cell_offsets[c]..cell_offsets[c + 1]]` are cell `c`'s corners.
    cell_offsets: Vec<u32>,
    corners: Vec<u32>,
    /// Per vertex, `around[vertex_offsets[v]..vertex_offsets[v + 1]]`: per incident face, the
    /// neighbour that follows `v` in it and the face.
    vertex_offsets: Vec<u32>,
    around: Vec<[u32; 2]>,
    /// Per edge, its ends and its two faces.
    edges: Vec<[u32; 4]>,
}

impl QuadStep {
    pub(crate) fn new(mesh: &HalfEdgeMesh) -> Option<Self> {
        if !mesh.has_simple_edges() || mesh.is_non_manifold() {
            return None;
        }
        let corners = mesh.he_from.clone();
        let mut cell_offsets = Vec::with_capacity(mesh.num_cells() + 1);
        cell_offsets.push(0);
        for c in 0..mesh.num_cells() {
            cell_offsets.push(mesh.cell_range(c).end as u32);
        }
        let edges = (0..mesh.num_edges())
            .map(|e| match mesh.edge_half_edges[mesh.edge_range(e)] {
                [h, twin] => {
                    let [a, b] = mesh.edge_vertices[e];
                    Some([a, b, mesh.cell_of(h), mesh.cell_of(twin)])
                }
                _ => None,
            })
            .collect::<Option<Vec<_>>>()?;
        let mut vertex_offsets = Vec::with_capacity(mesh.num_vertices() + 1);
        let mut around = Vec::with_capacity(mesh.num_half_edges());
        vertex_offsets.push(0);
        for v in 0..mesh.num_vertices() as u32 {
            let out = mesh.out_half_edges(v);
            if !(3..=MAX_VALENCE).contains(&out.len()) {
                return None;
            }
            let next = |h: u32| corners[mesh.next_in_cell(h) as usize];
            around.extend(out.iter().map(|&h| [next(h), mesh.cell_of(h)]));
            vertex_offsets.push(around.len() as u32);
        }
        Some(QuadStep { cell_offsets, corners, vertex_offsets, around, edges })
    }

    /// Number of points of the child level: a vertex point per vertex, a face point per cell,
    /// an edge point per edge.
    pub(crate) fn outputs(&self) -> usize {
        self.vertex_offsets.len() - 1 + self.cell_offsets.len() - 1 + self.edges.len()
    }

    pub(crate) fn bytes(&self) -> u64 {
        let lists = std::mem::size_of_val(&self.cell_offsets[..])
            + std::mem::size_of_val(&self.corners[..])
            + std::mem::size_of_val(&self.vertex_offsets[..])
            + std::mem::size_of_val(&self.around[..])
            + std::mem::size_of_val(&self.edges[..]);
        lists as u64
    }

    /// The child level's points, padded.
    pub(crate) fn padded(&self, points: &[[f32; 4]]) -> Vec<[f32; 4]> {
        let mut out = Vec::with_capacity(self.outputs());
        self.apply(points, &mut out);
        out
    }

    /// The step as a stencil table on this level's vertices: the rows of [`QuadStep::apply`]'s
    /// sums, each face point spread over its face's corners.
    pub(crate) fn table(&self) -> StencilTable {
        let vertices = self.vertex_offsets.len() - 1;
        let corners = |c: u32| {
            let span = self.cell_offsets.get(c as usize..c as usize + 2).unwrap_or(&[0, 0]);
            self.corners.get(span[0] as usize..span[1] as usize).unwrap_or(&[])
        };
        let face = |out: &mut TableWriter, c: u32, weight: f32| {
            let corners = corners(c);
            let each = weight / corners.len() as f32;
            corners.iter().for_each(|&x| out.add(x, each));
        };
        let entries = 2 * self.around.len() + vertices + self.corners.len() + 6 * self.edges.len();
        let mut out = TableWriter::new(vertices, self.outputs(), entries);
        let quads = self.corners.len() == 4 * (self.cell_offsets.len() - 1);
        for (v, span) in self.vertex_offsets.windows(2).enumerate() {
            let around = &self.around[span[0] as usize..span[1] as usize];
            let n = around.len() as f32;
            let v = v as u32;
            if quads {
                // Among quads each face point's corners are the vertex, its neighbour `q`, the
                // corner opposite and the next quad's `q`: so Catmull and Clark's weights
                // (n - 2)/n + 1/(4n) on the vertex, 3/(2n²) on each neighbour and 1/(4n²) on
                // each opposite corner, without spreading the face points.
                out.add(v, 1.0 - 2.0 / n + 0.25 / n);
                for &[q, c] in around {
                    let cell = &self.corners[4 * c as usize..4 * c as usize + 4];
                    let at = cell.iter().position(|&x| x == v).unwrap_or(0);
                    out.add(q, 1.5 / (n * n));
                    out.add(cell[(at + 2) % 4], 0.25 / (n * n));
                }
            } else {
                out.add(v, 1.0 - 2.0 / n);
                for &[q, c] in around {
                    out.add(q, 1.0 / (n * n));
                    face(&mut out, c, 1.0 / (n * n));
                }
            }
            out.end_row();
        }
        for c in 0..self.cell_offsets.len() as u32 - 1 {
            face(&mut out, c, 1.0);
            out.end_row();
        }
        for &[a, b, c0, c1] in &self.edges {
            out.add(a, 0.25);
            out.add(b, 0.25);
            face(&mut out, c0, 0.25);
            face(&mut out, c1, 0.25);
            out.end_row();
        }
        out.finish()
    }

    /// The child level's points from `points` (this level's, padded), to `out` in order.
    pub(crate) fn apply(&self, points: &[[f32; 4]], out: &mut impl PointSink) {
        let vertices = self.vertex_offsets.len() - 1;
        let cells = self.cell_offsets.len() - 1;
        if points.len() < vertices {
            return;
        }
        // SAFETY: the corners, the neighbours and the edges' ends are vertices of the mesh the
        // step was made from (`QuadStep::new`), so below `points.len()`; the faces are its
        // cells, below `faces.len()`. As in `regular_rings`, the checks are a good part of
        // these loops in wasm.
        let at = |i: u32| {
            debug_assert!((i as usize) < points.len());
            Lanes::load(unsafe { points.get_unchecked(i as usize) })
        };
        let faces: Vec<[f32; 4]> = match self.corners.as_chunks::<4>() {
            (quads, []) if quads.len() == cells => quads
                .iter()
                .map(|&[a, b, c, d]| at(a).add(at(b)).add(at(c).add(at(d))).scale(0.25).xyzw())
                .collect(),
            _ => (self.cell_offsets.windows(2))
                .map(|span| {
                    let corners = &self.corners[span[0] as usize..span[1] as usize];
                    let sum = corners.iter().fold(Lanes::ZERO, |sum, &v| sum.add(at(v)));
                    sum.scale(1.0 / corners.len() as f32).xyzw()
                })
                .collect(),
        };
        let face = |c: u32| {
            debug_assert!((c as usize) < faces.len());
            Lanes::load(unsafe { faces.get_unchecked(c as usize) })
        };
        out.put_all(self.vertex_offsets.windows(2).enumerate().map(|(v, span)| {
            // `v + (Σ (e_i - v) + Σ (F_i - v)) / n²`: Catmull and Clark's vertex rule,
            // `(n - 2)/n v + (Σ e_i + Σ F_i) / n²`, on differences.
            let centre = at(v as u32);
            let around = &self.around[span[0] as usize..span[1] as usize];
            let term = |sum: Lanes, &[q, c]: &[u32; 2]| {
                sum.add(at(q).sub(centre)).add(face(c).sub(centre))
            };
            match around {
                // Valence 4 (every edge point, and most vertices past level 1): a length the
                // compiler sees.
                [a, b, c, d] => {
                    let sum = term(term(Lanes::ZERO, a), b).add(term(term(Lanes::ZERO, c), d));
                    centre.add_lanes(sum, 1.0 / 16.0)
                }
                _ => {
                    let sum = around.iter().fold(Lanes::ZERO, term);
                    let n = around.len() as f32;
                    centre.add_lanes(sum, 1.0 / (n * n))
                }
            }
        }));
        out.put_all(faces.iter().map(Lanes::load));
        out.put_all(
            (self.edges.iter())
                .map(|&[a, b, c0, c1]| at(a).add(at(b)).add(face(c0).add(face(c1))).scale(0.25)),
        );
    }
}

/// The limit masks of a smooth Catmull-Clark vertex of one valence `n` (`rules::limit`): the
/// position's weight on each neighbour and on each face's opposite corner (differences from
/// the vertex), and the two tangents' weights on each.
#[derive(Clone, Debug, Default)]
struct LimitMasks {
    edge: f32,
    face: f32,
    /// Per `i`: `[first, second]` on `e_i`, then on `f_i`.
    tangents: Vec<[[f32; 2]; 2]>,
}

impl LimitMasks {
    fn new(n: usize) -> Self {
        use crate::rules::limit::{catmull_clark_face_scale, catmull_clark_tangent_weights};
        let (_, edge, face) = crate::rules::limit::catmull_clark_position_weights(n);
        let theta = std::f64::consts::TAU / n as f64;
        let cos = |i: usize| (theta * i as f64).cos();
        let mut tangents = Vec::with_capacity(n);
        catmull_clark_tangent_weights(n, cos, catmull_clark_face_scale(n), |_, weights| {
            tangents.push(weights.map(|pair| pair.map(|w| w as f32)));
        });
        LimitMasks { edge: edge as f32, face: face as f32, tangents }
    }
}

impl QuadRings {
    /// Catmull-Clark's limit from `steps`, every level of a closed cage
    /// ([`crate::smooth_levels::catmull_clark_steps`]), whose last level is the quads `faces`;
    /// `None` unless every vertex of that level has a closed ring. Without `limit`, the points
    /// are the last level's own (the normals still the limit's).
    pub(crate) fn new(steps: Vec<QuadStep>, faces: &PolyMesh, limit: bool) -> Option<Self> {
        let outputs = steps.last()?.outputs();
        if faces.face_sizes.iter().any(|&n| n != 4) {
            return None;
        }
        // Each corner's (next, opposite, previous) vertex: the fan's steps.
        let fan_steps = |[a, b, c, d]: [u32; 4]| {
            [(a, [b, c, d]), (b, [c, d, a]), (c, [d, a, b]), (d, [a, b, c])]
        };
        let quads = faces.indices.as_chunks::<4>().0;
        let rings = Rings::of_fans(quads, outputs, fan_steps, closed_ring)?;
        if outputs >= 1 << 28 {
            return None;
        }
        let (mut regular, mut others, mut other_rings) = (Vec::new(), Vec::new(), Vec::new());
        for v in 0..outputs as u32 {
            match *rings.of(v)? {
                [e0, f0, e1, f1, e2, f2, e3, f3] => {
                    regular.push([v, e0, f0, e1, f1, e2, f2, e3, f3].map(|i| i << 4))
                }
                ref ring => {
                    others.push([v, other_rings.len() as u32]);
                    other_rings.extend_from_slice(ring);
                }
            }
        }
        let masks = (0..=MAX_VALENCE)
            .map(|n| if n >= 3 { LimitMasks::new(n) } else { LimitMasks::default() })
            .collect();
        Some(QuadRings { steps, regular, others, other_rings, masks, outputs, limit })
    }

    /// Number of output vertices they give: all of them.
    pub(crate) fn num_points(&self) -> usize {
        self.outputs
    }

    /// What this adds to the table's bytes: the steps and the cases with their rings.
    pub(crate) fn bytes(&self) -> u64 {
        let cases = std::mem::size_of_val(&self.regular[..])
            + std::mem::size_of_val(&self.others[..])
            + std::mem::size_of_val(&self.other_rings[..]);
        self.steps.iter().map(QuadStep::bytes).sum::<u64>() + cases as u64
    }

    /// Each output vertex's limit point and tangents, from the padded control points.
    fn each(&self, control: &[[f32; 4]], mut emit: impl FnMut(usize, Lanes, [Lanes; 2])) {
        let mut points = std::borrow::Cow::Borrowed(control);
        for step in &self.steps {
            points = step.padded(&points).into();
        }
        if points.len() < self.outputs {
            return;
        }
        // SAFETY: the rings hold vertices below `self.outputs` (`Rings::of_fans` checked each),
        // so below `points.len()`; the regular cases hold them times 16.
        let at = |i: u32| {
            debug_assert!((i as usize) < points.len());
            Lanes::load(unsafe { points.get_unchecked(i as usize) })
        };
        let at_byte = |b: u32| {
            debug_assert!(b.is_multiple_of(16) && (b as usize) < 16 * points.len());
            Lanes::load(unsafe { &*points.as_ptr().byte_add(b as usize) })
        };
        for case in &self.regular {
            let [v, e0, f0, e1, f1, e2, f2, e3, f3] = case.map(at_byte);
            let edges = e0.add(e1).add(e2.add(e3));
            let faces = f0.add(f1).add(f2.add(f3));
            let point = match self.limit {
                true => faces.add_lanes(edges, 4.0).add_lanes(v, 16.0).scale(1.0 / 36.0),
                false => v,
            };
            let (f03, f12) = (f0.sub(f2), f1.sub(f3));
            let t1 = f03.sub(f12).add_lanes(e0.sub(e2), 4.0);
            let t2 = f03.add(f12).add_lanes(e1.sub(e3), 4.0);
            emit((case[0] >> 4) as usize, point, [t1, t2]);
        }
        let ends = self.others.iter().skip(1).map(|&[_, start]| start as usize);
        let ends = ends.chain([self.other_rings.len()]);
        for (&[v, start], end) in self.others.iter().zip(ends) {
            let ring = self.other_rings.get(start as usize..end).unwrap_or(&[]);
            let centre = at(v);
            let Some(m) = self.masks.get(ring.len() / 2) else { continue };
            let (mut edges, mut faces) = (Lanes::ZERO, Lanes::ZERO);
            let (mut t1, mut t2) = (Lanes::ZERO, Lanes::ZERO);
            for (pair, [on_edge, on_face]) in ring.as_chunks::<2>().0.iter().zip(&m.tangents) {
                let (e, f) = (at(pair[0]).sub(centre), at(pair[1]).sub(centre));
                edges = edges.add(e);
                faces = faces.add(f);
                t1 = t1.add_lanes(e, on_edge[0]).add_lanes(f, on_face[0]);
                t2 = t2.add_lanes(e, on_edge[1]).add_lanes(f, on_face[1]);
            }
            let point = match self.limit {
                true => centre.add_lanes(faces, m.face).add_lanes(edges, m.edge),
                false => centre,
            };
            emit(v as usize, point, [t1, t2]);
        }
    }
}

impl ClosedForms for QuadRings {
    fn rest(&self) -> &[u32] {
        &[]
    }

    fn points(&self, control: &[[f32; 4]], positions: &mut [[f32; 3]]) {
        self.each(control, |out, point, _| {
            if let Some(position) = positions.get_mut(out) {
                point.store_xyz(position);
            }
        });
    }

    fn points_and_normals(
        &self,
        control: &[[f32; 4]],
        positions: &mut [[f32; 3]],
        normals: &mut [[f32; 3]],
    ) {
        // The vertices come in order, in two runs: their normals mostly in runs of four.
        let mut normals = Normals::<true>::new(normals);
        self.each(control, |out, point, [t1, t2]| {
            if let Some(position) = positions.get_mut(out) {
                point.store_xyz(position);
            }
            normals.push(out, t1, t2);
        });
    }
}

/// Whether the fan steps `fan` (next, opposite, previous) of vertex `v` close into one ring of
/// distinct vertices other than `v`, left in `ring` as `[e0, f0, e1, f1, ...]`.
fn closed_ring(fan: &[[u32; 3]], v: u32, ring: &mut Vec<u32>) -> bool {
    ring.clear();
    let mut step = fan[0];
    for _ in 0..fan.len() {
        ring.extend_from_slice(&step[..2]);
        // The quad after this one, counter-clockwise, starts at this one's previous corner.
        let Some(&next) = fan.iter().find(|s| s[0] == step[2]) else { return false };
        step = next;
    }
    let closes = step == fan[0];
    let distinct = (0..ring.len()).all(|i| !ring[i + 1..].contains(&ring[i]));
    closes && !ring.contains(&v) && distinct
}
