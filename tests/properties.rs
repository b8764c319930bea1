//! Property tests on random valid meshes, for every scheme: the counts formulas hold (computed
//! here from our own edge count, not the library's), every result is a valid mesh without NaN,
//! the Euler characteristic is kept, and a second run gives identical bytes.
//!
//! `native_vs_wasm_fixture` also writes a set of seeded random meshes with their native results
//! to `artifacts/native-vs-wasm.json`; `tests/js/native_vs_wasm.mjs` runs the built npm package on
//! the same inputs and compares (scripts/test.sh runs both, in that order).

// Native only: proptest is a native dev-dependency, and the wasm runner does not run #[test]s.
#![cfg(not(target_arch = "wasm32"))]

use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, TestRunner};
use std::collections::HashMap;
use subsurf::{subdivide, Boundary, Options, PolyMesh, Scheme};

// ---------------------------------------------------------------------------------------------
// Random valid meshes

/// The shape of a random mesh before its positions are jittered.
#[derive(Clone, Copy, Debug)]
enum Kind {
    /// An open `a × b` grid.
    Grid,
    /// A closed `a × b` torus (`a`, `b` ≥ 3).
    Torus,
    /// A closed prism over an `a`-gon (`a` ≥ 3): two `a`-gons and `a` quads.
    Prism,
    /// An open fan of `a` triangles around a centre, or a closed cone over `a`-gon when `b` is
    /// even (a pyramid).
    Fan,
}

#[derive(Clone, Debug)]
struct Spec {
    kind: Kind,
    a: usize,
    b: usize,
    /// Bit `k` splits cell `k` into two triangles (grids and tori).
    split: u64,
    /// Reverse every face: the mesh stays consistently oriented.
    flip: bool,
    /// Per-vertex offsets in [-0.2, 0.2], cycled.
    noise: Vec<f32>,
    scale: f32,
    offset: [f32; 3],
}

fn spec() -> impl Strategy<Value = Spec> {
    (
        prop_oneof![Just(Kind::Grid), Just(Kind::Torus), Just(Kind::Prism), Just(Kind::Fan)],
        1usize..=5,
        1usize..=5,
        any::<u64>(),
        any::<bool>(),
        prop::collection::vec(-0.2f32..0.2, 3..48),
        prop_oneof![Just(1.0f32), 0.01f32..100.0],
        [-10.0f32..10.0, -10.0f32..10.0, -10.0f32..10.0],
    )
        .prop_map(|(kind, a, b, split, flip, noise, scale, offset)| Spec {
            kind,
            a,
            b,
            split,
            flip,
            noise,
            scale,
            offset,
        })
}

