//! Face-varying channels (UVs split at seams) through Doo-Sabin and √3 levels, alone and in
//! lists with Catmull-Clark and Loop, in every `FVarLinear` mode: closed-form expectations only.
//!
//! Most inputs are *charted*: each face belongs to a chart, and a corner's value index is one
//! per (vertex, chart of its face), so charts meet at seams. Three channels share those indices:
//! `uv = A_c(p)` (an affine map of the vertex position `p`, its own for each chart `c`), `xyz =
//! p`, and `chart = c`. Every rule is affine, so as long as each child value is an affine
//! combination of one chart's values, `uv = A_c(xyz)` holds at every corner of a child face of
//! chart `c`, and every corner of a child face sees the same `chart`. Both fail as soon as a face
//! mixes two charts (the maps differ), wherever it is. The seam checks then read the indices:
//! no value index is seen by faces of two charts (the two sides of a cut never share one), and
//! two faces of one chart that share an edge see the same indices along it (no new seam inside
//! a chart). On a flat mesh, `uv` is also compared with `A_c` of the refined positions (or, in
//! the piecewise-linear mode `all`, of the linear split's positions) at the corners of faces
//! away from the seams.

#![cfg(not(target_arch = "wasm32"))]

mod common;

use proptest::prelude::*;
use proptest::test_runner::Config;
use std::collections::HashMap;
use std::ops::Range;
use subsurf::attributes::Attribute;
use subsurf::mesh::HalfEdgeMesh;
use subsurf::refine::sqrt3;
use subsurf::rules::{centroid, Sqrt3Rules, Weights};
use subsurf::scheme::subdivide_with_attributes;
use subsurf::shapes::{
    cube, dodecahedron, grid, grid_with_hole, house, icosahedron, prism, sheet_with_holes, torus,
    torus_triangles, triangulate_quads,
};
use subsurf::{Boundary, FVarLinear, Options, PolyMesh, Scheme, Tags};
use Scheme::{CatmullClark as CC, DooSabin as DS, Loop, QuadTriangle as QT, Sqrt3 as S3};

// ---------------------------------------------------------------------------------------------
// Running

fn face_ranges(mesh: &PolyMesh) -> Vec<Range<usize>> {
    let mut start = 0;
    mesh.face_sizes
        .iter()
        .map(|&n| {
            start += n as usize;
            start - n as usize..start
        })
        .collect()
}

fn position(positions: &[f32], v: u32) -> [f32; 3] {
    let at = 3 * v as usize;
    [positions[at], positions[at + 1], positions[at + 2]]
}

fn name(schemes: &[Scheme]) -> String {
    schemes.iter().map(|s| s.name()).collect::<Vec<_>>().join(",")
}

fn run(
    mesh: &PolyMesh,
    attributes: &[Attribute],
    schemes: &[Scheme],
    mode: FVarLinear,
    boundary: Boundary,
) -> (PolyMesh, Vec<Attribute>) {
    let options =
        Options { schemes: schemes.to_vec(), boundary, fvar_linear: mode, ..Options::default() };
    subdivide_with_attributes(mesh, attributes, &options, &Tags::default()).unwrap_or_else(|e| {
        panic!("{} {mode} {boundary}: {e}", name(schemes));
    })
}

/// The index and value of corner `k` of a face-varying channel.
fn value(a: &Attribute, k: usize) -> (u32, &[f32]) {
    let i = a.indices.as_ref().unwrap()[k];
    (i, &a.values[i as usize * a.item_size..(i as usize + 1) * a.item_size])
}

/// Indices as long as the result's, in range, values finite.
fn check_shape(out: &PolyMesh, a: &Attribute, what: &str) {
    let indices = a.indices.as_ref().expect("face-varying");
    assert_eq!(indices.len(), out.indices.len(), "{what}: {} indices", a.name);
    assert_eq!(a.values.len() % a.item_size, 0, "{what}: {}", a.name);
    if let Some(k) = indices.iter().position(|&i| i as usize >= a.len()) {
        panic!("{what}: {} index {k} is {} of {} values", a.name, indices[k], a.len());
    }
    assert!(a.values.iter().all(|x| x.is_finite()), "{what}: {} has NaN", a.name);
}

// ---------------------------------------------------------------------------------------------
// Charted inputs

/// A mesh whose faces belong to charts.
struct Charted {
    mesh: PolyMesh,
    chart: Vec<u32>,
}

