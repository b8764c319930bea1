//! Joining pairs of triangles into quads, as Blender's "Tris to Quads" operator
//! (`bmo_join_triangles.c`) does, so that Catmull-Clark gets back the quads a triangulated model
//! was made of.

use super::edges::{angle_between, point, triangle_area, unit_normal, TriangleEdges};
use super::next3;
use super::sharp::SMOOTH;
use crate::error::{Error, Result};
use std::f64::consts::{FRAC_PI_2, PI};

/// The two thresholds of "Tris to Quads", in radians.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuadLimits {
    /// The largest angle between the normals of the two triangles joined.
    pub face_angle: f64,
    /// The largest angle between the normals of the two triangles on the quad's other diagonal
    /// (a skinny or folded quad exceeds it).
    pub shape_angle: f64,
}

impl Default for QuadLimits {
    /// Blender's defaults: 40° for both.
    fn default() -> Self {
        QuadLimits { face_angle: 40f64.to_radians(), shape_angle: 40f64.to_radians() }
    }
}

/// What else keeps two triangles apart, besides a marked edge. Every field is optional.
#[derive(Clone, Copy, Debug, Default)]
pub struct JoinConstraints<'a> {
    /// A group per triangle (a material): triangles of different groups stay apart.
    pub groups: Option<&'a [u32]>,
    /// A class per triangle corner (`3 t + j`): two triangles join only when the corners they
    /// have at each end of the shared edge are of one class (a UV seam at a vertex gives its
    /// sides different classes).
    pub corner_classes: Option<&'a [u32]>,
    /// Per triangle, whether it is a hole: holes join nothing.
    pub holes: Option<&'a [bool]>,
}

/// Polygons made of a triangle list's triangles: each a triangle or two joined into a quad.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Polygons {
    /// 3 or 4 per polygon.
    pub face_sizes: Vec<u32>,
    /// Per polygon corner, the triangle corner (`3 t + j`) it is: its vertex is that corner's,
    /// and so is any data the corner carries.
    pub corners: Vec<u32>,
    /// Per polygon, its (first) triangle. Polygons are in the order of these.
    pub first_triangles: Vec<u32>,
}

impl Polygons {
    /// Data given per triangle corner (`3 t + j`), one value per polygon corner: the corners'
    /// vertices, their input vertices. Errors when `per_corner` misses a corner.
    pub fn gather(&self, per_corner: &[u32]) -> Result<Vec<u32>> {
        self.corners
            .iter()
            .map(|&c| per_corner.get(c as usize).copied())
            .collect::<Option<Vec<u32>>>()
            .ok_or_else(|| {
                Error::mesh(format!(
                    "polygons: {} values given per triangle corner, but the polygons use corner {}",
                    per_corner.len(),
                    self.corners.iter().max().copied().unwrap_or_default()
                ))
            })
    }
}

/// Every triangle of a list of `triangles` (fewer than 2^32 / 3) as a polygon of its own.
pub(crate) fn triangle_polygons(triangles: usize) -> Polygons {
    Polygons {
        face_sizes: vec![3; triangles],
        corners: (0..3 * triangles as u32).collect(),
        first_triangles: (0..triangles as u32).collect(),
    }
}

/// Blender's join error of the quad (v1, v2, v3, v4) (`bmo_join_triangles.c`,
/// `quad_calc_error`): how far its two triangulations are from flat, how far its corners are
/// from right angles and how unequal the two triangulations' areas are (a concave quad's
/// differ); each term is 0 for a flat rectangle. Errors when a corner names no vertex of
/// `positions` (x, y, z per vertex).
pub fn quad_error(positions: &[f32], quad: [u32; 4]) -> Result<f64> {
    let vertices = positions.len() / 3;
    if let Some(&v) = quad.iter().find(|&&v| v as usize >= vertices) {
        return Err(Error::mesh(format!(
            "quad error: the quad names vertex {v}, but there are only {vertices}"
        )));
    }
    Ok(quad_error_unchecked(positions, quad))
}

