//! The Doo-Sabin and √3 hosts write the next level's half-edge mesh by index arithmetic
//! (`dqq::child_mesh`, `sqrt3::child_mesh`). That mesh must be exactly the one the general
//! builder makes of the same faces (`HalfEdgeMesh::from_poly(&refine(..))`), array for array:
//! the next level's face order, face rotations and vertex sums (summation order) depend on the
//! child's edge numbering and vertex lists. Checked on closed and open meshes, n-gons, holes,
//! valence-2 vertices, isolated vertices, both Doo-Sabin boundary modes, both √3 boundary
//! levels, over several levels.

use std::path::Path;
use subsurf::refine::{dqq, sqrt3};
use subsurf::rules::{DooSabin, Sqrt3};
use subsurf::shapes::{
    cube, dodecahedron, grid, grid_with_hole, house, icosahedron, prism, sheet_with_holes, torus,
    torus_triangles, triangulate_quads,
};
use subsurf::{Boundary, HalfEdgeMesh, PolyMesh};

/// Stop descending when a level has more half-edges than this (debug builds are slow).
const MAX_HALF_EDGES: usize = 60_000;

fn poly(positions: &[f32], indices: &[u32], face_sizes: &[u32]) -> PolyMesh {
    PolyMesh {
        positions: positions.to_vec(),
        indices: indices.to_vec(),
        face_sizes: face_sizes.to_vec(),
    }
}

/// Small meshes with what the arithmetic must get right: valence-2 vertices (whose Doo-Sabin
/// face is left out, and whose √3 child would have repeated edges), isolated vertices, single
/// faces, corners of one face.
fn special_meshes() -> Vec<(String, PolyMesh)> {
    let tri = [0., 0., 0., 1., 0., 0., 0., 1., 0.];
    let quad = [0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.];
    // A cube whose edge 0-1 has a vertex in its middle: an interior vertex of valence 2.
    let mut cube_split = cube();
    cube_split.positions.extend_from_slice(&[0.0, -1.0, -1.0]);
    let mid = 8u32;
    let mut indices = Vec::new();
    let mut sizes = Vec::new();
    let mut start = 0usize;
    for &n in &cube_split.face_sizes {
        let face = &cube_split.indices[start..start + n as usize];
        let mut out = Vec::new();
        for (k, &a) in face.iter().enumerate() {
            out.push(a);
            let b = face[(k + 1) % face.len()];
            let (pa, pb) =
                (&cube_split.positions[3 * a as usize..], &cube_split.positions[3 * b as usize..]);
            let on_edge =
                (0..3).all(|i| (pa[i] + pb[i]) / 2.0 == cube_split.positions[3 * mid as usize + i]);
            if on_edge {
                out.push(mid);
            }
        }
        sizes.push(out.len() as u32);
        indices.extend(out);
        start += n as usize;
    }
    let cube_split = PolyMesh { positions: cube_split.positions, indices, face_sizes: sizes };
    let mut with_isolated = cube();
    with_isolated.positions.extend_from_slice(&[5.0, 5.0, 5.0]);
    let mut tris_isolated = icosahedron();
    tris_isolated.positions.splice(0..0, [9.0, 9.0, 9.0]);
    tris_isolated.indices.iter_mut().for_each(|i| *i += 1);
    vec![
        ("triangle".into(), poly(&tri, &[0, 1, 2], &[3])),
        ("quad".into(), poly(&quad, &[0, 1, 2, 3], &[4])),
        ("pillow_triangles".into(), poly(&tri, &[0, 1, 2, 0, 2, 1], &[3, 3])),
        ("pillow_quads".into(), poly(&quad, &[0, 1, 2, 3, 0, 3, 2, 1], &[4, 4])),
        ("two_triangles".into(), poly(&quad, &[0, 1, 2, 0, 2, 3], &[3, 3])),
        ("fan".into(), triangulate_quads(&grid(1, 1))),
        ("cube_split_edge".into(), cube_split),
        ("cube_isolated_vertex".into(), with_isolated),
        ("icosahedron_isolated_vertex".into(), tris_isolated),
    ]
}

