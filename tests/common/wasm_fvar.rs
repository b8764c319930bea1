//! Face-varying channels (UVs) through the JS API: the `fvarLinear` option, `readObj` and
//! `writeObj` with `vt`, the built-in shapes' UV layouts, and `toDrawable`, which splits
//! vertices along seams for one WebGL index buffer. Expected values are closed forms: the
//! number of distinct (vertex, value index) pairs a mesh's corners use, the positions and values
//! of the corners themselves.
use super::*;
use subsurf::wasm::{fvar_linear_modes, shape, shape_names, to_drawable};

fn channel_with_indices(array: &[f32], item_size: f64, indices: &[u32]) -> JsValue {
    object(&[
        ("array", Float32Array::from(array).into()),
        ("itemSize", JsValue::from_f64(item_size)),
        ("indices", Uint32Array::from(indices).into()),
    ])
}

/// `mesh` (positions, indices, faceSizes) with `attributes` set to `channels`.
fn with_channels(mesh: &JsValue, channels: &[(&str, JsValue)]) -> JsValue {
    let copy = Object::assign(&Object::new(), mesh.unchecked_ref());
    Reflect::set(&copy, &"attributes".into(), &object(channels)).unwrap();
    copy.into()
}

/// The cube with each face on its own copy of the unit square: 24 values, corner `c` takes
/// value `c`, so every edge is a seam.
fn square_mapped_cube() -> JsValue {
    let square = [0., 0., 1., 0., 1., 1., 0., 1.];
    let indices: Vec<u32> = (0..24).collect();
    with_channels(&cube(), &[("uv", channel_with_indices(&square.repeat(6), 2.0, &indices))])
}

/// A channel of a result or mesh: (array, itemSize, indices).
fn channel_of(mesh: &JsValue, name: &str) -> (Vec<f32>, f64, Option<Vec<u32>>) {
    let channel = field(&field(mesh, "attributes"), name);
    let indices = field(&channel, "indices");
    let indices = (!indices.is_undefined()).then(|| u32s(&channel, "indices"));
    (f32s(&channel, "array"), field(&channel, "itemSize").as_f64().unwrap(), indices)
}

/// The distinct (vertex, value index) pairs of a mesh's corners: the vertex count a drawable
/// mesh must have.
fn distinct_pairs(indices: &[u32], values: &[u32]) -> usize {
    let mut pairs: Vec<(u32, u32)> = indices.iter().copied().zip(values.iter().copied()).collect();
    pairs.sort_unstable();
    pairs.dedup();
    pairs.len()
}

#[wasm_bindgen_test]
fn fvar_linear_option_takes_the_six_modes_and_names_a_near_miss() {
    let modes: Vec<String> = fvar_linear_modes().iter().map(|m| m.as_string().unwrap()).collect();
    let library: Vec<&str> = subsurf::FVarLinear::ALL.iter().map(|m| m.name()).collect();
    assert_eq!(modes, library);
    assert_eq!(modes.len(), 6);
    // Every mode is accepted (the cube has no face-varying channel, so the result is the same).
    let plain = f32s(&ok(subdivide(&cube(), &levels(1.0))), "positions");
    for mode in &modes {
        let options = object(&[("fvarLinear", mode.as_str().into())]);
        assert_eq!(f32s(&ok(subdivide(&cube(), &options)), "positions"), plain, "{mode}");
    }
    let refused: [(JsValue, &[&str]); 4] = [
        (
            "corners-plus-1".into(),
            &["unknown fvarLinear 'corners-plus-1'", "did you mean 'corners-plus1'?", "'all'"],
        ),
        ("linear".into(), &["unknown fvarLinear 'linear'", "'none', 'corners-only'"]),
        (JsValue::from(1), &["fvarLinear must be one of", "'boundaries'", "got 1"]),
        (JsValue::NULL, &["fvarLinear must be one of", "got null"]),
    ];
    for (value, parts) in refused {
        assert_mentions(&thrown(subdivide(&cube(), &object(&[("fvarLinear", value)]))), parts);
    }
    assert_mentions(
        &thrown(subdivide(&cube(), &object(&[("fvarlinear", "all".into())]))),
        &["unknown option 'fvarlinear'", "did you mean 'fvarLinear'"],
    );
    module_works_on("the fvarLinear errors");
}

fn module_works_on(after: &str) {
    let out = ok(subdivide(&cube(), &levels(1.0)));
    assert_eq!(u32s(&out, "faceSizes").len(), 24, "after {after}");
}

