//! Reading the caller's mesh and attribute arrays: typed arrays sized and copied through the
//! `%TypedArray%` intrinsics straight into Rust-owned vectors, so no caller getter runs between
//! sizing and copying and the caller's arrays are never written.

use super::*;

pub(super) fn mesh_error(message: String) -> Error {
    Error::InvalidMesh(message)
}

/// Copies the caller's typed arrays into a [`PolyMesh`].
pub(super) fn read_mesh(value: &JsValue) -> Result<PolyMesh, Error> {
    let (positions, indices, face_sizes) = read_mesh_arrays(value, |p| copy_f32(p, "positions"))?;
    Ok(PolyMesh { positions, indices, face_sizes })
}

/// Copies the caller's typed arrays into the arrays a [`HalfEdgeMesh`] keeps, and builds it:
/// one copy of each, where [`read_mesh`] and `from_poly` would make two.
pub(super) fn read_half_edge_mesh(value: &JsValue) -> Result<HalfEdgeMesh, Error> {
    let (positions, indices, face_sizes) = read_mesh_arrays(value, copy_vertices)?;
    HalfEdgeMesh::from_vertices(positions, indices, &face_sizes)
}

/// The channels of `mesh.attributes` (none when it is absent), copied, in the object's key
/// order. Their lengths are checked against the mesh later, with the mesh's counts.
pub(super) fn read_attributes(mesh: &JsValue) -> Result<Vec<Attribute>, Error> {
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
pub(super) fn read_mesh_arrays<P>(
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
pub(super) fn typed_array_kind(value: &JsValue) -> Option<String> {
    if !js_sys::ArrayBuffer::is_view(value) {
        return None;
    }
    Reflect::get(value, &js_sys::Symbol::to_string_tag()).ok()?.as_string()
}

/// The `%TypedArray%.prototype` getters and methods the copies use, rather than whatever the
/// caller's arrays inherit or shadow: no caller code runs while an array is sized, checked and
/// written. Looked up once per module instance.
pub(super) struct Intrinsics {
    pub(super) length: js_sys::Function,
    pub(super) buffer: js_sys::Function,
    pub(super) set: js_sys::Function,
    pub(super) fill: js_sys::Function,
}

thread_local! {
    static INTRINSICS: std::cell::RefCell<Option<std::rc::Rc<Intrinsics>>> = Default::default();
}

pub(super) fn intrinsics() -> Result<std::rc::Rc<Intrinsics>, JsValue> {
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
pub(super) fn typed_array_length(source: &JsValue, field: &str) -> Result<u32, Error> {
    let length =
        intrinsics().and_then(|i| i.length.call0(source)).map_err(|e| copy_threw(field, e))?;
    Ok(length.as_f64().unwrap_or_default() as u32)
}

pub(super) fn copy_threw(field: &str, e: JsValue) -> Error {
    mesh_error(format!("copying mesh.{field} threw {}", describe(&e)))
}

/// Copies the caller's typed array of `length` elements (from [`typed_array_length`]) straight
/// into wasm memory, `per_item` elements to an item of the result, by
/// `%TypedArray%.prototype.set` on a view of our own, which reads the source through its
/// internal slots. No code of the caller's runs between sizing and copying, so the length cannot
/// change in between; a detached source is an error; and no intermediate JS copy is made (a
/// fresh one cost 20 ms of page faults for a 1M-quad mesh).
pub(super) fn copy_in<T: Default + Clone>(
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
pub(super) fn memory_buffer() -> JsValue {
    wasm_bindgen::memory().unchecked_into::<js_sys::WebAssembly::Memory>().buffer()
}

pub(super) fn float32_view(buffer: &JsValue, offset: u32, len: u32) -> JsValue {
    Float32Array::new_with_byte_offset_and_length(buffer, offset, len).into()
}

pub(super) fn copy_f32(source: &JsValue, field: &str) -> Result<Vec<f32>, Error> {
    copy_in(source, field, (typed_array_length(source, field)?, 1), float32_view)
}

/// The positions as `[x, y, z]` per vertex, in one copy.
pub(super) fn copy_vertices(source: &JsValue) -> Result<Vec<[f32; 3]>, Error> {
    let length = typed_array_length(source, "positions")?;
    if !length.is_multiple_of(3) {
        return Err(crate::mesh::positions_not_in_threes(length as usize));
    }
    copy_in(source, "positions", (length, 3), float32_view)
}

pub(super) fn copy_u32(source: &JsValue, field: &str) -> Result<Vec<u32>, Error> {
    copy_in(source, field, (typed_array_length(source, field)?, 1), |buffer, offset, len| {
        Uint32Array::new_with_byte_offset_and_length(buffer, offset, len).into()
    })
}

/// `items` default values; `entries` is the length of the caller's array they stand for.
pub(super) fn zeroed<T: Default + Clone>(
    items: u32,
    entries: u32,
    field: &str,
) -> Result<Vec<T>, Error> {
    let mut out = Vec::new();
    out.try_reserve_exact(items as usize).map_err(|_| {
        Error::TooLarge(format!(
            "mesh.{field} has {entries} entries, more than the WebAssembly memory can hold"
        ))
    })?;
    out.resize(items as usize, T::default());
    Ok(out)
}

pub(super) fn get(object: &JsValue, key: &str) -> Result<JsValue, Error> {
    Reflect::get(object, &JsValue::from_str(key))
        .map_err(|e| mesh_error(format!("reading mesh.{key} threw {}", describe(&e))))
}

pub(super) fn wrong_array_type(field: &str, expected: &str, got: &JsValue) -> Error {
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

pub(super) fn is_typed_array(value: &JsValue) -> bool {
    typed_array_kind(value).is_some_and(|kind| kind != "DataView")
}

#[wasm_bindgen]
extern "C" {
    /// `Array.isArray`, which throws for a revoked Proxy: `catch` makes that an `Err`.
    #[wasm_bindgen(catch, js_namespace = Array, js_name = isArray)]
    fn checked_is_array(value: &JsValue) -> Result<bool, JsValue>;
}

pub(super) fn is_array(value: &JsValue) -> bool {
    checked_is_array(value).unwrap_or(false)
}

/// True when `Error.prototype` is on `value`'s prototype chain, walked with
/// `Reflect.getPrototypeOf` (errors, not exceptions) rather than `instanceof`, whose Proxy
/// traps could throw through this code.
pub(super) fn is_error(value: &JsValue) -> bool {
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
