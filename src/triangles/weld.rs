//! Welding: the vertices of a triangle list that lie at one position become one vertex.
//!
//! Positions are compared by their bit patterns (with -0 equal to +0), so welding never merges
//! two points a renderer meant to keep apart; a distance `> 0` then also merges distinct
//! positions that close. Both passes sort instead of hashing: the first sorts the vertices by
//! their bits, the second the grid cells of the remaining positions.

use crate::error::{Error, Result};
use std::cmp::Ordering;

/// [`Welded::weld_of`] of an input vertex that no triangle uses.
pub const UNUSED: u32 = u32::MAX;

/// The welded triangles of a triangle list.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Welded {
    /// Per input vertex, its welded vertex, or [`UNUSED`] when no triangle uses it. Welded
    /// vertices are numbered in order of first use by the triangle list.
    pub weld_of: Vec<u32>,
    /// x, y, z per welded vertex: the position of its representative input vertex (the first of
    /// its bit-identical copies; with a distance, the cluster's centre), never averaged.
    pub positions: Vec<f32>,
    /// The input triangles kept, ascending: those whose three corners weld to three different
    /// vertices (the others have no area left).
    pub kept: Vec<u32>,
    /// The welded vertex of each corner of each kept triangle, three per triangle.
    pub corners: Vec<u32>,
}

/// Welds a triangle list: `positions` holds x, y, z per input vertex, `corners` three input
/// vertices per triangle. Bit-identical positions (-0 and +0 alike) become one vertex; with
/// `distance > 0` positions nearer than that join too: in input order, each position joins the
/// nearest earlier cluster centre within `distance` (ties: the centre met first, cells in
/// ascending x, y, z and the latest centre first within a cell), or starts a cluster of its own.
///
/// Errors when `positions` is not x, y, z triples of finite numbers, when `corners` is not
/// whole triangles of existing vertices, or when `distance` is negative or not finite. The
/// inputs are not modified.
///
/// ```
/// use subsurf::triangles::weld_triangles;
/// // Two triangles of a square, stored with six vertices; and one that collapses.
/// let p = [0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 0., 0., 1., 1., 0., 0., 1., 0.];
/// let welded = weld_triangles(&p, &[0, 1, 2, 3, 4, 5, 0, 3, 1], 0.0).unwrap();
/// assert_eq!(welded.weld_of, [0, 1, 2, 0, 2, 3]);
/// assert_eq!(welded.kept, [0, 1]); // triangle 2 has two corners at vertex 0
/// assert_eq!(welded.corners, [0, 1, 2, 0, 2, 3]);
/// ```
pub fn weld_triangles(positions: &[f32], corners: &[u32], distance: f64) -> Result<Welded> {
    check(positions, corners, distance)?;
    let n = positions.len() / 3;
    let mut representative = bit_representatives(positions);
    if distance > 0.0 {
        let centre = distance_representatives(positions, &representative, distance);
        // A bit-identical copy follows its representative into that one's cluster.
        representative = representative.iter().map(|&r| centre[r as usize]).collect();
    }

    let mut weld_of = vec![UNUSED; n];
    let mut id_of_representative = vec![UNUSED; n];
    let mut order = Vec::new();
    for &v in corners {
        if weld_of[v as usize] != UNUSED {
            continue;
        }
        let r = representative[v as usize] as usize;
        if id_of_representative[r] == UNUSED {
            id_of_representative[r] = order.len() as u32;
            order.push(r);
        }
        weld_of[v as usize] = id_of_representative[r];
    }
    let welded_positions =
        order.iter().flat_map(|&r| [0, 1, 2].map(|k| positions[3 * r + k])).collect();

    let mut kept = Vec::new();
    let mut kept_corners = Vec::new();
    for (t, triangle) in corners.chunks_exact(3).enumerate() {
        let [a, b, c] = [0, 1, 2].map(|j| weld_of[triangle[j] as usize]);
        if a != b && b != c && c != a {
            kept.push(t as u32);
            kept_corners.extend_from_slice(&[a, b, c]);
        }
    }
    Ok(Welded { weld_of, positions: welded_positions, kept, corners: kept_corners })
}

