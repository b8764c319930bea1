//! The wasm-bindgen tests of the JS-facing API, shared by `tests/wasm_node.rs` (Node) and
//! `tests/wasm_browser.rs` (headless Chromium). Everything goes through `subsurf::wasm` with real
//! typed arrays and plain JS objects, as a web page would call it.

use js_sys::{Array, Float32Array, Object, Reflect, Uint32Array};
use subsurf::wasm::{read_obj, version, write_obj};
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::wasm_bindgen_test;

// ---------------------------------------------------------------------------------------------
// Helpers

// The cube with corners ±1 of the bad-input catalogue (vertex `i` has x, y, z signs from bits
// 0, 1, 2 of `i`).
use bad_inputs::catalogue::cube as cube_arrays;

/// A closed tetrahedron as a plain triangle list.
fn tetrahedron_arrays() -> (Vec<f32>, Vec<u32>) {
    let positions = vec![1., 1., 1., 1., -1., -1., -1., 1., -1., -1., -1., 1.];
    let indices = vec![0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2];
    (positions, indices)
}

fn js_mesh(positions: &[f32], indices: &[u32], face_sizes: Option<&[u32]>) -> JsValue {
    let mut fields = vec![
        ("positions", Float32Array::from(positions).into()),
        ("indices", Uint32Array::from(indices).into()),
    ];
    if let Some(sizes) = face_sizes {
        fields.push(("faceSizes", Uint32Array::from(sizes).into()));
    }
    object(&fields)
}

fn cube() -> JsValue {
    let (p, i, s) = cube_arrays();
    js_mesh(&p, &i, Some(&s))
}

fn object(fields: &[(&str, JsValue)]) -> JsValue {
    let object = Object::new();
    for (key, value) in fields {
        Reflect::set(&object, &JsValue::from_str(key), value).unwrap();
    }
    object.into()
}

/// `subsurf::wasm::subdivide` without `into`, as most cases call it.
fn subdivide(mesh: &JsValue, options: &JsValue) -> Result<JsValue, JsValue> {
    subsurf::wasm::subdivide(mesh, options, &JsValue::UNDEFINED)
}

fn levels(n: f64) -> JsValue {
    object(&[("levels", JsValue::from_f64(n))])
}

fn field(object: &JsValue, key: &str) -> JsValue {
    Reflect::get(object, &JsValue::from_str(key)).unwrap()
}

fn f32s(object: &JsValue, key: &str) -> Vec<f32> {
    field(object, key)
        .dyn_into::<Float32Array>()
        .unwrap_or_else(|v| panic!("{key} is {v:?}"))
        .to_vec()
}

fn u32s(object: &JsValue, key: &str) -> Vec<u32> {
    field(object, key)
        .dyn_into::<Uint32Array>()
        .unwrap_or_else(|v| panic!("{key} is {v:?}"))
        .to_vec()
}

fn ok<E: Into<JsValue>>(result: Result<JsValue, E>) -> JsValue {
    match result {
        Ok(value) => value,
        Err(error) => panic!("unexpected error: {}", message(error)),
    }
}

/// The message of a thrown `Error` (`subdivide` throws `JsValue`s, the other calls `JsError`s).
fn message<E: Into<JsValue>>(error: E) -> String {
    let value: JsValue = error.into();
    let error = value.dyn_into::<js_sys::Error>().expect("a JS Error object");
    error.message().into()
}

/// The message of the `Error` the call threw; fails the test when it did not throw.
fn thrown<T: std::fmt::Debug, E: Into<JsValue>>(result: Result<T, E>) -> String {
    match result {
        Ok(value) => panic!("expected an error, got {value:?}"),
        Err(error) => message(error),
    }
}

fn assert_mentions(message: &str, parts: &[&str]) {
    for part in parts {
        assert!(message.contains(part), "message {message:?} should mention {part:?}");
    }
}

fn close(a: &[f32], b: &[f32]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-6)
}

fn point(positions: &[f32], v: usize) -> [f32; 3] {
    [positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]]
}

// ---------------------------------------------------------------------------------------------
// Results

