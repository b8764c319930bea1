//! Semi-sharp creases, corners, holes and non-manifold features, as OpenSubdiv 3 defines them
//! (`Sdc::Crease`, the `Sdc` scheme masks, and how `Vtr`/`Far` tag a level), read from its
//! headers and sources and written anew here. The same rules serve Catmull-Clark
//! ([`super::CreasedCatmullClark`]) and Loop ([`super::CreasedLoop`]).
//!
//! # Sharpness of the base level
//!
//! Every edge and vertex has a sharpness: 0 smooth, 10 ([`SHARPNESS_INFINITE`]) or more
//! infinitely sharp, between the two semi-sharp. [`LevelTags::base`] starts from the user's
//! [`Tags`] and then does as OpenSubdiv's factory does (a vertex with one face, and one whose
//! faces form several fans around manifold edges, are not written into the sharpness array: the
//! vertex rule recognises them at every level, since their children are the same kind of vertex,
//! which saves a walk around every vertex here):
//!
//! - boundary edges (one face) and non-manifold edges (three or more faces, or two faces using
//!   the edge in the same direction) become infinitely sharp, whatever the boundary mode;
//! - under [`Boundary::EdgeAndCorner`], a vertex with one face and two edges is an infinitely
//!   sharp corner;
//! - a non-manifold vertex (on a non-manifold edge, or whose faces form several fans) is an
//!   infinitely sharp corner, except on an interior non-manifold crease: exactly two non-manifold
//!   edges, no boundary edge and more faces than edges (a "fin" along a seam), where it keeps
//!   its sharpness and so follows the crease rule along the seam;
//! - under [`Boundary::None`], before boundary edges are sharpened, every face at a vertex
//!   with a boundary edge that the user did not make infinitely sharp becomes a hole; the
//!   positions are those of edge-only (tag the boundary edges of a region with sharpness 10 to
//!   keep it).
//!
//! # Rules
//!
//! A vertex's rule follows from its sharpness and the number of sharp edges at it: a sharp vertex,
//! or three or more sharp edges, is a **corner** (it stays); two sharp edges a **crease**
//! (`3/4 v + 1/8 (a + b)`, `a` and `b` across the two sharp edges); one a **dart** and none
//! **smooth** (both the scheme's smooth rule). An edge point is the midpoint when the edge and both
//! its halves at the next level are sharp, the smooth rule when the edge is smooth.
//!
//! **Transitions.** When the rule at the next level differs (some sharpness decays to 0), the
//! point blends the two: for an edge of sharpness `s` (below 1, except with Chaikin),
//! `s · midpoint + (1 - s) · smooth`; for a
//! vertex, `w · parent rule + (1 - w) · child rule`, `w` the mean of the sharpness of the edges
//! (and the vertex) that are sharp now and smooth at the next level, at most 1.
//!
//! # Sharpness of the next level
//!
//! Inner edges (inside a parent face) and new vertices are smooth; each half of a parent edge, and
//! each child of a parent vertex, inherits a decayed sharpness: infinite stays infinite, and
//!
//! - [`CreaseMethod::Uniform`]: `s - 1`, or 0 when `s <= 1`;
//! - [`CreaseMethod::Chaikin`] (edges only; vertices decay uniformly): the half at vertex `v`
//!   gets `3/4 s + 1/4 m - 1` (0 if not positive), `m` the mean sharpness of the other
//!   semi-sharp edges at `v`; with no other semi-sharp edge at `v`, the uniform rule.
//!
//! Child faces of a hole are holes.

use super::{boundary_vertex_rule, fan, one_ring, Scaled, Weights};
use crate::error::{Error, Result};
use crate::mesh::HalfEdgeMesh;
use crate::options::Boundary;
use crate::options::CreaseMethod;
use crate::tags::{Tags, SHARPNESS_INFINITE};

