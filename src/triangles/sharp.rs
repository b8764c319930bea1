//! Sharp edges of a welded triangle list: where the surface folds by more than an angle, where
//! the input split its normals (a flat-shaded or hard-edged model), and the caller's creases.
//!
//! Each function takes the marks of the edges (one byte per edge of a [`TriangleEdges`]) and
//! returns them with its own added; the values say who made an edge sharp, which the later
//! steps read: [`join_quads`](super::join_quads) joins across none of them,
//! [`smoothing_fans`](super::smoothing_fans) splits at the infinitely sharp ones.

use super::edges::{TriangleEdges, NO_HALF_EDGE};
use super::next3;
use crate::error::{Error, Result};
use glam::DVec3;

/// Not sharp.
pub const SMOOTH: u8 = 0;
/// Found sharp here (an angle or a normal split): an infinitely sharp crease.
pub const FOUND: u8 = 1;
/// A crease of the caller's, semi-sharp (sharpness below 10).
pub const TAGGED: u8 = 2;
/// A crease of the caller's, infinitely sharp (sharpness 10 or more).
pub const TAGGED_SHARP: u8 = 3;

/// Whether a mark makes the surface's normals split along the edge.
pub fn splits_normals(mark: u8) -> bool {
    mark == FOUND || mark == TAGGED_SHARP
}

/// Marks [`FOUND`] every edge between two consistently wound triangles whose normals (from
/// [`triangle_normals`](super::triangle_normals)) differ by more than `angle` radians: the
/// dihedral angle test. Triangles without area never make an edge sharp. Errors when `normals`
/// (one per triangle) or `marks` (one per edge) do not fit the edges.
pub fn crease_angle_edges(
    edges: &TriangleEdges,
    normals: &[DVec3],
    angle: f64,
    marks: &mut [u8],
) -> Result<()> {
    edges.check_marks(marks, "crease angle")?;
    if normals.len() * 3 != edges.num_half_edges() {
        return Err(Error::mesh(format!(
            "crease angle: {} triangle normals for {} triangles; give one per triangle",
            normals.len(),
            edges.num_half_edges() / 3
        )));
    }
    let cos_limit = angle.cos();
    for (e, mark) in marks.iter_mut().enumerate() {
        let Some((t0, t1)) = edges.triangles(e) else { continue };
        let (n0, n1) = (normals[t0], normals[t1]);
        if n0.dot(n1) < cos_limit && n0 != DVec3::ZERO && n1 != DVec3::ZERO {
            *mark = FOUND;
        }
    }
    Ok(())
}

/// Two normals of one welded vertex are one (not split) within about 1 degree.
fn normal_split_cos() -> f64 {
    1f64.to_radians().cos()
}

/// Marks [`FOUND`] every edge between two consistently wound triangles whose input vertices
/// differ at both ends and carry normals more than about 1° apart at both ends: where the input
/// split its vertices to give each side its own normal. `input_corners` is the input vertex of
/// each triangle corner (the welded corners' copies), `normals` x, y, z per input vertex.
/// Errors when the arrays do not fit the edges or each other.
pub fn normal_split_edges(
    edges: &TriangleEdges,
    input_corners: &[u32],
    normals: &[f32],
    marks: &mut [u8],
) -> Result<()> {
    edges.check_marks(marks, "normal splits")?;
    if input_corners.len() != edges.num_half_edges() {
        return Err(Error::mesh(format!(
            "normal splits: {} input corners for {} triangle corners; give one per corner",
            input_corners.len(),
            edges.num_half_edges()
        )));
    }
    if let Some(k) = input_corners.iter().position(|&v| 3 * v as usize + 2 >= normals.len()) {
        return Err(Error::InvalidAttribute(format!(
            "normals: corner {k} is input vertex {}, but the normals (x, y, z per vertex) cover \
             only {} vertices; give a normal for every vertex",
            input_corners[k],
            normals.len() / 3
        )));
    }
    let cos_limit = normal_split_cos();
    let normal = |v: u32| super::edges::point(normals, v);
    let differ = |u: u32, v: u32| {
        if u == v {
            return false;
        }
        let (nu, nv) = (normal(u), normal(v));
        // Not `<`: a NaN normal differs from every other.
        let within = nu.dot(nv) >= cos_limit * nu.length() * nv.length();
        !within
    };
    for (e, mark) in marks.iter_mut().enumerate() {
        if !edges.opposite[e] || edges.h1[e] == NO_HALF_EDGE {
            continue;
        }
        // h0 runs a -> b, h1 runs b -> a.
        let (h0, h1) = (edges.h0[e] as usize, edges.h1[e] as usize);
        let (a0, b0) = (input_corners[h0], input_corners[next3(h0)]);
        let (b1, a1) = (input_corners[h1], input_corners[next3(h1)]);
        if differ(a0, a1) && differ(b0, b1) {
            *mark = FOUND;
        }
    }
    Ok(())
}

