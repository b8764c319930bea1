//! The JavaScript API: typed arrays in, typed arrays out, a thrown `Error` with a message.
//!
//! This layer only converts and checks. Mesh fields are read with `Reflect` calls (a throwing
//! getter becomes an error) and copied into Rust-owned vectors, so the caller's arrays are never
//! written; outputs are fresh typed arrays, or those the caller lends back for the purpose
//! (`into`), never views of wasm memory (those go stale when memory grows). Every failure is a
//! `Result`: a panic would abort the module instance and break every later call on the page.
//!
//! ```js
//! import init, { subdivide } from 'subsurf';
//! await init();
//! const out = subdivide({ positions, indices, faceSizes }, { levels: 2 });
//! gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, out.triangles, gl.STATIC_DRAW);
//! ```

use crate::attributes::{self, Attribute};
use crate::error::Error;
use crate::io;
use crate::mesh::{HalfEdgeMesh, PolyMesh};
use crate::scheme::{self, Boundary, Options, Refined, Scheme};
use crate::tags::{Corner, Crease, CreaseMethod, Tags};
use js_sys::{Array, Float32Array, Object, Reflect, Uint32Array};
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

// The macro consumes the item it marks, so the text lives in its own constant that the unit test
// below can also read.
#[wasm_bindgen(typescript_custom_section)]
const TYPESCRIPT_SECTION: &'static str = TYPESCRIPT_TYPES;

/// The interfaces of the JS API, added to `subsurf.d.ts`.
// The macro's expansion reads this in a way the dead-code lint does not see.
#[allow(dead_code)]
const TYPESCRIPT_TYPES: &str = include_str!("../js/types.d.ts");

/// Option keys, in the order error messages list them. Must match what [`read_options`] reads.
const OPTION_KEYS: [&str; 10] = [
    "scheme",
    "levels",
    "boundary",
    "maxFaces",
    "maxBytes",
    "creases",
    "corners",
    "holes",
    "creaseMethod",
    "smoothTriangles",
];

/// Mesh fields read from the input object.
const MESH_KEYS: [&str; 4] = ["positions", "indices", "faceSizes", "attributes"];

/// Fields of one attribute channel.
const CHANNEL_KEYS: [&str; 3] = ["array", "itemSize", "indices"];

/// Mesh fields accepted and ignored: the extra output of `subdivide` and of `readObj`.
const IGNORED_MESH_KEYS: [&str; 2] = ["triangles", "tags"];

/// The most levels one call accepts (the library's [`scheme::MAX_LEVELS`]).
pub const MAX_LEVELS: u32 = scheme::MAX_LEVELS as u32;

/// `Number.MAX_SAFE_INTEGER`: the largest whole number a JS number holds exactly.
const MAX_SAFE_INTEGER: f64 = 9_007_199_254_740_991.0;

type JsResult<T> = Result<T, JsError>;

fn js_error(error: Error) -> JsError {
    JsError::new(&error.to_string())
}

/// Subdivides a polygon mesh and returns the refined mesh as typed arrays.
///
/// `mesh.faceSizes` may be omitted when every face is a triangle. Throws an `Error` whose
/// message says what is wrong (an unknown option, a wrong array type, an index out of range, a
/// result larger than `maxFaces`, ...); the module stays usable after an error.
///
/// `into`, a previous result, lends its arrays: each one of the type and length needed is
/// written over instead of a fresh array being made (for 4M quads, fresh arrays cost 120 ms of
/// the call in page faults, refilling them 30). The result is a new object; use its arrays, not
/// `into`'s, which keeps any it could not reuse.
#[wasm_bindgen(js_name = subdivide, unchecked_return_type = "SubdivideResult")]
pub fn subdivide(
    #[wasm_bindgen(unchecked_param_type = "SubdivideMesh")] mesh: &JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "SubdivideOptions")] options: &JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "SubdivideResult")] into: &JsValue,
) -> JsResult<JsValue> {
    let (options, tags) = read_options(options).map_err(js_error)?;
    let lent = Lent::read(into).map_err(js_error)?;
    let base = read_half_edge_mesh(mesh).map_err(js_error)?;
    let attributes = read_attributes(mesh).map_err(js_error)?;
    let refined = scheme::subdivide_mesh_refined_with(base, &attributes, &options, &tags)
        .map_err(js_error)?;
    refined_object(&refined, lent)
}

/// A mesh built once, to be subdivided many times: with other options (a level slider), or with
/// other positions of the same faces (an animation, through `setPositions`). Building the
/// connectivity from the arrays, about a third of a `subdivide` call, is then paid once; this is
/// OpenSubdiv's split of `TopologyRefinerFactory::Create` from refining.
///
/// ```js
/// const base = new BaseMesh({ positions, indices, faceSizes });
/// let out = base.subdivide({ levels: 2 });
/// // every frame:
/// base.setPositions(skinnedPositions);
/// out = base.subdivide({ levels: 2 }, out);
/// // when done (or let the garbage collector do it):
/// base.free();
/// ```
#[wasm_bindgen]
pub struct BaseMesh {
    mesh: HalfEdgeMesh,
    attributes: Vec<Attribute>,
}

#[wasm_bindgen]
impl BaseMesh {
    /// Copies and checks the arrays as `subdivide` does, and builds the connectivity. Throws
    /// what `subdivide` would throw for the same mesh.
    #[wasm_bindgen(constructor)]
    pub fn new(
        #[wasm_bindgen(unchecked_param_type = "SubdivideMesh")] mesh: &JsValue,
    ) -> JsResult<BaseMesh> {
        let base = read_half_edge_mesh(mesh).map_err(js_error)?;
        let attributes = read_attributes(mesh).map_err(js_error)?;
        scheme::check_attributes(&attributes, &base).map_err(js_error)?;
        Ok(BaseMesh { mesh: base, attributes })
    }

    /// `subdivide(mesh, options, into)` for this mesh, which stays as it is.
    #[wasm_bindgen(unchecked_return_type = "SubdivideResult")]
    pub fn subdivide(
        &self,
        #[wasm_bindgen(unchecked_optional_param_type = "SubdivideOptions")] options: &JsValue,
        #[wasm_bindgen(unchecked_optional_param_type = "SubdivideResult")] into: &JsValue,
    ) -> JsResult<JsValue> {
        let (options, tags) = read_options(options).map_err(js_error)?;
        let lent = Lent::read(into).map_err(js_error)?;
        let refined =
            scheme::subdivide_mesh_borrowed_with(&self.mesh, &self.attributes, &options, &tags)
                .map_err(js_error)?;
        refined_object(&refined, lent)
    }

