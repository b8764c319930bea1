//! Procedural meshes for tests, benchmarks and the demo page.
//!
//! Every generator returns a valid, consistently oriented [`PolyMesh`] (counter-clockwise seen
//! from outside). Sizes are clamped to sensible minimums so that no argument can fail.

use crate::mesh::PolyMesh;
use std::f32::consts::{PI, TAU};

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

/// The `(ring, tube)` parameter grid of [`torus`] over `[0, 1]²` as a face-varying `uv`: one
/// value per grid point of `(rings + 1) × (segments + 1)`, so that the two closing loops are
/// seams (the benchmarks' textured torus; `bench/torus.mjs` makes the same).
pub fn torus_uv(rings: u32, segments: u32) -> crate::attributes::Attribute {
    let (rings, segments) = (rings.max(3), segments.max(3));
    let mut values = Vec::with_capacity(2 * ((rings + 1) * (segments + 1)) as usize);
    for i in 0..=rings {
        for j in 0..=segments {
            values.extend_from_slice(&[i as f32 / rings as f32, j as f32 / segments as f32]);
        }
    }
    let value = |i: u32, j: u32| i * (segments + 1) + j;
    let mut indices = Vec::with_capacity(4 * (rings * segments) as usize);
    for i in 0..rings {
        for j in 0..segments {
            let quad = [value(i, j), value(i + 1, j), value(i + 1, j + 1), value(i, j + 1)];
            indices.extend_from_slice(&quad);
        }
    }
    crate::attributes::Attribute::face_varying("uv", 2, values, indices)
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
// UV layouts of the demo shapes

/// The texture coordinates of [`demo_shape`]`(name)`: a face-varying channel named `uv` (2
/// floats, one index per face corner), laid out as a modeller would, with seams where the
/// layout cuts the surface open. Counter-clockwise faces stay counter-clockwise in UV space.
///
/// - cube: unfolded into a cross (14 values, square cells of 1/4);
/// - torus: the (ring, tube) parameter grid over [0, 1]², cut along one ring and one tube
///   circle;
/// - sheet with holes: the planar projection of x, y onto [0, 1]² (no seams);
/// - icosahedron, dodecahedron: latitude and longitude about the axis through vertex 0 (u over
///   [0, 2], v over [0, 1]), cut along one meridian; a pole's corners take the mean longitude of
///   their face;
/// - house: box mapping, each face projected along the axis its normal points most along.
pub fn demo_shape_uv(name: &str) -> Option<crate::attributes::Attribute> {
    let mesh = demo_shape(name)?;
    let per_corner: Vec<[f32; 2]> = match name {
        "cube" => cube_cross_uv(),
        "torus" => {
            let (rings, segments) = (24u32, 12u32);
            let mut uv = Vec::with_capacity(mesh.indices.len());
            for i in 0..rings {
                for j in 0..segments {
                    let at = |i: u32, j: u32| [i as f32 / rings as f32, j as f32 / segments as f32];
                    uv.extend([at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
                }
            }
            uv
        }
        "sheet-with-holes" => mesh
            .indices
            .iter()
            .map(|&v| {
                let p = &mesh.positions[3 * v as usize..];
                [(p[0] + 1.5) / 3.0, (p[1] + 1.5) / 3.0]
            })
            .collect(),
        "icosahedron" | "dodecahedron" => spherical_uv(&mesh, 0),
        _ => box_uv(&mesh),
    };
    Some(merge_corner_values(&mesh, &per_corner))
}

/// The cube of [`cube`] unfolded into a cross: the four faces around z in a row (a seam closes
/// the row), z+ above and z− below the first of them.
fn cube_cross_uv() -> Vec<[f32; 2]> {
    let at = |column: u32, row: u32| [column as f32 / 4.0, (2 * row + 1) as f32 / 8.0];
    let mut uv = Vec::with_capacity(24);
    // Faces 0..4 ([0,4,5,1], [4,6,7,5], [6,2,3,7], [2,0,1,3]) start at z− and run around z.
    for k in 0..4 {
        uv.extend([at(k, 1), at(k + 1, 1), at(k + 1, 2), at(k, 2)]);
    }
    uv.extend([at(0, 2), at(1, 2), at(1, 3), at(0, 3)]); // z+: [1, 5, 7, 3]
    uv.extend([at(0, 1), at(0, 0), at(1, 0), at(1, 1)]); // z−: [0, 2, 6, 4]
    uv
}

/// Longitude (u, over [0, 2)) and latitude (v, 0 at the south pole, 1 at the north pole) about
/// the axis through vertex `pole`, for meshes around the origin. A face that straddles the
/// meridian u = 0 takes its small longitudes one turn up, so the cut is a seam; a corner on a
/// pole, where longitude is undefined, takes the mean of its face's other corners.
fn spherical_uv(mesh: &PolyMesh, pole: u32) -> Vec<[f32; 2]> {
    let point = |v: u32| {
        let p = &mesh.positions[3 * v as usize..3 * v as usize + 3];
        let len = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt().max(f32::MIN_POSITIVE);
        [p[0] / len, p[1] / len, p[2] / len]
    };
    let axis = point(pole);
    // Any direction off the axis, made perpendicular: the meridian u = 0.
    let helper = if axis[0].abs() < 0.9 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] };
    let along = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let d = along(helper, axis);
    let e1 = normalize(sub(helper, axis.map(|x| x * d)));
    // Seen from outside, with the pole up, e2 = axis × e1 points right: u grows to the right.
    let e2 = cross(axis, e1);
    let mut uv = Vec::with_capacity(mesh.indices.len());
    let mut start = 0usize;
    for &n in &mesh.face_sizes {
        let face = &mesh.indices[start..start + n as usize];
        start += n as usize;
        let polar: Vec<Option<f32>> = face
            .iter()
            .map(|&v| {
                let p = point(v);
                let (x, y) = (along(p, e1), along(p, e2));
                (x * x + y * y > 1e-10).then(|| (y.atan2(x) / TAU).rem_euclid(1.0))
            })
            .collect();
        let known = || polar.iter().flatten().copied();
        let straddles = known().fold(f32::MIN, f32::max) - known().fold(f32::MAX, f32::min) > 0.5;
        let unwrapped = |u: f32| if straddles && u < 0.5 { u + 1.0 } else { u };
        let count = known().count().max(1) as f32;
        let mean = known().map(unwrapped).sum::<f32>() / count;
        for (&v, u) in face.iter().zip(&polar) {
            let latitude = 1.0 - along(point(v), axis).clamp(-1.0, 1.0).acos() / PI;
            uv.push([2.0 * u.map_or(mean, unwrapped), latitude]);
        }
    }
    uv
}

/// Box mapping: each face projected onto the coordinate plane its normal points most along,
/// right-handed seen from outside, scaled from [−1, 1] to [0, 1].
fn box_uv(mesh: &PolyMesh) -> Vec<[f32; 2]> {
    let mut uv = Vec::with_capacity(mesh.indices.len());
    let mut start = 0usize;
    for &n in &mesh.face_sizes {
        let face = &mesh.indices[start..start + n as usize];
        start += n as usize;
        let p = |v: u32| {
            let i = 3 * v as usize;
            [mesh.positions[i], mesh.positions[i + 1], mesh.positions[i + 2]]
        };
        // Newell's normal: the face's area vector, for any polygon.
        let mut normal = [0.0f32; 3];
        for (k, &a) in face.iter().enumerate() {
            let c = cross(p(a), p(face[(k + 1) % face.len()]));
            normal = [normal[0] + c[0], normal[1] + c[1], normal[2] + c[2]];
        }
        let axis = (0..3).max_by(|&a, &b| normal[a].abs().total_cmp(&normal[b].abs())).unwrap_or(2);
        let positive = normal[axis] >= 0.0;
        for &v in face {
            let [x, y, z] = p(v);
            // (u, v) with u × v along the normal: v is up (y) on the walls.
            let (u, w) = match (axis, positive) {
                (0, true) => (-z, y),
                (0, false) => (z, y),
                (1, true) => (x, -z),
                (1, false) => (x, z),
                (_, true) => (x, y),
                (_, false) => (-x, y),
            };
            uv.push([(u + 1.0) / 2.0, (w + 1.0) / 2.0]);
        }
    }
    uv
}

/// A face-varying channel from one value per corner, a vertex's corners with the same value
/// sharing it: a seam is where they differ.
fn merge_corner_values(mesh: &PolyMesh, per_corner: &[[f32; 2]]) -> crate::attributes::Attribute {
    // The values made so far for each vertex: a handful each, scanned.
    let mut by_vertex: Vec<Vec<([f32; 2], u32)>> = vec![Vec::new(); mesh.num_vertices()];
    let mut values = Vec::new();
    let mut indices = Vec::with_capacity(per_corner.len());
    for (&v, &uv) in mesh.indices.iter().zip(per_corner) {
        let known = &mut by_vertex[v as usize];
        let index = match known.iter().find(|(value, _)| *value == uv) {
            Some(&(_, index)) => index,
            None => {
                let index = (values.len() / 2) as u32;
                values.extend(uv);
                known.push((uv, index));
                index
            }
        };
        indices.push(index);
    }
    crate::attributes::Attribute::face_varying("uv", 2, values, indices)
}

fn normalize(a: [f32; 3]) -> [f32; 3] {
    let len = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt().max(f32::MIN_POSITIVE);
    a.map(|x| x / len)
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
    Ok(crate::limit::face_normals(mesh))
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

    /// The signed area of face-corner values `uv` (shoelace): positive when counter-clockwise.
    fn signed_area(uv: &[[f32; 2]]) -> f32 {
        let n = uv.len();
        (0..n).map(|k| uv[k][0] * uv[(k + 1) % n][1] - uv[(k + 1) % n][0] * uv[k][1]).sum::<f32>()
            / 2.0
    }

    #[test]
    fn demo_uv_layouts_are_valid_counter_clockwise_and_cut_where_expected() {
        // (name, values: from the layout's closed form, seams: vertices with more than one value)
        let expected =
            [("cube", 14, 6), ("torus", 25 * 13, 24 + 12 - 1), ("sheet-with-holes", 96, 0)];
        for name in DEMO_SHAPES {
            let mesh = demo_shape(name).unwrap();
            let uv = demo_shape_uv(name).unwrap();
            crate::attributes::validate(
                std::slice::from_ref(&uv),
                mesh.num_vertices(),
                mesh.indices.len(),
            )
            .unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!((uv.name.as_str(), uv.item_size), ("uv", 2));
            let indices = uv.indices.as_ref().unwrap();
            let value = |c: usize| {
                let t = indices[c] as usize;
                [uv.values[2 * t], uv.values[2 * t + 1]]
            };
            let mut start = 0;
            for (f, &n) in mesh.face_sizes.iter().enumerate() {
                let corners: Vec<[f32; 2]> = (start..start + n as usize).map(value).collect();
                let area = signed_area(&corners);
                assert!(area > 1e-4, "{name}: face {f} has UV area {area} ({corners:?})");
                start += n as usize;
            }
            let mut values_of = vec![std::collections::BTreeSet::new(); mesh.num_vertices()];
            for (&v, &t) in mesh.indices.iter().zip(indices) {
                values_of[v as usize].insert(t);
            }
            let seams = values_of.iter().filter(|s| s.len() > 1).count();
            if let Some(&(_, values, seam_vertices)) = expected.iter().find(|e| e.0 == name) {
                assert_eq!((uv.len(), seams), (values, seam_vertices), "{name}");
            } else {
                assert!(seams > 0 && uv.len() > mesh.num_vertices(), "{name}: cut open somewhere");
            }
        }
        assert!(demo_shape_uv("teapot").is_none());
    }

    #[test]
    fn spherical_uvs_follow_latitude_and_longitude() {
        // Vertex 0 is the north pole (v = 1), its antipode the south pole (v = 0), and v of
        // the others is 1 − angle/π from the pole axis. u is twice the longitude in turns; no
        // face spans half a turn or more (the cut made a seam rather than a face around the
        // globe).
        for name in ["icosahedron", "dodecahedron"] {
            let mesh = demo_shape(name).unwrap();
            let uv = demo_shape_uv(name).unwrap();
            let indices = uv.indices.as_ref().unwrap();
            let axis = [mesh.positions[0], mesh.positions[1], mesh.positions[2]];
            let norm = |p: &[f32]| (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            for (&v, &t) in mesh.indices.iter().zip(indices) {
                let p = &mesh.positions[3 * v as usize..3 * v as usize + 3];
                let cos =
                    (p[0] * axis[0] + p[1] * axis[1] + p[2] * axis[2]) / (norm(p) * norm(&axis));
                let want = 1.0 - cos.clamp(-1.0, 1.0).acos() / PI;
                let w = uv.values[2 * t as usize + 1];
                assert!((w - want).abs() < 1e-5, "{name} vertex {v}: v {w} vs {want}");
            }
            let mut start = 0;
            for &n in &mesh.face_sizes {
                let us: Vec<f32> = indices[start..start + n as usize]
                    .iter()
                    .map(|&t| uv.values[2 * t as usize])
                    .collect();
                let span = us.iter().fold(f32::MIN, |a, &b| a.max(b))
                    - us.iter().fold(f32::MAX, |a, &b| a.min(b));
                assert!(
                    span < 1.0 && us.iter().all(|&u| (0.0..3.0).contains(&u)),
                    "{name}: {us:?}"
                );
                start += n as usize;
            }
        }
    }
}
