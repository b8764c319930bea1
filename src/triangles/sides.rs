//! The sides of sharp edges: which triangle corners around a vertex share one normal
//! (a smoothing fan, as a glTF exporter's split vertices would have it), and, after
//! subdivision, one normal per side for the refined vertices on those edges.
//!
//! `subsurf/three` carries the fans through subdivision as a face-varying channel whose values
//! are the fans, so that a refined vertex on a sharp edge sees a different value on each side;
//! [`side_normals`] then gives each side the normal of its own faces.

use super::edges::TriangleEdges;
use super::next3;
use super::sharp::splits_normals;
use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use glam::DVec3;

/// Per triangle corner (`3 t + j`), the lowest corner of its smoothing fan: the corners around
/// a vertex joined across every edge between two consistently wound triangles that `marks`
/// (one per edge) does not make split the normals (see [`splits_normals`]). Errors when the
/// marks do not fit the edges.
pub fn smoothing_fans(edges: &TriangleEdges, marks: &[u8]) -> Result<Vec<u32>> {
    if marks.len() != edges.len() {
        return Err(Error::mesh(format!(
            "smoothing fans: {} edge marks for {} edges; give one per edge",
            marks.len(),
            edges.len()
        )));
    }
    let mut parent: Vec<u32> = (0..edges.edge_of.len() as u32).collect();
    fn find(parent: &mut [u32], mut c: u32) -> u32 {
        while parent[c as usize] != c {
            parent[c as usize] = parent[parent[c as usize] as usize];
            c = parent[c as usize];
        }
        c
    }
    // Linking the higher root under the lower keeps every root its set's lowest corner.
    let mut union = |x: u32, y: u32| {
        let (x, y) = (find(&mut parent, x), find(&mut parent, y));
        if x != y {
            parent[x.max(y) as usize] = x.min(y);
        }
    };
    for (e, &mark) in marks.iter().enumerate() {
        if splits_normals(mark) || !edges.opposite[e] {
            continue;
        }
        // h runs a -> b (its corner is at a), g runs b -> a (its corner is at b).
        let (h, g) = (edges.h0[e] as usize, edges.h1[e] as usize);
        union(h as u32, next3(g) as u32);
        union(next3(h) as u32, g as u32);
    }
    Ok((0..parent.len() as u32).map(|c| find(&mut parent, c)).collect())
}