fn check(positions: &[f32], corners: &[u32], distance: f64) -> Result<()> {
    if !positions.len().is_multiple_of(3) {
        return Err(Error::mesh(format!(
            "positions has {} numbers, which is not a multiple of 3; give x, y, z per vertex",
            positions.len()
        )));
    }
    let n = positions.len() / 3;
    if n >= UNUSED as usize {
        return Err(Error::TooLarge(format!(
            "{n} vertices; welding numbers vertices with 32-bit indices, below {UNUSED}"
        )));
    }
    if let Some(i) = crate::mesh::first_unusable(positions) {
        let what = if positions[i].is_finite() { "too large" } else { "not finite" };
        return Err(Error::mesh(format!(
            "position of vertex {} is {what} ({}); {}",
            i / 3,
            positions[i],
            crate::mesh::unusable_because(positions[i], "coordinate")
        )));
    }
    if !corners.len().is_multiple_of(3) {
        return Err(Error::mesh(format!(
            "the triangle list has {} corners, which is not a multiple of 3; give three \
             vertices per triangle",
            corners.len()
        )));
    }
    if let Some(c) = corners.iter().position(|&v| v as usize >= n) {
        return Err(Error::mesh(format!(
            "corner {c} (triangle {}) names vertex {}, but there are only {n} vertices",
            c / 3,
            corners[c]
        )));
    }
    if !(distance >= 0.0 && distance.is_finite()) {
        return Err(Error::InvalidOption(format!(
            "weld distance must be a finite number >= 0 (0: only bit-identical positions), \
             got {distance}"
        )));
    }
    Ok(())
}

/// Per vertex, the first vertex with the same position bits (-0 as +0): a sort of
/// (x, y, z, index) keys, whose runs of equal positions start with their lowest index.
fn bit_representatives(positions: &[f32]) -> Vec<u32> {
    let bits = |x: f32| if x == 0.0 { 0 } else { x.to_bits() };
    let mut keys: Vec<u128> = positions
        .chunks_exact(3)
        .enumerate()
        .map(|(v, p)| {
            (u128::from(bits(p[0])) << 96)
                | (u128::from(bits(p[1])) << 64)
                | (u128::from(bits(p[2])) << 32)
                | v as u128
        })
        .collect();
    keys.sort_unstable();
    let mut representative = vec![0u32; keys.len()];
    let mut first = 0u32;
    for (i, &key) in keys.iter().enumerate() {
        if i == 0 || key >> 32 != keys[i - 1] >> 32 {
            first = key as u32;
        }
        representative[key as u32 as usize] = first;
    }
    representative
}

/// A grid cell: the floors of x, y, z over the cell size, -0 made +0 so that it orders as 0.
type Cell = [f64; 3];

fn cell_order(a: &Cell, b: &Cell) -> Ordering {
    a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])).then(a[2].total_cmp(&b[2]))
}