    /// `predictCounts(mesh, options)` for this mesh: the sizes after each level, without
    /// refining (for the highest level that fits a budget).
    #[wasm_bindgen(js_name = predictCounts, unchecked_return_type = "PredictedCounts")]
    pub fn predict_counts(
        &self,
        #[wasm_bindgen(unchecked_optional_param_type = "SubdivideOptions")] options: &JsValue,
    ) -> JsResult<JsValue> {
        let (options, _) = read_options(options).map_err(js_error)?;
        predicted_counts_object(&self.mesh, &options)
    }

    /// Moves the vertices: x, y, z per vertex, as many vertices as the mesh has, all finite.
    /// The faces stay. Throws, and leaves the mesh as it was, otherwise.
    #[wasm_bindgen(js_name = setPositions)]
    pub fn set_positions(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] positions: &JsValue,
    ) -> JsResult<()> {
        if typed_array_kind(positions).as_deref() != Some("Float32Array") {
            return Err(js_error(wrong_array_type("positions", "Float32Array", positions)));
        }
        let positions = copy_vertices(positions).map_err(js_error)?;
        self.mesh.set_positions(positions).map_err(js_error)
    }

    /// Replaces the values of the vertex-varying channel `name` (given to the constructor in
    /// `mesh.attributes`): `itemSize` floats per vertex, all finite. Throws, and leaves the
    /// channel as it was, otherwise.
    #[wasm_bindgen(js_name = setAttribute)]
    pub fn set_attribute(
        &mut self,
        name: &str,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] array: &JsValue,
    ) -> JsResult<()> {
        let Some(i) = self.attributes.iter().position(|a| a.name == name) else {
            let names = quoted_list(self.attributes.iter().map(|a| a.name.as_str()));
            let known = if self.attributes.is_empty() { "none".to_string() } else { names };
            return Err(js_error(Error::InvalidAttribute(format!(
                "attribute '{name}': this mesh has no such channel (its channels: {known}); \
                 give every channel to the BaseMesh constructor in mesh.attributes"
            ))));
        };
        if self.attributes[i].is_face_varying() {
            return Err(js_error(Error::InvalidAttribute(format!(
                "attribute '{name}': setAttribute takes vertex-varying channels only"
            ))));
        }
        let field = format!("attributes.{name}.array");
        if typed_array_kind(array).as_deref() != Some("Float32Array") {
            return Err(js_error(wrong_array_type(&field, "Float32Array", array)));
        }
        let mut channel = self.attributes[i].clone();
        channel.values = copy_f32(array, &field).map_err(js_error)?;
        let vertices = self.mesh.num_vertices();
        attributes::validate(std::slice::from_ref(&channel), vertices, self.mesh.num_half_edges())
            .map_err(js_error)?;
        self.attributes[i] = channel;
        Ok(())
    }

    /// The number of vertices, which `setPositions` takes 3 numbers each of.
    #[wasm_bindgen(getter, js_name = numVertices)]
    pub fn num_vertices(&self) -> u32 {
        self.mesh.num_vertices() as u32
    }

    /// The number of faces.
    #[wasm_bindgen(getter, js_name = numFaces)]
    pub fn num_faces(&self) -> u32 {
        self.mesh.num_cells() as u32
    }
}

/// Parses the text of a Wavefront OBJ file: `v` and `f` lines, and OpenSubdiv's `t` tag lines
/// (`crease`, `corner`, `hole`, `interpolateboundary`, `creasemethod`, `smoothtriangles`) as
/// `tags`, in the shapes `subdivide`'s options take. Everything else is skipped. A malformed
/// line, tag lines included, throws an `Error` naming the line.
#[wasm_bindgen(js_name = readObj, unchecked_return_type = "ObjMesh")]
pub fn read_obj(
    #[wasm_bindgen(unchecked_param_type = "string")] text: &JsValue,
) -> JsResult<JsValue> {
    let text = text.as_string().ok_or_else(|| {
        JsError::new(&format!(
            "readObj expects the text of an OBJ file as a string, got {}; read the file with \
             await file.text() or fs.readFileSync(path, 'utf8')",
            describe(text)
        ))
    })?;
    let obj = io::read_obj_with_tags(&text).map_err(js_error)?;
    let object = mesh_object(&obj.mesh)?;
    set_field(&object, "tags", &obj_tags_object(&obj.tags, obj.boundary)?)?;
    Ok(object)
}

/// `ObjTags`: the reverse of [`read_tags`] for what an OBJ file can say. The optional fields
/// appear only when they differ from the option's default, so spreading the tags over the
/// options never silently resets a choice the file did not make.
fn obj_tags_object(tags: &Tags, boundary: Option<Boundary>) -> JsResult<JsValue> {
    let pairs: Vec<u32> = tags.creases.iter().flat_map(|c| c.vertices).collect();
    let crease_sharpness: Vec<f32> = tags.creases.iter().map(|c| c.sharpness).collect();
    let vertices: Vec<u32> = tags.corners.iter().map(|c| c.vertex).collect();
    let corner_sharpness: Vec<f32> = tags.corners.iter().map(|c| c.sharpness).collect();

    let creases = Object::new();
    set_field(&creases, "edges", &Uint32Array::from(&pairs[..]))?;
    set_field(&creases, "sharpness", &Float32Array::from(&crease_sharpness[..]))?;
    let corners = Object::new();
    set_field(&corners, "vertices", &Uint32Array::from(&vertices[..]))?;
    set_field(&corners, "sharpness", &Float32Array::from(&corner_sharpness[..]))?;

    let object = Object::new();
    set_field(&object, "creases", &creases)?;
    set_field(&object, "corners", &corners)?;
    set_field(&object, "holes", &Uint32Array::from(&tags.holes[..]))?;
    if let Some(boundary) = boundary {
        set_field(&object, "boundary", &JsValue::from_str(boundary.name()))?;
    }
    if tags.crease_method != CreaseMethod::default() {
        set_field(&object, "creaseMethod", &JsValue::from_str(tags.crease_method.name()))?;
    }
    if tags.smooth_triangles {
        set_field(&object, "smoothTriangles", &JsValue::TRUE)?;
    }
    Ok(object.into())
}

/// Writes a polygon mesh as Wavefront OBJ text (`v` and `f` lines, 1-based indices).
#[wasm_bindgen(js_name = writeObj)]
pub fn write_obj(
    #[wasm_bindgen(unchecked_param_type = "SubdivideMesh")] mesh: &JsValue,
) -> JsResult<String> {
    let mesh = read_mesh(mesh).map_err(js_error)?;
    // The library's mesh builder is the one place that knows what a valid mesh is; running it
    // here keeps a bad index from turning into an OBJ file no reader accepts.
    HalfEdgeMesh::from_poly(&mesh).map_err(js_error)?;
    Ok(io::write_obj(&mesh))
}