/// The subdivision rule of a vertex (OpenSubdiv's `Sdc::Crease::Rule`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VertexRule {
    /// No sharp edge: the smooth rule.
    Smooth,
    /// One sharp edge: the smooth rule too.
    Dart,
    /// Two sharp edges: `3/4 v + 1/8 (a + b)`.
    Crease,
    /// A sharp vertex, or three or more sharp edges: the vertex stays.
    Corner,
}

/// The rule of a vertex of sharpness `vertex_sharpness` with `sharp_edges` sharp edges.
#[inline]
pub fn vertex_rule(vertex_sharpness: f32, sharp_edges: u32) -> VertexRule {
    if vertex_sharpness > 0.0 {
        return VertexRule::Corner;
    }
    match sharp_edges {
        0 => VertexRule::Smooth,
        1 => VertexRule::Dart,
        2 => VertexRule::Crease,
        _ => VertexRule::Corner,
    }
}

/// Uniform decay: smooth stays smooth, infinite stays infinite, otherwise one less (0 at most 1).
#[inline]
pub fn decay(sharpness: f32) -> f32 {
    if sharpness >= SHARPNESS_INFINITE {
        SHARPNESS_INFINITE
    } else if sharpness > 1.0 {
        sharpness - 1.0
    } else {
        0.0
    }
}

/// Chaikin decay of an edge of sharpness `s` at a vertex whose semi-sharp edges (this one
/// included, if semi-sharp) have sharpness sum `semi_sum` and number `semi_count`.
#[inline]
pub fn chaikin_decay(s: f32, semi_sum: f32, semi_count: u32) -> f32 {
    if s <= 0.0 {
        return 0.0;
    }
    if s >= SHARPNESS_INFINITE {
        return SHARPNESS_INFINITE;
    }
    let blended = if semi_count > 1 {
        let others = (semi_sum - s) / (semi_count - 1) as f32;
        0.75 * s + 0.25 * others
    } else {
        s
    };
    let child = blended - 1.0;
    if child > 0.0 {
        child
    } else {
        0.0
    }
}

#[inline]
fn is_semi_sharp(s: f32) -> bool {
    s > 0.0 && s < SHARPNESS_INFINITE
}

/// The sharpness of one level's edges and vertices (after the base level's boundary and
/// non-manifold sharpening), its hole faces, and the options that go with them. Built for the
/// base mesh by [`LevelTags::base`], and for each refined level by the host
/// ([`crate::refine::pqq::child_tags`], [`crate::refine::ptq::child_tags`]).
#[derive(Clone, Debug, PartialEq)]
pub struct LevelTags {
    pub(crate) edges: Vec<f32>,
    pub(crate) vertices: Vec<f32>,
    /// One flag per face; empty when no face is a hole.
    pub(crate) holes: Vec<bool>,
    /// One flag per vertex: true when a non-manifold edge touches it, so its edges must be
    /// gathered the general way. Empty when the mesh has no non-manifold edge.
    pub(crate) non_manifold: Vec<bool>,
    pub(crate) method: CreaseMethod,
    pub(crate) smooth_triangles: bool,
    /// Chaikin only: per vertex, the sum and number of its semi-sharp edges.
    semi_sum: Vec<f32>,
    semi_count: Vec<u32>,
    /// Per vertex, its sharp edges now and at the next level: gathered edge by edge (so each
    /// distinct edge counts once, manifold or not) before the vertex rules run, so that most
    /// vertices on creases need no walk around them.
    sharp_edges: Vec<SharpEdges>,
}

/// The sharp edges at one vertex: how many are sharp, how many stay sharp at the next level,
/// how many decay to smooth and the sum of their sharpness. Counts saturate at 255 (a rule only
/// distinguishes 0, 1, 2 and more).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct SharpEdges {
    sharp: u8,
    child_sharp: u8,
    decayed: u8,
    decayed_sum: f32,
}

