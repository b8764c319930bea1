//! Reuse across calls: `subdivide`'s `into` (a previous result lends its arrays) and `BaseMesh`
//! (the mesh built once, subdivided again with other options or other positions). The expected
//! values are those of a plain `subdivide` call on the same input, which the other cases check
//! against the seeds and OpenSubdiv; here the results must be identical to it, bit for bit,
//! since the same arithmetic runs.
use super::*;
use subsurf::wasm::BaseMesh;

const RESULT_KEYS: [&str; 4] = ["positions", "indices", "faceSizes", "triangles"];

fn into(mesh: &JsValue, options: &JsValue, lent: &JsValue) -> JsValue {
    ok(subsurf::wasm::subdivide(mesh, options, lent))
}

fn same(a: &JsValue, b: &JsValue) -> bool {
    Object::is(a, b)
}

/// Equal arrays, key by key.
fn assert_same_values(a: &JsValue, b: &JsValue, what: &str) {
    assert_eq!(f32s(a, "positions"), f32s(b, "positions"), "{what}: positions");
    for key in &RESULT_KEYS[1..] {
        assert_eq!(u32s(a, key), u32s(b, key), "{what}: {key}");
    }
}

/// The cube with every coordinate doubled and shifted by 1 (a vertex count of 8).
fn moved_cube_positions() -> Vec<f32> {
    cube_arrays().0.iter().map(|x| 2.0 * x + 1.0).collect()
}

fn moved_cube() -> JsValue {
    let (_, i, s) = cube_arrays();
    js_mesh(&moved_cube_positions(), &i, Some(&s))
}

#[wasm_bindgen_test]
fn into_arrays_of_the_right_length_are_written_over() {
    let first = ok(subdivide(&cube(), &levels(2.0)));
    let second = into(&moved_cube(), &levels(2.0), &first);
    for key in RESULT_KEYS {
        assert!(same(&field(&second, key), &field(&first, key)), "{key} reused");
    }
    assert!(!same(&second, &first), "the result is a new object");
    let fresh = ok(subdivide(&moved_cube(), &levels(2.0)));
    assert_same_values(&second, &fresh, "written over");

    // Level 1 needs other lengths: fresh arrays, and the lent ones are left alone.
    let third = into(&cube(), &levels(1.0), &second);
    for key in RESULT_KEYS {
        assert!(!same(&field(&third, key), &field(&second, key)), "{key} not reused");
    }
    assert_same_values(&third, &ok(subdivide(&cube(), &levels(1.0))), "fresh");
    assert_same_values(&second, &fresh, "the lent arrays that did not fit");
}

#[wasm_bindgen_test]
fn into_arrays_of_another_type_or_lent_twice_are_not_reused() {
    let (p, i) = tetrahedron_arrays();
    let tetra = js_mesh(&p, &i, None);
    let options = object(&[("scheme", "loop".into())]);
    let expected = ok(subdivide(&tetra, &options));
    // Loop's result has as many indices as triangle indices (48), so one array fits both.
    let shared: JsValue = Uint32Array::new_with_length(48).into();
    let wrong_type: JsValue = Uint32Array::new_with_length(3 * 10).into();
    let lent = object(&[
        ("positions", wrong_type.clone()),
        ("indices", shared.clone()),
        ("triangles", shared.clone()),
    ]);
    let out = into(&tetra, &options, &lent);
    assert!(!same(&field(&out, "positions"), &wrong_type));
    assert!(field(&out, "positions").is_instance_of::<Float32Array>());
    let reused = [same(&field(&out, "indices"), &shared), same(&field(&out, "triangles"), &shared)];
    assert_eq!(reused.iter().filter(|&&r| r).count(), 1, "one field gets the array: {reused:?}");
    assert_same_values(&out, &expected, "partly lent");
}

/// The writes would corrupt the module's own memory: such an array is never used.
#[wasm_bindgen_test]
fn into_views_of_wasm_memory_are_not_written() {
    let expected = ok(subdivide(&cube(), &levels(1.0)));
    let buffer = field(&wasm_bindgen::memory(), "buffer");
    let length = f32s(&expected, "positions").len() as u32;
    let view = Float32Array::new_with_byte_offset_and_length(&buffer, 0, length);
    let before = view.to_vec();
    let out = into(&cube(), &levels(1.0), &object(&[("positions", view.clone().into())]));
    assert!(!same(&field(&out, "positions"), &view));
    assert_eq!(view.to_vec(), before);
    assert_same_values(&out, &expected, "not lent");
}

