//! Procedural meshes for tests, benchmarks and the demo page.
//!
//! Every generator returns a valid, consistently oriented [`PolyMesh`] (counter-clockwise seen
//! from outside). Sizes are clamped to sensible minimums so that no argument can fail.

use crate::mesh::PolyMesh;
use std::f32::consts::TAU;

/// The cube of seed `003`: corners at ±1, six quads.
pub fn cube() -> PolyMesh {
    let mut positions = Vec::with_capacity(24);
    for i in 0..8 {
        for bit in [4, 2, 1] {
            positions.push(if i & bit != 0 { 1.0 } else { -1.0 });
        }
    }
    PolyMesh {
        positions,
        indices: vec![0, 4, 5, 1, 4, 6, 7, 5, 6, 2, 3, 7, 2, 0, 1, 3, 1, 5, 7, 3, 0, 2, 6, 4],
        face_sizes: vec![4; 6],
    }
}

/// A torus of `rings × segments` quads around the z axis, major radius `major`, tube radius
/// `minor`. Vertex `i * segments + j` sits at ring angle `2πi/rings` and tube angle
/// `2πj/segments`; face `i * segments + j` is `(v(i,j), v(i+1,j), v(i+1,j+1), v(i,j+1))`.
pub fn torus(rings: u32, segments: u32, major: f32, minor: f32) -> PolyMesh {
    let (rings, segments) = (rings.max(3), segments.max(3));
    let mut positions = Vec::with_capacity(3 * (rings * segments) as usize);
    for i in 0..rings {
        let theta = TAU * i as f32 / rings as f32;
        for j in 0..segments {
            let phi = TAU * j as f32 / segments as f32;
            let radius = major + minor * phi.cos();
            positions.extend_from_slice(&[
                radius * theta.cos(),
                radius * theta.sin(),
                minor * phi.sin(),
            ]);
        }
    }
    let v = |i: u32, j: u32| (i % rings) * segments + (j % segments);
    let mut indices = Vec::with_capacity(4 * (rings * segments) as usize);
    for i in 0..rings {
        for j in 0..segments {
            indices.extend_from_slice(&[v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)]);
        }
    }
    PolyMesh { positions, indices, face_sizes: vec![4; (rings * segments) as usize] }
}

/// The same torus with every quad split into two triangles along its `v(i,j)–v(i+1,j+1)`
/// diagonal: `2 · rings · segments` triangles.
pub fn torus_triangles(rings: u32, segments: u32, major: f32, minor: f32) -> PolyMesh {
    triangulate_quads(&torus(rings, segments, major, minor))
}

/// A flat `nx × ny` grid of unit quads in the xy plane, vertex `j * (nx + 1) + i` at `(i, j, 0)`.
pub fn grid(nx: u32, ny: u32) -> PolyMesh {
    grid_with_hole(nx, ny, 0..0, 0..0)
}

/// A grid with the quads `i ∈ hole_x, j ∈ hole_y` left out, so it has an inner boundary.
pub fn grid_with_hole(
    nx: u32,
    ny: u32,
    hole_x: std::ops::Range<u32>,
    hole_y: std::ops::Range<u32>,
) -> PolyMesh {
    let (nx, ny) = (nx.max(1), ny.max(1));
    let mut positions = Vec::with_capacity(3 * ((nx + 1) * (ny + 1)) as usize);
    for j in 0..=ny {
        for i in 0..=nx {
            positions.extend_from_slice(&[i as f32, j as f32, 0.0]);
        }
    }
    let v = |i: u32, j: u32| j * (nx + 1) + i;
    let mut indices = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            if hole_x.contains(&i) && hole_y.contains(&j) {
                continue;
            }
            indices.extend_from_slice(&[v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)]);
        }
    }
    let faces = indices.len() / 4;
    PolyMesh { positions, indices, face_sizes: vec![4; faces] }
}

/// A closed prism over a regular `n`-gon: two `n`-gon caps and `n` quad sides.
pub fn prism(n: u32) -> PolyMesh {
    let n = n.max(3);
    let mut positions = Vec::with_capacity(6 * n as usize);
    for z in [-1.0f32, 1.0] {
        for k in 0..n {
            let a = TAU * k as f32 / n as f32;
            positions.extend_from_slice(&[a.cos(), a.sin(), z]);
        }
    }
    let mut indices: Vec<u32> = (0..n).rev().collect();
    indices.extend(n..2 * n);
    let mut face_sizes = vec![n, n];
    for k in 0..n {
        let k1 = (k + 1) % n;
        indices.extend_from_slice(&[k, k1, n + k1, n + k]);
        face_sizes.push(4);
    }
    PolyMesh { positions, indices, face_sizes }
}

