//! `Evaluator`: the JS face of [`crate::evaluator::Evaluator`] (refine once, evaluate every
//! frame). Conversion and errors only.

use super::*;
use crate::evaluator;
use crate::stencil::StencilTable;

/// A subdivision prepared for many frames: made by `BaseMesh.evaluator(options)`.
///
/// ```js
/// const evaluator = base.evaluator({ levels: 2, limit: true, normals: true });
/// const { indices, triangles } = evaluator.result();   // the topology, once
/// let frame;
/// // every frame:
/// frame = evaluator.evaluate(skinnedPositions, frame);  // { positions, normals }
/// ```
#[wasm_bindgen]
pub struct Evaluator {
    inner: evaluator::Evaluator,
    /// Scratch for the control positions and the outputs, kept between frames.
    control: Vec<f32>,
    positions: Vec<f32>,
    normals: Vec<f32>,
}

impl Evaluator {
    pub(super) fn build(
        mesh: &std::sync::Arc<HalfEdgeMesh>,
        attributes: &[Attribute],
        options: &Options,
        tags: &Tags,
    ) -> JsResult<Evaluator> {
        let inner =
            evaluator::Evaluator::new_shared(mesh, attributes, options, tags).map_err(js_error)?;
        Ok(Evaluator { inner, control: Vec::new(), positions: Vec::new(), normals: Vec::new() })
    }

    /// Evaluates the frame of control `positions` into the output buffers; errors name `call`.
    fn frame(&mut self, positions: &JsValue, call: &str) -> JsResult<()> {
        let field = format!("{call}: positions");
        read_f32_into(positions, &field, &mut self.control).map_err(js_error)?;
        let outputs = 3 * self.inner.num_vertices();
        self.positions.resize(outputs, 0.0);
        let normals = if self.inner.has_normals() {
            self.normals.resize(outputs, 0.0);
            Some(&mut self.normals[..])
        } else {
            None
        };
        // The core's messages name `evaluate`, the Rust call.
        self.inner.evaluate(&self.control, &mut self.positions, normals).map_err(|e| match e {
            Error::InvalidAttribute(message) => js_error(Error::InvalidAttribute(
                message.replacen("evaluate:", &format!("{call}:"), 1),
            )),
            other => js_error(other),
        })
    }
}

/// `array` when it is a Float32Array of `len` elements that is not a view of wasm memory, else
/// a fresh one; filled with `values`.
fn lend_or_new(array: &JsValue, values: &[f32]) -> Float32Array {
    if let Some(lent) = array.dyn_ref::<Float32Array>() {
        if lent.length() as usize == values.len() && JsValue::from(lent.buffer()) != memory_buffer()
        {
            lent.copy_from(values);
            return lent.clone();
        }
    }
    Float32Array::from(values)
}

/// A stencil table as `{ offsets, indices, weights, tangentWeights?, numControlVertices }`.
fn table_object(table: &StencilTable) -> JsResult<JsValue> {
    let object = Object::new();
    set_field(&object, "offsets", &Uint32Array::from(table.offsets()))?;
    set_field(&object, "indices", &Uint32Array::from(table.indices()))?;
    set_field(&object, "weights", &Float32Array::from(table.weights()))?;
    if let Some([first, second]) = table.tangent_weights() {
        let pair = Array::of2(&Float32Array::from(first), &Float32Array::from(second));
        set_field(&object, "tangentWeights", &pair)?;
    }
    let controls = JsValue::from(table.num_control_vertices() as u32);
    set_field(&object, "numControlVertices", &controls)?;
    Ok(object.into())
}

/// A Float32Array argument copied into `out`, or an error naming `field`.
fn read_f32_into(value: &JsValue, field: &str, out: &mut Vec<f32>) -> Result<(), Error> {
    let Some(array) = value.dyn_ref::<Float32Array>() else {
        let hint = if is_array(value) || is_typed_array(value) {
            "; convert it with new Float32Array(array)"
        } else {
            ""
        };
        return Err(Error::InvalidAttribute(format!(
            "{field} must be a Float32Array, got {}{hint}",
            describe(value)
        )));
    };
    out.resize(array.length() as usize, 0.0);
    array.copy_to(out);
    Ok(())
}

