//! Writing results: fresh typed arrays, or the arrays an `into` object lends, filled piece by
//! piece as the result hands them over.

use super::*;

/// A plain object of fresh typed arrays (copies, never views of wasm memory).
pub(super) fn mesh_object(mesh: &PolyMesh) -> JsResult<JsValue> {
    let object = Object::new();
    set_field(&object, "positions", &Float32Array::from(&mesh.positions[..]))?;
    set_field(&object, "indices", &Uint32Array::from(&mesh.indices[..]))?;
    set_field(&object, "faceSizes", &Uint32Array::from(&mesh.face_sizes[..]))?;
    Ok(object.into())
}

/// The arrays an `into` object lends, read before any work so that its getters run first and
/// a wrong `into` fails fast. Whether each can be reused is decided when the result is written.
pub(super) struct Lent {
    arrays: [JsValue; 4],
}

/// The result's fields, in the order of [`Lent::arrays`], with the typed array each must be.
pub(super) const RESULT_FIELDS: [(&str, &str); 4] = [
    ("positions", "Float32Array"),
    ("indices", "Uint32Array"),
    ("faceSizes", "Uint32Array"),
    ("triangles", "Uint32Array"),
];

impl Lent {
    pub(super) fn read(into: &JsValue) -> Result<Lent, Error> {
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
pub(super) fn refined_object(refined: &Refined, mut lent: Lent) -> JsResult<JsValue> {
    let intrinsics = intrinsics().map_err(|e| JsError::new(&describe(&e)))?;
    let positions = refined.positions();
    let mut out = Output::new(lent.take(0, positions.len(), &intrinsics)?, &intrinsics);
    // SAFETY: the view is used at once, before anything can allocate (and so grow the memory).
    out.push(positions, |chunk| unsafe { Float32Array::view(chunk) }.into());
    let mut indices = Output::new(lent.take(1, refined.num_indices(), &intrinsics)?, &intrinsics);
    let sizes = lent.take(2, refined.num_faces(), &intrinsics)?;
    let triangles = lent.take(3, refined.num_triangle_indices(), &intrinsics)?;
    let mut triangles = Output::new(triangles, &intrinsics);
    // Face-varying indices that are the faces' own but near seams come with the faces' pieces.
    let (attributes, seam_corners) = refined.attributes_in_pieces();
    let num_indices = u32::try_from(refined.num_indices())
        .map_err(|_| JsError::new("the result's indices are too long"))?;
    let mut in_pieces: Vec<_> = seam_corners
        .iter()
        .map(|(i, seams)| {
            let array = Uint32Array::new_with_length(num_indices).into();
            (*i, seams, Output::new(array, &intrinsics))
        })
        .collect();
    let (mut at, mut patched) = (0, Vec::new());
    refined.index_and_triangle_chunks(
        |c| {
            indices.push(c, u32_view);
            for (_, seams, out) in &mut in_pieces {
                patched.clear();
                patched.extend_from_slice(c);
                seams.patch(at, &mut patched);
                out.push(&patched, u32_view);
            }
            at += c.len();
        },
        |c| triangles.push(c, u32_view),
    );
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
    if let Some(normals) = refined.normals() {
        set_field(&object, "normals", &Float32Array::from(normals))?;
    }
    if !attributes.is_empty() {
        let mut made = Vec::with_capacity(in_pieces.len());
        for (i, _, out) in in_pieces {
            made.push((i, out.finish()?));
        }
        set_field(&object, "attributes", &channels_object_with(attributes, made)?)?;
    }
    Ok(object.into())
}

/// `{ name: { array, itemSize, indices? } }`: fresh arrays, `indices` for face-varying channels.
pub(super) fn channels_object(attributes: &[Attribute]) -> JsResult<JsValue> {
    channels_object_with(attributes, Vec::new())
}

/// [`channels_object`] with the `indices` of the attributes `made` names already in JS.
fn channels_object_with(
    attributes: &[Attribute],
    made: Vec<(usize, JsValue)>,
) -> JsResult<JsValue> {
    let channels = Object::new();
    for (k, a) in attributes.iter().enumerate() {
        let channel = Object::new();
        set_field(&channel, "array", &Float32Array::from(&a.values[..]))?;
        set_field(&channel, "itemSize", &JsValue::from(a.item_size as u32))?;
        if let Some((_, indices)) = made.iter().find(|(i, _)| *i == k) {
            set_field(&channel, "indices", indices)?;
        } else if let Some(indices) = &a.indices {
            set_field(&channel, "indices", &Uint32Array::from(&indices[..]))?;
        }
        set_field(&channels, &a.name, &channel)?;
    }
    Ok(channels.into())
}

pub(super) fn u32_view(chunk: &[u32]) -> JsValue {
    // SAFETY: as for the positions in `refined_object`: used before anything allocates.
    unsafe { Uint32Array::view(chunk) }.into()
}

/// A JS typed array of the length needed, filled from consecutive pieces through the
/// intrinsic `set` (the array may be the caller's, from `into`). The first failure is kept for
/// [`Output::finish`] and stops the writes.
pub(super) struct Output<'i> {
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

pub(super) fn set_field(object: &JsValue, key: &str, value: &JsValue) -> JsResult<()> {
    Reflect::set(object, &JsValue::from_str(key), value)
        .map(|_| ())
        .map_err(|_| JsError::new(&format!("could not set result field {key}")))
}
