//! The edges of a list of triangles over shared vertices, and the triangles' normals.
//!
//! Corner `h = 3 t + j` of triangle `t` is also the half-edge from that corner to the next one.
//! Edges are found by sorting the half-edges by their vertex pair, so a list of any size, with
//! edges used by any number of triangles, takes no hash map.

use super::next3;
use crate::error::{Error, Result};
use glam::DVec3;

/// [`TriangleEdges::h1`] of an edge that only one half-edge uses.
pub const NO_HALF_EDGE: u32 = u32::MAX;

/// The edges of a triangle list, numbered in the order the half-edges first meet them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleEdges {
    /// The lower vertex of each edge.
    pub(crate) a: Vec<u32>,
    /// The higher vertex of each edge.
    pub(crate) b: Vec<u32>,
    /// How many half-edges (triangle sides) lie on each edge.
    pub(crate) uses: Vec<u32>,
    /// The first half-edge on each edge.
    pub(crate) h0: Vec<u32>,
    /// The second half-edge on each edge, or [`NO_HALF_EDGE`].
    pub(crate) h1: Vec<u32>,
    /// The edge of each half-edge.
    pub(crate) edge_of: Vec<u32>,
    /// Whether each edge has exactly two half-edges running opposite ways: an edge between two
    /// consistently wound triangles of a manifold surface.
    pub(crate) opposite: Vec<bool>,
    /// (a, b) of each edge as `a << 32 | b`, ascending, with its edge: for [`Self::find`].
    by_pair: Vec<(u64, u32)>,
}

impl TriangleEdges {
    /// The edges of the triangles `corners` (three vertices per triangle). Errors when the
    /// corner count is not a multiple of 3 or does not fit 32-bit half-edge numbers.
    pub fn new(corners: &[u32]) -> Result<TriangleEdges> {
        if !corners.len().is_multiple_of(3) {
            return Err(Error::mesh(format!(
                "the triangle list has {} corners, which is not a multiple of 3; give three \
                 vertices per triangle",
                corners.len()
            )));
        }
        if corners.len() >= NO_HALF_EDGE as usize {
            return Err(Error::TooLarge(format!(
                "{} triangle corners; edges are numbered with 32-bit indices",
                corners.len()
            )));
        }
        let pair = |h: usize| {
            let (u, v) = (corners[h], corners[next3(h)]);
            (u64::from(u.min(v)) << 32) | u64::from(u.max(v))
        };
        let mut sorted: Vec<(u64, u32)> = (0..corners.len()).map(|h| (pair(h), h as u32)).collect();
        sorted.sort_unstable();

        // Each run of one pair is an edge; its lowest half-edge comes first in the run and names
        // it until the edges are numbered by first use.
        let mut leader = vec![0u32; corners.len()];
        let mut first = 0;
        for (i, &(key, h)) in sorted.iter().enumerate() {
            if i == 0 || key != sorted[i - 1].0 {
                first = h;
            }
            leader[h as usize] = first;
        }
        let mut edge_of = vec![0u32; corners.len()];
        let mut count = 0u32;
        for h in 0..corners.len() {
            let l = leader[h] as usize;
            if l == h {
                edge_of[h] = count;
                count += 1;
            } else {
                edge_of[h] = edge_of[l];
            }
        }
        let edges = count as usize;
        let (mut a, mut b, mut uses) = (vec![0; edges], vec![0; edges], vec![0; edges]);
        let (mut h0, mut h1) = (vec![NO_HALF_EDGE; edges], vec![NO_HALF_EDGE; edges]);
        let mut by_pair = Vec::with_capacity(edges);
        for &(key, h) in &sorted {
            let e = edge_of[h as usize] as usize;
            match uses[e] {
                0 => {
                    h0[e] = h;
                    (a[e], b[e]) = ((key >> 32) as u32, key as u32);
                    by_pair.push((key, e as u32));
                }
                1 => h1[e] = h,
                _ => {}
            }
            uses[e] += 1;
        }
        let opposite = (0..edges)
            .map(|e| uses[e] == 2 && corners[h0[e] as usize] == corners[next3(h1[e] as usize)])
            .collect();
        Ok(TriangleEdges { a, b, uses, h0, h1, edge_of, opposite, by_pair })
    }