fn meshes() -> Vec<(String, PolyMesh)> {
    let mut meshes: Vec<(String, PolyMesh)> = vec![
        ("cube".into(), cube()),
        ("torus".into(), torus(6, 5, 1.0, 0.3)),
        ("torus_triangles".into(), torus_triangles(6, 5, 1.0, 0.3)),
        ("grid".into(), grid(4, 3)),
        ("grid_triangles".into(), triangulate_quads(&grid(4, 3))),
        ("grid_hole".into(), grid_with_hole(6, 5, 2..4, 1..3)),
        ("grid_hole_triangles".into(), triangulate_quads(&grid_with_hole(6, 5, 2..4, 1..3))),
        ("prism".into(), prism(5)),
        ("icosahedron".into(), icosahedron()),
        ("dodecahedron".into(), dodecahedron()),
        ("sheet_with_holes".into(), sheet_with_holes()),
        ("house".into(), house()),
    ];
    meshes.extend(special_meshes());
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/meshes");
    for dir in [root.clone(), root.join("cgal"), root.join("osd"), root.join("osd_nonmanifold")] {
        let mut paths: Vec<_> = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .filter_map(|entry| entry.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|e| e == "obj"))
            .collect();
        paths.sort();
        for path in paths {
            let text = std::fs::read_to_string(&path).expect("test meshes are readable");
            if let Ok(mesh) = subsurf::io::read_obj(&text) {
                let name = path.file_stem().map(|s| s.to_string_lossy().into_owned());
                meshes.push((name.unwrap_or_default(), mesh));
            }
        }
    }
    meshes
}

/// Where two meshes differ, in the words of the public API (the full `Debug` is too long).
fn difference(ours: &HalfEdgeMesh, built: &HalfEdgeMesh) -> String {
    let counts =
        |m: &HalfEdgeMesh| (m.num_vertices(), m.num_edges(), m.num_half_edges(), m.num_cells());
    if counts(ours) != counts(built) {
        return format!("counts (V, E, H, F) {:?} vs {:?}", counts(ours), counts(built));
    }
    if ours.positions() != built.positions() {
        return "positions".into();
    }
    if ours.face_indices() != built.face_indices() {
        return "face indices".into();
    }
    for c in built.cell_indices() {
        let (a, b) =
            (ours.cell(c).map(|c| c.num_vertices()), built.cell(c).map(|c| c.num_vertices()));
        if a != b {
            return format!("cell {c} size {a:?} vs {b:?}");
        }
    }
    for v in built.vertex_indices() {
        let list = |m: &HalfEdgeMesh| -> Vec<u32> {
            m.vertex(v)
                .map(|v| v.half_edges_from().map(|h| h.index()).collect())
                .unwrap_or_default()
        };
        if list(ours) != list(built) {
            return format!("vertex {v} lists half-edges {:?} vs {:?}", list(ours), list(built));
        }
    }
    for e in 0..built.num_edges() as u32 {
        if ours.edge_vertices(e) != built.edge_vertices(e)
            || ours.edge_half_edges(e) != built.edge_half_edges(e)
        {
            return format!(
                "edge {e}: {:?} {:?} vs {:?} {:?}",
                ours.edge_vertices(e),
                ours.edge_half_edges(e),
                built.edge_vertices(e),
                built.edge_half_edges(e)
            );
        }
    }
    for h in built.half_edge_indices() {
        let around = |m: &HalfEdgeMesh| {
            m.half_edge(h).map(|h| (h.edge_index(), h.next_around_edge().index(), h.cell_index()))
        };
        if around(ours) != around(built) {
            return format!(
                "half-edge {h}: (edge, next around, cell) {:?} vs {:?}",
                around(ours),
                around(built)
            );
        }
    }
    format!(
        "flags: non-manifold edges {} vs {}, first non-manifold {:?} vs {:?}",
        ours.has_non_manifold_edges(),
        built.has_non_manifold_edges(),
        ours.first_non_manifold(),
        built.first_non_manifold()
    )
}

fn assert_same(what: &str, ours: &HalfEdgeMesh, built: &HalfEdgeMesh) {
    assert!(
        ours == built,
        "{what}: the arithmetic child mesh differs from the built one: {}",
        difference(ours, built)
    );
}

#[test]
fn doo_sabin_child_mesh_is_the_built_mesh() {
    let mut compared = 0;
    for (name, mesh) in meshes() {
        let base = HalfEdgeMesh::from_poly(&mesh).expect("test meshes are valid");
        for mode in [dqq::DualBoundary::Retract, dqq::DualBoundary::Chaikin] {
            let mut level = base.clone();
            for l in 1..=3 {
                if dqq::check(&level, "doo-sabin").is_err() || level.num_cells() == 0 {
                    // Never refined by `subdivide`; the general path must still not panic.
                    let _ = dqq::child_mesh(&level, &DooSabin, mode);
                    break;
                }
                let what = format!("{name} {mode:?} level {l}");
                let flat = dqq::refine(&level, &DooSabin, mode);
                let next = compare(&what, flat, dqq::child_mesh(&level, &DooSabin, mode));
                compared += 1;
                match next {
                    Some(next) => level = next,
                    None => break,
                }
            }
        }
    }
    println!("Doo-Sabin: {compared} child meshes compared");
    assert!(compared > 200, "only {compared} comparisons ran");
}

