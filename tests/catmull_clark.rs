//! Catmull-Clark: counts, topology invariants, affine invariance, the seed-003 cube, and
//! B-spline reproduction on a regular grid. Every expected value comes from a closed-form
//! formula or from the seed documents, as each test says.

mod common;

use common::*;
use subsurf::shapes::{cube, grid, grid_with_hole};
use subsurf::{subdivide, Boundary, HalfEdgeMesh, Options, PolyMesh, Scheme};

fn cc(mesh: &PolyMesh, levels: u32, boundary: Boundary) -> PolyMesh {
    subdivide(mesh, &Options::new(Scheme::CatmullClark, levels).with_boundary(boundary)).unwrap()
}

const MODES: [Boundary; 4] =
    [Boundary::EdgeAndCorner, Boundary::EdgeOnly, Boundary::Fixed, Boundary::Average];

/// Counts formulas: V' = V + E + F and F' = Σ face sizes (= number of half-edges).
#[test]
fn counts_follow_the_formulas() {
    for (name, mesh) in sample_meshes() {
        let mut current = mesh.clone();
        for level in 1..=3 {
            let he = HalfEdgeMesh::from_poly(&current).unwrap();
            let next = cc(&mesh, level, Boundary::EdgeAndCorner);
            assert_eq!(
                next.num_vertices(),
                he.num_vertices() + he.num_edges() + he.num_cells(),
                "{name} L{level}"
            );
            assert_eq!(next.num_faces(), he.num_half_edges(), "{name} L{level}");
            assert!(next.face_sizes.iter().all(|&n| n == 4), "{name} L{level}: all quads");
            current = next;
        }
    }
}

#[test]
fn euler_characteristic_and_closedness_are_kept() {
    for (name, mesh) in sample_meshes() {
        let chi = euler_characteristic(&mesh);
        let boundary = boundary_half_edges(&mesh);
        for level in 1..=3 {
            let out = cc(&mesh, level, Boundary::EdgeAndCorner);
            assert_eq!(euler_characteristic(&out), chi, "{name} L{level}");
            // Each boundary edge splits in two, so a closed mesh stays closed.
            assert_eq!(boundary_half_edges(&out), boundary << level, "{name} L{level}");
        }
    }
}

/// Subdivision is affine invariant: subdividing a transformed mesh equals transforming the result.
#[test]
fn affine_invariance() {
    let m = [[0.8f32, -0.3, 0.2], [0.1, 1.2, -0.4], [0.3, 0.2, 0.9]];
    let t = [1.5f32, -2.0, 0.25];
    let apply = |p: &[f32]| -> Vec<f32> {
        p.chunks_exact(3)
            .flat_map(|v| {
                (0..3).map(move |r| m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2] + t[r])
            })
            .collect()
    };
    for (name, mesh) in sample_meshes() {
        for mode in MODES {
            let moved = PolyMesh { positions: apply(&mesh.positions), ..mesh.clone() };
            let a = cc(&moved, 2, mode);
            let b = cc(&mesh, 2, mode);
            let b_moved = apply(&b.positions);
            let worst =
                a.positions.iter().zip(&b_moved).map(|(x, y)| (x - y).abs()).fold(0.0, f32::max);
            assert!(worst < 2e-5, "{name} {mode}: differs by {worst}");
            assert_eq!(a.indices, b.indices);
        }
    }
}

