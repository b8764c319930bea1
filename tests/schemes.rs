//! Every scheme: counts formulas, Euler characteristic, weights, closed-form masks, per-level
//! lists and refusals. Expected values come from closed-form formulas named in each test.

mod common;

use common::*;
use subsurf::rules::{doo_sabin_weight, loop_beta, triangle_vertex_weight};
use subsurf::shapes::{
    cube, dodecahedron, grid, grid_with_hole, icosahedron, prism, torus, torus_triangles,
    triangulate_quads,
};
use subsurf::{subdivide, Boundary, Error, HalfEdgeMesh, Options, PolyMesh, Scheme};

fn run(
    mesh: &PolyMesh,
    scheme: Scheme,
    levels: u32,
    boundary: Boundary,
) -> subsurf::Result<PolyMesh> {
    subdivide(mesh, &Options::new(scheme, levels).with_boundary(boundary))
}

fn triangle_meshes() -> Vec<(&'static str, PolyMesh)> {
    vec![
        ("cube-triangulated", triangulate_quads(&cube())),
        ("torus-triangles", torus_triangles(6, 5, 2.0, 0.7)),
        ("icosahedron", icosahedron()),
        ("grid-triangulated", triangulate_quads(&grid(4, 3))),
        ("holed-grid-triangulated", triangulate_quads(&grid_with_hole(5, 5, 2..3, 1..3))),
    ]
}

fn is_closed(mesh: &PolyMesh) -> bool {
    boundary_half_edges(mesh) == 0
}

/// Loop and midpoint: V' = V + E, F' = 4F.
#[test]
fn triangle_split_counts() {
    for (name, mesh) in triangle_meshes() {
        let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
        for scheme in [Scheme::Loop, Scheme::Midpoint] {
            let out = run(&mesh, scheme, 1, Boundary::EdgeAndCorner).unwrap();
            assert_eq!(out.num_vertices(), he.num_vertices() + he.num_edges(), "{name} {scheme}");
            assert_eq!(out.num_faces(), 4 * he.num_cells(), "{name} {scheme}");
            assert!(out.face_sizes.iter().all(|&n| n == 3));
        }
    }
}

/// Doo-Sabin on closed meshes: V' = H (one point per face corner), F' = V + E + F.
#[test]
fn doo_sabin_counts_on_closed_meshes() {
    for (name, mesh) in sample_meshes().into_iter().filter(|(_, m)| is_closed(m)) {
        let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
        let out = run(&mesh, Scheme::DooSabin, 1, Boundary::EdgeAndCorner).unwrap();
        assert_eq!(out.num_vertices(), he.num_half_edges(), "{name}");
        assert_eq!(out.num_faces(), he.num_vertices() + he.num_edges() + he.num_cells(), "{name}");
    }
}

/// Quad/Triangle: V' = V + E + (non-triangle faces), F' = 4 (triangles) + Σ other sizes.
#[test]
fn quad_triangle_counts() {
    for (name, mesh) in sample_meshes() {
        let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
        let tris = mesh.face_sizes.iter().filter(|&&n| n == 3).count();
        let others: u32 = mesh.face_sizes.iter().filter(|&&n| n != 3).sum();
        let out = run(&mesh, Scheme::QuadTriangle, 1, Boundary::EdgeAndCorner).unwrap();
        let centroids = mesh.num_faces() - tris;
        assert_eq!(out.num_vertices(), he.num_vertices() + he.num_edges() + centroids, "{name}");
        assert_eq!(out.num_faces(), 4 * tris + others as usize, "{name}");
    }
}

/// Every scheme keeps the Euler characteristic, on every mesh it is defined on, with every
/// boundary mode it takes.
#[test]
fn euler_characteristic_is_kept_by_every_scheme() {
    let mut meshes = sample_meshes();
    meshes.extend(triangle_meshes());
    for (name, mesh) in meshes {
        let chi = euler_characteristic(&mesh);
        let triangles = mesh.face_sizes.iter().all(|&n| n == 3);
        for &scheme in Scheme::ALL {
            if scheme.triangles_only() && !triangles {
                continue;
            }
            let modes: &[Boundary] = match scheme {
                Scheme::DooSabin => &[Boundary::EdgeAndCorner, Boundary::None],
                _ => &[
                    Boundary::EdgeAndCorner,
                    Boundary::EdgeOnly,
                    Boundary::Fixed,
                    Boundary::Average,
                ],
            };
            for &mode in modes {
                for levels in 1..=2 {
                    let out = run(&mesh, scheme, levels, mode).unwrap();
                    assert_eq!(euler_characteristic(&out), chi, "{name} {scheme} {mode} L{levels}");
                    assert!(out.positions.iter().all(|x| x.is_finite()), "{name} {scheme}");
                }
            }
        }
    }
}