/// Splits every quad `(a, b, c, d)` of `mesh` into `(a, b, c)` and `(a, c, d)`; other faces
/// are kept as they are.
pub fn triangulate_quads(mesh: &PolyMesh) -> PolyMesh {
    let mut indices = Vec::with_capacity(mesh.indices.len() * 3 / 2);
    let mut face_sizes = Vec::with_capacity(mesh.face_sizes.len() * 2);
    let mut start = 0usize;
    for &n in &mesh.face_sizes {
        let Some(face) = mesh.indices.get(start..start + n as usize) else {
            break;
        };
        if let [a, b, c, d] = *face {
            indices.extend_from_slice(&[a, b, c, a, c, d]);
            face_sizes.extend_from_slice(&[3, 3]);
        } else {
            indices.extend_from_slice(face);
            face_sizes.push(n);
        }
        start += n as usize;
    }
    PolyMesh { positions: mesh.positions.clone(), indices, face_sizes }
}

/// A regular icosahedron with vertices on the unit sphere: 12 vertices, 20 triangles.
pub fn icosahedron() -> PolyMesh {
    let phi = (1.0 + 5f32.sqrt()) / 2.0;
    let mut points = Vec::with_capacity(12);
    for (a, b) in [(1.0f32, phi), (-1.0, phi), (1.0, -phi), (-1.0, -phi)] {
        points.push([0.0, a, b]);
        points.push([a, b, 0.0]);
        points.push([b, 0.0, a]);
    }
    let norm = (1.0 + phi * phi).sqrt();
    let points: Vec<[f32; 3]> = points.iter().map(|p| p.map(|x| x / norm)).collect();
    // Faces are the triples of mutually adjacent vertices (edge length 2 / norm), wound so the
    // normal points away from the centre.
    let edge = 2.0 / norm;
    let adjacent = |i: usize, j: usize| (dist(points[i], points[j]) - edge).abs() < 1e-3;
    let mut indices = Vec::with_capacity(60);
    for i in 0..12 {
        for j in i + 1..12 {
            for k in j + 1..12 {
                if adjacent(i, j) && adjacent(j, k) && adjacent(i, k) {
                    let (a, b, c) = (points[i], points[j], points[k]);
                    let n = cross(sub(b, a), sub(c, a));
                    let outward = n[0] * a[0] + n[1] * a[1] + n[2] * a[2] > 0.0;
                    let tri = if outward { [i, j, k] } else { [i, k, j] };
                    indices.extend(tri.map(|v| v as u32));
                }
            }
        }
    }
    PolyMesh { positions: points.as_flattened().to_vec(), indices, face_sizes: vec![3; 20] }
}

/// A regular dodecahedron, the dual of [`icosahedron`]: 20 vertices, 12 pentagons.
pub fn dodecahedron() -> PolyMesh {
    let ico = icosahedron();
    let mut positions = Vec::with_capacity(60);
    for tri in ico.indices.chunks_exact(3) {
        let c = [0, 1, 2]
            .map(|k| tri.iter().map(|&v| ico.positions[3 * v as usize + k]).sum::<f32>() / 3.0);
        let len = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
        positions.extend(c.map(|x| x / len));
    }
    // Around each icosahedron vertex, its five triangles in order: each next triangle shares
    // the edge (v, w) where w follows v in the current one.
    let mut indices = Vec::with_capacity(60);
    for v in 0..12u32 {
        let corner = |t: usize| (0..3).find(|&k| ico.indices[3 * t + k] == v);
        let Some(first) = (0..20).find(|&t| corner(t).is_some()) else {
            continue;
        };
        let mut t = first;
        for _ in 0..5 {
            indices.push(t as u32);
            let Some(k) = corner(t) else { break };
            let prev = ico.indices[3 * t + (k + 2) % 3];
            // The triangle on the other side of edge (prev, v) contains v followed by prev.
            let Some(next) = (0..20)
                .find(|&s| corner(s).is_some_and(|m| ico.indices[3 * s + (m + 1) % 3] == prev))
            else {
                break;
            };
            t = next;
        }
    }
    PolyMesh { positions, indices, face_sizes: vec![5; 12] }
}

