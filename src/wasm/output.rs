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
    /// The four result fields ([`RESULT_FIELDS`]), then each lent channel's `array` and
    /// `indices`.
    arrays: Vec<JsValue>,
    /// The names of `into.attributes`' channels, in the order of their slots after the fields.
    channels: Vec<String>,
}

/// The result's fields, in the order of [`Lent::arrays`], with the typed array each must be.
pub(super) const RESULT_FIELDS: [(&str, &str); 4] = [
    ("positions", "Float32Array"),
    ("indices", "Uint32Array"),
    ("faceSizes", "Uint32Array"),
    ("triangles", "Uint32Array"),
];

impl Lent {
    /// Nothing lent.
    pub(super) fn none() -> Lent {
        Lent { arrays: vec![JsValue::UNDEFINED; RESULT_FIELDS.len()], channels: Vec::new() }
    }

    pub(super) fn read(into: &JsValue) -> Result<Lent, Error> {
        let mut lent = Lent::none();
        if into.is_undefined() || into.is_null() {
            return Ok(lent);
        }
        if !into.is_object() || is_array(into) {
            return Err(Error::InvalidOption(format!(
                "into must be a result of an earlier subdivide call, to reuse its arrays, or \
                 undefined; got {}",
                describe(into)
            )));
        }
        let get = |object: &JsValue, key: &str, path: &str| {
            Reflect::get(object, &JsValue::from_str(key)).map_err(|e| {
                Error::InvalidOption(format!("reading into.{path} threw {}", describe(&e)))
            })
        };
        let of_kind = |value: JsValue, kind: &str| {
            if typed_array_kind(&value).as_deref() == Some(kind) {
                value
            } else {
                JsValue::UNDEFINED
            }
        };
        for (slot, (key, kind)) in lent.arrays.iter_mut().zip(RESULT_FIELDS) {
            *slot = of_kind(get(into, key, key)?, kind);
        }
        // `into.attributes`: each channel's arrays, when they are typed arrays of their kind.
        let channels = get(into, "attributes", "attributes")?;
        if channels.is_object() && !is_array(&channels) {
            let names = Reflect::own_keys(&channels).map_err(|e| {
                Error::InvalidOption(format!("listing into.attributes threw {}", describe(&e)))
            })?;
            for name in names.iter().filter_map(|n| n.as_string()) {
                let channel = get(&channels, &name, &format!("attributes.{name}"))?;
                if !channel.is_object() {
                    continue;
                }
                let path = |key: &str| format!("attributes.{name}.{key}");
                let array = of_kind(get(&channel, "array", &path("array"))?, "Float32Array");
                let indices = of_kind(get(&channel, "indices", &path("indices"))?, "Uint32Array");
                lent.arrays.extend([array, indices]);
                lent.channels.push(name);
            }
        }
        Ok(lent)
    }

    /// Slot `i`'s lent array when it can be written over: it has `len` elements, is not a view
    /// of wasm memory (which the writes would corrupt) and is not lent for another slot too (so
    /// an array lent for two fields serves one at most). Called once per slot.
    fn reuse(&mut self, i: usize, len: usize, intrinsics: &Intrinsics) -> Option<JsValue> {
        let lent = self.arrays.get_mut(i).map(std::mem::take)?;
        if lent.is_undefined() {
            return None;
        }
        let fits = intrinsics.length.call0(&lent).ok().and_then(|n| n.as_f64()) == Some(len as f64);
        let ours = intrinsics.buffer.call0(&lent).is_ok_and(|b| b == memory_buffer());
        let again = self.arrays.iter().any(|other| Object::is(other, &lent));
        (fits && !ours && !again).then_some(lent)
    }

    /// Result field `i`'s array: the lent one ([`Lent::reuse`]) or a fresh one.
    fn field(&mut self, i: usize, len: usize, intrinsics: &Intrinsics) -> JsResult<JsValue> {
        if let Some(lent) = self.reuse(i, len, intrinsics) {
            return Ok(lent);
        }
        let len = u32::try_from(len).map_err(|_| {
            JsError::new(&format!("the result's {} is too long", RESULT_FIELDS[i].0))
        })?;
        Ok(match RESULT_FIELDS[i].1 {
            "Float32Array" => Float32Array::new_with_length(len).into(),
            _ => Uint32Array::new_with_length(len).into(),
        })
    }

    /// The lent `key` (0 `array`, 1 `indices`) of channel `name` when it can be written over
    /// with `len` elements.
    fn channel(
        &mut self,
        name: &str,
        key: usize,
        len: usize,
        intrinsics: &Intrinsics,
    ) -> Option<JsValue> {
        let slot = self.channel_slot(name)? + key;
        self.reuse(slot, len, intrinsics)
    }

    /// The slot of channel `name`'s `array` (its `indices` are the next), if `into` lent it.
    fn channel_slot(&self, name: &str) -> Option<usize> {
        let k = self.channels.iter().position(|n| n == name)?;
        Some(RESULT_FIELDS.len() + 2 * k)
    }
}

