//! Limit masks: where a vertex of a refined level lies on the limit surface, and the two limit
//! tangents there, as weights over the vertex and its one-ring. The masks are OpenSubdiv's
//! (`Sdc::Scheme<SCHEME_CATMARK/LOOP>::ComputeVertexLimitMask`, as `Far::PrimvarRefiner::Limit`
//! applies them to the last level), read from its headers and written anew.
//!
//! # The neighbourhood
//!
//! A vertex's incident edges and faces are listed as OpenSubdiv lists them: counter-clockwise
//! (seen from the side the faces are wound counter-clockwise from), face `i` between edge `i`
//! and edge `i + 1`. An interior vertex starts with the face of its first outgoing half-edge, a
//! boundary vertex with its leading boundary edge (the outgoing one, which the mesh lists
//! first). A mask weights the vertex itself ([`Weights::vertex`]), the other end of each edge
//! and, for Catmull-Clark, the vertex of each face opposite this one (both
//! [`Weights::corner`]). No face point is weighted.
//!
//! # The rule
//!
//! As for refinement ([`super::crease`]), read on the level whose limit is taken: a vertex
//! without faces stays and has no tangents; a sharp vertex, three or more sharp edges, a vertex
//! whose faces form several fans, a non-manifold vertex, a one-face vertex under
//! [`Boundary::EdgeAndCorner`] and any boundary vertex under [`Boundary::Fixed`] is a
//! **corner**; two sharp edges (a boundary vertex's two boundary edges among them) a
//! **crease**; otherwise **smooth** (a dart too). Boundary and non-manifold edges are sharp;
//! semi-sharp edges count as sharp (the limit of the level, not of the infinitely refined
//! surface, as OpenSubdiv does).
//!
//! # Position
//!
//! - corner: the vertex;
//! - crease: `2/3 v + 1/6 (a + b)`, `a`, `b` across the two sharp edges (the uniform cubic
//!   B-spline along the crease; both schemes);
//! - smooth Catmull-Clark of `n` faces: `1 - n(e + f)` on the vertex, `e = 4f` on each edge
//!   neighbour, `f = 1/(n(n + 5))` on each face-opposite vertex (4/9, 1/9, 1/36 at `n` = 4);
//!   a vertex of two faces is a corner;
//! - smooth Loop of `n` faces: `e = 1/(n + 3/(8γ))` on each neighbour, `1 - ne` on the vertex,
//!   `γ = (5/8 - β²)/n`, `β = 3/8 + cos(2π/n)/4` (1/12 and 1/2 at `n` = 6).
//!
//! # Tangents
//!
//! Weights summing to 0 (differences of points). `first` and `second` are OpenSubdiv's
//! `tan1` and `tan2`; their cross product `first × second` points to the side from which the
//! faces are wound counter-clockwise (outward on a closed mesh whose faces are wound so).
//!
//! - corner: `e0 - v` and `e1 - v` (Loop: three times these), the first two edges;
//! - crease, with sharp edges `c0 < c1` in the order above: `first` along the crease,
//!   `(e_c0 - e_c1)/2` (Loop: 3/2 of it), `second` across the faces between `c0` and `c1`
//!   (counter-clockwise from `c0`), Biermann et al.'s weights (OpenSubdiv's scaling);
//! - smooth: `Σ cos(2πi/n) ...` and the same rotated by one edge (Catmull-Clark weights face
//!   vertices too, `λ` its subdominant eigenvalue); Catmull-Clark's vertex of two faces takes
//!   the corner tangents.
//!
//! An interior crease or corner depends on where the list starts (the normal is that of the
//! span counter-clockwise from the first sharp edge, or of the first face); smooth vertices do
//! not. [`LimitRules::starts`] names OpenSubdiv's first face where the driver tracks it (runs
//! of Loop levels from the base mesh, [`crate::limit::FirstFaces`]).

use super::crease::{for_each_incident_edge, LevelTags};
use super::Weights;
use crate::mesh::HalfEdgeMesh;
use crate::options::{Boundary, Scheme};
use std::borrow::Cow;

/// The rule of a vertex at the limit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LimitRule {
    /// No faces: the vertex stays, and has no tangents.
    #[default]
    Isolated,
    /// The scheme's smooth masks (smooth and dart vertices).
    Smooth,
    /// Two sharp edges, at these positions of the edge list.
    Crease([u32; 2]),
    /// The vertex stays; tangents along its first two edges.
    Corner,
}