    /// The lower vertex of each edge.
    pub fn a(&self) -> &[u32] {
        &self.a
    }

    /// The higher vertex of each edge.
    pub fn b(&self) -> &[u32] {
        &self.b
    }

    /// How many half-edges (triangle sides) lie on each edge.
    pub fn uses(&self) -> &[u32] {
        &self.uses
    }

    /// The first half-edge (triangle corner `3 t + j`, from that corner to the next) on each
    /// edge.
    pub fn h0(&self) -> &[u32] {
        &self.h0
    }

    /// The second half-edge on each edge, or [`NO_HALF_EDGE`].
    pub fn h1(&self) -> &[u32] {
        &self.h1
    }

    /// The edge of each half-edge.
    pub fn edge_of(&self) -> &[u32] {
        &self.edge_of
    }

    /// Whether each edge lies between two consistently wound triangles (exactly two half-edges,
    /// running opposite ways).
    pub fn opposite(&self) -> &[bool] {
        &self.opposite
    }

    /// The number of half-edges (triangle corners) the edges were found from.
    pub fn num_half_edges(&self) -> usize {
        self.edge_of.len()
    }

    /// Errors unless `marks` has one entry per edge.
    pub(crate) fn check_marks(&self, marks: &[u8], what: &str) -> Result<()> {
        if marks.len() != self.len() {
            return Err(Error::mesh(format!(
                "{what}: {} edge marks for {} edges; give one per edge",
                marks.len(),
                self.len()
            )));
        }
        Ok(())
    }

    /// The number of edges.
    pub fn len(&self) -> usize {
        self.a.len()
    }

    /// Whether there are no edges (no triangles).
    pub fn is_empty(&self) -> bool {
        self.a.is_empty()
    }

    /// The edge between vertices `x` and `y` (either order), if a triangle has it.
    pub fn find(&self, x: u32, y: u32) -> Option<u32> {
        let key = (u64::from(x.min(y)) << 32) | u64::from(x.max(y));
        self.by_pair.binary_search_by_key(&key, |&(k, _)| k).ok().map(|i| self.by_pair[i].1)
    }

    /// The two triangles of edge `e` when it is [`Self::opposite`]: the first half-edge's, then
    /// the second's.
    pub fn triangles(&self, e: usize) -> Option<(usize, usize)> {
        self.opposite[e].then(|| (self.h0[e] as usize / 3, self.h1[e] as usize / 3))
    }
}

/// A point of `positions` (x, y, z per vertex), widened.
#[inline]
pub(crate) fn point(positions: &[f32], v: u32) -> DVec3 {
    let i = 3 * v as usize;
    DVec3::new(positions[i].into(), positions[i + 1].into(), positions[i + 2].into())
}

/// (j - i) × (k - i): twice the area vector of triangle (i, j, k).
#[inline]
pub(crate) fn cross(positions: &[f32], i: u32, j: u32, k: u32) -> DVec3 {
    let p = point(positions, i);
    (point(positions, j) - p).cross(point(positions, k) - p)
}

/// The unit normal of triangle (i, j, k), or `None` when it has no area.
#[inline]
pub(crate) fn unit_normal(positions: &[f32], i: u32, j: u32, k: u32) -> Option<DVec3> {
    let n = cross(positions, i, j, k);
    let length = n.length();
    (length > 0.0).then(|| n / length)
}

/// The area of triangle (i, j, k).
#[inline]
pub(crate) fn triangle_area(positions: &[f32], i: u32, j: u32, k: u32) -> f64 {
    0.5 * cross(positions, i, j, k).length()
}