fn quad_error_unchecked(positions: &[f32], quad: [u32; 4]) -> f64 {
    let [v1, v2, v3, v4] = quad;
    let normal = |i, j, k| unit_normal(positions, i, j, k);
    let flat = (angle_between(normal(v1, v2, v3), normal(v1, v3, v4))
        + angle_between(normal(v2, v3, v4), normal(v4, v1, v2)))
        / (2.0 * PI);
    let side = |i: usize| {
        let d = point(positions, quad[i]) - point(positions, quad[(i + 1) % 4]);
        let length = d.length();
        d / if length > 0.0 { length } else { 1.0 }
    };
    let sides = [side(0), side(1), side(2), side(3)];
    let square = (0..4)
        .map(|i| (angle_between(Some(sides[i]), Some(sides[(i + 1) % 4])) - FRAC_PI_2).abs())
        .sum::<f64>()
        / (2.0 * PI);
    let area = |i, j, k| triangle_area(positions, i, j, k);
    let area_a = area(v1, v2, v3) + area(v1, v3, v4);
    let area_b = area(v2, v3, v4) + area(v4, v1, v2);
    let max = area_a.max(area_b);
    let concave = if max > 0.0 { 1.0 - area_a.min(area_b) / max } else { 1.0 };
    flat + square + concave
}

