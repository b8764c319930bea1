//! The half-edge mesh API of seed 002, and input validation.

use subsurf::mesh::NonManifold;
use subsurf::shapes::{cube, grid};
use subsurf::{Error, HalfEdgeMesh};

fn quad_strip() -> HalfEdgeMesh {
    // Two quads sharing edge 1-4:  3-4-5 / 0-1-2
    let positions = [0., 0., 0., 1., 0., 0., 2., 0., 0., 0., 1., 0., 1., 1., 0., 2., 1., 0.];
    HalfEdgeMesh::from_faces(&positions, &[0, 1, 4, 3, 1, 2, 5, 4], &[4, 4]).unwrap()
}

#[test]
fn counts_and_indices() {
    let m = HalfEdgeMesh::from_poly(&cube()).unwrap();
    assert_eq!(
        (m.num_vertices(), m.num_half_edges(), m.num_cells(), m.num_edges()),
        (8, 24, 6, 12)
    );
    assert_eq!(m.max_vertex_index(), Some(7));
    assert_eq!(m.max_half_edge_index(), Some(23));
    assert_eq!(m.max_cell_index(), Some(5));
    assert_eq!(m.vertex_indices().count(), 8);
    assert_eq!(m.cell_indices().count(), 6);
    assert!(m.vertex(8).is_none() && m.half_edge(24).is_none() && m.cell(6).is_none());
    let v = m.vertex(0).unwrap();
    assert_eq!((v.dimension(), v.coord(0), v.coord(3)), (3, Some(-1.0), None));
    // Every cube vertex has valence 3 and no boundary.
    for v in m.vertex_indices() {
        let v = m.vertex(v).unwrap();
        assert_eq!(v.num_half_edges_from(), 3);
        assert!(!v.is_boundary());
    }
    assert_eq!(m.first_non_manifold(), None);
}

#[test]
fn half_edge_navigation() {
    let m = quad_strip();
    let h = m.vertex(1).unwrap().find_half_edge_to(4).unwrap();
    assert_eq!((h.from_vertex_index(), h.to_vertex_index(), h.cell_index()), (1, 4, 0));
    assert_eq!(h.next_in_cell().to_vertex_index(), 3);
    assert_eq!(h.prev_in_cell().from_vertex_index(), 0);
    assert_eq!(h.next_in_cell().prev_in_cell().index(), h.index());
    let twin = h.next_around_edge();
    assert_eq!((twin.from_vertex_index(), twin.to_vertex_index(), twin.cell_index()), (4, 1, 1));
    assert_eq!(twin.next_around_edge().index(), h.index());
    assert_eq!(twin.edge_index(), h.edge_index());
    assert!(!h.is_boundary());
    // prev around the from-vertex: across the edge before h in its cell.
    let g = m.vertex(1).unwrap().find_half_edge_to(2).unwrap();
    assert_eq!(g.prev_around_from_vertex().index(), h.index());
    assert_eq!(m.vertex(1).unwrap().find_half_edge_to(3).map(|h| h.index()), None);
    assert_eq!(m.cell(1).unwrap().vertex_indices(), &[1, 2, 5, 4]);
    assert_eq!(m.cell(1).unwrap().half_edge().from_vertex_index(), 1);
    assert_eq!(m.num_edges(), 7);
}

/// Seed 002: "If some boundary half edge comes from the vertex, then KthHalfEdgeFrom(0) is a
/// boundary half edge."
#[test]
fn kth_half_edge_from_zero_is_boundary() {
    let m = HalfEdgeMesh::from_poly(&grid(3, 3)).unwrap();
    for v in m.vertex_indices() {
        let vertex = m.vertex(v).unwrap();
        let has_boundary_out = vertex.half_edges_from().any(|h| h.is_boundary());
        if has_boundary_out {
            assert!(vertex.kth_half_edge_from(0).unwrap().is_boundary(), "vertex {v}");
        }
        // On a boundary, half-edges from = edges - 1.
        let edges = vertex.half_edges_from().count()
            + vertex.half_edges_from().filter(|h| h.prev_in_cell().is_boundary()).count();
        assert_eq!(
            vertex.num_half_edges_from() + usize::from(vertex.is_boundary()),
            edges,
            "vertex {v}"
        );
    }
}

