//! The limit options (`limit`, `normals`) and the evaluator (`BaseMesh.evaluator`) through the
//! JS API. The Rust API's results, which `tests/osd_limit_agreement.rs` and
//! `tests/evaluator.rs` check against OpenSubdiv and `subdivide`, are the expected values here:
//! the bindings must pass them through unchanged.
use super::*;
use subsurf::evaluator::subdivide_closed;
use subsurf::wasm::BaseMesh;
use subsurf::{scheme, HalfEdgeMesh, Options, PolyMesh, Scheme, Tags};

fn cube_poly() -> PolyMesh {
    let (positions, indices, face_sizes) = cube_arrays();
    PolyMesh { positions, indices, face_sizes }
}

fn limit_options(levels: f64, limit: bool, normals: bool) -> JsValue {
    object(&[
        ("levels", JsValue::from_f64(levels)),
        ("limit", JsValue::from_bool(limit)),
        ("normals", JsValue::from_bool(normals)),
    ])
}

/// A twist of the cube's corners, as an animation frame would move them.
fn twisted(positions: &[f32], t: f32) -> Vec<f32> {
    let mut out = positions.to_vec();
    for p in out.chunks_exact_mut(3) {
        let (s, c) = (t * p[1]).sin_cos();
        let (x, z) = (p[0], p[2]);
        p[0] = c * x - s * z;
        p[2] = s * x + c * z;
    }
    out
}

fn within(a: &[f32], b: &[f32], tolerance: f32) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tolerance)
}

/// The Rust result the bindings pass on for the limit with normals: on a closed cage with no
/// tags and no attributes the closed forms' (`subdivide_closed`), else `subdivide`'s masks.
fn rust_limit(mesh: &PolyMesh, options: &Options) -> (Vec<f32>, Vec<f32>) {
    let base = HalfEdgeMesh::from_poly(mesh).unwrap();
    let none = Tags::default();
    let mut refined = match subdivide_closed(&base, &[], options, &none).unwrap() {
        Some(closed) => closed,
        None => scheme::subdivide_refined_with(mesh, &[], options, &none).unwrap(),
    };
    let normals = refined.take_normals().unwrap();
    (refined.positions().to_vec(), normals)
}

#[wasm_bindgen_test]
fn limit_and_normals_options_give_the_rust_results() {
    let options = Options { limit: true, normals: true, ..Options::new(Scheme::CatmullClark, 2) };
    // The cube, closed, takes the closed forms; without its last face, the masks.
    let closed = cube_poly();
    let mut open = cube_poly();
    open.indices.truncate(open.indices.len() - 4);
    open.face_sizes.pop();
    for (name, mesh) in [("closed", &closed), ("open", &open)] {
        let (want_positions, want_normals) = rust_limit(mesh, &options);
        let js = js_mesh(&mesh.positions, &mesh.indices, Some(&mesh.face_sizes));
        let out = ok(subdivide(&js, &limit_options(2.0, true, true)));
        assert_eq!(f32s(&out, "positions"), want_positions, "{name}");
        assert_eq!(f32s(&out, "normals"), want_normals, "{name}");
        for n in want_normals.chunks_exact(3) {
            let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            assert!((length - 1.0).abs() < 1e-5, "{name}");
        }
    }
    // Without `normals`, none; with `normals` alone, the points stay where the level put them
    // (to f32 rounding: the closed forms' steps sum in their own order), with the same
    // normals.
    let limit_only = ok(subdivide(&cube(), &limit_options(2.0, true, false)));
    assert!(field(&limit_only, "normals").is_undefined());
    let normals_only = ok(subdivide(&cube(), &limit_options(2.0, false, true)));
    let plain = ok(subdivide(&cube(), &levels(2.0)));
    assert!(within(&f32s(&normals_only, "positions"), &f32s(&plain, "positions"), 1e-6));
    let (_, want_normals) = rust_limit(&closed, &options);
    assert!(within(&f32s(&normals_only, "normals"), &want_normals, 1e-5));
}

