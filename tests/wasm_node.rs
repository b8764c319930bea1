//! The JS-facing API (`subsurf::wasm`) under Node. The cases live in `common/wasm_cases.rs` and
//! also run in headless Chromium through `wasm_browser.rs`.
#![cfg(target_arch = "wasm32")]

#[path = "common/wasm_cases.rs"]
mod wasm_cases;
