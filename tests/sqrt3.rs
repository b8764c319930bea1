//! √3 subdivision (Kobbelt 2000, seed 001): counts, Euler characteristic, weights, the child
//! order, Kobbelt's boundary rule on every second level, and refusals. Agreement with CGAL is in
//! `tests/cgal_agreement.rs`.

mod common;

use common::*;
use subsurf::refine::sqrt3;
use subsurf::rules::{sqrt3_alpha, Sqrt3, Sqrt3Rules, Stencil};
use subsurf::scheme::predict_counts;
use subsurf::shapes::{
    cube, grid, grid_with_hole, icosahedron, torus_triangles, triangulate_quads,
};
use subsurf::{subdivide, Boundary, Error, HalfEdgeMesh, Options, PolyMesh, Scheme};

fn run(mesh: &PolyMesh, levels: u32) -> PolyMesh {
    subdivide(mesh, &Options::new(Scheme::Sqrt3, levels)).expect("sqrt3 runs")
}

fn closed_meshes() -> Vec<(&'static str, PolyMesh)> {
    vec![
        ("icosahedron", icosahedron()),
        ("cube-triangulated", triangulate_quads(&cube())),
        ("torus-triangles", torus_triangles(6, 5, 2.0, 0.7)),
    ]
}

fn open_meshes() -> Vec<(&'static str, PolyMesh)> {
    vec![
        ("grid-triangulated", triangulate_quads(&grid(4, 3))),
        ("holed-grid-triangulated", triangulate_quads(&grid_with_hole(5, 5, 2..3, 1..3))),
        (
            "single-triangle",
            PolyMesh {
                positions: vec![0., 0., 0., 1., 0., 0.1, 0.3, 0.9, -0.2],
                indices: vec![0, 1, 2],
                face_sizes: vec![3],
            },
        ),
    ]
}

fn point(mesh: &PolyMesh, v: u32) -> [f32; 3] {
    position(mesh, v as usize)
}

/// Boundary half-edge count of a triangle mesh: `2E - H`.
fn boundary_edges(mesh: &PolyMesh) -> usize {
    boundary_half_edges(mesh)
}

/// Closed meshes: V' = V + F and F' = 3F on every level.
#[test]
fn counts_on_closed_meshes() {
    for (name, mesh) in closed_meshes() {
        let (mut v, mut f) = (mesh.num_vertices(), mesh.num_faces());
        for levels in 1..=3 {
            let out = run(&mesh, levels);
            (v, f) = (v + f, 3 * f);
            assert_eq!((out.num_vertices(), out.num_faces()), (v, f), "{name} L{levels}");
            assert!(out.face_sizes.iter().all(|&n| n == 3), "{name}");
        }
    }
}

/// Open meshes: the first level adds the centroids only (V' = V + F); the second also splits
/// each boundary edge in three (V' = V + F + E_b); faces triple on every level.
#[test]
fn counts_on_open_meshes_follow_the_two_level_boundary_rhythm() {
    for (name, mesh) in open_meshes() {
        let one = run(&mesh, 1);
        assert_eq!(one.num_vertices(), mesh.num_vertices() + mesh.num_faces(), "{name}");
        assert_eq!(one.num_faces(), 3 * mesh.num_faces(), "{name}");
        assert_eq!(boundary_edges(&one), boundary_edges(&mesh), "{name}: L1 keeps the boundary");
        let two = run(&mesh, 2);
        let expected = one.num_vertices() + one.num_faces() + boundary_edges(&one);
        assert_eq!(two.num_vertices(), expected, "{name} L2");
        assert_eq!(two.num_faces(), 9 * mesh.num_faces(), "{name} L2");
        assert_eq!(boundary_edges(&two), 3 * boundary_edges(&mesh), "{name} L2");
    }
}

/// The predicted counts are the real ones, also for runs of √3 inside longer scheme lists.
#[test]
fn predicted_counts_are_exact() {
    let mut meshes = closed_meshes();
    meshes.extend(open_meshes());
    let lists: &[&[Scheme]] = &[
        &[Scheme::Sqrt3; 4],
        &[Scheme::Loop, Scheme::Sqrt3, Scheme::Sqrt3],
        &[Scheme::Sqrt3, Scheme::Loop, Scheme::Sqrt3, Scheme::Sqrt3, Scheme::Sqrt3],
    ];
    for (name, mesh) in meshes {
        let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
        for &list in lists {
            let options = Options { schemes: list.to_vec(), ..Options::default() };
            let out = subdivide(&mesh, &options).unwrap();
            let predicted = predict_counts(&he, &options);
            let actual = (out.num_vertices() as u64, out.num_faces() as u64);
            assert_eq!(predicted, actual, "{name} {list:?}");
            assert_eq!(euler_characteristic(&out), euler_characteristic(&mesh), "{name}");
        }
    }
}