/// The affine map of chart `c` (its own for each chart, so any mix of two charts shows).
fn affine(c: u32, p: [f32; 3]) -> [f32; 2] {
    let c = c as f32;
    [
        (0.25 + 0.5 * c) * p[0] - 0.5 * p[1] + 0.125 * p[2] + 3.0 * c,
        0.2 * p[0] + (0.5 + 0.3 * c) * p[1] - 0.25 * p[2] - c,
    ]
}

impl Charted {
    /// One value index per (vertex, chart of the face), and the keys in index order.
    fn keys(&self) -> (Vec<u32>, Vec<(u32, u32)>) {
        let mut map = HashMap::new();
        let (mut indices, mut keys) = (Vec::new(), Vec::new());
        for (f, range) in face_ranges(&self.mesh).into_iter().enumerate() {
            for k in range {
                let key = (self.mesh.indices[k], self.chart[f]);
                let i = *map.entry(key).or_insert_with(|| {
                    keys.push(key);
                    keys.len() as u32 - 1
                });
                indices.push(i);
            }
        }
        (indices, keys)
    }

    /// `uv`, `xyz` and `chart`, sharing one set of indices.
    fn channels(&self) -> Vec<Attribute> {
        let (indices, keys) = self.keys();
        let p = |v: u32| position(&self.mesh.positions, v);
        let uv = keys.iter().flat_map(|&(v, c)| affine(c, p(v))).collect();
        let xyz = keys.iter().flat_map(|&(v, _)| p(v)).collect();
        let chart = keys.iter().map(|&(_, c)| c as f32).collect();
        vec![
            Attribute::face_varying("uv", 2, uv, indices.clone()),
            Attribute::face_varying("xyz", 3, xyz, indices.clone()),
            Attribute::face_varying("chart", 1, chart, indices),
        ]
    }

    /// `uv` alone, and `chart` with the same seams but its values numbered the other way round
    /// (so the two travel as separate channels rather than side by side).
    fn apart(&self) -> Vec<Attribute> {
        let mut channels = self.channels();
        let chart = channels.pop().unwrap();
        channels.pop();
        let last = chart.len() as u32 - 1;
        let indices = chart.indices.unwrap().iter().map(|&i| last - i).collect();
        let values = chart.values.iter().rev().copied().collect();
        channels.push(Attribute::face_varying("chart", 1, values, indices));
        channels
    }
}

/// True when `schemes` has a Doo-Sabin level after a √3 level. A √3 level can leave a chart
/// with two values at one vertex, seen by faces that share no edge (where two faces of one
/// chart border the same face across seams, each sees that face's point at its own seam's
/// midpoint); a Doo-Sabin level then gives that vertex a face that borders both, and it can
/// agree along its edges with one of them only. So after such a list a chart may have a seam
/// inside it, from that vertex, and [`check_charted`] does not look for one.
fn pinches(schemes: &[Scheme]) -> bool {
    schemes.iter().position(|&s| s == S3).is_some_and(|i| schemes[i..].contains(&DS))
}