/// Blender's "Tris to Quads" on the triangles `corners` (three vertices of `positions` each)
/// with their `edges`: every edge between two consistently wound triangles that is not marked
/// (`marks`, one per edge: any value but [`SMOOTH`] keeps it), is allowed by `constraints`,
/// and makes a convex quad whose triangles' normals differ by at most `limits.face_angle` and
/// whose other diagonal's triangles' by at most `limits.shape_angle`, is a candidate;
/// candidates are taken greedily by [`quad_error`], smallest first (ties in edge order), while
/// both triangles are free. Two steps are ours, so that a quad mesh triangulated with one
/// diagonal per quad gets its own quads back: consecutive triangles `t`, `t + 1` that are a
/// candidate are joined first, in order (exporters write a quad's two triangles together),
/// and after the greedy pass, triangles left alone are joined where a short chain of
/// re-pairings allows it (`Matching::augment`). A quad (u, q, v, p) of triangles (u, v, p) and
/// (v, u, q) starts at the shared edge's corner in the lower triangle.
///
/// Errors when the arrays do not fit each other.
pub fn join_quads(
    positions: &[f32],
    corners: &[u32],
    edges: &TriangleEdges,
    marks: &[u8],
    constraints: &JoinConstraints,
    limits: QuadLimits,
) -> Result<Polygons> {
    let triangles = corners.len() / 3;
    check_join(positions, corners, edges, marks, constraints)?;
    let vertex = |h: usize| corners[h];
    let mut candidates = Vec::new();
    let mut errors = Vec::new();
    for (e, &mark) in marks.iter().enumerate() {
        if mark != SMOOTH {
            continue;
        }
        let Some((t1, t2)) = edges.triangles(e) else { continue };
        if t1 == t2 {
            continue;
        }
        if constraints.groups.is_some_and(|g| g[t1] != g[t2]) {
            continue;
        }
        if constraints.holes.is_some_and(|h| h[t1] || h[t2]) {
            continue;
        }
        // t1 = (u, v, p) with h: u -> v; t2 = (v, u, q) with g: v -> u; the quad is (u, q, v, p).
        let (h, g) = (edges.h0[e] as usize, edges.h1[e] as usize);
        let (u, v, p, q) =
            (vertex(h), vertex(next3(h)), vertex(next3(next3(h))), vertex(next3(next3(g))));
        if p == q {
            continue;
        }
        if let Some(class) = constraints.corner_classes {
            if class[h] != class[next3(g)] || class[next3(h)] != class[g] {
                continue;
            }
        }
        let normal = |i, j, k| unit_normal(positions, i, j, k);
        let (Some(n1), Some(n2)) = (normal(u, v, p), normal(v, u, q)) else { continue };
        if angle_between(Some(n1), Some(n2)) > limits.face_angle {
            continue;
        }
        let (Some(n3), Some(n4)) = (normal(q, v, p), normal(p, u, q)) else { continue };
        if angle_between(Some(n3), Some(n4)) > limits.shape_angle {
            continue;
        }
        // Convex: the other diagonal's triangles face the way the quad does.
        let n = n1 + n2;
        if n3.dot(n) <= 0.0 || n4.dot(n) <= 0.0 {
            continue;
        }
        candidates.push(e);
        errors.push(quad_error_unchecked(positions, [u, q, v, p]));
    }
    let mut order: Vec<usize> = (0..candidates.len()).collect();
    order.sort_by(|&i, &j| errors[i].total_cmp(&errors[j]).then(i.cmp(&j)));

    let graph = Candidates::new(edges, &candidates, &order, triangles);
    // Per triangle, its partner and the half-edge on the shared edge.
    let mut matching = Matching {
        partner: vec![FREE; triangles],
        join_edge: vec![FREE; triangles],
        apart: vec![false; triangles],
    };
    // Exporters (glTF, three.js geometries) write a quad's two triangles one after the other;
    // geometry alone cannot tell which of two near-equal pairs was the quad (the thin quads
    // of a fan around a pole, folded quads), their order can. So consecutive triangles are
    // joined first, in order, where the rule allows them; a consecutive pair the rule refuses
    // (a folded quad) stays two triangles: joining either with a neighbour would make a quad
    // the model never had.
    let mut t = 0;
    while t + 1 < triangles {
        let next_to = |e: u32| {
            let (t1, t2) = ends(edges, e as usize);
            t1.min(t2) == t && t1.max(t2) == t + 1
        };
        if !(0..3).any(|j| next_to(edges.edge_of[3 * t + j])) {
            t += 1;
            continue;
        }
        match graph.of(t).iter().find(|&&e| next_to(e)) {
            Some(&e) => matching.pair(edges, e as usize),
            None => (matching.apart[t], matching.apart[t + 1]) = (true, true),
        }
        t += 2;
    }
    for &i in &order {
        let (t1, t2) = ends(edges, candidates[i]);
        if matching.is_free(t1) && matching.is_free(t2) {
            matching.pair(edges, candidates[i]);
        }
    }
    matching.augment(edges, &graph);
    let joined = matching.partner.iter().filter(|&&p| p != FREE).count() / 2;
    let Matching { partner, join_edge, .. } = matching;

    let count = triangles - joined;
    let mut polygons = Polygons {
        face_sizes: Vec::with_capacity(count),
        corners: Vec::with_capacity(3 * triangles - 2 * joined),
        first_triangles: Vec::with_capacity(count),
    };
    for t in 0..triangles {
        let o = partner[t];
        if o != FREE && (o as usize) < t {
            continue;
        }
        polygons.first_triangles.push(t as u32);
        if o == FREE {
            polygons.face_sizes.push(3);
            polygons.corners.extend_from_slice(&[3 * t as u32, 3 * t as u32 + 1, 3 * t as u32 + 2]);
        } else {
            polygons.face_sizes.push(4);
            let (h, g) = (join_edge[t] as usize, join_edge[o as usize] as usize);
            polygons
                .corners
                .extend([h, next3(next3(g)), next3(h), next3(next3(h))].map(|c| c as u32));
        }
    }
    Ok(polygons)
}

const FREE: u32 = u32::MAX;

/// The triangles of edge `e`'s first two half-edges (a candidate's two triangles).
fn ends(edges: &TriangleEdges, e: usize) -> (usize, usize) {
    (edges.h0[e] as usize / 3, edges.h1[e] as usize / 3)
}

