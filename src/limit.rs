//! Evaluation at the limit (OpenSubdiv's `Far::PrimvarRefiner::Limit` and `LimitFaceVarying`):
//! the limit masks of [`crate::rules::limit`] applied to one level's positions, to its
//! vertex-varying rows and to its face-varying values, through the same sinks that refine them;
//! and vertex normals from faces, for the schemes without limit masks.

use crate::fvar::{tag, FVarLevel};
use crate::mesh::{HalfEdgeMesh, PolyMesh};
use crate::primvar::{FVarSum, LimitSources, PointSum, Primvar, RowSum};
use crate::rules::limit::{LimitRule, LimitRules, Neighbourhood};
use crate::rules::{Source, Stencil};
use glam::DVec3;

/// The limit positions, tangents and normals of one level's vertices, three floats each.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LimitFrame {
    pub positions: Vec<f32>,
    /// OpenSubdiv's `tan1` and `tan2` (see [`crate::rules::limit`]).
    pub tangents: [Vec<f32>; 2],
    /// `tangents[0] × tangents[1]`, normalised; zero where that cross product is zero or not
    /// finite (an isolated vertex, or tangents along one line).
    pub normals: Vec<f32>,
}

/// The unit vector along `first × second`, or zero when there is none.
///
/// In f32 when that is as good: the products of the cross product are rounded to f32, an
/// error of about `|first| |second| 2^-24` against a length of `|first| |second| sin θ`, so
/// tangents at least 0.1 rad apart and lengths well inside f32's range lose nothing that
/// shows in an f32 result. Otherwise in f64, where the products of f32 values are exact:
/// tangents that nearly cancel or nearly align, whose f32 cross product would lose digits (or
/// be subnormal) and not come out unit length. (A frame of a million normals spent a quarter
/// of its time in the f64 square root and divisions.)
pub fn normal(first: [f32; 3], second: [f32; 3]) -> [f32; 3] {
    let ([a0, a1, a2], [b0, b1, b2]) = (first, second);
    let n = [a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0];
    let length2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    let scale2 = (a0 * a0 + a1 * a1 + a2 * a2) * (b0 * b0 + b1 * b1 + b2 * b2);
    // sin²θ ≥ 0.01, and both well away from f32's subnormals and overflow.
    if length2 >= 0.01 * scale2 && length2 > 1e-30 && scale2 < 1e30 {
        let inverse = 1.0 / length2.sqrt();
        return n.map(|x| x * inverse);
    }
    let wide = |v: [f32; 3]| DVec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]));
    let n = wide(first).cross(wide(second));
    let length = n.length();
    if length > 0.0 && length.is_finite() {
        let unit = n / length;
        [unit.x as f32, unit.y as f32, unit.z as f32]
    } else {
        [0.0; 3]
    }
}