/// Seed 002 allows more than two half-edges around an edge: they form a cycle.
#[test]
fn non_manifold_edge_is_a_cycle() {
    // Three triangles on edge 0-1.
    let positions = [0., 0., 0., 1., 0., 0., 0., 1., 0., 0., -1., 0., 0., 0., 1.];
    let m = HalfEdgeMesh::from_faces(&positions, &[0, 1, 2, 1, 0, 3, 0, 1, 4], &[3, 3, 3]).unwrap();
    let h = m.vertex(0).unwrap().find_half_edge_to(1).unwrap();
    let mut cycle = vec![h.index()];
    let mut g = h.next_around_edge();
    while g.index() != h.index() {
        cycle.push(g.index());
        g = g.next_around_edge();
    }
    assert_eq!(cycle.len(), 3);
    assert_eq!(m.edge_half_edges(h.edge_index()).unwrap().len(), 3);
    assert!(matches!(m.first_non_manifold(), Some(NonManifold::Edge { from: 0, to: 1, .. })));
}

#[test]
fn non_manifold_vertex_is_found() {
    // Two triangles touching at vertex 0 only (a bow tie).
    let positions = [0., 0., 0., 1., 0., 0., 1., 1., 0., -1., 0., 0., -1., -1., 0.];
    let m = HalfEdgeMesh::from_faces(&positions, &[0, 1, 2, 0, 3, 4], &[3, 3]).unwrap();
    assert_eq!(m.first_non_manifold(), Some(NonManifold::Vertex { vertex: 0 }));
}

#[test]
fn add_cell_and_vertices() {
    let mut m = quad_strip();
    let c = m.add_cell(&[2, 6, 5]).unwrap();
    assert_eq!(c, 2);
    assert_eq!(m.num_vertices(), 7, "vertex 6 was created");
    m.set_coord(6, [3.0, 0.5, 0.0]).unwrap();
    assert_eq!(m.vertex(6).unwrap().position(), [3.0, 0.5, 0.0]);
    assert!(m.vertex(5).unwrap().find_half_edge_to(2).is_some());
    assert!(m.set_coord(9, [0.0; 3]).is_err());
    assert!(m.set_coord(0, [f32::NAN, 0.0, 0.0]).is_err());
    let first = m.add_vertices(2);
    assert_eq!((first, m.num_vertices()), (7, 9));
    assert_eq!(m.vertex(8).unwrap().num_half_edges_from(), 0);
    assert!(m.add_cell(&[0, 1]).is_err(), "a two-vertex cell is refused");
}

fn error_of(positions: &[f32], indices: &[u32], sizes: &[u32]) -> String {
    match HalfEdgeMesh::from_faces(positions, indices, sizes) {
        Err(Error::InvalidMesh(m)) => m,
        other => panic!("expected an invalid-mesh error, got {other:?}"),
    }
}

#[test]
fn validation_names_the_fault() {
    let tri = [0., 0., 0., 1., 0., 0., 0., 1., 0.];
    assert!(error_of(&tri[..8], &[0, 1, 2], &[3]).contains("multiple of 3"));
    assert!(error_of(&[], &[], &[]).contains("empty"));
    let mut nan = tri;
    nan[4] = f32::NAN;
    assert!(error_of(&nan, &[0, 1, 2], &[3]).contains("vertex 1 has coordinate y"));
    assert!(error_of(&tri, &[0, 1, 2], &[4]).contains("sum to 4"));
    assert!(error_of(&tri, &[0, 1, 2, 0, 1], &[3, 2]).contains("face 1 has 2 vertices"));
    let msg = error_of(&tri, &[0, 1, 7], &[3]);
    assert!(
        msg.contains("face 0") && msg.contains("indices[2]") && msg.contains("vertex 7"),
        "{msg}"
    );
    // A face may repeat a vertex (OpenSubdiv accepts it): not an error.
    assert!(HalfEdgeMesh::from_faces(&tri, &[0, 1, 1], &[3]).unwrap().has_repeated_corners());
}

