//! Helpers for viewers (the demo page): named shapes, predicted sizes, normals, edges, and
//! meshes with seams made drawable.

use super::*;

#[wasm_bindgen(typescript_custom_section)]
pub(super) const VIEWER_TYPESCRIPT_SECTION: &'static str = include_str!("../../js/viewer.d.ts");

/// The names `shape(name)` accepts, in the order a page would list them.
#[wasm_bindgen(js_name = shapeNames, unchecked_return_type = "string[]")]
pub fn shape_names() -> Array {
    crate::shapes::DEMO_SHAPES.iter().map(|s| JsValue::from_str(s)).collect()
}

/// A built-in mesh by name (see `shapeNames()`): the demo page's cube, torus, sheet with holes,
/// icosahedron, dodecahedron and house (quads and triangles), with its UV layout as the
/// face-varying channel `attributes.uv` (seams where the layout cuts the surface open).
#[wasm_bindgen(js_name = shape, unchecked_return_type = "ShapeMesh")]
pub fn shape(#[wasm_bindgen(unchecked_param_type = "string")] name: &JsValue) -> JsResult<JsValue> {
    let text = name.as_string();
    let mesh = text.as_deref().and_then(crate::shapes::demo_shape);
    let uv = text.as_deref().and_then(crate::shapes::demo_shape_uv);
    match (mesh, uv) {
        (Some(mesh), Some(uv)) => {
            let object = mesh_object(&mesh)?;
            set_field(&object, "attributes", &channels_object(&[uv])?)?;
            Ok(object)
        }
        _ => Err(JsError::new(&format!(
            "unknown shape {}; use one of {}",
            describe(name),
            quoted_list(crate::shapes::DEMO_SHAPES.iter().copied())
        ))),
    }
}

/// The sizes `subdivide(mesh, options)` would produce after each of its levels, from the
/// counts formulas, without refining: the same numbers its `maxFaces` guard checks, so the
/// highest level that fits is the last `l` with `faces[l] <= maxFaces`. `options.maxFaces` is
/// read and checked but does not limit the prediction.
#[wasm_bindgen(js_name = predictCounts, unchecked_return_type = "PredictedCounts")]
pub fn predict_counts(
    #[wasm_bindgen(unchecked_param_type = "SubdivideMesh")] mesh: &JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "SubdivideOptions")] options: &JsValue,
) -> JsResult<JsValue> {
    let (options, _) = read_options(options).map_err(js_error)?;
    let mesh = read_mesh(mesh).map_err(js_error)?;
    let base = HalfEdgeMesh::from_poly(&mesh).map_err(js_error)?;
    predicted_counts_object(&base, &options)
}

/// [`predict_counts`]'s result for a built mesh.
pub(super) fn predicted_counts_object(base: &HalfEdgeMesh, options: &Options) -> JsResult<JsValue> {
    let levels = options.levels();
    let (mut vertices, mut faces) =
        (Vec::with_capacity(levels + 1), Vec::with_capacity(levels + 1));
    for level in 0..=levels {
        let prefix = Options { schemes: options.schemes[..level].to_vec(), ..options.clone() };
        let (v, f) = scheme::predict_counts(base, &prefix);
        vertices.push(v as f64);
        faces.push(f as f64);
    }
    let object = Object::new();
    for (key, values) in [("vertices", vertices), ("faces", faces)] {
        Reflect::set(&object, &JsValue::from_str(key), &js_sys::Float64Array::from(&values[..]))
            .map_err(|_| JsError::new(&format!("could not set result field {key}")))?;
    }
    Ok(object.into())
}

/// Smooth vertex normals for shading, x, y, z per vertex: the area-weighted mean of the normals
/// of the faces around each vertex, normalised; (0, 0, 0) for a vertex no face uses.
#[wasm_bindgen(js_name = vertexNormals)]
pub fn vertex_normals(
    #[wasm_bindgen(unchecked_param_type = "SubdivideMesh")] mesh: &JsValue,
) -> JsResult<Float32Array> {
    let mesh = read_mesh(mesh).map_err(js_error)?;
    let normals = crate::shapes::vertex_normals(&mesh).map_err(js_error)?;
    Ok(Float32Array::from(&normals[..]))
}

/// Every edge of the faces once, as vertex index pairs `[a0, b0, a1, b1, ...]` for
/// `gl.drawElements(gl.LINES, ...)`: a wireframe of the polygons, not of their triangulation.
#[wasm_bindgen(js_name = edgeList)]
pub fn edge_list(
    #[wasm_bindgen(unchecked_param_type = "SubdivideMesh")] mesh: &JsValue,
) -> JsResult<Uint32Array> {
    let mesh = read_mesh(mesh).map_err(js_error)?;
    let edges = crate::shapes::edge_list(&mesh).map_err(js_error)?;
    Ok(Uint32Array::from(&edges[..]))
}

/// A mesh with face-varying channels (a result with UVs) as one WebGL index buffer needs it: one
/// vertex per distinct combination of a vertex and the value indices of its face corners, so
/// vertices split along seams. Returns `positions`, `indices` and `faceSizes` in the new
/// numbering, `triangles` (the fan of each face, as `subdivide`'s), `origins` (the input vertex
/// of each new one, ascending) and `attributes`: every channel of `mesh.attributes` with one
/// value per new vertex (vertex-varying ones copied from the origin, face-varying ones
/// resolved, no `indices`). Vertices no face uses are left out. Checks the arrays as
/// `subdivide` does.
#[wasm_bindgen(js_name = toDrawable, unchecked_return_type = "DrawableMesh")]
pub fn to_drawable(
    #[wasm_bindgen(unchecked_param_type = "SubdivideMesh")] mesh: &JsValue,
) -> JsResult<JsValue> {
    let poly = read_mesh(mesh).map_err(js_error)?;
    let attributes = read_attributes(mesh).map_err(js_error)?;
    let drawable = crate::drawable::to_drawable(&poly, &attributes).map_err(js_error)?;
    let object = Object::new();
    set_field(&object, "positions", &Float32Array::from(&drawable.positions[..]))?;
    set_field(&object, "indices", &Uint32Array::from(&drawable.indices[..]))?;
    set_field(&object, "faceSizes", &Uint32Array::from(&drawable.face_sizes[..]))?;
    set_field(&object, "triangles", &Uint32Array::from(&drawable.triangles[..]))?;
    set_field(&object, "origins", &Uint32Array::from(&drawable.origins[..]))?;
    set_field(&object, "attributes", &channels_object(&drawable.attributes)?)?;
    Ok(object.into())
}
