//! `options.onProgress`: told after each level, in order, by `subdivide` and
//! `BaseMesh.subdivide`; what it throws stops the call and comes out of it unchanged.

use super::*;
use js_sys::Function;
use subsurf::wasm::BaseMesh;

/// A JS function that pushes `[level, levels, faces, vertices]` of each call onto `log`, and
/// throws `new RangeError('stop at ' + level)` at level `stop` (0: never).
fn recorder(log: &Array, stop: u32) -> Function {
    let body = "return function (p) { \
                  log.push([p.level, p.levels, p.faces, p.vertices]); \
                  if (p.level === stop) throw new RangeError('stop at ' + p.level); \
                };";
    let make = Function::new_with_args("log, stop", body);
    make.call2(&JsValue::UNDEFINED, log, &stop.into()).unwrap().unchecked_into()
}

fn logged(log: &Array) -> Vec<Vec<u32>> {
    log.iter()
        .map(|row| {
            row.unchecked_into::<Array>().iter().map(|x| x.as_f64().unwrap() as u32).collect()
        })
        .collect()
}

fn with_progress(options: &[(&str, JsValue)], function: &Function) -> JsValue {
    let mut fields = options.to_vec();
    fields.push(("onProgress", function.clone().into()));
    object(&fields)
}

/// The cube at levels 1-3: 24, 96, 384 quads on 26, 98, 386 vertices.
const CUBE_LEVELS: [[u32; 4]; 3] = [[1, 3, 24, 26], [2, 3, 96, 98], [3, 3, 384, 386]];

#[wasm_bindgen_test]
fn progress_is_told_after_each_level_in_order() {
    let log = Array::new();
    let options = with_progress(&[("levels", 3.into())], &recorder(&log, 0));
    let out = ok(subdivide(&cube(), &options));
    assert_eq!(logged(&log), CUBE_LEVELS.map(|r| r.to_vec()).to_vec());
    let plain = ok(subdivide(&cube(), &levels(3.0)));
    assert_eq!(f32s(&out, "positions"), f32s(&plain, "positions"), "the callback changes nothing");

    // The same through BaseMesh, with the limit (told after it) and normals.
    let log = Array::new();
    let base = BaseMesh::new(&cube()).unwrap();
    let options = [("levels", 3.into()), ("limit", true.into())];
    ok(base.subdivide(&with_progress(&options, &recorder(&log, 0)), &JsValue::UNDEFINED));
    assert_eq!(logged(&log), CUBE_LEVELS.map(|r| r.to_vec()).to_vec());

    // No levels, nothing to tell.
    let log = Array::new();
    ok(subdivide(&cube(), &with_progress(&[("levels", 0.into())], &recorder(&log, 0))));
    assert_eq!(log.length(), 0);
}

#[wasm_bindgen_test]
fn a_throwing_callback_stops_the_call_with_its_own_exception() {
    let log = Array::new();
    let options = with_progress(&[("levels", 3.into())], &recorder(&log, 2));
    let error = subdivide(&cube(), &options).unwrap_err();
    let error = error.dyn_into::<js_sys::RangeError>().expect("the callback's own RangeError");
    assert_eq!(String::from(error.message()), "stop at 2");
    assert_eq!(logged(&log), CUBE_LEVELS[..2].iter().map(|r| r.to_vec()).collect::<Vec<_>>());

    let base = BaseMesh::new(&cube()).unwrap();
    let error = base.subdivide(&options, &JsValue::UNDEFINED).unwrap_err();
    assert!(error.is_instance_of::<js_sys::RangeError>());
    // With the limit, the closed cube's points come from the closed forms, which tell each
    // level as they make it: the throw ends the call there too.
    let log = Array::new();
    let limit = [("levels", 3.into()), ("limit", true.into())];
    let error = base.subdivide(&with_progress(&limit, &recorder(&log, 2)), &JsValue::UNDEFINED);
    assert!(error.unwrap_err().is_instance_of::<js_sys::RangeError>());
    assert_eq!(logged(&log), CUBE_LEVELS[..2].iter().map(|r| r.to_vec()).collect::<Vec<_>>());
    // The module and the mesh work on.
    assert_eq!(u32s(&ok(base.subdivide(&levels(2.0), &JsValue::UNDEFINED)), "faceSizes").len(), 96);
    assert_eq!(u32s(&ok(subdivide(&cube(), &levels(1.0))), "faceSizes").len(), 24);
}

#[wasm_bindgen_test]
fn on_progress_must_be_a_function() {
    for (value, shown) in [(JsValue::from(3), "got 3"), (JsValue::from("log"), "got string 'log'")]
    {
        let m = thrown(subdivide(&cube(), &object(&[("onProgress", value)])));
        assert_mentions(&m, &["onProgress must be a function", shown]);
    }
    let m = thrown(subdivide(&cube(), &object(&[("onProgres", 3.into())])));
    assert_mentions(&m, &["unknown option 'onProgres'", "did you mean 'onProgress'"]);
}
