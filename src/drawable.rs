//! A mesh with face-varying channels, made drawable with one index buffer.
//!
//! WebGL (and every GPU API) indexes all vertex buffers with one index per corner, so a vertex
//! whose corners take different values of a face-varying channel (the two sides of a UV seam)
//! has to become one vertex per distinct combination. [`to_drawable`] makes exactly those: one
//! output vertex per distinct (vertex, value index of each face-varying channel) that a face
//! corner uses, every channel resolved per output vertex, and the fan triangulation of the faces
//! in the new numbering.
//!
//! ```
//! use subsurf::attributes::Attribute;
//! use subsurf::drawable::to_drawable;
//! use subsurf::PolyMesh;
//!
//! // Two triangles sharing the edge 1–2, which is a UV seam: each side has its own values.
//! let mesh = PolyMesh {
//!     positions: vec![0., 0., 0., 1., 0., 0., 0., 1., 0., 1., 1., 0.],
//!     indices: vec![0, 1, 2, 2, 1, 3],
//!     face_sizes: vec![3, 3],
//! };
//! let uv = Attribute::face_varying("uv", 2, vec![0.; 12], vec![0, 1, 2, 3, 4, 5]);
//! let drawable = to_drawable(&mesh, &[uv]).unwrap();
//! assert_eq!(drawable.origins, [0, 1, 1, 2, 2, 3]); // vertices 1 and 2 split
//! assert_eq!(drawable.triangles, [0, 1, 3, 4, 2, 5]);
//! ```

use crate::attributes::{self, Attribute};
use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use std::cmp::Ordering;

/// A mesh that one index buffer draws: every channel has one value per vertex.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Drawable {
    /// x, y, z per output vertex: its origin's position.
    pub positions: Vec<f32>,
    /// The input's faces in the output numbering (same face sizes, corner for corner).
    pub indices: Vec<u32>,
    pub face_sizes: Vec<u32>,
    /// The fan triangulation of the faces, as [`PolyMesh::triangles`] makes it.
    pub triangles: Vec<u32>,
    /// The input vertex each output vertex comes from (ascending).
    pub origins: Vec<u32>,
    /// Every input channel, in the order given, as a vertex-varying channel of the output:
    /// vertex-varying ones copied from the origin, face-varying ones resolved through the
    /// corners.
    pub attributes: Vec<Attribute>,
}

/// One output vertex per distinct (vertex, face-varying value indices) combination the face
/// corners use, numbered by input vertex and then by value indices; vertices no face uses are
/// left out. The mesh's arrays and the channels are checked first (as `subdivide` checks them).
pub fn to_drawable(mesh: &PolyMesh, attributes: &[Attribute]) -> Result<Drawable> {
    mesh.check_arrays()?;
    attributes::validate(attributes, mesh.num_vertices(), mesh.indices.len())?;
    if u32::try_from(mesh.indices.len()).is_err() {
        return Err(Error::TooLarge(format!(
            "{} face corners; a drawable mesh numbers its vertices with 32-bit indices",
            mesh.indices.len()
        )));
    }
    let fvar: Vec<&[u32]> = attributes.iter().filter_map(|a| a.indices.as_deref()).collect();
    let (corner_vertex, origins, first_corners) = split_vertices(mesh, &fvar);

    let gather = |values: &[f32], size: usize, rows: &[u32]| -> Vec<f32> {
        let mut out = Vec::with_capacity(rows.len() * size);
        for &r in rows {
            out.extend_from_slice(&values[r as usize * size..(r as usize + 1) * size]);
        }
        out
    };
    let channels = attributes
        .iter()
        .map(|a| {
            let values = match &a.indices {
                None => gather(&a.values, a.item_size, &origins),
                Some(indices) => {
                    let rows: Vec<u32> =
                        first_corners.iter().map(|&c| indices[c as usize]).collect();
                    gather(&a.values, a.item_size, &rows)
                }
            };
            Attribute::vertex(a.name.clone(), a.item_size, values)
        })
        .collect();
    let out = PolyMesh {
        positions: gather(&mesh.positions, 3, &origins),
        indices: corner_vertex,
        face_sizes: mesh.face_sizes.clone(),
    };
    let triangles = out.triangles();
    Ok(Drawable {
        positions: out.positions,
        indices: out.indices,
        face_sizes: out.face_sizes,
        triangles,
        origins,
        attributes: channels,
    })
}

