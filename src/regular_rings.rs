//! Loop's limit points in closed form from the level before the last, where that level is
//! regular: what [`crate::patches`] does for Catmull-Clark, for Loop's scheme.
//!
//! At the last level `L`, the limit point of a vertex's child is the limit mask of Loop's
//! scheme (Loop 1987; the masks of `rules::limit`) applied to that child's ring at level `L`,
//! and the child's ring is itself made by the refinement rules from level `L - 1`. Where the
//! vertices involved at level `L - 1` are smooth interior vertices of valence 6 (no tags), the
//! masks are constants, and composed they fold into sums and differences of a few level-`L - 1`
//! points. With a regular vertex `v` and its ring `q0..q5` counter-clockwise, its child's limit
//! point and two tangents are
//!
//! ```text
//! P = (6v + Σq) / 12,   t1 = 2(q0 - q3) + (q1 - q4) - (q2 - q5),   t2 = (q1 - q4) + (q2 - q5),
//! ```
//!
//! and for the child of an edge `(a, b)` whose ends are both regular, with `c` opposite the
//! edge on the left and `d` on the right, `a`'s ring `b, c, a2, a3, a4, d` and `b`'s
//! `a, d, b2, b3, b4, c`,
//!
//! ```text
//! P  = (63(a + b) + 26(c + d) + 3(a2 + a4 + b2 + b4) + a3 + b3) / 192,
//! t1 = 13(a - b) + 2(a2 + a4 - b2 - b4) + a3 - b3,   t2 = 6(d - c) + a4 - a2 + b2 - b4.
//! ```
//!
//! The tangents are the limit tangents of `rules::limit` times positive constants, so their
//! cross product has the same direction. (Worked out and checked against the limit rows in the
//! sixteenth session, `tools/loop_regular_limit.py`; see DEVELOPERS.md.)
//!
//! Why: a limit row of the horse at level 2 reads about 11 control points with three weights
//! each, some 170 wasm operations a point with the normal; these read 7 or 10 points of the
//! level before and take about 45. Level `L - 1`'s points are made each frame: at level 1
//! they are the control points; on a closed cage, by Loop's smooth rules level by level
//! ([`Step`]); otherwise by a refined table of their own. The table's rows stay whole, for
//! `stencils()` and the GPU; the points these give are left out of the rows' frame, and where
//! they give every point (a closed cage) the evaluator makes the table only when asked for it.
//!
//! Refined points with the limit's normals (`normals` without `limit`) on a closed cage take
//! the same closed forms for the normals, and one step of Loop's smooth rules ([`Step`]) from
//! the same level before for the last level's own points: the table's tangent rows made those
//! evaluators' builds 2.6 to 3.4 times a `subdivide` on the horse, and their frames read them.

use crate::mesh::HalfEdgeMesh;
use crate::stencil::{ClosedForms, Lanes, Normals, PointSink, StencilTable, TableWriter, Written};

/// What a closed form reads: the child of a regular vertex (`[v, q0..q5, output]`) or of an
/// edge between two (`[a, b, c, d, a2, a3, a4, b2, b3, b4, output]`), the points read as byte
/// offsets (16 bytes a padded point) once `RegularRings::new` is done.
type VertexCase = [u32; 8];
type EdgeCase = [u32; 11];
/// The child of an edge `(a, b)` with a closed fan at each end, one of them not regular:
/// `[a, b, c, d, x_ca, x_ad, x_bc, x_db, child of a, child of b, output]`, where `x_pq` is the
/// vertex across edge `(p, q)` from the edge's other end and the children index
/// `RegularRings::children`.
type FanEdgeCase = [u32; 11];

/// Past this many faces a vertex keeps its rows (as `limit::MaskMerge` keeps its templates).
pub(crate) const MAX_VALENCE: usize = 64;

/// The last level's points that Loop's closed forms give from the level before, and how that
/// level's points are made.
#[derive(Clone, Debug)]
pub(crate) struct RegularRings {
    /// How level `L - 1`'s points come from the control points.
    previous: Previous,
    vertices: Vec<VertexCase>,
    edges: Vec<EdgeCase>,
    /// Children of edges next to a vertex that is not regular, from the level-`L` vertex
    /// children they read (`children`).
    fan_edges: Vec<FanEdgeCase>,
    /// Vertices of the level before whose level-`L` child a fan edge reads.
    children: Vec<u32>,
    /// Children of vertices with a closed fan of `n != 6` faces: `[v, output]`.
    fan_vertices: Vec<[u32; 2]>,
    /// The rings of the level before, which `children` and `fan_vertices` read.
    rings: Rings,
    /// Per valence `n` (up to [`MAX_VALENCE`]): Loop's `β` and limit weight `χ`, and the
    /// tangent masks `cos(2πk/n)`, `sin(2πk/n)`.
    masks: Vec<FanMasks>,
    /// The output vertices no closed form gives, ascending: their rows give them.
    rest: Vec<u32>,
    /// Points of the level before, and output vertices: every case's indices are below.
    parent_vertices: usize,
    outputs: usize,
    /// For refined points with the limit's normals (`normals` without `limit`): the step that
    /// makes the last level's own points from the level before (on `rings`), which the closed
    /// forms then give the normals of. `None` for the limit.
    refined: Option<Box<Children>>,
}

