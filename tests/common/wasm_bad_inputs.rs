//! Bad input never breaks subsurf, through the JS API in Node and in headless Chromium: every case
//! of the catalogue in `bad_inputs.rs` (shared with the Rust API and CLI runners of
//! `tests/bad_inputs.rs`), each followed by a good call on the same module instance; and the
//! caller's typed arrays stay byte-identical through every scheme.

use super::*;

#[path = "bad_inputs.rs"]
pub(super) mod catalogue;

use catalogue::{Case, Channel, Expect, Input, JsField, JsMesh, Stage, Val};

fn js_value(value: &Val) -> JsValue {
    match value {
        Val::Str(s) => JsValue::from_str(s),
        Val::Num(n) => JsValue::from_f64(*n),
        Val::List(names) => names.iter().map(|n| JsValue::from_str(n)).collect::<Array>().into(),
        Val::Bool(b) => JsValue::from_bool(*b),
    }
}

fn js_options(case: &Case) -> JsValue {
    if let Some(value) = &case.options.not_an_object {
        return js_value(value);
    }
    if case.options.entries.is_empty() {
        return JsValue::UNDEFINED;
    }
    let fields: Vec<(&str, JsValue)> =
        case.options.entries.iter().map(|(k, v)| (*k, js_value(v))).collect();
    object(&fields)
}

fn js_field(field: &JsField) -> Option<JsValue> {
    Some(match field {
        JsField::Float32(v) => Float32Array::from(&v[..]).into(),
        JsField::Uint32(v) => Uint32Array::from(&v[..]).into(),
        JsField::Float64(v) => js_sys::Float64Array::from(&v[..]).into(),
        JsField::Int32(v) => js_sys::Int32Array::from(&v[..]).into(),
        JsField::Uint8(v) => js_sys::Uint8Array::from(&v[..]).into(),
        JsField::Plain(v) => v.iter().map(|&x| JsValue::from_f64(x)).collect::<Array>().into(),
        JsField::Missing => return None,
    })
}

fn js_mesh_object(mesh: &JsMesh) -> JsValue {
    if let Some(value) = &mesh.not_an_object {
        return js_value(value);
    }
    let mut fields = Vec::new();
    for (key, field) in [
        ("positions", &mesh.positions),
        ("indices", &mesh.indices),
        ("faceSizes", &mesh.face_sizes),
    ] {
        if let Some(value) = js_field(field) {
            fields.push((key, value));
        }
    }
    if let Some(extra) = mesh.extra {
        fields.push((extra, Uint32Array::from(&[4u32; 6][..]).into()));
    }
    object(&fields)
}

/// The catalogue's cube with `mesh.attributes = { [c.name]: channel }`.
fn js_channel_mesh(c: &Channel) -> JsValue {
    let mut fields = vec![("itemSize", JsValue::from_f64(c.item_size))];
    if let Some(array) = js_field(&c.array) {
        fields.push(("array", array));
    }
    if let Some(indices) = c.indices.as_ref().and_then(js_field) {
        fields.push(("indices", indices));
    }
    if let Some(extra) = c.extra {
        fields.push((extra, JsValue::from_f64(c.item_size)));
    }
    let (p, i, f) = cube_arrays();
    let mesh = js_mesh(&p, &i, Some(&f));
    Reflect::set(&mesh, &"attributes".into(), &object(&[(c.name, object(&fields))])).unwrap();
    mesh
}

/// A copy of every typed array of a mesh object, to check it is unchanged afterwards.
fn snapshot(mesh: &JsValue) -> Vec<(String, Vec<u8>)> {
    if !mesh.is_object() {
        return Vec::new();
    }
    let keys = Object::keys(mesh.unchecked_ref::<Object>());
    keys.iter()
        .filter_map(|key| {
            let value = Reflect::get(mesh, &key).ok()?;
            if !js_sys::ArrayBuffer::is_view(&value) {
                return None;
            }
            let view: js_sys::Uint8Array = js_sys::Uint8Array::new_with_byte_offset_and_length(
                &Reflect::get(&value, &"buffer".into()).ok()?,
                Reflect::get(&value, &"byteOffset".into()).ok()?.as_f64()? as u32,
                Reflect::get(&value, &"byteLength".into()).ok()?.as_f64()? as u32,
            );
            Some((key.as_string()?, view.to_vec()))
        })
        .collect()
}