#[wasm_bindgen_test]
fn read_obj_returns_the_uv_channel_and_write_obj_writes_it() {
    // Two triangles on the edge 2–3 with a seam there: vertices 2 and 3 have two values each.
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n\
                vt 0 0\nvt 1 0\nvt 0 1\nvt 0.5 0.5 9\nvt 1 1\nvt 0.5 1\n\
                f 1/1 2/2 3/3\nf 3/6 2/4 4/5\n";
    let mesh = ok(read_obj(&text.into()));
    let (values, item_size, indices) = channel_of(&mesh, "uv");
    assert_eq!(item_size, 2.0);
    // The third component of `vt 0.5 0.5 9` is dropped.
    assert_eq!(values, [0., 0., 1., 0., 0., 1., 0.5, 0.5, 1., 1., 0.5, 1.]);
    assert_eq!(indices, Some(vec![0, 1, 2, 5, 3, 4]));
    // Files without vt indices on their faces have no attributes field.
    let plain = ok(read_obj(&"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1 2 3\n".into()));
    assert!(field(&plain, "attributes").is_undefined());

    let written = write_obj(&mesh).unwrap_or_else(|e| panic!("{}", message(e)));
    assert!(written.contains("vt 0.5 1\n") && written.contains("\nf 3/6 2/4 4/5\n"), "{written}");
    let again = ok(read_obj(&written.into()));
    assert_eq!(channel_of(&again, "uv"), channel_of(&mesh, "uv"));
    assert_eq!(u32s(&again, "indices"), u32s(&mesh, "indices"));

    // A vertex-varying uv is written with one vt per vertex; a uv that cannot be one is refused.
    let per_vertex = object(&[
        ("array", Float32Array::from(&[0., 0., 1., 0., 0., 1., 1., 1.][..]).into()),
        ("itemSize", 2.into()),
    ]);
    let (p, i) = (f32s(&mesh, "positions"), u32s(&mesh, "indices"));
    let written = write_obj(&with_channels(&js_mesh(&p, &i, None), &[("uv", per_vertex)]))
        .unwrap_or_else(|e| panic!("{}", message(e)));
    assert!(written.contains("\nf 1/1 2/2 3/3\nf 3/3 2/2 4/4\n"), "{written}");
    let wide = with_channels(
        &js_mesh(&p, &i, None),
        &[("uv", channel_with_indices(&[0.0; 24], 4.0, &[0, 1, 2, 3, 4, 5]))],
    );
    assert_mentions(
        &thrown(write_obj(&wide).map(JsValue::from)),
        &["'uv'", "itemSize is 4", "1 to 3"],
    );
    let far = with_channels(
        &js_mesh(&p, &i, None),
        &[("uv", channel_with_indices(&[0.0; 12], 2.0, &[0, 1, 2, 3, 4, 6]))],
    );
    assert_mentions(
        &thrown(write_obj(&far).map(JsValue::from)),
        &["'uv'", "index 5 is 6", "6 values"],
    );
    module_works_on("the writeObj errors");
}

#[wasm_bindgen_test]
fn built_in_shapes_carry_their_uv_layouts() {
    for name in shape_names().iter() {
        let name = name.as_string().unwrap();
        let mesh = ok(shape(&name.as_str().into()));
        let (values, item_size, indices) = channel_of(&mesh, "uv");
        let indices = indices.unwrap_or_else(|| panic!("{name}: the uv channel is face-varying"));
        let corners = u32s(&mesh, "indices");
        assert_eq!((item_size, indices.len()), (2.0, corners.len()), "{name}");
        assert!(indices.iter().all(|&t| (t as usize) < values.len() / 2), "{name}");
        // Seams: the layouts cut every shape but the sheet open, so they have more distinct
        // (vertex, value) pairs than vertices.
        let vertices = f32s(&mesh, "positions").len() / 3;
        let pairs = distinct_pairs(&corners, &indices);
        if name == "sheet-with-holes" {
            assert_eq!(pairs, vertices, "{name}: no seam");
        } else {
            assert!(pairs > vertices, "{name}: {pairs} pairs, {vertices} vertices");
        }
    }
    // The cube's cross: 14 values, each of one vertex.
    let cube_shape = ok(shape(&"cube".into()));
    assert_eq!(channel_of(&cube_shape, "uv").0.len(), 28);
    assert_mentions(&thrown(shape(&"teapot".into())), &["unknown shape", "'teapot'", "'cube'"]);
}