#[wasm_bindgen]
impl Evaluator {
    /// Number of vertices of the mesh it was built from (`evaluate` takes 3 floats each).
    #[wasm_bindgen(getter, js_name = numControlVertices)]
    pub fn num_control_vertices(&self) -> u32 {
        self.inner.num_control_vertices() as u32
    }

    /// Number of output vertices (stencils).
    #[wasm_bindgen(getter, js_name = numVertices)]
    pub fn num_vertices(&self) -> u32 {
        self.inner.num_vertices() as u32
    }

    /// True when `evaluate` gives normals (`normals: true` at build time).
    #[wasm_bindgen(getter, js_name = hasNormals)]
    pub fn has_normals(&self) -> bool {
        self.inner.has_normals()
    }

    /// What `subdivide` returns for the positions at build time: positions, indices, faceSizes,
    /// triangles, attributes (face-varying ones fixed from then on) and normals. Fresh arrays;
    /// the points (to f32 rounding) and normals are the table's, evaluated on the first call.
    #[wasm_bindgen(unchecked_return_type = "SubdivideResult")]
    pub fn result(&self) -> JsResult<JsValue> {
        let inner = &self.inner;
        let object = Object::new();
        set_field(&object, "positions", &Float32Array::from(inner.positions()))?;
        set_field(&object, "indices", &Uint32Array::from(inner.indices()))?;
        set_field(&object, "faceSizes", &Uint32Array::from(inner.face_sizes()))?;
        set_field(&object, "triangles", &Uint32Array::from(&inner.triangles()[..]))?;
        if let Some(normals) = self.inner.normals() {
            set_field(&object, "normals", &Float32Array::from(normals))?;
        }
        if !self.inner.attributes().is_empty() {
            set_field(&object, "attributes", &channels_object(self.inner.attributes())?)?;
        }
        Ok(object.into())
    }

    /// The stencil table as fresh typed arrays, for a shader of your own: output vertex `i` is
    /// the sum over `k` from `offsets[i]` to `offsets[i + 1]` of `weights[k]` times control
    /// vertex `indices[k]`; with normals, `tangentWeights` are the two limit tangents' weights
    /// on the same entries (the normal is their cross product, normalised).
    #[wasm_bindgen(unchecked_return_type = "StencilArrays")]
    pub fn stencils(&self) -> JsResult<JsValue> {
        table_object(self.inner.table().map_err(js_error)?)
    }

    /// Whether the stencil table of `stencils()` is made: with the evaluator, or since it was
    /// first asked for (evaluators whose closed forms give every point leave it out until
    /// then). `createGpuEvaluator` uploads `levelStencils()` where it is not made and the
    /// evaluator has no normals, this table otherwise.
    #[wasm_bindgen(getter, js_name = hasStencilTable)]
    pub fn has_stencil_table(&self) -> bool {
        self.inner.has_table()
    }

    /// The stencils level by level, as fresh typed arrays (OpenSubdiv's stencil tables with
    /// `factorizeIntermediateLevels` off): each table as `stencils()` gives it, table `k`'s
    /// control vertices being the outputs of table `k - 1` (the first's, the base mesh's
    /// vertices), the last's outputs the evaluator's. Where the limit's masks run (`limit`,
    /// or `normals` of Catmull-Clark and Loop), the last table holds them, on the last level's
    /// points. Their rows are not composed: a fraction of `stencils()`'s build and bytes, for
    /// one GPU pass per table (what `createGpuEvaluator` runs for an evaluator without normals
    /// that left its composed table out).
    #[wasm_bindgen(js_name = levelStencils, unchecked_return_type = "StencilArrays[]")]
    pub fn level_stencils(&self) -> JsResult<JsValue> {
        let tables = self.inner.level_tables().map_err(js_error)?;
        let list = Array::new();
        for table in &tables {
            list.push(&table_object(table)?);
        }
        Ok(list.into())
    }

    /// Bytes of the stencil table (4 per offset, 8 per entry, 16 with tangent weights); an
    /// evaluator that left its table out (see `bytes`) makes it here, as `stencils()` does.
    #[wasm_bindgen(getter, js_name = stencilBytes)]
    pub fn stencil_bytes(&self) -> JsResult<f64> {
        Ok(self.inner.table().map_err(js_error)?.bytes() as f64)
    }