#[wasm_bindgen_test]
fn limit_options_are_checked() {
    let bad = object(&[("limit", JsValue::from_f64(1.0))]);
    assert_mentions(&thrown(subdivide(&cube(), &bad)), &["limit must be true or false, got 1"]);
    let bad = object(&[("normals", "yes".into())]);
    assert_mentions(&thrown(subdivide(&cube(), &bad)), &["normals must be true or false"]);
    let doo_sabin = object(&[("scheme", "doo-sabin".into()), ("limit", JsValue::TRUE)]);
    let message = thrown(subdivide(&cube(), &doo_sabin));
    assert_mentions(&message, &["limit: true is not available", "doo-sabin", "normals: true"]);
    // The module keeps working.
    assert!(subdivide(&cube(), &limit_options(1.0, true, true)).is_ok());
}

#[wasm_bindgen_test]
fn an_evaluator_gives_subdivide_for_every_frame() {
    let base = BaseMesh::new(&cube()).unwrap();
    let options = limit_options(2.0, true, true);
    let mut evaluator = base.evaluator(&options).unwrap();
    assert_eq!(evaluator.num_control_vertices(), 8);
    assert_eq!(evaluator.num_vertices(), 98);
    assert!(evaluator.has_normals());
    // At build time, the result is subdivide's (the points to rounding: the table gives them).
    let built = ok(evaluator.result());
    let plain = ok(subdivide(&cube(), &options));
    for key in ["indices", "faceSizes", "triangles"] {
        assert_eq!(u32s(&built, key), u32s(&plain, key), "{key}");
    }
    assert!(within(&f32s(&built, "positions"), &f32s(&plain, "positions"), 1e-5));
    assert!(within(&f32s(&built, "normals"), &f32s(&plain, "normals"), 1e-4));
    let mut frame = JsValue::UNDEFINED;
    for t in [0.0f32, 0.5, 1.3] {
        let moved = twisted(&cube_arrays().0, t);
        let next = ok(evaluator.evaluate(&Float32Array::from(&moved[..]).into(), &frame));
        if !frame.is_undefined() {
            assert!(Object::is(&field(&next, "positions"), &field(&frame, "positions")), "reused");
        }
        let (_, i, s) = cube_arrays();
        let want = ok(subdivide(&js_mesh(&moved, &i, Some(&s)), &options));
        assert!(within(&f32s(&next, "positions"), &f32s(&want, "positions"), 1e-5), "t {t}");
        assert!(within(&f32s(&next, "normals"), &f32s(&want, "normals"), 1e-4), "t {t}");
        frame = next;
    }
    // The stencil arrays: CSR rows over the control vertices.
    let stencils = ok(evaluator.stencils());
    let offsets = u32s(&stencils, "offsets");
    assert_eq!(offsets.len(), 99);
    assert_eq!(*offsets.last().unwrap() as usize, u32s(&stencils, "indices").len());
    assert_eq!(f32s(&stencils, "weights").len(), u32s(&stencils, "indices").len());
    let tangents: Array = field(&stencils, "tangentWeights").dyn_into().unwrap();
    assert_eq!(tangents.length(), 2);
    // Vertex-varying data through the same stencils: the positions themselves.
    let same = evaluator
        .evaluate_attribute(
            &Float32Array::from(&cube_arrays().0[..]).into(),
            3,
            &JsValue::UNDEFINED,
        )
        .unwrap();
    assert!(within(&same.to_vec(), &f32s(&plain, "positions"), 1e-5));
}