/// Checks a drawable mesh against its source: every corner's new vertex comes from the corner's
/// vertex, has its position and the corner's value of every channel; `triangles` is the fan.
fn assert_drawable_matches(source: &JsValue, drawable: &JsValue, fvar: &str, what: &str) {
    let (positions, indices) = (f32s(source, "positions"), u32s(source, "indices"));
    let sizes = u32s(source, "faceSizes");
    let (values, item_size, value_indices) = channel_of(source, fvar);
    let value_indices = value_indices.expect("a face-varying channel");
    let size = item_size as usize;
    let origins = u32s(drawable, "origins");
    let new_positions = f32s(drawable, "positions");
    let corner_vertex = u32s(drawable, "indices");
    let (resolved, resolved_size, none) = channel_of(drawable, fvar);
    assert_eq!((resolved_size, none), (item_size, None), "{what}: resolved per vertex");
    assert_eq!(origins.len(), distinct_pairs(&indices, &value_indices), "{what}: vertex count");
    assert_eq!(new_positions.len(), 3 * origins.len(), "{what}");
    assert_eq!(resolved.len(), size * origins.len(), "{what}");
    assert!(origins.windows(2).all(|w| w[0] <= w[1]), "{what}: origins ascend");
    assert_eq!(corner_vertex.len(), indices.len(), "{what}");
    for (c, (&v, &o)) in indices.iter().zip(&corner_vertex).enumerate() {
        let o = o as usize;
        assert_eq!(origins[o], v, "{what}: corner {c}");
        assert_eq!(new_positions[3 * o..3 * o + 3], positions[3 * v as usize..3 * v as usize + 3]);
        let t = value_indices[c] as usize;
        assert_eq!(
            resolved[size * o..size * (o + 1)],
            values[size * t..size * (t + 1)],
            "{what}: corner {c}"
        );
    }
    assert_eq!(u32s(drawable, "faceSizes"), sizes, "{what}");
    // The fan of each face, as subdivide's triangles: (first, k, k + 1).
    let mut fan = Vec::new();
    let mut start = 0;
    for &n in &sizes {
        for k in 1..n as usize - 1 {
            fan.extend([
                corner_vertex[start],
                corner_vertex[start + k],
                corner_vertex[start + k + 1],
            ]);
        }
        start += n as usize;
    }
    assert_eq!(u32s(drawable, "triangles"), fan, "{what}: triangles");
}

#[wasm_bindgen_test]
fn to_drawable_splits_seam_vertices() {
    // The square-mapped cube: every corner its own value, so 24 vertices, 3 per cube vertex.
    let mesh = square_mapped_cube();
    let drawable = ok(to_drawable(&mesh));
    assert_drawable_matches(&mesh, &drawable, "uv", "square-mapped cube");
    assert_eq!(u32s(&drawable, "origins"), (0..8).flat_map(|v| [v; 3]).collect::<Vec<u32>>());
    // Every built-in shape with its layout, a vertex-varying channel alongside.
    for name in shape_names().iter() {
        let name = name.as_string().unwrap();
        let mesh = ok(shape(&name.as_str().into()));
        let uv = field(&field(&mesh, "attributes"), "uv");
        let x: Vec<f32> = f32s(&mesh, "positions").chunks(3).map(|p| p[0]).collect();
        let x = object(&[("array", Float32Array::from(&x[..]).into()), ("itemSize", 1.into())]);
        let mesh = with_channels(&mesh, &[("uv", uv), ("x", x)]);
        let drawable = ok(to_drawable(&mesh));
        assert_drawable_matches(&mesh, &drawable, "uv", &name);
        // The vertex-varying channel follows the origin: it is still each vertex's x.
        let xs: Vec<f32> = f32s(&drawable, "positions").chunks(3).map(|p| p[0]).collect();
        assert_eq!(channel_of(&drawable, "x").0, xs, "{name}");
    }
    // A drawable mesh is a mesh: the other helpers take it as it is (its origins ignored), and
    // splitting it again changes nothing.
    let drawable = ok(to_drawable(&square_mapped_cube()));
    let again = ok(to_drawable(&drawable));
    assert_eq!(u32s(&again, "origins"), (0..24).collect::<Vec<u32>>());
    assert_eq!(f32s(&again, "positions"), f32s(&drawable, "positions"));
    let normals =
        subsurf::wasm::vertex_normals(&drawable).unwrap_or_else(|e| panic!("{}", message(e)));
    assert_eq!(normals.length(), 3 * 24);

    // Without face-varying channels every used vertex stays, once, in order.
    let plain = ok(to_drawable(&cube()));
    assert_eq!(u32s(&plain, "origins"), (0..8).collect::<Vec<u32>>());
    assert_eq!(u32s(&plain, "triangles"), u32s(&ok(subdivide(&cube(), &levels(0.0))), "triangles"));
}

