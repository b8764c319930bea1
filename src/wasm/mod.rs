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
use crate::evaluator::closed_call;
use crate::io;
use crate::mesh::{HalfEdgeMesh, PolyMesh};
use crate::scheme::{self, Boundary, FVarLinear, Options, Progress, Refined, Scheme};
use crate::tags::{Corner, Crease, CreaseMethod, Tags};
use js_sys::{Array, Float32Array, Function, Object, Reflect, Uint32Array};
use std::ops::ControlFlow;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

mod evaluator;
mod input;
mod messages;
mod options;
mod output;
mod triangles;
mod viewer;

pub use evaluator::Evaluator;
use input::*;
use messages::*;
use options::*;
use output::*;
pub use triangles::*;
pub use viewer::*;

// The macro consumes the item it marks, so the text lives in its own constant that the unit test
// below can also read.
#[wasm_bindgen(typescript_custom_section)]
const TYPESCRIPT_SECTION: &'static str = TYPESCRIPT_TYPES;

/// The interfaces of the JS API, added to `subsurf.d.ts`.
// The macro's expansion reads this in a way the dead-code lint does not see.
#[allow(dead_code)]
const TYPESCRIPT_TYPES: &str = include_str!("../../js/types.d.ts");

/// Option keys, in the order error messages list them. Must match what [`read_options`] reads.
const OPTION_KEYS: [&str; 14] = [
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
    "fvarLinear",
    "limit",
    "normals",
    "onProgress",
];

/// Mesh fields read from the input object.
const MESH_KEYS: [&str; 4] = ["positions", "indices", "faceSizes", "attributes"];

/// Fields of one attribute channel.
const CHANNEL_KEYS: [&str; 3] = ["array", "itemSize", "indices"];

/// Mesh fields accepted and ignored: the extra output of `subdivide`, `readObj` and
/// `toDrawable`, and its normals.
const IGNORED_MESH_KEYS: [&str; 4] = ["triangles", "tags", "origins", "normals"];

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
///
/// `options.onProgress`, a function, is called after each level with `{ level, levels, faces,
/// vertices }`; whatever it throws stops the call and is thrown by `subdivide`.
#[wasm_bindgen(js_name = subdivide, unchecked_return_type = "SubdivideResult")]
pub fn subdivide(
    #[wasm_bindgen(unchecked_param_type = "SubdivideMesh")] mesh: &JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "SubdivideOptions")] options: &JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "SubdivideResult")] into: &JsValue,
) -> Result<JsValue, JsValue> {
    let (parsed, tags) = read_options(options).map_err(js_error)?;
    let on_progress = read_on_progress(options).map_err(js_error)?;
    let lent = Lent::read(into).map_err(js_error)?;
    let base = read_half_edge_mesh(mesh).map_err(js_error)?;
    let attributes = read_attributes(mesh).map_err(js_error)?;
    if let Some(refined) = closed(&base, &attributes, &parsed, &tags, on_progress.clone())? {
        return Ok(refined_object(&refined, lent)?);
    }
    let refined = with_progress(on_progress, |progress| match progress {
        None => scheme::subdivide_mesh_refined_with(base, &attributes, &parsed, &tags),
        Some(progress) => scheme::subdivide_mesh_refined_with_progress(
            base,
            &attributes,
            &parsed,
            &tags,
            progress,
        ),
    })?;
    Ok(refined_object(&refined, lent)?)
}

/// The call by the closed forms where they give every point (`evaluator::subdivide_closed`),
/// telling `on_progress` as the masks' call would; `None` leaves the call to the masks.
fn closed<'a>(
    base: &'a HalfEdgeMesh,
    attributes: &[Attribute],
    options: &Options,
    tags: &crate::tags::Tags,
    on_progress: Option<Function>,
) -> Result<Option<Refined<'a>>, JsValue> {
    with_progress(on_progress, |progress| closed_call(base, attributes, options, tags, progress))
}