fn sub(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn dist(a: [f32; 3], b: [f32; 3]) -> f32 {
    let d = sub(a, b);
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
}

// ---------------------------------------------------------------------------------------------
// Demo shapes, by name

/// The names [`demo_shape`] knows, in the order the demo page lists them.
pub const DEMO_SHAPES: [&str; 6] =
    ["cube", "torus", "sheet-with-holes", "icosahedron", "dodecahedron", "house"];

/// The demo page's built-in meshes: cube (quads), torus (quads), a saddle-shaped sheet with two
/// holes (three boundary loops), icosahedron (triangles), dodecahedron (pentagons) and a house
/// (quad walls and floor under a pyramid roof of triangles). `None` for any other name.
pub fn demo_shape(name: &str) -> Option<PolyMesh> {
    Some(match name {
        "cube" => cube(),
        "torus" => torus(24, 12, 1.0, 0.4),
        "sheet-with-holes" => sheet_with_holes(),
        "icosahedron" => icosahedron(),
        "dodecahedron" => dodecahedron(),
        "house" => house(),
        _ => return None,
    })
}

/// A 9 × 9 grid of quads over [-1.5, 1.5]² bent into the saddle z = 0.25 (x² − y²), with two
/// 2 × 3 holes side by side that share no vertex with each other or with the outer boundary:
/// 96 vertices, 69 quads, three boundary loops, Euler characteristic −1.
pub fn sheet_with_holes() -> PolyMesh {
    const N: u32 = 9;
    let coordinate = |i: u32| -1.5 + 3.0 * i as f32 / N as f32;
    let mut positions = Vec::with_capacity(3 * ((N + 1) * (N + 1)) as usize);
    for j in 0..=N {
        for i in 0..=N {
            let (x, y) = (coordinate(i), coordinate(j));
            positions.extend_from_slice(&[x, y, 0.25 * (x * x - y * y)]);
        }
    }
    let in_hole =
        |i: u32, j: u32| (3..6).contains(&j) && ((2..4).contains(&i) || (5..7).contains(&i));
    let v = |i: u32, j: u32| j * (N + 1) + i;
    let mut indices = Vec::with_capacity(4 * (N * N) as usize);
    for j in 0..N {
        for i in 0..N {
            if !in_hole(i, j) {
                indices.extend_from_slice(&[v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)]);
            }
        }
    }
    // The grid points inside the holes belong to no face: drop them and renumber the rest.
    let mut new_index = vec![u32::MAX; (N + 1) as usize * (N + 1) as usize];
    indices.iter().for_each(|&i| new_index[i as usize] = 0);
    let mut kept = Vec::with_capacity(positions.len());
    for (old, slot) in new_index.iter_mut().enumerate() {
        if *slot == 0 {
            *slot = (kept.len() / 3) as u32;
            kept.extend_from_slice(&positions[3 * old..3 * old + 3]);
        }
    }
    indices.iter_mut().for_each(|i| *i = new_index[*i as usize]);
    let faces = indices.len() / 4;
    PolyMesh { positions: kept, indices, face_sizes: vec![4; faces] }
}

/// A closed mixed mesh, y up: a 2 × 1.3 × 2 box of four quad walls and a quad floor under a
/// pyramid roof of four triangles. 9 vertices, 16 edges, 9 faces.
pub fn house() -> PolyMesh {
    let (floor, eaves, ridge) = (-1.0f32, 0.3f32, 1.2f32);
    let mut positions = Vec::with_capacity(27);
    for y in [floor, eaves] {
        positions.extend_from_slice(&[-1.0, y, -1.0, 1.0, y, -1.0, 1.0, y, 1.0, -1.0, y, 1.0]);
    }
    positions.extend_from_slice(&[0.0, ridge, 0.0]);
    let indices = vec![
        0, 1, 2, 3, // floor
        3, 2, 6, 7, // front wall (+z)
        1, 0, 4, 5, // back wall (-z)
        2, 1, 5, 6, // right wall (+x)
        0, 3, 7, 4, // left wall (-x)
        7, 6, 8, 6, 5, 8, 5, 4, 8, 4, 7, 8, // roof
    ];
    PolyMesh { positions, indices, face_sizes: vec![4, 4, 4, 4, 4, 3, 3, 3, 3] }
}

// ---------------------------------------------------------------------------------------------
// What a viewer needs besides the faces: smooth normals and the edges

/// Calls `f(a, b)` for every directed edge `a → b` of every face, face after face.
fn for_each_half_edge(mesh: &PolyMesh, mut f: impl FnMut(u32, u32)) {
    let mut start = 0usize;
    for &n in &mesh.face_sizes {
        let face = &mesh.indices[start..start + n as usize];
        start += n as usize;
        if let (Some(&first), Some(&last)) = (face.first(), face.last()) {
            face.windows(2).for_each(|pair| f(pair[0], pair[1]));
            f(last, first);
        }
    }
}