#[wasm_bindgen_test]
fn to_drawable_refuses_bad_input_and_leaves_the_input_alone() {
    let (p, i, s) = cube_arrays();
    let square = [0., 0., 1., 0., 1., 1., 0., 1.].repeat(6);
    let cases: Vec<(JsValue, &[&str])> = vec![
        (
            with_channels(&cube(), &[("uv", channel_with_indices(&square, 2.0, &[0; 23]))]),
            &["attribute 'uv'", "23 indices", "24 face corners"],
        ),
        (
            with_channels(&cube(), &[("uv", channel_with_indices(&square, 2.0, &[24; 24]))]),
            &["attribute 'uv'", "index 0 is 24", "24 values"],
        ),
        (
            with_channels(
                &cube(),
                &[(
                    "uv",
                    object(&[
                        ("array", Float32Array::from(&square[..]).into()),
                        ("itemSize", 2.into()),
                        ("indices", js_sys::Int32Array::new_with_length(24).into()),
                    ]),
                )],
            ),
            &["attributes.uv.indices must be a Uint32Array", "Int32Array"],
        ),
        (
            js_mesh(&p, &[&i[..5], &[99], &i[6..]].concat(), Some(&s)),
            &["indices[5] refers to vertex 99"],
        ),
        (JsValue::from(3), &["mesh must be an object"]),
    ];
    for (mesh, parts) in cases {
        assert_mentions(&thrown(to_drawable(&mesh)), parts);
        module_works_on("a toDrawable error");
    }
    // The caller's arrays are read, never written.
    let mesh = square_mapped_cube();
    let uv = field(&field(&mesh, "attributes"), "uv");
    let before = (
        f32s(&uv, "array"),
        u32s(&uv, "indices"),
        f32s(&mesh, "positions"),
        u32s(&mesh, "indices"),
    );
    let drawable = ok(to_drawable(&mesh));
    let after = (
        f32s(&uv, "array"),
        u32s(&uv, "indices"),
        f32s(&mesh, "positions"),
        u32s(&mesh, "indices"),
    );
    assert_eq!(before, after);
    assert!(!Object::is(&field(&drawable, "positions"), &field(&mesh, "positions")));
}

/// The components of a channel's values in eighths, sorted and deduplicated; fails unless every
/// component is a whole number of eighths.
fn eighths(values: &[f32]) -> Vec<u32> {
    assert!(values.iter().all(|&x| (x * 8.0 - (x * 8.0).round()).abs() < 1e-6), "{values:?}");
    let mut set: Vec<u32> = values.iter().map(|&x| (x * 8.0).round() as u32).collect();
    set.sort_unstable();
    set.dedup();
    set
}