/// Where the points of the level before the last come from.
#[derive(Clone, Debug)]
pub(crate) enum Previous {
    /// They are the control points (level 1).
    Control,
    /// A refined table of that level.
    Table(StencilTable),
    /// Loop's smooth rules, level by level, on a closed mesh (every vertex has a closed fan):
    /// each level's points from the one before, a few each, instead of a row of about ten
    /// control points per point.
    Steps(Vec<Step>),
    /// One step of Loop's smooth rules from the level before the closed forms of the level
    /// before, which give this level's vertex children: the limit point of a vertex's child
    /// is the vertex's own, and there they read a level four times smaller, in its own
    /// order. The step's points are numbered as this level's cases first read them
    /// (`number_parents_as_read`), which their reads would not be in the vertex children's
    /// order.
    Nested(Box<RegularRings>, Step),
}

impl Previous {
    fn bytes(&self) -> u64 {
        match self {
            Previous::Control => 0,
            Previous::Table(table) => table.bytes(),
            Previous::Steps(steps) => steps.iter().map(Step::bytes).sum(),
            Previous::Nested(inner, step) => inner.bytes() + step.bytes(),
        }
    }
}

/// One level of Loop's smooth rules on a closed mesh with a closed fan at every vertex, in the
/// order `refine::ptq` numbers the child level: each vertex's child (`v + β Σ (q - v)`), then
/// each edge's (`3/8 (a + b) + 1/8 (c + d)`).
#[derive(Clone, Debug)]
pub(crate) struct Step {
    /// Every vertex's ring.
    rings: Rings,
    children: Children,
}

/// What a [`Step`] makes, apart from the rings its vertex children read: the closed forms of a
/// refined evaluator keep it on their own rings of the same level (`RegularRings::refined`).
#[derive(Clone, Debug)]
struct Children {
    /// The vertex whose child each of the first outputs is: every vertex once, in order,
    /// unless [`RegularRings`] reordered the last step's output.
    centres: Vec<u32>,
    /// Per edge child, its edge's ends and the corners opposite it: `[a, b, c, d]`.
    edges: Vec<[u32; 4]>,
}

impl Step {
    /// The step from `mesh`, when it is a closed triangle mesh whose every vertex has a closed
    /// fan of at most [`MAX_VALENCE`] triangles.
    pub(crate) fn new(mesh: &HalfEdgeMesh) -> Option<Self> {
        let cells = mesh.num_cells();
        if mesh.num_half_edges() != 3 * cells || !mesh.has_simple_edges() {
            return None;
        }
        let corners = &mesh.he_from;
        let rings = Rings::new(corners.as_chunks::<3>().0, mesh.num_vertices())?;
        if !(0..mesh.num_vertices() as u32).all(|v| rings.of(v).is_some()) {
            return None;
        }
        let third = |h: u32| corners[mesh.prev_in_cell(h) as usize];
        let edges = (0..mesh.num_edges())
            .map(|e| match mesh.edge_half_edges[mesh.edge_range(e)] {
                [h, twin] => {
                    let [a, b] = [corners[h as usize], corners[twin as usize]];
                    Some([a, b, third(h), third(twin)])
                }
                _ => None,
            })
            .collect::<Option<Vec<_>>>()?;
        let centres = (0..mesh.num_vertices() as u32).collect();
        Some(Step { rings, children: Children { centres, edges } })
    }

    pub(crate) fn bytes(&self) -> u64 {
        self.rings.bytes() + self.children.bytes()
    }

    /// The child level's points from `points` (this level's, padded), to `out` in order.
    pub(crate) fn apply(&self, points: &[[f32; 4]], masks: &[FanMasks], out: &mut impl PointSink) {
        self.children.apply(&self.rings, points, masks, out);
    }

    /// Number of points of the child level.
    pub(crate) fn outputs(&self) -> usize {
        self.children.outputs()
    }