/// Smooth vertex normals, x, y, z per vertex: the sum of the area vectors of the faces around
/// each vertex (so large faces weigh more), normalised. A vertex no face uses, or whose faces
/// cancel out, gets (0, 0, 0). Faces may be any polygons; a non-planar face counts with the
/// sum of its fan triangles' area vectors.
pub fn vertex_normals(mesh: &PolyMesh) -> crate::Result<Vec<f32>> {
    mesh.check_arrays()?;
    let p = |v: u32| {
        let i = 3 * v as usize;
        [mesh.positions[i], mesh.positions[i + 1], mesh.positions[i + 2]]
    };
    let mut normals = vec![0.0f32; mesh.positions.len()];
    let mut start = 0usize;
    for &n in &mesh.face_sizes {
        let face = &mesh.indices[start..start + n as usize];
        start += n as usize;
        let Some(&first) = face.first() else { continue };
        let origin = p(first);
        let mut area = [0.0f32; 3];
        for pair in face[1..].windows(2) {
            let c = cross(sub(p(pair[0]), origin), sub(p(pair[1]), origin));
            area = [area[0] + c[0], area[1] + c[1], area[2] + c[2]];
        }
        for &v in face {
            let out = &mut normals[3 * v as usize..3 * v as usize + 3];
            for k in 0..3 {
                out[k] += area[k];
            }
        }
    }
    for normal in normals.chunks_exact_mut(3) {
        let length = (normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]).sqrt();
        let scale = if length > f32::MIN_POSITIVE { 1.0 / length } else { 0.0 };
        normal.iter_mut().for_each(|x| *x *= scale);
    }
    Ok(normals)
}

/// Every edge of the faces once, as pairs of vertex indices `[a0, b0, a1, b1, ...]` in the
/// order the faces first use them, ready for `gl.drawElements(gl.LINES, ...)`. An edge between
/// two faces appears once (from the face where it runs from the lower index to the higher);
/// a boundary edge appears once, as its one face runs it. Linear time: no sorting, no hashing.
pub fn edge_list(mesh: &PolyMesh) -> crate::Result<Vec<u32>> {
    mesh.check_arrays()?;
    let vertices = mesh.num_vertices();
    // The targets of each vertex's outgoing half-edges, grouped by vertex (CSR), so that
    // "does b → a exist" is a scan of b's few neighbours.
    let mut first = vec![0u32; vertices + 1];
    for_each_half_edge(mesh, |a, _| first[a as usize + 1] += 1);
    for v in 0..vertices {
        first[v + 1] += first[v];
    }
    let mut cursor = first[..vertices].to_vec();
    let mut targets = vec![0u32; mesh.indices.len()];
    for_each_half_edge(mesh, |a, b| {
        targets[cursor[a as usize] as usize] = b;
        cursor[a as usize] += 1;
    });
    let outgoing = |v: u32| &targets[first[v as usize] as usize..first[v as usize + 1] as usize];
    let mut edges = Vec::with_capacity(mesh.indices.len());
    for_each_half_edge(mesh, |a, b| {
        if a < b || (a > b && !outgoing(b).contains(&a)) {
            edges.extend_from_slice(&[a, b]);
        }
    });
    Ok(edges)
}

#[cfg(test)]
mod demo_tests {
    use super::*;
    use crate::mesh::HalfEdgeMesh;

    fn boundary_half_edges(mesh: &HalfEdgeMesh) -> usize {
        mesh.half_edge_indices().filter(|&h| mesh.half_edge(h).unwrap().is_boundary()).count()
    }

    #[test]
    fn demo_shapes_are_valid_meshes_with_the_expected_topology() {
        // (name, vertices, faces, Euler characteristic, closed, face sizes present)
        let expected = [
            ("cube", 8, 6, 2, true, &[4][..]),
            ("torus", 288, 288, 0, true, &[4]),
            ("sheet-with-holes", 96, 69, -1, false, &[4]),
            ("icosahedron", 12, 20, 2, true, &[3]),
            ("dodecahedron", 20, 12, 2, true, &[5]),
            ("house", 9, 9, 2, true, &[3, 4]),
        ];
        assert_eq!(expected.map(|e| e.0), DEMO_SHAPES);
        for (name, vertices, faces, euler, closed, sizes) in expected {
            let poly = demo_shape(name).unwrap();
            let mesh = HalfEdgeMesh::from_poly(&poly)
                .unwrap_or_else(|e| panic!("{name} is not a valid mesh: {e}"));
            assert_eq!(mesh.num_vertices(), vertices, "{name} vertices");
            assert_eq!(mesh.num_cells(), faces, "{name} faces");
            let chi = mesh.num_vertices() as i64 - mesh.num_edges() as i64 + faces as i64;
            assert_eq!(chi, euler, "{name} Euler characteristic");
            assert_eq!(boundary_half_edges(&mesh) == 0, closed, "{name} closed");
            let mut present: Vec<u32> = poly.face_sizes.clone();
            present.sort_unstable();
            present.dedup();
            assert_eq!(present, sizes, "{name} face sizes");
        }
        assert!(demo_shape("teapot").is_none());
    }