impl LevelTags {
    /// The base level: the user's tags, validated against `mesh`, then the sharpening described
    /// in the module docs. `boundary_holes` turns the faces at boundary vertices into holes (for
    /// [`Boundary::None`] on a primal scheme).
    pub fn base(mesh: &HalfEdgeMesh, tags: &Tags, boundary_holes: bool) -> Result<Self> {
        tags.validate(mesh.num_vertices(), mesh.num_cells())?;
        let crease_edges = crease_edges(mesh, tags)?;
        Ok(Self::base_with_edges(mesh, tags, &crease_edges, boundary_holes))
    }

    /// [`LevelTags::base`] for tags already validated, with the edge of each crease.
    pub(crate) fn base_with_edges(
        mesh: &HalfEdgeMesh,
        tags: &Tags,
        crease_edges: &[u32],
        boundary_holes: bool,
    ) -> Self {
        let mut edges = vec![0.0f32; mesh.num_edges()];
        for (c, &e) in tags.creases.iter().zip(crease_edges) {
            edges[e as usize] = c.sharpness.min(SHARPNESS_INFINITE);
        }
        let mut vertices = vec![0.0f32; mesh.num_vertices()];
        for c in &tags.corners {
            vertices[c.vertex as usize] = c.sharpness.min(SHARPNESS_INFINITE);
        }
        let mut holes = Vec::new();
        if !tags.holes.is_empty() || boundary_holes {
            holes = vec![false; mesh.num_cells()];
            for &f in &tags.holes {
                holes[f as usize] = true;
            }
        }

        if boundary_holes {
            // Before boundary edges are sharpened: a vertex with a boundary edge that the user
            // did not make infinitely sharp has all its faces excluded.
            let mut excluded = vec![false; mesh.num_vertices()];
            for (e, &s) in edges.iter().enumerate() {
                if mesh.edge_offsets[e + 1] - mesh.edge_offsets[e] == 1 && s < SHARPNESS_INFINITE {
                    for v in mesh.edge_vertices[e] {
                        excluded[v as usize] = true;
                    }
                }
            }
            for (v, _) in excluded.iter().enumerate().filter(|(_, &x)| x) {
                for &h in mesh.out_half_edges(v as u32) {
                    holes[mesh.cell_of(h) as usize] = true;
                }
            }
        }
        let mut non_manifold = Vec::new();
        if mesh.non_manifold_edges {
            non_manifold = vec![false; mesh.num_vertices()];
        }
        for (e, s) in edges.iter_mut().enumerate() {
            let count = mesh.edge_offsets[e + 1] - mesh.edge_offsets[e];
            // A marked edge (from a face that repeats a vertex) may have one half-edge.
            let non_manifold_edge = mesh.non_manifold_edges && mesh.is_non_manifold_edge(e as u32);
            if count == 1 || non_manifold_edge {
                *s = SHARPNESS_INFINITE;
            }
            if non_manifold_edge {
                let [a, b] = mesh.edge_vertices[e];
                non_manifold[a as usize] = true;
                non_manifold[b as usize] = true;
            }
        }

        // Vertices on a non-manifold edge: corners, except along an interior non-manifold
        // crease (a seam with fins: two non-manifold edges, no boundary, more faces than
        // edges). Topological corners (edge-and-corner) and vertices with several fans around
        // manifold edges are corners too, but the vertex rule finds those itself at every level
        // (their children are the same kind), which saves a walk around every vertex here.
        for (v, sharpness) in vertices.iter_mut().enumerate() {
            if !non_manifold.get(v).copied().unwrap_or(false) {
                continue;
            }
            let faces = mesh.out_half_edges(v as u32).len();
            let (mut incident, mut boundary_edges, mut non_manifold_edges) = (0usize, 0, 0);
            for_each_incident_edge(mesh, v as u32, true, |e, _| {
                incident += 1;
                let count = mesh.edge_offsets[e as usize + 1] - mesh.edge_offsets[e as usize];
                boundary_edges += (count == 1) as u32;
                non_manifold_edges += mesh.is_non_manifold_edge(e) as u32;
            });
            let seam = non_manifold_edges == 2 && boundary_edges == 0 && faces > incident;
            if !seam {
                *sharpness = SHARPNESS_INFINITE;
            }
        }
        Self::new(
            mesh,
            edges,
            vertices,
            holes,
            non_manifold,
            tags.crease_method,
            tags.smooth_triangles,
        )
    }