/// One vertex's neighbourhood in OpenSubdiv's order (see the module docs), gathered by
/// [`LimitRules::gather`] and read by [`LimitRules::position`] and [`LimitRules::tangents`]. Keep
/// one and gather into it vertex after vertex: its lists are reused.
#[derive(Clone, Debug, Default)]
pub struct Neighbourhood {
    /// The vertex.
    pub vertex: u32,
    /// Per incident edge, a half-edge whose from-vertex is the edge's other end (a corner).
    pub edges: Vec<u32>,
    /// Per incident face, the half-edge of the corner two steps on from the vertex (the
    /// opposite vertex of a quad).
    pub faces: Vec<u32>,
    pub rule: LimitRule,
    /// Catmull-Clark's masks (else Loop's): the scheme's, or for Quad/Triangle the vertex's
    /// faces' (see [`LimitRules::scheme`]).
    pub catmull_clark: bool,
    /// The smooth tangents' cosines and sines, made once per valence rather than once per
    /// vertex (they were a tenth of a limit `subdivide` in wasm, whose `cos` is software).
    angles: Angles,
}

/// Per valence `n`, `[cos, sin]` of `2πi/n` for `i` in `0..=n` (the last is the first again,
/// as computed: `cos(n · 2π/n)`), and Catmull-Clark's face scale `1/(4λ - 1)`.
#[derive(Clone, Debug, Default)]
struct Angles {
    rows: Vec<(Vec<[f64; 2]>, f64)>,
}

impl Angles {
    /// Makes the table of valence `n` if it is not there.
    fn prepare(&mut self, n: usize) {
        if self.rows.len() <= n {
            self.rows.resize(n + 1, (Vec::new(), 0.0));
        }
        if self.rows[n].0.is_empty() {
            self.rows[n] = Self::valence(n);
        }
    }

    /// The table of valence `n`: [`Angles::prepare`]'s, or made now (a neighbourhood that
    /// [`LimitRules::gather`] did not fill).
    fn of(&self, n: usize) -> Cow<'_, (Vec<[f64; 2]>, f64)> {
        match self.rows.get(n) {
            Some(row) if row.0.len() == n + 1 => Cow::Borrowed(row),
            _ => Cow::Owned(Self::valence(n)),
        }
    }

    fn valence(n: usize) -> (Vec<[f64; 2]>, f64) {
        let theta = std::f64::consts::TAU / n as f64;
        let angles = (0..=n).map(|i| {
            let a = theta * i as f64;
            [a.cos(), a.sin()]
        });
        (angles.collect(), catmull_clark_face_scale(n))
    }
}

/// Catmull-Clark's smooth limit position at valence `n`: the weights `(vertex, edge, face)` on
/// the vertex, each edge neighbour and each face's opposite corner (see the module docs; a
/// vertex of two faces stays).
pub(crate) fn catmull_clark_position_weights(n: usize) -> (f64, f64, f64) {
    match n {
        2 => (1.0, 0.0, 0.0),
        4 => (4.0 / 9.0, 1.0 / 9.0, 1.0 / 36.0),
        _ => {
            let n = n as f64;
            let f = 1.0 / (n * (n + 5.0));
            (1.0 - n * 5.0 * f, 4.0 * f, f)
        }
    }
}

/// Catmull-Clark's smooth limit tangents at valence `n` (3 or more): `each(i, [on_edge,
/// on_face])` for `i` in `0..n`, each `[first, second]`, the weights on edge neighbour `i` and on
/// face `i`'s opposite corner. `first` is `Σ 4 cos_i e_i + s (cos_i + cos_(i+1)) f_i` and
/// `second` is `first` rotated by one (its weight at `i` is `first`'s at `i - 1`); `cos(i)`
/// gives `cos(2πi/n)` for `i` in `0..=n` and `face_scale` is `s`
/// ([`catmull_clark_face_scale`]), both exact at `n` = 4 whatever is given.
pub(crate) fn catmull_clark_tangent_weights(
    n: usize,
    cos: impl Fn(usize) -> f64,
    face_scale: f64,
    mut each: impl FnMut(usize, [[f64; 2]; 2]),
) {
    let cos = |i: usize| if n == 4 { [1.0, 0.0, -1.0, 0.0][i % 4] } else { cos(i) };
    let face_scale = if n == 4 { 1.0 } else { face_scale };
    let face_weight = |i: usize| face_scale * (cos(i) + cos(i + 1));
    for i in 0..n {
        let before = (i + n - 1) % n;
        each(i, [[4.0 * cos(i), 4.0 * cos(before)], [face_weight(i), face_weight(before)]]);
    }
}