/// Asserts that a host's child mesh (`ours`) is the general builder's mesh of the same level's
/// flat arrays (`flat`), and returns it as the next level while it stays small enough to refine.
fn compare(
    what: &str,
    flat: PolyMesh,
    ours: subsurf::Result<HalfEdgeMesh>,
) -> Option<HalfEdgeMesh> {
    let built = HalfEdgeMesh::from_poly(&flat).unwrap_or_else(|e| panic!("{what}: {e}"));
    let ours = ours.unwrap_or_else(|e| panic!("{what}: {e}"));
    assert_same(what, &ours, &built);
    (ours.num_half_edges() <= MAX_HALF_EDGES).then_some(ours)
}

fn sqrt3_levels(name: &str, base: &HalfEdgeMesh, boundary: Boundary, pattern: &[bool]) -> usize {
    let rules = Sqrt3 { boundary };
    let mut level = base.clone();
    let mut compared = 0;
    for (l, &refine_boundary) in pattern.iter().enumerate() {
        let triangles = level.num_half_edges() == 3 * level.num_cells();
        if dqq::check(&level, "sqrt3").is_err() || !triangles || level.num_cells() == 0 {
            break;
        }
        let what =
            format!("{name} {boundary:?} level {} (refine boundary: {refine_boundary})", l + 1);
        let flat = sqrt3::refine(&level, &rules, refine_boundary);
        let next = compare(&what, flat, sqrt3::child_mesh(&level, &rules, refine_boundary));
        compared += 1;
        match next {
            Some(next) => level = next,
            None => break,
        }
    }
    compared
}

#[test]
fn sqrt3_child_mesh_is_the_built_mesh() {
    let mut compared = 0;
    for (name, mesh) in meshes() {
        let base = HalfEdgeMesh::from_poly(&mesh).expect("test meshes are valid");
        for boundary in [Boundary::EdgeAndCorner, Boundary::Fixed] {
            // A run of √3 levels (the boundary split every second level), and every pattern of
            // two levels: the public host takes any flag on any triangle mesh.
            compared += sqrt3_levels(&name, &base, boundary, &[false, true, false, true]);
            compared += sqrt3_levels(&name, &base, boundary, &[true, true]);
            compared += sqrt3_levels(&name, &base, boundary, &[true, false]);
            compared += sqrt3_levels(&name, &base, boundary, &[false, false]);
        }
    }
    println!("sqrt3: {compared} child meshes compared");
    assert!(compared > 200, "only {compared} comparisons ran");
}

/// A run of levels through `subdivide` (which uses the arithmetic child meshes between levels)
/// gives what refining level by level through the general builder gives.
#[test]
fn subdivide_equals_level_by_level_general_path() {
    use subsurf::{subdivide, Options, Scheme};
    for (name, mesh) in meshes() {
        let triangles = mesh.face_sizes.iter().all(|&n| n == 3);
        for (scheme, boundary) in [
            (Scheme::DooSabin, Boundary::None),
            (Scheme::DooSabin, Boundary::EdgeAndCorner),
            (Scheme::Sqrt3, Boundary::EdgeAndCorner),
            (Scheme::Sqrt3, Boundary::Fixed),
        ] {
            if scheme == Scheme::Sqrt3 && !triangles {
                continue;
            }
            let options = Options::new(scheme, 3).with_boundary(boundary);
            let Ok(result) = subdivide(&mesh, &options) else {
                continue;
            };
            let mut level = HalfEdgeMesh::from_poly(&mesh).expect("test meshes are valid");
            let mut poly = mesh.clone();
            for l in 0..3 {
                poly = match scheme {
                    Scheme::DooSabin => {
                        let mode = if boundary == Boundary::None {
                            dqq::DualBoundary::Retract
                        } else {
                            dqq::DualBoundary::Chaikin
                        };
                        dqq::refine(&level, &DooSabin, mode)
                    }
                    _ => sqrt3::refine(&level, &Sqrt3 { boundary }, l % 2 == 1),
                };
                if poly.positions.is_empty() {
                    break;
                }
                level = HalfEdgeMesh::from_poly(&poly).expect("a level of a valid mesh is valid");
            }
            assert!(
                result == poly,
                "{name} {scheme} {boundary:?}: subdivide differs from the general path"
            );
        }
    }
}