    /// Assembles a level's tags; computes the per-vertex sums Chaikin's rule reads.
    pub(crate) fn new(
        mesh: &HalfEdgeMesh,
        edges: Vec<f32>,
        vertices: Vec<f32>,
        holes: Vec<bool>,
        non_manifold: Vec<bool>,
        method: CreaseMethod,
        smooth_triangles: bool,
    ) -> Self {
        let (mut semi_sum, mut semi_count) = (Vec::new(), Vec::new());
        if method == CreaseMethod::Chaikin && edges.iter().any(|&s| is_semi_sharp(s)) {
            semi_sum = vec![0.0f32; mesh.num_vertices()];
            semi_count = vec![0u32; mesh.num_vertices()];
            for (e, &s) in edges.iter().enumerate() {
                if is_semi_sharp(s) {
                    for v in mesh.edge_vertices[e] {
                        semi_sum[v as usize] += s;
                        semi_count[v as usize] += 1;
                    }
                }
            }
        }
        let mut tags = LevelTags {
            edges,
            vertices,
            holes,
            non_manifold,
            method,
            smooth_triangles,
            semi_sum,
            semi_count,
            sharp_edges: Vec::new(),
        };
        let mut sharp_edges = vec![SharpEdges::default(); mesh.num_vertices()];
        for (e, &s) in tags.edges.iter().enumerate() {
            if s > 0.0 {
                for v in mesh.edge_vertices[e] {
                    let child = tags.decay_at(s, v);
                    let at = &mut sharp_edges[v as usize];
                    at.sharp = at.sharp.saturating_add(1);
                    if child > 0.0 {
                        at.child_sharp = at.child_sharp.saturating_add(1);
                    } else {
                        at.decayed = at.decayed.saturating_add(1);
                        at.decayed_sum += s;
                    }
                }
            }
        }
        tags.sharp_edges = sharp_edges;
        tags
    }

    /// Sharpness of edge `e` (infinite for boundary and non-manifold edges).
    pub fn edge_sharpness(&self, e: u32) -> f32 {
        self.edges[e as usize]
    }

    /// Sharpness of vertex `v`.
    pub fn vertex_sharpness(&self, v: u32) -> f32 {
        self.vertices[v as usize]
    }

    /// True when face `f` is a hole.
    pub fn is_hole(&self, f: u32) -> bool {
        self.holes.get(f as usize).copied().unwrap_or(false)
    }

    /// True when some face is a hole.
    pub fn has_holes(&self) -> bool {
        !self.holes.is_empty()
    }

    /// True when a non-manifold edge touches vertex `v`.
    #[inline]
    pub(crate) fn is_non_manifold_vertex(&self, v: u32) -> bool {
        self.non_manifold.get(v as usize).copied().unwrap_or(false)
    }

    /// The sharpness, at the next level, of an edge of sharpness `s` at (the half touching)
    /// vertex `at`.
    #[inline]
    pub(crate) fn decay_at(&self, s: f32, at: u32) -> f32 {
        match self.method {
            CreaseMethod::Chaikin if !self.semi_sum.is_empty() => {
                chaikin_decay(s, self.semi_sum[at as usize], self.semi_count[at as usize])
            }
            _ => decay(s),
        }
    }

    /// The sharpness at the next level of the half of edge `e` that touches its vertex `at`.
    #[inline]
    pub fn child_edge_sharpness(&self, e: u32, at: u32) -> f32 {
        self.decay_at(self.edges[e as usize], at)
    }

