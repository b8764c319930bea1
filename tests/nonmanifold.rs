//! Non-manifold input, as OpenSubdiv treats it (see `src/rules/crease.rs`): non-manifold edges
//! (three or more faces, or two faces using the edge the same way) are infinitely sharp creases;
//! non-manifold vertices (on such an edge, or with several fans of faces) are infinitely sharp
//! corners, except along an interior non-manifold seam, where they follow the crease rule. A
//! face may repeat a vertex, as OpenSubdiv's `Vtr` allows (see `src/mesh/mod.rs`): a half-edge
//! from a vertex to itself is a degenerate edge of its own, a vertex pair one face uses twice
//! gets one edge per use, and all of those are non-manifold edges.
//!
//! Every row of `tests/fixtures/osd_nonmanifold/MANIFEST.tsv` (OpenSubdiv's non-manifold
//! regression shapes, `catmark_fan` and the `*nonman*` ones, tags used) and of
//! `tests/fixtures/osd_nonmanifold_untagged/MANIFEST.tsv` (the same shapes untagged under both
//! boundary modes, and with the bilinear and midpoint schemes), both made by
//! `tools/osd/make_fixtures.sh`, is compared with OpenSubdiv as in `tests/osd_agreement.rs`,
//! including the five shapes with a face that repeats a vertex (`catmark_nonman_edges`,
//! `catmark_nonman_quadpole8`/`64`/`360`, `loop_nonman_edges`). Doo-Sabin, √3 and
//! Quad/Triangle refuse those five, naming the face and the vertex.
//!
//! Also: no NaN and no panic on any of them at levels 1 to 3 under every boundary rule;
//! isolated vertices keep their index and position; degenerate (zero-area) faces are refined
//! like any other.

#[path = "common/osd.rs"]
mod osd;

use osd::{compare, our_scheme, read_manifest, root, Entry, Set};
use std::collections::BTreeSet;
use subsurf::io::{read_obj, read_obj_with_tags};
use subsurf::{
    subdivide, subdivide_with_tags, Boundary, Error, HalfEdgeMesh, Options, PolyMesh, Scheme,
};

/// The shapes with a face that repeats a vertex: OpenSubdiv's five, and ours
/// (`tools/osd/make_meshes.py repeated`: a degenerate edge as the only sharp edge at a vertex,
/// a shared edge that a split pair makes non-manifold, a vertex with only split edges, and a
/// vertex twice in one face far apart).
const REPEATED_VERTEX_SHAPES: &[&str] = &[
    "catmark_nonman_edges",
    "catmark_nonman_quadpole360",
    "catmark_nonman_quadpole64",
    "catmark_nonman_quadpole8",
    "loop_nonman_edges",
    "own_repeat_pair",
    "own_repeat_pole",
    "own_repeat_slit",
    "own_repeat_sphere",
];

fn shape_name(input: &str) -> String {
    std::path::Path::new(input).file_stem().unwrap().to_string_lossy().into_owned()
}

fn scheme_of(shape: &str) -> Scheme {
    if shape.starts_with("loop") {
        Scheme::Loop
    } else {
        Scheme::CatmullClark
    }
}

