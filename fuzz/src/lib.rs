//! Checks shared by the fuzz targets: what every accepted mesh, every result and every error
//! must satisfy. A failed check panics, which libFuzzer reports as a crash.

use subsurf::{Error, HalfEdgeMesh, PolyMesh};

/// The most vertices, faces and indices a fuzzed mesh gets, so that one execution stays fast.
pub const MAX_ELEMENTS: usize = 64;

/// The memory guard the targets use: a few thousand faces at most per execution.
pub const MAX_FACES: u64 = 4096;

/// An independent statement of what `HalfEdgeMesh::from_faces` accepts: coordinates within
/// ±`MAX_COORDINATE` (so finite). A face may repeat a vertex (OpenSubdiv accepts such faces).
pub fn is_valid(positions: &[f32], indices: &[u32], face_sizes: &[u32]) -> bool {
    is_valid_within(positions, indices, face_sizes, subsurf::mesh::MAX_COORDINATE)
}

/// [`is_valid`] with coordinates bounded by `bound` instead.
fn is_valid_within(positions: &[f32], indices: &[u32], face_sizes: &[u32], bound: f32) -> bool {
    if positions.is_empty() || !positions.len().is_multiple_of(3) {
        return false;
    }
    if !positions.iter().all(|x| x.abs() <= bound) {
        return false;
    }
    let vertices = positions.len() / 3;
    if face_sizes.iter().map(|&n| n as u64).sum::<u64>() != indices.len() as u64 {
        return false;
    }
    let mut start = 0;
    for &n in face_sizes {
        let face = &indices[start..start + n as usize];
        if n < 3 || face.iter().any(|&i| i as usize >= vertices) {
            return false;
        }
        start += n as usize;
    }
    true
}

/// True when some face lists a vertex twice.
pub fn repeats_a_vertex(mesh: &PolyMesh) -> bool {
    let mut start = 0;
    mesh.face_sizes.iter().any(|&n| {
        let face = &mesh.indices[start..start + n as usize];
        start += n as usize;
        (1..face.len()).any(|k| face[..k].contains(&face[k]))
    })
}

/// A subdivision result: a well-formed polygon mesh whose faces never repeat a vertex (every
/// scheme's faces join distinct points, even when the input's faces repeat one).
pub fn check_result(mesh: &PolyMesh, what: &str) {
    check_poly(mesh, what);
    assert!(!repeats_a_vertex(mesh), "{what}: a face of the result repeats a vertex");
}

/// A well-formed polygon mesh with finite coordinates: what every result and every accepted OBJ
/// file must be. (A result is not held to `MAX_COORDINATE`: a rule with a negative weight may
/// pass it a little.)
pub fn check_poly(mesh: &PolyMesh, what: &str) {
    assert!(
        is_valid_within(&mesh.positions, &mesh.indices, &mesh.face_sizes, f32::MAX),
        "{what}: not a valid mesh: {} positions, {} indices, sizes {:?}",
        mesh.positions.len(),
        mesh.indices.len(),
        mesh.face_sizes
    );
    HalfEdgeMesh::from_poly(mesh).unwrap_or_else(|e| panic!("{what}: from_poly refused it: {e}"));
}

/// An error must say something. (Its text may quote the input, so nothing in it is forbidden.)
pub fn check_error(error: &Error, what: &str) {
    let message = error.to_string();
    assert!(message.len() > 16, "{what}: message too short: {message:?}");
}

/// The connectivity the half-edge mesh promises, through its public query API.
pub fn check_connectivity(mesh: &HalfEdgeMesh) {
    for h in mesh.half_edge_indices() {
        let he = mesh.half_edge(h).unwrap();
        assert_eq!(he.next_in_cell().prev_in_cell().index(), h);
        assert_eq!(he.next_in_cell().from_vertex_index(), he.to_vertex_index());
        assert_eq!(he.next_in_cell().cell_index(), he.cell_index());
        // The half-edges around an edge form a cycle through h, all on the same vertex pair.
        let pair = |x: &subsurf::mesh::HalfEdgeRef| {
            let (a, b) = (x.from_vertex_index(), x.to_vertex_index());
            (a.min(b), a.max(b))
        };
        let mut around = he.next_around_edge();
        let mut steps = 1;
        while around.index() != h {
            assert_eq!(pair(&around), pair(&he), "half-edge {h}: edge cycle leaves its edge");
            assert_eq!(around.edge_index(), he.edge_index());
            around = around.next_around_edge();
            steps += 1;
            assert!(steps <= mesh.num_half_edges(), "half-edge {h}: edge cycle does not close");
        }
        assert_eq!(he.is_boundary(), steps == 1);
        // No cell has two half-edges on one edge (a face that uses a pair twice gets an edge
        // per use, as OpenSubdiv builds it).
        let mut g = he.next_in_cell();
        while g.index() != h {
            assert_ne!(
                g.edge_index(),
                he.edge_index(),
                "half-edge {h}: its cell uses its edge twice"
            );
            g = g.next_in_cell();
        }
    }
    for v in mesh.vertex_indices() {
        let vertex = mesh.vertex(v).unwrap();
        let n = vertex.num_half_edges_from();
        assert_eq!(vertex.half_edges_from().count(), n);
        assert!(vertex.half_edges_from().all(|h| h.from_vertex_index() == v));
        if vertex.half_edges_from().any(|h| h.is_boundary()) {
            assert!(vertex.kth_half_edge_from(0).unwrap().is_boundary(), "vertex {v}: k = 0");
        }
        assert!(vertex.kth_half_edge_from(n).is_none());
    }
    let _ = mesh.first_non_manifold();
}