/// Which triangles are joined: per triangle its partner (or [`FREE`]) and its half-edge on the
/// shared edge.
struct Matching {
    partner: Vec<u32>,
    join_edge: Vec<u32>,
    /// Triangles kept apart: they join nothing.
    apart: Vec<bool>,
}

/// The candidate edges around each triangle, in join-error order (compressed rows).
struct Candidates {
    start: Vec<u32>,
    around: Vec<u32>,
}

impl Candidates {
    fn new(edges: &TriangleEdges, candidates: &[usize], order: &[usize], triangles: usize) -> Self {
        let mut start = vec![0u32; triangles + 1];
        for &e in candidates {
            for t in <[usize; 2]>::from(ends(edges, e)) {
                start[t + 1] += 1;
            }
        }
        for t in 0..triangles {
            start[t + 1] += start[t];
        }
        let mut fill = start.clone();
        let mut around = vec![0u32; start[triangles] as usize];
        for &i in order {
            let e = candidates[i];
            for t in <[usize; 2]>::from(ends(edges, e)) {
                around[fill[t] as usize] = e as u32;
                fill[t] += 1;
            }
        }
        Candidates { start, around }
    }

    /// The candidate edges of triangle `t`.
    fn of(&self, t: usize) -> &[u32] {
        &self.around[self.start[t] as usize..self.start[t + 1] as usize]
    }
}

impl Matching {
    /// Whether triangle `t` may still be joined.
    fn is_free(&self, t: usize) -> bool {
        self.partner[t] == FREE && !self.apart[t]
    }

    /// Joins the two triangles of candidate edge `e` (whatever they were joined to before).
    fn pair(&mut self, edges: &TriangleEdges, e: usize) {
        let (h, g) = (edges.h0[e], edges.h1[e]);
        let (t1, t2) = ends(edges, e);
        (self.partner[t1], self.partner[t2]) = (t2 as u32, t1 as u32);
        (self.join_edge[t1], self.join_edge[t2]) = (h, g);
    }

    /// Joins triangles that the greedy pass left alone, where a short chain of re-pairings
    /// allows it (an augmenting path of the matching): free `a`, joined `b`–`c`, free `d` with
    /// candidate edges `a`–`b` and `c`–`d` become `a`–`b` and `c`–`d`, and so on along longer
    /// chains. Blender stops after the greedy pass. Next to thin, nearly triangular quads of a
    /// triangulated quad mesh its join error can prefer two triangles of neighbouring quads,
    /// which strands each one's true partner; this pass gives those quads back, so that a
    /// triangulated quad mesh is joined into its own quads. Chains are searched breadth first
    /// over at most `MAX_VISITED` triangles, candidates in join-error order, so the search
    /// stays local and repeatable.
    fn augment(&mut self, edges: &TriangleEdges, graph: &Candidates) {
        const MAX_VISITED: usize = 64;
        let triangles = self.partner.len();
        let (start, around) = (&graph.start, &graph.around);
        // Per triangle reached as a partner's partner: the edge that reached its partner and
        // the triangle it came from; `seen` marks the triangles of the current search.
        let mut via = vec![(FREE, FREE); triangles];
        let mut seen = vec![FREE; triangles];
        let mut queue = Vec::with_capacity(MAX_VISITED);
        for root in 0..triangles {
            if !self.is_free(root) || start[root] == start[root + 1] {
                continue;
            }
            let stamp = root as u32;
            seen[root] = stamp;
            queue.clear();
            queue.push(root);
            let mut next = 0;
            'search: while next < queue.len() && queue.len() < MAX_VISITED {
                let outer = queue[next];
                next += 1;
                for &e in &around[start[outer] as usize..start[outer + 1] as usize] {
                    let (t1, t2) = ends(edges, e as usize);
                    let inner = if t1 == outer { t2 } else { t1 };
                    if seen[inner] == stamp || self.apart[inner] {
                        continue;
                    }
                    seen[inner] = stamp;
                    let mate = self.partner[inner];
                    if mate == FREE {
                        self.flip(edges, outer, e as usize, root, &via);
                        break 'search;
                    }
                    if seen[mate as usize] != stamp {
                        seen[mate as usize] = stamp;
                        via[inner] = (e, outer as u32);
                        queue.push(mate as usize);
                    }
                }
            }
        }
    }

    /// Flips the chain found by [`Matching::augment`]: `outer` joins the free triangle across
    /// `e`, then each stranded partner back to `root` joins the triangle that reached it.
    fn flip(
        &mut self,
        edges: &TriangleEdges,
        mut outer: usize,
        mut e: usize,
        root: usize,
        via: &[(u32, u32)],
    ) {
        loop {
            let stranded = self.partner[outer];
            self.pair(edges, e);
            if outer == root {
                return;
            }
            let (edge, from) = via[stranded as usize];
            (e, outer) = (edge as usize, from as usize);
        }
    }
}