    /// The step as a stencil table on this level's vertices: the rows of [`Step::apply`]'s
    /// sums.
    pub(crate) fn table(&self, masks: &[FanMasks]) -> StencilTable {
        let children = &self.children;
        let entries = self.rings.list.len() + children.centres.len() + 4 * children.edges.len();
        let mut out = TableWriter::new(self.rings.vertices(), self.outputs(), entries);
        for &v in &children.centres {
            let ring = self.rings.of(v).unwrap_or(&[]);
            let beta = masks.get(ring.len()).map_or(0.0, |m| m.beta);
            out.add(v, 1.0 - ring.len() as f32 * beta);
            ring.iter().for_each(|&q| out.add(q, beta));
            out.end_row();
        }
        for &[a, b, c, d] in &children.edges {
            for (x, w) in [(a, 0.375), (b, 0.375), (c, 0.125), (d, 0.125)] {
                out.add(x, w);
            }
            out.end_row();
        }
        out.finish()
    }

    /// The child level's points, padded.
    pub(crate) fn padded(&self, points: &[[f32; 4]], masks: &[FanMasks]) -> Vec<[f32; 4]> {
        let mut out = Vec::with_capacity(self.outputs());
        self.apply(points, masks, &mut out);
        out
    }
}

impl Children {
    fn bytes(&self) -> u64 {
        (std::mem::size_of_val(&self.centres[..]) + std::mem::size_of_val(&self.edges[..])) as u64
    }

    /// Makes output `k` what output `old[k]` was (`old` a permutation that keeps the vertex
    /// children before the edge children).
    fn reorder(&mut self, old: &[u32]) {
        let (vertex_children, edge_children) = old.split_at(self.centres.len());
        self.centres = vertex_children.iter().map(|&o| self.centres[o as usize]).collect();
        let first_edge = self.centres.len();
        self.edges = edge_children.iter().map(|&o| self.edges[o as usize - first_edge]).collect();
    }

    /// Reads input `new[v]` where it read input `v`, the outputs unchanged: the step from a
    /// level its closed forms renumbered (`number_parents_as_read`, which renumbers the rings).
    fn renumber_inputs(&mut self, new: &[u32]) {
        let renumber = |v: &mut u32| *v = new[*v as usize];
        self.centres.iter_mut().for_each(renumber);
        self.edges.iter_mut().flatten().for_each(renumber);
    }

    /// The child level's points from `points` (this level's, padded, whose vertices have
    /// `rings`), to `out` in order.
    fn apply(
        &self,
        rings: &Rings,
        points: &[[f32; 4]],
        masks: &[FanMasks],
        out: &mut impl PointSink,
    ) {
        if points.len() < rings.vertices() {
            return;
        }
        // SAFETY: the centres, the rings and the edges hold vertices of the mesh the step was
        // made from (`Step::new`; `reorder` permutes them), so below `points.len()`. As in
        // `RegularRings::each`, the checks are a good part of the loop in wasm.
        let at = |i: u32| {
            debug_assert!((i as usize) < points.len());
            Lanes::load(unsafe { points.get_unchecked(i as usize) })
        };
        let beta = |n: usize| masks.get(n).map_or(0.0, |m| m.beta);
        let regular = beta(6);
        out.put_all(self.centres.iter().map(|&v| {
            // (Every vertex has a ring here: `Step::new`.)
            let centre = at(v);
            let moved = match *rings.of(v).unwrap_or(&[]) {
                // The same sum as below, of a length the compiler sees.
                [q0, q1, q2, q3, q4, q5] => {
                    ring_sum(&at, centre, &[q0, q1, q2, q3, q4, q5]).scale(regular)
                }
                ref ring => ring_sum(&at, centre, ring).scale(beta(ring.len())),
            };
            centre.add(moved)
        }));
        out.put_all(
            self.edges.iter().map(|&[a, b, c, d]| {
                at(c).add(at(d)).scale(0.125).add_lanes(at(a).add(at(b)), 0.375)
            }),
        );
    }

    fn outputs(&self) -> usize {
        self.centres.len() + self.edges.len()
    }
}

/// The weights of a smooth Loop vertex of one valence.
#[derive(Clone, Debug, Default)]
pub(crate) struct FanMasks {
    beta: f32,
    chi: f32,
    cos: Vec<f32>,
    sin: Vec<f32>,
}

/// [`FanMasks`] of every valence up to [`MAX_VALENCE`] (none below 3).
pub(crate) fn fan_masks() -> Vec<FanMasks> {
    (0..=MAX_VALENCE).map(|n| if n >= 3 { FanMasks::new(n) } else { FanMasks::default() }).collect()
}

impl FanMasks {
    fn new(n: usize) -> Self {
        let beta = crate::rules::loop_beta(n as u32);
        let chi = (1.0 / (n as f64 + 3.0 / (8.0 * f64::from(beta)))) as f32;
        let angle = |k: usize| std::f64::consts::TAU * k as f64 / n as f64;
        let cos = (0..n).map(|k| angle(k).cos() as f32).collect();
        let sin = (0..n).map(|k| angle(k).sin() as f32).collect();
        FanMasks { beta, chi, cos, sin }
    }
}