    /// Bytes of everything a frame reads besides its input: the stencil table when frames read
    /// it, and the closed forms' data (the levels' topology, the points each reads). An
    /// evaluator whose closed forms give every point (see `stencilBytes`) counts no table.
    #[wasm_bindgen(getter)]
    pub fn bytes(&self) -> f64 {
        self.inner.bytes() as f64
    }

    /// The output for new control `positions` (a Float32Array, x, y, z per vertex of the mesh
    /// it was built from, all finite): `{ positions, normals? }`, equal to `subdivide`'s with
    /// the same options. `into`, an earlier frame, lends its arrays (written over when their
    /// lengths fit). Throws, leaving `into` as it was, on a wrong type, length or a non-finite
    /// value.
    #[wasm_bindgen(unchecked_return_type = "EvaluatedFrame")]
    pub fn evaluate(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] positions: &JsValue,
        #[wasm_bindgen(unchecked_optional_param_type = "EvaluatedFrame")] into: &JsValue,
    ) -> JsResult<JsValue> {
        self.frame(positions, "evaluate")?;
        let lent = |key: &str| -> JsValue {
            if into.is_object() {
                Reflect::get(into, &JsValue::from_str(key)).unwrap_or(JsValue::UNDEFINED)
            } else {
                JsValue::UNDEFINED
            }
        };
        let object = Object::new();
        set_field(&object, "positions", &lend_or_new(&lent("positions"), &self.positions))?;
        if self.inner.has_normals() {
            set_field(&object, "normals", &lend_or_new(&lent("normals"), &self.normals))?;
        }
        Ok(object.into())
    }

    /// `evaluate` without the copy out: the frame's arrays are views of the evaluator's own
    /// output in the module's memory, for `gl.bufferSubData` or `queue.writeBuffer` to read
    /// straight from. They hold this frame until the evaluator's next `evaluate` or
    /// `evaluateView`, and go empty (length 0) when any call makes the module's memory grow;
    /// never write into them, nor read them after the evaluator's `free()`. Why: the copy out
    /// of the module is about 2 ns of a limit frame's 15 to 18 per point.
    #[wasm_bindgen(js_name = evaluateView, unchecked_return_type = "EvaluatedFrame")]
    pub fn evaluate_view(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] positions: &JsValue,
    ) -> JsResult<JsValue> {
        self.frame(positions, "evaluateView")?;
        let object = Object::new();
        // SAFETY: the views are of `self`'s output buffers, which keep their place until the
        // next frame resizes them to the same length; the JS side is told above how long the
        // views hold and that they are read-only.
        set_field(
            &object,
            "positions",
            &JsValue::from(unsafe { Float32Array::view(&self.positions) }),
        )?;
        if self.inner.has_normals() {
            set_field(
                &object,
                "normals",
                &JsValue::from(unsafe { Float32Array::view(&self.normals) }),
            )?;
        }
        Ok(object.into())
    }

    /// Vertex-varying data through the same stencils (colours, skin weights, a morph target):
    /// `values` holds `itemSize` floats per control vertex; returns `itemSize` per output
    /// vertex, into `into` when it is a Float32Array of that length.
    #[wasm_bindgen(js_name = evaluateAttribute)]
    pub fn evaluate_attribute(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] values: &JsValue,
        #[wasm_bindgen(js_name = itemSize)] item_size: u32,
        #[wasm_bindgen(unchecked_optional_param_type = "Float32Array")] into: &JsValue,
    ) -> JsResult<Float32Array> {
        let mut input = Vec::new();
        read_f32_into(values, "evaluateAttribute: values", &mut input).map_err(js_error)?;
        let width = item_size as usize;
        if !(1..=attributes::MAX_ITEM_SIZE).contains(&width) {
            return Err(js_error(Error::InvalidAttribute(format!(
                "evaluateAttribute: itemSize is {item_size}; give 1 to {} floats per vertex",
                attributes::MAX_ITEM_SIZE
            ))));
        }
        let mut out = vec![0.0; width * self.inner.num_vertices()];
        self.inner.evaluate_attribute(&input, width, &mut out).map_err(js_error)?;
        Ok(lend_or_new(into, &out))
    }
}