fn check_join(
    positions: &[f32],
    corners: &[u32],
    edges: &TriangleEdges,
    marks: &[u8],
    constraints: &JoinConstraints,
) -> Result<()> {
    let triangles = corners.len() / 3;
    let vertices = positions.len() / 3;
    let wrong = |what: String| Err(Error::mesh(format!("joining quads: {what}")));
    if !corners.len().is_multiple_of(3) || edges.edge_of.len() != corners.len() {
        return wrong(format!(
            "{} corners and edges of {} half-edges; give the edges of these triangles \
             (TriangleEdges::new(corners))",
            corners.len(),
            edges.edge_of.len()
        ));
    }
    if let Some(c) = corners.iter().position(|&v| v as usize >= vertices) {
        return wrong(format!(
            "corner {c} names vertex {}, but there are only {vertices}",
            corners[c]
        ));
    }
    if marks.len() != edges.len() {
        return wrong(format!(
            "{} edge marks for {} edges; give one per edge",
            marks.len(),
            edges.len()
        ));
    }
    let per = |len: Option<usize>, wanted: usize, what: &str| match len {
        Some(len) if len != wanted => wrong(format!(
            "{len} {what}, but there are {wanted}; give one per {}",
            &what[..what.len() - 1]
        )),
        _ => Ok(()),
    };
    per(constraints.groups.map(<[u32]>::len), triangles, "triangle groups")?;
    per(constraints.holes.map(<[bool]>::len), triangles, "triangle hole flags")?;
    per(constraints.corner_classes.map(<[u32]>::len), corners.len(), "corner classes")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn join(positions: &[f32], corners: &[u32], constraints: &JoinConstraints) -> Polygons {
        let edges = TriangleEdges::new(corners).unwrap();
        let marks = vec![SMOOTH; edges.len()];
        join_quads(positions, corners, &edges, &marks, constraints, QuadLimits::default()).unwrap()
    }

    const SQUARE: [f32; 12] = [0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.];

    #[test]
    fn two_triangles_of_a_unit_square_join_to_one_quad() {
        let quads = join(&SQUARE, &[0, 1, 2, 0, 2, 3], &Default::default());
        assert_eq!(quads.face_sizes, [4]);
        assert_eq!(quads.first_triangles, [0]);
        // (u, q, v, p): from the shared edge's corner in the first triangle, vertex 2.
        let vertices: Vec<u32> =
            quads.corners.iter().map(|&c| [0, 1, 2, 0, 2, 3][c as usize]).collect();
        assert_eq!(vertices, [2, 3, 0, 1]);
        assert_eq!(quad_error(&SQUARE, [0, 1, 2, 3]).unwrap(), 0.0);
        assert!(quad_error(&SQUARE, [0, 1, 2, 4]).is_err());
    }

    #[test]
    fn constraints_keep_the_triangles_apart() {
        let corners = [0, 1, 2, 0, 2, 3];
        let apart = |c: JoinConstraints| join(&SQUARE, &corners, &c).face_sizes == [3, 3];
        assert!(apart(JoinConstraints { groups: Some(&[0, 1]), ..Default::default() }));
        assert!(apart(JoinConstraints { holes: Some(&[false, true]), ..Default::default() }));
        // A seam at vertex 0: the two triangles' corners there are of different classes.
        assert!(apart(JoinConstraints {
            corner_classes: Some(&[0, 1, 2, 9, 2, 3]),
            ..Default::default()
        }));
        assert!(!apart(JoinConstraints {
            corner_classes: Some(&[0, 1, 2, 0, 2, 3]),
            ..Default::default()
        }));
        // A marked (sharp) diagonal.
        let edges = TriangleEdges::new(&corners).unwrap();
        let mut marks = vec![SMOOTH; edges.len()];
        marks[edges.find(0, 2).unwrap() as usize] = super::super::sharp::FOUND;
        let kept = join_quads(
            &SQUARE,
            &corners,
            &edges,
            &marks,
            &Default::default(),
            QuadLimits::default(),
        );
        assert_eq!(kept.unwrap().face_sizes, [3, 3]);
    }

    #[test]
    fn a_folded_or_concave_pair_stays_two_triangles() {
        // Folded by 90° along the diagonal 0-2.
        let folded = [0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 0., 1.];
        assert_eq!(join(&folded, &[0, 1, 2, 2, 3, 0], &Default::default()).face_sizes, [3, 3]);
        // Concave at vertex 2: the other diagonal's triangles face opposite ways.
        let concave = [0., 0., 0., 1., 0., 0., 0.3, 0.3, 0., 0., 1., 0.];
        assert_eq!(join(&concave, &[0, 1, 2, 0, 2, 3], &Default::default()).face_sizes, [3, 3]);
    }

    #[test]
    fn a_triangulated_grid_joins_back_to_its_quads() {
        // A 4 x 3 grid of unit squares, each split along alternating diagonals.
        let (nx, ny) = (4u32, 3u32);
        let positions: Vec<f32> = (0..=ny)
            .flat_map(|y| (0..=nx).map(move |x| [x as f32, y as f32, 0.]))
            .flatten()
            .collect();
        let at = |x: u32, y: u32| y * (nx + 1) + x;
        let mut corners = Vec::new();
        let mut squares = Vec::new();
        for y in 0..ny {
            for x in 0..nx {
                let [a, b, c, d] = [at(x, y), at(x + 1, y), at(x + 1, y + 1), at(x, y + 1)];
                if (x + y) % 2 == 0 {
                    corners.extend_from_slice(&[a, b, c, a, c, d]);
                } else {
                    corners.extend_from_slice(&[a, b, d, b, c, d]);
                }
                let mut square = vec![a, b, c, d];
                square.sort_unstable();
                squares.push(square);
            }
        }
        let quads = join(&positions, &corners, &Default::default());
        assert_eq!(quads.face_sizes, vec![4; (nx * ny) as usize]);
        for (f, quad) in quads.corners.chunks_exact(4).enumerate() {
            let mut vertices: Vec<u32> = quad.iter().map(|&c| corners[c as usize]).collect();
            vertices.sort_unstable();
            assert_eq!(vertices, squares[f], "quad {f}");
        }
    }

    #[test]
    fn arrays_that_do_not_fit_are_errors() {
        let corners = [0, 1, 2, 0, 2, 3];
        let edges = TriangleEdges::new(&corners).unwrap();
        let marks = vec![SMOOTH; edges.len()];
        let limits = QuadLimits::default();
        let groups = JoinConstraints { groups: Some(&[0]), ..Default::default() };
        let message =
            join_quads(&SQUARE, &corners, &edges, &marks, &groups, limits).unwrap_err().to_string();
        assert!(message.contains("1 triangle groups, but there are 2"), "{message}");
        assert!(join_quads(&SQUARE[..9], &corners, &edges, &marks, &Default::default(), limits)
            .is_err());
        assert!(join_quads(&SQUARE, &corners, &edges, &marks[1..], &Default::default(), limits)
            .is_err());
    }
}
