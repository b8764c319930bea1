//! Every scheme, one or two levels, every boundary rule, on small fuzzed meshes that are valid
//! (in-range corners, finite positions) but of any topology: open, non-manifold, mis-oriented,
//! mixed face sizes, isolated vertices, and (with `repeats`) faces that repeat a vertex, next to
//! each other or far apart. A call either returns a valid mesh whose faces never repeat a vertex,
//! no larger than predicted and inside the input's bounding box, or refuses with `Unsupported`
//! or `TooLarge` (Doo-Sabin, √3 and Quad/Triangle refuse a face that repeats a vertex; the
//! primal schemes take it); never a panic and never an invalid intermediate mesh. The same
//! call with attribute channels: the x coordinate as a channel stays the x coordinate of every
//! refined vertex and the positions do not change; a fuzzed extra channel (any size, values or
//! indices, so face-varying with any seams, in any face-varying mode) is refined, its indices
//! parallel to the result's and in range, or refused with `InvalidAttribute` or `Unsupported`.
//! And the evaluator with normals (and the limit, when `limit`): built, it gives the call's
//! positions for the control positions, and unit (or zero) normals; or both refuse alike.
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use subsurf::attributes::Attribute;
use subsurf::scheme::{predict_counts, subdivide_refined_with, subdivide_with_attributes};
use subsurf::{subdivide, Boundary, Error, Evaluator, HalfEdgeMesh, Options, PolyMesh, Scheme};
use subsurf_fuzz::{check_error, check_result, repeats_a_vertex, MAX_ELEMENTS, MAX_FACES};

#[derive(Arbitrary, Debug)]
struct Input {
    points: Vec<[i8; 3]>,
    faces: Vec<Vec<u8>>,
    first: u8,
    second: Option<u8>,
    boundary: u8,
    extra: Option<Channel>,
    /// Keep a face's corners as they come (a vertex may repeat) instead of dropping repeats.
    repeats: bool,
    /// The evaluator at the limit (else refined points with normals).
    limit: bool,
}

#[derive(Arbitrary, Debug)]
struct Channel {
    mode: u8,
    item_size: u8,
    values: Vec<f32>,
    indices: Option<Vec<u32>>,
}

fuzz_target!(|input: Input| {
    let mut points = input.points;
    points.truncate(MAX_ELEMENTS);
    if points.is_empty() {
        points.push([0; 3]);
    }
    let n = points.len();
    let positions: Vec<f32> = points.iter().flat_map(|c| c.map(|x| x as f32 / 4.0)).collect();
    let mut indices = Vec::new();
    let mut face_sizes = Vec::new();
    for face in input.faces.iter().take(MAX_ELEMENTS) {
        let mut corners: Vec<u32> = Vec::new();
        for &c in face.iter().take(8) {
            let v = c as u32 % n as u32;
            if input.repeats || !corners.contains(&v) {
                corners.push(v);
            }
        }
        if corners.len() >= 3 {
            face_sizes.push(corners.len() as u32);
            indices.extend(corners);
        }
    }
    let mesh = PolyMesh { positions, indices, face_sizes };
    let scheme = |b: u8| Scheme::ALL[b as usize % Scheme::ALL.len()];
    let mut schemes = vec![scheme(input.first)];
    schemes.extend(input.second.map(scheme));
    let boundary = Boundary::ALL[input.boundary as usize % Boundary::ALL.len()];
    let options = Options { schemes, boundary, max_faces: MAX_FACES, ..Options::default() };
    let what = format!("{:?} {boundary} on {} faces", options.schemes, mesh.num_faces());

    let (predicted_vertices, predicted_faces) =
        predict_counts(&HalfEdgeMesh::from_poly(&mesh).expect("a valid mesh"), &options);
    // Doo-Sabin of a mesh without faces is a mesh without vertices, and stays one.
    let faceless_doo_sabin = mesh.num_faces() == 0 && options.schemes.contains(&Scheme::DooSabin);
    let result = subdivide(&mesh, &options);
    check_attributes(&mesh, &options, &result, input.extra, &what);
    check_evaluator(&mesh, &options, input.limit, &what);
    match result {
        Ok(out) if faceless_doo_sabin && out.positions.is_empty() => {}
        Ok(out) => {
            check_result(&out, &what);
            let refusing = [Scheme::DooSabin, Scheme::Sqrt3, Scheme::QuadTriangle];
            assert!(
                !(repeats_a_vertex(&mesh) && refusing.contains(&options.schemes[0])),
                "{what}: a face repeats a vertex, but {} took it",
                options.schemes[0]
            );
            assert!(out.num_faces() as u64 <= predicted_faces, "{what}: more faces than predicted");
            assert!(
                out.num_vertices() as u64 <= predicted_vertices,
                "{what}: more vertices than predicted"
            );
            let (lo, hi) = bounds(&mesh.positions);
            let (out_lo, out_hi) = bounds(&out.positions);
            for k in 0..3 {
                let slack = 1e-4 * (1.0 + hi[k] - lo[k]);
                assert!(
                    out_lo[k] >= lo[k] - slack && out_hi[k] <= hi[k] + slack,
                    "{what}: result leaves the input's bounding box on axis {k}"
                );
            }
        }
        Err(e) => {
            assert!(
                matches!(e, Error::Unsupported(_) | Error::TooLarge(_) | Error::InvalidOption(_)),
                "{what}: a valid mesh gave {e:?}"
            );
            if let Error::TooLarge(_) = e {
                assert!(predicted_faces > MAX_FACES, "{what}: refused below the limit: {e}");
            }
            check_error(&e, &what);
        }
    }
});