fn build(spec: &Spec) -> PolyMesh {
    let mut points: Vec<[f32; 3]> = Vec::new();
    let mut faces: Vec<Vec<u32>> = Vec::new();
    let tau = std::f32::consts::TAU;
    let quad = |faces: &mut Vec<Vec<u32>>, k: usize, q: [u32; 4]| {
        if spec.split >> (k % 64) & 1 == 1 {
            faces.push(vec![q[0], q[1], q[2]]);
            faces.push(vec![q[0], q[2], q[3]]);
        } else {
            faces.push(q.to_vec());
        }
    };
    match spec.kind {
        Kind::Grid => {
            let (nx, ny) = (spec.a, spec.b);
            for j in 0..=ny {
                for i in 0..=nx {
                    points.push([i as f32, j as f32, 0.0]);
                }
            }
            let at = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
            for j in 0..ny {
                for i in 0..nx {
                    quad(
                        &mut faces,
                        j * nx + i,
                        [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)],
                    );
                }
            }
        }
        Kind::Torus => {
            let (nu, nv) = (spec.a + 2, spec.b + 2);
            for i in 0..nu {
                for j in 0..nv {
                    let (u, v) = (tau * i as f32 / nu as f32, tau * j as f32 / nv as f32);
                    let r = 2.0 + 0.7 * v.cos();
                    points.push([r * u.cos(), r * u.sin(), 0.7 * v.sin()]);
                }
            }
            let at = |i: usize, j: usize| ((i % nu) * nv + j % nv) as u32;
            for i in 0..nu {
                for j in 0..nv {
                    quad(
                        &mut faces,
                        i * nv + j,
                        [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)],
                    );
                }
            }
        }
        Kind::Prism => {
            let n = spec.a + 2;
            for z in [0.0, 1.5] {
                for k in 0..n {
                    let t = tau * k as f32 / n as f32;
                    points.push([t.cos(), t.sin(), z]);
                }
            }
            let n32 = n as u32;
            faces.push((0..n32).rev().collect());
            faces.push((n32..2 * n32).collect());
            for k in 0..n32 {
                let next = (k + 1) % n32;
                quad(&mut faces, k as usize, [k, next, next + n32, k + n32]);
            }
        }
        Kind::Fan => {
            let n = spec.a + 2;
            let closed = spec.b.is_multiple_of(2);
            points.push([0.0, 0.0, 1.0]);
            for k in 0..n {
                let t = tau * k as f32 / n as f32;
                points.push([t.cos(), t.sin(), 0.0]);
            }
            let n32 = n as u32;
            let spokes = if closed { n32 } else { n32 - 1 };
            for k in 0..spokes {
                faces.push(vec![0, 1 + k, 1 + (k + 1) % n32]);
            }
            if closed {
                faces.push((1..=n32).rev().collect());
            }
        }
    }
    let mut positions = Vec::with_capacity(3 * points.len());
    for (v, p) in points.iter().enumerate() {
        for (k, (&x, &offset)) in p.iter().zip(&spec.offset).enumerate() {
            let jitter = spec.noise[(3 * v + k) % spec.noise.len()];
            positions.push((x + jitter) * spec.scale + offset);
        }
    }
    let mut indices = Vec::new();
    let mut face_sizes = Vec::new();
    for mut face in faces {
        if spec.flip {
            face.reverse();
        }
        face_sizes.push(face.len() as u32);
        indices.extend(face);
    }
    PolyMesh { positions, indices, face_sizes }
}

/// Every face fanned into triangles, for the schemes defined on triangles only.
fn triangulated(mesh: &PolyMesh) -> PolyMesh {
    let mut indices = Vec::new();
    let mut start = 0;
    for &n in &mesh.face_sizes {
        let face = &mesh.indices[start..start + n as usize];
        for k in 1..face.len() - 1 {
            indices.extend([face[0], face[k], face[k + 1]]);
        }
        start += n as usize;
    }
    let face_sizes = vec![3; indices.len() / 3];
    PolyMesh { positions: mesh.positions.clone(), indices, face_sizes }
}

fn input_for(scheme: Scheme, spec: &Spec) -> PolyMesh {
    let mesh = build(spec);
    if scheme.triangles_only() {
        triangulated(&mesh)
    } else {
        mesh
    }
}

// ---------------------------------------------------------------------------------------------
// Counting, independently of the library

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Counts {
    vertices: u64,
    edges: u64,
    faces: u64,
    corners: u64,
    triangles: u64,
    boundary_edges: u64,
    /// Vertices used by at least one face.
    used_vertices: u64,
}

fn counts(mesh: &PolyMesh) -> Counts {
    let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
    let mut used = vec![false; mesh.num_vertices()];
    let mut start = 0;
    for &n in &mesh.face_sizes {
        let face = &mesh.indices[start..start + n as usize];
        for k in 0..face.len() {
            let (a, b) = (face[k], face[(k + 1) % face.len()]);
            *edges.entry((a.min(b), a.max(b))).or_default() += 1;
            used[a as usize] = true;
        }
        start += n as usize;
    }
    Counts {
        vertices: mesh.num_vertices() as u64,
        edges: edges.len() as u64,
        faces: mesh.num_faces() as u64,
        corners: mesh.indices.len() as u64,
        triangles: mesh.face_sizes.iter().filter(|&&n| n == 3).count() as u64,
        boundary_edges: edges.values().filter(|&&n| n == 1).count() as u64,
        used_vertices: used.iter().filter(|&&u| u).count() as u64,
    }
}

fn euler(c: &Counts) -> i64 {
    c.vertices as i64 - c.edges as i64 + c.faces as i64
}

