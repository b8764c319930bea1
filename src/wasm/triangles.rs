//! Triangle soups (a renderer's triangle list) made into faces to subdivide: the bindings of
//! `crate::triangles`, which `subsurf/three` calls. Arrays in, arrays out, errors as `Error`.

use super::*;
use crate::triangles::{self, FaceOptions, QuadLimits};

#[wasm_bindgen(typescript_custom_section)]
const TRIANGLES_TYPESCRIPT_SECTION: &'static str = include_str!("../../js/triangles.d.ts");

/// Fields of `triangleFaces`' first argument.
const TRIANGLE_KEYS: [&str; 3] = ["positions", "corners", "inputCorners"];

/// Options of `triangleFaces`.
const FACE_OPTION_KEYS: [&str; 8] = [
    "creaseAngle",
    "splitNormals",
    "creases",
    "quads",
    "groups",
    "cornerClasses",
    "holes",
    "sides",
];

/// Welds a triangle list: vertices with bit-identical positions (-0 as 0) become one, and with
/// `weld > 0` positions nearer than `weld` too (each joins the nearest earlier cluster centre).
/// `index` names three vertices per triangle. Returns `weldOf` (the welded vertex of each input
/// vertex, -1 for one no triangle uses; numbered by first use), `positions` (x, y, z per welded
/// vertex: its first copy's, never averaged), `kept` (the input triangles whose corners stay
/// three different vertices, ascending) and `corners` (three welded vertices per kept triangle).
#[wasm_bindgen(js_name = weldTriangles, unchecked_return_type = "WeldedTriangles")]
pub fn weld_triangles(
    #[wasm_bindgen(unchecked_param_type = "Float32Array")] positions: &JsValue,
    #[wasm_bindgen(unchecked_param_type = "Uint32Array")] index: &JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "number")] weld: &JsValue,
) -> JsResult<JsValue> {
    let positions = f32_argument(positions, "weldTriangles: positions").map_err(js_error)?;
    let index = u32_argument(index, "weldTriangles: index").map_err(js_error)?;
    let distance = if weld.is_undefined() {
        0.0
    } else {
        weld.as_f64().ok_or_else(|| {
            JsError::new(&format!(
                "weldTriangles: weld must be a distance >= 0 (0: only bit-identical positions), \
                 got {}",
                describe(weld)
            ))
        })?
    };
    let welded = triangles::weld_triangles(&positions, &index, distance).map_err(js_error)?;
    let weld_of: Vec<i32> = welded.weld_of.iter().map(|&w| w as i32).collect();
    let object = Object::new();
    set_field(&object, "weldOf", &js_sys::Int32Array::from(&weld_of[..]))?;
    set_field(&object, "positions", &Float32Array::from(&welded.positions[..]))?;
    set_field(&object, "kept", &Uint32Array::from(&welded.kept[..]))?;
    set_field(&object, "corners", &Uint32Array::from(&welded.corners[..]))?;
    Ok(object.into())
}