/// Weights sum to 1, checked two ways: the closed-form weight functions directly, and
/// translation invariance of every scheme (a stencil whose weights do not sum to 1 moves a
/// translated mesh by a different amount).
#[test]
fn stencil_weights_sum_to_one() {
    for n in 3..=16 {
        let sum: f64 = (0..n).map(|k| doo_sabin_weight(n, k) as f64).sum();
        assert!((sum - 1.0).abs() < 1e-6, "Doo-Sabin n={n}: {sum}");
    }
    let shift = [10.0f32, -7.0, 3.0];
    let mut meshes = sample_meshes();
    meshes.extend(triangle_meshes());
    for (name, mesh) in meshes {
        let triangles = mesh.face_sizes.iter().all(|&n| n == 3);
        let moved = PolyMesh {
            positions: mesh.positions.iter().enumerate().map(|(i, x)| x + shift[i % 3]).collect(),
            ..mesh.clone()
        };
        for &scheme in Scheme::ALL {
            if scheme.triangles_only() && !triangles {
                continue;
            }
            let a = run(&mesh, scheme, 1, Boundary::EdgeAndCorner).unwrap();
            let b = run(&moved, scheme, 1, Boundary::EdgeAndCorner).unwrap();
            let worst = a
                .positions
                .iter()
                .zip(&b.positions)
                .enumerate()
                .map(|(i, (x, y))| (y - x - shift[i % 3]).abs())
                .fold(0.0, f32::max);
            assert!(worst < 1e-4, "{name} {scheme}: translation changes the result by {worst}");
        }
    }
}

/// Textbook weights at regular and small valences: Loop's β(6) = 1/16 and β(3) = 3/16
/// (Loop 1987), Doo-Sabin's quad mask (9, 3, 1, 3)/16, and the Quad/Triangle triangle weight
/// a(6) = 1/4, which makes the averaging step reproduce Loop.
#[test]
fn textbook_weights() {
    assert!((loop_beta(6) - 1.0 / 16.0).abs() < 1e-7);
    assert!((loop_beta(3) - 3.0 / 16.0).abs() < 1e-7);
    let quad: Vec<f32> = (0..4).map(|k| doo_sabin_weight(4, k) * 16.0).collect();
    for (w, e) in quad.iter().zip([9.0, 3.0, 1.0, 3.0]) {
        assert!((w - e).abs() < 1e-5, "{quad:?}");
    }
    assert!((triangle_vertex_weight(6) - 0.25).abs() < 1e-7);
    for n in 3..12 {
        // a(n) = 1 - 2nβ(n): the averaging form of Loop's vertex rule.
        let a = triangle_vertex_weight(n);
        assert!((a - (1.0 - 2.0 * n as f32 * loop_beta(n))).abs() < 1e-6, "n={n}");
    }
}