impl RegularRings {
    /// The closed forms of a Loop level from the triangles `parents` of the level before (its
    /// cells in order, `parent_vertices` vertices) to the output triangles `children` (cell
    /// `t`'s children at `4t..4t + 4`, in the order of `refine::ptq`) on `outputs` vertices.
    /// `previous` gives the parents' points. `refined`, a [`Step`] from the parents, makes
    /// the evaluator's points the last level's own (its rings are the parents', and these
    /// keep them). `None` when no point qualifies, or when the children do not follow that
    /// order.
    pub(crate) fn new(
        parents: &[u32],
        parent_vertices: usize,
        children: &[u32],
        outputs: usize,
        previous: Previous,
        refined: Option<Step>,
    ) -> Option<Self> {
        let (parents, _) = parents.as_chunks::<3>();
        let (child_faces, _) = children.as_chunks::<3>();
        if child_faces.len() != 4 * parents.len() {
            return None;
        }
        let (rings, refined) = match refined {
            Some(Step { rings, children }) => (rings, Some(Box::new(children))),
            None => (Rings::new(parents, parent_vertices)?, None),
        };
        let mut given = vec![false; outputs];
        let mut vertex_child = vec![u32::MAX; parent_vertices];
        let (mut edges, mut fan_edges) = (Vec::new(), Vec::new());
        // Per vertex of the level before, its index in `children`, once a fan edge reads it.
        let mut child_of = vec![u32::MAX; parent_vertices];
        let mut children = Vec::new();
        let mut child = |v: u32| {
            let slot = &mut child_of[v as usize];
            if *slot == u32::MAX {
                *slot = children.len() as u32;
                children.push(v);
            }
            *slot
        };
        for (t, &[a, b, c]) in parents.iter().enumerate() {
            let [f0, f1, f2, f3] = [0, 1, 2, 3].map(|k| child_faces[4 * t + k]);
            let [e0, e1, e2] = [f0[1], f1[2], f2[0]];
            if f1[0] != e0 || f2[1] != e1 || f0[2] != e2 || f3 != [e1, e2, e0] {
                return None;
            }
            for (v, child) in [(a, f0[0]), (b, f1[1]), (c, f2[2])] {
                let slot = vertex_child.get_mut(v as usize)?;
                if *slot != u32::MAX && *slot != child {
                    return None;
                }
                *slot = child;
            }
            for (from, to, out) in [(a, b, e0), (b, c, e1), (c, a, e2)] {
                if given.get(out as usize).is_none_or(|&g| g) {
                    continue;
                }
                let (Some((na, ra)), Some((nb, rb))) = (rings.from(from, to), rings.from(to, from))
                else {
                    continue;
                };
                // a's ring from b is b, c, ..., d; b's from a must be a, d, ..., c.
                if rb(1) != ra(na - 1) || rb(nb - 1) != ra(1) {
                    continue;
                }
                given[out as usize] = true;
                if na == 6 && nb == 6 {
                    edges.push([
                        from,
                        to,
                        ra(1),
                        ra(5),
                        ra(2),
                        ra(3),
                        ra(4),
                        rb(2),
                        rb(3),
                        rb(4),
                        out,
                    ]);
                } else {
                    let (ca, cb) = (child(from), child(to));
                    let across = [ra(2), ra(na - 2), rb(nb - 2), rb(2)];
                    let [x_ca, x_ad, x_bc, x_db] = across;
                    fan_edges.push([from, to, ra(1), rb(1), x_ca, x_ad, x_bc, x_db, ca, cb, out]);
                }
            }
        }
        if let Previous::Nested(inner, _) = &previous {
            // The inner closed forms write their level's vertex `v`, which must be the child
            // of `v` here (as `refine::ptq` numbers them).
            let mut inner_given = vec![true; inner.outputs];
            inner.rest.iter().for_each(|&v| inner_given[v as usize] = false);
            for (v, _) in inner_given.iter().enumerate().filter(|(_, &g)| g) {
                if vertex_child.get(v) != Some(&(v as u32)) || given.get(v) != Some(&false) {
                    return None;
                }
                given[v] = true;
            }
        }
        let (mut vertices, mut fan_vertices) = (Vec::new(), Vec::new());
        for (v, &out) in vertex_child.iter().enumerate() {
            let Some(ring) = rings.of(v as u32) else { continue };
            if given.get(out as usize).is_none_or(|&g| g) {
                continue;
            }
            given[out as usize] = true;
            if let &[q0, q1, q2, q3, q4, q5] = ring {
                vertices.push([v as u32, q0, q1, q2, q3, q4, q5, out]);
            } else {
                fan_vertices.push([v as u32, out]);
            }
        }
        if vertices.is_empty()
            && edges.is_empty()
            && fan_edges.is_empty()
            && fan_vertices.is_empty()
            && !matches!(previous, Previous::Nested(..))
        {
            return None;
        }
        // In output order, so that the points and normals are written in runs (four normals
        // at a time, `Normals`), not scattered over the level's 24 bytes a point as the
        // triangles number their edges' children: 0.95 times the horse's level-3 frame, 0.97
        // times level 2's (`bench/stencil_ab.mjs`-style alternating frames). The level before
        // is then numbered in that order too (`number_parents_as_read`).
        vertices.sort_unstable_by_key(|case| case[7]);
        edges.sort_unstable_by_key(|case| case[10]);
        fan_edges.sort_unstable_by_key(|case| case[10]);
        let masks = fan_masks();
        let rest = (0..outputs as u32).filter(|&v| !given[v as usize]).collect();
        let mut forms = RegularRings {
            previous,
            vertices,
            edges,
            fan_edges,
            children,
            fan_vertices,
            rings,
            masks,
            rest,
            parent_vertices,
            outputs,
            refined,
        };
        forms.number_parents_as_read();
        // The regular cases' reads as byte offsets (see `each`).
        if parent_vertices >= 1 << 28 {
            return None;
        }
        let bytes = |v: &mut u32| *v <<= 4;
        forms.vertices.iter_mut().flat_map(|case| &mut case[..7]).for_each(bytes);
        forms.edges.iter_mut().flat_map(|case| &mut case[..10]).for_each(bytes);
        Some(forms)
    }

