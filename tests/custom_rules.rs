//! A rule set written outside the crate and run on an existing host: the modified butterfly
//! scheme (Dyn, Levin & Gregory 1990; Zorin, Schröder & Sweldens 1996), an interpolating scheme,
//! on the primal triangle split. It uses only the public mesh API.

use subsurf::mesh::{HalfEdgeMesh, HalfEdgeRef, PolyMesh};
use subsurf::refine::ptq;
use subsurf::rules::{edge_midpoint, Stencil, TriSplitRules, Weights};
use subsurf::shapes::{grid, icosahedron, triangulate_quads};

struct Butterfly;

/// The corner across the edge of `h` from `h`'s own triangle (see [`Weights::corner`]).
fn opposite(h: HalfEdgeRef<'_>) -> HalfEdgeRef<'_> {
    h.prev_in_cell()
}

/// Interior valence, or `None` on the boundary.
fn interior_valence(mesh: &HalfEdgeMesh, v: u32) -> Option<usize> {
    let vertex = mesh.vertex(v)?;
    (!vertex.is_boundary()).then(|| vertex.num_half_edges_from())
}

/// Zorin's stencil around an extraordinary vertex `h.from` of valence `k`, for the edge of `h`:
/// `3/4` on the vertex and `s_j` on its neighbours, `j` counted from the edge's other end;
/// `scale` times all of it.
fn extraordinary(h: HalfEdgeRef<'_>, k: usize, scale: f32, w: &mut impl Weights) {
    let s = |j: usize| -> f32 {
        match k {
            3 => [5.0 / 12.0, -1.0 / 12.0, -1.0 / 12.0][j],
            4 => [3.0 / 8.0, 0.0, -1.0 / 8.0, 0.0][j],
            _ => {
                let t = std::f32::consts::TAU * j as f32 / k as f32;
                (0.25 + t.cos() + 0.5 * (2.0 * t).cos()) / k as f32
            }
        }
    };
    w.corner(h.index(), 0.75 * scale);
    let mut g = h;
    for j in 0..k {
        // The neighbour is the to-vertex of g: the corner where g's successor starts.
        w.corner(g.next_in_cell().index(), s(j) * scale);
        // The next neighbour clockwise: across the previous edge of g's triangle.
        g = g.prev_around_from_vertex();
    }
}

impl TriSplitRules for Butterfly {
    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights) {
        let Some(&[h0, h1]) = mesh.edge_half_edges(edge) else {
            return edge_midpoint(mesh, edge, w);
        };
        let (Some(h0), Some(h1)) = (mesh.half_edge(h0), mesh.half_edge(h1)) else {
            return edge_midpoint(mesh, edge, w);
        };
        let (a, b) = (h0.from_vertex_index(), h0.to_vertex_index());
        match (interior_valence(mesh, a), interior_valence(mesh, b)) {
            (Some(6), Some(6)) => {
                let wing = |g: HalfEdgeRef<'_>| opposite(g.next_around_edge()).index();
                w.vertex(a, 0.5);
                w.vertex(b, 0.5);
                w.corner(opposite(h0).index(), 0.125);
                w.corner(opposite(h1).index(), 0.125);
                for g in
                    [h0.next_in_cell(), h0.prev_in_cell(), h1.next_in_cell(), h1.prev_in_cell()]
                {
                    w.corner(wing(g), -0.0625);
                }
            }
            (Some(ka), Some(6)) => extraordinary(h0, ka, 1.0, w),
            (Some(6), Some(kb)) => extraordinary(h1, kb, 1.0, w),
            (Some(ka), Some(kb)) => {
                extraordinary(h0, ka, 0.5, w);
                extraordinary(h1, kb, 0.5, w);
            }
            _ => edge_midpoint(mesh, edge, w),
        }
    }

    fn vertex_point(&self, _: &HalfEdgeMesh, vertex: u32, w: &mut impl Weights) {
        w.vertex(vertex, 1.0)
    }
}

fn butterfly(mesh: &PolyMesh) -> PolyMesh {
    let he = HalfEdgeMesh::from_poly(mesh).unwrap();
    let points = ptq::refine_points(&he, &Butterfly);
    assert_eq!(points.len(), ptq::num_child_vertices(&he));
    let indices = ptq::child_face_indices(&he);
    let face_sizes = vec![3; indices.len() / 3];
    PolyMesh { positions: points.into_flattened(), indices, face_sizes }
}

/// An interpolating scheme keeps the old vertices where they are.
#[test]
fn butterfly_interpolates() {
    let mesh = icosahedron();
    let out = butterfly(&mesh);
    assert_eq!(&out.positions[..mesh.positions.len()], &mesh.positions[..]);
    assert_eq!(out.num_faces(), 80);
    // The new points of a convex solid lie outside its faces' planes (the sphere bulges out).
    let radius = |p: &[f32]| (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    // An edge midpoint of the unit icosahedron (edge 1.0515) lies at sqrt(1 - 0.5257²) = 0.8507.
    let midpoint_radius = 0.8507;
    for p in out.positions.chunks_exact(3).skip(12) {
        assert!(radius(p) > midpoint_radius, "{p:?}");
    }
}

/// The butterfly scheme has cubic precision on a regular grid (Dyn, Levin & Gregory 1990): for
/// heights from a cubic polynomial, the edge point of an interior regular edge is the
/// polynomial's value at the midpoint.
#[test]
fn butterfly_reproduces_cubics_on_a_regular_grid() {
    let n = 8;
    let mut mesh = triangulate_quads(&grid(n, n));
    let f = |x: f32, y: f32| {
        0.01 * (x * x * x - 2.0 * x * x * y + 3.0 * x * y * y - y * y * y) + 0.1 * x - 0.2 * y * y
    };
    for p in mesh.positions.chunks_exact_mut(3) {
        p[2] = f(p[0], p[1]);
    }
    let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
    let out = butterfly(&mesh);
    let mut checked = 0;
    for e in 0..he.num_edges() as u32 {
        let [a, b] = he.edge_vertices(e).unwrap();
        let regular = |v: u32| interior_valence(&he, v) == Some(6);
        // The wing vertices must be regular too: stay two rings away from the border.
        let deep = |v: u32| {
            let [x, y, _] = he.vertex(v).unwrap().position();
            x >= 2.0 && y >= 2.0 && x <= (n - 2) as f32 && y <= (n - 2) as f32
        };
        if !(regular(a) && regular(b) && deep(a) && deep(b)) {
            continue;
        }
        let child = he.num_vertices() + e as usize;
        let p = &out.positions[3 * child..3 * child + 3];
        assert!((p[2] - f(p[0], p[1])).abs() < 1e-5, "edge {e}: {} vs {}", p[2], f(p[0], p[1]));
        checked += 1;
    }
    assert!(checked > 50, "{checked}");
}

/// Written as weights, every butterfly stencil is affine: its weights sum to 1, including
/// Zorin's negative ones around extraordinary vertices.
#[test]
fn butterfly_stencils_are_affine() {
    for mesh in [icosahedron(), triangulate_quads(&grid(5, 4))] {
        let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
        for e in 0..he.num_edges() as u32 {
            let mut stencil = Stencil::default();
            Butterfly.edge_point(&he, e, &mut stencil);
            assert!((stencil.total() - 1.0).abs() < 1e-6, "edge {e}: {stencil:?}");
        }
    }
}