/// Checks the structure of a charted result of `schemes` (module docs); returns each face's
/// chart.
fn check_charted(
    out: &PolyMesh,
    channels: &[Attribute],
    schemes: &[Scheme],
    what: &str,
) -> Vec<u32> {
    let [uv, xyz, chart] = channels else { panic!("{what}: three channels") };
    for a in channels {
        check_shape(out, a, what);
    }
    let faces = face_ranges(out);
    let mut face_chart = Vec::with_capacity(faces.len());
    for (f, range) in faces.iter().enumerate() {
        let c = value(chart, range.start).1[0];
        assert!(
            (c - c.round()).abs() < 1e-4 && c > -0.5,
            "{what}: face {f} sees chart value {c}, no chart's"
        );
        for k in range.clone() {
            let other = value(chart, k).1[0];
            assert!((other - c).abs() < 1e-4, "{what}: face {f} mixes charts {c} and {other}");
        }
        let c = c.round() as u32;
        for k in range.clone() {
            let (p, got) = (value(xyz, k).1, value(uv, k).1);
            let want = affine(c, [p[0], p[1], p[2]]);
            let scale = 1.0 + want[0].abs().max(want[1].abs());
            assert!(
                (got[0] - want[0]).abs() < 2e-5 * scale && (got[1] - want[1]).abs() < 2e-5 * scale,
                "{what}: face {f} corner {k}: uv {got:?} is not chart {c}'s map of {p:?}: {want:?}"
            );
        }
        face_chart.push(c);
    }
    // Values are numbered as `fvar` numbers them: a value below the vertex count is that
    // vertex's first value (so where nothing mismatches, the corner values are the indices).
    let uv_indices = uv.indices.as_ref().unwrap();
    for (k, (&i, &v)) in uv_indices.iter().zip(&out.indices).enumerate() {
        let own = i as usize >= out.num_vertices() || i == v;
        assert!(own, "{what}: corner {k} of vertex {v} sees value {i}, another vertex's");
    }
    // The two sides of a cut never share a value index.
    let mut index_chart = vec![u32::MAX; uv.len()];
    for (f, range) in faces.iter().enumerate() {
        for k in range.clone() {
            let seen = &mut index_chart[uv_indices[k] as usize];
            assert!(
                *seen == u32::MAX || *seen == face_chart[f],
                "{what}: value {} seen by charts {} and {}",
                uv_indices[k],
                *seen,
                face_chart[f]
            );
            *seen = face_chart[f];
        }
    }
    // No seam inside a chart: faces of one chart that share an edge see the same values on it.
    if pinches(schemes) {
        return face_chart;
    }
    let mut edges: HashMap<(u32, u32), (usize, u32, u32)> = HashMap::new();
    for (f, range) in faces.iter().enumerate() {
        let n = range.len();
        for j in 0..n {
            let (k0, k1) = (range.start + j, range.start + (j + 1) % n);
            let (a, b) = (out.indices[k0], out.indices[k1]);
            let (ia, ib) = (uv_indices[k0], uv_indices[k1]);
            if let Some(&(g, jb, ja)) = edges.get(&(b, a)) {
                if face_chart[g] == face_chart[f] {
                    assert!(
                        (ia, ib) == (ja, jb),
                        "{what}: faces {g} and {f} of chart {} see different values on edge \
                         {a}-{b}: ({ja}, {jb}) and ({ia}, {ib})",
                        face_chart[f]
                    );
                }
            }
            edges.insert((a, b), (f, ia, ib));
        }
    }
    face_chart
}

/// Compares `uv` with its chart's map of `positions` (one point per result vertex) at every
/// corner of each face all of whose corners `inside` accepts; returns the corners compared.
fn check_linear(
    out: &PolyMesh,
    uv: &Attribute,
    face_chart: &[u32],
    positions: &[f32],
    inside: impl Fn([f32; 3]) -> bool,
    what: &str,
) -> usize {
    let mut checked = 0;
    for (f, range) in face_ranges(out).into_iter().enumerate() {
        if !range.clone().all(|k| inside(position(positions, out.indices[k]))) {
            continue;
        }
        for k in range {
            let p = position(positions, out.indices[k]);
            let want = affine(face_chart[f], p);
            let got = value(uv, k).1;
            let scale = 1.0 + want[0].abs().max(want[1].abs());
            assert!(
                (got[0] - want[0]).abs() < 2e-5 * scale && (got[1] - want[1]).abs() < 2e-5 * scale,
                "{what}: face {f} corner {k} at {p:?}: uv {got:?}, chart {}'s map gives {want:?}",
                face_chart[f]
            );
            checked += 1;
        }
    }
    checked
}

// ---------------------------------------------------------------------------------------------
// The flat grid with seams

const NX: u32 = 16;
const NY: u32 = 12;
/// The seams: the grid lines x = SX and y = SY, four charts meeting at (SX, SY).
const SX: f32 = 8.0;
const SY: f32 = 6.0;

/// A flat `NX × NY` grid in the xy plane, its points moved within the plane (but for those on
/// the seam lines and the boundary, which move only along their line, so the lines stay
/// straight), cut into four charts by the seams; `triangles` splits every quad.
fn seamed_grid(triangles: bool) -> Charted {
    let mut mesh = grid(NX, NY);
    for (v, p) in mesh.positions.chunks_exact_mut(3).enumerate() {
        let (i, j) = (v as u32 % (NX + 1), v as u32 / (NX + 1));
        let hash = (v as u32).wrapping_mul(2654435761) >> 8;
        let jitter = |bits: u32| ((hash >> bits) & 255) as f32 / 255.0 * 0.4 - 0.2;
        let on_x_line = i == 0 || i == NX || i as f32 == SX;
        let on_y_line = j == 0 || j == NY || j as f32 == SY;
        if !on_x_line {
            p[0] += jitter(0);
        }
        if !on_y_line {
            p[1] += jitter(8);
        }
    }
    let side = |i: u32, j: u32| (i as f32 >= SX) as u32 + 2 * (j as f32 >= SY) as u32;
    let mut chart: Vec<u32> = (0..NX * NY).map(|f| side(f % NX, f / NX)).collect();
    if triangles {
        mesh = triangulate_quads(&mesh);
        chart = chart.iter().flat_map(|&c| [c, c]).collect();
    }
    Charted { mesh, chart }
}