/// The faces to subdivide from welded triangles (`weldTriangles`' `positions` and `corners`,
/// with `inputCorners`, the input vertex of each corner): sharp edges found by `creaseAngle`
/// and `splitNormals`, triangles joined into quads by `quads` (Blender's "Tris to Quads"), and
/// with `sides`, the smoothing fan of each face corner. Low-level: `subdivideGeometry` of
/// `subsurf/three` is its user; see `TriangleFacesOptions`.
#[wasm_bindgen(js_name = triangleFaces, unchecked_return_type = "TriangleFaces")]
pub fn triangle_faces(
    #[wasm_bindgen(unchecked_param_type = "TriangleFacesInput")] input: &JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "TriangleFacesOptions")] options: &JsValue,
) -> JsResult<JsValue> {
    let read = || -> Result<_, Error> {
        object_argument(input, "triangleFaces: triangles", &TRIANGLE_KEYS)?;
        let positions = f32_argument(&get(input, "positions")?, "triangleFaces: positions")?;
        let corners = u32_argument(&get(input, "corners")?, "triangleFaces: corners")?;
        let input_corners =
            u32_argument(&get(input, "inputCorners")?, "triangleFaces: inputCorners")?;
        Ok((positions, corners, input_corners))
    };
    let (positions, corners, input_corners) = read().map_err(js_error)?;
    let options = FaceArguments::read(options).map_err(js_error)?;
    let faces = triangles::triangle_faces(&positions, &corners, &input_corners, &options.borrow())
        .map_err(js_error)?;
    let polygons = &faces.polygons;
    let indices = polygons.gather(&corners).map_err(js_error)?;
    let input_indices = polygons.gather(&input_corners).map_err(js_error)?;
    let object = Object::new();
    set_field(&object, "faceSizes", &Uint32Array::from(&polygons.face_sizes[..]))?;
    set_field(&object, "indices", &Uint32Array::from(&indices[..]))?;
    set_field(&object, "inputIndices", &Uint32Array::from(&input_indices[..]))?;
    set_field(&object, "firstTriangles", &Uint32Array::from(&polygons.first_triangles[..]))?;
    set_field(&object, "creases", &Uint32Array::from(&faces.creases[..]))?;
    set_field(&object, "holes", &Uint32Array::from(&faces.holes[..]))?;
    if let Some(sides) = &faces.sides {
        set_field(&object, "sides", &Uint32Array::from(&sides[..]))?;
    }
    Ok(object.into())
}

/// `normals` (x, y, z per drawn vertex) with the drawn vertices on sharp edges given their own
/// side's normal: `mesh` is the refined mesh, `sides` a side per face corner (below
/// `sideCount`), `drawnIndices` each face corner's drawn vertex (`toDrawable`'s `indices`).
/// Returns a new array; `normals` is not written. Low-level: used by `subdivideGeometry`.
#[wasm_bindgen(js_name = sideNormals)]
pub fn side_normals(
    #[wasm_bindgen(unchecked_param_type = "SubdivideMesh")] mesh: &JsValue,
    #[wasm_bindgen(unchecked_param_type = "Uint32Array")] sides: &JsValue,
    #[wasm_bindgen(js_name = sideCount)] side_count: u32,
    #[wasm_bindgen(js_name = drawnIndices, unchecked_param_type = "Uint32Array")]
    drawn_indices: &JsValue,
    #[wasm_bindgen(unchecked_param_type = "Float32Array")] normals: &JsValue,
) -> JsResult<Float32Array> {
    let read = || -> Result<_, Error> {
        let mesh = read_mesh(mesh)?;
        let sides = u32_argument(sides, "sideNormals: sides")?;
        let drawn = u32_argument(drawn_indices, "sideNormals: drawnIndices")?;
        let normals = f32_argument(normals, "sideNormals: normals")?;
        triangles::side_normals(&mesh, &sides, side_count as usize, &drawn, &normals)
    };
    let normals = read().map_err(js_error)?;
    Ok(Float32Array::from(&normals[..]))
}

/// The owned arrays of `TriangleFacesOptions`, lent to [`FaceOptions`].
#[derive(Default)]
struct FaceArguments {
    crease_angle: Option<f64>,
    split_normals: Option<Vec<f32>>,
    creases: Vec<u32>,
    crease_sharpness: Vec<f32>,
    quads: Option<QuadLimits>,
    groups: Option<Vec<u32>>,
    corner_classes: Option<Vec<u32>>,
    holes: Vec<u32>,
    sides: bool,
}