/// The good call after every bad one: the cube at level 1 is 26 vertices and 24 quads, and its
/// first corner moves to 5/9 of itself (seed 003).
fn module_still_works(after: &str) {
    let out = match subdivide(&cube(), &levels(1.0)) {
        Ok(out) => out,
        Err(e) => panic!("after {after}: the good call failed: {}", message(e)),
    };
    assert_eq!(f32s(&out, "positions").len(), 3 * 26, "after {after}: vertices");
    assert_eq!(u32s(&out, "faceSizes"), vec![4; 24], "after {after}: faces");
    assert!(close(&point(&f32s(&out, "positions"), 0), &[-5.0 / 9.0; 3]), "after {after}");
}

/// The message of a call that must fail, checked for every fragment.
fn expect_error<E: Into<JsValue>>(
    name: &str,
    what: &str,
    result: Result<JsValue, E>,
    fragments: &[&str],
) {
    match result {
        Ok(value) => panic!("{name}: {what} succeeded: {value:?}"),
        Err(error) => {
            let m = message(error);
            assert!(!m.is_empty(), "{name}: {what} threw an empty message");
            for fragment in fragments {
                assert!(m.contains(fragment), "{name}: {what}: {m:?} should mention {fragment:?}");
            }
        }
    }
}

/// Runs one case: every call that must fail does, with the fragments, and leaves the caller's
/// arrays as they were.
fn run_case(case: &Case, fragments: &[&str]) {
    let name = case.name;
    let mesh = match &case.input {
        Input::Obj(text) => {
            let result = read_obj(&JsValue::from_str(text));
            if case.stage == Stage::Obj {
                return expect_error(name, "readObj", result, fragments);
            }
            match result {
                Ok(mesh) => mesh,
                Err(e) => panic!("{name}: readObj refused a valid file: {}", message(e)),
            }
        }
        Input::Arrays { positions, indices, face_sizes } => {
            js_mesh(positions, indices, face_sizes.as_deref())
        }
        Input::Js(mesh) => js_mesh_object(mesh),
        Input::Channel(c) => js_channel_mesh(c),
        Input::ObjBytes(_) => panic!("{name}: not a JS input"),
    };
    let before = snapshot(&mesh);
    expect_error(name, "subdivide", subdivide(&mesh, &js_options(case)), fragments);
    if case.stage == Stage::Mesh {
        expect_error(name, "writeObj", write_obj(&mesh).map(JsValue::from), fragments);
    }
    // The same refusal through BaseMesh: its constructor for a bad mesh, else its subdivide.
    match (case.stage, subsurf::wasm::BaseMesh::new(&mesh)) {
        (Stage::Mesh | Stage::Attributes, built) => {
            expect_error(name, "new BaseMesh", built.map(|b| b.num_faces().into()), fragments)
        }
        (_, Ok(base)) => {
            let result = base.subdivide(&js_options(case), &JsValue::UNDEFINED);
            expect_error(name, "BaseMesh.subdivide", result, fragments)
        }
        (_, Err(e)) => panic!("{name}: new BaseMesh refused a valid mesh: {}", message(e)),
    }
    assert_eq!(snapshot(&mesh), before, "{name}: the failed call changed the caller's arrays");
}

/// Every case of the catalogue whose JS expectation is an error. Pending cases (the library
/// does not refuse them yet) are skipped here: `result_beyond_wasm_memory` would trap the module.
#[wasm_bindgen_test]
fn bad_input_catalogue_through_the_js_api() {
    let mut ran = 0;
    let mut pending = Vec::new();
    for case in catalogue::catalogue() {
        match &case.js {
            Expect::Error(fragments) => {
                run_case(&case, fragments);
                module_still_works(case.name);
                ran += 1;
            }
            Expect::Pending { .. } => pending.push(case.name),
            Expect::NotApplicable(_) => {}
        }
    }
    assert!(ran >= 40, "only {ran} catalogue cases ran through the JS API");
    assert!(pending.is_empty(), "pending JS cases: {pending:?}");
}