/// True when `p` is farther than `seam` from the seams and farther than `edge` from the grid's
/// boundary.
fn away(p: [f32; 3], seam: f32, edge: f32) -> bool {
    let (x, y) = (p[0], p[1]);
    (x - SX).abs() > seam
        && (y - SY).abs() > seam
        && x > edge
        && y > edge
        && x < NX as f32 - edge
        && y < NY as f32 - edge
}

/// √3 with linear rules: old vertices stay, face points are centroids, boundary points the
/// thirds. Its positions are those at which mode `all` must be linear.
struct LinearSqrt3;

impl Sqrt3Rules for LinearSqrt3 {
    fn face_point(&self, mesh: &HalfEdgeMesh, cell: u32, w: &mut impl Weights) {
        centroid(mesh, cell, w);
    }

    fn vertex_point(&self, _: &HalfEdgeMesh, vertex: u32, _: bool, w: &mut impl Weights) {
        w.vertex(vertex, 1.0);
    }

    fn boundary_point(&self, mesh: &HalfEdgeMesh, h: u32, near: usize, w: &mut impl Weights) {
        let next = mesh.half_edge(h).unwrap().next_in_cell().index();
        let (near_end, far_end) = if near == 0 { (h, next) } else { (next, h) };
        w.corner(near_end, 2.0 / 3.0);
        w.corner(far_end, 1.0 / 3.0);
    }
}

/// The linear √3 split of `mesh`, `levels` times (boundary edges split on every second level,
/// as in a run of √3 levels).
fn linear_sqrt3(mesh: &PolyMesh, levels: usize) -> PolyMesh {
    let mut mesh = mesh.clone();
    for level in 0..levels {
        let he = HalfEdgeMesh::from_poly(&mesh).unwrap();
        mesh = sqrt3::refine(&he, &LinearSqrt3, level % 2 == 1);
    }
    mesh
}

/// The scheme lists the flat-grid tests run, with the margins (from the seams, from the
/// boundary) outside which `uv` must be its chart's map of the refined positions in `mode`;
/// `None` where no closed form applies (mode `all` after a smooth primal level, whose values
/// are bilinear while its positions are smooth).
fn margins(schemes: &[Scheme], mode: FVarLinear) -> Option<(f32, f32)> {
    let only = |s: Scheme| schemes.iter().all(|&x| x == s);
    let linear_boundaries = matches!(mode, FVarLinear::Boundaries | FVarLinear::All);
    if only(DS) {
        // Every value is its face's own affine combination: only the faces that straddle a
        // seam (within a quarter of a cell of it at the first level) differ.
        Some((0.5, 0.0))
    } else if only(S3) && mode == FVarLinear::All {
        Some((1.5, 0.0))
    } else if mode == FVarLinear::All {
        None
    } else if only(S3) && !linear_boundaries {
        Some((2.0, 0.0))
    } else {
        Some((2.0, 2.0))
    }
}

const QUAD_LISTS: &[&[Scheme]] = &[
    &[DS],
    &[DS, DS],
    &[DS, DS, DS],
    &[CC, DS],
    &[DS, CC],
    &[CC, DS, DS],
    &[DS, CC, DS],
    &[DS, QT],
    &[QT, DS],
];
const TRIANGLE_LISTS: &[&[Scheme]] = &[
    &[S3],
    &[S3, S3],
    &[S3, S3, S3],
    &[Loop, S3],
    &[S3, Loop],
    &[S3, S3, Loop],
    &[Loop, S3, S3],
    &[S3, DS],
    &[S3, CC],
    &[S3, QT],
];

/// The boundary rules a list is run with.
fn boundaries(schemes: &[Scheme]) -> &'static [Boundary] {
    if schemes.iter().all(|&s| s == DS) {
        &[Boundary::EdgeAndCorner, Boundary::None]
    } else if schemes.iter().all(|&s| s == S3) {
        &[Boundary::EdgeAndCorner, Boundary::Fixed]
    } else {
        &[Boundary::EdgeAndCorner]
    }
}

