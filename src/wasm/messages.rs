//! Error messages: unknown keys with the closest allowed one, and short descriptions of any JS
//! value.

use super::*;

/// Rejects own string keys of `object` outside `allowed` and `ignored`, naming the closest
/// allowed one when it looks like a typo.
pub(super) fn check_keys(
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
pub(super) fn closest<'a>(key: &str, allowed: &[&'a str]) -> Option<&'a str> {
    let key = key.to_lowercase();
    allowed
        .iter()
        .map(|&a| (edit_distance(&key, &a.to_lowercase()), a))
        .filter(|&(d, _)| d <= 2)
        .min_by_key(|&(d, _)| d)
        .map(|(_, a)| a)
}

pub(super) fn edit_distance(a: &str, b: &str) -> usize {
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

pub(super) fn quoted_list<'a>(names: impl Iterator<Item = &'a str>) -> String {
    names.map(|n| format!("'{n}'")).collect::<Vec<_>>().join(", ")
}

/// A short description of a JS value for error messages: `undefined`, `-1`, `string '2'`,
/// `Float32Array`, `Array`, `object`.
pub(super) fn describe(value: &JsValue) -> String {
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

pub(super) fn constructor_name(value: &JsValue) -> Option<String> {
    let constructor = Reflect::get(value, &JsValue::from_str("constructor")).ok()?;
    if !constructor.is_function() {
        return None;
    }
    Reflect::get(&constructor, &JsValue::from_str("name"))
        .ok()?
        .as_string()
        .filter(|name| !name.is_empty())
}