#[wasm_bindgen_test]
fn into_that_is_not_an_object_is_refused() {
    for (value, shown) in [(JsValue::from_f64(5.0), "5"), ("out".into(), "string 'out'")] {
        let m = thrown(subsurf::wasm::subdivide(&cube(), &levels(1.0), &value));
        assert_mentions(&m, &["into must be a result of an earlier subdivide call", shown]);
    }
    let array: JsValue = Array::new().into();
    assert_mentions(&thrown(subsurf::wasm::subdivide(&cube(), &levels(1.0), &array)), &["Array"]);
    // null and undefined mean no reuse.
    assert_same_values(
        &into(&cube(), &levels(1.0), &JsValue::NULL),
        &ok(subdivide(&cube(), &levels(1.0))),
        "null",
    );
}

#[wasm_bindgen_test]
fn base_mesh_gives_what_subdivide_gives() {
    let (p, i) = tetrahedron_arrays();
    let tetra = js_mesh(&p, &i, None);
    let crease = object(&[
        ("edges", Uint32Array::from(&[0u32, 1][..]).into()),
        ("sharpness", Float32Array::from(&[2.5f32][..]).into()),
    ]);
    let cases = [
        // A single quad split keeps the base as the parent of its implicit faces.
        (cube(), levels(1.0)),
        (cube(), levels(3.0)),
        (cube(), object(&[("scheme", "doo-sabin".into()), ("levels", 2.into())])),
        (cube(), object(&[("creases", crease), ("levels", 2.into())])),
        (tetra.clone(), object(&[("scheme", "loop".into()), ("levels", 2.into())])),
        (tetra, object(&[("scheme", "sqrt3".into()), ("levels", 0.into())])),
    ];
    for (n, (mesh, options)) in cases.iter().enumerate() {
        let base = BaseMesh::new(mesh).unwrap_or_else(|e| panic!("case {n}: {}", message(e)));
        let expected = ok(subdivide(mesh, options));
        let first = ok(base.subdivide(options, &JsValue::UNDEFINED));
        assert_same_values(&first, &expected, &format!("case {n}"));
        let again = ok(base.subdivide(options, &first));
        assert!(same(&field(&again, "positions"), &field(&first, "positions")));
        assert_same_values(&again, &expected, &format!("case {n}, again into the first"));
    }
}

#[wasm_bindgen_test]
fn base_mesh_set_positions_moves_the_result() {
    let mut base = BaseMesh::new(&cube()).unwrap_or_else(|e| panic!("{}", message(e)));
    assert_eq!((base.num_vertices(), base.num_faces()), (8, 6));
    let moved = Float32Array::from(&moved_cube_positions()[..]);
    base.set_positions(&moved).unwrap_or_else(|e| panic!("{}", message(e)));
    let expected = ok(subdivide(&moved_cube(), &levels(2.0)));
    assert_same_values(&ok(base.subdivide(&levels(2.0), &JsValue::UNDEFINED)), &expected, "moved");

    let mut nan = moved_cube_positions();
    nan[3 * 3 + 1] = f32::NAN;
    let refused: [(JsValue, &[&str]); 4] = [
        (Float32Array::new_with_length(21).into(), &["7 vertices", "the mesh has 8"]),
        (Float32Array::new_with_length(25).into(), &["25", "3"]),
        (Float32Array::from(&nan[..]).into(), &["vertex 3 has coordinate y = NaN"]),
        (Array::of1(&1.into()).into(), &["positions must be a Float32Array", "Array"]),
    ];
    for (positions, parts) in refused {
        assert_mentions(&thrown(base.set_positions(&positions)), parts);
    }
    let after = ok(base.subdivide(&levels(2.0), &JsValue::UNDEFINED));
    assert_same_values(&after, &expected, "unchanged by the refused calls");
    assert_eq!(moved.to_vec(), moved_cube_positions(), "the caller's array is only read");
}

#[wasm_bindgen_test]
fn base_mesh_refuses_what_subdivide_refuses() {
    let (p, mut i, s) = cube_arrays();
    i[5] = 99;
    let bad = js_mesh(&p, &i, Some(&s));
    let from_subdivide = thrown(subdivide(&bad, &levels(1.0)));
    let from_base = thrown(BaseMesh::new(&bad).map(|base| base.num_faces()));
    assert_eq!(from_base, from_subdivide);
    assert_mentions(&from_base, &["99"]);
    let base = BaseMesh::new(&cube()).unwrap_or_else(|e| panic!("{}", message(e)));
    assert_mentions(&thrown(base.subdivide(&levels_typo(), &JsValue::UNDEFINED)), &["'levels'"]);
    let too_many = object(&[("levels", 9.into()), ("maxFaces", 1000.into())]);
    assert_mentions(&thrown(base.subdivide(&too_many, &JsValue::UNDEFINED)), &["maxFaces"]);
    assert_eq!(u32s(&ok(base.subdivide(&levels(1.0), &JsValue::UNDEFINED)), "faceSizes").len(), 24);
}