/// Seed 003: the vertex list of its Haskell output (26 points) and the 24 quads of its OCaml
/// output, compared as unordered cycles of positions (the seed's Haskell face list pairs each
/// corner with the wrong edge point, and the OCaml cube lists its faces with mixed windings).
#[test]
fn seed_003_cube() {
    let out = cc(&cube(), 1, Boundary::EdgeAndCorner);
    let s = 5.0f32 / 9.0;
    let mut expected_vertices = vec![
        [0.0, -1.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        [-0.75, -0.75, 0.0],
        [-0.75, 0.0, -0.75],
        [0.0, -0.75, -0.75],
        [-0.75, 0.0, 0.75],
        [0.0, -0.75, 0.75],
        [-0.75, 0.75, 0.0],
        [0.0, 0.75, -0.75],
        [0.0, 0.75, 0.75],
        [0.75, -0.75, 0.0],
        [0.75, 0.0, -0.75],
        [0.75, 0.0, 0.75],
        [0.75, 0.75, 0.0],
    ];
    for i in 0..8 {
        let sign = |bit: i32| if i & bit != 0 { s } else { -s };
        expected_vertices.push([sign(4), sign(2), sign(1)]);
    }
    assert_eq!(out.num_vertices(), 26);
    for e in &expected_vertices {
        let hits = (0..26).filter(|&v| distance(position(&out, v), *e) < 1e-6).count();
        assert_eq!(hits, 1, "seed vertex {e:?} should appear exactly once");
    }

    // OCaml output of seed 003, rounded to 4 decimals there.
    let (a, b, c) = (0.75f32, 0.5556f32, 1.0f32);
    #[rustfmt::skip]
    let expected_quads: [[[f32; 3]; 4]; 24] = [
        [[-a,0.,-a],[-b,-b,-b],[-a,-a,0.],[-c,0.,0.]], [[-a,-a,0.],[-b,-b,b],[-a,0.,a],[-c,0.,0.]],
        [[-a,0.,a],[-b,b,b],[-a,a,0.],[-c,0.,0.]],     [[-a,a,0.],[-b,b,-b],[-a,0.,-a],[-c,0.,0.]],
        [[a,0.,-a],[b,-b,-b],[a,-a,0.],[c,0.,0.]],     [[a,-a,0.],[b,-b,b],[a,0.,a],[c,0.,0.]],
        [[a,0.,a],[b,b,b],[a,a,0.],[c,0.,0.]],         [[a,a,0.],[b,b,-b],[a,0.,-a],[c,0.,0.]],
        [[-a,-a,0.],[-b,-b,-b],[0.,-a,-a],[0.,-c,0.]], [[0.,-a,-a],[b,-b,-b],[a,-a,0.],[0.,-c,0.]],
        [[a,-a,0.],[b,-b,b],[0.,-a,a],[0.,-c,0.]],     [[0.,-a,a],[-b,-b,b],[-a,-a,0.],[0.,-c,0.]],
        [[-a,a,0.],[-b,b,-b],[0.,a,-a],[0.,c,0.]],     [[0.,a,-a],[b,b,-b],[a,a,0.],[0.,c,0.]],
        [[a,a,0.],[b,b,b],[0.,a,a],[0.,c,0.]],         [[0.,a,a],[-b,b,b],[-a,a,0.],[0.,c,0.]],
        [[0.,-a,-a],[-b,-b,-b],[-a,0.,-a],[0.,0.,-c]], [[-a,0.,-a],[-b,b,-b],[0.,a,-a],[0.,0.,-c]],
        [[0.,a,-a],[b,b,-b],[a,0.,-a],[0.,0.,-c]],     [[a,0.,-a],[b,-b,-b],[0.,-a,-a],[0.,0.,-c]],
        [[0.,-a,a],[-b,-b,b],[-a,0.,a],[0.,0.,c]],     [[-a,0.,a],[-b,b,b],[0.,a,a],[0.,0.,c]],
        [[0.,a,a],[b,b,b],[a,0.,a],[0.,0.,c]],         [[a,0.,a],[b,-b,b],[0.,-a,a],[0.,0.,c]],
    ];
    let ours: Vec<[[f32; 3]; 4]> = out
        .indices
        .chunks_exact(4)
        .map(|q| [0, 1, 2, 3].map(|k| position(&out, q[k] as usize)))
        .collect();
    let same_cycle = |p: &[[f32; 3]; 4], q: &[[f32; 3]; 4]| {
        (0..4).any(|shift| {
            (0..4).all(|k| distance(p[k], q[(k + shift) % 4]) < 1e-4)
                || (0..4).all(|k| distance(p[k], q[(shift + 4 - k) % 4]) < 1e-4)
        })
    };
    assert_eq!(ours.len(), 24);
    for (i, e) in expected_quads.iter().enumerate() {
        let hits = ours.iter().filter(|q| same_cycle(q, e)).count();
        assert_eq!(hits, 1, "seed quad {i} should appear exactly once");
    }
}

/// On a regular grid the interior reproduces uniform bicubic B-spline refinement: along each
/// axis a new vertex point takes (1, 6, 1)/8 of the old ones and a new edge point (1, 1)/2
/// (Lane-Riesenfeld), and the 2D masks are their tensor products.
#[test]
fn regular_grid_reproduces_bicubic_b_spline() {
    let n = 6u32;
    let mut mesh = grid(n, n);
    // Heights from a fixed pseudo-random sequence; x and y stay on the integer lattice.
    let mut seed = 12345u32;
    let mut height = vec![0.0f32; ((n + 1) * (n + 1)) as usize];
    for (v, h) in height.iter_mut().enumerate() {
        seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        *h = (seed >> 8) as f32 / (1u32 << 24) as f32 - 0.5;
        mesh.positions[3 * v + 2] = *h;
    }
    let weights = |child: u32| -> Vec<(u32, f32)> {
        let k = child / 2;
        if child.is_multiple_of(2) {
            vec![(k.wrapping_sub(1), 0.125), (k, 0.75), (k + 1, 0.125)]
        } else {
            vec![(k, 0.5), (k + 1, 0.5)]
        }
    };
    let out = cc(&mesh, 1, Boundary::EdgeAndCorner);
    let mut checked = 0;
    for v in 0..out.num_vertices() {
        let [x, y, z] = position(&out, v);
        let (ci, cj) = ((2.0 * x).round() as u32, (2.0 * y).round() as u32);
        assert_eq!((ci as f32 / 2.0, cj as f32 / 2.0), (x, y), "child {v} off the half lattice");
        // Only children whose stencil uses no boundary rule: interior parent vertices, edges
        // off the boundary rows and columns, and every face.
        let interior = |c: u32| c % 2 == 1 || (c >= 2 && c <= 2 * n - 2);
        if !(interior(ci) && interior(cj)) {
            continue;
        }
        let mut expected = 0.0f32;
        for (i, wi) in weights(ci) {
            for (j, wj) in weights(cj) {
                expected += wi * wj * height[(j * (n + 1) + i) as usize];
            }
        }
        assert!((z - expected).abs() < 1e-6, "child ({ci}, {cj}): {z} vs B-spline {expected}");
        checked += 1;
    }
    // (2n - 1)² children have all-interior stencils.
    assert_eq!(checked, ((2 * n - 1) * (2 * n - 1)) as usize);
}

/// Seed 000: boundary vertices keep their positions and boundary edge points are midpoints.
#[test]
fn fixed_boundary_keeps_boundary_vertices() {
    let mesh = grid_with_hole(4, 4, 1..3, 1..2);
    let out = cc(&mesh, 1, Boundary::Fixed);
    let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
    let mut seen = 0;
    for v in he.vertex_indices() {
        if he.vertex(v).unwrap().is_boundary() {
            assert_eq!(position(&out, v as usize), position(&mesh, v as usize), "vertex {v}");
            seen += 1;
        }
    }
    // Outer ring of a 4×4 grid: 16 vertices; a 2×1 hole: 6 more.
    assert_eq!(seen, 16 + 6);
}

/// Seed 003's hole rule: a boundary vertex becomes the mean of itself and the midpoints of its
/// two boundary edges, (v + (v+a)/2 + (v+b)/2) / 3; a boundary edge point is the midpoint.
#[test]
fn average_boundary_is_seed_003_rule() {
    let mesh = grid(3, 2);
    let out = cc(&mesh, 1, Boundary::Average);
    // Vertex 1 = (1,0,0): boundary neighbours (0,0,0) and (2,0,0).
    let expect = [(1.0 + 0.5 + 1.5) / 3.0, 0.0, 0.0];
    assert!(distance(position(&out, 1), expect) < 1e-6);
    // Corner vertex 0 = (0,0,0): boundary neighbours (1,0,0) and (0,1,0).
    let expect = [0.5 / 3.0, 0.5 / 3.0, 0.0];
    assert!(distance(position(&out, 0), expect) < 1e-6);
}

/// OpenSubdiv's boundary rules on an open grid, from their definitions: crease vertices move to
/// (a + 6v + b)/8, corners (one face) stay in edge-and-corner and follow the crease rule in
/// edge-only.
#[test]
fn edge_only_and_edge_and_corner_differ_only_at_corners() {
    let mut mesh = grid(3, 3);
    mesh.positions[2] = 1.0; // lift corner 0 so the rules differ
    let corner = cc(&mesh, 1, Boundary::EdgeAndCorner);
    let only = cc(&mesh, 1, Boundary::EdgeOnly);
    assert_eq!(position(&corner, 0), [0.0, 0.0, 1.0]);
    let expected = [(6.0 * 0.0 + 1.0 + 0.0) / 8.0, 1.0 / 8.0, 6.0 / 8.0];
    assert!(distance(position(&only, 0), expected) < 1e-6, "{:?}", position(&only, 0));
    let differing: Vec<usize> = (0..corner.num_vertices())
        .filter(|&v| distance(position(&corner, v), position(&only, v)) > 0.0)
        .collect();
    // The four grid corners (one face each) are the only vertices whose rule changes.
    assert_eq!(differing, vec![0, 3, 12, 15]);
}

#[test]
fn level_zero_returns_the_input() {
    let mesh = cube();
    let out = subdivide(&mesh, &Options::new(Scheme::CatmullClark, 0)).unwrap();
    assert_eq!(out, mesh);
}

#[test]
fn memory_guard_refuses_before_work() {
    let options = Options { max_faces: 1000, ..Options::new(Scheme::CatmullClark, 4) };
    let err = subdivide(&cube(), &options).unwrap_err().to_string();
    // 6 quads × 4^4 = 1536 faces.
    assert!(err.contains("1536") && err.contains("maxFaces"), "{err}");
}