#[wasm_bindgen_test]
fn face_varying_channels_are_refined_through_subdivide_and_base_mesh() {
    // The square-mapped cube. Bilinear level 1 quarters each square: values {0, 0.5, 1}², and
    // each corner's value is the bilinear parameter of its position on its cube face, which for
    // these axis-aligned unit squares is a closed form of the position (checked through the
    // drawable mesh, one value per vertex).
    let mesh = square_mapped_cube();
    let out = ok(subdivide(&mesh, &object(&[("scheme", "bilinear".into())])));
    let (values, item_size, indices) = channel_of(&out, "uv");
    let indices = indices.expect("the result's channel is face-varying");
    assert_eq!((item_size, indices.len()), (2.0, u32s(&out, "indices").len()));
    assert_eq!(eighths(&values), [0, 4, 8]);
    let drawable = ok(to_drawable(&out));
    assert_drawable_matches(&out, &drawable, "uv", "bilinear level 1");
    // Each face of the drawable mesh spans exactly a quarter of its square: its corners' values
    // differ by 0.5 in u or v along every edge, in the order (0,0), (1/2,0), (1/2,1/2), (0,1/2)
    // rotated and shifted.
    let uv = channel_of(&drawable, "uv").0;
    for (f, face) in u32s(&drawable, "indices").chunks(4).enumerate() {
        let at = |k: usize| [uv[2 * face[k] as usize], uv[2 * face[k] as usize + 1]];
        let area: f32 =
            (0..4).map(|k| at(k)[0] * at((k + 1) % 4)[1] - at((k + 1) % 4)[0] * at(k)[1]).sum();
        assert!(
            (area / 2.0 - 0.25).abs() < 1e-6,
            "face {f}: UV area {} (counter-clockwise quarter)",
            area / 2.0
        );
    }

    // The option reaches the rules: Catmull-Clark level 1 keeps the squares' corners under the
    // default 'corners-plus1' and moves them by 3/4 c + 1/8 (a + b) under 'none': 1/8 and 7/8.
    let default = channel_of(&ok(subdivide(&mesh, &levels(1.0))), "uv").0;
    assert_eq!(eighths(&default), [0, 4, 8]);
    let none = object(&[("fvarLinear", "none".into())]);
    assert_eq!(eighths(&channel_of(&ok(subdivide(&mesh, &none)), "uv").0), [0, 1, 4, 7, 8]);

    // BaseMesh: the same result; setAttribute scales the values, and the rules, being linear in
    // them, scale the result; a new array too short for the indices is refused.
    let mut base = subsurf::wasm::BaseMesh::new(&mesh).unwrap_or_else(|e| panic!("{}", message(e)));
    let once = ok(base.subdivide(&levels(2.0), &JsValue::UNDEFINED));
    assert_eq!(channel_of(&once, "uv"), channel_of(&ok(subdivide(&mesh, &levels(2.0))), "uv"));
    let square = [0., 0., 1., 0., 1., 1., 0., 1.].repeat(6);
    let doubled: Vec<f32> = square.iter().map(|x| 2.0 * x).collect();
    base.set_attribute("uv", &Float32Array::from(&doubled[..]).into()).unwrap();
    let twice = ok(base.subdivide(&levels(2.0), &JsValue::UNDEFINED));
    let (once_values, _, once_indices) = channel_of(&once, "uv");
    let (twice_values, _, twice_indices) = channel_of(&twice, "uv");
    assert_eq!(once_indices, twice_indices);
    for (a, b) in once_values.iter().zip(&twice_values) {
        assert!((2.0 * a - b).abs() < 1e-6, "{a} doubled is not {b}");
    }
    let short = base.set_attribute("uv", &Float32Array::from(&doubled[..46]).into());
    assert_mentions(&thrown(short), &["attribute 'uv'", "index 23 is 23", "23 values"]);
    let kept = ok(base.subdivide(&levels(2.0), &JsValue::UNDEFINED));
    assert_eq!(
        channel_of(&kept, "uv"),
        channel_of(&twice, "uv"),
        "the refused call kept the values"
    );

    // The caller's channel was read, never written, by every call above.
    let uv = field(&field(&mesh, "attributes"), "uv");
    assert_eq!(
        (f32s(&uv, "array"), u32s(&uv, "indices")),
        (square.clone(), (0..24).collect::<Vec<u32>>())
    );

    // Doo-Sabin refines the channel too: each of its values is a weighted mean within one
    // face's square, and its faces across the cube's edges take one side's square, so every
    // value stays in [0, 1]², with indices parallel to the result's.
    let dual = ok(subdivide(&mesh, &object(&[("scheme", "doo-sabin".into())])));
    let (values, _, indices) = channel_of(&dual, "uv");
    assert_eq!(indices.map(|i| i.len()), Some(u32s(&dual, "indices").len()));
    assert!(values.iter().all(|x| (0.0..=1.0).contains(x)), "{values:?}");
}

#[wasm_bindgen_test]
fn obj_uvs_survive_subdivide_write_and_read() {
    // A textured OBJ through the whole JS path: readObj, subdivide, writeObj, readObj again.
    let text =
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n";
    let mesh = ok(read_obj(&text.into()));
    let out = ok(subdivide(&mesh, &object(&[("levels", 2.into()), ("scheme", "bilinear".into())])));
    let written = write_obj(&out).unwrap_or_else(|e| panic!("{}", message(e)));
    let again = ok(read_obj(&written.into()));
    assert_eq!(channel_of(&again, "uv"), channel_of(&out, "uv"));
    // One quad, two bilinear levels: the 5 × 5 grid of quarter steps, and a planar quad's UV
    // is its position (x, y).
    let (values, _, indices) = channel_of(&out, "uv");
    assert_eq!(values.len(), 2 * 25);
    let positions = f32s(&out, "positions");
    for (&v, &t) in u32s(&out, "indices").iter().zip(&indices.unwrap()) {
        let (v, t) = (v as usize, t as usize);
        assert_eq!([values[2 * t], values[2 * t + 1]], [positions[3 * v], positions[3 * v + 1]]);
    }
}