/// The limit frame of every vertex of `mesh` (whose positions are the level's) when `with_frame`
/// (else it is left empty: a stencil table gives the frame of any positions later), and the
/// limit of `rows` (the level's vertex-varying rows, or any [`Primvar`], possibly empty) under
/// the position masks; with `tangent_rows`, `rows` under the two tangent masks too (for stencil
/// tables of normals), all three from [`Primvar::limit_rows`]. The rows of a vertex that
/// `elsewhere` marks (empty: none) are left empty: a stencil build makes the limit rows of
/// regular Catmull-Clark faces from their patches instead (see `crate::patches`).
pub fn evaluate<V: Primvar>(
    mesh: &HalfEdgeMesh,
    rules: &LimitRules,
    rows: &V,
    tangent_rows: bool,
    with_frame: bool,
    elsewhere: &[bool],
) -> (LimitFrame, V, Option<[V; 2]>) {
    let elsewhere = |v: u32| elsewhere.get(v as usize).copied().unwrap_or(false);
    let n = mesh.num_vertices();
    let points = &mesh.positions;
    let reserved = if with_frame { 3 * n } else { 0 };
    let mut frame = LimitFrame {
        positions: Vec::with_capacity(reserved),
        tangents: [Vec::with_capacity(reserved), Vec::with_capacity(reserved)],
        normals: Vec::with_capacity(reserved),
    };
    let with_rows = !rows.is_empty();
    // With tangent rows, all three rows of a vertex come from `Primvar::limit_rows` below.
    let position_rows = with_rows && !tangent_rows;
    let mut out_rows = rows.with_capacity(if position_rows { n } else { 0 });
    let mut row_sum = rows.sum(&mesh.he_from, None);
    let mut hood = Neighbourhood::default();
    // Nothing to walk for without the frame or rows of positions (tangent rows come below).
    let walked = if with_frame || position_rows { n as u32 } else { 0 };
    for v in 0..walked {
        let skip = elsewhere(v);
        if !skip || with_frame {
            rules.gather(mesh, v, &mut hood);
        }
        if position_rows && skip {
            out_rows.push(&mut row_sum, |_| {});
        } else if position_rows {
            out_rows.push(&mut row_sum, |w| rules.position(&hood, w));
        }
        if !with_frame {
            continue;
        }
        let mut sum = PointSum::new(points, &mesh.he_from, &[]);
        frame.positions.extend(sum.eval(|w| rules.position(&hood, w)));
        let mut second = PointSum::new(points, &mesh.he_from, &[]);
        let first = sum.eval(|w| {
            rules.tangents(&hood, w, &mut second);
        });
        let second = second.sum;
        frame.tangents[0].extend(first);
        frame.tangents[1].extend(second);
        frame.normals.extend(normal(first, second));
    }
    let mut tangents = None;
    if with_rows && tangent_rows {
        let mut masks = MaskMerge::new(mesh.num_vertices());
        let (positions, both) = rows.limit_rows(mesh, &mut |v, sources| {
            if elsewhere(v) {
                return;
            }
            rules.gather(mesh, v, &mut hood);
            masks.merge(rules, &hood, &mesh.he_from, sources);
        });
        out_rows = positions;
        tangents = Some(both);
    }
    (frame, out_rows, tangents)
}

/// Merged masks by slot of a neighbourhood: 0 the vertex, `1..=E` its edges' ends, then its
/// faces' opposite corners.
type SlotMasks = Vec<(usize, [f32; 3])>;

/// One vertex's three limit masks (position, two tangents) merged per vertex of the level, for
/// the rows of a stencil table: each weighted vertex once, in the order the masks first name it
/// (the position's mask first), with its three weights.
///
/// A smooth vertex's masks depend on its valence and scheme only, so its merged masks are kept
/// per valence as weights on the slots of its neighbourhood (the vertex, its edges' ends, its
/// faces' opposite corners) and reused: the masks and their merge were a fifth of a limit
/// table's build, for a million vertices of a few valences. A vertex whose slots name some
/// vertex twice (a degenerate face or edge) is merged from its masks, as every other rule is.
struct MaskMerge {
    recorded: [Stencil; 3],
    /// Per level vertex, the stamp of the vertex that last listed it, and where.
    listed: Vec<(u32, u32)>,
    stamp: u32,
    /// Per scheme (Loop, Catmull-Clark) and valence, a smooth vertex's merged masks by slot.
    smooth: [Vec<Option<SlotMasks>>; 2],
    /// The vertices of the slots the masks of one valence weight.
    slots: Vec<u32>,
}

impl MaskMerge {
    /// The largest valence whose merged masks are kept.
    const KEPT_VALENCES: usize = 64;

    fn new(vertices: usize) -> Self {
        MaskMerge {
            recorded: Default::default(),
            listed: vec![(0, 0); vertices],
            stamp: 0,
            smooth: Default::default(),
            slots: Vec::new(),
        }
    }