#[wasm_bindgen_test]
fn cube_counts_at_levels_1_to_3() {
    // Catmull-Clark: V' = V + E + F, F' = sum of face sizes (every face becomes quads).
    for (level, vertices, faces) in [(1, 26, 24), (2, 98, 96), (3, 386, 384)] {
        let out = ok(subdivide(&cube(), &levels(level as f64)));
        assert_eq!(f32s(&out, "positions").len(), 3 * vertices, "level {level} vertices");
        assert_eq!(u32s(&out, "faceSizes"), vec![4; faces], "level {level} face sizes");
        assert_eq!(u32s(&out, "indices").len(), 4 * faces, "level {level} indices");
        let triangles = u32s(&out, "triangles");
        assert_eq!(triangles.len(), 6 * faces, "level {level}: two triangles per quad");
        assert!(
            triangles.iter().all(|&i| (i as usize) < vertices),
            "level {level} triangle index range"
        );
    }
}

#[wasm_bindgen_test]
fn cube_positions_match_seed_003() {
    let (corners, _, _) = cube_arrays();
    let out = ok(subdivide(&cube(), &levels(1.0)));
    let p = f32s(&out, "positions");
    // Old vertex i keeps index i: a corner of valence 3 moves to 5/9 of itself.
    for v in 0..8 {
        let expected = point(&corners, v).map(|c| c * 5.0 / 9.0);
        assert!(
            close(&point(&p, v), &expected),
            "vertex point {v}: {:?} vs {expected:?}",
            point(&p, v)
        );
    }
    let mut face_points = 0;
    let mut edge_points = 0;
    for v in 8..26 {
        let q = point(&p, v);
        let mut abs: Vec<f32> = q.iter().map(|c| c.abs()).collect();
        abs.sort_by(f32::total_cmp);
        if close(&abs, &[0.0, 0.0, 1.0]) {
            face_points += 1; // like (0, -1, 0)
        } else if close(&abs, &[0.0, 0.75, 0.75]) {
            edge_points += 1; // like (0, -0.75, -0.75)
        } else {
            panic!("vertex {v} at {q:?} is neither a face point nor an edge point");
        }
    }
    assert_eq!((face_points, edge_points), (6, 12));
    let has = |target: [f32; 3]| (8..26).any(|v| close(&point(&p, v), &target));
    assert!(has([0.0, -1.0, 0.0]), "face point (0, -1, 0)");
    assert!(has([0.0, -0.75, -0.75]), "edge point (0, -0.75, -0.75)");
    assert!(close(&point(&p, 7), &[0.5555556, 0.5555556, 0.5555556]));
}

#[wasm_bindgen_test]
fn omitted_face_sizes_mean_triangles() {
    let (p, i) = tetrahedron_arrays();
    let implicit = ok(subdivide(&js_mesh(&p, &i, None), &levels(1.0)));
    let explicit = ok(subdivide(&js_mesh(&p, &i, Some(&[3, 3, 3, 3])), &levels(1.0)));
    // V' = 4 + 6 + 4, F' = 4 * 3.
    assert_eq!(f32s(&implicit, "positions").len(), 3 * 14);
    assert_eq!(u32s(&implicit, "faceSizes"), vec![4; 12]);
    for key in ["indices", "faceSizes", "triangles"] {
        assert_eq!(u32s(&implicit, key), u32s(&explicit, key), "{key}");
    }
    assert_eq!(f32s(&implicit, "positions"), f32s(&explicit, "positions"));
}

#[wasm_bindgen_test]
fn inputs_are_not_modified() {
    let (p, i, s) = cube_arrays();
    let mesh = js_mesh(&p, &i, Some(&s));
    let options = object(&[("levels", 2.into()), ("boundary", "fixed".into())]);
    ok(subdivide(&mesh, &options));
    assert_eq!(f32s(&mesh, "positions"), p);
    assert_eq!(u32s(&mesh, "indices"), i);
    assert_eq!(u32s(&mesh, "faceSizes"), s);
    assert_eq!(Object::keys(options.unchecked_ref::<Object>()).length(), 2);
    assert_eq!(field(&options, "levels"), JsValue::from(2));
}

#[wasm_bindgen_test]
fn results_are_fresh_arrays_not_views_of_wasm_memory() {
    let out = ok(subdivide(&cube(), &levels(1.0)));
    let memory_buffer = field(&wasm_bindgen::memory(), "buffer");
    for key in ["positions", "indices", "faceSizes", "triangles"] {
        assert_ne!(field(&field(&out, key), "buffer"), memory_buffer, "{key} must own its buffer");
    }
    let again = ok(subdivide(&cube(), &levels(1.0)));
    assert_ne!(field(&out, "positions"), field(&again, "positions"));
}