/// The angle between two unit vectors, in radians; π when either is missing.
#[inline]
pub(crate) fn angle_between(n: Option<DVec3>, m: Option<DVec3>) -> f64 {
    match (n, m) {
        (Some(n), Some(m)) => n.dot(m).clamp(-1.0, 1.0).acos(),
        _ => std::f64::consts::PI,
    }
}

/// The unit normal of each triangle of `corners` over `positions` (x, y, z per vertex);
/// (0, 0, 0) for a triangle without area. Errors when a corner names no vertex of
/// `positions` or the corners are not whole triangles.
pub fn triangle_normals(positions: &[f32], corners: &[u32]) -> Result<Vec<DVec3>> {
    check_corners(positions, corners, "triangle normals")?;
    Ok(corners
        .chunks_exact(3)
        .map(|t| unit_normal(positions, t[0], t[1], t[2]).unwrap_or(DVec3::ZERO))
        .collect())
}

/// Errors unless `corners` are whole triangles of vertices of `positions` (x, y, z each).
pub(crate) fn check_corners(positions: &[f32], corners: &[u32], what: &str) -> Result<()> {
    if !positions.len().is_multiple_of(3) || !corners.len().is_multiple_of(3) {
        return Err(Error::mesh(format!(
            "{what}: {} position coordinates and {} corners; give x, y, z per vertex and three \
             corners per triangle",
            positions.len(),
            corners.len()
        )));
    }
    let vertices = positions.len() / 3;
    if let Some(c) = corners.iter().position(|&v| v as usize >= vertices) {
        return Err(Error::mesh(format!(
            "{what}: corner {c} names vertex {}, but there are only {vertices}",
            corners[c]
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_triangles_of_a_square() {
        // (0, 1, 2) and (0, 2, 3): the diagonal 0-2 is shared, running opposite ways.
        let edges = TriangleEdges::new(&[0, 1, 2, 0, 2, 3]).unwrap();
        assert_eq!(edges.len(), 5);
        assert_eq!(edges.a, [0, 1, 0, 2, 0]);
        assert_eq!(edges.b, [1, 2, 2, 3, 3]);
        assert_eq!(edges.uses, [1, 1, 2, 1, 1]);
        assert_eq!((edges.h0[2], edges.h1[2]), (2, 3));
        assert_eq!(edges.edge_of, [0, 1, 2, 2, 3, 4]);
        assert_eq!(edges.opposite, [false, false, true, false, false]);
        assert_eq!(edges.find(2, 0), Some(2));
        assert_eq!(edges.find(1, 3), None);
        assert_eq!(edges.triangles(2), Some((0, 1)));
    }

    #[test]
    fn inconsistent_winding_and_three_triangles_on_an_edge_are_not_opposite() {
        let flipped = TriangleEdges::new(&[0, 1, 2, 0, 3, 2]).unwrap();
        assert_eq!(flipped.uses[flipped.find(0, 2).unwrap() as usize], 2);
        assert!(!flipped.opposite[flipped.find(0, 2).unwrap() as usize]);
        let fin = TriangleEdges::new(&[0, 1, 2, 1, 0, 3, 0, 1, 4]).unwrap();
        let e = fin.find(0, 1).unwrap() as usize;
        assert_eq!((fin.uses[e], fin.h0[e], fin.h1[e]), (3, 0, 3));
        assert!(!fin.opposite[e]);
    }

    #[test]
    fn normals_of_a_unit_square_and_a_degenerate_triangle() {
        let p = [0., 0., 0., 1., 0., 0., 1., 1., 0., 2., 0., 0.];
        let normals = triangle_normals(&p, &[0, 1, 2, 0, 1, 3]).unwrap();
        assert_eq!(normals, [DVec3::Z, DVec3::ZERO]);
        assert_eq!(triangle_area(&p, 0, 1, 2), 0.5);
        assert!(TriangleEdges::new(&[0, 1]).is_err());
        assert!(triangle_normals(&p, &[0, 1, 4]).is_err());
    }
}