/// The scale `1/(4λ - 1)` of Catmull-Clark's smooth tangent weights on the faces' opposite
/// corners at valence `n`, `λ` the scheme's subdominant eigenvalue there.
pub(crate) fn catmull_clark_face_scale(n: usize) -> f64 {
    let theta = std::f64::consts::TAU / n as f64;
    let lambda = 5.0 / 16.0
        + (theta.cos() + (0.5 * theta).cos() * (2.0 * (9.0 + theta.cos())).sqrt()) / 16.0;
    1.0 / (4.0 * lambda - 1.0)
}

/// The limit masks of Catmull-Clark or Loop on one level (see the module docs): `tags` is the
/// level's sharpness when the level follows tags (the crease rules), `None` on the plain path.
#[derive(Clone, Copy, Debug)]
pub struct LimitRules<'a> {
    /// [`Scheme::CatmullClark`] or [`Scheme::Loop`]; [`Scheme::QuadTriangle`] on a level of quads
    /// and triangles takes Catmull-Clark's masks at a vertex whose faces are all quads, Loop's
    /// where they are all triangles (there the scheme is that scheme, and the neighbourhood
    /// the masks read evolves as under it), and where quads meet triangles, for want of
    /// published masks, the corner rule (the point stays; the normal is its first face
    /// corner's); any other scheme takes Loop's masks.
    pub scheme: Scheme,
    pub boundary: Boundary,
    pub tags: Option<&'a LevelTags>,
    /// Per vertex, an outgoing half-edge in the face an interior vertex's list starts with
    /// (OpenSubdiv's first face, see [`crate::limit::FirstFaces`]); `None`, or an entry that is
    /// not an outgoing half-edge of its vertex, starts at the vertex's first outgoing half-edge.
    pub starts: Option<&'a [u32]>,
}