/// Loop on a regular triangle grid reproduces the refinement masks of the three-direction
/// quartic box spline: vertex (10 v + Σ six neighbours)/16, edge 3/8 (a + b) + 1/8 (c + d).
#[test]
fn loop_reproduces_box_spline_masks_on_a_regular_grid() {
    let n = 6i32;
    let mut mesh = triangulate_quads(&grid(n as u32, n as u32));
    let index = |i: i32, j: i32| (j * (n + 1) + i) as usize;
    let mut seed = 99u32;
    for v in 0..mesh.num_vertices() {
        seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        mesh.positions[3 * v + 2] = (seed >> 8) as f32 / (1u32 << 24) as f32 - 0.5;
    }
    let z = |i: i32, j: i32| mesh.positions[3 * index(i, j) + 2];
    let inside = |i: i32, j: i32| i > 0 && j > 0 && i < n && j < n;
    // Lattice directions of the grid triangulation (quads split along (i,j)-(i+1,j+1)).
    let dirs = [(1, 0), (0, 1), (1, 1), (-1, 0), (0, -1), (-1, -1)];
    let out = run(&mesh, Scheme::Loop, 1, Boundary::EdgeAndCorner).unwrap();
    let mut checked = 0;
    for v in 0..out.num_vertices() {
        let [x, y, zz] = position(&out, v);
        let (ci, cj) = ((2.0 * x).round() as i32, (2.0 * y).round() as i32);
        let expected = if ci % 2 == 0 && cj % 2 == 0 {
            let (i, j) = (ci / 2, cj / 2);
            if !inside(i, j) {
                continue;
            }
            (10.0 * z(i, j) + dirs.iter().map(|(di, dj)| z(i + di, j + dj)).sum::<f32>()) / 16.0
        } else {
            let (p, q) =
                (((ci - 1).div_euclid(2), (cj - 1).div_euclid(2)), ((ci + 1) / 2, (cj + 1) / 2));
            let (p, q) = if ci % 2 == 0 {
                ((ci / 2, p.1), (ci / 2, q.1))
            } else if cj % 2 == 0 {
                ((p.0, cj / 2), (q.0, cj / 2))
            } else {
                (p, q)
            };
            // The two opposite corners are the common lattice neighbours of p and q.
            let common: Vec<(i32, i32)> = dirs
                .iter()
                .map(|(di, dj)| (p.0 + di, p.1 + dj))
                .filter(|r| dirs.iter().any(|(di, dj)| (q.0 + di, q.1 + dj) == *r))
                .collect();
            if common.iter().any(|&(i, j)| i < 0 || j < 0 || i > n || j > n) {
                continue;
            }
            // Interior edges only: an edge on the grid border is a boundary crease.
            let on_border =
                (p.0 == q.0 && (p.0 == 0 || p.0 == n)) || (p.1 == q.1 && (p.1 == 0 || p.1 == n));
            if on_border {
                continue;
            }
            assert_eq!(common.len(), 2, "edge {p:?}-{q:?}");
            0.375 * (z(p.0, p.1) + z(q.0, q.1))
                + 0.125 * (z(common[0].0, common[0].1) + z(common[1].0, common[1].1))
        };
        assert!((zz - expected).abs() < 1e-6, "child ({ci}, {cj}): {zz} vs box spline {expected}");
        checked += 1;
    }
    // (n-1)² interior vertices plus every interior edge: 3n² - 2n... counted from the grid.
    let interior_edges = (3 * n * n - 2 * n) as usize;
    assert_eq!(checked, ((n - 1) * (n - 1)) as usize + interior_edges);
}

/// Quad/Triangle's own rules (its host, [`subsurf::refine::quad_tri`], with
/// [`subsurf::rules::QuadTriangle`]) are Loop's on a manifold mesh of triangles, every boundary
/// rule: one level, vertex by vertex (the two hosts number child vertices alike). `subdivide`
/// runs Loop itself for Quad/Triangle on triangles (see
/// `quad_triangle_is_loop_on_every_triangle_mesh`), so this is where the triangle rules, which
/// mixed meshes use, are checked against Loop.
#[test]
fn quad_triangle_rules_are_loop_rules_on_triangles() {
    use subsurf::refine::quad_tri;
    use subsurf::rules::QuadTriangle;
    for mode in [Boundary::EdgeAndCorner, Boundary::EdgeOnly, Boundary::Fixed, Boundary::Average] {
        for (name, mesh) in triangle_meshes() {
            let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
            let qt = quad_tri::refine(&he, &QuadTriangle { boundary: mode });
            let lp = run(&mesh, Scheme::Loop, 1, mode).unwrap();
            assert_eq!((&qt.indices, &qt.face_sizes), (&lp.indices, &lp.face_sizes), "{name}");
            for (i, (p, q)) in qt.positions.iter().zip(&lp.positions).enumerate() {
                assert!((p - q).abs() < 1e-5, "{name} {mode}: coordinate {i}: {p} vs {q}");
            }
        }
    }
}