/// The call again with channels: see the module docs.
fn check_attributes(
    mesh: &PolyMesh,
    options: &Options,
    plain: &Result<PolyMesh, Error>,
    extra: Option<Channel>,
    what: &str,
) {
    let x: Vec<f32> = mesh.positions.chunks_exact(3).map(|p| p[0]).collect();
    let mut channels = vec![Attribute::vertex("x", 1, x)];
    let fuzzed = extra.is_some();
    let mut options = options.clone();
    if let Some(c) = extra {
        let modes = subsurf::FVarLinear::ALL;
        options.fvar_linear = modes[c.mode as usize % modes.len()];
        let mut values = c.values;
        values.truncate(16 * MAX_ELEMENTS);
        let indices = c.indices.map(|mut i| {
            i.truncate(8 * MAX_ELEMENTS);
            i
        });
        let item_size = c.item_size as usize % 18;
        channels.push(Attribute { name: "extra".into(), item_size, values, indices });
    }
    let tags = subsurf::Tags::default();
    match (subdivide_with_attributes(mesh, &channels, &options, &tags), plain) {
        (Ok((out, refined)), Ok(expected)) => {
            assert_eq!(&out, expected, "{what}: channels changed the positions");
            if let Some(extra) = refined.get(1) {
                if let Some(indices) = &extra.indices {
                    assert_eq!(indices.len(), out.indices.len(), "{what}: one index per corner");
                    assert!(indices.iter().all(|&i| (i as usize) < extra.len()), "{what}: range");
                }
            }
            let x = &refined[0];
            assert_eq!(x.len(), out.num_vertices(), "{what}: one x per vertex");
            for (p, got) in out.positions.chunks_exact(3).zip(&x.values) {
                assert!(
                    (p[0] - got).abs() <= 1e-4 * (1.0 + p[0].abs()),
                    "{what}: x {got} vs {}",
                    p[0]
                );
            }
        }
        (Err(e), Err(expected)) if !fuzzed => assert_eq!(&e, expected, "{what}"),
        (Err(e @ (Error::InvalidAttribute(_) | Error::Unsupported(_))), _) if fuzzed => {
            check_error(&e, what);
        }
        (Err(_), Err(_)) => {}
        (got, expected) => panic!("{what}: with channels {got:?}, without {expected:?}"),
    }
}

/// The evaluator against the call with the same options: see the module docs.
fn check_evaluator(mesh: &PolyMesh, options: &Options, limit: bool, what: &str) {
    let options = Options { limit, normals: true, ..options.clone() };
    let tags = subsurf::Tags::default();
    let base = HalfEdgeMesh::from_poly(mesh).expect("a valid mesh");
    let evaluator = Evaluator::new(&base, &[], &options, &tags);
    let call = subdivide_refined_with(mesh, &[], &options, &tags);
    match (evaluator, call) {
        (Ok(evaluator), Ok(mut call)) => {
            let normals_want = call.take_normals().expect("normals were asked for");
            let n = 3 * evaluator.num_vertices();
            assert_eq!(n, call.positions().len(), "{what}: output vertices");
            let (mut positions, mut normals) = (vec![0.0; n], vec![0.0; n]);
            evaluator.evaluate(&mesh.positions, &mut positions, Some(&mut normals)).unwrap();
            for (a, b) in positions.iter().zip(call.positions()) {
                assert!((a - b).abs() <= 1e-4 * (1.0 + b.abs()), "{what}: evaluator {a} vs {b}");
            }
            assert_eq!(normals.len(), normals_want.len());
            for n in normals.chunks_exact(3) {
                let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                assert!(length == 0.0 || (length - 1.0).abs() < 1e-4, "{what}: normal {n:?}");
            }
        }
        (Err(e), Err(f)) => {
            check_error(&e, what);
            assert_eq!(std::mem::discriminant(&e), std::mem::discriminant(&f), "{what}: {e} / {f}");
        }
        (Err(Error::TooLarge(_)), Ok(_)) => {}
        (got, expected) => panic!(
            "{what}: evaluator {:?}, call {:?}",
            got.map(|e| e.num_vertices()),
            expected.map(|r| r.positions().len())
        ),
    }
}

fn bounds(positions: &[f32]) -> ([f32; 3], [f32; 3]) {
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for p in positions.chunks_exact(3) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}