/// The names `options.scheme` accepts, in the library's order.
#[wasm_bindgen(js_name = schemeNames, unchecked_return_type = "SchemeName[]")]
pub fn scheme_names() -> Array {
    Scheme::ALL.iter().map(|s| JsValue::from_str(s.name())).collect()
}

/// The names `options.boundary` accepts, the default first.
#[wasm_bindgen(js_name = boundaryRules, unchecked_return_type = "BoundaryRule[]")]
pub fn boundary_rules() -> Array {
    Boundary::ALL.iter().map(|b| JsValue::from_str(b.name())).collect()
}

/// The version of the subsurf package.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}

// ---------------------------------------------------------------------------------------------
// Helpers for viewers (the demo page): named shapes, predicted sizes, normals, edges

#[wasm_bindgen(typescript_custom_section)]
const VIEWER_TYPESCRIPT_SECTION: &'static str = include_str!("../js/viewer.d.ts");

/// The names `shape(name)` accepts, in the order a page would list them.
#[wasm_bindgen(js_name = shapeNames, unchecked_return_type = "string[]")]
pub fn shape_names() -> Array {
    crate::shapes::DEMO_SHAPES.iter().map(|s| JsValue::from_str(s)).collect()
}

/// A built-in mesh by name (see `shapeNames()`): the demo page's cube, torus, sheet with holes,
/// icosahedron, dodecahedron and house (quads and triangles).
#[wasm_bindgen(js_name = shape, unchecked_return_type = "PolygonMesh")]
pub fn shape(#[wasm_bindgen(unchecked_param_type = "string")] name: &JsValue) -> JsResult<JsValue> {
    let mesh = name.as_string().and_then(|name| crate::shapes::demo_shape(&name));
    match mesh {
        Some(mesh) => mesh_object(&mesh),
        None => Err(JsError::new(&format!(
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
fn predicted_counts_object(base: &HalfEdgeMesh, options: &Options) -> JsResult<JsValue> {
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

// ---------------------------------------------------------------------------------------------
// Options

fn option_error(message: String) -> Error {
    Error::InvalidOption(message)
}

fn read_options(value: &JsValue) -> Result<(Options, Tags), Error> {
    if value.is_undefined() || value.is_null() {
        return Ok((Options::default(), Tags::default()));
    }
    if !value.is_object() || is_array(value) {
        return Err(option_error(format!(
            "options must be an object such as {{ levels: 2 }}, got {}",
            describe(value)
        )));
    }
    check_keys(value, &OPTION_KEYS, &[], "option", "options").map_err(option_error)?;
    // Each field is read as a raw JS value so that the checks below can name the option and
    // show what was given. Reflect.get returns a throwing getter's exception as an error
    // instead of letting it unwind through this code.
    let field = |key: &str| {
        Reflect::get(value, &JsValue::from_str(key))
            .map_err(|e| option_error(format!("reading options.{key} threw {}", describe(&e))))
    };

    let levels = read_levels(&field("levels")?)?;
    let schemes = match read_schemes(&field("scheme")?)? {
        SchemeChoice::Default => vec![Scheme::default(); levels.unwrap_or(1) as usize],
        SchemeChoice::One(scheme) => vec![scheme; levels.unwrap_or(1) as usize],
        SchemeChoice::PerLevel(list) => {
            if let Some(levels) = levels {
                if levels as usize != list.len() {
                    return Err(option_error(format!(
                        "scheme lists {} schemes (one per level) but levels is {levels}; \
                         drop levels or make the two agree",
                        list.len()
                    )));
                }
            }
            list
        }
    };
    let boundary = read_boundary(&field("boundary")?)?;
    let max_faces = read_limit(&field("maxFaces")?, "maxFaces")?;
    let max_bytes = read_limit(&field("maxBytes")?, "maxBytes")?;
    let defaults = Options::default();
    let options = Options {
        schemes,
        boundary: boundary.unwrap_or(defaults.boundary),
        max_faces: max_faces.unwrap_or(defaults.max_faces),
        max_bytes: max_bytes.unwrap_or(defaults.max_bytes),
    };
    Ok((options, read_tags(&field)?))
}

/// The tag options: `creases`, `corners`, `holes`, `creaseMethod`, `smoothTriangles`.
fn read_tags(field: &dyn Fn(&str) -> Result<JsValue, Error>) -> Result<Tags, Error> {
    let mut tags = Tags::default();
    let creases = field("creases")?;
    if !creases.is_undefined() {
        let (pairs, sharpness) = read_sharpness(&creases, "creases", "edges")?;
        if pairs.len() % 2 != 0 {
            return Err(option_error(format!(
                "creases.edges has {} entries; give vertex pairs, two entries per edge",
                pairs.len()
            )));
        }
        let count = pairs.len() / 2;
        let value = per_item(&sharpness, count, "creases")?;
        tags.creases = (0..count)
            .map(|i| Crease { vertices: [pairs[2 * i], pairs[2 * i + 1]], sharpness: value(i) })
            .collect();
    }
    let corners = field("corners")?;
    if !corners.is_undefined() {
        let (vertices, sharpness) = read_sharpness(&corners, "corners", "vertices")?;
        let value = per_item(&sharpness, vertices.len(), "corners")?;
        tags.corners = vertices
            .iter()
            .enumerate()
            .map(|(i, &vertex)| Corner { vertex, sharpness: value(i) })
            .collect();
    }
    let holes = field("holes")?;
    if !holes.is_undefined() {
        tags.holes = match typed_array_kind(&holes).as_deref() {
            Some("Uint32Array") => copy_u32(&holes, "holes")?,
            _ => return Err(wrong_option_array("holes", "Uint32Array", &holes)),
        };
    }
    let method = field("creaseMethod")?;
    if !method.is_undefined() {
        tags.crease_method = match method.as_string().as_deref() {
            Some("uniform") => CreaseMethod::Uniform,
            Some("chaikin") => CreaseMethod::Chaikin,
            _ => {
                return Err(option_error(format!(
                    "creaseMethod must be 'uniform' or 'chaikin', got {}",
                    describe(&method)
                )))
            }
        };
    }
    let smooth = field("smoothTriangles")?;
    if !smooth.is_undefined() {
        tags.smooth_triangles = smooth.as_bool().ok_or_else(|| {
            option_error(format!(
                "smoothTriangles must be true or false, got {}",
                describe(&smooth)
            ))
        })?;
    }
    Ok(tags)
}

/// `{ <items>: Uint32Array, sharpness: Float32Array }` of `creases` or `corners`.
fn read_sharpness(value: &JsValue, name: &str, items: &str) -> Result<(Vec<u32>, Vec<f32>), Error> {
    if !value.is_object() || is_array(value) {
        return Err(option_error(format!(
            "{name} must be an object {{ {items}: Uint32Array, sharpness: Float32Array }}, got {}",
            describe(value)
        )));
    }
    let list = get(value, items)?;
    let list = match typed_array_kind(&list).as_deref() {
        Some("Uint32Array") => copy_u32(&list, &format!("{name}.{items}"))?,
        _ => return Err(wrong_option_array(&format!("{name}.{items}"), "Uint32Array", &list)),
    };
    let sharpness = get(value, "sharpness")?;
    let sharpness = match typed_array_kind(&sharpness).as_deref() {
        Some("Float32Array") => copy_f32(&sharpness, &format!("{name}.sharpness"))?,
        _ => {
            return Err(wrong_option_array(
                &format!("{name}.sharpness"),
                "Float32Array",
                &sharpness,
            ))
        }
    };
    Ok((list, sharpness))
}

/// One sharpness per item, or one for all of them.
fn per_item<'a>(
    sharpness: &'a [f32],
    count: usize,
    name: &str,
) -> Result<impl Fn(usize) -> f32 + 'a, Error> {
    let n = sharpness.len();
    if n != 1 && n != count {
        return Err(option_error(format!(
            "{name}.sharpness has {n} entries for {count} {name}; give one per item or one for all"
        )));
    }
    Ok(move |i: usize| sharpness[if n == 1 { 0 } else { i }])
}

fn wrong_option_array(field: &str, expected: &str, got: &JsValue) -> Error {
    option_error(format!("options.{field} must be a {expected}, got {}", describe(got)))
}

fn read_levels(value: &JsValue) -> Result<Option<u32>, Error> {
    if value.is_undefined() {
        return Ok(None);
    }
    match value.as_f64() {
        Some(x) if x.fract() == 0.0 && (0.0..=MAX_LEVELS as f64).contains(&x) => Ok(Some(x as u32)),
        _ => Err(option_error(format!(
            "levels must be a whole number from 0 to {MAX_LEVELS}, got {}",
            describe(value)
        ))),
    }
}

/// A guard limit (`maxFaces`, `maxBytes`): a whole number from 1 to `MAX_SAFE_INTEGER`.
fn read_limit(value: &JsValue, name: &str) -> Result<Option<u64>, Error> {
    if value.is_undefined() {
        return Ok(None);
    }
    match value.as_f64() {
        Some(x) if x.fract() == 0.0 && (1.0..=MAX_SAFE_INTEGER).contains(&x) => Ok(Some(x as u64)),
        _ => Err(option_error(format!(
            "{name} must be a whole number from 1 to Number.MAX_SAFE_INTEGER, got {}",
            describe(value)
        ))),
    }
}

fn read_boundary(value: &JsValue) -> Result<Option<Boundary>, Error> {
    if value.is_undefined() {
        return Ok(None);
    }
    match value.as_string() {
        Some(name) => name.parse().map(Some),
        None => Err(option_error(format!(
            "boundary must be one of {}, got {}",
            quoted_list(Boundary::ALL.iter().map(|b| b.name())),
            describe(value)
        ))),
    }
}

enum SchemeChoice {
    Default,
    One(Scheme),
    PerLevel(Vec<Scheme>),
}

fn read_schemes(value: &JsValue) -> Result<SchemeChoice, Error> {
    if value.is_undefined() {
        return Ok(SchemeChoice::Default);
    }
    if let Some(name) = value.as_string() {
        return name.parse().map(SchemeChoice::One);
    }
    if is_array(value) {
        // Read through Reflect, which turns a Proxy trap's exception into an error.
        let threw = |what: String, e: JsValue| {
            option_error(format!("reading options.{what} threw {}", describe(&e)))
        };
        let length = Reflect::get(value, &JsValue::from_str("length"))
            .map_err(|e| threw("scheme.length".into(), e))?
            .as_f64()
            .unwrap_or(0.0);
        if length > MAX_LEVELS as f64 {
            return Err(option_error(format!(
                "scheme lists {length} schemes, one per level; at most {MAX_LEVELS} levels are allowed"
            )));
        }
        let mut schemes = Vec::with_capacity(length as usize);
        for i in 0..length as u32 {
            let item = Reflect::get_u32(value, i).map_err(|e| threw(format!("scheme[{i}]"), e))?;
            let scheme = match item.as_string() {
                Some(name) => name.parse().map_err(|e| match e {
                    Error::InvalidOption(m) => option_error(format!("scheme[{i}]: {m}")),
                    other => other,
                })?,
                None => {
                    return Err(option_error(format!(
                        "scheme[{i}] must be a scheme name such as '{}', got {}",
                        Scheme::default().name(),
                        describe(&item)
                    )))
                }
            };
            schemes.push(scheme);
        }
        return Ok(SchemeChoice::PerLevel(schemes));
    }
    Err(option_error(format!(
        "scheme must be one of {} or an array of them (one per level), got {}",
        quoted_list(Scheme::ALL.iter().map(|s| s.name())),
        describe(value)
    )))
}

// ---------------------------------------------------------------------------------------------
// Meshes

fn mesh_error(message: String) -> Error {
    Error::InvalidMesh(message)
}

/// Copies the caller's typed arrays into a [`PolyMesh`].
fn read_mesh(value: &JsValue) -> Result<PolyMesh, Error> {
    let (positions, indices, face_sizes) = read_mesh_arrays(value, |p| copy_f32(p, "positions"))?;
    Ok(PolyMesh { positions, indices, face_sizes })
}

/// Copies the caller's typed arrays into the arrays a [`HalfEdgeMesh`] keeps, and builds it:
/// one copy of each, where [`read_mesh`] and `from_poly` would make two.
fn read_half_edge_mesh(value: &JsValue) -> Result<HalfEdgeMesh, Error> {
    let (positions, indices, face_sizes) = read_mesh_arrays(value, copy_vertices)?;
    HalfEdgeMesh::from_vertices(positions, indices, &face_sizes)
}

/// The channels of `mesh.attributes` (none when it is absent), copied, in the object's key
/// order. Their lengths are checked against the mesh later, with the mesh's counts.
fn read_attributes(mesh: &JsValue) -> Result<Vec<Attribute>, Error> {
    let value = get(mesh, "attributes")?;
    if value.is_undefined() || value.is_null() {
        return Ok(Vec::new());
    }
    let attribute_error = |message: String| Error::InvalidAttribute(message);
    if !value.is_object() || is_array(&value) || is_typed_array(&value) {
        return Err(attribute_error(format!(
            "mesh.attributes must be an object of channels by name, {{ color: {{ array: \
             Float32Array, itemSize: 3 }} }}, got {}",
            describe(&value)
        )));
    }
    let keys = Reflect::own_keys(&value)
        .map_err(|e| attribute_error(format!("listing mesh.attributes threw {}", describe(&e))))?;
    let mut channels = Vec::new();
    for key in keys.iter() {
        let Some(name) = key.as_string() else { continue };
        let at = |what: &str| format!("attribute '{name}': {what}");
        let channel = Reflect::get(&value, &key)
            .map_err(|e| attribute_error(at(&format!("reading it threw {}", describe(&e)))))?;
        if !channel.is_object() || is_array(&channel) || is_typed_array(&channel) {
            return Err(attribute_error(at(&format!(
                "must be an object {{ array: Float32Array, itemSize: number, indices?: \
                 Uint32Array }}, got {}",
                describe(&channel)
            ))));
        }
        check_keys(&channel, &CHANNEL_KEYS, &[], "channel field", "channel fields")
            .map_err(|m| attribute_error(at(&m)))?;
        let read = |field: &str| {
            Reflect::get(&channel, &JsValue::from_str(field)).map_err(|e| {
                attribute_error(at(&format!("reading {field} threw {}", describe(&e))))
            })
        };
        let item_size = read("itemSize")?;
        let item_size = match item_size.as_f64() {
            Some(n) if n.fract() == 0.0 && (1.0..=16.0).contains(&n) => n as usize,
            _ => {
                return Err(attribute_error(at(&format!(
                    "itemSize must be a whole number from 1 to 16, got {}",
                    describe(&item_size)
                ))));
            }
        };
        let field = format!("attributes.{name}.array");
        let array = read("array")?;
        if typed_array_kind(&array).as_deref() != Some("Float32Array") {
            return Err(wrong_array_type(&field, "Float32Array", &array));
        }
        let values = copy_f32(&array, &field)?;
        let indices = read("indices")?;
        let indices = if indices.is_undefined() || indices.is_null() {
            None
        } else {
            let field = format!("attributes.{name}.indices");
            if typed_array_kind(&indices).as_deref() != Some("Uint32Array") {
                return Err(wrong_array_type(&field, "Uint32Array", &indices));
            }
            Some(copy_u32(&indices, &field)?)
        };
        channels.push(Attribute { name, item_size, values, indices });
    }
    Ok(channels)
}

/// The three arrays of the caller's mesh object, checked and copied in this order (so that the
/// first fault is the one reported), the positions by `positions`.
fn read_mesh_arrays<P>(
    value: &JsValue,
    positions: impl FnOnce(&JsValue) -> Result<P, Error>,
) -> Result<(P, Vec<u32>, Vec<u32>), Error> {
    if !value.is_object() || is_array(value) {
        return Err(mesh_error(format!(
            "mesh must be an object {{ positions: Float32Array, indices: Uint32Array, \
             faceSizes?: Uint32Array }}, got {}",
            describe(value)
        )));
    }
    check_keys(value, &MESH_KEYS, &IGNORED_MESH_KEYS, "mesh field", "mesh fields")
        .map_err(mesh_error)?;

    let positions_value = get(value, "positions")?;
    let positions = match typed_array_kind(&positions_value).as_deref() {
        Some("Float32Array") => positions(&positions_value)?,
        _ => return Err(wrong_array_type("positions", "Float32Array", &positions_value)),
    };
    let indices = get(value, "indices")?;
    let indices = match typed_array_kind(&indices).as_deref() {
        Some("Uint32Array") => copy_u32(&indices, "indices")?,
        _ => return Err(wrong_array_type("indices", "Uint32Array", &indices)),
    };
    let face_sizes = get(value, "faceSizes")?;
    let face_sizes = if face_sizes.is_undefined() || face_sizes.is_null() {
        if indices.len() % 3 != 0 {
            return Err(mesh_error(format!(
                "mesh.indices has {} entries, which is not a multiple of 3; without \
                 mesh.faceSizes every face is a triangle, so give faceSizes for other polygons",
                indices.len()
            )));
        }
        vec![3; indices.len() / 3]
    } else {
        match typed_array_kind(&face_sizes).as_deref() {
            Some("Uint32Array") => copy_u32(&face_sizes, "faceSizes")?,
            _ => return Err(wrong_array_type("faceSizes", "Uint32Array", &face_sizes)),
        }
    };
    Ok((positions, indices, face_sizes))
}

/// The kind of typed array `value` is ("Float32Array", "Uint32Array", ...), or `None`. Decided
/// by the internal slots (`ArrayBuffer.isView`, the `%TypedArray%` tag getter), not by
/// `instanceof`: arrays from another realm (an iframe) count, and a Proxy, whose traps could
/// throw through this code, is never a view.
fn typed_array_kind(value: &JsValue) -> Option<String> {
    if !js_sys::ArrayBuffer::is_view(value) {
        return None;
    }
    Reflect::get(value, &js_sys::Symbol::to_string_tag()).ok()?.as_string()
}

/// The `%TypedArray%.prototype` getters and methods the copies use, rather than whatever the
/// caller's arrays inherit or shadow: no caller code runs while an array is sized, checked and
/// written. Looked up once per module instance.
struct Intrinsics {
    length: js_sys::Function,
    buffer: js_sys::Function,
    set: js_sys::Function,
    fill: js_sys::Function,
}

thread_local! {
    static INTRINSICS: std::cell::RefCell<Option<std::rc::Rc<Intrinsics>>> = Default::default();
}

fn intrinsics() -> Result<std::rc::Rc<Intrinsics>, JsValue> {
    if let Some(found) = INTRINSICS.with(|cell| cell.borrow().clone()) {
        return Ok(found);
    }
    let prototype =
        Object::get_prototype_of(&Object::get_prototype_of(&Uint32Array::new_with_length(0)));
    let getter = |key: &str| -> Result<js_sys::Function, JsValue> {
        let descriptor = Reflect::get_own_property_descriptor(&prototype, &JsValue::from_str(key))?;
        Reflect::get(&descriptor, &JsValue::from_str("get"))?.dyn_into()
    };
    let method = |key: &str| -> Result<js_sys::Function, JsValue> {
        Reflect::get(&prototype, &JsValue::from_str(key))?.dyn_into()
    };
    let found = std::rc::Rc::new(Intrinsics {
        length: getter("length")?,
        buffer: getter("buffer")?,
        set: method("set")?,
        fill: method("fill")?,
    });
    INTRINSICS.with(|cell| *cell.borrow_mut() = Some(found.clone()));
    Ok(found)
}

/// The element count of a typed array, from the `%TypedArray%.prototype.length` getter itself:
/// a `length` the caller shadowed never runs.
fn typed_array_length(source: &JsValue, field: &str) -> Result<u32, Error> {
    let length =
        intrinsics().and_then(|i| i.length.call0(source)).map_err(|e| copy_threw(field, e))?;
    Ok(length.as_f64().unwrap_or_default() as u32)
}

fn copy_threw(field: &str, e: JsValue) -> Error {
    mesh_error(format!("copying mesh.{field} threw {}", describe(&e)))
}

/// Copies the caller's typed array of `length` elements (from [`typed_array_length`]) straight
/// into wasm memory, `per_item` elements to an item of the result, by
/// `%TypedArray%.prototype.set` on a view of our own, which reads the source through its
/// internal slots. No code of the caller's runs between sizing and copying, so the length cannot
/// change in between; a detached source is an error; and no intermediate JS copy is made (a
/// fresh one cost 20 ms of page faults for a 1M-quad mesh).
fn copy_in<T: Default + Clone>(
    source: &JsValue,
    field: &str,
    (length, per_item): (u32, u32),
    view: impl Fn(&JsValue, u32, u32) -> JsValue,
) -> Result<Vec<T>, Error> {
    let mut out = zeroed(length / per_item, length, field)?;
    // The view is made after the allocation, which may grow (and so detach) the memory's
    // buffer. JS writes `out` through it as `copy_to` would; nothing else holds `out`.
    let target = view(&memory_buffer(), out.as_mut_ptr() as u32, length);
    intrinsics().and_then(|i| i.set.call1(&target, source)).map_err(|e| copy_threw(field, e))?;
    Ok(out)
}

/// The module's memory as it is now (growing it replaces the buffer).
fn memory_buffer() -> JsValue {
    wasm_bindgen::memory().unchecked_into::<js_sys::WebAssembly::Memory>().buffer()
}

fn float32_view(buffer: &JsValue, offset: u32, len: u32) -> JsValue {
    Float32Array::new_with_byte_offset_and_length(buffer, offset, len).into()
}

fn copy_f32(source: &JsValue, field: &str) -> Result<Vec<f32>, Error> {
    copy_in(source, field, (typed_array_length(source, field)?, 1), float32_view)
}

/// The positions as `[x, y, z]` per vertex, in one copy.
fn copy_vertices(source: &JsValue) -> Result<Vec<[f32; 3]>, Error> {
    let length = typed_array_length(source, "positions")?;
    if !length.is_multiple_of(3) {
        return Err(crate::mesh::positions_not_in_threes(length as usize));
    }
    copy_in(source, "positions", (length, 3), float32_view)
}

fn copy_u32(source: &JsValue, field: &str) -> Result<Vec<u32>, Error> {
    copy_in(source, field, (typed_array_length(source, field)?, 1), |buffer, offset, len| {
        Uint32Array::new_with_byte_offset_and_length(buffer, offset, len).into()
    })
}

/// `items` default values; `entries` is the length of the caller's array they stand for.
fn zeroed<T: Default + Clone>(items: u32, entries: u32, field: &str) -> Result<Vec<T>, Error> {
    let mut out = Vec::new();
    out.try_reserve_exact(items as usize).map_err(|_| {
        Error::TooLarge(format!(
            "mesh.{field} has {entries} entries, more than the WebAssembly memory can hold"
        ))
    })?;
    out.resize(items as usize, T::default());
    Ok(out)
}

fn get(object: &JsValue, key: &str) -> Result<JsValue, Error> {
    Reflect::get(object, &JsValue::from_str(key))
        .map_err(|e| mesh_error(format!("reading mesh.{key} threw {}", describe(&e))))
}

fn wrong_array_type(field: &str, expected: &str, got: &JsValue) -> Error {
    if got.is_undefined() {
        return mesh_error(format!("mesh.{field} is missing; it must be a {expected}"));
    }
    let hint = if is_array(got) || is_typed_array(got) {
        format!("; convert it with new {expected}(array)")
    } else {
        String::new()
    };
    mesh_error(format!("mesh.{field} must be a {expected}, got {}{hint}", describe(got)))
}

fn is_typed_array(value: &JsValue) -> bool {
    typed_array_kind(value).is_some_and(|kind| kind != "DataView")
}

#[wasm_bindgen]
extern "C" {
    /// `Array.isArray`, which throws for a revoked Proxy: `catch` makes that an `Err`.
    #[wasm_bindgen(catch, js_namespace = Array, js_name = isArray)]
    fn checked_is_array(value: &JsValue) -> Result<bool, JsValue>;
}

fn is_array(value: &JsValue) -> bool {
    checked_is_array(value).unwrap_or(false)
}

/// True when `Error.prototype` is on `value`'s prototype chain, walked with
/// `Reflect.getPrototypeOf` (errors, not exceptions) rather than `instanceof`, whose Proxy
/// traps could throw through this code.
fn is_error(value: &JsValue) -> bool {
    let Ok(error_prototype) = Reflect::get_prototype_of(&js_sys::Error::new("").into()) else {
        return false;
    };
    let mut current = value.clone();
    for _ in 0..64 {
        match Reflect::get_prototype_of(&current) {
            Ok(prototype) if prototype.is_null() => return false,
            Ok(prototype) if *prototype == *error_prototype => return true,
            Ok(prototype) => current = prototype.into(),
            Err(_) => return false,
        }
    }
    false
}

/// A plain object of fresh typed arrays (copies, never views of wasm memory).
fn mesh_object(mesh: &PolyMesh) -> JsResult<JsValue> {
    let object = Object::new();
    set_field(&object, "positions", &Float32Array::from(&mesh.positions[..]))?;
    set_field(&object, "indices", &Uint32Array::from(&mesh.indices[..]))?;
    set_field(&object, "faceSizes", &Uint32Array::from(&mesh.face_sizes[..]))?;
    Ok(object.into())
}

/// The arrays an `into` object lends, read before any work so that its getters run first and
/// a wrong `into` fails fast. Whether each can be reused is decided when the result is written.
struct Lent {
    arrays: [JsValue; 4],
}

/// The result's fields, in the order of [`Lent::arrays`], with the typed array each must be.
const RESULT_FIELDS: [(&str, &str); 4] = [
    ("positions", "Float32Array"),
    ("indices", "Uint32Array"),
    ("faceSizes", "Uint32Array"),
    ("triangles", "Uint32Array"),
];

impl Lent {
    fn read(into: &JsValue) -> Result<Lent, Error> {
        let mut arrays: [JsValue; 4] = Default::default();
        if into.is_undefined() || into.is_null() {
            return Ok(Lent { arrays });
        }
        if !into.is_object() || is_array(into) {
            return Err(Error::InvalidOption(format!(
                "into must be a result of an earlier subdivide call, to reuse its arrays, or \
                 undefined; got {}",
                describe(into)
            )));
        }
        for (slot, (key, kind)) in arrays.iter_mut().zip(RESULT_FIELDS) {
            let value = Reflect::get(into, &JsValue::from_str(key)).map_err(|e| {
                Error::InvalidOption(format!("reading into.{key} threw {}", describe(&e)))
            })?;
            if typed_array_kind(&value).as_deref() == Some(kind) {
                *slot = value;
            }
        }
        Ok(Lent { arrays })
    }

    /// Field `i`'s array when it has `len` elements, is not a view of wasm memory (which the
    /// writes would corrupt) and is not lent for a later field too (so an array lent for two
    /// fields serves one at most); else a fresh array. Called once per field, in order.
    fn take(&mut self, i: usize, len: usize, intrinsics: &Intrinsics) -> JsResult<JsValue> {
        let lent = std::mem::take(&mut self.arrays[i]);
        if !lent.is_undefined() {
            let fits =
                intrinsics.length.call0(&lent).ok().and_then(|n| n.as_f64()) == Some(len as f64);
            let ours = intrinsics.buffer.call0(&lent).is_ok_and(|b| b == memory_buffer());
            let again = self.arrays.iter().any(|other| Object::is(other, &lent));
            if fits && !ours && !again {
                return Ok(lent);
            }
        }
        let len = u32::try_from(len).map_err(|_| {
            JsError::new(&format!("the result's {} is too long", RESULT_FIELDS[i].0))
        })?;
        Ok(match RESULT_FIELDS[i].1 {
            "Float32Array" => Float32Array::new_with_length(len).into(),
            _ => Uint32Array::new_with_length(len).into(),
        })
    }
}

/// `subdivide`'s result. The index arrays are copied into JS piece by piece as the result hands
/// them over, so that those it keeps implicit (the faces of a last quad split, and every fan
/// triangulation) are never written whole to wasm memory and read back.
fn refined_object(refined: &Refined, mut lent: Lent) -> JsResult<JsValue> {
    let intrinsics = intrinsics().map_err(|e| JsError::new(&describe(&e)))?;
    let positions = refined.positions();
    let mut out = Output::new(lent.take(0, positions.len(), &intrinsics)?, &intrinsics);
    // SAFETY: the view is used at once, before anything can allocate (and so grow the memory).
    out.push(positions, |chunk| unsafe { Float32Array::view(chunk) }.into());
    let mut indices = Output::new(lent.take(1, refined.num_indices(), &intrinsics)?, &intrinsics);
    let sizes = lent.take(2, refined.num_faces(), &intrinsics)?;
    let triangles = lent.take(3, refined.num_triangle_indices(), &intrinsics)?;
    let mut triangles = Output::new(triangles, &intrinsics);
    refined
        .index_and_triangle_chunks(|c| indices.push(c, u32_view), |c| triangles.push(c, u32_view));
    let mut face_sizes = Output::new(sizes, &intrinsics);
    match refined.uniform_face_size() {
        Some(n) => face_sizes.fill(n),
        None => refined.face_size_chunks(|c| face_sizes.push(c, u32_view)),
    }
    let object = Object::new();
    set_field(&object, "positions", &out.finish()?)?;
    set_field(&object, "indices", &indices.finish()?)?;
    set_field(&object, "faceSizes", &face_sizes.finish()?)?;
    set_field(&object, "triangles", &triangles.finish()?)?;
    if !refined.attributes().is_empty() {
        let channels = Object::new();
        for a in refined.attributes() {
            let channel = Object::new();
            set_field(&channel, "array", &Float32Array::from(&a.values[..]))?;
            set_field(&channel, "itemSize", &JsValue::from(a.item_size as u32))?;
            if let Some(indices) = &a.indices {
                set_field(&channel, "indices", &Uint32Array::from(&indices[..]))?;
            }
            set_field(&channels, &a.name, &channel)?;
        }
        set_field(&object, "attributes", &channels)?;
    }
    Ok(object.into())
}

fn u32_view(chunk: &[u32]) -> JsValue {
    // SAFETY: as for the positions in `refined_object`: used before anything allocates.
    unsafe { Uint32Array::view(chunk) }.into()
}

/// A JS typed array of the length needed, filled from consecutive pieces through the
/// intrinsic `set` (the array may be the caller's, from `into`). The first failure is kept for
/// [`Output::finish`] and stops the writes.
struct Output<'i> {
    array: JsValue,
    at: u32,
    intrinsics: &'i Intrinsics,
    failed: Option<JsValue>,
}

impl<'i> Output<'i> {
    fn new(array: JsValue, intrinsics: &'i Intrinsics) -> Self {
        Output { array, at: 0, intrinsics, failed: None }
    }

    /// Writes `chunk` after the pieces before it; `set` itself refuses to write past the end.
    fn push<T>(&mut self, chunk: &[T], view: impl Fn(&[T]) -> JsValue) {
        if self.failed.is_none() {
            let at = JsValue::from(self.at);
            self.failed = self.intrinsics.set.call2(&self.array, &view(chunk), &at).err();
            self.at += chunk.len() as u32;
        }
    }

    fn fill(&mut self, value: u32) {
        self.failed = self.intrinsics.fill.call1(&self.array, &JsValue::from(value)).err();
    }

    fn finish(self) -> JsResult<JsValue> {
        match self.failed {
            None => Ok(self.array),
            Some(e) => Err(JsError::new(&format!("writing the result threw {}", describe(&e)))),
        }
    }
}

fn set_field(object: &JsValue, key: &str, value: &JsValue) -> JsResult<()> {
    Reflect::set(object, &JsValue::from_str(key), value)
        .map(|_| ())
        .map_err(|_| JsError::new(&format!("could not set result field {key}")))
}

// ---------------------------------------------------------------------------------------------
// Messages

/// Rejects own string keys of `object` outside `allowed` and `ignored`, naming the closest
/// allowed one when it looks like a typo.
fn check_keys(
    object: &JsValue,
    allowed: &[&str],
    ignored: &[&str],
    what: &str,
    what_plural: &str,
) -> Result<(), String> {
    let keys = Reflect::own_keys(object)
        .map_err(|e| format!("listing the {what_plural} threw {}", describe(&e)))?;
    for key in keys.iter() {
        let Some(key) = key.as_string() else { continue };
        if allowed.contains(&key.as_str()) || ignored.contains(&key.as_str()) {
            continue;
        }
        let suggestion =
            closest(&key, allowed).map(|k| format!(" (did you mean '{k}'?)")).unwrap_or_default();
        return Err(format!(
            "unknown {what} '{key}'{suggestion}; allowed {what_plural} are {}",
            quoted_list(allowed.iter().copied())
        ));
    }
    Ok(())
}

/// The allowed key within edit distance 2 of `key`, ignoring case, if there is one.
fn closest<'a>(key: &str, allowed: &[&'a str]) -> Option<&'a str> {
    let key = key.to_lowercase();
    allowed
        .iter()
        .map(|&a| (edit_distance(&key, &a.to_lowercase()), a))
        .filter(|&(d, _)| d <= 2)
        .min_by_key(|&(d, _)| d)
        .map(|(_, a)| a)
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitute = diagonal + usize::from(ca != cb);
            diagonal = row[j + 1];
            row[j + 1] = substitute.min(row[j] + 1).min(diagonal + 1);
        }
    }
    row[b.len()]
}