/// `(vertices, faces)` after one level of `scheme` on a mesh with counts `c`, from each scheme's
/// definition. `splits_boundary` is for √3's second level of a run, which trisects each boundary
/// edge (two new vertices) and splits its triangle into three towards the far corner instead of
/// adding a centroid: one vertex more per boundary edge, still three triangles per triangle.
fn one_level(scheme: Scheme, c: &Counts, splits_boundary: bool) -> (u64, u64) {
    match scheme {
        Scheme::CatmullClark | Scheme::Bilinear => (c.vertices + c.edges + c.faces, c.corners),
        Scheme::Loop | Scheme::Midpoint => (c.vertices + c.edges, 4 * c.faces),
        // Chaikin boundary: a corner point per corner, two points per boundary edge; a face per
        // face, per edge and per used vertex.
        Scheme::DooSabin => (c.corners + 2 * c.boundary_edges, c.faces + c.edges + c.used_vertices),
        Scheme::QuadTriangle => (
            c.vertices + c.edges + (c.faces - c.triangles),
            4 * c.triangles + (c.corners - 3 * c.triangles),
        ),
        Scheme::Sqrt3 if splits_boundary => (c.vertices + c.faces + c.boundary_edges, 3 * c.faces),
        Scheme::Sqrt3 => (c.vertices + c.faces, 3 * c.faces),
    }
}

fn face_size_ok(scheme: Scheme, n: u32) -> bool {
    match scheme {
        Scheme::CatmullClark | Scheme::Bilinear => n == 4,
        Scheme::Loop | Scheme::Midpoint | Scheme::Sqrt3 => n == 3,
        Scheme::QuadTriangle => n == 3 || n == 4,
        Scheme::DooSabin => n >= 3,
    }
}

// ---------------------------------------------------------------------------------------------
// The properties

fn options(scheme: Scheme, levels: u32) -> Options {
    Options::new(scheme, levels)
}

/// Checks one scheme on one random mesh, levels 1 and 2.
fn check_scheme(scheme: Scheme, spec: &Spec) -> Result<(), TestCaseError> {
    let input = input_for(scheme, spec);
    let c0 = counts(&input);
    let one = subdivide(&input, &options(scheme, 1))
        .map_err(|e| TestCaseError::fail(format!("level 1: {e}")))?;
    let two = subdivide(&input, &options(scheme, 2))
        .map_err(|e| TestCaseError::fail(format!("level 2: {e}")))?;
    let c1 = counts(&one);
    let c2 = counts(&two);
    let levels = [(1, &one, c0, c1, false), (2, &two, c1, c2, scheme == Scheme::Sqrt3)];
    for (level, out, before, after, splits_boundary) in levels {
        let (vertices, faces) = one_level(scheme, &before, splits_boundary);
        prop_assert_eq!(
            (after.vertices, after.faces),
            (vertices, faces),
            "{} level {}: counts from {:?}",
            scheme,
            level,
            before
        );
        prop_assert!(
            out.positions.iter().all(|x| x.is_finite()),
            "{} level {}: NaN",
            scheme,
            level
        );
        prop_assert!(
            out.face_sizes.iter().all(|&n| face_size_ok(scheme, n)),
            "{} level {}: face sizes {:?}",
            scheme,
            level,
            out.face_sizes
        );
        prop_assert!(
            subsurf::HalfEdgeMesh::from_poly(out).is_ok(),
            "{} level {}: the result is not a valid mesh",
            scheme,
            level
        );
        // Every scheme here keeps the topology of the surface: same V - E + F.
        prop_assert_eq!(
            euler(&after),
            euler(&c0),
            "{} level {}: Euler characteristic",
            scheme,
            level
        );
    }
    // Deterministic: a second run gives the same bytes.
    let again = subdivide(&input, &options(scheme, 2)).unwrap();
    prop_assert!(same_bytes(&two, &again), "{}: a second run differs", scheme);
    Ok(())
}

fn same_bytes(a: &PolyMesh, b: &PolyMesh) -> bool {
    a.indices == b.indices
        && a.face_sizes == b.face_sizes
        && a.positions.len() == b.positions.len()
        && a.positions.iter().zip(&b.positions).all(|(x, y)| x.to_bits() == y.to_bits())
}

const CASES: u32 = 256;

macro_rules! scheme_properties {
    ($($name:ident: $scheme:expr;)*) => {
        $(
            proptest! {
                #![proptest_config(Config { cases: CASES, failure_persistence: None, ..Config::default() })]
                #[test]
                fn $name(spec in spec()) {
                    check_scheme($scheme, &spec)?;
                }
            }
        )*
    };
}