    /// When the level before is one [`Step`] after nested closed forms ([`Previous::Nested`]),
    /// numbers its points in the order the cases first read them, the vertex children and the
    /// edge children each in their own run (as a step makes them), and has the step make them
    /// in that order. Why: numbered as the refinement numbers them, a level's neighbours lie in
    /// four or five runs far apart; at level 3 the cases' reads of level 2's 12 MB made the
    /// horse's frame 21 ns per point, against about 18 read in this order.
    fn number_parents_as_read(&mut self) {
        let Previous::Nested(_, last) = &mut self.previous else { return };
        let count = self.parent_vertices;
        let vertex_children = last.children.centres.len();
        if last.children.edges.len() + vertex_children != count {
            return;
        }
        let mut first_read = Vec::with_capacity(count);
        let mut read = vec![false; count];
        let mut visit = |v: u32| {
            if let Some(seen) = read.get_mut(v as usize).filter(|seen| !**seen) {
                *seen = true;
                first_read.push(v);
            }
        };
        let rings = &self.rings;
        let ring = |v: u32| rings.of(v).unwrap_or(&[]);
        // The edges' children first: they are three in four of the points.
        self.edges.iter().flat_map(|case| &case[..10]).for_each(|&v| visit(v));
        self.vertices.iter().flat_map(|case| &case[..7]).for_each(|&v| visit(v));
        for &v in self.fan_vertices.iter().map(|[v, _]| v).chain(&self.children) {
            visit(v);
            ring(v).iter().for_each(|&q| visit(q));
        }
        self.fan_edges.iter().flat_map(|case| &case[..8]).for_each(|&v| visit(v));
        (0..count as u32).for_each(visit);
        let mut new = vec![0u32; count];
        let (mut next_vertex, mut next_edge) = (0, vertex_children as u32);
        for &v in &first_read {
            let next =
                if (v as usize) < vertex_children { &mut next_vertex } else { &mut next_edge };
            new[v as usize] = *next;
            *next += 1;
        }
        let mut old = vec![0u32; count];
        for (v, &n) in new.iter().enumerate() {
            old[n as usize] = v as u32;
        }
        last.children.reorder(&old);
        if let Some(refined) = &mut self.refined {
            refined.renumber_inputs(&new);
        }
        let renumber = |v: &mut u32| *v = new[*v as usize];
        self.vertices.iter_mut().flat_map(|case| &mut case[..7]).for_each(renumber);
        self.edges.iter_mut().flat_map(|case| &mut case[..10]).for_each(renumber);
        self.fan_vertices.iter_mut().map(|[v, _]| v).chain(&mut self.children).for_each(renumber);
        self.fan_edges.iter_mut().flat_map(|case| &mut case[..8]).for_each(renumber);
        self.rings = rings.renumbered(&old, &new);
    }

    /// Number of output vertices the closed forms give.
    pub(crate) fn num_points(&self) -> usize {
        let inner = match &self.previous {
            Previous::Nested(inner, _) => inner.num_points(),
            _ => 0,
        };
        inner
            + self.vertices.len()
            + self.edges.len()
            + self.fan_edges.len()
            + self.fan_vertices.len()
    }

    /// What this adds to the table's bytes: the previous level's table and the cases.
    pub(crate) fn bytes(&self) -> u64 {
        let cases = std::mem::size_of_val(&self.vertices[..])
            + std::mem::size_of_val(&self.edges[..])
            + std::mem::size_of_val(&self.fan_edges[..])
            + std::mem::size_of_val(&self.children[..])
            + std::mem::size_of_val(&self.fan_vertices[..])
            + std::mem::size_of_val(&self.rest[..]);
        let refined = self.refined.as_ref().map_or(0, |children| children.bytes());
        self.previous.bytes() + self.rings.bytes() + cases as u64 + refined
    }

