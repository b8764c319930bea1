//! `mesh.attributes` through the JS API: vertex-varying channels refined with the positions'
//! weights, in `subdivide` and `BaseMesh` (with `setAttribute`), and every way to get a channel
//! wrong. The expected values are closed-form: the rules are affine, so a channel that is an
//! affine function of the positions stays that function of the refined positions.
use super::*;
use subsurf::wasm::BaseMesh;

/// An affine function of a position, 4 components.
fn affine(p: &[f32]) -> [f32; 4] {
    [p[0] + 2.0 * p[1] - p[2] + 0.5, 3.0 * p[2] - 1.0, -p[0] + 0.25 * p[1], 7.0]
}

fn channel(array: &[f32], item_size: f64) -> JsValue {
    object(&[
        ("array", Float32Array::from(array).into()),
        ("itemSize", JsValue::from_f64(item_size)),
    ])
}

/// `mesh` with `attributes` set to `channels`.
fn with_attributes(mesh: &JsValue, channels: &[(&str, JsValue)]) -> JsValue {
    let copy = Object::assign(&Object::new(), mesh.unchecked_ref());
    Reflect::set(&copy, &"attributes".into(), &object(channels)).unwrap();
    copy.into()
}

fn affine_channel(mesh: &JsValue) -> JsValue {
    let positions = f32s(mesh, "positions");
    let values: Vec<f32> = positions.chunks(3).flat_map(affine).collect();
    channel(&values, 4.0)
}

fn attribute(result: &JsValue, name: &str) -> (Vec<f32>, f64) {
    let channel = field(&field(result, "attributes"), name);
    (f32s(&channel, "array"), field(&channel, "itemSize").as_f64().unwrap())
}

fn assert_affine(result: &JsValue, what: &str) {
    let (values, item_size) = attribute(result, "a");
    assert_eq!(item_size, 4.0, "{what}");
    let positions = f32s(result, "positions");
    assert_eq!(values.len(), positions.len() / 3 * 4, "{what}: one value per vertex");
    for (v, (p, got)) in positions.chunks(3).zip(values.chunks(4)).enumerate() {
        for (k, (g, want)) in got.iter().zip(affine(p)).enumerate() {
            assert!((g - want).abs() < 1e-4, "{what}: vertex {v}[{k}] {g} vs {want}");
        }
    }
}

#[wasm_bindgen_test]
fn a_channel_follows_the_positions() {
    let mesh = with_attributes(&cube(), &[("a", affine_channel(&cube()))]);
    for scheme in ["catmull-clark", "doo-sabin", "quad-triangle", "bilinear"] {
        let options = object(&[("scheme", scheme.into()), ("levels", 2.into())]);
        assert_affine(&ok(subdivide(&mesh, &options)), scheme);
    }
    let (p, i) = tetrahedron_arrays();
    let tetra = js_mesh(&p, &i, None);
    let tetra = with_attributes(&tetra, &[("a", affine_channel(&tetra))]);
    for scheme in ["loop", "sqrt3", "midpoint"] {
        let options = object(&[("scheme", scheme.into()), ("levels", 3.into())]);
        assert_affine(&ok(subdivide(&tetra, &options)), scheme);
    }
    // Positions are those of a call without channels, and no channel means no field.
    let plain = ok(subdivide(&cube(), &levels(2.0)));
    assert_eq!(f32s(&plain, "positions"), f32s(&ok(subdivide(&mesh, &levels(2.0))), "positions"));
    assert!(field(&plain, "attributes").is_undefined());
}

#[wasm_bindgen_test]
fn several_channels_keep_their_names_and_sizes() {
    let ones = vec![1.0f32; 8];
    let mesh = with_attributes(
        &cube(),
        &[("a", affine_channel(&cube())), ("weight", channel(&ones, 1.0))],
    );
    let result = ok(subdivide(&mesh, &levels(1.0)));
    assert_affine(&result, "two channels");
    let (weight, size) = attribute(&result, "weight");
    assert_eq!(size, 1.0);
    assert_eq!(weight.len(), 26);
    assert!(weight.iter().all(|&w| (w - 1.0).abs() < 1e-6), "{weight:?}");
}