/// The catalogue's faces that repeat a vertex, which Doo-Sabin, √3 and Quad/Triangle refuse,
/// are subdivided by Catmull-Clark and bilinear (and on triangles by Loop and midpoint), as
/// OpenSubdiv does: a result with the expected face count.
#[wasm_bindgen_test]
fn faces_that_repeat_a_vertex_are_accepted_by_the_primal_schemes() {
    let mut ran = 0;
    for case in catalogue::catalogue().into_iter().filter(|c| c.name.contains("repeats_a")) {
        let (mesh, sizes) = match &case.input {
            Input::Arrays { positions, indices, face_sizes } => {
                let sizes = face_sizes.clone().unwrap();
                (js_mesh(positions, indices, Some(&sizes)), sizes)
            }
            Input::Obj(text) => (read_obj(&JsValue::from_str(text)).unwrap(), vec![3]),
            other => panic!("{}: {other:?}", case.name),
        };
        let mut schemes = vec![("catmull-clark", 4), ("bilinear", 4)];
        if sizes.iter().all(|&n| n == 3) {
            schemes.extend([("loop", 3), ("midpoint", 3)]);
        }
        let corners: u32 = sizes.iter().sum();
        for (scheme, size) in schemes {
            let options = object(&[("scheme", scheme.into()), ("levels", 1.into())]);
            let out = subdivide(&mesh, &options)
                .unwrap_or_else(|e| panic!("{} {scheme}: {}", case.name, message(e)));
            let indices: Uint32Array = field(&out, "indices").dyn_into().unwrap();
            let faces = if size == 4 { corners } else { 4 * sizes.len() as u32 };
            assert_eq!(indices.length(), size * faces, "{} {scheme}", case.name);
            ran += 1;
        }
    }
    assert!(ran >= 10, "only {ran} calls ran");
}

/// The guard refuses from the prediction, before any work: the message gives the predicted
/// face count and names the option, and the same instance then subdivides at the limit.
#[wasm_bindgen_test]
fn max_faces_guard_gives_the_predicted_size_and_the_option() {
    let options = object(&[("levels", 5.into()), ("maxFaces", 6143.into())]);
    let m = thrown(subdivide(&cube(), &options));
    assert_mentions(&m, &["5 level(s) would make 6144 faces", "limit of 6143", "maxFaces"]);
    let options = object(&[("levels", 5.into()), ("maxFaces", 6144.into())]);
    assert_eq!(u32s(&ok(subdivide(&cube(), &options)), "faceSizes").len(), 6144);
    // Far beyond memory: refused at once, the instance keeps working.
    let options = object(&[("levels", 32.into()), ("maxFaces", 9_007_199_254_740_991.0.into())]);
    assert_mentions(&thrown(subdivide(&cube(), &options)), &["32 level(s) would make", "maxFaces"]);
    module_still_works("a 32-level request");
}

// ---------------------------------------------------------------------------------------------
// Inputs are never mutated

/// A square, a triangle roof on it and a pentagon beside it: open, manifold, mixed sizes.
fn house() -> (Vec<f32>, Vec<u32>, Vec<u32>) {
    #[rustfmt::skip]
    let positions = vec![
        0., 0., 0.,  1., 0., 0.1,  1., 1., 0.,  0., 1., 0.2,  0.5, 1.6, 0.,
        1.8, -0.2, 0.3,  2.3, 0.6, 0.,  1.7, 1.3, -0.1,
    ];
    let indices = vec![0, 1, 2, 3, 3, 2, 4, 1, 5, 6, 7, 2];
    (positions, indices, vec![4, 3, 5])
}

/// An open fan of four triangles around vertex 0.
fn fan() -> (Vec<f32>, Vec<u32>, Vec<u32>) {
    let positions =
        vec![0., 0., 0.3, 1., 0., 0., 0.6, 0.8, 0., -0.4, 0.9, 0., -1., 0.1, 0., -0.5, -0.8, 0.];
    (positions, vec![0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5], vec![3; 4])
}

fn bytes_of(array: &JsValue) -> Vec<u8> {
    js_sys::Uint8Array::new(&Reflect::get(array, &"buffer".into()).unwrap()).to_vec()
}

