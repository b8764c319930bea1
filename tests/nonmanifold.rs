//! Non-manifold input, as OpenSubdiv treats it (see `src/rules/crease.rs`): non-manifold edges
//! (three or more faces, or two faces using the edge the same way) are infinitely sharp creases;
//! non-manifold vertices (on such an edge, or with several fans of faces) are infinitely sharp
//! corners, except along an interior non-manifold seam, where they follow the crease rule.
//!
//! Every row of `tests/fixtures/osd_nonmanifold/MANIFEST.tsv` (OpenSubdiv's non-manifold
//! regression shapes, `catmark_fan` and the `*nonman*` ones, made by
//! `tools/osd/make_fixtures.sh`) is compared with OpenSubdiv as in `tests/osd_agreement.rs`,
//! except the shapes with a face that repeats a vertex (`catmark_nonman_edges`,
//! `catmark_nonman_quadpole8`/`64`/`360`, `loop_nonman_edges`): OpenSubdiv accepts those
//! (a degenerate edge from a vertex to itself), our mesh builder refuses them by design, and the
//! test checks that it does, with the OBJ line.
//!
//! Also: no NaN and no panic on any of them at levels 1 to 3 under every boundary rule;
//! isolated vertices keep their index and position; degenerate (zero-area) faces are refined
//! like any other.

#[path = "common/osd.rs"]
mod osd;

use osd::{compare, read_manifest, root, Set};
use std::collections::BTreeSet;
use subsurf::io::read_obj_with_tags;
use subsurf::{subdivide, subdivide_with_tags, Boundary, Error, Options, PolyMesh, Scheme};

/// The shapes with a face that repeats a vertex, which our builder refuses.
const REPEATED_VERTEX_SHAPES: &[&str] = &[
    "catmark_nonman_edges",
    "catmark_nonman_quadpole360",
    "catmark_nonman_quadpole64",
    "catmark_nonman_quadpole8",
    "loop_nonman_edges",
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

#[test]
fn non_manifold_shapes_match_opensubdiv() {
    let dir = Set::NonManifold.dir();
    let filter = std::env::var("OSD_FIXTURE_FILTER").unwrap_or_default();
    let entries: Vec<_> =
        read_manifest(&dir).into_iter().filter(|e| e.fixture.contains(&filter)).collect();
    assert!(
        !filter.is_empty() || entries.len() >= 30,
        "too few rows in {}/MANIFEST.tsv",
        dir.display()
    );
    let (mut compared, mut refused, mut failures) = (0, BTreeSet::new(), Vec::new());
    let mut shapes = BTreeSet::new();
    for entry in &entries {
        let shape = shape_name(&entry.input);
        shapes.insert(shape.clone());
        if REPEATED_VERTEX_SHAPES.contains(&shape.as_str()) {
            // Refused by design, naming the line of the face.
            let text = std::fs::read_to_string(root().join(&entry.input)).unwrap();
            match read_obj_with_tags(&text) {
                Err(Error::Obj { line, message }) => {
                    assert!(line > 0 && message.contains("repeat a vertex"), "{shape}: {message}")
                }
                other => {
                    panic!("{shape}: expected the repeated vertex to be refused, got {other:?}")
                }
            }
            refused.insert(shape);
            continue;
        }
        compared += 1;
        if let Err(message) = compare(entry, scheme_of(&shape), Set::NonManifold) {
            failures.push(format!("{}: {message}", entry.label()));
        }
    }
    println!(
        "non-manifold: {} rows on {} shapes: {compared} compared, {} failed; refused (a face repeats a vertex): {}",
        entries.len(),
        shapes.len(),
        failures.len(),
        refused.iter().cloned().collect::<Vec<_>>().join(", ")
    );
    if filter.is_empty() {
        assert_eq!(refused.len(), REPEATED_VERTEX_SHAPES.len(), "every refused shape has fixtures");
    }
    assert!(failures.is_empty(), "disagree with OpenSubdiv:\n  {}", failures.join("\n  "));
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
        if REPEATED_VERTEX_SHAPES.contains(&shape.as_str()) {
            continue;
        }
        let obj = read_obj_with_tags(&std::fs::read_to_string(&path).unwrap()).unwrap();
        out.push((shape, obj.mesh, obj.tags));
    }
    assert!(out.len() >= 9);
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