/// Compares the rows of `set` that `pick` gives a scheme to (`OSD_FIXTURE_FILTER` applies),
/// prints the counts under `label`, and fails listing every row that disagrees. Returns the
/// shapes compared; asserts that at least `min_rows` ran (unless filtered).
fn compare_rows(
    set: Set,
    label: &str,
    min_rows: usize,
    pick: impl Fn(&Entry) -> Option<Scheme>,
) -> BTreeSet<String> {
    let dir = set.dir();
    let filter = std::env::var("OSD_FIXTURE_FILTER").unwrap_or_default();
    let rows: Vec<(Entry, Scheme)> = read_manifest(&dir)
        .into_iter()
        .filter(|e| e.fixture.contains(&filter))
        .filter_map(|e| pick(&e).map(|scheme| (e, scheme)))
        .collect();
    assert!(
        !filter.is_empty() || rows.len() >= min_rows,
        "{label}: only {} rows in {}/MANIFEST.tsv, expected at least {min_rows}",
        rows.len(),
        dir.display()
    );
    let (mut failures, mut shapes) = (Vec::new(), BTreeSet::new());
    for (entry, scheme) in &rows {
        shapes.insert(shape_name(&entry.input));
        if let Err(message) = compare(entry, *scheme, set) {
            failures.push(format!("{}: {message}", entry.label()));
        }
    }
    println!(
        "{label}: {} of {} agree, on {} shapes ({} with a face that repeats a vertex)",
        rows.len() - failures.len(),
        rows.len(),
        shapes.len(),
        shapes.iter().filter(|s| REPEATED_VERTEX_SHAPES.contains(&s.as_str())).count()
    );
    assert!(
        failures.is_empty(),
        "{label}: {} of {} disagree with OpenSubdiv:\n  {}",
        failures.len(),
        rows.len(),
        failures.join("\n  ")
    );
    shapes
}

/// Every shape with a face that repeats a vertex is among `shapes` (when nothing is filtered).
fn assert_repeated_vertex_shapes_ran(shapes: &BTreeSet<String>) {
    if std::env::var("OSD_FIXTURE_FILTER").unwrap_or_default().is_empty() {
        for shape in REPEATED_VERTEX_SHAPES {
            assert!(shapes.contains(*shape), "no comparison ran on {shape}");
        }
    }
}

/// Tags used (creases, boundary mode): Catmull-Clark and Loop, levels 1 to 3.
#[test]
fn non_manifold_shapes_match_opensubdiv() {
    let shapes =
        compare_rows(Set::NonManifold, "non-manifold tagged", 51, |e| Some(our_scheme(&e.scheme)));
    assert_repeated_vertex_shapes_ran(&shapes);
}

/// Untagged, edge-and-corner and edge-only: Catmull-Clark and Loop, levels 1 to 3.
#[test]
fn untagged_non_manifold_shapes_match_opensubdiv() {
    let shapes = compare_rows(Set::NonManifoldUntagged, "non-manifold untagged", 102, |e| {
        matches!(e.scheme.as_str(), "catmark" | "loop").then(|| our_scheme(&e.scheme))
    });
    assert_repeated_vertex_shapes_ran(&shapes);
}

/// Bilinear (OpenSubdiv's bilinear scheme) on every shape and midpoint (OpenSubdiv's Loop
/// topology, positions interpolated as varying data) on the triangle shapes, levels 1 to 3.
#[test]
fn linear_schemes_match_opensubdiv_on_non_manifold_shapes() {
    let shapes =
        compare_rows(Set::NonManifoldUntagged, "non-manifold bilinear, midpoint", 63, |e| {
            matches!(e.scheme.as_str(), "bilinear" | "midpoint").then(|| our_scheme(&e.scheme))
        });
    assert_repeated_vertex_shapes_ran(&shapes);
}

/// Quad/Triangle is Loop on a mesh of triangles, non-manifold ones included: every Loop row
/// of both sets but those whose faces repeat a vertex (which Quad/Triangle refuses).
#[test]
fn quad_triangle_matches_opensubdiv_loop_on_non_manifold_triangle_shapes() {
    let loop_rows = |e: &Entry| {
        let shape = shape_name(&e.input);
        (e.scheme == "loop" && !REPEATED_VERTEX_SHAPES.contains(&shape.as_str()))
            .then_some(Scheme::QuadTriangle)
    };
    compare_rows(Set::NonManifold, "non-manifold tagged, quad-triangle", 9, loop_rows);
    compare_rows(Set::NonManifoldUntagged, "non-manifold untagged, quad-triangle", 18, loop_rows);
}