/// Quad/Triangle equals Loop on every mesh of triangles, non-manifold ones included (an edge
/// of three or more faces or two the same way, a vertex of several fans, a valence-2 vertex
/// inside a pillow): every all-triangle mesh under `tests/meshes/` and the generated ones,
/// levels 1 to 3, every boundary rule Quad/Triangle takes, result for result. (The driver runs
/// Loop's host and rules, tagged path included, for Quad/Triangle on triangles.)
#[test]
fn quad_triangle_is_loop_on_every_triangle_mesh() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/meshes");
    let mut meshes: Vec<(String, PolyMesh)> =
        triangle_meshes().into_iter().map(|(n, m)| (n.to_string(), m)).collect();
    for dir in [root.clone(), root.join("cgal"), root.join("osd"), root.join("osd_nonmanifold")] {
        let mut paths: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "obj"))
            .collect();
        paths.sort();
        for path in paths {
            let mesh = subsurf::io::read_obj(&std::fs::read_to_string(&path).unwrap()).unwrap();
            let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
            // Quad/Triangle refuses a face that repeats a vertex (tests/nonmanifold.rs).
            if mesh.face_sizes.iter().all(|&n| n == 3) && !he.has_repeated_corners() {
                let name = path.file_stem().unwrap().to_string_lossy().into_owned();
                meshes.push((name, mesh));
            }
        }
    }
    let non_manifold = meshes
        .iter()
        .filter(|(_, m)| HalfEdgeMesh::from_poly(m).unwrap().first_non_manifold().is_some())
        .count();
    assert!(meshes.len() >= 45 && non_manifold >= 3, "{} meshes", meshes.len());
    for (name, mesh) in &meshes {
        for mode in
            [Boundary::EdgeAndCorner, Boundary::EdgeOnly, Boundary::Fixed, Boundary::Average]
        {
            let levels = if mesh.num_faces() > 200 { 2 } else { 3 };
            for level in 1..=levels {
                let qt = run(mesh, Scheme::QuadTriangle, level, mode).unwrap();
                let lp = run(mesh, Scheme::Loop, level, mode).unwrap();
                assert!(qt == lp, "{name} {mode} level {level}: quad-triangle differs from loop");
            }
        }
    }
}

/// Quad/Triangle is Catmull-Clark on all-quad meshes and Loop on all-triangle meshes, with
/// boundaries (compared as sets of positions: the child order of later levels may differ).
#[test]
fn quad_triangle_reduces_to_catmull_clark_and_loop() {
    let sorted =
        |m: &PolyMesh| m.positions.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect::<Vec<_>>();
    for mode in [Boundary::EdgeAndCorner, Boundary::EdgeOnly, Boundary::Fixed, Boundary::Average] {
        for (name, mesh) in [
            ("grid", grid(3, 2)),
            ("torus", torus(6, 4, 2.0, 0.5)),
            ("holed", grid_with_hole(4, 4, 1..2, 1..3)),
        ] {
            let qt = run(&mesh, Scheme::QuadTriangle, 2, mode).unwrap();
            let cc = run(&mesh, Scheme::CatmullClark, 2, mode).unwrap();
            assert_same_points(&sorted(&qt), &sorted(&cc), 1e-5, &format!("{name} {mode}"));
        }
        for (name, mesh) in triangle_meshes() {
            let qt = run(&mesh, Scheme::QuadTriangle, 2, mode).unwrap();
            let lp = run(&mesh, Scheme::Loop, 2, mode).unwrap();
            assert_same_points(&sorted(&qt), &sorted(&lp), 1e-5, &format!("{name} {mode}"));
        }
    }
}

/// A list of schemes runs them level after level: the same as chaining single-level calls.
#[test]
fn per_level_scheme_lists() {
    let mesh = prism(5);
    let list = Options {
        schemes: vec![Scheme::DooSabin, Scheme::CatmullClark, Scheme::CatmullClark],
        ..Options::default()
    };
    let at_once = subdivide(&mesh, &list).unwrap();
    let step1 = run(&mesh, Scheme::DooSabin, 1, Boundary::EdgeAndCorner).unwrap();
    let chained = run(&step1, Scheme::CatmullClark, 2, Boundary::EdgeAndCorner).unwrap();
    assert_eq!(at_once, chained);
    assert_eq!(
        Scheme::parse_list("doo-sabin, catmull-clark").unwrap(),
        vec![Scheme::DooSabin, Scheme::CatmullClark]
    );
    let err = Scheme::parse_list("loop,cc").unwrap_err().to_string();
    assert!(err.contains("unknown scheme 'cc'") && err.contains("'quad-triangle'"), "{err}");
}

