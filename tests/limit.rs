//! The limit surface (`scheme::subdivide_limit`) beyond the OpenSubdiv fixtures
//! (`tests/osd_limit_agreement.rs`): normals are unit length and outward on closed meshes
//! wound counter-clockwise, sharp creases and corners take the normal of one of their faces, the
//! masks are affine (positions) and differences (tangents), vertex-varying data takes the
//! position masks, and what has no limit is an error, not a panic.

use subsurf::attributes::Attribute;
use subsurf::io::read_obj;
use subsurf::mesh::HalfEdgeMesh;
use subsurf::rules::limit::LimitRules;
use subsurf::scheme::{subdivide_limit, subdivide_limit_with, Refined};
use subsurf::{shapes, Boundary, Crease, Error, Options, PolyMesh, Scheme, Tags};

fn osd_shape(name: &str) -> PolyMesh {
    let path = format!("{}/tests/meshes/osd/{name}.obj", env!("CARGO_MANIFEST_DIR"));
    read_obj(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn limit(mesh: &PolyMesh, scheme: Scheme, levels: u32, tags: &Tags) -> Refined<'static> {
    subdivide_limit(mesh, &Options::new(scheme, levels), tags).unwrap()
}

fn triple(values: &[f32], v: usize) -> [f64; 3] {
    [values[3 * v] as f64, values[3 * v + 1] as f64, values[3 * v + 2] as f64]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn centroid(positions: &[f32]) -> [f64; 3] {
    let n = (positions.len() / 3) as f64;
    let mut c = [0.0; 3];
    for p in positions.chunks_exact(3) {
        for k in 0..3 {
            c[k] += p[k] as f64 / n;
        }
    }
    c
}

/// Every normal of `result` is unit length; returns Σ normal · (p - centroid) and the smallest
/// single term.
fn outwardness(result: &Refined) -> (f64, f64) {
    let positions = result.positions();
    let normals = result.normals().unwrap();
    let c = centroid(positions);
    let (mut sum, mut least) = (0.0, f64::INFINITY);
    for v in 0..positions.len() / 3 {
        let n = triple(normals, v);
        assert!((dot(n, n).sqrt() - 1.0).abs() < 1e-5, "normal {v} = {n:?} is not unit length");
        let p = triple(positions, v);
        let term = dot(n, [p[0] - c[0], p[1] - c[1], p[2] - c[2]]);
        sum += term;
        least = least.min(term);
    }
    (sum, least)
}

#[test]
fn normals_are_unit_and_outward_on_closed_meshes() {
    let cases: Vec<(&str, PolyMesh, Scheme)> = vec![
        ("cube", shapes::cube(), Scheme::CatmullClark),
        ("catmark_cube", osd_shape("catmark_cube"), Scheme::CatmullClark),
        ("catmark_torus", osd_shape("catmark_torus"), Scheme::CatmullClark),
        ("torus 12x8", shapes::torus(12, 8, 1.0, 0.3), Scheme::CatmullClark),
        ("dodecahedron", shapes::dodecahedron(), Scheme::CatmullClark),
        ("icosahedron", shapes::icosahedron(), Scheme::Loop),
        ("loop_cube", osd_shape("loop_cube"), Scheme::Loop),
        ("loop_tetrahedron", osd_shape("loop_tetrahedron"), Scheme::Loop),
        ("torus triangles", shapes::torus_triangles(12, 8, 1.0, 0.3), Scheme::Loop),
    ];
    for (name, mesh, scheme) in cases {
        for levels in 1..=3 {
            let result = limit(&mesh, scheme, levels, &Tags::default());
            let (sum, least) = outwardness(&result);
            assert!(sum > 0.0, "{name} level {levels}: normals point inward (sum {sum})");
            // Convex shapes: every normal points away from the centre.
            if !name.contains("torus") {
                assert!(least > 0.0, "{name} level {levels}: a normal points inward ({least})");
            }
        }
    }
}

/// The orientation the docs state: `first × second` points outward on the cube, whose faces are
/// wound counter-clockwise seen from outside; at a corner of the cube, along the diagonal.
#[test]
fn cube_corner_normal_is_along_the_diagonal() {
    let result = limit(&shapes::cube(), Scheme::CatmullClark, 1, &Tags::default());
    let positions = result.positions();
    let c = centroid(positions);
    for v in 0..8 {
        let p = triple(positions, v);
        let d = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
        let d_length = dot(d, d).sqrt();
        let n = triple(result.normals().unwrap(), v);
        assert!(dot(n, d) / d_length > 0.999_99, "corner {v}: normal {n:?}, diagonal {d:?}");
        let [t1, t2] = result.tangents().unwrap();
        let (a, b) = (triple(t1, v), triple(t2, v));
        let cross =
            [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
        assert!(dot(cross, d) > 0.0, "corner {v}: first × second points inward");
    }
}

/// Every edge of `mesh` infinitely sharp.
fn all_sharp(mesh: &PolyMesh) -> Tags {
    let he = HalfEdgeMesh::from_poly(mesh).unwrap();
    let creases = (0..he.num_edges() as u32)
        .map(|e| Crease { vertices: he.edge_vertices(e).unwrap(), sharpness: 10.0 })
        .collect();
    Tags { creases, ..Tags::default() }
}

/// With every edge infinitely sharp the faces stay flat; a vertex inside a face has the face's
/// normal, and a vertex on a crease or at a corner the normal of one of the faces it touches,
/// outward.
#[test]
fn sharp_creases_and_corners_take_the_normal_of_one_side() {
    let cases = [
        ("cube", shapes::cube(), Scheme::CatmullClark),
        ("loop_cube", osd_shape("loop_cube"), Scheme::Loop),
        ("icosahedron", shapes::icosahedron(), Scheme::Loop),
    ];
    for (name, mesh, scheme) in cases {
        // The outward unit normal of each base face.
        let face_normals: Vec<[f64; 3]> = {
            let mut start = 0usize;
            mesh.face_sizes
                .iter()
                .map(|&n| {
                    let corner =
                        |k: usize| triple(&mesh.positions, mesh.indices[start + k] as usize);
                    let (a, b, c) = (corner(0), corner(1), corner(2));
                    start += n as usize;
                    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
                    let w = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
                    let x = [
                        u[1] * w[2] - u[2] * w[1],
                        u[2] * w[0] - u[0] * w[2],
                        u[0] * w[1] - u[1] * w[0],
                    ];
                    let l = dot(x, x).sqrt();
                    [x[0] / l, x[1] / l, x[2] / l]
                })
                .collect()
        };
        let tags = all_sharp(&mesh);
        for levels in 1..=3 {
            let result = limit(&mesh, scheme, levels, &tags);
            let normals = result.normals().unwrap();
            let (mut on_crease, mut inside) = (0, 0);
            for v in 0..result.positions().len() / 3 {
                let n = triple(normals, v);
                let matches = face_normals.iter().any(|f| dot(*f, n) > 1.0 - 1e-6);
                assert!(matches, "{name} level {levels}: vertex {v} normal {n:?} is no face's");
                // Count how many faces' planes the vertex lies on: more than one means a crease
                // or a corner.
                let p = triple(result.positions(), v);
                let mut planes: Vec<[f64; 3]> = face_normals
                    .iter()
                    .enumerate()
                    .filter(|(f, normal)| {
                        let start: usize = mesh.face_sizes[..*f].iter().map(|&n| n as usize).sum();
                        let a = triple(&mesh.positions, mesh.indices[start] as usize);
                        let d = dot(**normal, [p[0] - a[0], p[1] - a[1], p[2] - a[2]]);
                        d.abs() < 1e-5
                    })
                    .map(|(_, normal)| *normal)
                    .collect();
                // Faces in one plane (a triangulated square) count once.
                planes.dedup_by(|a, b| dot(*a, *b) > 1.0 - 1e-6);
                if planes.len() > 1 {
                    on_crease += 1;
                } else {
                    inside += 1;
                }
            }
            // (At level 1 every vertex of a triangle split is on a base edge.)
            assert!(on_crease > 0, "{name} level {levels}: no vertex on a crease");
            assert!(inside > 0 || levels == 1, "{name} level {levels}: no vertex inside a face");
        }
    }
}

#[test]
fn position_masks_are_affine_and_tangent_masks_sum_to_zero() {
    let quads = shapes::torus(6, 5, 1.0, 0.3);
    let grid = shapes::grid(3, 3);
    let triangles = shapes::icosahedron();
    let cases = [
        (&quads, Scheme::CatmullClark, Boundary::EdgeAndCorner),
        (&grid, Scheme::CatmullClark, Boundary::EdgeAndCorner),
        (&grid, Scheme::CatmullClark, Boundary::EdgeOnly),
        (&grid, Scheme::CatmullClark, Boundary::Fixed),
        (&triangles, Scheme::Loop, Boundary::EdgeAndCorner),
        (&shapes::triangulate_quads(&grid), Scheme::Loop, Boundary::EdgeOnly),
    ];
    for (mesh, scheme, boundary) in cases {
        let he = HalfEdgeMesh::from_poly(mesh).unwrap();
        let rules = LimitRules { scheme, boundary, tags: None, starts: None };
        for v in he.vertex_indices() {
            let [position, first, second] = subsurf::limit::stencils(&he, &rules, v);
            assert!((position.total() - 1.0).abs() < 1e-5, "{scheme} vertex {v}: {position:?}");
            assert!(first.total().abs() < 1e-5, "{scheme} vertex {v}: {first:?}");
            assert!(second.total().abs() < 1e-5, "{scheme} vertex {v}: {second:?}");
            assert!(!first.sources.is_empty() && !second.sources.is_empty());
        }
    }
}

#[test]
fn vertex_varying_data_takes_the_position_masks() {
    let mesh = shapes::torus(8, 6, 1.0, 0.3);
    let channel = Attribute::vertex("copy", 3, mesh.positions.clone());
    let options = Options::new(Scheme::CatmullClark, 2);
    let result = subdivide_limit_with(&mesh, &[channel], &options, &Tags::default()).unwrap();
    let positions = result.positions().to_vec();
    let copy = &result.attributes()[0].values;
    assert_eq!(copy.len(), positions.len());
    for (a, b) in copy.iter().zip(&positions) {
        assert!((a - b).abs() < 1e-6);
    }
}

#[test]
fn limit_positions_lie_on_the_refined_surface() {
    // The limit of level L is close to level L + 4 refined (a check independent of the masks).
    let mesh = shapes::torus(8, 6, 1.0, 0.3);
    let limit = limit(&mesh, Scheme::CatmullClark, 1, &Tags::default());
    let deep = subsurf::subdivide(&mesh, &Options::new(Scheme::CatmullClark, 6)).unwrap();
    // Vertices of level 1 keep their indices in every later level (children of vertices first).
    for v in 0..limit.positions().len() / 3 {
        let (a, b) = (triple(limit.positions(), v), triple(&deep.positions, v));
        let d = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
        assert!(d < 1e-3, "vertex {v}: limit {a:?}, level 6 {b:?}");
    }
}

#[test]
fn what_has_no_limit_is_an_error() {
    let cube = shapes::cube();
    let none = Tags::default();
    let refuse = |options: Options, mesh: &PolyMesh| match subdivide_limit(mesh, &options, &none) {
        Err(Error::Unsupported(message)) => message,
        other => panic!("expected Unsupported, got {:?}", other.map(|r| r.positions().len())),
    };
    assert!(refuse(Options::new(Scheme::CatmullClark, 0), &cube).contains("at least one level"));
    assert!(refuse(Options::new(Scheme::DooSabin, 1), &cube).contains("doo-sabin"));
    assert!(refuse(Options::new(Scheme::Sqrt3, 1), &shapes::icosahedron()).contains("sqrt3"));
    let average = Options::new(Scheme::CatmullClark, 1).with_boundary(Boundary::Average);
    assert!(refuse(average, &cube).contains("average"));
    // Quad/Triangle on quads is Catmull-Clark, limit included.
    let quad_triangle = subdivide_limit(&cube, &Options::new(Scheme::QuadTriangle, 2), &none);
    let catmull_clark = limit(&cube, Scheme::CatmullClark, 2, &none);
    // (Its host numbers vertices its own way: each point must be one of Catmull-Clark's.)
    let (a, b) = (quad_triangle.unwrap(), catmull_clark);
    let (a, b) = (a.positions().as_chunks::<3>().0, b.positions().as_chunks::<3>().0);
    assert_eq!(a.len(), b.len());
    for p in a {
        let near = |q: &&[f32; 3]| (0..3).all(|k| (p[k] - q[k]).abs() < 1e-6);
        assert!(b.iter().any(|q| near(&q)), "{p:?} is not a Catmull-Clark limit point");
    }
    // Bilinear points are on their limit already: they stay, with normals from the faces.
    let bilinear = subdivide_limit(&cube, &Options::new(Scheme::Bilinear, 2), &none).unwrap();
    let plain = subsurf::subdivide(&cube, &Options::new(Scheme::Bilinear, 2)).unwrap();
    assert_eq!(bilinear.positions(), &plain.positions[..]);
    assert_eq!(bilinear.normals().unwrap(), &subsurf::shapes::vertex_normals(&plain).unwrap()[..]);
    // Quad/Triangle on triangles is Loop, which has a limit.
    assert!(subdivide_limit(&shapes::icosahedron(), &Options::new(Scheme::QuadTriangle, 1), &none)
        .is_ok());
    // A list ending with Catmull-Clark has one.
    let list =
        Options { schemes: vec![Scheme::DooSabin, Scheme::CatmullClark], ..Options::default() };
    assert!(subdivide_limit(&cube, &list, &none).is_ok());
}

#[test]
fn odd_inputs_do_not_panic() {
    // An isolated vertex stays, with a zero normal; a degenerate face gives finite values.
    let mut mesh = shapes::grid(2, 2);
    mesh.positions.extend_from_slice(&[5.0, 5.0, 5.0]);
    let isolated = mesh.positions.len() / 3 - 1;
    let result = limit(&mesh, Scheme::CatmullClark, 1, &Tags::default());
    assert_eq!(triple(result.positions(), isolated), [5.0, 5.0, 5.0]);
    assert_eq!(triple(result.normals().unwrap(), isolated), [0.0; 3]);
    let flat =
        PolyMesh { positions: vec![0.0; 12], indices: vec![0, 1, 2, 3], face_sizes: vec![4] };
    for boundary in [Boundary::EdgeAndCorner, Boundary::EdgeOnly, Boundary::None, Boundary::Fixed] {
        let options = Options::new(Scheme::CatmullClark, 2).with_boundary(boundary);
        let result = subdivide_limit(&flat, &options, &Tags::default()).unwrap();
        assert!(result.positions().iter().chain(result.normals().unwrap()).all(|x| x.is_finite()));
    }
    // Every non-manifold shape, every boundary mode, with and without tags.
    let dir = format!("{}/tests/meshes/osd_nonmanifold", env!("CARGO_MANIFEST_DIR"));
    for entry in std::fs::read_dir(dir).unwrap() {
        let text = std::fs::read_to_string(entry.unwrap().path()).unwrap();
        let obj = subsurf::io::read_obj_with_tags(&text).unwrap();
        let triangles = obj.mesh.face_sizes.iter().all(|&n| n == 3);
        let scheme = if triangles { Scheme::Loop } else { Scheme::CatmullClark };
        for boundary in
            [Boundary::EdgeAndCorner, Boundary::EdgeOnly, Boundary::None, Boundary::Fixed]
        {
            for tags in [&Tags::default(), &obj.tags] {
                let options = Options::new(scheme, 1).with_boundary(boundary);
                let result = subdivide_limit(&obj.mesh, &options, tags).unwrap();
                assert!(result.positions().iter().all(|x| x.is_finite()));
                assert!(result.normals().unwrap().iter().all(|x| x.is_finite()));
            }
        }
    }
}

#[test]
fn the_byte_guard_counts_tangents_and_normals() {
    // A budget the plain result fits and the limit (nine more floats per vertex) does not.
    let mesh = shapes::cube();
    let prediction = subsurf::scheme::predict(
        &HalfEdgeMesh::from_poly(&mesh).unwrap(),
        &Options::new(Scheme::CatmullClark, 2),
    );
    let mut options = Options::new(Scheme::CatmullClark, 2);
    options.max_bytes = prediction.bytes() + 4 * prediction.vertices;
    assert!(subsurf::subdivide(&mesh, &options).is_ok());
    assert!(matches!(subdivide_limit(&mesh, &options, &Tags::default()), Err(Error::TooLarge(_))));
    options.max_bytes = prediction.bytes() + 36 * prediction.vertices;
    assert!(subdivide_limit(&mesh, &options, &Tags::default()).is_ok());
}

/// Quad/Triangle where quads meet triangles (a prism: quad sides, triangle caps): a vertex
/// whose faces are all quads or all triangles takes Catmull-Clark's or Loop's masks, one where
/// they meet stays where the level put it (the corner rule); normals are unit and outward.
#[test]
fn quad_triangle_takes_masks_by_the_faces_around_each_vertex() {
    let prism = shapes::prism(3);
    let options = Options::new(Scheme::QuadTriangle, 2);
    let result = subdivide_limit(&prism, &options, &Tags::default()).unwrap();
    let plain = subsurf::subdivide(&prism, &options).unwrap();
    assert_eq!(result.positions().len(), plain.positions.len());
    // Which vertices have quads and triangles around them.
    let n = plain.num_vertices();
    let (mut quads, mut triangles) = (vec![false; n], vec![false; n]);
    let mut start = 0;
    for &size in &plain.face_sizes {
        for &v in &plain.indices[start..start + size as usize] {
            if size == 4 {
                quads[v as usize] = true
            } else {
                triangles[v as usize] = true
            }
        }
        start += size as usize;
    }
    let centroid: [f64; 3] = (0..3)
        .map(|k| {
            plain.positions.iter().skip(k).step_by(3).map(|&x| x as f64).sum::<f64>() / n as f64
        })
        .collect::<Vec<_>>()
        .try_into()
        .unwrap();
    let (mut mixed, mut moved) = (0, 0);
    for v in 0..n {
        let (a, b) = (triple(result.positions(), v), triple(&plain.positions, v));
        if quads[v] && triangles[v] {
            mixed += 1;
            assert_eq!(a, b, "vertex {v}, where quads meet triangles, stays");
        } else if (0..3).any(|k| (a[k] - b[k]).abs() > 1e-6) {
            moved += 1;
        }
        let normal = triple(result.normals().unwrap(), v);
        let length = normal.iter().map(|x| x * x).sum::<f64>().sqrt();
        assert!((length - 1.0).abs() < 1e-5, "vertex {v}: {normal:?}");
        let outward: f64 = (0..3).map(|k| normal[k] * (a[k] - centroid[k])).sum();
        assert!(outward > 0.0, "vertex {v}: {normal:?} points inward");
    }
    assert!(mixed > 0 && moved > 0, "{mixed} mixed vertices, {moved} moved");
}