/// `evaluateView` gives `evaluate`'s frame bit for bit, as views of the module's memory that
/// the evaluator's next frame writes over; it throws as `evaluate` does, and `evaluate` lends
/// no view's arrays (it makes fresh ones).
#[wasm_bindgen_test]
fn an_evaluator_view_is_its_frame_in_place() {
    let base = BaseMesh::new(&cube()).unwrap();
    let mut evaluator = base.evaluator(&limit_options(2.0, true, true)).unwrap();
    let frame_at = |t: f32| JsValue::from(Float32Array::from(&twisted(&cube_arrays().0, t)[..]));
    let copied = ok(evaluator.evaluate(&frame_at(0.5), &JsValue::UNDEFINED));
    let view = ok(evaluator.evaluate_view(&frame_at(0.5)));
    let memory = Reflect::get(&wasm_bindgen::memory(), &"buffer".into()).unwrap();
    for key in ["positions", "normals"] {
        assert_eq!(f32s(&view, key), f32s(&copied, key), "{key}");
        let array: Float32Array = field(&view, key).dyn_into().unwrap();
        assert_eq!(JsValue::from(array.buffer()), memory, "{key} is a view of the memory");
    }
    let next = ok(evaluator.evaluate(&frame_at(1.3), &view));
    assert!(!Object::is(&field(&next, "positions"), &field(&view, "positions")), "not lent");
    assert_eq!(f32s(&view, "positions"), f32s(&next, "positions"), "written over");
    assert_ne!(f32s(&view, "positions"), f32s(&copied, "positions"));
    let short: JsValue = Float32Array::new_with_length(9).into();
    assert_mentions(
        &thrown(evaluator.evaluate_view(&short)),
        &["evaluateView: positions has 9 floats; expected 24"],
    );
    let array: JsValue = Array::of1(&1.into()).into();
    assert_mentions(
        &thrown(evaluator.evaluate_view(&array)),
        &["evaluateView: positions must be a Float32Array"],
    );
    assert_eq!(
        f32s(&ok(evaluator.evaluate_view(&frame_at(0.5))), "normals"),
        f32s(&copied, "normals")
    );
}

#[wasm_bindgen_test]
fn evaluator_errors_are_clear_and_it_keeps_working() {
    let base = BaseMesh::new(&cube()).unwrap();
    let mut evaluator = base.evaluator(&limit_options(1.0, true, true)).unwrap();
    let positions: JsValue = Float32Array::from(&cube_arrays().0[..]).into();
    let good = ok(evaluator.evaluate(&positions, &JsValue::UNDEFINED));
    let array: JsValue = Array::of3(&1.into(), &2.into(), &3.into()).into();
    assert_mentions(
        &thrown(evaluator.evaluate(&array, &JsValue::UNDEFINED)),
        &["evaluate: positions must be a Float32Array", "new Float32Array(array)"],
    );
    let short: JsValue = Float32Array::new_with_length(9).into();
    assert_mentions(
        &thrown(evaluator.evaluate(&short, &JsValue::UNDEFINED)),
        &["has 9 floats; expected 24"],
    );
    let mut nan = cube_arrays().0;
    nan[5] = f32::NAN;
    let nan: JsValue = Float32Array::from(&nan[..]).into();
    assert_mentions(
        &thrown(evaluator.evaluate(&nan, &JsValue::UNDEFINED)),
        &["positions[5] (vertex 1, z) is NaN", "finite"],
    );
    assert_mentions(
        &thrown(evaluator.evaluate_attribute(&positions, 0, &JsValue::UNDEFINED)),
        &["itemSize is 0"],
    );
    assert_mentions(
        &thrown(evaluator.evaluate_attribute(&nan, 3, &JsValue::UNDEFINED)),
        &["evaluateAttribute: values[5] (vertex 1, component 2) is NaN", "finite"],
    );
    let mut huge = cube_arrays().0;
    huge[7] = 1e35;
    let huge: JsValue = Float32Array::from(&huge[..]).into();
    assert_mentions(
        &thrown(evaluator.evaluate(&huge, &JsValue::UNDEFINED)),
        &["positions[7]", "±1e30"],
    );
    // A failed call leaves the lent frame alone, and the evaluator works on.
    let before = f32s(&good, "positions");
    let _ = evaluator.evaluate(&short, &good);
    assert_eq!(f32s(&good, "positions"), before);
    // The evaluator owns its table: freeing the base mesh leaves it working.
    // (JS's `free()` is this drop.)
    drop(base);
    let again = ok(evaluator.evaluate(&positions, &JsValue::UNDEFINED));
    assert_eq!(f32s(&again, "positions"), before);
    // Options are checked when it is built.
    let base = BaseMesh::new(&cube()).unwrap();
    let sqrt3 = object(&[("scheme", "doo-sabin".into()), ("limit", JsValue::TRUE)]);
    assert_mentions(&thrown(base.evaluator(&sqrt3).map(|_| ())), &["doo-sabin"]);
    let huge =
        object(&[("levels", JsValue::from_f64(3.0)), ("maxBytes", JsValue::from_f64(1000.0))]);
    assert_mentions(&thrown(base.evaluator(&huge).map(|_| ())), &["maxBytes"]);
}