    /// The merged masks of the vertex `hood` was gathered for, into `sources` (empty).
    fn merge(
        &mut self,
        rules: &LimitRules,
        hood: &Neighbourhood,
        he_from: &[u32],
        sources: &mut LimitSources,
    ) {
        let slot_vertex = |slot: usize| match slot {
            0 => Some(hood.vertex),
            i if i <= hood.edges.len() => Some(he_from[hood.edges[i - 1] as usize]),
            i => hood.faces.get(i - 1 - hood.edges.len()).map(|&h| he_from[h as usize]),
        };
        let n = hood.faces.len();
        // Only valences up to `KEPT_VALENCES` are kept: a template is found and checked slot by
        // slot, which for the hub of a fan (valence 100k) cost `n²` steps, while such a vertex is
        // merged from its masks in `n`.
        let smooth =
            hood.rule == LimitRule::Smooth && hood.edges.len() == n && n <= Self::KEPT_VALENCES;
        let kept = smooth.then(|| &self.smooth[usize::from(hood.catmull_clark)]);
        if let Some(Some(Some(template))) = kept.map(|t| t.get(n)) {
            self.slots.clear();
            self.slots.extend(template.iter().filter_map(|&(slot, _)| slot_vertex(slot)));
            let distinct = self.slots.len() == template.len()
                && self.slots.iter().enumerate().all(|(i, v)| !self.slots[..i].contains(v));
            if distinct {
                sources.extend(self.slots.iter().zip(template).map(|(&v, &(_, w))| (v, w)));
                return;
            }
        }
        for mask in &mut self.recorded {
            mask.sources.clear();
        }
        let [position, first, second] = &mut self.recorded;
        rules.position(hood, position);
        rules.tangents(hood, first, second);
        self.merge_recorded(he_from, sources);
        if smooth {
            self.keep(hood, n);
        }
    }

    /// Merges the recorded masks per vertex, through the stamps.
    fn merge_recorded(&mut self, he_from: &[u32], sources: &mut LimitSources) {
        if self.stamp == u32::MAX {
            self.listed.iter_mut().for_each(|l| l.0 = 0);
            self.stamp = 0;
        }
        self.stamp += 1;
        let stamp = self.stamp;
        for (k, mask) in self.recorded.iter().enumerate() {
            for &(source, weight) in &mask.sources {
                let vertex = match source {
                    Source::Vertex(v) => v,
                    Source::Corner(h) => he_from[h as usize],
                    // Limit masks weight no face point.
                    Source::FacePoint(_) => continue,
                };
                let entry = &mut self.listed[vertex as usize];
                let at = (entry.0 == stamp).then_some(entry.1 as usize);
                *entry = (stamp, at.unwrap_or(sources.len()) as u32);
                add_weight(sources, at, vertex, k, weight);
            }
        }
    }

    /// Keeps the recorded masks of a smooth vertex of valence `n` as weights by slot, merged per
    /// slot in the order first named (as [`MaskMerge::merge_recorded`] merges them per vertex).
    fn keep(&mut self, hood: &Neighbourhood, n: usize) {
        let kept = &mut self.smooth[usize::from(hood.catmull_clark)];
        if kept.len() <= n {
            kept.resize(n + 1, None);
        }
        if kept[n].is_some() {
            return;
        }
        let slot_of = |source: Source| match source {
            Source::Vertex(v) => (v == hood.vertex).then_some(0),
            Source::Corner(h) => match hood.edges.iter().position(|&e| e == h) {
                Some(i) => Some(1 + i),
                None => hood.faces.iter().position(|&f| f == h).map(|i| 1 + hood.edges.len() + i),
            },
            Source::FacePoint(_) => None,
        };
        let mut template = SlotMasks::new();
        for (k, mask) in self.recorded.iter().enumerate() {
            for &(source, weight) in &mask.sources {
                let Some(slot) = slot_of(source) else { return };
                let at = template.iter().position(|t| t.0 == slot);
                add_weight(&mut template, at, slot, k, weight);
            }
        }
        kept[n] = Some(template);
    }
}

/// Adds mask `k`'s `weight` on `key` to `list`: to its entry at `at`, or as a new entry (the
/// other masks' weights 0), so that entries stay in the order first named.
fn add_weight<K>(list: &mut Vec<(K, [f32; 3])>, at: Option<usize>, key: K, k: usize, weight: f32) {
    match at.and_then(|at| list.get_mut(at)) {
        Some(entry) => entry.1[k] += weight,
        None => {
            let mut w = [0.0; 3];
            w[k] = weight;
            list.push((key, w));
        }
    }
}