impl LimitRules<'_> {
    /// Gathers `vertex`'s neighbourhood and rule into `hood`.
    pub fn gather(&self, mesh: &HalfEdgeMesh, vertex: u32, hood: &mut Neighbourhood) {
        hood.vertex = vertex;
        hood.edges.clear();
        hood.faces.clear();
        let (edges, faces) = (&mut hood.edges, &mut hood.faces);
        let out = mesh.out_half_edges(vertex);
        if out.is_empty() {
            hood.rule = LimitRule::Isolated;
            return;
        }
        // Sharp edges by position in the list: the first two, and how many.
        let (mut sharp, mut sharp_count) = ([0u32; 2], 0u32);
        let mut note = |sharp_edge: bool, position: usize| {
            if sharp_edge {
                if sharp_count < 2 {
                    sharp[sharp_count as usize] = position as u32;
                }
                sharp_count += 1;
            }
        };
        // Without tags only boundary edges are sharp.
        let is_sharp = |e: u32, boundary: bool| match self.tags {
            Some(tags) => tags.edge_sharpness(e) > 0.0,
            None => boundary,
        };
        let opposite = |h: u32| mesh.next_in_cell(mesh.next_in_cell(h));
        let general = self.tags.is_some_and(|t| t.is_non_manifold_vertex(vertex));
        let mut corner = false;
        if general {
            // A non-manifold vertex: its edges in no particular order (it is a corner unless
            // it lies on a seam of fins, where only the two sharp edges matter).
            for_each_incident_edge(mesh, vertex, true, |e, c| {
                note(is_sharp(e, false), edges.len());
                edges.push(c);
            });
            faces.extend(out.iter().map(|&h| opposite(h)));
        } else {
            // A boundary vertex starts at its leading boundary edge (listed first); an interior
            // one where `starts` says, if anywhere.
            let interior = mesh.he_next_around_edge[out[0] as usize] != out[0];
            let start = match self.starts.and_then(|s| s.get(vertex as usize)) {
                Some(&h) if interior && mesh.he_from.get(h as usize) == Some(&vertex) => h,
                _ => out[0],
            };
            let mut h = start;
            let mut closed = false;
            let mut open = false;
            for _ in 0..out.len() {
                let e = mesh.he_edge[h as usize];
                let boundary = mesh.he_next_around_edge[h as usize] == h;
                note(is_sharp(e, boundary), edges.len());
                edges.push(mesh.next_in_cell(h));
                faces.push(opposite(h));
                let incoming = mesh.prev_in_cell(h);
                let across = mesh.he_next_around_edge[incoming as usize];
                if across == incoming {
                    note(is_sharp(mesh.he_edge[incoming as usize], true), edges.len());
                    edges.push(incoming);
                    open = true;
                    break;
                }
                if across == start {
                    closed = true;
                    break;
                }
                if mesh.he_from[across as usize] != vertex {
                    break;
                }
                h = across;
            }
            // Several fans (or a walk sent astray): a corner.
            corner |= !(open || closed) || faces.len() != out.len();
            corner |= open && self.boundary == Boundary::Fixed;
            corner |= open && out.len() == 1 && self.boundary == Boundary::EdgeAndCorner;
        }
        corner |= self.tags.is_some_and(|t| t.vertex_sharpness(vertex) > 0.0);
        hood.catmull_clark = match self.scheme {
            Scheme::CatmullClark => true,
            Scheme::QuadTriangle => {
                let size = |h: &u32| mesh.cell_range(mesh.cell_of(*h) as usize).len();
                let quads = out.iter().filter(|h| size(h) == 4).count();
                corner |= quads != 0 && quads != out.len();
                quads == out.len()
            }
            _ => false,
        };
        hood.rule = if corner || sharp_count > 2 {
            LimitRule::Corner
        } else if sharp_count == 2 {
            LimitRule::Crease(sharp)
        } else {
            hood.angles.prepare(hood.faces.len());
            LimitRule::Smooth
        };
    }

    /// The weights of the limit position of the vertex `hood` was gathered for.
    pub fn position(&self, hood: &Neighbourhood, w: &mut impl Weights) {
        let v = hood.vertex;
        match hood.rule {
            LimitRule::Isolated | LimitRule::Corner => w.vertex(v, 1.0),
            LimitRule::Crease([a, b]) => {
                let (a, b) = (hood.edges[a as usize], hood.edges[b as usize]);
                w.scaled(1.0 / 6.0, |w| {
                    w.corner(a, 1.0);
                    w.corner(b, 1.0);
                });
                w.vertex(v, 2.0 / 3.0);
            }
            LimitRule::Smooth => {
                let n = hood.faces.len();
                let (vertex, edge, face) = match hood.catmull_clark {
                    true => catmull_clark_position_weights(n),
                    _ if n == 6 => (0.5, 1.0 / 12.0, 0.0),
                    _ => {
                        let cos = hood.angles.of(n).0.get(1).map_or(1.0, |a| a[0]);
                        let n = n as f64;
                        let beta = 0.25 * cos + 0.375;
                        let gamma = (0.625 - beta * beta) / n;
                        let e = 1.0 / (n + 3.0 / (8.0 * gamma));
                        (1.0 - e * n, e, 0.0)
                    }
                };
                // The small weights first, as OpenSubdiv sums them.
                if face != 0.0 {
                    let group = w.begin_group(face as f32);
                    for &c in &hood.faces {
                        w.corner(c, 1.0);
                    }
                    w.end_group(group);
                }
                if edge != 0.0 {
                    let group = w.begin_group(edge as f32);
                    for &c in &hood.edges[..n.min(hood.edges.len())] {
                        w.corner(c, 1.0);
                    }
                    w.end_group(group);
                }
                w.vertex(v, vertex as f32);
            }
        }
    }

    /// The weights of the two limit tangents (OpenSubdiv's `tan1`, `tan2`) of the vertex `hood`
    /// was gathered for. Each sums to 0; an isolated vertex weights nothing (zero tangents).
    pub fn tangents(
        &self,
        hood: &Neighbourhood,
        first: &mut impl Weights,
        second: &mut impl Weights,
    ) {
        let v = hood.vertex;
        let loop_scheme = !hood.catmull_clark;
        let edge = |i: usize| hood.edges.get(i).copied();
        let face = |i: usize| hood.faces.get(i).copied();
        // Catmull-Clark's vertex of two faces takes the corner's tangents.
        let corner = match hood.rule {
            LimitRule::Corner => true,
            LimitRule::Smooth => !loop_scheme && hood.faces.len() == 2,
            _ => false,
        };
        if corner {
            let s = if loop_scheme { 3.0 } else { 1.0 };
            add(first, edge(0), s);
            add(second, edge(1), s);
            first.vertex(v, -s as f32);
            second.vertex(v, -s as f32);
            return;
        }
        match hood.rule {
            LimitRule::Isolated | LimitRule::Corner => {}
            LimitRule::Smooth => {
                let n = hood.faces.len();
                let table = hood.angles.of(n);
                let (angles, face_scale) = (&table.0, table.1);
                if loop_scheme {
                    for (i, &[cos, sin]) in angles.iter().take(n).enumerate() {
                        add(first, edge(i), cos);
                        add(second, edge(i), sin);
                    }
                } else {
                    let cos = |i: usize| angles.get(i).map_or(0.0, |a| a[0]);
                    // The faces first, then the edges, as OpenSubdiv sums them.
                    catmull_clark_tangent_weights(n, cos, face_scale, |i, [_, on_face]| {
                        add(first, face(i), on_face[0]);
                        add(second, face(i), on_face[1]);
                    });
                    catmull_clark_tangent_weights(n, cos, face_scale, |i, [on_edge, _]| {
                        add(first, edge(i), on_edge[0]);
                        add(second, edge(i), on_edge[1]);
                    });
                }
            }
            LimitRule::Crease([c0, c1]) => {
                let (c0, c1) = (c0 as usize, c1 as usize);
                let along = if loop_scheme { 1.5 } else { 0.5 };
                add(first, edge(c0), along);
                add(first, edge(c1), -along);
                let interior = c1 - c0 - 1;
                let mut center = 0.0;
                if interior == 0 {
                    // No face between the sharp edges: across runs from the vertex to the
                    // midpoint of their ends (both schemes).
                    center = -6.0;
                    add(second, edge(c0), 3.0);
                    add(second, edge(c1), 3.0);
                } else if loop_scheme {
                    match interior {
                        1 => {
                            center = -3.0;
                            add(second, edge(c0 + 1), 3.0);
                        }
                        2 => {
                            let root3 = 3f64.sqrt();
                            center = -root3;
                            add(second, edge(c0), -0.5 * root3);
                            add(second, edge(c1), -0.5 * root3);
                            add(second, edge(c0 + 1), root3);
                            add(second, edge(c0 + 2), root3);
                        }
                        k => {
                            let theta = std::f64::consts::PI / (k + 1) as f64;
                            let ends = -3.0 * theta.sin();
                            add(second, edge(c0), ends);
                            add(second, edge(c1), ends);
                            let coefficient = -6.0 * (theta.cos() - 1.0);
                            for i in 1..=k {
                                add(second, edge(c0 + i), coefficient * (i as f64 * theta).sin());
                            }
                        }
                    }
                } else {
                    match interior {
                        1 => {
                            add(second, face(c0), 1.0 / 6.0);
                            add(second, face(c0 + 1), 1.0 / 6.0);
                            add(second, edge(c0), -1.0 / 6.0);
                            add(second, edge(c0 + 1), 4.0 / 6.0);
                            add(second, edge(c1), -1.0 / 6.0);
                            center = -4.0 / 6.0;
                        }
                        k => {
                            let k = (k + 1) as f64;
                            let theta = std::f64::consts::PI / k;
                            let (cos, sin) = (theta.cos(), theta.sin());
                            let denominator = 1.0 / (k * (3.0 + cos));
                            let r = (cos + 1.0) / sin;
                            add(second, face(c0), sin * denominator);
                            let mut sin_i;
                            let mut sin_next = sin;
                            for i in 1..(k as usize) {
                                sin_i = sin_next;
                                sin_next = ((i + 1) as f64 * theta).sin();
                                add(second, face(c0 + i), (sin_i + sin_next) * denominator);
                                add(second, edge(c0 + i), 4.0 * sin_i * denominator);
                            }
                            let ends = -r * (1.0 + 2.0 * cos) * denominator;
                            add(second, edge(c0), ends);
                            add(second, edge(c1), ends);
                            center = 4.0 * r * (cos - 1.0) * denominator;
                        }
                    }
                }
                if center != 0.0 {
                    second.vertex(v, center as f32);
                }
            }
        }
    }
}

/// Adds `weight` on corner `at`, when there is one and the weight is not 0.
#[inline(always)]
fn add(w: &mut impl Weights, at: Option<u32>, weight: f64) {
    if let Some(c) = at {
        if weight != 0.0 {
            w.corner(c, weight as f32);
        }
    }
}