/// `from_vertices` keeps the arrays it is given and builds the same mesh as `from_faces`, with
/// the same validation.
#[test]
fn from_vertices_is_from_faces_without_the_copies() {
    for poly in [cube(), grid(4, 3), subsurf::shapes::prism(6)] {
        let vertices: Vec<[f32; 3]> =
            poly.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
        let kept = HalfEdgeMesh::from_vertices(vertices, poly.indices.clone(), &poly.face_sizes);
        assert_eq!(kept.unwrap(), HalfEdgeMesh::from_poly(&poly).unwrap());
    }
    let tri = vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]];
    for (indices, sizes, expected) in
        [(vec![0, 1, 3], vec![3], "refers to vertex 3"), (vec![0, 1, 2], vec![4], "sum to 4")]
    {
        let message = match HalfEdgeMesh::from_vertices(tri.clone(), indices.clone(), &sizes) {
            Err(e) => e.to_string(),
            Ok(_) => String::new(),
        };
        assert!(message.contains(expected), "{message}");
        assert!(error_of(tri.as_flattened(), &indices, &sizes).contains(expected));
    }
}

/// Checks every invariant the module docs of `subsurf::mesh` promise, through the public API:
/// each half-edge is listed by its edge and its from-vertex, an edge's half-edges are ascending,
/// form its `next_around_edge` cycle and join its two vertices, a vertex lists a boundary
/// half-edge first when it has one, and no cell has two half-edges on one edge.
fn assert_valid(what: &str, m: &HalfEdgeMesh) {
    let mut listed = vec![0usize; m.num_half_edges()];
    for e in 0..m.num_edges() as u32 {
        let hs = m.edge_half_edges(e).unwrap();
        let [a, b] = m.edge_vertices(e).unwrap();
        assert!(!hs.is_empty(), "{what}: edge {e} has no half-edge");
        for (i, &h) in hs.iter().enumerate() {
            let he = m.half_edge(h).unwrap();
            listed[h as usize] += 1;
            assert_eq!(he.edge_index(), e, "{what}: half-edge {h}");
            assert_eq!(
                he.next_around_edge().index(),
                hs[(i + 1) % hs.len()],
                "{what}: cycle of {e}"
            );
            let ends = [he.from_vertex_index(), he.to_vertex_index()];
            assert!(ends == [a, b] || ends == [b, a], "{what}: half-edge {h} is not on edge {e}");
        }
    }
    assert!(listed.iter().all(|&n| n == 1), "{what}: every half-edge on exactly one edge");
    for c in m.cell_indices() {
        let cell = m.cell(c).unwrap();
        let mut h = cell.half_edge();
        let mut edges = Vec::new();
        for _ in 0..cell.num_vertices() {
            assert_eq!(h.cell_index(), c, "{what}");
            edges.push(h.edge_index());
            h = h.next_in_cell();
        }
        edges.sort_unstable();
        edges.dedup();
        assert_eq!(edges.len(), cell.num_vertices(), "{what}: cell {c} uses an edge twice");
    }
    let mut from = vec![0usize; m.num_half_edges()];
    for v in m.vertex_indices() {
        let vertex = m.vertex(v).unwrap();
        for h in vertex.half_edges_from() {
            assert_eq!(h.from_vertex_index(), v, "{what}");
            from[h.index() as usize] += 1;
        }
        if vertex.half_edges_from().any(|h| h.is_boundary()) {
            assert!(vertex.kth_half_edge_from(0).unwrap().is_boundary(), "{what}: vertex {v}");
        }
    }
    assert!(from.iter().all(|&n| n == 1), "{what}: every half-edge leaves one vertex");
}

fn edges_of(m: &HalfEdgeMesh) -> Vec<([u32; 2], Vec<u32>)> {
    (0..m.num_edges() as u32)
        .map(|e| (m.edge_vertices(e).unwrap(), m.edge_half_edges(e).unwrap().to_vec()))
        .collect()
}