/// Runs `call` with a progress callback that calls the JS function `on_progress`, if any. What
/// the function throws stops the call (`ControlFlow::Break`) and is thrown as it is, so that
/// the caller sees its own exception rather than a message of ours.
fn with_progress<T>(
    on_progress: Option<Function>,
    call: impl FnOnce(Option<&mut scheme::OnProgress<'_>>) -> Result<T, crate::error::Error>,
) -> Result<T, JsValue> {
    let Some(function) = on_progress else {
        return call(None).map_err(|e| js_error(e).into());
    };
    let mut thrown = None;
    let mut tell = |p: Progress| match progress_object(p)
        .and_then(|object| function.call1(&JsValue::UNDEFINED, &object))
    {
        Ok(_) => ControlFlow::Continue(()),
        Err(exception) => {
            thrown = Some(exception);
            ControlFlow::Break(())
        }
    };
    let result = call(Some(&mut tell));
    match (result, thrown) {
        (_, Some(exception)) => Err(exception),
        (result, None) => result.map_err(|e| js_error(e).into()),
    }
}

/// `SubdivideProgress`: `{ level, levels, faces, vertices }`.
fn progress_object(p: Progress) -> Result<JsValue, JsValue> {
    let object = Object::new();
    for (key, value) in
        [("level", p.level), ("levels", p.levels), ("faces", p.faces), ("vertices", p.vertices)]
    {
        set_field(&object, key, &JsValue::from_f64(value as f64))?;
    }
    Ok(object.into())
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
    /// Shared with the evaluators made from it, which keep it for their tables on first use;
    /// `setPositions` copies it once if one still holds it.
    mesh: std::sync::Arc<HalfEdgeMesh>,
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
        Ok(BaseMesh { mesh: std::sync::Arc::new(base), attributes })
    }

    /// `subdivide(mesh, options, into)` for this mesh, which stays as it is.
    #[wasm_bindgen(unchecked_return_type = "SubdivideResult")]
    pub fn subdivide(
        &self,
        #[wasm_bindgen(unchecked_optional_param_type = "SubdivideOptions")] options: &JsValue,
        #[wasm_bindgen(unchecked_optional_param_type = "SubdivideResult")] into: &JsValue,
    ) -> Result<JsValue, JsValue> {
        let (parsed, tags) = read_options(options).map_err(js_error)?;
        let on_progress = read_on_progress(options).map_err(js_error)?;
        let lent = Lent::read(into).map_err(js_error)?;
        let (mesh, attributes) = (&self.mesh, &self.attributes);
        if let Some(refined) = closed(mesh, attributes, &parsed, &tags, on_progress.clone())? {
            return Ok(refined_object(&refined, lent)?);
        }
        let refined = with_progress(on_progress, |progress| match progress {
            None => scheme::subdivide_mesh_borrowed_with(mesh, attributes, &parsed, &tags),
            Some(progress) => scheme::subdivide_mesh_borrowed_with_progress(
                mesh, attributes, &parsed, &tags, progress,
            ),
        })?;
        Ok(refined_object(&refined, lent)?)
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
        std::sync::Arc::make_mut(&mut self.mesh).set_positions(positions).map_err(js_error)
    }

    /// Replaces the values of the channel `name` (given to the constructor in `mesh.attributes`):
    /// `itemSize` floats per value, all finite; one value per vertex for a vertex-varying
    /// channel. A face-varying channel keeps its `indices`, so the new array needs a value for
    /// every index they use (to change the indices, build a new `BaseMesh`). Throws, and leaves
    /// the channel as it was, otherwise.
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
        let field = format!("attributes.{name}.array");
        if typed_array_kind(array).as_deref() != Some("Float32Array") {
            return Err(js_error(wrong_array_type(&field, "Float32Array", array)));
        }
        let values = copy_f32(array, &field).map_err(js_error)?;
        let channel = Attribute { values, ..self.attributes[i].clone() };
        let vertices = self.mesh.num_vertices();
        attributes::validate(std::slice::from_ref(&channel), vertices, self.mesh.num_half_edges())
            .map_err(js_error)?;
        self.attributes[i] = channel;
        Ok(())
    }

    /// An evaluator for `options` (levels, scheme, tags, `limit`, `normals`): this mesh refined
    /// once, its stencils recorded, so that `evaluator.evaluate(positions)` gives
    /// `subdivide`'s positions (and normals) for new positions of the same faces without
    /// refining again. The evaluator owns what it needs: it stays usable after this mesh is
    /// changed or freed. Throws what `subdivide` would throw for the same options, and when the
    /// stencil table would pass `maxBytes`.
    pub fn evaluator(
        &self,
        #[wasm_bindgen(unchecked_optional_param_type = "SubdivideOptions")] options: &JsValue,
    ) -> JsResult<Evaluator> {
        let (options, tags) = read_options(options).map_err(js_error)?;
        Evaluator::build(&self.mesh, &self.attributes, &options, &tags)
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

/// Parses the text of a Wavefront OBJ file: `v` and `f` lines; `vt` lines and the corners' `vt`
/// indices as the face-varying channel `attributes.uv` (when the faces give them); and
/// OpenSubdiv's `t` tag lines (`crease`, `corner`, `hole`, `interpolateboundary`,
/// `creasemethod`, `smoothtriangles`) as `tags`, in the shapes `subdivide`'s options take.
/// Everything else is skipped. A malformed line, tag and `vt` lines included, and faces that
/// give `vt` indices on some corners but not others, throw an `Error` naming the line.
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
    if !obj.attributes.is_empty() {
        set_field(&object, "attributes", &channels_object(&obj.attributes)?)?;
    }
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

/// Writes a polygon mesh as Wavefront OBJ text (`v` and `f` lines, 1-based indices). A channel
/// `mesh.attributes.uv` (itemSize 1 to 3) is written as `vt` lines and `f v/vt` corners:
/// face-varying, each corner with its own value; vertex-varying, each vertex's. Other channels
/// have no place in OBJ and are left out.
#[wasm_bindgen(js_name = writeObj)]
pub fn write_obj(
    #[wasm_bindgen(unchecked_param_type = "SubdivideMesh")] mesh: &JsValue,
) -> JsResult<String> {
    let poly = read_mesh(mesh).map_err(js_error)?;
    // The library's mesh builder is the one place that knows what a valid mesh is; running it
    // here keeps a bad index from turning into an OBJ file no reader accepts.
    HalfEdgeMesh::from_poly(&poly).map_err(js_error)?;
    let attributes = read_attributes(mesh).map_err(js_error)?;
    attributes::validate(&attributes, poly.num_vertices(), poly.indices.len()).map_err(js_error)?;
    io::write_obj_with(&poly, &attributes).map_err(js_error)
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

/// The names `options.fvarLinear` accepts, from smoothest to most linear (the default is
/// 'corners-plus1').
#[wasm_bindgen(js_name = fvarLinearModes, unchecked_return_type = "FVarLinearMode[]")]
pub fn fvar_linear_modes() -> Array {
    FVarLinear::ALL.iter().map(|m| JsValue::from_str(m.name())).collect()
}

/// The version of the subsurf package.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
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
            format!("Default '{}'.", FVarLinear::default().name()),
        ];
        let modes = format!(
            "export type FVarLinearMode = {};",
            union(FVarLinear::ALL.iter().map(|m| m.name()))
        );
        let keys = OPTION_KEYS.map(|key| format!(" {key}?: "));
        for text in [schemes, boundaries, modes].iter().chain(&defaults).chain(&keys) {
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