/// The limit of a face-varying channel on `mesh`, its last level (OpenSubdiv's
/// `PrimvarRefiner::LimitFaceVarying`): a value whose neighbourhood matches the surface's takes
/// the vertex's position mask, each neighbour read through the corner it is seen from; a
/// crease value the B-spline crease limit `2/3 v + 1/6 (a + b)` along its span's bounding
/// edges; a corner value stays; with `linear` (mode `all`, or a linear scheme) every value
/// stays, as does every value of a vertex without faces.
pub fn limit_face_varying(
    mesh: &HalfEdgeMesh,
    rules: &LimitRules,
    level: &mut FVarLevel,
    linear: bool,
) {
    if linear {
        return;
    }
    let width = level.width;
    let mut out = level.values.clone();
    let slot = |i: u32| i as usize * width..(i as usize + 1) * width;
    let mut sum = FVarSum::new(&level.values, width, &level.corner_values, &[]);
    let mut hood = Neighbourhood::default();
    for v in mesh.vertex_indices() {
        if mesh.out_half_edges(v).is_empty() {
            continue;
        }
        if level.tags[v as usize] & tag::MISMATCH == 0 {
            rules.gather(mesh, v, &mut hood);
            sum.eval_into(&mut out[slot(v)], [(v, v); 2], |w| rules.position(&hood, w));
            continue;
        }
        for s in 0..level.count(v) {
            let value = level.value(v, s);
            if level.tags[value as usize] & tag::CREASE == 0 {
                continue;
            }
            let [a, b] = level.crease_end_values(mesh, value);
            let target = &mut out[slot(value)];
            target.fill(0.0);
            RowSum::add(target, &level.values[slot(a)], 1.0 / 6.0);
            RowSum::add(target, &level.values[slot(b)], 1.0 / 6.0);
            RowSum::add(target, &level.values[slot(value)], 2.0 / 3.0);
        }
    }
    level.values = out;
}

/// Vertex normals from the faces of `poly`: at each vertex, the sum of the area vectors
/// (Newell's normal, twice the area along the normal) of the faces around it, normalised;
/// zero for a vertex without faces or where they cancel. What the schemes without limit
/// masks (bilinear, midpoint, Doo-Sabin, √3, Quad/Triangle where quads meet triangles) give.
pub fn face_normals(poly: &PolyMesh) -> Vec<f32> {
    let mut out = vec![0.0; poly.positions.len()];
    face_normals_into(&poly.positions, &poly.indices, &poly.face_sizes, &mut out);
    out
}

/// [`face_normals`] of the faces `indices`, `face_sizes` over `positions`, into `out` (as long
/// as `positions`; the faces' indices must be in range).
pub fn face_normals_into(positions: &[f32], indices: &[u32], face_sizes: &[u32], out: &mut [f32]) {
    let mut sums = vec![DVec3::ZERO; positions.len() / 3];
    let mut start = 0;
    for &n in face_sizes {
        let face = &indices[start..start + n as usize];
        start += n as usize;
        let area = crate::mesh::area_vector(positions, face);
        for &v in face {
            sums[v as usize] += area;
        }
    }
    for (sum, out) in sums.into_iter().zip(out.chunks_exact_mut(3)) {
        let length = sum.length();
        let unit = if length > 0.0 && length.is_finite() { sum / length } else { DVec3::ZERO };
        out.copy_from_slice(&[unit.x as f32, unit.y as f32, unit.z as f32]);
    }
}

/// The weights of vertex `vertex`'s limit position and tangents, recorded (for tests and for
/// stencil tables).
pub fn stencils(mesh: &HalfEdgeMesh, rules: &LimitRules, vertex: u32) -> [Stencil; 3] {
    let mut hood = Neighbourhood::default();
    let mut out: [Stencil; 3] = Default::default();
    if vertex as usize >= mesh.num_vertices() {
        return out;
    }
    rules.gather(mesh, vertex, &mut hood);
    let [position, first, second] = &mut out;
    rules.position(&hood, position);
    rules.tangents(&hood, first, second);
    out
}