#[test]
fn euler_characteristic_is_kept() {
    let mut meshes = closed_meshes();
    meshes.extend(open_meshes());
    for (name, mesh) in meshes {
        let chi = euler_characteristic(&mesh);
        for boundary in [Boundary::EdgeAndCorner, Boundary::Fixed] {
            for levels in 1..=4 {
                let options = Options::new(Scheme::Sqrt3, levels).with_boundary(boundary);
                let out = subdivide(&mesh, &options).unwrap();
                assert_eq!(euler_characteristic(&out), chi, "{name} {boundary} L{levels}");
                assert!(out.positions.iter().all(|x| x.is_finite()), "{name}");
            }
        }
    }
}

/// α(n) = (4 - 2cos(2π/n))/9: 1/3 at n = 6 (Kobbelt), (4 + 1)/9 at n = 3; and every stencil's
/// weights sum to 1: a constant field stays constant.
#[test]
fn weights() {
    assert!((sqrt3_alpha(6) - 1.0 / 3.0).abs() < 1e-7);
    assert!((sqrt3_alpha(3) - 5.0 / 9.0).abs() < 1e-7);
    assert!((sqrt3_alpha(4) - 4.0 / 9.0).abs() < 1e-7);
    let mut meshes = closed_meshes();
    meshes.extend(open_meshes());
    for (name, mesh) in meshes {
        let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
        for boundary in [Boundary::EdgeAndCorner, Boundary::Fixed] {
            let rules = Sqrt3 { boundary };
            let mut stencils: Vec<Stencil> = Vec::new();
            let mut record = |rule: &dyn Fn(&mut Stencil)| {
                let mut s = Stencil::default();
                rule(&mut s);
                stencils.push(s);
            };
            for v in he.vertex_indices() {
                record(&|w| rules.vertex_point(&he, v, false, w));
                record(&|w| rules.vertex_point(&he, v, true, w));
            }
            for f in he.cell_indices() {
                record(&|w| rules.face_point(&he, f, w));
            }
            for h in he.half_edge_indices() {
                if he.half_edge(h).unwrap().is_boundary() {
                    record(&|w| rules.boundary_point(&he, h, 0, w));
                    record(&|w| rules.boundary_point(&he, h, 1, w));
                }
            }
            for s in stencils {
                let total = s.total();
                assert!(
                    (total - 1.0).abs() < 1e-6,
                    "{name} {boundary}: a stencil's weights sum to {total}: {s:?}"
                );
            }
        }
    }
}

/// Child vertices `[old | centroids]` and child face `3c + k` = `(corner k of c, centroid across
/// corner k's half-edge, centroid of c)` on a closed mesh.
#[test]
fn child_order_on_a_closed_mesh() {
    let mesh = icosahedron();
    let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
    let out = sqrt3::refine(&he, &Sqrt3::default(), false);
    let v = mesh.num_vertices() as u32;
    for c in he.cell_indices() {
        let cell = he.cell(c).unwrap();
        let centroid = point(&out, v + c);
        let corners = cell.vertex_indices();
        let mean = corners.iter().fold([0.0f32; 3], |s, &i| {
            let p = point(&mesh, i);
            [s[0] + p[0] / 3.0, s[1] + p[1] / 3.0, s[2] + p[2] / 3.0]
        });
        assert!(distance(centroid, mean) < 1e-6, "centroid of face {c}");
        for k in 0..3u32 {
            let h = he.half_edge(3 * c + k).unwrap();
            let across = h.next_around_edge().cell_index();
            let face = &out.indices[(9 * c + 3 * k) as usize..(9 * c + 3 * k + 3) as usize];
            assert_eq!(face, [corners[k as usize], v + across, v + c], "face {c} corner {k}");
        }
    }
}