fn quoted_list<'a>(names: impl Iterator<Item = &'a str>) -> String {
    names.map(|n| format!("'{n}'")).collect::<Vec<_>>().join(", ")
}

/// A short description of a JS value for error messages: `undefined`, `-1`, `string '2'`,
/// `Float32Array`, `Array`, `object`.
fn describe(value: &JsValue) -> String {
    if value.is_undefined() {
        return "undefined".into();
    }
    if value.is_null() {
        return "null".into();
    }
    if let Some(b) = value.as_bool() {
        return format!("boolean {b}");
    }
    if let Some(x) = value.as_f64() {
        return if x.is_nan() {
            "NaN".into()
        } else if x.is_infinite() {
            if x > 0.0 { "Infinity" } else { "-Infinity" }.into()
        } else {
            format!("{x}")
        };
    }
    if let Some(s) = value.as_string() {
        let shown: String = s.chars().take(40).collect();
        let ellipsis = if shown.len() < s.len() { "..." } else { "" };
        return format!("string '{shown}{ellipsis}'");
    }
    if value.is_bigint() {
        return "bigint".into();
    }
    if value.is_symbol() {
        return "symbol".into();
    }
    if value.is_function() {
        return "function".into();
    }
    if is_error(value) {
        let message = Reflect::get(value, &JsValue::from_str("message")).ok();
        return format!("Error '{}'", message.and_then(|m| m.as_string()).unwrap_or_default());
    }
    constructor_name(value).unwrap_or_else(|| "object".into())
}