#[test]
fn triangle_schemes_refuse_other_faces() {
    for scheme in [Scheme::Loop, Scheme::Midpoint] {
        let err = run(&prism(5), scheme, 1, Boundary::EdgeAndCorner).unwrap_err();
        let msg = err.to_string();
        assert!(matches!(err, Error::Unsupported(_)));
        assert!(
            msg.contains("face 0")
                && msg.contains("5 vertices")
                && msg.contains("quad-triangle")
                && msg.contains("triangulate"),
            "{msg}"
        );
    }
    // After a Catmull-Clark level every face is a quad.
    let list = Options { schemes: vec![Scheme::CatmullClark, Scheme::Loop], ..Options::default() };
    let msg = subdivide(&triangulate_quads(&cube()), &list).unwrap_err().to_string();
    assert!(msg.contains("level 2") && msg.contains("previous level"), "{msg}");
    // Boundary 'none' is defined for Catmull-Clark, Loop and Doo-Sabin, not for √3.
    let msg =
        run(&triangulate_quads(&cube()), Scheme::Sqrt3, 1, Boundary::None).unwrap_err().to_string();
    assert!(msg.contains("'none' is defined for catmull-clark, loop and doo-sabin"), "{msg}");
}

#[test]
fn doo_sabin_refuses_non_manifold_meshes() {
    let positions = [0., 0., 0., 1., 0., 0., 0., 1., 0., 0., -1., 0., 0., 0., 1.];
    let fan = PolyMesh {
        positions: positions.to_vec(),
        indices: vec![0, 1, 2, 1, 0, 3, 0, 1, 4],
        face_sizes: vec![3; 3],
    };
    let msg = run(&fan, Scheme::DooSabin, 1, Boundary::EdgeAndCorner).unwrap_err().to_string();
    assert!(msg.contains("vertices 0 and 1") && msg.contains("manifold"), "{msg}");
    assert_eq!(msg.matches("unsupported input").count(), 1, "{msg}");
}

/// Doo-Sabin's two boundary modes on an open grid. Retract (CGAL): only faces of faces,
/// interior edges and interior vertices, F' = 9 + 12 + 4 on a 3×3 grid. Chaikin: the boundary
/// points are exactly the Chaikin points (3a + b)/4 and (a + 3b)/4 of the old boundary edges.
#[test]
fn doo_sabin_boundary_modes() {
    let mesh = grid(3, 3);
    let retract = run(&mesh, Scheme::DooSabin, 1, Boundary::None).unwrap();
    assert_eq!(retract.num_faces(), 9 + 12 + 4);
    assert_eq!(retract.num_vertices(), 36);
    let keep = run(&mesh, Scheme::DooSabin, 1, Boundary::EdgeAndCorner).unwrap();
    // 9 faces + 24 edges + 16 vertices, and 36 corners + 2 × 12 boundary points.
    assert_eq!((keep.num_faces(), keep.num_vertices()), (49, 60));
    let he = HalfEdgeMesh::from_poly(&keep).unwrap();
    let mut on_boundary: Vec<[i32; 2]> = he
        .vertex_indices()
        .filter(|&v| he.vertex(v).unwrap().is_boundary())
        .map(|v| {
            let [x, y, _] = he.vertex(v).unwrap().position();
            [(x * 4.0).round() as i32, (y * 4.0).round() as i32]
        })
        .collect();
    on_boundary.sort();
    let mut chaikin = Vec::new();
    for k in 0..3 {
        for t in [4 * k + 1, 4 * k + 3] {
            chaikin.extend_from_slice(&[[t, 0], [t, 12], [0, t], [12, t]]);
        }
    }
    chaikin.sort();
    assert_eq!(on_boundary, chaikin);
}

/// The procedural solids are closed 2-manifolds of genus 0 (χ = 2) with the textbook counts.
#[test]
fn procedural_solids() {
    for (name, mesh, v, f) in [
        ("icosahedron", icosahedron(), 12, 20),
        ("dodecahedron", dodecahedron(), 20, 12),
        ("cube", cube(), 8, 6),
    ] {
        let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
        assert_eq!((he.num_vertices(), he.num_cells()), (v, f), "{name}");
        assert_eq!(euler_characteristic(&mesh), 2, "{name}");
        assert!(is_closed(&mesh) && he.first_non_manifold().is_none(), "{name}");
        // Outward winding: the signed volume is positive.
        let p = |i: u32| position(&mesh, i as usize);
        let mut volume = 0.0f32;
        let mut start = 0usize;
        for &n in &mesh.face_sizes {
            let face = &mesh.indices[start..start + n as usize];
            for k in 1..face.len() - 1 {
                let (a, b, c) = (p(face[0]), p(face[k]), p(face[k + 1]));
                volume += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0]);
            }
            start += n as usize;
        }
        assert!(volume > 0.0, "{name}: faces wound inward");
    }
}