#[wasm_bindgen_test]
fn options_may_be_undefined_null_or_empty() {
    for options in [JsValue::UNDEFINED, JsValue::NULL, Object::new().into()] {
        let out = ok(subdivide(&cube(), &options));
        assert_eq!(u32s(&out, "faceSizes").len(), 24, "default is one level for {options:?}");
    }
}

#[wasm_bindgen_test]
fn level_zero_returns_the_input_mesh() {
    let (p, i, s) = cube_arrays();
    let out = ok(subdivide(&cube(), &levels(0.0)));
    assert_eq!(f32s(&out, "positions"), p);
    assert_eq!(u32s(&out, "indices"), i);
    assert_eq!(u32s(&out, "faceSizes"), s);
    assert_eq!(u32s(&out, "triangles").len(), 6 * 2 * 3);
}

#[wasm_bindgen_test]
fn scheme_can_be_one_name_or_one_per_level() {
    let named = object(&[("scheme", "catmull-clark".into()), ("levels", 2.into())]);
    let per_level = Array::of2(&"catmull-clark".into(), &"catmull-clark".into());
    let listed = object(&[("scheme", per_level.into())]);
    let a = ok(subdivide(&cube(), &named));
    let b = ok(subdivide(&cube(), &listed));
    assert_eq!(u32s(&a, "faceSizes").len(), 96);
    assert_eq!(u32s(&a, "indices"), u32s(&b, "indices"));
    assert_eq!(f32s(&a, "positions"), f32s(&b, "positions"));
}

/// The bindings copy `indices`, `faceSizes` and `triangles` into JS in pieces of up to 49,152
/// indices (made on the fly for Catmull-Clark's last level). Joined, they must be the flat arrays
/// of the Rust API's `subdivide` and `PolyMesh::triangles` (the fan (0, k, k + 1) of every face,
/// checked face by face in src/mesh/poly.rs). The quad and mixed-face results here span several
/// pieces; Loop's triangles come whole.
#[wasm_bindgen_test]
fn streamed_arrays_are_the_flat_arrays() {
    let (p, i) = tetrahedron_arrays();
    let tetra = js_mesh(&p, &i, None);
    let native =
        subsurf::PolyMesh { positions: p.clone(), indices: i.clone(), face_sizes: vec![3; 4] };
    for (scheme, level) in [("catmull-clark", 6), ("doo-sabin", 6), ("loop", 5)] {
        let options =
            object(&[("scheme", scheme.into()), ("levels", JsValue::from_f64(level as f64))]);
        let out = ok(subdivide(&tetra, &options));
        let scheme_value: subsurf::Scheme = scheme.parse().unwrap();
        let flat =
            subsurf::subdivide(&native, &subsurf::Options::new(scheme_value, level)).unwrap();
        assert_eq!(u32s(&out, "indices"), flat.indices, "{scheme}");
        assert_eq!(u32s(&out, "faceSizes"), flat.face_sizes, "{scheme}");
        let triangles = u32s(&out, "triangles");
        assert!(scheme == "loop" || triangles.len() > 49_152, "{scheme}: the case spans pieces");
        assert_eq!(triangles, flat.triangles(), "{scheme}");
    }
}

#[wasm_bindgen_test]
fn other_schemes_and_per_level_lists() {
    let (p, i) = tetrahedron_arrays();
    let tetra = js_mesh(&p, &i, None);
    // Loop: V' = V + E, F' = 4F, triangles stay triangles.
    let looped = ok(subdivide(&tetra, &object(&[("scheme", "loop".into())])));
    assert_eq!(f32s(&looped, "positions").len(), 3 * 10);
    assert_eq!(u32s(&looped, "faceSizes"), vec![3; 16]);
    // Loop then Catmull-Clark: 10 + 24 + 16 vertices, 16 * 3 quads.
    let list = Array::of2(&"loop".into(), &"catmull-clark".into());
    let mixed = ok(subdivide(&tetra, &object(&[("scheme", list.into())])));
    assert_eq!(f32s(&mixed, "positions").len(), 3 * 50);
    assert_eq!(u32s(&mixed, "faceSizes"), vec![4; 48]);
    // The other order gives Loop quads, which it refuses.
    let list = Array::of2(&"catmull-clark".into(), &"loop".into());
    let m = thrown(subdivide(&tetra, &object(&[("scheme", list.into())])));
    assert_mentions(&m, &["loop"]);
}

