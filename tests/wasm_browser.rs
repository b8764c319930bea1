//! The JS-facing API (`subsurf::wasm`) in headless Chromium (found through `chromedriver` on
//! PATH). The cases live in `common/wasm_cases.rs` and also run under Node through `wasm_node.rs`.
#![cfg(target_arch = "wasm32")]

wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

#[path = "common/wasm_cases.rs"]
mod wasm_cases;