    #[test]
    fn the_sheet_has_three_boundary_loops() {
        // Each boundary loop of a grid is a rectangle of grid edges: 4·9 outside, 2·(2+3) each hole.
        let mesh = HalfEdgeMesh::from_poly(&sheet_with_holes()).unwrap();
        assert_eq!(boundary_half_edges(&mesh), 36 + 10 + 10);
    }

    #[test]
    fn cube_normals_point_along_the_diagonals() {
        let normals = vertex_normals(&cube()).unwrap();
        let cube = cube();
        for (n, p) in normals.chunks_exact(3).zip(cube.positions.chunks_exact(3)) {
            for k in 0..3 {
                assert!((n[k] - p[k] / 3f32.sqrt()).abs() < 1e-6, "normal {n:?} at {p:?}");
            }
        }
    }

    #[test]
    fn sphere_like_normals_point_outwards_and_flat_ones_up() {
        for mesh in [icosahedron(), dodecahedron()] {
            let normals = vertex_normals(&mesh).unwrap();
            for (n, p) in normals.chunks_exact(3).zip(mesh.positions.chunks_exact(3)) {
                let dot = n[0] * p[0] + n[1] * p[1] + n[2] * p[2];
                assert!(dot > 0.999, "vertices on the unit sphere: normal {n:?} at {p:?}");
            }
        }
        let normals = vertex_normals(&grid(3, 2)).unwrap();
        assert!(normals.chunks_exact(3).all(|n| n == [0.0, 0.0, 1.0]));
    }

    #[test]
    fn an_unused_vertex_gets_a_zero_normal() {
        let mut mesh = grid(1, 1);
        mesh.positions.extend_from_slice(&[5.0, 5.0, 5.0]);
        let normals = vertex_normals(&mesh).unwrap();
        assert_eq!(&normals[12..], &[0.0, 0.0, 0.0]);
    }

    #[test]
    fn edge_lists_hold_every_edge_once() {
        let shapes = [cube(), torus(5, 4, 1.0, 0.3), grid(3, 2), grid_with_hole(4, 4, 1..3, 1..2)]
            .into_iter()
            .chain(DEMO_SHAPES.iter().map(|name| demo_shape(name).unwrap()));
        for poly in shapes {
            let edges = edge_list(&poly).unwrap();
            let mesh = HalfEdgeMesh::from_poly(&poly).unwrap();
            assert_eq!(edges.len(), 2 * mesh.num_edges());
            let mut keys: Vec<(u32, u32)> =
                edges.chunks_exact(2).map(|e| (e[0].min(e[1]), e[0].max(e[1]))).collect();
            keys.sort_unstable();
            keys.dedup();
            assert_eq!(keys.len(), mesh.num_edges(), "no edge twice");
            for (a, b) in keys {
                assert!(
                    mesh.vertex(a).unwrap().find_half_edge_to(b).is_some()
                        || mesh.vertex(b).unwrap().find_half_edge_to(a).is_some()
                );
            }
        }
        assert_eq!(edge_list(&grid(2, 1)).unwrap().len(), 2 * 7);
    }

    #[test]
    fn display_helpers_refuse_inconsistent_arrays() {
        let mut mesh = cube();
        mesh.indices[5] = 8;
        let message = edge_list(&mesh).unwrap_err().to_string();
        assert!(message.contains("indices[5] refers to vertex 8"), "{message}");
        assert!(vertex_normals(&mesh).is_err());
        let mut mesh = cube();
        mesh.face_sizes[0] = 5;
        assert!(edge_list(&mesh).unwrap_err().to_string().contains("add up to 25"));
        let mut mesh = cube();
        mesh.positions.pop();
        assert!(vertex_normals(&mesh).unwrap_err().to_string().contains("multiple of 3"));
    }
}