/// OpenSubdiv's first face at every vertex and edge of a level (`Vtr`'s vertex-face and
/// edge-face order), tracked through triangle splits so that an interior crease or corner of a
/// Loop level starts its neighbourhood where OpenSubdiv does. As half-edges: per vertex an
/// outgoing half-edge in its first face, per edge a half-edge of it in its first face (`u32::MAX`
/// for none).
///
/// The base level lists a vertex's and an edge's faces in face order, so the first is the lowest
/// (our first outgoing half-edge of an interior vertex, our first half-edge of an edge). The
/// triangle split (`Vtr::TriRefinement`) keeps a parent vertex's order (the child at the same
/// corner of the parent's first face first), starts an edge point at the leading child face of
/// the edge's first face (the child at the edge's far corner), gives each half of a parent edge
/// the child of the edge's first face, and each inner edge the corner child before the middle
/// one.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FirstFaces {
    pub vertices: Vec<u32>,
    pub edges: Vec<u32>,
}

impl FirstFaces {
    /// The base level's.
    pub fn base(mesh: &HalfEdgeMesh) -> Self {
        let vertices = mesh
            .vertex_indices()
            .map(|v| mesh.out_half_edges(v).first().copied().unwrap_or(u32::MAX))
            .collect();
        let edges = (0..mesh.num_edges())
            .map(|e| mesh.edge_half_edges[mesh.edge_range(e)].first().copied().unwrap_or(u32::MAX))
            .collect();
        FirstFaces { vertices, edges }
    }

    /// The child half-edges that are first at their vertex and at their edge after a triangle
    /// split of a level of `faces` triangles, in child half-edge numbers (child face `4t + j`
    /// has half-edges `3(4t + j) + i`); [`FirstFaces::scatter`] files them by the child mesh.
    pub fn triangle_split(&self, faces: usize) -> (Vec<u32>, Vec<u32>) {
        // Parent half-edge `h` = `3t + k`: triangle `t`, corner `k`.
        let at_corner = |h: u32| {
            let (t, k) = (h / 3, h % 3);
            3 * (4 * t + k) + k
        };
        let leading = |h: u32| {
            let (t, k) = (h / 3, h % 3);
            3 * (4 * t + (k + 1) % 3) + k
        };
        let valid = |&h: &u32| h != u32::MAX && (h as usize) < 3 * faces;
        let mut vertices: Vec<u32> =
            self.vertices.iter().filter(|h| valid(h)).map(|&h| at_corner(h)).collect();
        vertices.extend(self.edges.iter().filter(|h| valid(h)).map(|&h| leading(h)));
        let mut edges = Vec::with_capacity(2 * self.edges.len() + 3 * faces);
        for &h in self.edges.iter().filter(|h| valid(h)) {
            edges.push(at_corner(h));
            edges.push(leading(h));
        }
        for t in 0..faces as u32 {
            for j in 0..3 {
                edges.push(3 * (4 * t + j) + (j + 1) % 3);
            }
        }
        (vertices, edges)
    }

    /// Files the child half-edges of [`FirstFaces::triangle_split`] by their vertex and edge in
    /// `child`.
    pub fn scatter(child: &HalfEdgeMesh, (vertices, edges): (Vec<u32>, Vec<u32>)) -> Self {
        let mut out = FirstFaces {
            vertices: vec![u32::MAX; child.num_vertices()],
            edges: vec![u32::MAX; child.num_edges()],
        };
        for h in vertices {
            if let Some(&v) = child.he_from.get(h as usize) {
                out.vertices[v as usize] = h;
            }
        }
        for h in edges {
            if let Some(&e) = child.he_edge.get(h as usize) {
                out.edges[e as usize] = h;
            }
        }
        out
    }
}