/// Marks the caller's creases, given as pairs of (welded) vertices with a sharpness each:
/// [`TAGGED_SHARP`] from sharpness 10 on, [`TAGGED`] below; a later pair overrides an earlier
/// one on the same edge. Pairs that are no edge of the triangles are left out. Errors when the
/// sharpness values do not fit the pairs or `marks` the edges.
pub fn tagged_edges(
    edges: &TriangleEdges,
    pairs: &[u32],
    sharpness: &[f32],
    marks: &mut [u8],
) -> Result<()> {
    if !pairs.len().is_multiple_of(2) || sharpness.len() != pairs.len() / 2 {
        return Err(Error::InvalidTag(format!(
            "creases: {} vertices and {} sharpness values; give vertex pairs and one sharpness \
             per pair",
            pairs.len(),
            sharpness.len()
        )));
    }
    edges.check_marks(marks, "creases")?;
    for (pair, &s) in pairs.chunks_exact(2).zip(sharpness) {
        if let Some(e) = edges.find(pair[0], pair[1]) {
            marks[e as usize] = if s >= 10.0 { TAGGED_SHARP } else { TAGGED };
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::triangles::{triangle_normals, weld_triangles};

    /// A unit cube, 12 triangles over 8 shared vertices, wound outwards.
    pub(crate) fn cube() -> (Vec<f32>, Vec<u32>) {
        let positions =
            (0..8u32).flat_map(|i| [i & 1, (i >> 1) & 1, (i >> 2) & 1].map(|b| b as f32)).collect();
        let quads =
            [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
        let corners = quads.iter().flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]]).collect();
        (positions, corners)
    }

    #[test]
    fn the_dihedral_angle_of_a_cube_edge_is_ninety_degrees() {
        let (positions, corners) = cube();
        let edges = TriangleEdges::new(&corners).unwrap();
        let normals = triangle_normals(&positions, &corners).unwrap();
        assert_eq!(edges.len(), 18); // 12 cube edges and 6 diagonals
        let sharp_at = |degrees: f64| {
            let mut marks = vec![SMOOTH; edges.len()];
            crease_angle_edges(&edges, &normals, degrees.to_radians(), &mut marks).unwrap();
            marks.iter().filter(|&&m| m == FOUND).count()
        };
        assert_eq!(sharp_at(89.0), 12);
        assert_eq!(sharp_at(91.0), 0);
        assert_eq!(sharp_at(0.0), 12); // the diagonals are flat
        let mut marks = vec![SMOOTH; edges.len()];
        assert!(crease_angle_edges(&edges, &normals[1..], 0.5, &mut marks).is_err());
        assert!(crease_angle_edges(&edges, &normals, 0.5, &mut marks[1..]).is_err());
    }

    #[test]
    fn split_normals_make_the_cube_edges_sharp() {
        // Flat-shaded: four vertices per face, each with the face's normal.
        let (cube_positions, cube_corners) = cube();
        let (mut positions, mut corners, mut normals) = (Vec::new(), Vec::new(), Vec::new());
        for tri in cube_corners.chunks_exact(3) {
            let n = triangle_normals(&cube_positions, tri).unwrap()[0];
            for &v in tri {
                corners.push((positions.len() / 3) as u32);
                positions.extend_from_slice(&cube_positions[3 * v as usize..3 * v as usize + 3]);
                normals.extend_from_slice(&[n.x as f32, n.y as f32, n.z as f32]);
            }
        }
        let welded = weld_triangles(&positions, &corners, 0.0).unwrap();
        let edges = TriangleEdges::new(&welded.corners).unwrap();
        let mut marks = vec![SMOOTH; edges.len()];
        normal_split_edges(&edges, &corners, &normals, &mut marks).unwrap();
        assert_eq!(marks.iter().filter(|&&m| m == FOUND).count(), 12);
        assert!(normal_split_edges(&edges, &corners, &normals[..9], &mut marks).is_err());
    }

    #[test]
    fn tagged_creases_take_the_last_sharpness() {
        let (_, corners) = cube();
        let edges = TriangleEdges::new(&corners).unwrap();
        let mut marks = vec![SMOOTH; edges.len()];
        tagged_edges(&edges, &[0, 1, 1, 0, 0, 7, 2, 3], &[10.0, 2.0, 10.0, 10.0], &mut marks)
            .unwrap();
        assert_eq!(marks[edges.find(0, 1).unwrap() as usize], TAGGED);
        assert_eq!(marks[edges.find(2, 3).unwrap() as usize], TAGGED_SHARP);
        assert_eq!(marks.iter().filter(|&&m| m != SMOOTH).count(), 2); // 0-7 is no edge
        assert!(tagged_edges(&edges, &[0, 1, 2], &[1.0], &mut marks).is_err());
    }
}