#[wasm_bindgen_test]
fn scheme_and_boundary_names_are_listed() {
    let names: Vec<String> =
        subsurf::wasm::scheme_names().iter().map(|v| v.as_string().unwrap()).collect();
    let expected: Vec<&str> = subsurf::Scheme::ALL.iter().map(|s| s.name()).collect();
    assert_eq!(names, expected);
    assert!(names.iter().any(|n| n == "catmull-clark"));
    let rules: Vec<String> =
        subsurf::wasm::boundary_rules().iter().map(|v| v.as_string().unwrap()).collect();
    assert_eq!(rules, ["edge-and-corner", "edge-only", "fixed", "average", "none"]);
    // Every listed name is accepted.
    for name in names
        .iter()
        .filter(|n| !subsurf::Scheme::ALL.iter().any(|s| s.name() == *n && s.triangles_only()))
    {
        ok(subdivide(&cube(), &object(&[("scheme", name.as_str().into())])));
    }
    for rule in &rules {
        ok(subdivide(&cube(), &object(&[("boundary", rule.as_str().into())])));
    }
}

#[wasm_bindgen_test]
fn boundary_option_reaches_the_rules() {
    // One open unit quad: with 'edge-and-corner' its corners stay, with 'edge-only' a corner
    // follows the crease rule (a + 6v + b) / 8.
    let quad =
        js_mesh(&[0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.], &[0, 1, 2, 3], Some(&[4]));
    let corner = |boundary: &str| {
        let out = ok(subdivide(&quad, &object(&[("boundary", boundary.into())])));
        point(&f32s(&out, "positions"), 0)
    };
    assert!(close(&corner("edge-and-corner"), &[0.0, 0.0, 0.0]));
    assert!(close(&corner("fixed"), &[0.0, 0.0, 0.0]));
    assert!(close(&corner("edge-only"), &[0.125, 0.125, 0.0]), "{:?}", corner("edge-only"));
    assert!(!close(&corner("average"), &corner("edge-only")));
}

#[wasm_bindgen_test]
fn obj_round_trip() {
    let text = "# a square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1 4/1\n";
    let mesh = ok(read_obj(&text.into()));
    assert_eq!(f32s(&mesh, "positions"), vec![0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.]);
    assert_eq!(u32s(&mesh, "indices"), vec![0, 1, 2, 3]);
    assert_eq!(u32s(&mesh, "faceSizes"), vec![4]);
    let refined = ok(subdivide(&mesh, &levels(1.0)));
    let written = write_obj(&refined).unwrap_or_else(|e| panic!("{}", message(e)));
    assert_eq!(written.lines().filter(|l| l.starts_with("v ")).count(), 9);
    assert_eq!(written.lines().filter(|l| l.starts_with("f ")).count(), 4);
    let again = ok(read_obj(&written.into()));
    assert_eq!(u32s(&again, "indices"), u32s(&refined, "indices"));
    assert_eq!(f32s(&again, "positions"), f32s(&refined, "positions"));
}

#[wasm_bindgen_test]
fn version_is_the_crate_version() {
    assert_eq!(version(), env!("CARGO_PKG_VERSION"));
}

// ---------------------------------------------------------------------------------------------
// Errors

#[wasm_bindgen_test]
fn unknown_option_key_is_named_with_the_allowed_ones() {
    let m = thrown(subdivide(&cube(), &levels_typo()));
    assert_mentions(
        &m,
        &["unknown option 'level'", "'levels'", "'scheme'", "'boundary'", "'maxFaces'"],
    );
}

fn levels_typo() -> JsValue {
    object(&[("level", 2.into())])
}