/// A face that repeats a vertex, as OpenSubdiv's `Vtr` builds it: a half-edge from a vertex to
/// itself is an edge of its own, a vertex pair that one face uses twice gets an edge per use,
/// and those edges (with the shared one) are non-manifold; other faces share edges as usual.
#[test]
fn faces_that_repeat_a_vertex_split_their_edges_as_opensubdiv() {
    let positions = [0.0; 3 * 6];
    let build = |indices: &[u32], sizes: &[u32]| {
        let m = HalfEdgeMesh::from_faces(&positions, indices, sizes).unwrap();
        assert_valid(&format!("{indices:?}"), &m);
        m
    };
    // Triangle (0, 1, 1): 0→1, the degenerate 1→1 and 1→0, each an edge of its own.
    let m = build(&[0, 1, 1], &[3]);
    assert_eq!(edges_of(&m), vec![([0, 1], vec![0]), ([1, 1], vec![1]), ([1, 0], vec![2])]);
    assert!(m.has_repeated_corners() && m.has_non_manifold_edges());
    assert_eq!(m.first_repeated_corner(), Some((0, 1)));
    assert!(matches!(m.first_non_manifold(), Some(NonManifold::Edge { edge: 0, .. })));
    // Quad (0, 1, 0, 2): both pairs are used twice, so four edges.
    let m = build(&[0, 1, 0, 2], &[4]);
    assert_eq!(m.num_edges(), 4);
    assert_eq!(m.first_repeated_corner(), Some((0, 0)));
    // A later face shares the pair's first edge: triangle (0, 1, 2), then the quad (1, 0, 3, 0)
    // runs 1→0 on the triangle's edge and uses 0–3 twice.
    let m = build(&[0, 1, 2, 1, 0, 3, 0], &[3, 4]);
    let edges = edges_of(&m);
    assert_eq!(edges.len(), 6);
    assert_eq!(edges[0], ([0, 1], vec![0, 3]), "0–1 shared by both faces");
    assert_eq!(&edges[3..], &[([0, 3], vec![4]), ([3, 0], vec![5]), ([0, 1], vec![6])][..]);
    // A face that repeats a vertex in corners far apart (no pair twice, no degenerate edge):
    // the edges are the usual ones, and the vertex has two fans.
    let m = build(&[0, 1, 2, 0, 3, 4], &[6]);
    assert_eq!(m.num_edges(), 6);
    assert!(!m.has_non_manifold_edges());
    assert_eq!(m.first_non_manifold(), Some(NonManifold::Vertex { vertex: 0 }));
    // Closed up by two triangles, the same face is a sphere around a manifold vertex 0.
    let m = build(&[0, 1, 2, 0, 3, 4, 0, 2, 1, 0, 4, 3], &[6, 3, 3]);
    assert_eq!(m.num_edges(), 6);
    assert_eq!(m.first_non_manifold(), None);
    assert!(m.has_repeated_corners());
    // A face of more than eight corners takes the linear check: (0..6, 0, 1, 2, 3) uses the
    // pairs 0–1, 1–2 and 2–3 twice.
    let m = build(&[0, 1, 2, 3, 4, 5, 0, 1, 2, 3], &[10]);
    assert_eq!(m.num_edges(), 10);
    assert_eq!(m.first_repeated_corner(), Some((0, 0)));
}

/// The OpenSubdiv shapes with faces that repeat a vertex give valid meshes, and so do their
/// refined levels (the hosts keep the two halves of a degenerate edge apart).
#[test]
fn meshes_with_repeated_vertices_and_their_refinements_are_valid() {
    use subsurf::refine::{pqq, ptq};
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/meshes/osd_nonmanifold");
    for shape in ["catmark_nonman_edges", "catmark_nonman_quadpole8", "loop_nonman_edges"] {
        let text = std::fs::read_to_string(dir.join(format!("{shape}.obj"))).unwrap();
        let base = HalfEdgeMesh::from_poly(&subsurf::io::read_obj(&text).unwrap()).unwrap();
        assert!(base.has_repeated_corners(), "{shape}");
        assert_valid(shape, &base);
        let (mut quads, mut tris) = (base.clone(), base.clone());
        for level in 1..=2 {
            quads = pqq::child_mesh(&quads, pqq::refine_points(&quads, &subsurf::rules::Bilinear));
            assert_valid(&format!("{shape} quad split {level}"), &quads);
            assert!(!quads.has_repeated_corners() && quads.has_non_manifold_edges());
            if shape.starts_with("loop") {
                tris = ptq::child_mesh(&tris, ptq::refine_points(&tris, &subsurf::rules::Midpoint));
                assert_valid(&format!("{shape} triangle split {level}"), &tris);
                assert!(!tris.has_repeated_corners() && tris.has_non_manifold_edges());
            }
        }
    }
}