impl FaceArguments {
    fn read(value: &JsValue) -> Result<FaceArguments, Error> {
        let mut out = FaceArguments::default();
        if value.is_undefined() || value.is_null() {
            return Ok(out);
        }
        object_argument(value, "triangleFaces: options", &FACE_OPTION_KEYS)?;
        let field = |key: &str| {
            let found = get(value, key)?;
            Ok::<_, Error>((!found.is_undefined() && !found.is_null()).then_some(found))
        };
        let angle = |value: &JsValue, name: &str| match value.as_f64() {
            Some(a) if (0.0..=std::f64::consts::PI).contains(&a) => Ok(a),
            _ => Err(option_error(format!(
                "{name} must be an angle in radians from 0 to Math.PI, got {}",
                describe(value)
            ))),
        };
        if let Some(a) = field("creaseAngle")? {
            out.crease_angle = Some(angle(&a, "creaseAngle")?);
        }
        if let Some(normals) = field("splitNormals")? {
            out.split_normals =
                Some(f32_argument(&normals, "triangleFaces: options.splitNormals")?);
        }
        if let Some(creases) = field("creases")? {
            let (edges, sharpness) = read_sharpness(&creases, "creases", "edges")?;
            let count = edges.len() / 2;
            let sharpness_of = per_item(&sharpness, count, "creases")?;
            out.crease_sharpness = (0..count).map(sharpness_of).collect();
            out.creases = edges;
        }
        if let Some(quads) = field("quads")? {
            if quads.as_bool() == Some(true) {
                out.quads = Some(QuadLimits::default());
            } else if quads.as_bool() != Some(false) {
                if !quads.is_object() {
                    return Err(option_error(format!(
                        "quads must be true, false or {{ faceAngle, shapeAngle }} (radians), got {}",
                        describe(&quads)
                    )));
                }
                let mut limits = QuadLimits::default();
                if let Some(a) = Some(get(&quads, "faceAngle")?).filter(|a| !a.is_undefined()) {
                    limits.face_angle = angle(&a, "quads.faceAngle")?;
                }
                if let Some(a) = Some(get(&quads, "shapeAngle")?).filter(|a| !a.is_undefined()) {
                    limits.shape_angle = angle(&a, "quads.shapeAngle")?;
                }
                out.quads = Some(limits);
            }
        }
        if let Some(groups) = field("groups")? {
            out.groups = Some(u32_argument(&groups, "triangleFaces: options.groups")?);
        }
        if let Some(classes) = field("cornerClasses")? {
            out.corner_classes =
                Some(u32_argument(&classes, "triangleFaces: options.cornerClasses")?);
        }
        if let Some(holes) = field("holes")? {
            out.holes = u32_argument(&holes, "triangleFaces: options.holes")?;
        }
        if let Some(sides) = field("sides")? {
            out.sides = sides.as_bool().ok_or_else(|| {
                option_error(format!("sides must be true or false, got {}", describe(&sides)))
            })?;
        }
        Ok(out)
    }

    fn borrow(&self) -> FaceOptions<'_> {
        FaceOptions {
            crease_angle: self.crease_angle,
            split_normals: self.split_normals.as_deref(),
            creases: &self.creases,
            crease_sharpness: &self.crease_sharpness,
            quads: self.quads,
            groups: self.groups.as_deref(),
            corner_classes: self.corner_classes.as_deref(),
            holes: &self.holes,
            sides: self.sides,
        }
    }
}

fn object_argument(value: &JsValue, name: &str, keys: &[&str]) -> Result<(), Error> {
    if !value.is_object() || is_array(value) || is_typed_array(value) {
        return Err(option_error(format!(
            "{name} must be an object with {}, got {}",
            quoted_list(keys.iter().copied()),
            describe(value)
        )));
    }
    check_keys(value, keys, &[], "field", "fields")
        .map_err(|m| option_error(format!("{name}: {m}")))
}

/// `field` ("function: name") as a copy, when it is a Float32Array.
fn f32_argument(value: &JsValue, field: &str) -> Result<Vec<f32>, Error> {
    if typed_array_kind(value).as_deref() != Some("Float32Array") {
        return Err(wrong_type(field, "Float32Array", value));
    }
    copy_f32(value, field)
}

/// `field` ("function: name") as a copy, when it is a Uint32Array.
fn u32_argument(value: &JsValue, field: &str) -> Result<Vec<u32>, Error> {
    if typed_array_kind(value).as_deref() != Some("Uint32Array") {
        return Err(wrong_type(field, "Uint32Array", value));
    }
    copy_u32(value, field)
}

fn wrong_type(field: &str, expected: &str, got: &JsValue) -> Error {
    let hint = if is_array(got) || is_typed_array(got) {
        format!("; convert it with new {expected}(array)")
    } else {
        String::new()
    };
    Error::InvalidMesh(format!("{field} must be a {expected}, got {}{hint}", describe(got)))
}