fn flat_grid_case(triangles: bool, lists: &[&[Scheme]]) {
    let charted = seamed_grid(triangles);
    let channels = charted.channels();
    let apart = charted.apart();
    let mut checked_total = 0;
    for &schemes in lists {
        for &boundary in boundaries(schemes) {
            for &mode in FVarLinear::ALL {
                let what = format!("{} {mode} {boundary}", name(schemes));
                let (out, result) = run(&charted.mesh, &channels, schemes, mode, boundary);
                let face_chart = check_charted(&out, &result, schemes, &what);
                // The same seams, the channels apart: the same values.
                let (out2, result2) = run(&charted.mesh, &apart, schemes, mode, boundary);
                assert_eq!(out2.indices, out.indices, "{what}");
                assert_eq!(result2[0].indices, result[0].indices, "{what}: uv apart");
                let mut same = result2[0].values.iter().zip(&result[0].values);
                assert!(same.all(|(a, b)| (a - b).abs() <= 1e-6 * (1.0 + b.abs())), "{what}");
                // `chart` apart has the same seams: its indices are uv's, renamed.
                let (a, b) = (result2[1].indices.as_ref(), result[0].indices.as_ref());
                let mut rename = HashMap::new();
                for (&x, &y) in a.unwrap().iter().zip(b.unwrap()) {
                    assert_eq!(*rename.entry(y).or_insert(x), x, "{what}: chart apart");
                }
                let Some((seam, edge)) = margins(schemes, mode) else { continue };
                let all_s3 = schemes.iter().all(|&s| s == S3);
                let positions = if all_s3 && mode == FVarLinear::All {
                    let linear = linear_sqrt3(&charted.mesh, schemes.len());
                    assert_eq!(linear.indices, out.indices, "{what}: linear split's faces");
                    linear.positions
                } else {
                    out.positions.clone()
                };
                let inside = |p: [f32; 3]| away(p, seam, edge);
                let checked =
                    check_linear(&out, &result[0], &face_chart, &positions, inside, &what);
                assert!(checked > 100, "{what}: only {checked} corners away from the seams");
                checked_total += checked;
            }
        }
    }
    assert!(checked_total > 0);
}

#[test]
fn doo_sabin_keeps_charts_linear_on_a_seamed_grid() {
    flat_grid_case(false, QUAD_LISTS);
}

#[test]
fn sqrt3_keeps_charts_linear_on_a_seamed_grid() {
    flat_grid_case(true, TRIANGLE_LISTS);
}

/// Doo-Sabin on triangles too (its faces are any polygons).
#[test]
fn doo_sabin_keeps_charts_linear_on_a_seamed_triangle_grid() {
    flat_grid_case(true, &[&[DS], &[DS, DS], &[DS, CC]]);
}

/// Mode `all` of √3 is the linear split, which differs from the smooth modes on this grid
/// (its points are not evenly spaced): the comparison above could fail.
#[test]
fn sqrt3_mode_all_differs_from_its_smooth_modes() {
    let charted = seamed_grid(true);
    let channels = charted.channels();
    let run_mode = |mode| run(&charted.mesh, &channels, &[S3, S3], mode, Boundary::EdgeAndCorner);
    let (_, linear) = run_mode(FVarLinear::All);
    let (_, smooth) = run_mode(FVarLinear::CornersPlus1);
    assert_eq!(linear[0].indices, smooth[0].indices);
    let differs =
        linear[0].values.iter().zip(&smooth[0].values).filter(|(a, b)| (*a - *b).abs() > 1e-3);
    assert!(differs.count() > 100);
}

// ---------------------------------------------------------------------------------------------
// Closed and open shapes

/// `mesh` with one more vertex, which no face uses.
fn with_lone_vertex(mut mesh: PolyMesh) -> PolyMesh {
    mesh.positions.extend_from_slice(&[0.5, 0.5, 3.0]);
    mesh
}

fn quad_shapes() -> Vec<(&'static str, PolyMesh)> {
    vec![
        ("grid-and-lone-vertex", with_lone_vertex(grid(3, 2))),
        ("cube", cube()),
        ("torus", torus(8, 6, 2.0, 0.5)),
        ("prism5", prism(5)),
        ("dodecahedron", dodecahedron()),
        ("house", house()),
        ("grid-with-hole", grid_with_hole(5, 5, 2..3, 1..3)),
        ("sheet-with-holes", sheet_with_holes()),
        ("prism7-mixed", triangulate_quads(&prism(7))),
    ]
}

fn triangle_shapes() -> Vec<(&'static str, PolyMesh)> {
    vec![
        ("grid-triangles-and-lone-vertex", with_lone_vertex(triangulate_quads(&grid(3, 2)))),
        ("icosahedron", icosahedron()),
        ("torus-triangles", torus_triangles(6, 5, 2.0, 0.7)),
        ("cube-triangles", triangulate_quads(&cube())),
        ("grid-with-hole-triangles", triangulate_quads(&grid_with_hole(5, 5, 2..3, 1..3))),
        ("grid-triangles", triangulate_quads(&grid(4, 3))),
    ]
}