/// `set_positions` replaces the positions and nothing else, and refuses another vertex count or a
/// non-finite coordinate (naming it, as the builder does) without changing the mesh.
#[test]
fn set_positions_keeps_the_connectivity() {
    let mut mesh = HalfEdgeMesh::from_poly(&cube()).unwrap();
    let before = mesh.clone();
    let moved: Vec<[f32; 3]> = mesh.positions().iter().map(|p| [p[2], p[0], p[1] + 1.0]).collect();
    mesh.set_positions(moved.clone()).unwrap();
    assert_eq!(mesh.positions(), &moved[..]);
    assert_eq!(mesh.face_indices(), before.face_indices());
    let rebuilt = HalfEdgeMesh::from_faces(moved.as_flattened(), before.face_indices(), &[4; 6]);
    assert_eq!(mesh, rebuilt.unwrap(), "as if built with the new positions");

    let changed = mesh.clone();
    let short = mesh.set_positions(moved[..7].to_vec()).unwrap_err().to_string();
    assert!(short.contains("7 vertices") && short.contains("the mesh has 8"), "{short}");
    let mut nan = moved.clone();
    nan[5][2] = f32::INFINITY;
    let infinite = mesh.set_positions(nan).unwrap_err().to_string();
    assert!(infinite.contains("vertex 5 has coordinate z = inf"), "{infinite}");
    assert_eq!(mesh, changed, "a refused call changes nothing");
}

/// A fan's hub (an outgoing list longer than the build scans, so searched sorted) gets the edges
/// of the plain definition: one edge per vertex pair, numbered in the order of its lowest
/// half-edge, from that half-edge's ends, listing its half-edges ascending. Closed cones of
/// valence 150 as they are, with a fin (a third face on a spoke: non-manifold) and with a face
/// turned the other way round (two half-edges the same way on a spoke).
#[test]
fn a_hubs_edges_are_the_plain_definitions() {
    let n = 150u32;
    let mut cone = Vec::new();
    for i in 0..n {
        let (a, b) = (2 + i, 2 + (i + 1) % n);
        cone.extend([0, a, b, 1, b, a]);
    }
    let fin = [cone.clone(), vec![0, 2, n + 2]].concat();
    let mut turned = cone.clone();
    turned.swap(1, 2);
    for (what, indices) in [("cone", cone), ("fin", fin), ("turned", turned)] {
        let positions = vec![0.0; 3 * (n as usize + 3)];
        let sizes = vec![3; indices.len() / 3];
        let m = HalfEdgeMesh::from_faces(&positions, &indices, &sizes).unwrap();
        assert_valid(what, &m);
        let mut plain: Vec<([u32; 2], Vec<u32>)> = Vec::new();
        let mut edge_of = std::collections::BTreeMap::<(u32, u32), usize>::new();
        for (h, &a) in indices.iter().enumerate() {
            let b = indices[if h % 3 == 2 { h - 2 } else { h + 1 }];
            match edge_of.get(&(a.min(b), a.max(b))) {
                Some(&e) => plain[e].1.push(h as u32),
                None => {
                    edge_of.insert((a.min(b), a.max(b)), plain.len());
                    plain.push(([a, b], vec![h as u32]));
                }
            }
        }
        assert_eq!(edges_of(&m), plain, "{what}");
        assert_eq!(m.has_non_manifold_edges(), what != "cone", "{what}");
    }
}