/// Quad/Triangle evaluates its averaging step on the parent mesh. Here the step is done the
/// long way, as the derivation states it: split linearly (midpoints and centroids), build the
/// refined mesh, and average every vertex over its refined one-ring. Both must agree, on mixed
/// meshes with n-gons, triangles, quads and boundaries.
#[test]
fn quad_triangle_equals_the_literal_two_step_construction() {
    for (name, mesh) in [
        ("prism7-mixed", triangulate_quads(&prism(7))),
        ("dodecahedron", dodecahedron()),
        ("mixed-grid", mixed_grid()),
    ] {
        let out = run(&mesh, Scheme::QuadTriangle, 1, Boundary::EdgeOnly).unwrap();
        let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
        // Linear positions in the child order [old | centroids of non-triangles | midpoints].
        let mut linear: Vec<[f32; 3]> = he.positions().to_vec();
        for c in he.cell_indices() {
            let corners = he.cell(c).unwrap().vertex_indices();
            if corners.len() != 3 {
                let mut sum = [0.0f32; 3];
                for &v in corners {
                    (0..3).for_each(|k| sum[k] += he.positions()[v as usize][k]);
                }
                linear.push(sum.map(|x| x / corners.len() as f32));
            }
        }
        for e in 0..he.num_edges() as u32 {
            let [a, b] = he.edge_vertices(e).unwrap();
            let (pa, pb) = (he.positions()[a as usize], he.positions()[b as usize]);
            linear.push([0, 1, 2].map(|k| (pa[k] + pb[k]) / 2.0));
        }
        let refined =
            HalfEdgeMesh::from_faces(linear.as_flattened(), &out.indices, &out.face_sizes).unwrap();
        for v in refined.vertex_indices() {
            let vertex = refined.vertex(v).unwrap();
            let p = glam::Vec3::from_array(vertex.position());
            let at = |w: u32| glam::Vec3::from_array(refined.positions()[w as usize]);
            let (mut n, mut quads, mut tris) = (0u32, 0u32, 0u32);
            let (mut nbrs, mut diag, mut boundary) =
                (glam::Vec3::ZERO, glam::Vec3::ZERO, glam::Vec3::ZERO);
            for h in vertex.half_edges_from() {
                n += 1;
                nbrs += at(h.to_vertex_index());
                if h.is_boundary() {
                    boundary += at(h.to_vertex_index());
                }
                if h.prev_in_cell().is_boundary() {
                    n += 1;
                    nbrs += at(h.prev_in_cell().from_vertex_index());
                    boundary += at(h.prev_in_cell().from_vertex_index());
                }
                if h.cell().num_vertices() == 4 {
                    quads += 1;
                    diag += at(h.next_in_cell().to_vertex_index());
                } else {
                    tris += 1;
                }
            }
            let nf = n as f32;
            let expected = if vertex.is_boundary() {
                p * 0.5 + boundary * 0.25
            } else if tris == 0 {
                p * ((nf - 3.0) / nf) + (nbrs * 2.0 + diag) / (nf * nf)
            } else if quads == 0 {
                let a = triangle_vertex_weight(n);
                p * a + nbrs * ((1.0 - a) / nf)
            } else {
                (p + nbrs * 0.5 + diag * 0.25) / (1.0 + 0.5 * nf + 0.25 * quads as f32)
            };
            let got = glam::Vec3::from_slice(&out.positions[3 * v as usize..]);
            assert!(
                (got - expected).length() < 1e-5,
                "{name} vertex {v}: {got} vs two-step {expected}"
            );
        }
    }
}

/// A 3×2 grid whose middle column of quads is split into triangles: quads, triangles and
/// vertices where both meet, with a boundary.
fn mixed_grid() -> PolyMesh {
    let g = grid(3, 2);
    let mut indices = Vec::new();
    let mut face_sizes = Vec::new();
    for (f, q) in g.indices.chunks_exact(4).enumerate() {
        if f % 3 == 1 {
            indices.extend_from_slice(&[q[0], q[1], q[2], q[0], q[2], q[3]]);
            face_sizes.extend_from_slice(&[3, 3]);
        } else {
            indices.extend_from_slice(q);
            face_sizes.push(4);
        }
    }
    PolyMesh { positions: g.positions, indices, face_sizes }
}