/// Doo-Sabin, √3 and Quad/Triangle cannot take a face that repeats a vertex: they refuse it,
/// naming the face and the vertex, and say what to use instead; Catmull-Clark, Loop, bilinear
/// and midpoint take the same meshes.
#[test]
fn schemes_without_repeated_vertices_refuse_them() {
    for shape in REPEATED_VERTEX_SHAPES {
        let path = root().join(format!("tests/meshes/osd_nonmanifold/{shape}.obj"));
        let mesh = read_obj(&std::fs::read_to_string(path).unwrap()).unwrap();
        let built = HalfEdgeMesh::from_poly(&mesh).unwrap();
        let (face, vertex) = built.first_repeated_corner().expect("a face repeats a vertex");
        assert!(built.has_repeated_corners(), "{shape}");
        // A degenerate edge or a pair used twice makes non-manifold edges; a vertex twice in
        // a face far apart (own_repeat_sphere) does not.
        assert_eq!(built.has_non_manifold_edges(), *shape != "own_repeat_sphere", "{shape}");
        let corners = osd::our_faces(&mesh)[face as usize];
        assert_eq!(corners.iter().filter(|&&v| v == vertex).count(), 2, "{shape} face {face}");
        let triangles = mesh.face_sizes.iter().all(|&n| n == 3);
        let mut refusing = vec![Scheme::DooSabin, Scheme::QuadTriangle];
        let mut accepting = vec![Scheme::CatmullClark, Scheme::Bilinear];
        if triangles {
            refusing.push(Scheme::Sqrt3);
            accepting.extend([Scheme::Loop, Scheme::Midpoint]);
        }
        for scheme in refusing {
            let message = match subdivide(&mesh, &Options::new(scheme, 1)) {
                Err(e @ Error::Unsupported(_)) => e.to_string(),
                other => panic!("{shape} {scheme}: expected Unsupported, got {other:?}"),
            };
            let expected = format!(
                "level 1: face {face} repeats vertex {vertex}; {scheme} needs faces with distinct vertices; use catmull-clark, loop or bilinear"
            );
            assert!(message.contains(&expected), "{shape}: {message}");
        }
        for scheme in accepting {
            let out = subdivide(&mesh, &Options::new(scheme, 2)).unwrap();
            assert!(out.positions.iter().all(|x| x.is_finite()), "{shape} {scheme}");
        }
    }
}

/// `own_repeat_sphere` lists vertex 0 twice in its hexagon, far apart; vertex 0 is an ordinary
/// vertex of valence 4. Its fixtures stop at level 1, where OpenSubdiv agrees; from level 2 on
/// OpenSubdiv 3.5 takes the wrong child faces around vertex 0 (see `tools/osd/make_fixtures.sh`,
/// `levels_of`). Here level 2 must be level 1 refined once more, as a mesh of its own (which
/// has no repeated vertex): the same positions, up to order.
#[test]
fn a_vertex_twice_in_one_face_refines_as_its_level_one_mesh() {
    let path = root().join("tests/meshes/osd_nonmanifold/own_repeat_sphere.obj");
    let sphere = read_obj(&std::fs::read_to_string(path).unwrap()).unwrap();
    let sorted = |m: &PolyMesh| {
        let mut points: Vec<[f32; 3]> =
            m.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
        points.sort_by(|a, b| a.partial_cmp(b).unwrap());
        points
    };
    for scheme in [Scheme::CatmullClark, Scheme::Bilinear] {
        let one = subdivide(&sphere, &Options::new(scheme, 1)).unwrap();
        let two = subdivide(&sphere, &Options::new(scheme, 2)).unwrap();
        let again = subdivide(&one, &Options::new(scheme, 1)).unwrap();
        assert_eq!(osd::our_faces(&two).len(), osd::our_faces(&again).len());
        for (p, q) in sorted(&two).iter().zip(&sorted(&again)) {
            let d = (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f32>().sqrt();
            assert!(d < 1e-6, "{scheme}: {p:?} vs {q:?}");
        }
    }
}

fn non_manifold_inputs() -> Vec<(String, PolyMesh, subsurf::Tags)> {
    let dir = root().join("tests/meshes/osd_nonmanifold");
    let mut paths: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "obj"))
        .collect();
    paths.sort();
    let mut out = Vec::new();
    for path in paths {
        let shape = shape_name(&path.to_string_lossy());
        let obj = read_obj_with_tags(&std::fs::read_to_string(&path).unwrap()).unwrap();
        out.push((shape, obj.mesh, obj.tags));
    }
    assert!(out.len() >= 18);
    out
}