#[wasm_bindgen_test]
fn unknown_option_values_are_named_with_the_allowed_ones() {
    let m = thrown(subdivide(&cube(), &object(&[("scheme", "loopy".into())])));
    assert_mentions(&m, &["scheme", "'loopy'", "'catmull-clark'", "'loop'", "'doo-sabin'"]);

    let m = thrown(subdivide(&cube(), &object(&[("boundary", "sharp".into())])));
    assert_mentions(
        &m,
        &["boundary", "'sharp'", "'edge-and-corner'", "'edge-only'", "'fixed'", "'average'"],
    );

    let m = thrown(subdivide(&cube(), &object(&[("boundary", 3.into())])));
    assert_mentions(&m, &["boundary", "got 3"]);

    let list = Array::of2(&"catmull-clark".into(), &"nope".into());
    let m = thrown(subdivide(&cube(), &object(&[("scheme", list.into())])));
    assert_mentions(&m, &["scheme[1]", "'nope'"]);

    let m = thrown(subdivide(&cube(), &JsValue::from_str("catmull-clark")));
    assert_mentions(&m, &["options must be an object"]);
}

#[wasm_bindgen_test]
fn bad_levels_are_refused() {
    for (value, shown) in [
        (JsValue::from(-1), "got -1"),
        (JsValue::from(1.5), "got 1.5"),
        (JsValue::from("2"), "got string '2'"),
        (JsValue::from(f64::NAN), "got NaN"),
        (JsValue::from(1000), "got 1000"),
    ] {
        let m = thrown(subdivide(&cube(), &object(&[("levels", value)])));
        assert_mentions(&m, &["levels must be a whole number", shown]);
    }
    let list = Array::of1(&"catmull-clark".into());
    let m = thrown(subdivide(&cube(), &object(&[("scheme", list.into()), ("levels", 2.into())])));
    assert_mentions(&m, &["scheme lists 1", "levels is 2"]);
}

#[wasm_bindgen_test]
fn max_faces_is_enforced() {
    let options = object(&[("levels", 3.into()), ("maxFaces", 100.into())]);
    let m = thrown(subdivide(&cube(), &options));
    assert_mentions(&m, &["384", "100"]);
    let m = thrown(subdivide(&cube(), &object(&[("maxFaces", (-5).into())])));
    assert_mentions(&m, &["maxFaces must be", "got -5"]);
}

#[wasm_bindgen_test]
fn wrong_typed_array_types_are_named() {
    let (p, i, s) = cube_arrays();
    let positions: JsValue = Float32Array::from(&p[..]).into();
    let indices: JsValue = Uint32Array::from(&i[..]).into();
    let sizes: JsValue = Uint32Array::from(&s[..]).into();

    let as_floats: JsValue =
        Float32Array::from(&i.iter().map(|&x| x as f32).collect::<Vec<_>>()[..]).into();
    let mesh = object(&[
        ("positions", positions.clone()),
        ("indices", as_floats),
        ("faceSizes", sizes.clone()),
    ]);
    assert_mentions(
        &thrown(subdivide(&mesh, &JsValue::UNDEFINED)),
        &["mesh.indices must be a Uint32Array, got Float32Array"],
    );

    let plain: JsValue = p.iter().map(|&x| JsValue::from(x)).collect::<Array>().into();
    let mesh =
        object(&[("positions", plain), ("indices", indices.clone()), ("faceSizes", sizes.clone())]);
    assert_mentions(
        &thrown(subdivide(&mesh, &JsValue::UNDEFINED)),
        &["mesh.positions must be a Float32Array, got Array"],
    );

    let bytes: JsValue = js_sys::Uint8Array::new_with_length(6).into();
    let mesh = object(&[
        ("positions", positions.clone()),
        ("indices", indices.clone()),
        ("faceSizes", bytes),
    ]);
    assert_mentions(
        &thrown(subdivide(&mesh, &JsValue::UNDEFINED)),
        &["mesh.faceSizes must be a Uint32Array, got Uint8Array"],
    );

    let mesh = object(&[("indices", indices.clone())]);
    assert_mentions(&thrown(subdivide(&mesh, &JsValue::UNDEFINED)), &["mesh.positions is missing"]);

    let mesh = object(&[("positions", positions), ("indices", indices), ("faceSize", sizes)]);
    assert_mentions(
        &thrown(subdivide(&mesh, &JsValue::UNDEFINED)),
        &["unknown mesh field 'faceSize'", "'faceSizes'"],
    );

    assert_mentions(
        &thrown(subdivide(&JsValue::NULL, &JsValue::UNDEFINED)),
        &["mesh must be an object", "got null"],
    );
    assert_mentions(&thrown(write_obj(&JsValue::from(7))), &["mesh must be an object", "got 7"]);
}