/// Per vertex (representatives of [`bit_representatives`] only), its cluster centre: in input
/// order, the nearest earlier centre within `distance`, or itself. The grid has cells of size
/// `distance`, numbered by sorting their coordinates; a position's candidates are the centres
/// in the 27 cells around its own, each cell's kept as a list with the latest first.
fn distance_representatives(positions: &[f32], representative: &[u32], distance: f64) -> Vec<u32> {
    const NONE: u32 = u32::MAX;
    let n = representative.len();
    let point = |v: usize| [0, 1, 2].map(|k| f64::from(positions[3 * v + k]));
    let cell_of_point = |p: [f64; 3]| p.map(|x| (x / distance).floor() + 0.0);
    let mut by_cell: Vec<(Cell, u32)> = (0..n)
        .filter(|&v| representative[v] as usize == v)
        .map(|v| (cell_of_point(point(v)), v as u32))
        .collect();
    by_cell.sort_unstable_by(|a, b| cell_order(&a.0, &b.0));
    let mut cells: Vec<Cell> = Vec::new();
    let mut cell_of = vec![NONE; n];
    for &(cell, v) in &by_cell {
        if cells.last().is_none_or(|last| cell_order(last, &cell) != Ordering::Equal) {
            cells.push(cell);
        }
        cell_of[v as usize] = (cells.len() - 1) as u32;
    }
    let m = cells.len();

    // The cells around cell i with x + dx, y + dy are a run of the sorted list from the first
    // one not below (x + dx, y + dy, z - 1). Adding the offsets keeps the list's order, so one
    // merge-like sweep per offset finds every run's start (no search per vertex); a rounding
    // that breaks the order (cells beyond 2^53) falls back to a binary search.
    const OFFSETS: [(f64, f64); 9] = [
        (-1., -1.),
        (-1., 0.),
        (-1., 1.),
        (0., -1.),
        (0., 0.),
        (0., 1.),
        (1., -1.),
        (1., 0.),
        (1., 1.),
    ];
    let mut run_start = vec![0u32; OFFSETS.len() * m];
    for (o, &(dx, dy)) in OFFSETS.iter().enumerate() {
        let mut j = 0;
        let mut previous: Option<Cell> = None;
        for (i, cell) in cells.iter().enumerate() {
            let low = [cell[0] + dx, cell[1] + dy, cell[2] - 1.0];
            if previous.is_some_and(|p| cell_order(&low, &p) == Ordering::Less) {
                j = cells.partition_point(|c| cell_order(c, &low) == Ordering::Less);
            }
            while j < m && cell_order(&cells[j], &low) == Ordering::Less {
                j += 1;
            }
            run_start[o * m + i] = j as u32;
            previous = Some(low);
        }
    }

    let mut head = vec![NONE; m];
    let mut next_in_cell = vec![NONE; n];
    let mut centre: Vec<u32> = (0..n as u32).collect();
    let limit = distance * distance;
    for v in (0..n).filter(|&v| cell_of[v] != NONE) {
        let p = point(v);
        let c = cell_of[v] as usize;
        let own = cells[c];
        let (mut best, mut best_distance) = (NONE, f64::INFINITY);
        for (o, &(dx, dy)) in OFFSETS.iter().enumerate() {
            let (x, y) = (own[0] + dx, own[1] + dy);
            let mut i = run_start[o * m + c] as usize;
            while i < m && cells[i][0] == x && cells[i][1] == y && cells[i][2] <= own[2] + 1.0 {
                let mut u = head[i];
                while u != NONE {
                    let q = point(u as usize);
                    let d = (q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2) + (q[2] - p[2]).powi(2);
                    if d <= limit && d < best_distance {
                        best = u;
                        best_distance = d;
                    }
                    u = next_in_cell[u as usize];
                }
                i += 1;
            }
        }
        if best != NONE {
            centre[v] = best;
        } else {
            next_in_cell[v] = head[c];
            head[c] = v as u32;
        }
    }
    centre
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube as 12 triangles with 4 vertices of its own per face (24 vertices).
    fn split_cube() -> (Vec<f32>, Vec<u32>) {
        let corner = |i: u32| [i & 1, (i >> 1) & 1, (i >> 2) & 1].map(|b| b as f32);
        let faces =
            [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
        let mut positions = Vec::new();
        let mut corners = Vec::new();
        for (f, face) in faces.iter().enumerate() {
            for &c in face {
                positions.extend_from_slice(&corner(c));
            }
            let b = 4 * f as u32;
            corners.extend_from_slice(&[b, b + 1, b + 2, b, b + 2, b + 3]);
        }
        (positions, corners)
    }

    #[test]
    fn a_cube_with_split_vertices_welds_to_eight() {
        let (positions, corners) = split_cube();
        let welded = weld_triangles(&positions, &corners, 0.0).unwrap();
        assert_eq!(welded.positions.len(), 8 * 3);
        assert_eq!(welded.kept, (0..12).collect::<Vec<_>>());
        // Every welded vertex sits where each of its copies does.
        for (v, &w) in welded.weld_of.iter().enumerate() {
            assert_eq!(
                positions[3 * v..3 * v + 3],
                welded.positions[3 * w as usize..3 * w as usize + 3]
            );
        }
        // Numbered by first use: the first triangle's corners are 0, 1, 2.
        assert_eq!(welded.corners[..3], [0, 1, 2]);
    }

    #[test]
    fn minus_zero_welds_with_zero_and_near_points_need_a_distance() {
        let positions = [0., 0., 0., -0., 0., 0., 1., 0., 0., 0., 1., 0., 1.0001, 0., 0.];
        let corners = [0, 2, 3, 1, 4, 3];
        let exact = weld_triangles(&positions, &corners, 0.0).unwrap();
        assert_eq!(exact.weld_of, [0, 0, 1, 2, 3]);
        let near = weld_triangles(&positions, &corners, 0.001).unwrap();
        assert_eq!(near.weld_of, [0, 0, 1, 2, 1]);
        assert_eq!(near.positions[3..6], [1., 0., 0.]); // the centre's, not an average
        assert_eq!(near.kept, [0, 1]);
    }

    #[test]
    fn a_point_joins_the_nearest_earlier_centre() {
        // Centres at x = 0 and x = 1 (more than 0.6 apart); 0.55 is within 0.6 of both, nearer 1.
        let positions = [0., 0., 0., 1., 0., 0., 0.55, 0., 0., 5., 5., 5.];
        let welded = weld_triangles(&positions, &[0, 1, 3, 2, 3, 1], 0.6).unwrap();
        assert_eq!(welded.weld_of, [0, 1, 1, 2]);
        // Clusters do not chain: 0.55 joined 1, so a point 0.5 from 0.55 but 0.95 from 1 and
        // 0.05 from 0 joins 0.
        let positions = [0., 0., 0., 1., 0., 0., 0.55, 0., 0., 0.05, 0., 0., 5., 5., 5.];
        let welded = weld_triangles(&positions, &[0, 1, 4, 2, 3, 4], 0.6).unwrap();
        assert_eq!(welded.weld_of, [0, 1, 1, 0, 2]);
    }

    #[test]
    fn unused_vertices_and_degenerate_triangles() {
        let positions = [0., 0., 0., 1., 0., 0., 0., 1., 0., 9., 9., 9.];
        let welded = weld_triangles(&positions, &[0, 1, 2, 0, 0, 1], 0.0).unwrap();
        assert_eq!(welded.weld_of, [0, 1, 2, UNUSED]);
        assert_eq!(welded.kept, [0]);
        let none = weld_triangles(&positions, &[1, 1, 2], 0.0).unwrap();
        assert!(none.kept.is_empty() && none.corners.is_empty());
    }

    #[test]
    fn the_grid_finds_what_a_scan_of_every_centre_finds() {
        // Random points (no exact ties), some negative, some on a coarse lattice so that many
        // share cells; the rule checked by brute force: the nearest earlier centre within d.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut random = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let n = 2000;
        let positions: Vec<f32> = (0..3 * n).map(|_| (random() * 4.0 - 2.0) as f32).collect();
        let corners: Vec<u32> = (0..n as u32).flat_map(|v| [v, v, v]).collect();
        for distance in [0.05, 0.2, 0.7] {
            let welded = weld_triangles(&positions, &corners, distance).unwrap();
            let point = |v: usize| [0, 1, 2].map(|k| f64::from(positions[3 * v + k]));
            let mut centres: Vec<usize> = Vec::new();
            let mut cluster = vec![0usize; n];
            for v in 0..n {
                let p = point(v);
                let nearest = centres
                    .iter()
                    .map(|&c| {
                        let q = point(c);
                        ((0..3).map(|k| (q[k] - p[k]).powi(2)).sum::<f64>(), c)
                    })
                    .filter(|&(d, _)| d <= distance * distance)
                    .min_by(|a, b| a.0.total_cmp(&b.0));
                cluster[v] = match nearest {
                    Some((_, c)) => cluster[c],
                    None => {
                        centres.push(v);
                        v
                    }
                };
            }
            // Same partition: welded ids are numbered by first use, clusters by centre.
            for u in 0..n {
                for v in [u / 2, (u * 7) % n, (u + 1) % n] {
                    assert_eq!(
                        welded.weld_of[u] == welded.weld_of[v],
                        cluster[u] == cluster[v],
                        "distance {distance}, vertices {u} and {v}"
                    );
                }
            }
        }
    }

    #[test]
    fn bad_input_is_an_error_that_says_where() {
        let p = [0., 0., 0., 1., 0., 0., 0., 1., 0.];
        let message = |r: Result<Welded>| r.unwrap_err().to_string();
        assert!(message(weld_triangles(&p[..8], &[0, 1, 2], 0.0)).contains("multiple of 3"));
        assert!(message(weld_triangles(&p, &[0, 1], 0.0)).contains("2 corners"));
        assert!(message(weld_triangles(&p, &[0, 1, 3], 0.0))
            .contains("corner 2 (triangle 0) names vertex 3"));
        assert!(message(weld_triangles(&[0., f32::NAN, 0.], &[0, 0, 0], 0.0))
            .contains("vertex 0 is not finite"));
        assert!(message(weld_triangles(&p, &[0, 1, 2], -1.0)).contains(">= 0"));
        assert!(message(weld_triangles(&p, &[0, 1, 2], f64::NAN)).contains(">= 0"));
    }
}