#[test]
fn no_nan_and_no_panic_under_every_boundary_rule() {
    for (shape, mesh, tags) in non_manifold_inputs() {
        let scheme = scheme_of(&shape);
        for &boundary in Boundary::ALL {
            for levels in 1..=3 {
                let options = Options::new(scheme, levels).with_boundary(boundary);
                for tags in [&tags, &subsurf::Tags::default()] {
                    let out = subdivide_with_tags(&mesh, &options, tags)
                        .unwrap_or_else(|e| panic!("{shape} {boundary} L{levels}: {e}"));
                    assert!(
                        out.positions.iter().all(|x| x.is_finite()),
                        "{shape} {boundary} L{levels}: a coordinate is not finite"
                    );
                    // Isolated input vertices keep their index and position.
                    let used: BTreeSet<u32> = mesh.indices.iter().copied().collect();
                    for v in (0..mesh.num_vertices() as u32).filter(|v| !used.contains(v)) {
                        let v = v as usize;
                        assert_eq!(
                            &out.positions[3 * v..3 * v + 3],
                            &mesh.positions[3 * v..3 * v + 3],
                            "{shape}: isolated vertex {v}"
                        );
                    }
                }
            }
        }
    }
}

/// Three faces sharing one edge (a "book"): the shared edge is an infinitely sharp crease, so
/// its edge point is the midpoint, and its two vertices (non-manifold, with boundary edges) are
/// corners and stay. Quads for Catmull-Clark, triangles for Loop.
#[test]
fn an_edge_with_three_faces_is_a_sharp_crease_with_corner_ends() {
    let positions = vec![
        0., 0., 0., 0., 0., 1., // the shared edge 0-1
        1., 0., 0., 1., 0., 1., // page 1
        -1., 0., 0., -1., 0., 1., // page 2
        0., 1., 0., 0., 1., 1., // page 3
    ];
    let quads = PolyMesh {
        positions: positions.clone(),
        indices: vec![0, 2, 3, 1, 1, 5, 4, 0, 0, 6, 7, 1],
        face_sizes: vec![4; 3],
    };
    let triangles =
        PolyMesh { positions, indices: vec![0, 2, 1, 1, 4, 0, 0, 6, 1], face_sizes: vec![3; 3] };
    for (scheme, book) in [(Scheme::CatmullClark, quads), (Scheme::Loop, triangles)] {
        assert!(subsurf::HalfEdgeMesh::from_poly(&book).unwrap().has_non_manifold_edges());
        for levels in 1..=2 {
            let out = subdivide(&book, &Options::new(scheme, levels)).unwrap();
            assert_eq!(&out.positions[0..6], &book.positions[0..6], "{scheme}: corners stay");
            // The points along the shared edge stay on it, evenly spaced: (0, 0, k / 2^levels).
            let steps = 1 << levels;
            for k in 1..steps {
                let z = k as f32 / steps as f32;
                let on_edge = out
                    .positions
                    .chunks_exact(3)
                    .any(|p| p[0].abs() < 1e-6 && p[1].abs() < 1e-6 && (p[2] - z).abs() < 1e-6);
                assert!(on_edge, "{scheme} L{levels}: no point at (0, 0, {z}) on the shared edge");
            }
        }
    }
}