/// On a torus every face is regular, so at the limit the evaluator gives every point (and its
/// normal) from a bicubic patch (`Evaluator::patch_vertices`): `subdivide`'s surface, which
/// takes the limit masks.
#[wasm_bindgen_test]
fn an_evaluator_on_regular_faces_gives_subdivide() {
    let torus = subsurf::shapes::torus(12, 9, 2.0, 0.5);
    let mesh = js_mesh(&torus.positions, &torus.indices, Some(&torus.face_sizes));
    let base = BaseMesh::new(&mesh).unwrap();
    for (levels, normals) in [(1.0, false), (2.0, false), (1.0, true), (2.0, true)] {
        let options = limit_options(levels, true, normals);
        let mut evaluator = base.evaluator(&options).unwrap();
        let plain = ok(subdivide(&mesh, &options));
        let frame = ok(evaluator
            .evaluate(&Float32Array::from(&torus.positions[..]).into(), &JsValue::UNDEFINED));
        assert!(within(&f32s(&frame, "positions"), &f32s(&plain, "positions"), 1e-5));
        if normals {
            assert!(within(&f32s(&frame, "normals"), &f32s(&plain, "normals"), 1e-4));
        }
    }
}

/// The closed forms of a triangle cage, in wasm: Loop's (the level before's regular vertices
/// and edges, the fans of the others, and from level 3 the nested level) and Catmull-Clark's
/// (the last level by the rules, then its limit masks), with their normals written in runs of
/// four. A frame equals `subdivide` at levels 1 to 3 on closed triangle meshes, one of valence
/// 6 everywhere and one of valence 5 everywhere.
#[wasm_bindgen_test]
fn evaluators_on_closed_triangle_cages_give_subdivide() {
    let shapes =
        [subsurf::shapes::torus_triangles(12, 9, 2.0, 0.5), subsurf::shapes::icosahedron()];
    for shape in shapes {
        let mesh = js_mesh(&shape.positions, &shape.indices, Some(&shape.face_sizes));
        let base = BaseMesh::new(&mesh).unwrap();
        for (scheme, levels) in [1.0, 2.0, 3.0]
            .map(|l| ("loop", l))
            .into_iter()
            .chain([1.0, 2.0, 3.0].map(|l| ("catmull-clark", l)))
        {
            let options = limit_options(levels, true, true);
            Reflect::set(&options, &"scheme".into(), &scheme.into()).unwrap();
            let mut evaluator = base.evaluator(&options).unwrap();
            let moved = twisted(&shape.positions, 0.7);
            let frame =
                ok(evaluator.evaluate(&Float32Array::from(&moved[..]).into(), &JsValue::UNDEFINED));
            let want =
                ok(subdivide(&js_mesh(&moved, &shape.indices, Some(&shape.face_sizes)), &options));
            for (key, tolerance) in [("positions", 1e-5), ("normals", 1e-4)] {
                let (got, want) = (f32s(&frame, key), f32s(&want, key));
                assert!(
                    within(&got, &want, tolerance),
                    "{scheme} {key}, {} faces, level {levels}",
                    shape.face_sizes.len()
                );
            }
        }
    }
}