#[wasm_bindgen_test]
fn caller_arrays_are_byte_identical_after_every_scheme() {
    let (cp, ci, cs) = cube_arrays();
    let (hp, hi, hs) = house();
    let (tp, ti) = tetrahedron_arrays();
    let (fp, fi, fs) = fan();
    let polygons = [("cube", cp, ci, Some(cs)), ("house", hp, hi, Some(hs))];
    let triangles = [("tetrahedron", tp, ti, None), ("fan", fp, fi, Some(fs))];
    let mut calls = 0;
    for scheme in subsurf::Scheme::ALL {
        let meshes = if scheme.triangles_only() { &triangles } else { &polygons };
        for (name, positions, indices, sizes) in meshes {
            for level in [1, 2] {
                let mesh = js_mesh(positions, indices, sizes.as_deref());
                let keys = ["positions", "indices", "faceSizes"];
                let arrays: Vec<(&str, JsValue)> = keys
                    .iter()
                    .map(|&k| (k, field(&mesh, k)))
                    .filter(|(_, v)| !v.is_undefined())
                    .collect();
                let before: Vec<Vec<u8>> = arrays.iter().map(|(_, a)| bytes_of(a)).collect();
                let options = object(&[("scheme", scheme.name().into()), ("levels", level.into())]);
                let what = format!("{scheme} level {level} on the {name}");
                let out = match subdivide(&mesh, &options) {
                    Ok(out) => out,
                    Err(e) => panic!("{what}: {}", message(e)),
                };
                assert!(!u32s(&out, "faceSizes").is_empty(), "{what}: no faces");
                for ((key, array), bytes) in arrays.iter().zip(&before) {
                    assert_eq!(&bytes_of(array), bytes, "{what}: the bytes of {key} changed");
                    assert!(field(&mesh, key) == *array, "{what}: mesh.{key} was replaced");
                }
                assert_eq!(f32s(&mesh, "positions"), *positions, "{what}");
                assert_eq!(u32s(&mesh, "indices"), *indices, "{what}");
                assert_eq!(Object::keys(options.unchecked_ref::<Object>()).length(), 2, "{what}");
                assert!(write_obj(&mesh).is_ok(), "{what}: writeObj");
                for ((key, array), bytes) in arrays.iter().zip(&before) {
                    assert_eq!(&bytes_of(array), bytes, "{what}: writeObj changed {key}");
                }
                calls += 1;
            }
        }
    }
    assert_eq!(calls, subsurf::Scheme::ALL.len() * 4);
}

// ---------------------------------------------------------------------------------------------
// Hostile JS values

/// A value made by a snippet of JS (`return ...`).
pub(super) fn js(body: &str) -> JsValue {
    js_sys::Function::new_no_args(body).call0(&JsValue::NULL).unwrap()
}