/// Two closed fans meeting at one vertex (two tetrahedra sharing a vertex, a "pinch"): the
/// vertex is a corner and stays, with and without tags.
#[test]
fn a_vertex_with_two_fans_stays() {
    // Vertex 0 at the origin; tetrahedron A above, B below.
    let positions = vec![
        0., 0., 0., 1., 0., 1., -1., 1., 1., -1., -1., 1., 1., 0., -1., -1., -1., -1., -1., 1., -1.,
    ];
    let tets = PolyMesh {
        positions,
        indices: vec![
            0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2, // A
            0, 5, 4, 0, 6, 5, 0, 4, 6, 4, 5, 6, // B
        ],
        face_sizes: vec![3; 8],
    };
    let he = subsurf::HalfEdgeMesh::from_poly(&tets).unwrap();
    assert!(!he.has_non_manifold_edges());
    assert!(he.first_non_manifold().is_some());
    for scheme in [Scheme::CatmullClark, Scheme::Loop] {
        for levels in 1..=2 {
            let out = subdivide(&tets, &Options::new(scheme, levels)).unwrap();
            assert_eq!(&out.positions[0..3], &[0.0, 0.0, 0.0], "{scheme} L{levels}");
            let tags = subsurf::Tags {
                creases: vec![subsurf::Crease { vertices: [1, 2], sharpness: 1.5 }],
                ..Default::default()
            };
            let tagged = subdivide_with_tags(&tets, &Options::new(scheme, levels), &tags).unwrap();
            assert_eq!(&tagged.positions[0..3], &[0.0, 0.0, 0.0], "{scheme} L{levels} tagged");
        }
    }
}

/// A degenerate (zero-area) face is valid input and refined like any other: no NaN, and the
/// output has the usual counts.
#[test]
fn degenerate_faces_are_refined() {
    // A quad whose four corners are collinear, next to an ordinary quad.
    let mesh = PolyMesh {
        positions: vec![0., 0., 0., 1., 0., 0., 2., 0., 0., 3., 0., 0., 0., 1., 0., 3., 1., 0.],
        indices: vec![0, 1, 2, 3, 0, 3, 5, 4],
        face_sizes: vec![4, 4],
    };
    for levels in 1..=3 {
        let out = subdivide(&mesh, &Options::new(Scheme::CatmullClark, levels)).unwrap();
        assert!(out.positions.iter().all(|x| x.is_finite()));
        assert_eq!(out.num_faces(), 8 * 4usize.pow(levels - 1));
    }
}

/// The public hosts of the schemes that refuse faces repeating a vertex (`subdivide` refuses
/// before they run) must not panic when called on such a mesh directly: whatever they return,
/// no panic, and a mesh with the expected counts.
#[test]
fn hosts_called_directly_on_repeated_vertices_do_not_panic() {
    use subsurf::refine::{dqq, quad_tri, sqrt3};
    use subsurf::rules::{DooSabin, QuadTriangle, Sqrt3};
    for shape in REPEATED_VERTEX_SHAPES {
        let path = root().join(format!("tests/meshes/osd_nonmanifold/{shape}.obj"));
        let mesh = read_obj(&std::fs::read_to_string(path).unwrap()).unwrap();
        let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
        let qt = quad_tri::refine(&he, &QuadTriangle { boundary: Boundary::EdgeOnly });
        let centroids = mesh.face_sizes.iter().filter(|&&n| n != 3).count();
        assert_eq!(qt.num_vertices(), he.num_vertices() + he.num_edges() + centroids, "{shape}");
        for mode in [dqq::DualBoundary::Retract, dqq::DualBoundary::Chaikin] {
            let _ = dqq::refine(&he, &DooSabin, mode);
            let _ = dqq::child_mesh(&he, &DooSabin, mode);
        }
        if mesh.face_sizes.iter().all(|&n| n == 3) {
            for refine_boundary in [false, true] {
                let rules = Sqrt3 { boundary: Boundary::EdgeAndCorner };
                let _ = sqrt3::refine(&he, &rules, refine_boundary);
                let _ = sqrt3::child_mesh(&he, &rules, refine_boundary);
            }
        }
    }
}