    /// The points of the level before, from the padded control points.
    fn parents<'c>(&self, control: &'c [[f32; 4]]) -> std::borrow::Cow<'c, [[f32; 4]]> {
        match &self.previous {
            Previous::Control => control.into(),
            Previous::Table(table) => table.points_padded(control).into(),
            Previous::Steps(steps) => {
                let mut points = std::borrow::Cow::Borrowed(control);
                for step in steps {
                    points = step.padded(&points, &self.masks).into();
                }
                points
            }
            Previous::Nested(inner, step) => {
                step.padded(&inner.parents(control), &self.masks).into()
            }
        }
    }

    /// Each case's output vertex, limit point and tangents, from the padded control points:
    /// the nested closed forms' first, if any (see [`Previous::Nested`]); then the parents'
    /// points, which a refined evaluator's last step reads (`refined`).
    #[inline(always)]
    fn run<'c>(
        &self,
        control: &'c [[f32; 4]],
        mut emit: impl FnMut(usize, Lanes, [Lanes; 2]),
    ) -> std::borrow::Cow<'c, [[f32; 4]]> {
        let parents = if let Previous::Nested(inner, step) = &self.previous {
            let before = inner.parents(control);
            inner.each(&before, &mut emit);
            step.padded(&before, &self.masks).into()
        } else {
            self.parents(control)
        };
        self.each(&parents, &mut emit);
        parents
    }

    /// Each case's output vertex, limit point and tangents, from the parents' points. (Out of
    /// line: [`RegularRings::run`] calls it twice.)
    #[inline(never)]
    fn each(&self, parents: &[[f32; 4]], mut emit: impl FnMut(usize, Lanes, [Lanes; 2])) {
        if parents.len() < self.parent_vertices {
            return;
        }
        // SAFETY: every parent index of a case and of a fan is a vertex of the level before
        // (`Rings::new` checked each against the count), so below `parents.len()`. In wasm the
        // checks cost about 7 % of the frame.
        let at = |i: u32| Lanes::load(unsafe { parents.get_unchecked(i as usize) });
        // SAFETY: as `at`, with the index times 16 (the regular cases, `new`). In wasm that
        // spares a shift per read: x64 addressing scales by at most 8.
        let at_byte = |b: u32| {
            debug_assert!(b.is_multiple_of(16) && (b as usize) < 16 * parents.len());
            Lanes::load(unsafe { &*parents.as_ptr().byte_add(b as usize) })
        };
        let ring = |v: u32| self.rings.of(v).unwrap_or(&[]);
        // (Rings have 3 to `MAX_VALENCE` vertices: each has its masks.)
        let masks = |ring: &[u32]| &self.masks[ring.len()];
        for case in &self.vertices {
            let [v, q0, q1, q2, q3, q4, q5] = [0, 1, 2, 3, 4, 5, 6].map(|k| at_byte(case[k]));
            let ring = q0.add(q1).add(q2.add(q3)).add(q4.add(q5));
            let point = ring.add_lanes(v, 6.0).scale(1.0 / 12.0);
            let (d03, d14, d25) = (q0.sub(q3), q1.sub(q4), q2.sub(q5));
            let t1 = d14.sub(d25).add_lanes(d03, 2.0);
            let t2 = d14.add(d25);
            emit(case[7] as usize, point, [t1, t2]);
        }
        for case in &self.edges {
            let [a, b, c, d, a2, a3, a4, b2, b3, b4] =
                [0, 1, 2, 3, 4, 5, 6, 7, 8, 9].map(|k| at_byte(case[k]));
            let (near_a, near_b) = (a2.add(a4), b2.add(b4));
            let point = a3
                .add(b3)
                .add_lanes(a.add(b), 63.0)
                .add_lanes(c.add(d), 26.0)
                .add_lanes(near_a.add(near_b), 3.0)
                .scale(1.0 / 192.0);
            let t1 = a3.sub(b3).add_lanes(a.sub(b), 13.0).add_lanes(near_a.sub(near_b), 2.0);
            let t2 = a4.sub(a2).add(b2.sub(b4)).add_lanes(d.sub(c), 6.0);
            emit(case[10] as usize, point, [t1, t2]);
        }
        for &[v, out] in &self.fan_vertices {
            // Loop's smooth limit masks of its valence (`rules::limit`), on differences from v.
            let (centre, fan) = (at(v), ring(v));
            let m = masks(fan);
            let (mut sum, mut t1, mut t2) = (Lanes::ZERO, Lanes::ZERO, Lanes::ZERO);
            for (k, &q) in fan.iter().enumerate() {
                let d = at(q).sub(centre);
                sum = sum.add(d);
                t1 = t1.add_lanes(d, m.cos[k]);
                t2 = t2.add_lanes(d, m.sin[k]);
            }
            emit(out as usize, centre.add_lanes(sum, m.chi), [t1, t2]);
        }
        if self.fan_edges.is_empty() {
            return;
        }
        // Each level-L vertex child a fan edge reads, as its move from its parent:
        // `β Σ (q - v)`, Loop's smooth vertex rule.
        let moves: Vec<Lanes> = (self.children.iter())
            .map(|&v| {
                let fan = ring(v);
                ring_sum(&at, at(v), fan).scale(masks(fan).beta)
            })
            .collect();
        for case in &self.fan_edges {
            // The edge child's level-L ring from b', by Loop's rules, relative to a (so that
            // the tangents, differences of near points, keep their digits), then the regular
            // limit masks on it.
            let a = at(case[0]);
            let [b, c, d, x_ca, x_ad, x_bc, x_db] =
                [1, 2, 3, 4, 5, 6, 7].map(|k| at(case[k]).sub(a));
            // (`new` gave every fan edge its two children.)
            let moved = |k: usize| moves.get(case[k] as usize).copied().unwrap_or(Lanes::ZERO);
            let (move_a, move_b) = (moved(8), moved(9));
            let (three, one) = (0.375, 0.125);
            let edge = c.add(d).scale(one).add_lanes(b, three);
            let ring = [
                b.add(move_b),
                x_bc.scale(one).add_lanes(b.add(c), three),
                b.add(x_ca).scale(one).add_lanes(c, three),
                move_a,
                b.add(x_ad).scale(one).add_lanes(d, three),
                x_db.scale(one).add_lanes(d.add(b), three),
            ];
            let sum = ring[0].add(ring[1]).add(ring[2].add(ring[3])).add(ring[4].add(ring[5]));
            let point = a.add(sum.add_lanes(edge, 6.0).scale(1.0 / 12.0));
            let (d03, d14, d25) =
                (ring[0].sub(ring[3]), ring[1].sub(ring[4]), ring[2].sub(ring[5]));
            let t1 = d14.sub(d25).add_lanes(d03, 2.0);
            let t2 = d14.add(d25);
            emit(case[10] as usize, point, [t1, t2]);
        }
    }
}