/// Charts by the octant of each face's centroid (the mesh centred first), so seams run along
/// the faces' edges in three directions and meet.
fn octant_charts(mesh: &PolyMesh) -> Charted {
    let n = mesh.num_vertices() as f32;
    let mut centre = [0.0f32; 3];
    for p in mesh.positions.chunks_exact(3) {
        (0..3).for_each(|k| centre[k] += p[k] / n);
    }
    let chart = face_ranges(mesh)
        .into_iter()
        .map(|range| {
            let mut c = [0.0f32; 3];
            for k in range.clone() {
                let p = position(&mesh.positions, mesh.indices[k]);
                (0..3).for_each(|i| c[i] += p[i] / range.len() as f32);
            }
            (0..3).map(|i| ((c[i] > centre[i]) as u32) << i).sum()
        })
        .collect();
    Charted { mesh: mesh.clone(), chart }
}

/// The constant channels: one value for every corner (one index), and one value per face (the
/// face's own index: every edge a seam).
fn constants(mesh: &PolyMesh) -> Vec<Attribute> {
    let faces = mesh.num_faces() as u32;
    let per_face_indices = face_ranges(mesh)
        .into_iter()
        .enumerate()
        .flat_map(|(f, range)| range.map(move |_| f as u32))
        .collect();
    vec![
        Attribute::face_varying("one", 2, vec![0.75, -2.5], vec![0; mesh.indices.len()]),
        Attribute::face_varying(
            "per-face",
            1,
            (0..faces).map(|f| 1.0 + 0.5 * f as f32).collect(),
            per_face_indices,
        ),
    ]
}

fn check_constants(out: &PolyMesh, channels: &[Attribute], faces: u32, what: &str) {
    let [one, per_face] = channels else { panic!("{what}: two channels") };
    check_shape(out, one, what);
    check_shape(out, per_face, what);
    for k in 0..out.indices.len() {
        let got = value(one, k).1;
        assert!(
            (got[0] - 0.75).abs() < 1e-5 && (got[1] + 2.5).abs() < 1e-5,
            "{what}: corner {k} of the constant channel is {got:?}"
        );
    }
    for (f, range) in face_ranges(out).into_iter().enumerate() {
        let c = value(per_face, range.start).1[0];
        let parent = (c - 1.0) / 0.5;
        assert!(
            (parent - parent.round()).abs() < 1e-3 && parent > -0.5 && parent < faces as f32,
            "{what}: face {f} sees {c}, no input face's value"
        );
        for k in range {
            let other = value(per_face, k).1[0];
            assert!((other - c).abs() < 1e-5, "{what}: face {f} sees {c} and {other}");
        }
    }
}

fn shapes_case(shapes: Vec<(&'static str, PolyMesh)>, lists: &[&[Scheme]]) {
    for (shape, mesh) in shapes {
        let charted = octant_charts(&mesh);
        let channels = charted.channels();
        let constant_channels = constants(&mesh);
        for &schemes in lists {
            for &boundary in boundaries(schemes) {
                for &mode in FVarLinear::ALL {
                    let what = format!("{shape} {} {mode} {boundary}", name(schemes));
                    let (out, result) = run(&mesh, &channels, schemes, mode, boundary);
                    check_charted(&out, &result, schemes, &what);
                    let (out, result) = run(&mesh, &constant_channels, schemes, mode, boundary);
                    check_constants(&out, &result, mesh.num_faces() as u32, &what);
                }
            }
        }
    }
}

#[test]
fn doo_sabin_keeps_constants_and_charts_on_shapes() {
    shapes_case(quad_shapes(), QUAD_LISTS);
}

#[test]
fn sqrt3_keeps_constants_and_charts_on_shapes() {
    shapes_case(triangle_shapes(), TRIANGLE_LISTS);
}

/// The UV torus: one chart, cut along its two closing loops (u and v jump from 1 to 0 there):
/// no refined face may reach across a cut, so no face sees a u (or v) range of half or more.
#[test]
fn torus_uvs_stay_cut_along_the_closing_loops() {
    let (rings, segments) = (8u32, 6u32);
    let quads = torus(rings, segments, 2.0, 0.5);
    let mut uv = Vec::new();
    for i in 0..=rings {
        for j in 0..=segments {
            uv.extend_from_slice(&[i as f32 / rings as f32, j as f32 / segments as f32]);
        }
    }
    let at = |i: u32, j: u32| i * (segments + 1) + j;
    let mut indices = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            indices.extend_from_slice(&[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    let triangle_indices: Vec<u32> =
        indices.chunks_exact(4).flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]]).collect();
    let cases = [
        (quads.clone(), indices, QUAD_LISTS),
        (triangulate_quads(&quads), triangle_indices, TRIANGLE_LISTS),
    ];
    for (mesh, indices, lists) in cases {
        let channel = [Attribute::face_varying("uv", 2, uv.clone(), indices)];
        for &schemes in lists {
            for &mode in FVarLinear::ALL {
                let what = format!("{} {mode}", name(schemes));
                let (out, result) = run(&mesh, &channel, schemes, mode, Boundary::EdgeAndCorner);
                check_shape(&out, &result[0], &what);
                let mut seen = [false; 4];
                for (f, range) in face_ranges(&out).into_iter().enumerate() {
                    for axis in 0..2 {
                        let values = range.clone().map(|k| value(&result[0], k).1[axis]);
                        let (lo, hi) =
                            values.fold((f32::MAX, f32::MIN), |(lo, hi), x| (lo.min(x), hi.max(x)));
                        assert!(hi - lo < 0.5, "{what}: face {f} spans {lo}..{hi} on axis {axis}");
                        // Both sides of both cuts are still there.
                        seen[2 * axis] |= lo < 0.1;
                        seen[2 * axis + 1] |= hi > 0.9;
                    }
                }
                assert_eq!(seen, [true; 4], "{what}");
            }
        }
    }
}