/// An `into` a page can pass by mistake or on purpose. Its getters may throw (an error naming
/// the field); its arrays may be detached, lie about their `length`, or shadow `set` and `fill`
/// (none of that code runs: the intrinsics size and write them, so a lying array is not reused
/// and a shadowed method is not called). The result is always the plain call's.
#[wasm_bindgen_test]
fn hostile_into_objects_give_errors_or_fresh_arrays() {
    use super::bad_inputs::js;
    let expected = ok(subdivide(&cube(), &levels(1.0)));
    let refused = [
        (
            "return { get positions() { throw new Error('boom'); } }",
            "reading into.positions threw Error 'boom'",
        ),
        (
            "return new Proxy({}, { get() { throw new Error('trap'); } })",
            "reading into.positions threw Error 'trap'",
        ),
    ];
    for (body, part) in refused {
        assert_mentions(
            &thrown(subsurf::wasm::subdivide(&cube(), &levels(1.0), &js(body))),
            &[part],
        );
    }
    let lying = "const a = new Float32Array(5); Object.defineProperty(a, 'length', { value: 78 }); return { positions: a };";
    let detached = "const a = new Uint32Array(96); structuredClone(a.buffer, { transfer: [a.buffer] }); return { indices: a };";
    let shadowing = "const no = () => { throw new Error('called'); }; const t = new Uint32Array(144); t.set = no; const f = new Uint32Array(24); f.fill = no; return { triangles: t, faceSizes: f };";
    for body in [lying, detached, shadowing] {
        let lent = js(body);
        let out = into(&cube(), &levels(1.0), &lent);
        assert_same_values(&out, &expected, body);
        let reused: Vec<_> =
            RESULT_KEYS.iter().filter(|k| same(&field(&out, k), &field(&lent, k))).collect();
        let expect_reused: &[&str] =
            if body == shadowing { &["faceSizes", "triangles"] } else { &[] };
        assert_eq!(reused, expect_reused.iter().collect::<Vec<_>>(), "{body}");
    }
}

/// `predictCounts` and `BaseMesh.predictCounts` give the sizes after 0..levels levels. For
/// Catmull-Clark on the cube they follow V' = V + E + F, F' = 4F, E' = 2E + 4F (8/12/6 to
/// 26/48/24 to 98/192/96 to 386/768/384; level 1 is seed 003's cube), and they are the sizes
/// `subdivide` returns.
#[wasm_bindgen_test]
fn predicted_counts_with_and_without_base_mesh() {
    use subsurf::wasm::predict_counts;
    let f64s = |object: &JsValue, key: &str| -> Vec<f64> {
        field(object, key).dyn_into::<js_sys::Float64Array>().expect(key).to_vec()
    };
    let base = BaseMesh::new(&cube()).unwrap_or_else(|e| panic!("{}", message(e)));
    let from_mesh = ok(predict_counts(&cube(), &levels(3.0)));
    let from_base = ok(base.predict_counts(&levels(3.0)));
    for predicted in [&from_mesh, &from_base] {
        assert_eq!(f64s(predicted, "vertices"), [8.0, 26.0, 98.0, 386.0]);
        assert_eq!(f64s(predicted, "faces"), [6.0, 24.0, 96.0, 384.0]);
    }
    for level in 1..=3 {
        let out = ok(base.subdivide(&levels(level as f64), &JsValue::UNDEFINED));
        assert_eq!(f32s(&out, "positions").len() as f64, 3.0 * f64s(&from_base, "vertices")[level]);
        assert_eq!(u32s(&out, "faceSizes").len() as f64, f64s(&from_base, "faces")[level]);
    }
    assert_mentions(&thrown(base.predict_counts(&levels_typo())), &["'levels'"]);
}

/// The cube with its demo UV layout (a face-varying `uv`, seams on 7 edges) and a vertex-varying
/// `color`, as a JS mesh.
fn textured_cube() -> JsValue {
    let mesh = ok(subsurf::wasm::shape(&"cube".into()));
    let color = Float32Array::from(&cube_arrays().0[..]);
    let channels = field(&mesh, "attributes");
    let channel = object(&[("array", color.into()), ("itemSize", JsValue::from_f64(3.0))]);
    Reflect::set(&channels, &"color".into(), &channel).unwrap();
    mesh
}

/// The channels' arrays of a result, as `(name, key)` and the array.
const CHANNEL_ARRAYS: [(&str, &str); 3] = [("uv", "array"), ("uv", "indices"), ("color", "array")];