    /// True when both halves of sharp edge `e` are still sharp at the next level, so the edge
    /// point is the plain midpoint (no transition).
    #[inline]
    pub(crate) fn both_halves_sharp(&self, mesh: &HalfEdgeMesh, e: u32) -> bool {
        let s = self.edges[e as usize];
        match self.method {
            CreaseMethod::Uniform => s > 1.0,
            CreaseMethod::Chaikin => {
                let [a, b] = mesh.edge_vertices[e as usize];
                self.decay_at(s, a) > 0.0 && self.decay_at(s, b) > 0.0
            }
        }
    }
}

/// The edge of each crease tag, or an error naming the first crease that is not an edge. The
/// vertices must be in range ([`Tags::validate`]).
pub(crate) fn crease_edges(mesh: &HalfEdgeMesh, tags: &Tags) -> Result<Vec<u32>> {
    tags.creases
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let [a, b] = c.vertices;
            find_edge(mesh, a, b).ok_or_else(|| {
                Error::InvalidTag(format!(
                    "crease {i} (vertices {a}, {b}): the mesh has no edge between vertices {a} and {b}; \
                     a crease must name the two vertices of an edge"
                ))
            })
        })
        .collect()
}

/// The edge joining `a` and `b`, either way round (the first of `a`'s outgoing half-edges that
/// has one, else `b`'s).
pub(crate) fn find_edge(mesh: &HalfEdgeMesh, a: u32, b: u32) -> Option<u32> {
    let find = |from: u32| {
        mesh.out_half_edges(from).iter().map(|&h| mesh.he_edge[h as usize]).find(|&e| {
            let [x, y] = mesh.edge_vertices[e as usize];
            (x == a && y == b) || (x == b && y == a)
        })
    };
    // Unless a face repeats a vertex, two vertices share at most one edge, so the shorter list
    // may be searched first: a crease on each spoke of a fan's hub made `n²` steps otherwise.
    let short_first =
        !mesh.repeated_corners && mesh.out_half_edges(b).len() < mesh.out_half_edges(a).len();
    let (first, second) = if short_first { (b, a) } else { (a, b) };
    find(first).or_else(|| find(second))
}

/// Calls `visit(edge, corner)` once for every edge at `vertex`, where `corner` is a half-edge
/// whose from-vertex is the edge's other end (see [`Weights::corner`]). The fast way (every
/// outgoing half-edge, plus incoming boundary half-edges) counts each manifold edge once; with
/// `general` (a non-manifold edge touches the vertex) the edges are gathered from every outgoing
/// and incoming half-edge and de-duplicated.
#[inline]
pub(crate) fn for_each_incident_edge(
    mesh: &HalfEdgeMesh,
    vertex: u32,
    general: bool,
    mut visit: impl FnMut(u32, u32),
) {
    let out = mesh.out_half_edges(vertex);
    if !general {
        for &h in out {
            visit(mesh.he_edge[h as usize], mesh.next_in_cell(h));
            let incoming = mesh.prev_in_cell(h);
            if mesh.he_next_around_edge[incoming as usize] == incoming {
                visit(mesh.he_edge[incoming as usize], incoming);
            }
        }
        return;
    }
    let mut list: Vec<(u32, u32)> = Vec::with_capacity(2 * out.len());
    for &h in out {
        list.push((mesh.he_edge[h as usize], mesh.next_in_cell(h)));
        let incoming = mesh.prev_in_cell(h);
        list.push((mesh.he_edge[incoming as usize], incoming));
    }
    list.sort_unstable();
    list.dedup_by_key(|p| p.0);
    for (e, corner) in list {
        visit(e, corner);
    }
}