impl ClosedForms for RegularRings {
    fn rest(&self) -> &[u32] {
        &self.rest
    }

    /// Writes the closed forms' points from the padded control points.
    fn points(&self, control: &[[f32; 4]], positions: &mut [[f32; 3]]) {
        if positions.len() < self.outputs {
            return;
        }
        if let Some(refined) = &self.refined {
            let parents = self.parents(control);
            refined.apply(&self.rings, &parents, &self.masks, &mut Written::new(positions));
            return;
        }
        self.run(control, |out, point, _| {
            // SAFETY: `out` is a case's output vertex, below `self.outputs` (`new`).
            point.store_xyz(unsafe { positions.get_unchecked_mut(out) });
        });
    }

    /// Writes the closed forms' points and unit normals (`t1 × t2`, as
    /// [`crate::limit::normal`]) from the padded control points.
    fn points_and_normals(
        &self,
        control: &[[f32; 4]],
        positions: &mut [[f32; 3]],
        normals: &mut [[f32; 3]],
    ) {
        if positions.len() < self.outputs {
            return;
        }
        // The cases come in output order (`new`), so their normals mostly in runs of four.
        let mut normals = Normals::<true>::new(normals);
        if let Some(refined) = &self.refined {
            let parents = self.run(control, |out, _, [t1, t2]| normals.push(out, t1, t2));
            refined.apply(&self.rings, &parents, &self.masks, &mut Written::new(positions));
            return;
        }
        self.run(control, |out, point, [t1, t2]| {
            // SAFETY: as in `points`.
            point.store_xyz(unsafe { positions.get_unchecked_mut(out) });
            normals.push(out, t1, t2);
        });
    }
}

/// `Σ (q - centre)` over a ring: what Loop's smooth vertex rule and its limit weight.
#[inline(always)]
fn ring_sum(at: &impl Fn(u32) -> Lanes, centre: Lanes, ring: &[u32]) -> Lanes {
    ring.iter().fold(Lanes::ZERO, |sum, &q| sum.add(at(q).sub(centre)))
}

/// The rings of a triangle mesh's vertices with a closed fan (3 to [`MAX_VALENCE`] triangles
/// around, each neighbour once), counter-clockwise as the triangles are wound; or, made by
/// [`Rings::of_fans`], of another kind of cell (`crate::quad_rings`'s quads).
#[derive(Clone, Debug)]
pub(crate) struct Rings {
    /// `list[offsets[v]..offsets[v + 1]]` is `v`'s ring, empty when it has none.
    offsets: Vec<u32>,
    list: Vec<u32>,
}