/// `subdivide`'s result. The index arrays are copied into JS piece by piece as the result hands
/// them over, so that those it keeps implicit (the faces of a last quad split, and every fan
/// triangulation) are never written whole to wasm memory and read back.
pub(super) fn refined_object(refined: &Refined, mut lent: Lent) -> JsResult<JsValue> {
    let intrinsics = intrinsics().map_err(|e| JsError::new(&describe(&e)))?;
    let positions = refined.positions();
    let mut out = Output::new(lent.field(0, positions.len(), &intrinsics)?, &intrinsics);
    out.push(positions, f32_view);
    let mut indices = Output::new(lent.field(1, refined.num_indices(), &intrinsics)?, &intrinsics);
    let sizes = lent.field(2, refined.num_faces(), &intrinsics)?;
    let triangles = lent.field(3, refined.num_triangle_indices(), &intrinsics)?;
    let mut triangles = Output::new(triangles, &intrinsics);
    // Face-varying indices that are the faces' own but near seams come with the faces' pieces.
    let (attributes, seam_corners) = refined.attributes_in_pieces();
    let num_indices = u32::try_from(refined.num_indices())
        .map_err(|_| JsError::new("the result's indices are too long"))?;
    let mut in_pieces: Vec<_> = seam_corners
        .iter()
        .map(|(i, seams)| {
            let name = attributes.get(*i).map_or("", |a| a.name.as_str());
            let array = lent
                .channel(name, 1, num_indices as usize, &intrinsics)
                .unwrap_or_else(|| Uint32Array::new_with_length(num_indices).into());
            (*i, seams, Output::new(array, &intrinsics))
        })
        .collect();
    let (mut at, mut patched) = (0, Vec::new());
    refined.index_and_triangle_chunks(
        |c| {
            indices.push(c, u32_view);
            for (_, seams, out) in &mut in_pieces {
                if !seams.touches(at, c.len()) {
                    out.push(c, u32_view);
                    continue;
                }
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
        let channels = channels_object_with(attributes, made, &mut lent, &intrinsics)?;
        set_field(&object, "attributes", &channels)?;
    }
    Ok(object.into())
}

/// `{ name: { array, itemSize, indices? } }`: fresh arrays, `indices` for face-varying channels.
pub(super) fn channels_object(attributes: &[Attribute]) -> JsResult<JsValue> {
    let intrinsics = intrinsics().map_err(|e| JsError::new(&describe(&e)))?;
    channels_object_with(attributes, Vec::new(), &mut Lent::none(), &intrinsics)
}

/// [`channels_object`] with the `indices` of the attributes `made` names already in JS, and
/// the arrays `lent` lends for the others where they fit (else fresh copies, one `slice` each).
fn channels_object_with(
    attributes: &[Attribute],
    made: Vec<(usize, JsValue)>,
    lent: &mut Lent,
    intrinsics: &Intrinsics,
) -> JsResult<JsValue> {
    let channels = Object::new();
    for (k, a) in attributes.iter().enumerate() {
        let channel = Object::new();
        let array = lent.channel(&a.name, 0, a.values.len(), intrinsics);
        let array = copied(array, &a.values, f32_view, |v| Float32Array::from(v), intrinsics)?;
        set_field(&channel, "array", &array)?;
        set_field(&channel, "itemSize", &JsValue::from(a.item_size as u32))?;
        if let Some((_, indices)) = made.iter().find(|(i, _)| *i == k) {
            set_field(&channel, "indices", indices)?;
        } else if let Some(indices) = &a.indices {
            let array = lent.channel(&a.name, 1, indices.len(), intrinsics);
            set_field(
                &channel,
                "indices",
                &copied(array, indices, u32_view, |v| Uint32Array::from(v), intrinsics)?,
            )?;
        }
        set_field(&channels, &a.name, &channel)?;
    }
    Ok(channels.into())
}

/// `values` in JS: written over `lent` (through `view` of them), or else a fresh copy made by
/// `fresh` (one `slice`, which costs less than a fresh array filled). `view` is the typed array
/// view of wasm memory ([`f32_view`], [`u32_view`]).
fn copied<T, A: Into<JsValue>>(
    lent: Option<JsValue>,
    values: &[T],
    view: impl Fn(&[T]) -> JsValue,
    fresh: impl Fn(&[T]) -> A,
    intrinsics: &Intrinsics,
) -> JsResult<JsValue> {
    let Some(lent) = lent else { return Ok(fresh(values).into()) };
    let mut out = Output::new(lent, intrinsics);
    out.push(values, view);
    out.finish()
}

pub(super) fn f32_view(chunk: &[f32]) -> JsValue {
    // SAFETY: the view is used at once, before anything can allocate (and so grow the memory).
    unsafe { Float32Array::view(chunk) }.into()
}

pub(super) fn u32_view(chunk: &[u32]) -> JsValue {
    // SAFETY: as for `f32_view`.
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