#[wasm_bindgen_test]
fn bad_indices_are_refused() {
    let (p, mut i, s) = cube_arrays();
    i[5] = 99;
    let m = thrown(subdivide(&js_mesh(&p, &i, Some(&s)), &JsValue::UNDEFINED));
    assert_mentions(&m, &["face 1", "vertex 99", "8 vertices"]);
    assert_mentions(&thrown(write_obj(&js_mesh(&p, &i, Some(&s)))), &["vertex 99"]);

    let (p, i) = tetrahedron_arrays();
    let m = thrown(subdivide(&js_mesh(&p, &i[..10], None), &JsValue::UNDEFINED));
    assert_mentions(&m, &["10 entries", "not a multiple of 3", "faceSizes"]);

    let m = thrown(subdivide(&js_mesh(&p, &i, Some(&[3, 3, 3])), &JsValue::UNDEFINED));
    assert_mentions(&m, &["faceSizes sum to 9", "12"]);
}

#[wasm_bindgen_test]
fn obj_errors_are_thrown_with_the_line() {
    let m = thrown(read_obj(&"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n".into()));
    assert_mentions(&m, &["line 4", "vertex 7"]);
    let m = thrown(read_obj(&JsValue::from(12)));
    assert_mentions(&m, &["readObj expects", "string", "got 12"]);
}