scheme_properties! {
    catmull_clark: Scheme::CatmullClark;
    loop_subdivision: Scheme::Loop;
    doo_sabin: Scheme::DooSabin;
    quad_triangle: Scheme::QuadTriangle;
    sqrt3: Scheme::Sqrt3;
    bilinear: Scheme::Bilinear;
    midpoint: Scheme::Midpoint;
}

#[test]
fn every_scheme_has_a_property_test() {
    // The list above must grow with Scheme::ALL.
    assert_eq!(Scheme::ALL.len(), 7);
}

proptest! {
    #![proptest_config(Config { cases: CASES, failure_persistence: None, ..Config::default() })]
    /// Every boundary rule a scheme accepts gives a valid, finite result with the counts of
    /// the default rule (boundary rules move points, not topology), except Doo-Sabin's 'none',
    /// which drops the boundary faces, and Catmull-Clark/Loop's 'none', which makes holes.
    #[test]
    fn boundary_rules_move_points_not_topology(spec in spec(), pick in 0usize..7) {
        let scheme = Scheme::ALL[pick];
        let input = input_for(scheme, &spec);
        let reference = subdivide(&input, &options(scheme, 1)).unwrap();
        for &boundary in Boundary::ALL {
            match subdivide(&input, &options(scheme, 1).with_boundary(boundary)) {
                Ok(out) => {
                    prop_assert!(out.positions.iter().all(|x| x.is_finite()));
                    prop_assert!(subsurf::HalfEdgeMesh::from_poly(&out).is_ok());
                    if boundary != Boundary::None {
                        prop_assert_eq!(&out.face_sizes, &reference.face_sizes, "{} {}", scheme, boundary);
                        prop_assert_eq!(&out.indices, &reference.indices, "{} {}", scheme, boundary);
                    }
                }
                Err(e) => {
                    prop_assert!(boundary == Boundary::None, "{} refused {}: {}", scheme, boundary, e);
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(Config { cases: CASES, failure_persistence: None, ..Config::default() })]
    /// Random affine channels on random meshes, every scheme, two levels and every boundary
    /// rule: the channels come out as the same affine functions of the refined positions (the
    /// rules are affine, closed form), and the positions are those of a call without channels.
    #[test]
    fn affine_channels_follow_the_positions(
        spec in spec(),
        pick in 0usize..7,
        bound in 0usize..5,
        a in prop::array::uniform4(-2.0f32..2.0),
        b in prop::array::uniform4(-2.0f32..2.0),
    ) {
        let scheme = Scheme::ALL[pick];
        let input = input_for(scheme, &spec);
        let f = |p: &[f32]| [a[0] * p[0] + a[1] * p[1] + a[2] * p[2] + a[3], b[0] * p[0] + b[1] * p[1] + b[2] * p[2] + b[3]];
        let values: Vec<f32> = input.positions.chunks(3).flat_map(f).collect();
        let channels = [subsurf::attributes::Attribute::vertex("f", 2, values)];
        let options = options(scheme, 2).with_boundary(Boundary::ALL[bound]);
        let tags = subsurf::Tags::default();
        let plain = subdivide(&input, &options);
        match subsurf::scheme::subdivide_with_attributes(&input, &channels, &options, &tags) {
            Ok((out, refined)) => {
                prop_assert_eq!(Some(&out), plain.as_ref().ok());
                let scale = out.positions.iter().fold(1.0f32, |m, x| m.max(x.abs()));
                for (p, got) in out.positions.chunks(3).zip(refined[0].values.chunks(2)) {
                    let want = f(p);
                    for k in 0..2 {
                        prop_assert!((got[k] - want[k]).abs() <= 1e-4 * scale, "{} {:?}: {:?} vs {:?}", scheme, options.boundary, got, want);
                    }
                }
            }
            Err(e) => prop_assert_eq!(Some(e), plain.err()),
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Native vs wasm: the fixture

/// Where the fixture goes: `artifacts/` under the crate root (ignored by git).
fn fixture_path() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("artifacts/native-vs-wasm.json")
}

fn json_u32s(values: impl IntoIterator<Item = u32>) -> String {
    let items: Vec<String> = values.into_iter().map(|v| v.to_string()).collect();
    format!("[{}]", items.join(","))
}

/// Seeded random meshes (proptest's deterministic runner, so the same every run) through every
/// scheme at levels 1 and 2, with the native results, as JSON. Floats are written as their bit
/// patterns so that the wasm side gets exactly the same inputs.
#[test]
fn native_vs_wasm_fixture() {
    let mut runner = TestRunner::deterministic();
    let strategy = spec();
    let mut cases = Vec::new();
    for round in 0..10 {
        for (k, &scheme) in Scheme::ALL.iter().enumerate() {
            let spec = strategy.new_tree(&mut runner).unwrap().current();
            let input = input_for(scheme, &spec);
            let levels = 1 + (round + k) as u32 % 2;
            let boundary =
                [Boundary::EdgeAndCorner, Boundary::EdgeOnly, Boundary::Fixed, Boundary::Average]
                    [(round + 2 * k) % 4];
            let out = subdivide(&input, &options(scheme, levels).with_boundary(boundary))
                .unwrap_or_else(|e| panic!("{scheme} on {spec:?}: {e}"));
            let mesh = |m: &PolyMesh| {
                format!(
                    "{{\"positionBits\":{},\"indices\":{},\"faceSizes\":{}}}",
                    json_u32s(m.positions.iter().map(|x| x.to_bits())),
                    json_u32s(m.indices.iter().copied()),
                    json_u32s(m.face_sizes.iter().copied())
                )
            };
            cases.push(format!(
                "{{\"name\":\"{scheme} round {round}\",\"options\":{{\"scheme\":\"{scheme}\",\"levels\":{levels},\"boundary\":\"{boundary}\"}},\"input\":{},\"native\":{}}}",
                mesh(&input),
                mesh(&out)
            ));
        }
    }
    let path = fixture_path();
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    let json = format!("{{\"tolerance\":1e-6,\"cases\":[\n{}\n]}}\n", cases.join(",\n"));
    std::fs::write(&path, json).unwrap();
    assert_eq!(cases.len(), 10 * Scheme::ALL.len());
    // The same generator gives the same meshes on a second pass.
    let mut again = TestRunner::deterministic();
    let first = build(&strategy.new_tree(&mut again).unwrap().current());
    let mut runner = TestRunner::deterministic();
    assert_eq!(first, build(&strategy.new_tree(&mut runner).unwrap().current()));
}

// ---------------------------------------------------------------------------------------------
// Regressions found by fuzzing (fuzz/fuzz_targets/subdivide.rs)

/// One vertex and no faces: every scheme gives a result without error.
fn lone_vertex() -> PolyMesh {
    PolyMesh { positions: vec![0.0, 0.0, 0.0], indices: vec![], face_sizes: vec![] }
}

#[test]
fn one_level_of_every_scheme_on_a_mesh_without_faces() {
    for &scheme in Scheme::ALL {
        let out = subdivide(&lone_vertex(), &options(scheme, 1))
            .unwrap_or_else(|e| panic!("{scheme}: {e}"));
        assert_eq!(out.num_faces(), 0, "{scheme}");
        // Primal schemes keep the vertex; Doo-Sabin has a vertex per face corner: none.
        let expected = if scheme == Scheme::DooSabin { 0 } else { 1 };
        assert_eq!(out.num_vertices(), expected, "{scheme}");
    }
}

/// Found by the `subdivide` fuzz target: Doo-Sabin's first level makes a mesh without vertices,
/// and the second level then says "invalid mesh: positions is empty", about a mesh the caller
/// never gave. It should return the empty mesh again (or refuse with an `Unsupported` message
/// at level 1), never call a valid input invalid.
#[test]
fn doo_sabin_twice_on_a_mesh_without_faces() {
    for schemes in [vec![Scheme::DooSabin; 2], vec![Scheme::DooSabin, Scheme::CatmullClark]] {
        let options = Options { schemes: schemes.clone(), ..Options::default() };
        match subdivide(&lone_vertex(), &options) {
            Ok(out) => assert_eq!((out.num_vertices(), out.num_faces()), (0, 0), "{schemes:?}"),
            Err(subsurf::Error::Unsupported(_)) => {}
            Err(e) => panic!("{schemes:?}: a valid input gave {e}"),
        }
    }
}

/// Found by the `subdivide` fuzz target: two triangles on the same three vertices, facing
/// opposite ways (a closed "pillow"), pass the manifold check, but every vertex has valence 2,
/// and Doo-Sabin's face for a vertex has one corner per face around it: a 2-sided face. One
/// level returns it to the caller; a second level refuses the library's own result ("invalid
/// mesh: face 5 has 2 vertices"). The same happens at any interior vertex of valence 2. Doo-Sabin
/// should refuse such a vertex by name (`Unsupported`) or leave the 2-sided face out.
#[test]
fn doo_sabin_at_a_vertex_of_valence_two() {
    let pillow = PolyMesh {
        positions: vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0],
        indices: vec![0, 1, 2, 0, 2, 1],
        face_sizes: vec![3, 3],
    };
    for levels in [1, 2] {
        match subdivide(&pillow, &options(Scheme::DooSabin, levels)) {
            Ok(out) => assert!(
                out.face_sizes.iter().all(|&n| n >= 3),
                "level {levels}: faces of sizes {:?}",
                out.face_sizes
            ),
            Err(subsurf::Error::Unsupported(m)) => assert!(m.contains("vertex"), "{m}"),
            Err(e) => panic!("level {levels}: a valid input gave {e}"),
        }
    }
}

/// Found by the `subdivide` fuzz target: `predict_counts` promises an upper bound for Doo-Sabin,
/// but on an open mesh it undercounts the half-edges of the result (each boundary vertex's face
/// has two Chaikin corners besides its face corners), so the level after it is predicted too
/// small and the memory guard can let through more faces than `max_faces`. One triangle,
/// Doo-Sabin then Catmull-Clark: predicted 18 faces, made 24.
#[test]
fn prediction_after_doo_sabin_on_an_open_mesh() {
    let triangle = PolyMesh {
        positions: vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0],
        indices: vec![0, 1, 2],
        face_sizes: vec![3],
    };
    let options =
        Options { schemes: vec![Scheme::DooSabin, Scheme::CatmullClark], ..Options::default() };
    let base = subsurf::HalfEdgeMesh::from_poly(&triangle).unwrap();
    let (vertices, faces) = subsurf::scheme::predict_counts(&base, &options);
    let out = subdivide(&triangle, &options).unwrap();
    assert!(out.num_faces() as u64 <= faces, "predicted {faces} faces, made {}", out.num_faces());
    assert!(
        out.num_vertices() as u64 <= vertices,
        "predicted {vertices} vertices, made {}",
        out.num_vertices()
    );
    // The guard must refuse what it would otherwise let through.
    let guarded = Options { max_faces: out.num_faces() as u64 - 1, ..options };
    assert!(
        subdivide(&triangle, &guarded).is_err(),
        "max_faces let {} faces through",
        out.num_faces()
    );
}

/// Found by the `subdivide` fuzz target: Quad/Triangle's prediction takes the larger of "every
/// face a triangle" (4F) and "no face a triangle" (H), but a mesh of T triangles among other
/// polygons makes 4T + (H − 3T) = H + T faces, more than both when it mixes them. A triangle
/// and a pentagon: predicted 8 faces, made 9; so `max_faces = 8` does not refuse it. An upper
/// bound is H + F faces and V + E + F vertices.
#[test]
fn quad_triangle_prediction_on_a_triangle_and_a_pentagon() {
    let mesh = PolyMesh {
        positions: vec![
            0., 0., 0., 1., 0., 0., 0.5, -1., 0., 1.5, 1., 0., 0.5, 1.8, 0., -0.5, 1., 0.,
        ],
        indices: vec![0, 2, 1, 0, 1, 3, 4, 5],
        face_sizes: vec![3, 5],
    };
    let base = subsurf::HalfEdgeMesh::from_poly(&mesh).unwrap();
    for levels in [1, 2] {
        let options = options(Scheme::QuadTriangle, levels);
        let (vertices, faces) = subsurf::scheme::predict_counts(&base, &options);
        let out = subdivide(&mesh, &options).unwrap();
        assert!(
            out.num_faces() as u64 <= faces && out.num_vertices() as u64 <= vertices,
            "level {levels}: predicted {vertices} vertices and {faces} faces, made {} and {}",
            out.num_vertices(),
            out.num_faces()
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Face-varying channels with random seams

proptest! {
    #![proptest_config(Config { cases: CASES, failure_persistence: None, ..Config::default() })]
    /// Random meshes with random seams (random face corners get a value of their own), every
    /// scheme that refines face-varying channels and every mode, one or two levels: the indices
    /// are parallel to the result's and in range, nothing is NaN, a constant channel stays
    /// constant (every rule is affine), a channel without seams under mode `none` follows the
    /// positions as a vertex-varying one does (closed form: the same affine function of the
    /// refined positions), and at level 1 of the quad and triangle splits a seam stays a seam
    /// (corners that saw different values at a vertex see different values at its child).
    #[test]
    fn face_varying_channels_with_random_seams(
        spec in spec(),
        pick in 0usize..5,
        mode in 0usize..6,
        levels in 1u32..3,
        seams in any::<u64>(),
        a in prop::array::uniform4(-2.0f32..2.0),
    ) {
        use subsurf::attributes::Attribute;
        use subsurf::FVarLinear;
        let scheme = [Scheme::CatmullClark, Scheme::Loop, Scheme::QuadTriangle, Scheme::Bilinear, Scheme::Midpoint][pick];
        let mode = FVarLinear::ALL[mode];
        let input = input_for(scheme, &spec);
        let nv = input.num_vertices();
        // One value per vertex, then some corners get their own.
        let mut cut = input.indices.clone();
        let mut extra = 0u32;
        for (k, slot) in cut.iter_mut().enumerate() {
            if (seams >> (k % 61)) & 1 == 1 && (k / 61) % 2 == 0 {
                *slot = nv as u32 + extra;
                extra += 1;
            }
        }
        let values = nv + extra as usize;
        let constant = Attribute::face_varying("c", 2, [3.5f32, -1.25].repeat(values), cut.clone());
        let f = |p: &[f32]| a[0] * p[0] + a[1] * p[1] + a[2] * p[2] + a[3];
        let affine: Vec<f32> = input.positions.chunks(3).map(f).collect();
        let smooth = Attribute::face_varying("f", 1, affine, input.indices.clone());
        let options = options(scheme, levels).with_fvar_linear(mode);
        let tags = subsurf::Tags::default();
        let Ok((out, channels)) = subsurf::scheme::subdivide_with_attributes(&input, &[constant, smooth], &options, &tags) else {
            return Ok(());
        };
        for channel in &channels {
            let indices = channel.indices.as_ref().expect("face-varying");
            prop_assert_eq!(indices.len(), out.indices.len());
            prop_assert!(indices.iter().all(|&i| (i as usize) < channel.len()));
            prop_assert!(channel.values.iter().all(|x| x.is_finite()));
        }
        for c in channels[0].values.chunks(2) {
            prop_assert!((c[0] - 3.5).abs() < 1e-5 && (c[1] + 1.25).abs() < 1e-5, "{:?}", c);
        }
        if mode == FVarLinear::None {
            let scale = out.positions.iter().fold(1.0f32, |m, x| m.max(x.abs()));
            let f_indices = channels[1].indices.as_ref().unwrap();
            for (&v, &i) in out.indices.iter().zip(f_indices) {
                let want = f(&out.positions[3 * v as usize..3 * v as usize + 3]);
                let got = channels[1].values[i as usize];
                prop_assert!((got - want).abs() <= 1e-4 * scale, "{} {}: {} vs {}", scheme, levels, got, want);
            }
        }
        let split = match scheme {
            Scheme::CatmullClark | Scheme::Bilinear => Some(4),
            Scheme::Loop | Scheme::Midpoint => Some(3),
            _ => None,
        };
        if let (Some(n), 1) = (split, levels) {
            // The output corner at an old vertex, and the input corner it descends from.
            let pairs: Vec<(usize, usize)> = if n == 4 {
                (0..input.indices.len()).map(|h| (4 * h, h)).collect()
            } else {
                (0..input.indices.len()).map(|h| (3 * (4 * (h / 3) + h % 3) + h % 3, h)).collect()
            };
            let out_c = channels[0].indices.as_ref().unwrap();
            let mut seen: HashMap<(u32, u32), u32> = HashMap::new();
            for &(o, i) in &pairs {
                let v = out.indices[o];
                prop_assert_eq!(v, input.indices[i]);
                seen.insert((v, cut[i]), out_c[o]);
            }
            for (&(v, x), &value) in &seen {
                for (&(w, y), &other) in &seen {
                    if v == w && x != y {
                        prop_assert_ne!(value, other, "vertex {} values {} and {}", v, x, y);
                    }
                }
            }
        }
    }
}