#[wasm_bindgen_test]
fn base_mesh_carries_channels_and_set_attribute_replaces_one() {
    let mesh = with_attributes(&cube(), &[("a", affine_channel(&cube()))]);
    let mut base = BaseMesh::new(&mesh).unwrap_or_else(|e| panic!("{}", message(e)));
    let once = ok(base.subdivide(&levels(2.0), &JsValue::UNDEFINED));
    assert_affine(&once, "BaseMesh");
    assert_eq!(attribute(&once, "a"), attribute(&ok(subdivide(&mesh, &levels(2.0))), "a"));

    // Moving the vertices and their channel together keeps the channel affine.
    let moved: Vec<f32> = cube_arrays().0.iter().map(|x| 2.0 * x + 1.0).collect();
    base.set_positions(&Float32Array::from(&moved[..]).into()).unwrap();
    let values: Vec<f32> = moved.chunks(3).flat_map(affine).collect();
    base.set_attribute("a", &Float32Array::from(&values[..]).into()).unwrap();
    assert_affine(&ok(base.subdivide(&levels(2.0), &JsValue::UNDEFINED)), "after setAttribute");

    let refused = [
        (
            base.set_attribute("b", &Float32Array::from(&values[..]).into()),
            &["'b'", "no such channel", "'a'"][..],
        ),
        (
            base.set_attribute("a", &Float32Array::from(&values[..31]).into()),
            &["'a'", "31 values", "multiple of itemSize 4"],
        ),
        (
            base.set_attribute("a", &Float32Array::from(&values[..28]).into()),
            &["'a'", "7 values", "8 vertices"],
        ),
        (
            base.set_attribute("a", &js_sys::Float64Array::new_with_length(32).into()),
            &["attributes.a.array", "Float32Array", "Float64Array"],
        ),
    ];
    for (result, parts) in refused {
        assert_mentions(&thrown(result), parts);
    }
    // The refused calls left the channel as it was.
    assert_affine(&ok(base.subdivide(&levels(1.0), &JsValue::UNDEFINED)), "after refusals");
}

#[wasm_bindgen_test]
fn bad_channels_are_named_and_the_module_works_on() {
    let good = affine_channel(&cube());
    let eight = |x: f32| vec![x; 8];
    let nan: Vec<f32> = (0..8).map(|i| if i == 5 { f32::NAN } else { 0.0 }).collect();
    let cases: Vec<(JsValue, &[&str])> = vec![
        (channel(&eight(0.0), 0.0), &["'a'", "itemSize must be a whole number from 1 to 16", "0"]),
        (channel(&vec![0.0; 17 * 8], 17.0), &["'a'", "itemSize", "17"]),
        (channel(&eight(0.0), 2.5), &["'a'", "itemSize", "2.5"]),
        (channel(&eight(0.0)[..7], 1.0), &["'a'", "7 values", "8 vertices"]),
        (channel(&nan, 1.0), &["'a'", "value 5", "NaN", "finite"]),
        (
            object(&[
                ("array", js_sys::Float64Array::new_with_length(8).into()),
                ("itemSize", 1.into()),
            ]),
            &["attributes.a.array must be a Float32Array", "Float64Array"],
        ),
        (
            object(&[
                ("array", Float32Array::from(&eight(0.0)[..]).into()),
                ("itemSize", 1.into()),
                ("indice", 1.into()),
            ]),
            &["'a'", "unknown channel field 'indice'", "did you mean 'indices'"],
        ),
        (
            object(&[
                ("array", Float32Array::from(&eight(0.0)[..]).into()),
                ("itemSize", 1.into()),
                ("indices", Uint32Array::from(&[0u32; 23][..]).into()),
            ]),
            &["'a'", "23 indices", "24 face corners"],
        ),
        (
            object(&[
                ("array", Float32Array::from(&eight(0.0)[..]).into()),
                ("itemSize", 1.into()),
                ("indices", Uint32Array::from(&[9u32; 24][..]).into()),
            ]),
            &["'a'", "index 0 is 9", "8 values"],
        ),
        ("red".into(), &["'a'", "must be an object", "'red'"]),
    ];
    for (bad, parts) in cases {
        let mesh = with_attributes(&cube(), &[("a", bad)]);
        assert_mentions(&thrown(subdivide(&mesh, &levels(1.0))), parts);
        assert_mentions(&thrown(BaseMesh::new(&mesh).map(|_| ())), parts);
        // The instance works on.
        assert_affine(
            &ok(subdivide(&with_attributes(&cube(), &[("a", good.clone())]), &levels(1.0))),
            "after an error",
        );
    }
    let not_an_object = {
        let copy = Object::assign(&Object::new(), cube().unchecked_ref());
        Reflect::set(&copy, &"attributes".into(), &Float32Array::new_with_length(3)).unwrap();
        JsValue::from(copy)
    };
    assert_mentions(
        &thrown(subdivide(&not_an_object, &levels(1.0))),
        &["mesh.attributes must be an object", "Float32Array"],
    );
}

#[wasm_bindgen_test]
fn channel_arrays_are_not_modified() {
    let values: Vec<f32> = f32s(&cube(), "positions").chunks(3).flat_map(affine).collect();
    let array = Float32Array::from(&values[..]);
    let mesh = with_attributes(
        &cube(),
        &[("a", object(&[("array", array.clone().into()), ("itemSize", 4.into())]))],
    );
    let result = ok(subdivide(&mesh, &levels(2.0)));
    assert_eq!(array.to_vec(), values);
    // The result's array is a fresh one, not the input's.
    assert!(!Object::is(&field(&field(&field(&result, "attributes"), "a"), "array"), &array));
}