fn constructor_name(value: &JsValue) -> Option<String> {
    let constructor = Reflect::get(value, &JsValue::from_str("constructor")).ok()?;
    if !constructor.is_function() {
        return None;
    }
    Reflect::get(&constructor, &JsValue::from_str("name"))
        .ok()?
        .as_string()
        .filter(|name| !name.is_empty())
}

#[cfg(test)]
mod tests {
    use super::*;
    use wasm_bindgen_test::wasm_bindgen_test;

    fn union(names: impl Iterator<Item = &'static str>) -> String {
        names.map(|n| format!("'{n}'")).collect::<Vec<_>>().join(" | ")
    }

    /// The TypeScript section is hand-written; it must name exactly the library's schemes and
    /// boundary rules, in the library's order.
    #[wasm_bindgen_test]
    fn typescript_names_match_the_library() {
        // Compared with whitespace collapsed, so the section may wrap its lines freely.
        let types = TYPESCRIPT_TYPES.split_whitespace().collect::<Vec<_>>().join(" ");
        let schemes =
            format!("export type SchemeName = {};", union(Scheme::ALL.iter().map(|s| s.name())));
        let boundaries = format!(
            "export type BoundaryRule = {};",
            union(Boundary::ALL.iter().map(|b| b.name()))
        );
        let defaults = [
            format!("from 0 to {MAX_LEVELS}."),
            format!("Default {}.", crate::scheme::DEFAULT_MAX_FACES),
            format!("Default '{}'.", Scheme::default().name()),
            format!("Default '{}'.", Boundary::default().name()),
        ];
        let keys = OPTION_KEYS.map(|key| format!(" {key}?: "));
        for text in [schemes, boundaries].iter().chain(&defaults).chain(&keys) {
            assert!(types.contains(text.as_str()), "TypeScript section should contain {text:?}");
        }
    }