/// The output vertex of every corner, the origin of every output vertex and one corner of each.
/// Corners are grouped by vertex with a counting sort (no hashing), and each vertex's few
/// corners are sorted by their value indices, so equal combinations sit side by side.
fn split_vertices(mesh: &PolyMesh, fvar: &[&[u32]]) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    let vertices = mesh.num_vertices();
    let corners = mesh.indices.len();
    let mut first = vec![0u32; vertices + 1];
    for &v in &mesh.indices {
        first[v as usize + 1] += 1;
    }
    for v in 0..vertices {
        first[v + 1] += first[v];
    }
    let mut cursor = first[..vertices].to_vec();
    let mut order = vec![0u32; corners];
    for (c, &v) in mesh.indices.iter().enumerate() {
        order[cursor[v as usize] as usize] = c as u32;
        cursor[v as usize] += 1;
    }
    let compare = |a: u32, b: u32| {
        fvar.iter()
            .map(|indices| indices[a as usize].cmp(&indices[b as usize]))
            .find(|o| o.is_ne())
            .unwrap_or(Ordering::Equal)
    };
    let mut corner_vertex = vec![0u32; corners];
    let mut origins = Vec::with_capacity(vertices);
    let mut first_corners = Vec::with_capacity(vertices);
    for v in 0..vertices {
        let group = &mut order[first[v] as usize..first[v + 1] as usize];
        match fvar {
            [] => {}
            [one] => group.sort_unstable_by_key(|&c| one[c as usize]),
            _ => group.sort_unstable_by(|&a, &b| compare(a, b)),
        }
        let mut previous: Option<u32> = None;
        for &c in group.iter() {
            if previous.is_none_or(|p| compare(p, c).is_ne()) {
                origins.push(v as u32);
                first_corners.push(c);
                previous = Some(c);
            }
            corner_vertex[c as usize] = (origins.len() - 1) as u32;
        }
    }
    (corner_vertex, origins, first_corners)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    /// `n` unit quads in a row: vertices 0..=n along y = 0, n + 1..=2n + 1 along y = 1.
    fn strip(n: u32) -> PolyMesh {
        shapes::grid(n, 1)
    }

    #[test]
    fn without_face_varying_channels_every_used_vertex_stays_once() {
        let mut mesh = shapes::cube();
        mesh.positions.extend_from_slice(&[9.0, 9.0, 9.0]); // used by no face: left out
        let x: Vec<f32> = mesh.positions.chunks(3).map(|p| p[0]).collect();
        let d = to_drawable(&mesh, &[Attribute::vertex("x", 1, x)]).unwrap();
        assert_eq!(d.origins, (0..8).collect::<Vec<u32>>());
        assert_eq!(d.indices, mesh.indices);
        assert_eq!(d.triangles, mesh.triangles());
        assert_eq!(d.positions, mesh.positions[..24]);
        let xs: Vec<f32> = d.positions.chunks(3).map(|p| p[0]).collect();
        assert_eq!(d.attributes[0].values, xs);
        assert!(d.attributes[0].indices.is_none());
    }

    #[test]
    fn a_seam_splits_its_vertices_and_nothing_else() {
        // Two quads side by side whose UVs do not meet at the shared edge 1–4: vertices 1 and 4
        // get one output vertex per side; the others one each. 6 + 2 = 8 vertices.
        let mesh = strip(2);
        let uv_values = vec![0.; 16];
        let uv = Attribute::face_varying("uv", 2, uv_values, vec![0, 1, 2, 3, 4, 5, 6, 7]);
        let d = to_drawable(&mesh, &[uv]).unwrap();
        assert_eq!(mesh.indices, [0, 1, 4, 3, 1, 2, 5, 4]);
        assert_eq!(d.origins, [0, 1, 1, 2, 3, 4, 4, 5]);
        assert_eq!(d.indices, [0, 1, 5, 4, 2, 3, 7, 6]);
        // Every corner's output vertex has the corner's own vertex and value.
        for (c, &o) in d.indices.iter().enumerate() {
            assert_eq!(d.origins[o as usize], mesh.indices[c]);
        }
    }

    #[test]
    fn values_resolve_per_corner_and_channels_combine() {
        // A vertex-varying weight, a UV split along edge 1–4, and a second face-varying channel
        // whose one odd value sits on vertex 2's only corner, so it splits nothing: 8 vertices.
        let mesh = strip(2);
        let uv = Attribute::face_varying(
            "uv",
            2,
            (0..16).map(|i| i as f32).collect(),
            vec![0, 1, 2, 3, 4, 5, 6, 7],
        );
        let id = Attribute::face_varying("id", 1, vec![10., 20.], vec![0, 0, 0, 0, 0, 1, 0, 0]);
        let weight = Attribute::vertex("w", 1, vec![0., 1., 2., 3., 4., 5.]);
        let d = to_drawable(&mesh, &[weight, uv, id]).unwrap();
        assert_eq!(d.origins.len(), 8);
        for (c, &o) in d.indices.iter().enumerate() {
            let o = o as usize;
            assert_eq!(d.attributes[0].values[o], mesh.indices[c] as f32, "corner {c}: w");
            let uv = &d.attributes[1].values[2 * o..2 * o + 2];
            assert_eq!(uv, [2.0 * c as f32, 2.0 * c as f32 + 1.0], "corner {c}: uv");
            let id = if c == 5 { 20.0 } else { 10.0 };
            assert_eq!(d.attributes[2].values[o], id, "corner {c}: id");
        }
        assert_eq!(d.attributes.iter().map(|a| a.item_size).collect::<Vec<_>>(), [1, 2, 1]);
    }

    #[test]
    fn a_vertex_split_three_ways_keeps_one_vertex_per_value() {
        // The cube with each face on its own copy of the unit square (every edge a seam): each
        // cube vertex has three corners with three different values, so 24 output vertices,
        // one per corner.
        let mesh = shapes::cube();
        let square = [0., 0., 1., 0., 1., 1., 0., 1.];
        let uv = Attribute::face_varying("uv", 2, square.repeat(6), (0..24).collect());
        let d = to_drawable(&mesh, &[uv]).unwrap();
        assert_eq!(d.origins.len(), 24);
        let mut used = d.indices.clone();
        used.sort_unstable();
        assert_eq!(used, (0..24).collect::<Vec<u32>>(), "one corner per output vertex");
        assert!(d.origins.windows(2).all(|w| w[0] <= w[1]), "origins ascend");
        assert!(d.triangles.iter().all(|&t| (t as usize) < d.origins.len()));
        assert_eq!(d.triangles.len(), 36);
    }

    #[test]
    fn bad_input_is_refused() {
        let mut mesh = strip(1);
        mesh.indices[2] = 9;
        assert!(to_drawable(&mesh, &[]).unwrap_err().to_string().contains("indices[2]"));
        let short = Attribute::face_varying("uv", 2, vec![0.; 8], vec![0; 3]);
        let message = to_drawable(&strip(1), &[short]).unwrap_err().to_string();
        assert!(message.contains("'uv'") && message.contains("3 indices"), "{message}");
    }
}