fn channel_field(result: &JsValue, name: &str, key: &str) -> JsValue {
    field(&field(&field(result, "attributes"), name), key)
}

/// A channel array's numbers, whichever of the two types it is.
fn numbers(result: &JsValue, name: &str, key: &str) -> Vec<f64> {
    let channel = field(&field(result, "attributes"), name);
    match key {
        "indices" => u32s(&channel, key).into_iter().map(f64::from).collect(),
        _ => f32s(&channel, key).into_iter().map(f64::from).collect(),
    }
}

/// `into.attributes` lends the channels' arrays too: written over when their type and length
/// fit (the face-varying indices of a last Catmull-Clark level are made piece by piece, those
/// of a level with a hole are listed), fresh otherwise; the values are a plain call's, bit for
/// bit.
#[wasm_bindgen_test]
fn into_attribute_arrays_are_written_over_when_they_fit() {
    let mesh = textured_cube();
    let holed = object(&[("levels", 1.into()), ("holes", Uint32Array::from(&[5u32][..]).into())]);
    for options in [levels(2.0), holed] {
        let first = ok(subdivide(&mesh, &options));
        let second = into(&mesh, &options, &first);
        let expected = ok(subdivide(&mesh, &options));
        for (name, key) in CHANNEL_ARRAYS {
            let reused =
                same(&channel_field(&second, name, key), &channel_field(&first, name, key));
            assert!(reused, "{name}.{key} reused");
            assert_eq!(numbers(&second, name, key), numbers(&expected, name, key), "{name}.{key}");
        }
        assert_same_values(&second, &expected, "with channels");
    }
    // Another level: other lengths, fresh arrays, and the lent ones are left alone.
    let first = ok(subdivide(&mesh, &levels(1.0)));
    let before: Vec<_> = CHANNEL_ARRAYS.iter().map(|(n, k)| numbers(&first, n, k)).collect();
    let second = into(&mesh, &levels(2.0), &first);
    for ((name, key), before) in CHANNEL_ARRAYS.into_iter().zip(before) {
        let reused = same(&channel_field(&second, name, key), &channel_field(&first, name, key));
        assert!(!reused, "{name}.{key} not reused");
        assert_eq!(numbers(&first, name, key), before, "{name}.{key} untouched");
    }
}

/// A channel array lent for two fields serves one at most, one of another type is not used, and
/// a hostile `into.attributes` gives an error naming the place (a throwing getter) or fresh
/// arrays; the result is always the plain call's.
#[wasm_bindgen_test]
fn into_attribute_arrays_lent_twice_or_wrong_are_not_reused() {
    use super::bad_inputs::js;
    let mesh = textured_cube();
    let expected = ok(subdivide(&mesh, &levels(1.0)));
    let indices = field(&expected, "indices");
    let uv = field(&field(&expected, "attributes"), "uv");
    // The uv indices have the faces' length: the same array lent for both serves one.
    let shared = Uint32Array::new_with_length(u32s(&expected, "indices").len() as u32);
    let uv_lent = object(&[("indices", shared.clone().into()), ("array", indices.clone())]);
    let lent =
        object(&[("indices", shared.clone().into()), ("attributes", object(&[("uv", uv_lent)]))]);
    let out = into(&mesh, &levels(1.0), &lent);
    let out_uv = field(&field(&out, "attributes"), "uv");
    let reused =
        [same(&field(&out, "indices"), &shared), same(&field(&out_uv, "indices"), &shared)];
    assert_eq!(reused.iter().filter(|&&r| r).count(), 1, "{reused:?}");
    assert!(!same(&field(&out_uv, "array"), &indices), "a Uint32Array is no uv array");
    assert_same_values(&out, &expected, "lent twice");
    assert_eq!(f32s(&out_uv, "array"), f32s(&uv, "array"));
    assert_eq!(u32s(&out_uv, "indices"), u32s(&uv, "indices"));

    let thrower = "return { attributes: { uv: { get array() { throw new Error('boom'); } } } };";
    let m = thrown(subsurf::wasm::subdivide(&mesh, &levels(1.0), &js(thrower)));
    assert_mentions(&m, &["reading into.attributes.uv.array threw Error 'boom'"]);
    let proxy = "return { attributes: new Proxy({}, { ownKeys() { throw new Error('keys'); } }) };";
    let m = thrown(subsurf::wasm::subdivide(&mesh, &levels(1.0), &js(proxy)));
    assert_mentions(&m, &["listing into.attributes threw Error 'keys'"]);
    for body in ["return { attributes: 5 };", "return { attributes: { uv: 'no' } };"] {
        let out = into(&mesh, &levels(1.0), &js(body));
        assert_same_values(&out, &expected, body);
    }
}