/// Normals with sharp edges honoured: `normals` (x, y, z per drawn vertex, as smooth shading
/// would have them) with each drawn vertex on a sharp edge given the normalised sum of the area
/// vectors of its side's faces.
///
/// `mesh` is the refined mesh; `corner_sides` gives each of its face corners a side (a value
/// below `side_count`; corners of one vertex on one side share it, a vertex on a sharp edge has
/// more than one), and `drawn_corners` each face corner's drawn vertex (a vertex split per
/// side, as [`crate::drawable::to_drawable`] makes them). A vertex whose corners all see one
/// side keeps its normal. Errors when the arrays do not fit each other; `normals` is not
/// modified.
pub fn side_normals(
    mesh: &PolyMesh,
    corner_sides: &[u32],
    side_count: usize,
    drawn_corners: &[u32],
    normals: &[f32],
) -> Result<Vec<f32>> {
    mesh.check_arrays()?;
    let corners = mesh.indices.len();
    let wrong = |what: String| Err(Error::mesh(format!("side normals: {what}")));
    if corner_sides.len() != corners || drawn_corners.len() != corners {
        return wrong(format!(
            "{} corner sides and {} drawn corners for {corners} face corners; give one each per \
             corner",
            corner_sides.len(),
            drawn_corners.len()
        ));
    }
    if let Some(k) = corner_sides.iter().position(|&s| s as usize >= side_count) {
        return wrong(format!(
            "corner {k} has side {}, but there are {side_count}",
            corner_sides[k]
        ));
    }
    let drawn = normals.len() / 3;
    if !normals.len().is_multiple_of(3) {
        return wrong(format!(
            "{} normal coordinates; give x, y, z per drawn vertex",
            normals.len()
        ));
    }
    if let Some(k) = drawn_corners.iter().position(|&d| d as usize >= drawn) {
        return wrong(format!(
            "corner {k} is drawn vertex {}, but there are normals for {drawn}",
            drawn_corners[k]
        ));
    }

    // Vertices whose corners see more than one side.
    const NONE: u32 = u32::MAX;
    let mut first_side = vec![NONE; mesh.num_vertices()];
    let mut several = vec![false; mesh.num_vertices()];
    for (&v, &s) in mesh.indices.iter().zip(corner_sides) {
        let first = &mut first_side[v as usize];
        if *first == NONE {
            *first = s;
        } else if *first != s {
            several[v as usize] = true;
        }
    }
    let mut drawn_side = vec![0u32; drawn];
    for (&d, &s) in drawn_corners.iter().zip(corner_sides) {
        drawn_side[d as usize] = s;
    }

    let mut sums = vec![DVec3::ZERO; side_count];
    let mut start = 0;
    for &n in &mesh.face_sizes {
        let face = &mesh.indices[start..start + n as usize];
        let area = crate::mesh::area_vector(&mesh.positions, face);
        for (k, &v) in face.iter().enumerate() {
            if several[v as usize] {
                sums[corner_sides[start + k] as usize] += area;
            }
        }
        start += n as usize;
    }
    let mut out = normals.to_vec();
    for (normal, &s) in out.chunks_exact_mut(3).zip(&drawn_side) {
        let sum = sums[s as usize];
        let length = sum.length();
        if length > 0.0 {
            let unit = sum / length;
            normal.copy_from_slice(&[unit.x as f32, unit.y as f32, unit.z as f32]);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::triangles::sharp::{FOUND, SMOOTH, TAGGED, TAGGED_SHARP};

    #[test]
    fn fans_split_at_sharp_edges_only() {
        // A square as two triangles (0, 1, 2) and (0, 2, 3): corners 0 and 3 are at vertex 0,
        // corners 2 and 4 at vertex 2.
        let edges = TriangleEdges::new(&[0, 1, 2, 0, 2, 3]).unwrap();
        let diagonal = edges.find(0, 2).unwrap() as usize;
        let fans = |mark: u8| {
            let mut marks = vec![SMOOTH; edges.len()];
            marks[diagonal] = mark;
            smoothing_fans(&edges, &marks).unwrap()
        };
        assert_eq!(fans(SMOOTH), [0, 1, 2, 0, 2, 5]);
        assert_eq!(fans(TAGGED), [0, 1, 2, 0, 2, 5]); // semi-sharp: normals stay smooth
        assert_eq!(fans(FOUND), [0, 1, 2, 3, 4, 5]);
        assert_eq!(fans(TAGGED_SHARP), [0, 1, 2, 3, 4, 5]);
        assert!(smoothing_fans(&edges, &[]).is_err());
    }

    #[test]
    fn each_side_of_a_fold_gets_its_faces_normal() {
        // Two unit squares folded by 90° along the edge 1-4: a floor (z = 0) and a wall (x = 1).
        let mesh = PolyMesh {
            positions: vec![0., 0., 0., 1., 0., 0., 1., 0., 1., 0., 1., 0., 1., 1., 0., 1., 1., 1.],
            indices: vec![0, 1, 4, 3, 1, 2, 5, 4],
            face_sizes: vec![4, 4],
        };
        // Sides: the floor's corners see 0..4, the wall's 4..8, but at the vertices off the fold
        // (0, 3, 2, 5) one side each; vertices 1 and 4 see two. Drawn vertices: one per corner.
        let corner_sides = [0, 1, 2, 3, 4, 5, 6, 7];
        let drawn: Vec<u32> = (0..8).collect();
        let smooth = vec![9.0; 24];
        let normals = side_normals(&mesh, &corner_sides, 8, &drawn, &smooth).unwrap();
        let floor = [0., 0., 1.];
        let wall = [-1., 0., 0.];
        assert_eq!(normals[3..6], floor); // vertex 1, floor side
        assert_eq!(normals[6..9], floor); // vertex 4, floor side
        assert_eq!(normals[12..15], wall); // vertex 1, wall side
        assert_eq!(normals[21..24], wall); // vertex 4, wall side
        assert_eq!(normals[0..3], [9.0; 3]); // vertex 0: one side, its normal stays
        assert!(side_normals(&mesh, &corner_sides, 7, &drawn, &smooth).is_err());
        assert!(side_normals(&mesh, &corner_sides, 8, &drawn, &smooth[..21]).is_err());
    }
}