    /// The keys [`obj_tags_object`] may write. `readObj`'s tags are spread into `subdivide`'s
    /// options, so every key must be an option, and `ObjTags` must declare each of them.
    const OBJ_TAG_KEYS: [&str; 6] =
        ["creases", "corners", "holes", "boundary", "creaseMethod", "smoothTriangles"];

    #[wasm_bindgen_test]
    fn obj_tag_keys_are_option_keys() {
        let types = TYPESCRIPT_TYPES.split_whitespace().collect::<Vec<_>>().join(" ");
        let (start, end) = (
            types.find("export interface ObjTags {").expect("ObjTags in the TypeScript section"),
            types.find("export interface ObjMesh ").expect("ObjMesh in the TypeScript section"),
        );
        for key in OBJ_TAG_KEYS {
            assert!(OPTION_KEYS.contains(&key), "{key} is not an option");
            assert!(types[start..end].contains(&format!(" {key}")), "ObjTags should declare {key}");
        }
        let boundaries = ["none", "edge-and-corner", "edge-only"];
        for name in boundaries {
            assert!(Boundary::ALL.iter().any(|b| b.name() == name), "{name} is a boundary rule");
        }
    }

    #[wasm_bindgen_test]
    fn typo_suggestions() {
        assert_eq!(closest("level", &OPTION_KEYS), Some("levels"));
        assert_eq!(closest("MaxFaces", &OPTION_KEYS), Some("maxFaces"));
        assert_eq!(closest("face_sizes", &MESH_KEYS), Some("faceSizes"));
        assert_eq!(closest("normals", &MESH_KEYS), None);
        assert_eq!(closest("faceSize", &MESH_KEYS), Some("faceSizes"));
        assert_eq!(edit_distance("kitten", "sitting"), 3);
    }
}