impl Rings {
    fn new(triangles: &[[u32; 3]], vertices: usize) -> Option<Self> {
        // Each corner's (next, previous) vertex.
        let steps = |[a, b, c]: [u32; 3]| [(a, [b, c]), (b, [c, a]), (c, [a, b])];
        Rings::of_fans(triangles, vertices, steps, closed_ring)
    }

    /// The rings of the vertices of `cells` (`vertices` of them) whose fan of 3 to
    /// [`MAX_VALENCE`] cells `close` closes into a ring: `steps` gives each corner of a cell as
    /// `(vertex, step)`, the steps are grouped by vertex, and `close(fan, v, ring)` says whether
    /// vertex `v`'s steps close, leaving its ring in `ring`. `None` when a cell names a vertex
    /// past `vertices`.
    pub(crate) fn of_fans<const N: usize, const S: usize>(
        cells: &[[u32; N]],
        vertices: usize,
        steps: impl Fn([u32; N]) -> [(u32, [u32; S]); N],
        close: impl Fn(&[[u32; S]], u32, &mut Vec<u32>) -> bool,
    ) -> Option<Self> {
        let mut offsets = vec![0u32; vertices + 1];
        for &v in cells.as_flattened() {
            *offsets.get_mut(v as usize + 1)? += 1;
        }
        for v in 1..offsets.len() {
            offsets[v] += offsets[v - 1];
        }
        let mut fill = offsets.clone();
        let mut grouped = vec![[0u32; S]; N * cells.len()];
        for &cell in cells {
            for (v, step) in steps(cell) {
                let slot = &mut fill[v as usize];
                grouped[*slot as usize] = step;
                *slot += 1;
            }
        }
        let mut ring = Vec::new();
        let (mut ring_offsets, mut list) = (Vec::with_capacity(vertices + 1), Vec::new());
        ring_offsets.push(0);
        for v in 0..vertices {
            let fan = &grouped[offsets[v] as usize..offsets[v + 1] as usize];
            if (3..=MAX_VALENCE).contains(&fan.len()) && close(fan, v as u32, &mut ring) {
                list.extend_from_slice(&ring);
            }
            ring_offsets.push(list.len() as u32);
        }
        Some(Rings { offsets: ring_offsets, list })
    }

    /// Number of vertices (with a ring or not).
    fn vertices(&self) -> usize {
        self.offsets.len() - 1
    }

    /// The rings with vertex `v` numbered `new[v]` (`old` the inverse permutation).
    fn renumbered(&self, old: &[u32], new: &[u32]) -> Rings {
        let mut offsets = Vec::with_capacity(old.len() + 1);
        let mut list = Vec::with_capacity(self.list.len());
        offsets.push(0);
        for &v in old {
            list.extend(self.of(v).unwrap_or(&[]).iter().map(|&q| new[q as usize]));
            offsets.push(list.len() as u32);
        }
        Rings { offsets, list }
    }

    pub(crate) fn bytes(&self) -> u64 {
        (std::mem::size_of_val(&self.offsets[..]) + std::mem::size_of_val(&self.list[..])) as u64
    }

    /// The ring of `v`, when it has one.
    pub(crate) fn of(&self, v: u32) -> Option<&[u32]> {
        let (start, end) = (*self.offsets.get(v as usize)?, *self.offsets.get(v as usize + 1)?);
        (end > start).then(|| &self.list[start as usize..end as usize])
    }

    /// The ring of `v` starting at its neighbour `first`, when it has one: its length, and its
    /// `i`-th vertex from `first` for any `i` (read in place, not copied: a build asks this
    /// twice per edge).
    fn from(&self, v: u32, first: u32) -> Option<(usize, impl Fn(usize) -> u32 + '_)> {
        let ring = self.of(v)?;
        let k = ring.iter().position(|&q| q == first)?;
        Some((ring.len(), move |i: usize| ring[(k + i) % ring.len()]))
    }
}

/// Whether the fan steps `fan` of vertex `v` close into one ring of distinct neighbours (other
/// than `v`), left in `ring` from the first step.
fn closed_ring(fan: &[[u32; 2]], v: u32, ring: &mut Vec<u32>) -> bool {
    ring.clear();
    ring.push(fan[0][0]);
    while ring.len() < fan.len() {
        let Some(step) = fan.iter().find(|s| s[0] == ring[ring.len() - 1]) else {
            return false;
        };
        ring.push(step[1]);
    }
    let closes = fan.iter().find(|s| s[0] == ring[ring.len() - 1]).is_some_and(|s| s[1] == ring[0]);
    let distinct = (0..ring.len()).all(|i| !ring[i + 1..].contains(&ring[i]));
    closes && !ring.contains(&v) && distinct
}