/// Objects a page can pass by mistake or on purpose: getters and proxies that throw, detached
/// and shared buffers, typed-array subclasses, properties shadowing `length`. Each call must
/// return (an error or a result), never let a JS exception run through the Rust code, and the
/// instance must keep working.
#[wasm_bindgen_test]
fn hostile_js_values_give_errors_not_exceptions() {
    let cube_fields = "positions: new Float32Array([-1,-1,-1, 1,-1,-1, -1,1,-1, 1,1,-1, -1,-1,1, 1,-1,1, -1,1,1, 1,1,1]), \
         indices: new Uint32Array([0,2,3,1, 4,5,7,6, 0,1,5,4, 2,6,7,3, 0,4,6,2, 1,3,7,5]), \
         faceSizes: new Uint32Array([4,4,4,4,4,4])";
    let revoked = "const r = Proxy.revocable({}, {}); r.revoke(); return r.proxy;";
    let errors: Vec<(&str, JsValue, JsValue, &[&str])> = vec![
        (
            "a throwing positions getter",
            js("return { get positions() { throw new Error('boom'); }, indices: new Uint32Array(3) }"),
            JsValue::UNDEFINED,
            &["reading mesh.positions threw", "boom"],
        ),
        (
            "a mesh proxy whose keys throw",
            js("return new Proxy({}, { ownKeys() { throw new Error('no keys'); } })"),
            JsValue::UNDEFINED,
            &["mesh fields threw", "no keys"],
        ),
        ("a revoked proxy as the mesh", js(revoked), JsValue::UNDEFINED, &["mesh fields threw"]),
        (
            "an options proxy whose keys throw",
            cube(),
            js("return new Proxy({}, { ownKeys() { throw new Error('no keys'); } })"),
            &["options threw", "no keys"],
        ),
        ("a revoked proxy as the options", cube(), js(revoked), &["options threw"]),
        (
            "a throwing levels getter",
            cube(),
            js("return { get levels() { throw new Error('nope'); } }"),
            &["reading options.levels threw", "nope"],
        ),
        (
            "a scheme list whose items throw",
            cube(),
            js("return { scheme: new Proxy(['loop'], { get(t, k) { if (k === '0') throw new Error('item'); return t[k]; } }) }"),
            &["reading options.scheme[0] threw", "item"],
        ),
        (
            "a proxy around a Float32Array as positions",
            js(&format!(
                "const m = {{ {cube_fields} }}; m.positions = new Proxy(m.positions, {{ getPrototypeOf() {{ throw new Error('proto'); }} }}); return m;"
            )),
            JsValue::UNDEFINED,
            &["mesh.positions must be a Float32Array"],
        ),
        (
            "an error whose prototype trap throws, as the levels",
            cube(),
            js("return { levels: new Proxy(new Error('x'), { getPrototypeOf() { throw new Error('proto'); } }) }"),
            &["levels must be a whole number"],
        ),
        (
            "a detached positions buffer",
            js(&format!(
                "const m = {{ {cube_fields} }}; structuredClone(m.positions.buffer, {{ transfer: [m.positions.buffer] }}); return m;"
            )),
            JsValue::UNDEFINED,
            &["mesh.positions"],
        ),
        (
            "a positions array whose length property throws",
            js(&format!(
                "const m = {{ {cube_fields} }}; Object.defineProperty(m.positions, 'length', {{ get() {{ throw new Error('no length'); }} }}); return m;"
            )),
            JsValue::UNDEFINED,
            &[],
        ),
        (
            "a positions array whose subarray method throws",
            js(&format!(
                "const m = {{ {cube_fields} }}; m.positions.subarray = () => {{ throw new Error('no subarray'); }}; return m;"
            )),
            JsValue::UNDEFINED,
            &[],
        ),
    ];
    for (what, mesh, options, fragments) in errors {
        match subdivide(&mesh, &options) {
            Ok(out) => {
                // Reading the length from the prototype instead of the shadowing property is
                // also fine: then the result must be the cube's.
                assert!(fragments.is_empty(), "{what}: succeeded");
                assert_eq!(u32s(&out, "faceSizes").len(), 24, "{what}");
            }
            Err(e) => assert_mentions(&message(e), fragments),
        }
        module_still_works(what);
    }

    let fine = [
        ("a Float32Array subclass", format!("class P extends Float32Array {{}}; const m = {{ {cube_fields} }}; m.positions = new P(m.positions); return m;")),
        ("views into a larger buffer", format!("const m = {{ {cube_fields} }}; const b = new ArrayBuffer(1024); const p = new Float32Array(b, 64, 24); p.set(m.positions); m.positions = p; return m;")),
        ("a frozen mesh object", format!("return Object.freeze({{ {cube_fields} }});")),
        (
            // The copy reads the array's own length slot, not a property that shadows it.
            "positions and indices whose length properties lie",
            format!("const m = {{ {cube_fields} }}; for (const a of [m.positions, m.indices]) Object.defineProperty(a, 'length', {{ get() {{ return 3; }} }}); return m;"),
        ),
        (
            "a mesh with a null prototype",
            format!("return Object.assign(Object.create(null), {{ {cube_fields} }});"),
        ),
    ];
    for (what, body) in fine {
        let out = match subdivide(&js(&body), &levels(1.0)) {
            Ok(out) => out,
            Err(e) => panic!("{what}: {}", message(e)),
        };
        assert_eq!(u32s(&out, "faceSizes").len(), 24, "{what}");
    }
    if js("return typeof SharedArrayBuffer").as_string().as_deref() == Some("function") {
        let body = format!("const m = {{ {cube_fields} }}; const p = new Float32Array(new SharedArrayBuffer(96)); p.set(m.positions); m.positions = p; return m;");
        let out = ok(subdivide(&js(&body), &levels(1.0)));
        assert_eq!(u32s(&out, "faceSizes").len(), 24, "shared buffer");
    }
    // Typed arrays of another realm (an iframe's) are typed arrays too.
    if js("return typeof document").as_string().as_deref() == Some("object") {
        let body = format!(
            "const f = document.createElement('iframe'); document.body.appendChild(f); \
             const m = {{ {cube_fields} }}; m.positions = new f.contentWindow.Float32Array(m.positions); \
             m.indices = new f.contentWindow.Uint32Array(m.indices); return m;"
        );
        let out = ok(subdivide(&js(&body), &levels(1.0)));
        assert_eq!(u32s(&out, "faceSizes").len(), 24, "iframe arrays");
    }
    module_still_works("the hostile values");
}
