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
    assert!(error_of(&tri, &[0, 1, 1], &[3]).contains("face 0 uses vertex 1 twice"));
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
    for (indices, sizes, expected) in [
        (vec![0, 1, 3], vec![3], "refers to vertex 3"),
        (vec![0, 1, 1], vec![3], "uses vertex 1 twice"),
        (vec![0, 1, 2], vec![4], "sum to 4"),
    ] {
        let message = match HalfEdgeMesh::from_vertices(tri.clone(), indices.clone(), &sizes) {
            Err(e) => e.to_string(),
            Ok(_) => String::new(),
        };
        assert!(message.contains(expected), "{message}");
        assert!(error_of(tri.as_flattened(), &indices, &sizes).contains(expected));
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