/// Walks once around `vertex` (which must have faces) as [`super::fan`] does, calling
/// `visit(edge, corner)` for each incident edge as [`for_each_incident_edge`] does; returns the
/// number of edges, or `None` when the faces do not form one fan (a non-manifold vertex). Edges
/// may have been visited before `None` is known.
#[inline]
fn walk_fan(mesh: &HalfEdgeMesh, vertex: u32, mut visit: impl FnMut(u32, u32)) -> Option<u32> {
    let out = mesh.out_half_edges(vertex);
    let start = out[0];
    let open = mesh.he_next_around_edge[start as usize] == start;
    let mut h = start;
    for faces in 1..=out.len() as u32 {
        visit(mesh.he_edge[h as usize], mesh.next_in_cell(h));
        let incoming = mesh.prev_in_cell(h);
        let across = mesh.he_next_around_edge[incoming as usize];
        if across == incoming {
            visit(mesh.he_edge[incoming as usize], incoming);
            return (open && faces as usize == out.len()).then_some(faces + 1);
        }
        if across == start {
            return (!open && faces as usize == out.len()).then_some(faces);
        }
        if mesh.he_from[across as usize] != vertex {
            return None;
        }
        h = across;
    }
    None
}

/// The weights of `vertex`'s new position under the crease rules. `smooth.0(n)` is the scheme's
/// smooth vertex mask for `n` faces: the weight on the vertex and on each neighbour, and with
/// `smooth.1` on each face point too (Catmull-Clark). See the module docs.
#[inline]
pub(crate) fn creased_vertex_point<W: Weights>(
    mesh: &HalfEdgeMesh,
    tags: &LevelTags,
    boundary: Boundary,
    vertex: u32,
    (smooth_mask, faces): (impl Fn(u32) -> [f32; 2], bool),
    w: &mut W,
) {
    let out = mesh.out_half_edges(vertex);
    if out.is_empty() {
        return w.vertex(vertex, 1.0);
    }
    let general = tags.is_non_manifold_vertex(vertex);
    if !general {
        if matches!(boundary, Boundary::Fixed | Boundary::Average) {
            // Our own boundary rules replace the crease rules at boundary vertices.
            let Some(ring) = fan(mesh, vertex) else {
                return w.vertex(vertex, 1.0); // several fans: a corner
            };
            if boundary_vertex_rule(boundary, mesh, vertex, &ring, w) {
                return;
            }
        } else if out.len() == 1 && boundary == Boundary::EdgeAndCorner {
            return w.vertex(vertex, 1.0); // one face (and so two edges): a corner
        }
    }
    let counts = tags.sharp_edges[vertex as usize];
    let vertex_sharpness = tags.vertices[vertex as usize];
    let child_vertex_sharpness = decay(vertex_sharpness);
    let parent_rule = vertex_rule(vertex_sharpness, counts.sharp as u32);
    let child_rule = vertex_rule(child_vertex_sharpness, counts.child_sharp as u32);
    // A corner that stays one needs nothing more. (A vertex whose faces form several fans is a
    // corner too; the walks below find those.)
    if parent_rule == VertexRule::Corner && child_rule == VertexRule::Corner {
        return w.vertex(vertex, 1.0);
    }
    // Only a smooth or dart vertex needs its whole neighbourhood; it is interior and manifold
    // (boundary and non-manifold edges are sharp), so its outgoing half-edges reach every edge.
    let smooth = |scale: f32, w: &mut W| match fan(mesh, vertex) {
        Some(ring) => {
            let [center, ring_weight] = smooth_mask(ring.faces);
            let mut scaled = Scaled { inner: w, scale };
            one_ring(mesh, vertex, &ring, ring_weight, faces, &mut scaled);
            scaled.vertex(vertex, center);
        }
        None => w.vertex(vertex, scale),
    };
    if matches!(parent_rule, VertexRule::Smooth | VertexRule::Dart) {
        // Sharpness only decays: a smooth or dart vertex stays one.
        return smooth(1.0, w);
    }
    // A crease, or a corner in transition: find the sharp edges' other ends (as corners), now
    // and at the next level.
    let (mut ends, mut found) = ([0u32; 2], 0u32);
    let (mut child_ends, mut child_found) = ([0u32; 2], 0u32);
    let visit = |e: u32, corner: u32| {
        let s = tags.edges[e as usize];
        if s > 0.0 {
            if found == 0 {
                ends[0] = corner;
            }
            ends[1] = corner;
            found += 1;
            if tags.decay_at(s, vertex) > 0.0 {
                if child_found == 0 {
                    child_ends[0] = corner;
                }
                child_ends[1] = corner;
                child_found += 1;
            }
        }
    };
    if general {
        for_each_incident_edge(mesh, vertex, true, visit);
    } else if walk_fan(mesh, vertex, visit).is_none() {
        return w.vertex(vertex, 1.0); // several fans: a corner
    }
    let crease = |[a, b]: [u32; 2], scale: f32, w: &mut W| {
        w.scaled(0.125 * scale, |w| {
            w.corner(a, 1.0);
            w.corner(b, 1.0);
        });
        w.vertex(vertex, 0.75 * scale);
    };
    let (mut decayed_sum, mut decayed) = (counts.decayed_sum, counts.decayed as u32);
    if vertex_sharpness > 0.0 && child_vertex_sharpness <= 0.0 {
        decayed_sum += vertex_sharpness;
        decayed += 1;
    }
    // Without a transition the parent rule alone; otherwise `weight` of it and the rest of the
    // child rule.
    let transition = child_rule != parent_rule && decayed > 0;
    let weight = if transition { (decayed_sum / decayed as f32).min(1.0) } else { 1.0 };
    match parent_rule {
        VertexRule::Crease => crease(ends, weight, w),
        _ => w.vertex(vertex, weight),
    }
    if !transition {
        return;
    }
    let rest = 1.0 - weight;
    match child_rule {
        VertexRule::Smooth | VertexRule::Dart => smooth(rest, w),
        VertexRule::Crease => crease(child_ends, rest, w),
        VertexRule::Corner => w.vertex(vertex, rest),
    }
}

