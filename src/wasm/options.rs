//! Reading `SubdivideOptions`: every key checked, every value's type and range named in the
//! error.

use super::*;

pub(super) fn option_error(message: String) -> Error {
    Error::InvalidOption(message)
}

pub(super) fn read_options(value: &JsValue) -> Result<(Options, Tags), Error> {
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
    let fvar_linear = read_fvar_linear(&field("fvarLinear")?)?;
    let limit = read_bool(&field("limit")?, "limit")?;
    let normals = read_bool(&field("normals")?, "normals")?;
    let defaults = Options::default();
    let options = Options {
        schemes,
        boundary: boundary.unwrap_or(defaults.boundary),
        max_faces: max_faces.unwrap_or(defaults.max_faces),
        max_bytes: max_bytes.unwrap_or(defaults.max_bytes),
        fvar_linear: fvar_linear.unwrap_or(defaults.fvar_linear),
        limit: limit.unwrap_or(false),
        // The limit surface is shaded with its own normals.
        normals: normals.unwrap_or(false),
    };
    Ok((options, read_tags(&field)?))
}

/// `options.onProgress`: a function, or `None` when absent. Read apart from [`read_options`],
/// whose `Options` stay plain data (the evaluator and `predictCounts` ignore the key).
pub(super) fn read_on_progress(value: &JsValue) -> Result<Option<Function>, Error> {
    if !value.is_object() {
        return Ok(None);
    }
    let field = Reflect::get(value, &JsValue::from_str("onProgress"))
        .map_err(|e| option_error(format!("reading options.onProgress threw {}", describe(&e))))?;
    if field.is_undefined() {
        return Ok(None);
    }
    match field.dyn_into::<Function>() {
        Ok(function) => Ok(Some(function)),
        Err(other) => Err(option_error(format!(
            "onProgress must be a function such as ({{ level, levels }}) => console.log(level, levels), got {}",
            describe(&other)
        ))),
    }
}

/// The tag options: `creases`, `corners`, `holes`, `creaseMethod`, `smoothTriangles`.
pub(super) fn read_tags(field: &dyn Fn(&str) -> Result<JsValue, Error>) -> Result<Tags, Error> {
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
    if let Some(smooth) = read_bool(&field("smoothTriangles")?, "smoothTriangles")? {
        tags.smooth_triangles = smooth;
    }
    Ok(tags)
}

/// A boolean option, `None` when absent.
fn read_bool(value: &JsValue, name: &str) -> Result<Option<bool>, Error> {
    if value.is_undefined() {
        return Ok(None);
    }
    value.as_bool().map(Some).ok_or_else(|| {
        option_error(format!("{name} must be true or false, got {}", describe(value)))
    })
}

/// `{ <items>: Uint32Array, sharpness: Float32Array }` of `creases` or `corners`.
pub(super) fn read_sharpness(
    value: &JsValue,
    name: &str,
    items: &str,
) -> Result<(Vec<u32>, Vec<f32>), Error> {
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
pub(super) fn per_item<'a>(
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

pub(super) fn wrong_option_array(field: &str, expected: &str, got: &JsValue) -> Error {
    option_error(format!("options.{field} must be a {expected}, got {}", describe(got)))
}

pub(super) fn read_levels(value: &JsValue) -> Result<Option<u32>, Error> {
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
pub(super) fn read_limit(value: &JsValue, name: &str) -> Result<Option<u64>, Error> {
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

pub(super) fn read_boundary(value: &JsValue) -> Result<Option<Boundary>, Error> {
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

/// `fvarLinear`: one of the six names; a near miss gets a suggestion.
pub(super) fn read_fvar_linear(value: &JsValue) -> Result<Option<FVarLinear>, Error> {
    if value.is_undefined() {
        return Ok(None);
    }
    let names: Vec<&str> = FVarLinear::ALL.iter().map(|m| m.name()).collect();
    let allowed = quoted_list(names.iter().copied());
    let Some(name) = value.as_string() else {
        return Err(option_error(format!(
            "fvarLinear must be one of {allowed}, got {}",
            describe(value)
        )));
    };
    name.parse().map(Some).map_err(|_| {
        let suggestion =
            closest(&name, &names).map(|k| format!(" (did you mean '{k}'?)")).unwrap_or_default();
        option_error(format!(
            "unknown fvarLinear '{name}'{suggestion}; use one of {allowed} (OpenSubdiv's \
             face-varying linear interpolation: where UVs stay linear)"
        ))
    })
}

pub(super) enum SchemeChoice {
    Default,
    One(Scheme),
    PerLevel(Vec<Scheme>),
}

pub(super) fn read_schemes(value: &JsValue) -> Result<SchemeChoice, Error> {
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