/// The cube of `cube_arrays` as OBJ text (1-based), followed by `tags`.
fn cube_obj(tags: &str) -> String {
    let (positions, indices, sizes) = cube_arrays();
    let mut text = String::new();
    for p in positions.chunks(3) {
        text += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    let mut start = 0;
    for &n in &sizes {
        let face: Vec<String> =
            indices[start..start + n as usize].iter().map(|i| (i + 1).to_string()).collect();
        text += &format!("f {}\n", face.join(" "));
        start += n as usize;
    }
    text + tags
}

fn own_keys(object: &JsValue) -> Vec<String> {
    Reflect::own_keys(object).unwrap().iter().filter_map(|k| k.as_string()).collect()
}

#[wasm_bindgen_test]
fn obj_tags_are_returned_in_the_shapes_subdivide_takes() {
    // Edges 0-1, 1-3 and 3-2 are on face z- (0 2 3 1); one sharpness for all on the second line.
    let tags = "t crease 2/1/0 0 1 2.5\n\
                t crease 4/1/0 1 3 3 2 10\n\
                t corner 2/2/0 7 4 10 0.5\n\
                t hole 1/0/0 5\n\
                t interpolateboundary 1/0/0 2\n\
                t creasemethod 0/0/1 chaikin\n\
                t smoothtriangles 0/0/1 smooth\n";
    let mesh = ok(read_obj(&cube_obj(tags).into()));
    assert_eq!(u32s(&mesh, "faceSizes"), vec![4; 6]);
    let tags = field(&mesh, "tags");
    assert_eq!(
        own_keys(&tags),
        ["creases", "corners", "holes", "boundary", "creaseMethod", "smoothTriangles"]
    );
    let creases = field(&tags, "creases");
    assert_eq!(u32s(&creases, "edges"), vec![0, 1, 1, 3, 3, 2]);
    assert_eq!(f32s(&creases, "sharpness"), vec![2.5, 10.0, 10.0]);
    let corners = field(&tags, "corners");
    assert_eq!(u32s(&corners, "vertices"), vec![7, 4]);
    assert_eq!(f32s(&corners, "sharpness"), vec![10.0, 0.5]);
    assert_eq!(u32s(&tags, "holes"), vec![5]);
    assert_eq!(field(&tags, "boundary").as_string().as_deref(), Some("edge-only"));
    assert_eq!(field(&tags, "creaseMethod").as_string().as_deref(), Some("chaikin"));
    assert_eq!(field(&tags, "smoothTriangles").as_bool(), Some(true));

    // The mesh, tags and all, goes to subdivide as it is; the tags spread into the options.
    let plain = ok(subdivide(&mesh, &levels(1.0)));
    let options = Object::assign(&Object::new(), tags.unchecked_ref::<Object>());
    Reflect::set(&options, &"levels".into(), &JsValue::from(1)).unwrap();
    let tagged = ok(subdivide(&mesh, &options));
    // Hole 5 leaves out the 4 children of face 5; the creases and corners move vertices.
    assert_eq!(u32s(&plain, "faceSizes").len(), 24);
    assert_eq!(u32s(&tagged, "faceSizes").len(), 20);
    assert_ne!(f32s(&tagged, "positions"), f32s(&plain, "positions"));
    // A corner of sharpness 10 stays where it is.
    assert!(close(&point(&f32s(&tagged, "positions"), 7), &[1.0, 1.0, 1.0]));
}

#[wasm_bindgen_test]
fn obj_without_tags_has_empty_tags_and_no_optional_fields() {
    let tags = field(&ok(read_obj(&cube_obj("").into())), "tags");
    assert_eq!(own_keys(&tags), ["creases", "corners", "holes"]);
    let creases = field(&tags, "creases");
    assert_eq!(u32s(&creases, "edges"), Vec::<u32>::new());
    assert_eq!(f32s(&creases, "sharpness"), Vec::<f32>::new());
    assert_eq!(u32s(&field(&tags, "corners"), "vertices"), Vec::<u32>::new());
    assert_eq!(u32s(&tags, "holes"), Vec::<u32>::new());
    // The defaults written out are still absent: they would override options when spread.
    let defaults = "t creasemethod 0/0/1 normal\nt smoothtriangles 0/0/1 catmark\n";
    let tags = field(&ok(read_obj(&cube_obj(defaults).into())), "tags");
    assert_eq!(own_keys(&tags), ["creases", "corners", "holes"]);
    let tags = field(&ok(read_obj(&cube_obj("t interpolateboundary 1/0/0 0\n").into())), "tags");
    assert_eq!(field(&tags, "boundary").as_string().as_deref(), Some("none"));
}

#[wasm_bindgen_test]
fn bad_obj_tags_are_thrown_with_the_line() {
    // The cube takes lines 1-14; the tags start at line 15.
    let cases: [(&str, &[&str]); 5] = [
        ("t crease 2/1/0 0 7 1\n", &["line 15", "vertices 0 and 7 are not joined by an edge"]),
        ("t corner 1/1/0 3 1\nt corner 1/1/0 8 1\n", &["line 16", "8"]),
        ("t hole 1/0/0 6\n", &["line 15", "6"]),
        ("t crease 2/1/0 0 1 -1\n", &["line 15", "-1"]),
        ("t interpolateboundary 1/0/0 3\n", &["line 15", "3 is not a boundary mode"]),
    ];
    for (tags, parts) in cases {
        assert_mentions(&thrown(read_obj(&cube_obj(tags).into())), parts);
    }
}

#[wasm_bindgen_test]
fn errors_are_js_errors_and_the_module_keeps_working() {
    let error: JsValue = subdivide(&cube(), &levels_typo()).unwrap_err();
    assert!(error.is_instance_of::<js_sys::Error>());
    let (p, mut i, s) = cube_arrays();
    i[0] = 1000;
    let _ = subdivide(&js_mesh(&p, &i, Some(&s)), &levels(2.0)).unwrap_err();
    let _ = read_obj(&"f 1 2 3".into()).unwrap_err();
    let out = ok(subdivide(&cube(), &levels(2.0)));
    assert_eq!(f32s(&out, "positions").len(), 3 * 98);
    assert_eq!(u32s(&out, "faceSizes").len(), 96);
    let seed = ok(subdivide(&cube(), &levels(1.0)));
    assert!(close(&point(&f32s(&seed, "positions"), 0), &[-5.0 / 9.0; 3]));
}

#[path = "wasm_schemes.rs"]
mod schemes;

#[path = "wasm_bad_inputs.rs"]
mod bad_inputs;

#[path = "wasm_reuse.rs"]
mod reuse;

#[path = "wasm_attributes.rs"]
mod attributes;

#[path = "wasm_fvar.rs"]
mod fvar;

#[path = "wasm_limit.rs"]
mod limit;

#[path = "wasm_progress.rs"]
mod progress;