/// The two half-edges of `edge` when its point needs the scheme's smooth mask (a smooth edge,
/// or a sharp one in transition); `None` when it is the midpoint: a sharp edge whose halves stay
/// sharp, or a boundary or non-manifold edge (infinitely sharp).
#[inline]
pub(crate) fn sharp_or_smooth(
    mesh: &HalfEdgeMesh,
    tags: &LevelTags,
    edge: u32,
) -> Option<[u32; 2]> {
    let s = tags.edges[edge as usize];
    if s > 0.0 && tags.both_halves_sharp(mesh, edge) {
        return None;
    }
    super::smooth_edge(mesh, edge)
}

/// The weights of the ends of a sharp or smooth edge; returns the weight of each of the two
/// opposite points (face points or opposite corners), which the caller weights itself.
/// `vertex_weight` on each end and `face_weight` on each opposite point are the scheme's smooth
/// mask; a sharp edge whose halves stay sharp gives the midpoint, one whose halves decay blends
/// the midpoint and the smooth mask by its sharpness (`s < 1` with the uniform method; with
/// Chaikin `s` may exceed 1, and the blend is then an extrapolation, exactly as OpenSubdiv
/// computes it).
#[inline]
pub(crate) fn creased_edge_point(
    mesh: &HalfEdgeMesh,
    tags: &LevelTags,
    edge: u32,
    vertex_weight: f32,
    face_weight: f32,
    w: &mut impl Weights,
) -> f32 {
    let s = tags.edges[edge as usize];
    let (vertex_weight, face_weight) = if s <= 0.0 {
        (vertex_weight, face_weight)
    } else if tags.both_halves_sharp(mesh, edge) {
        (0.5, 0.0)
    } else {
        (s * 0.5 + (1.0 - s) * vertex_weight, (1.0 - s) * face_weight)
    };
    super::edge_ends(mesh, edge, vertex_weight, w);
    face_weight
}