/// Level 1 keeps boundary vertices and edges; level 2 moves boundary vertex `s` between boundary
/// neighbours `t`, `r` to `(4t + 19s + 4r)/27` and puts `(q + 16t + 10s)/27` and
/// `(10t + 16s + r)/27` on boundary edge `t → s`.
#[test]
fn kobbelt_boundary_rule_on_every_second_level() {
    for (name, mesh) in open_meshes() {
        let one = run(&mesh, 1);
        let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
        for v in he.vertex_indices() {
            if he.vertex(v).unwrap().is_boundary() {
                assert_eq!(point(&one, v), point(&mesh, v), "{name}: L1 moved boundary vertex {v}");
            }
        }
        let he1 = HalfEdgeMesh::from_poly(&one).unwrap();
        let two = run(&mesh, 2);
        let he2 = HalfEdgeMesh::from_poly(&two).unwrap();
        let p = |v: u32| glam::Vec3::from_array(point(&one, v));
        // Walk each boundary half-edge t → s of level 1 with its neighbours q → t and s → r.
        let next_boundary = |v: u32| -> u32 {
            let h = he1.vertex(v).unwrap().kth_half_edge_from(0).unwrap();
            assert!(h.is_boundary());
            h.to_vertex_index()
        };
        for h in he1.half_edge_indices() {
            let h = he1.half_edge(h).unwrap();
            if !h.is_boundary() {
                continue;
            }
            let (t, s) = (h.from_vertex_index(), h.to_vertex_index());
            let r = next_boundary(s);
            let expected = (p(t) * 4.0 + p(s) * 19.0 + p(r) * 4.0) / 27.0;
            assert!(distance(point(&two, s), expected.to_array()) < 1e-5, "{name} vertex {s}");
            // The two new points on t → s are the boundary neighbours in between.
            let near_s = (p(t) * 10.0 + p(s) * 16.0 + p(r)) / 27.0;
            let hs = he2.vertex(s).unwrap();
            let incoming: Vec<u32> = he2
                .half_edge_indices()
                .filter(|&g| {
                    let g = he2.half_edge(g).unwrap();
                    g.is_boundary() && g.to_vertex_index() == s
                })
                .map(|g| he2.half_edge(g).unwrap().from_vertex_index())
                .collect();
            assert_eq!(incoming.len(), 1, "{name}: one boundary edge into {s}");
            let found = point(&two, incoming[0]);
            assert!(distance(found, near_s.to_array()) < 1e-5, "{name}: point on {t}→{s}");
            assert!(hs.is_boundary());
        }
    }
}

/// `fixed` keeps every old boundary vertex in place and puts new boundary points on the old
/// boundary edges.
#[test]
fn fixed_boundary_keeps_the_boundary_polygon() {
    for (name, mesh) in open_meshes() {
        let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
        let options = Options::new(Scheme::Sqrt3, 2).with_boundary(Boundary::Fixed);
        let out = subdivide(&mesh, &options).unwrap();
        for v in he.vertex_indices() {
            if he.vertex(v).unwrap().is_boundary() {
                assert_eq!(point(&out, v), point(&mesh, v), "{name} vertex {v}");
            }
        }
        assert_eq!(boundary_edges(&out), 3 * boundary_edges(&mesh), "{name}");
    }
}

#[test]
fn refuses_other_faces_and_non_manifold_meshes() {
    let quads = subdivide(&cube(), &Options::new(Scheme::Sqrt3, 1));
    match quads {
        Err(Error::Unsupported(message)) => {
            assert!(message.contains("triangles only"), "{message}")
        }
        other => panic!("quads: {other:?}"),
    }
    // Three triangles on one edge.
    let fin = PolyMesh {
        positions: vec![0., 0., 0., 1., 0., 0., 0., 1., 0., 0., -1., 0., 0., 0., 1.],
        indices: vec![0, 1, 2, 1, 0, 3, 0, 1, 4],
        face_sizes: vec![3, 3, 3],
    };
    match subdivide(&fin, &Options::new(Scheme::Sqrt3, 1)) {
        Err(Error::Unsupported(message)) => assert!(message.contains("manifold"), "{message}"),
        other => panic!("non-manifold edge: {other:?}"),
    }
}

/// The host itself takes anything the mesh builder accepts (quads, fins, bowties) without
/// panicking, and its output is a valid mesh.
#[test]
fn host_never_panics_on_valid_meshes() {
    let bowtie = PolyMesh {
        positions: vec![0., 0., 0., 1., -1., 0., 1., 1., 0., -1., 1., 0., -1., -1., 0.],
        indices: vec![0, 1, 2, 0, 3, 4],
        face_sizes: vec![3, 3],
    };
    let fin = PolyMesh {
        positions: vec![0., 0., 0., 1., 0., 0., 0., 1., 0., 0., -1., 0., 0., 0., 1.],
        indices: vec![0, 1, 2, 1, 0, 3, 0, 1, 4],
        face_sizes: vec![3, 3, 3],
    };
    for (name, mesh) in [("cube", cube()), ("bowtie", bowtie), ("fin", fin)] {
        let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
        for refine_boundary in [false, true] {
            let out = sqrt3::refine(&he, &Sqrt3::default(), refine_boundary);
            assert!(HalfEdgeMesh::from_poly(&out).is_ok(), "{name} {refine_boundary}");
            assert!(out.positions.iter().all(|x| x.is_finite()), "{name}");
        }
    }
    // A √3 level after a Loop level: the run rule splits the boundary on the second √3 level.
    let grid = triangulate_quads(&grid(3, 3));
    let options =
        Options { schemes: vec![Scheme::Loop, Scheme::Sqrt3, Scheme::Sqrt3], ..Options::default() };
    let out = subdivide(&grid, &options).unwrap();
    assert_eq!(boundary_edges(&out), 3 * 2 * boundary_edges(&grid));
}
