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