/// Without seams a face-varying channel refines as a vertex-varying one: Doo-Sabin in every
/// mode (its values are linear in each face anyway), √3 where the mode keeps its boundary
/// smooth and its values not linear.
#[test]
fn without_seams_face_varying_is_vertex_varying() {
    let cases = [(quad_shapes(), QUAD_LISTS), (triangle_shapes(), TRIANGLE_LISTS)];
    for (shapes, lists) in cases {
        for (shape, mesh) in shapes {
            let f = |p: &[f32]| [p[0] - 2.0 * p[1] + 0.5, p[2] * p[0] + 1.0];
            let values: Vec<f32> = mesh.positions.chunks_exact(3).flat_map(f).collect();
            let channels = [
                Attribute::face_varying("fv", 2, values.clone(), mesh.indices.clone()),
                Attribute::vertex("vv", 2, values),
            ];
            for &schemes in lists {
                // The primal schemes sharpen the corners of one face in some modes.
                if schemes.iter().any(|&s| s != DS && s != S3) {
                    continue;
                }
                for &mode in FVarLinear::ALL {
                    let linear = matches!(mode, FVarLinear::All | FVarLinear::Boundaries);
                    if linear && schemes.contains(&S3) {
                        continue;
                    }
                    let what = format!("{shape} {} {mode}", name(schemes));
                    let (out, result) =
                        run(&mesh, &channels, schemes, mode, Boundary::EdgeAndCorner);
                    let [fv, vv] = &result[..] else { panic!() };
                    check_shape(&out, fv, &what);
                    for (k, &v) in out.indices.iter().enumerate() {
                        let (got, want) = (value(fv, k).1, &vv.values[2 * v as usize..][..2]);
                        let close = got.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-5);
                        assert!(close, "{what}: corner {k} (vertex {v}): {got:?} vs {want:?}");
                    }
                    // One value per vertex: the indices are the vertices.
                    assert_eq!(fv.indices.as_ref().unwrap(), &out.indices, "{what}");
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Random meshes with random seams

/// A random open grid or closed torus (`a × b`), quads split into triangles by the bits of
/// `split`, points moved by `noise`.
fn random_mesh(torus_kind: bool, a: u32, b: u32, split: u64, noise: &[f32]) -> PolyMesh {
    let mut positions = Vec::new();
    let (nu, nv) = if torus_kind { (a + 2, b + 2) } else { (a + 1, b + 1) };
    let tau = std::f32::consts::TAU;
    for i in 0..nu {
        for j in 0..nv {
            let p = if torus_kind {
                let (u, v) = (tau * i as f32 / nu as f32, tau * j as f32 / nv as f32);
                let r = 2.0 + 0.7 * v.cos();
                [r * u.cos(), r * u.sin(), 0.7 * v.sin()]
            } else {
                [i as f32, j as f32, 0.0]
            };
            positions.extend(p);
        }
    }
    for (k, x) in positions.iter_mut().enumerate() {
        *x += noise[k % noise.len()];
    }
    let at = |i: u32, j: u32| (i % nu) * nv + j % nv;
    let (cu, cv) = if torus_kind { (nu, nv) } else { (a, b) };
    let (mut indices, mut face_sizes) = (Vec::new(), Vec::new());
    for i in 0..cu {
        for j in 0..cv {
            let q = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
            if split >> ((i * cv + j) % 64) & 1 == 1 {
                indices.extend_from_slice(&[q[0], q[1], q[2], q[0], q[2], q[3]]);
                face_sizes.extend_from_slice(&[3, 3]);
            } else {
                indices.extend_from_slice(&q);
                face_sizes.push(4);
            }
        }
    }
    PolyMesh { positions, indices, face_sizes }
}

fn random_lists() -> Vec<Vec<Scheme>> {
    let mut lists: Vec<Vec<Scheme>> = QUAD_LISTS.iter().map(|l| l.to_vec()).collect();
    lists.extend(TRIANGLE_LISTS.iter().map(|l| l.to_vec()));
    lists
}

proptest! {
    #![proptest_config(Config { cases: 256, failure_persistence: None, ..Config::default() })]

    /// Random charts on random meshes: the chart structure holds (no face mixes charts, the
    /// sides of a cut share no value, no seam appears inside a chart) and constants stay.
    #[test]
    fn random_charts_stay_apart(
        torus_kind in any::<bool>(),
        a in 1u32..=4,
        b in 1u32..=4,
        split in any::<u64>(),
        charts in any::<u64>(),
        noise in prop::collection::vec(-0.2f32..0.2, 3..24),
        list in 0usize..64,
        mode in 0usize..6,
        boundary in 0usize..2,
    ) {
        let lists = random_lists();
        let schemes = &lists[list % lists.len()];
        let mut mesh = random_mesh(torus_kind, a, b, split, &noise);
        if schemes[0].triangles_only() {
            mesh = triangulate_quads(&mesh);
        }
        let boundary = boundaries(schemes)[boundary % boundaries(schemes).len()];
        let mode = FVarLinear::ALL[mode];
        let chart = (0..mesh.num_faces()).map(|f| (charts >> (2 * (f % 32)) & 3) as u32).collect();
        let charted = Charted { mesh, chart };
        let what = format!("{} {mode} {boundary}", name(schemes));
        let (out, result) = run(&charted.mesh, &charted.channels(), schemes, mode, boundary);
        check_charted(&out, &result, schemes, &what);
        let (out, result) = run(&charted.mesh, &constants(&charted.mesh), schemes, mode, boundary);
        check_constants(&out, &result, charted.mesh.num_faces() as u32, &what);
    }

    /// Arbitrary value indices (darts, values shared by far-apart corners): every result is
    /// well formed, and every value stays within the range of the input values (the weights of
    /// Doo-Sabin and √3 are all positive).
    #[test]
    fn random_indices_stay_in_range(
        torus_kind in any::<bool>(),
        a in 1u32..=4,
        b in 1u32..=4,
        split in any::<u64>(),
        picks in prop::collection::vec(0u32..6, 1..40),
        noise in prop::collection::vec(-0.2f32..0.2, 3..24),
        dual in any::<bool>(),
        levels in 1usize..=3,
        mode in 0usize..6,
        boundary in 0usize..2,
    ) {
        let schemes = vec![if dual { DS } else { S3 }; levels];
        let mut mesh = random_mesh(torus_kind, a, b, split, &noise);
        if !dual {
            mesh = triangulate_quads(&mesh);
        }
        let boundary = boundaries(&schemes)[boundary];
        let mode = FVarLinear::ALL[mode];
        // Each corner picks one of a few values near its vertex's, or one of six shared ones.
        let n = mesh.num_vertices() as u32;
        let indices: Vec<u32> = mesh
            .indices
            .iter()
            .enumerate()
            .map(|(k, &v)| match picks[k % picks.len()] {
                0 => n * 3 + k as u32 % 6,
                p => v * 3 + p % 3,
            })
            .collect();
        let count = 3 * n + 6;
        let values: Vec<f32> = (0..count).map(|i| ((i * 7919) % 101) as f32 / 10.0 - 5.0).collect();
        let (lo, hi) = values.iter().fold((f32::MAX, f32::MIN), |(l, h), &x| (l.min(x), h.max(x)));
        let channel = [Attribute::face_varying("x", 1, values, indices)];
        let what = format!("{} {mode} {boundary}", name(&schemes));
        let (out, result) = run(&mesh, &channel, &schemes, mode, boundary);
        check_shape(&out, &result[0], &what);
        let outside = result[0].values.iter().find(|&&x| x < lo - 1e-4 || x > hi + 1e-4);
        prop_assert!(outside.is_none(), "{}: value {:?} outside {}..{}", what, outside, lo, hi);
    }
}
