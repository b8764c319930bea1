//! The catalogue of bad inputs: every way a caller can get a mesh, an OBJ file or an option wrong,
//! and what the error must say. Plain data (std only), shared by three runners:
//!
//! - `tests/bad_inputs.rs`: the Rust API (`subsurf::subdivide`, `HalfEdgeMesh::from_faces`,
//!   `subsurf::io::read_obj`, `Scheme`/`Boundary` parsing) and the command line;
//! - `tests/common/wasm_cases.rs`: the JS API (`subdivide`, `readObj`, `writeObj`) in Node and in
//!   headless Chromium, checking after every bad call that the same module instance still
//!   subdivides a cube correctly.
//!
//! Each case says, per runner, the fragments the error message must contain (the problem and its
//! place: face, vertex, index, OBJ line or option), or why that runner cannot express the input.
//! A case the library does not handle yet is `Pending`: the runners skip it in their normal run,
//! and `tests/bad_inputs.rs` has an `#[ignore = "needs library change: ..."]` test that runs it.
#![allow(dead_code)]

/// A JS-style option value. The Rust API and the CLI translate what they can express.
#[derive(Clone, Debug, PartialEq)]
pub enum Val {
    Str(&'static str),
    Num(f64),
    /// A JS array of names; a comma-separated list on the command line.
    List(&'static [&'static str]),
    Bool(bool),
}

/// The options of a call, keyed by their JS names (`scheme`, `levels`, `boundary`, `maxFaces`,
/// `maxBytes`, or an unknown key). The CLI flag is the kebab-case name: `--max-faces`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Opts {
    pub entries: Vec<(&'static str, Val)>,
    /// JS only: the options argument is this value instead of an object.
    pub not_an_object: Option<Val>,
}

impl Opts {
    pub fn get(&self, key: &str) -> Option<&Val> {
        self.entries.iter().find(|(k, _)| *k == key).map(|(_, v)| v)
    }
}

/// A field of a mesh object as JS sees it.
#[derive(Clone, Debug, PartialEq)]
pub enum JsField {
    Float32(Vec<f32>),
    Uint32(Vec<u32>),
    Float64(Vec<f64>),
    Int32(Vec<i32>),
    Uint8(Vec<u8>),
    /// A plain JS `Array` of numbers.
    Plain(Vec<f64>),
    Missing,
}

/// A mesh object for the JS API, possibly with wrongly typed or unknown fields.
#[derive(Clone, Debug, PartialEq)]
pub struct JsMesh {
    pub positions: JsField,
    pub indices: JsField,
    pub face_sizes: JsField,
    /// An extra field (a typo), holding a copy of the face sizes.
    pub extra: Option<&'static str>,
    /// The mesh argument is this value instead of an object.
    pub not_an_object: Option<Val>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Input {
    /// Flat arrays as the Rust API and the JS API take them. `face_sizes: None` is the JS API's
    /// "every face is a triangle". The CLI runs these as an OBJ file written by [`to_obj`].
    Arrays { positions: Vec<f32>, indices: Vec<u32>, face_sizes: Option<Vec<u32>> },
    /// The text of an OBJ file: `read_obj`, `readObj`, the CLI's input file.
    Obj(String),
    /// Raw file bytes (not UTF-8): the CLI only.
    ObjBytes(Vec<u8>),
    /// A JS mesh object that only JS can get wrong this way.
    Js(JsMesh),
    /// The catalogue's cube with one attribute channel: `mesh.attributes[name]` in JS, an
    /// `Attribute` in Rust (which cannot express every JS shape of a channel).
    Channel(Channel),
}

/// One attribute channel as JS gives it.
#[derive(Clone, Debug, PartialEq)]
pub struct Channel {
    pub name: &'static str,
    /// A JS number: the Rust runner needs a whole one.
    pub item_size: f64,
    pub array: JsField,
    pub indices: Option<JsField>,
    /// An extra field (a typo), holding a copy of the item size.
    pub extra: Option<&'static str>,
}

/// Where the input first fails.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Reading the OBJ text.
    Obj,
    /// Building the mesh from arrays: `HalfEdgeMesh::from_faces` must fail too.
    Mesh,
    /// Reading the options.
    Options,
    /// The mesh is valid, but subdividing it with these options is refused.
    Subdivide,
    /// The mesh is valid, but one of its attribute channels is not.
    Attributes,
}

/// What one runner must see.
#[derive(Clone, Debug, PartialEq)]
pub enum Expect {
    /// An error whose message contains every fragment.
    Error(&'static [&'static str]),
    /// The runner cannot express this input; the reason says why.
    NotApplicable(&'static str),
    /// The library does not give this error yet: `what` says what it should do, and the
    /// fragments are what the message should contain once it does.
    Pending { what: &'static str, fragments: &'static [&'static str] },
}

#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    pub name: &'static str,
    pub input: Input,
    pub options: Opts,
    pub stage: Stage,
    pub rust: Expect,
    pub js: Expect,
    pub cli: Expect,
}

impl Case {
    fn new(
        name: &'static str,
        input: Input,
        stage: Stage,
        fragments: &'static [&'static str],
    ) -> Self {
        let all = Expect::Error(fragments);
        Case {
            name,
            input,
            options: Opts::default(),
            stage,
            rust: all.clone(),
            js: all.clone(),
            cli: all,
        }
    }
    fn opt(mut self, key: &'static str, value: Val) -> Self {
        self.options.entries.push((key, value));
        self
    }
    fn rust(mut self, expect: Expect) -> Self {
        self.rust = expect;
        self
    }
    fn js(mut self, expect: Expect) -> Self {
        self.js = expect;
        self
    }
    fn cli(mut self, expect: Expect) -> Self {
        self.cli = expect;
        self
    }
    fn only_js(self, why: &'static str) -> Self {
        self.rust(Expect::NotApplicable(why)).cli(Expect::NotApplicable(why))
    }
}

use Expect::{Error as E, NotApplicable as NA};
use Val::{List, Num, Str};

// ---------------------------------------------------------------------------------------------
// Meshes

/// The cube with corners ±1; vertex `i` has x, y, z signs from bits 0, 1, 2 of `i`.
pub fn cube() -> (Vec<f32>, Vec<u32>, Vec<u32>) {
    let mut positions = Vec::new();
    for i in 0..8 {
        for bit in 0..3 {
            positions.push(if i >> bit & 1 == 1 { 1.0 } else { -1.0 });
        }
    }
    #[rustfmt::skip]
    let indices = vec![
        0, 2, 3, 1, // z-
        4, 5, 7, 6, // z+
        0, 1, 5, 4, // y-
        2, 6, 7, 3, // y+
        0, 4, 6, 2, // x-
        1, 3, 7, 5, // x+
    ];
    (positions, indices, vec![4; 6])
}

pub fn tetrahedron() -> (Vec<f32>, Vec<u32>, Vec<u32>) {
    let positions = vec![1., 1., 1., 1., -1., -1., -1., 1., -1., -1., -1., 1.];
    (positions, vec![0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2], vec![3; 4])
}

fn arrays(positions: Vec<f32>, indices: Vec<u32>, face_sizes: Vec<u32>) -> Input {
    Input::Arrays { positions, indices, face_sizes: Some(face_sizes) }
}

fn cube_with(edit: impl FnOnce(&mut Vec<f32>, &mut Vec<u32>, &mut Vec<u32>)) -> Input {
    let (mut p, mut i, mut s) = cube();
    edit(&mut p, &mut i, &mut s);
    arrays(p, i, s)
}

/// `n` vertices on a small fan, each at a distinct place.
fn points(n: usize) -> Vec<f32> {
    (0..n).flat_map(|k| [k as f32, (k * k % 7) as f32, (k % 3) as f32]).collect()
}

/// Three triangles around the edge 0–1: a non-manifold "book" of three pages.
fn book() -> Input {
    arrays(points(5), vec![0, 1, 2, 1, 0, 3, 0, 1, 4], vec![3; 3])
}

/// Two triangles that share only vertex 0.
fn bowtie() -> Input {
    arrays(points(5), vec![0, 1, 2, 0, 3, 4], vec![3; 2])
}

/// Two triangles on the edge 0–1 that both run 0 → 1.
fn misoriented_pair() -> Input {
    arrays(points(4), vec![0, 1, 2, 0, 1, 3], vec![3; 2])
}

fn js_mesh(positions: JsField, indices: JsField, face_sizes: JsField) -> Input {
    Input::Js(JsMesh { positions, indices, face_sizes, extra: None, not_an_object: None })
}

fn js_cube_fields() -> (JsField, JsField, JsField) {
    let (p, i, s) = cube();
    (JsField::Float32(p), JsField::Uint32(i), JsField::Uint32(s))
}

/// Three vertices and then `face` as the only face line.
fn obj_triangle_then(face: &str) -> Input {
    Input::Obj(format!("v 0 0 0\nv 1 0 0\nv 0 1 0\n{face}\n"))
}

/// An OBJ file for the CLI: `v` lines with Rust's float formatting (`NaN`, `inf`), `f` lines
/// with 1-based indices. `None` when OBJ cannot express the arrays (a partial vertex, or face
/// sizes that do not cover the indices).
pub fn to_obj(positions: &[f32], indices: &[u32], face_sizes: Option<&[u32]>) -> Option<String> {
    if !positions.len().is_multiple_of(3) {
        return None;
    }
    let triangles;
    let sizes = match face_sizes {
        Some(sizes) => sizes,
        None if indices.len().is_multiple_of(3) => {
            triangles = vec![3; indices.len() / 3];
            &triangles[..]
        }
        None => return None,
    };
    if sizes.iter().map(|&n| n as u64).sum::<u64>() != indices.len() as u64 {
        return None;
    }
    let mut text = String::new();
    for p in positions.chunks_exact(3) {
        text += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    let mut start = 0;
    for &n in sizes {
        text.push('f');
        for &i in &indices[start..start + n as usize] {
            text += &format!(" {}", i as u64 + 1);
        }
        text.push('\n');
        start += n as usize;
    }
    Some(text)
}

// ---------------------------------------------------------------------------------------------
// The catalogue

const NO_CLI_CHANNELS: &str =
    "the command line reads channels only from OBJ vt lines, which the obj_vt_* cases cover";
const JS_ONLY_CHANNEL: &str = "an Attribute has a whole item size and f32 values";

/// A channel of the cube (8 vertices, 24 face corners).
fn channel(name: &'static str, item_size: f64, array: JsField, indices: Option<JsField>) -> Input {
    Input::Channel(Channel { name, item_size, array, indices, extra: None })
}

fn attribute_case(name: &'static str, input: Input, fragments: &'static [&'static str]) -> Case {
    Case::new(name, input, Stage::Attributes, fragments).cli(NA(NO_CLI_CHANNELS))
}

const NO_OBJ_PARTIAL: &str = "an OBJ 'v' line always has three coordinates";
const NO_OBJ_SIZES: &str = "OBJ face lines carry their own sizes";
const RUST_TYPED: &str = "the Rust API's types cannot hold this value";
const RUST_NO_KEYS: &str = "Rust options are a struct: there is no unknown key";

/// Every bad input, in a stable order. Names are unique snake_case identifiers.
pub fn catalogue() -> Vec<Case> {
    vec![
        // -- array shapes
        Case::new(
            "positions_not_a_multiple_of_3",
            cube_with(|p, _, _| {
                p.pop();
            }),
            Stage::Mesh,
            &["positions has 23 numbers", "not a multiple of 3"],
        )
        .cli(NA(NO_OBJ_PARTIAL)),
        Case::new(
            "positions_empty",
            arrays(vec![], vec![0, 1, 2], vec![3]),
            Stage::Mesh,
            &["positions is empty"],
        )
        // The OBJ form is a file with one face line and no vertices.
        .cli(E(&["OBJ line 1", "vertex 1", "only 0 vertices"])),
        Case::new(
            "positions_and_faces_empty",
            arrays(vec![], vec![], vec![]),
            Stage::Mesh,
            &["positions is empty", "at least one vertex"],
        )
        .cli(E(&["OBJ line 1", "no 'v' lines"])),
        Case::new(
            "face_sizes_sum_below_index_count",
            cube_with(|_, _, s| {
                s.pop();
            }),
            Stage::Mesh,
            &["faceSizes sum to 20", "indices has 24 entries"],
        )
        .cli(NA(NO_OBJ_SIZES)),
        Case::new(
            "face_sizes_sum_above_index_count",
            cube_with(|_, _, s| s.push(4)),
            Stage::Mesh,
            &["faceSizes sum to 28", "indices has 24 entries"],
        )
        .cli(NA(NO_OBJ_SIZES)),
        Case::new(
            "face_sizes_sum_overflows_u32",
            cube_with(|_, _, s| *s = vec![u32::MAX, 25]),
            Stage::Mesh,
            &["faceSizes sum to 4294967320", "indices has 24 entries"],
        )
        .cli(NA(NO_OBJ_SIZES)),
        Case::new(
            "implicit_triangles_with_leftover_indices",
            Input::Arrays {
                positions: tetrahedron().0,
                indices: tetrahedron().1[..10].to_vec(),
                face_sizes: None,
            },
            Stage::Mesh,
            &["indices has 10 entries", "not a multiple of 3", "faceSizes"],
        )
        .rust(NA("PolyMesh always has face_sizes"))
        .cli(NA(NO_OBJ_SIZES)),
        // -- indices
        Case::new(
            "index_out_of_range",
            cube_with(|_, i, _| i[5] = 99),
            Stage::Mesh,
            &["face 1", "indices[5]", "vertex 99", "only 8 vertices"],
        )
        .cli(E(&["OBJ line 10", "vertex 100", "only 8 vertices"])),
        Case::new(
            "index_one_past_the_end",
            cube_with(|_, i, _| i[23] = 8),
            Stage::Mesh,
            &["face 5", "indices[23]", "vertex 8", "(0..7)"],
        )
        .cli(E(&["OBJ line 14", "vertex 9", "only 8 vertices"])),
        Case::new(
            "index_u32_max",
            cube_with(|_, i, _| i[0] = u32::MAX),
            Stage::Mesh,
            &["face 0", "indices[0]", "vertex 4294967295"],
        )
        .cli(E(&["OBJ line 9", "face index 4294967296 is too large"])),
        // -- faces
        Case::new(
            "face_with_two_vertices",
            arrays(points(3), vec![0, 1, 2, 0, 1], vec![3, 2]),
            Stage::Mesh,
            &["face 1 has 2 vertices", "at least 3"],
        )
        .cli(E(&["OBJ line 5", "face has 2 vertices", "at least 3"])),
        Case::new(
            "face_with_no_vertices",
            arrays(points(3), vec![0, 1, 2], vec![0, 3]),
            Stage::Mesh,
            &["face 0 has 0 vertices"],
        )
        .cli(E(&["OBJ line 4", "face has 0 vertices"])),
        // A face may repeat a vertex (OpenSubdiv accepts it: catmull-clark, loop, bilinear and
        // midpoint do too); the schemes that cannot take it refuse it.
        Case::new(
            "face_repeats_a_neighbouring_vertex_doo_sabin",
            arrays(points(3), vec![0, 1, 1], vec![3]),
            Stage::Subdivide,
            &[
                "level 1: face 0 repeats vertex 1",
                "doo-sabin needs faces with distinct vertices",
                "use catmull-clark, loop or bilinear",
            ],
        )
        .opt("scheme", Str("doo-sabin")),
        Case::new(
            "face_repeats_a_distant_vertex_quad_triangle",
            cube_with(|_, i, _| i[10] = 0),
            Stage::Subdivide,
            &["face 2 repeats vertex 0", "quad-triangle needs faces with distinct vertices"],
        )
        .opt("scheme", Str("quad-triangle")),
        Case::new(
            "face_repeats_a_vertex_sqrt3",
            arrays(points(4), vec![0, 1, 2, 2, 1, 1], vec![3, 3]),
            Stage::Subdivide,
            &["face 1 repeats vertex 1", "sqrt3 needs faces with distinct vertices"],
        )
        .opt("scheme", Str("sqrt3")),
        // -- coordinates
        Case::new(
            "nan_coordinate",
            cube_with(|p, _, _| p[7] = f32::NAN),
            Stage::Mesh,
            &["vertex 2", "coordinate y", "NaN", "finite"],
        )
        .cli(E(&["OBJ line 3", "'NaN'", "not a finite"])),
        Case::new(
            "infinite_coordinate",
            cube_with(|p, _, _| p[12] = f32::INFINITY),
            Stage::Mesh,
            &["vertex 4", "coordinate x", "inf", "finite"],
        )
        .cli(E(&["OBJ line 5", "'inf'", "not a finite"])),
        Case::new(
            "negative_infinite_coordinate",
            cube_with(|p, _, _| p[23] = f32::NEG_INFINITY),
            Stage::Mesh,
            &["vertex 7", "coordinate z", "-inf", "finite"],
        )
        .cli(E(&["OBJ line 8", "'-inf'", "not a finite"])),
        // Finite, but sums of such values overflow f32 (a fuzzed OBJ file found it).
        Case::new(
            "too_large_coordinate",
            cube_with(|p, _, _| p[13] = 1e38),
            Stage::Mesh,
            &["vertex 4", "coordinate y", "within ±1e30", "scale them down"],
        )
        .cli(E(&["OBJ line 5", "too large", "within ±1e30"])),
        // -- topology some schemes refuse (catmull-clark and loop take it as creases)
        Case::new(
            "non_manifold_edge_doo_sabin",
            book(),
            Stage::Subdivide,
            &["doo-sabin needs a manifold mesh", "edge between vertices 0 and 1"],
        )
        .opt("scheme", Str("doo-sabin")),
        Case::new(
            "non_manifold_edge_sqrt3",
            book(),
            Stage::Subdivide,
            &["sqrt3 needs a manifold mesh", "edge between vertices 0 and 1"],
        )
        .opt("scheme", Str("sqrt3")),
        Case::new(
            "non_manifold_vertex_doo_sabin",
            bowtie(),
            Stage::Subdivide,
            &["doo-sabin needs a manifold mesh", "vertex 0", "more than one fan"],
        )
        .opt("scheme", Str("doo-sabin")),
        Case::new(
            "non_manifold_vertex_sqrt3",
            bowtie(),
            Stage::Subdivide,
            &["sqrt3 needs a manifold mesh", "vertex 0", "more than one fan"],
        )
        .opt("scheme", Str("sqrt3")),
        Case::new(
            "inconsistent_orientation_doo_sabin",
            misoriented_pair(),
            Stage::Subdivide,
            &["doo-sabin", "edge between vertices 0 and 1", "facing the same way"],
        )
        .opt("scheme", Str("doo-sabin")),
        Case::new(
            "inconsistent_orientation_sqrt3",
            misoriented_pair(),
            Stage::Subdivide,
            &["sqrt3", "edge between vertices 0 and 1", "facing the same way"],
        )
        .opt("scheme", Str("sqrt3")),
        Case::new(
            "duplicated_face_doo_sabin",
            cube_with(|_, i, s| {
                i.extend_from_slice(&[1, 3, 7, 5]);
                s.push(4);
            }),
            Stage::Subdivide,
            &["level 1", "doo-sabin needs a manifold mesh", "edge between vertices"],
        )
        .opt("scheme", Str("doo-sabin")),
        Case::new(
            "duplicated_face_sqrt3",
            {
                let (p, mut i, mut s) = tetrahedron();
                i.extend_from_slice(&[0, 1, 2]);
                s.push(3);
                arrays(p, i, s)
            },
            Stage::Subdivide,
            &["level 1", "sqrt3 needs a manifold mesh", "edge between vertices"],
        )
        .opt("scheme", Str("sqrt3")),
        // -- schemes given faces they are not defined on
        Case::new(
            "loop_on_quads",
            cube_with(|_, _, _| {}),
            Stage::Subdivide,
            &["level 1", "loop is defined on triangles only", "face 0", "has 4 vertices"],
        )
        .opt("scheme", Str("loop")),
        Case::new(
            "midpoint_on_quads",
            cube_with(|_, _, _| {}),
            Stage::Subdivide,
            &["level 1", "midpoint is defined on triangles only", "face 0", "has 4 vertices"],
        )
        .opt("scheme", Str("midpoint")),
        Case::new(
            "sqrt3_on_quads",
            cube_with(|_, _, _| {}),
            Stage::Subdivide,
            &["level 1", "sqrt3 is defined on triangles only", "face 0", "has 4 vertices"],
        )
        .opt("scheme", Str("sqrt3")),
        Case::new(
            "loop_on_a_pentagon_among_triangles",
            arrays(points(6), vec![0, 1, 2, 2, 1, 3, 4, 5], vec![3, 5]),
            Stage::Subdivide,
            &["level 1", "loop is defined on triangles only", "face 1", "has 5 vertices"],
        )
        .opt("scheme", Str("loop")),
        Case::new(
            "loop_after_catmull_clark",
            {
                let (p, i, s) = tetrahedron();
                arrays(p, i, s)
            },
            Stage::Subdivide,
            &["level 2", "loop is defined on triangles only", "the previous level's result"],
        )
        .opt("scheme", List(&["catmull-clark", "loop"])),
        Case::new(
            "boundary_none_with_quad_triangle",
            cube_with(|_, _, _| {}),
            Stage::Subdivide,
            &["level 1", "boundary 'none'", "quad-triangle", "'edge-and-corner'"],
        )
        .opt("scheme", Str("quad-triangle"))
        .opt("boundary", Str("none")),
        // -- option values
        Case::new(
            "unknown_scheme",
            cube_with(|_, _, _| {}),
            Stage::Options,
            &["unknown scheme 'loopy'", "'catmull-clark'", "'loop'", "'doo-sabin'"],
        )
        .opt("scheme", Str("loopy")),
        Case::new(
            "scheme_name_in_the_wrong_case",
            cube_with(|_, _, _| {}),
            Stage::Options,
            &["unknown scheme 'Catmull-Clark'", "'catmull-clark'"],
        )
        .opt("scheme", Str("Catmull-Clark")),
        Case::new(
            "unknown_scheme_in_a_per_level_list",
            cube_with(|_, _, _| {}),
            Stage::Options,
            &["unknown scheme 'nope'"],
        )
        .opt("scheme", List(&["catmull-clark", "nope"]))
        .js(E(&["scheme[1]", "unknown scheme 'nope'"])),
        Case::new(
            "scheme_of_the_wrong_type",
            cube_with(|_, _, _| {}),
            Stage::Options,
            &["scheme must be one of", "'catmull-clark'", "got 3"],
        )
        .opt("scheme", Num(3.0))
        .rust(NA(RUST_TYPED))
        .cli(NA("command-line values are text")),
        Case::new(
            "unknown_boundary",
            cube_with(|_, _, _| {}),
            Stage::Options,
            &["unknown boundary 'sharp'", "'edge-and-corner'", "'edge-only'"],
        )
        .opt("boundary", Str("sharp")),
        Case::new(
            "boundary_of_the_wrong_type",
            cube_with(|_, _, _| {}),
            Stage::Options,
            &["boundary must be one of", "got boolean true"],
        )
        .opt("boundary", Val::Bool(true))
        .rust(NA(RUST_TYPED))
        .cli(NA("command-line values are text")),
        // -- option keys
        Case::new(
            "unknown_option_key",
            cube_with(|_, _, _| {}),
            Stage::Options,
            &["unknown option 'level'", "did you mean 'levels'", "'scheme'", "'maxFaces'"],
        )
        .opt("level", Num(2.0))
        .rust(NA(RUST_NO_KEYS))
        .cli(E(&["unknown option '--level'"])),
        Case::new(
            "unknown_option_key_unlike_any",
            cube_with(|_, _, _| {}),
            Stage::Options,
            &["unknown option 'smoothness'", "'levels'"],
        )
        .opt("smoothness", Num(0.5))
        .rust(NA(RUST_NO_KEYS))
        .cli(E(&["unknown option '--smoothness'"])),
        Case::new(
            "options_not_an_object",
            cube_with(|_, _, _| {}),
            Stage::Options,
            &["options must be an object", "got string 'catmull-clark'"],
        )
        .only_js("only JS passes options as one value")
        .with_options_value(Str("catmull-clark")),
        // -- levels
        Case::new(
            "levels_negative",
            cube_with(|_, _, _| {}),
            Stage::Options,
            &["levels must be a whole number from 0 to 32", "got -1"],
        )
        .opt("levels", Num(-1.0))
        .rust(NA(RUST_TYPED))
        .cli(E(&["--levels '-1' is not a whole number"])),
        Case::new(
            "levels_fractional",
            cube_with(|_, _, _| {}),
            Stage::Options,
            &["levels must be a whole number", "got 1.5"],
        )
        .opt("levels", Num(1.5))
        .rust(NA(RUST_TYPED))
        .cli(E(&["--levels '1.5' is not a whole number"])),
        Case::new(
            "levels_not_a_number",
            cube_with(|_, _, _| {}),
            Stage::Options,
            &["levels must be a whole number", "got string 'two'"],
        )
        .opt("levels", Str("two"))
        .rust(NA(RUST_TYPED))
        .cli(E(&["--levels 'two' is not a whole number"])),
        Case::new(
            "levels_nan",
            cube_with(|_, _, _| {}),
            Stage::Options,
            &["levels must be a whole number", "got NaN"],
        )
        .opt("levels", Num(f64::NAN))
        .rust(NA(RUST_TYPED))
        .cli(E(&["--levels 'NaN' is not a whole number"])),
        Case::new(
            "levels_too_many",
            cube_with(|_, _, _| {}),
            Stage::Subdivide,
            &["33 levels is more than the 32 subsurf accepts"],
        )
        .opt("levels", Num(33.0))
        .js(E(&["levels must be a whole number from 0 to 32", "got 33"]))
        .cli(E(&["--levels 33 is more than the 32 subsurf accepts"])),
        Case::new(
            "levels_a_million",
            cube_with(|_, _, _| {}),
            Stage::Subdivide,
            &["1000000 levels is more than the 32 subsurf accepts"],
        )
        .opt("levels", Num(1e6))
        .js(E(&["levels must be a whole number from 0 to 32", "got 1000000"]))
        .cli(E(&["--levels 1000000 is more than the 32 subsurf accepts"])),
        Case::new(
            "scheme_list_and_levels_disagree",
            cube_with(|_, _, _| {}),
            Stage::Options,
            &["scheme lists 2 schemes", "levels is 3"],
        )
        .opt("scheme", List(&["catmull-clark", "catmull-clark"]))
        .opt("levels", Num(3.0))
        .rust(NA("Options holds the list, whose length is the number of levels"))
        .cli(E(&["--scheme lists 2 schemes but --levels is 3"])),
        // -- the memory guard
        Case::new(
            "max_faces_exceeded",
            cube_with(|_, _, _| {}),
            Stage::Subdivide,
            &["3 level(s) would make 384 faces", "more than the limit of 100", "maxFaces"],
        )
        .opt("levels", Num(3.0))
        .opt("maxFaces", Num(100.0))
        .cli(E(&["3 level(s) would make 384 faces", "limit of 100", "--max-faces"])),
        Case::new(
            "default_max_faces_exceeded",
            cube_with(|_, _, _| {}),
            Stage::Subdivide,
            &["11 level(s) would make 25165824 faces", "limit of 16777216", "maxFaces"],
        )
        .opt("levels", Num(11.0)),
        Case::new(
            "max_faces_zero",
            cube_with(|_, _, _| {}),
            Stage::Subdivide,
            &["1 level(s) would make 24 faces", "limit of 0"],
        )
        .opt("maxFaces", Num(0.0))
        .js(E(&["maxFaces must be a whole number from 1", "got 0"])),
        Case::new(
            "max_faces_negative",
            cube_with(|_, _, _| {}),
            Stage::Options,
            &["maxFaces must be a whole number", "got -5"],
        )
        .opt("maxFaces", Num(-5.0))
        .rust(NA(RUST_TYPED))
        .cli(E(&["--max-faces '-5' is not a whole number"])),
        Case::new(
            "max_faces_fractional",
            cube_with(|_, _, _| {}),
            Stage::Options,
            &["maxFaces must be a whole number", "got 99.5"],
        )
        .opt("maxFaces", Num(99.5))
        .rust(NA(RUST_TYPED))
        .cli(E(&["--max-faces '99.5' is not a whole number"])),
        Case::new("levels_u32_max", cube_with(|_, _, _| {}), Stage::Options, &[])
            .opt("levels", Num(4294967295.0))
            .js(E(&["levels must be a whole number from 0 to 32", "got 4294967295"]))
            .rust(NA("the caller builds the per-level list of Options::schemes"))
            .cli(E(&["--levels", "4294967295", "32"])),
        Case::new("levels_beyond_the_prediction", cube_with(|_, _, _| {}), Stage::Subdivide, &[])
            .opt("levels", Num(40.0))
            .opt("maxFaces", Num(1e18))
            .js(E(&["levels must be a whole number from 0 to 32", "got 40"]))
            .rust(E(&["40 levels is more than the 32 subsurf accepts"]))
            .cli(E(&["--levels 40 is more than the 32 subsurf accepts"])),
        Case::new("max_bytes_exceeded", cube_with(|_, _, _| {}), Stage::Subdivide, &[])
            .opt("levels", Num(3.0))
            .opt("maxBytes", Num(1000.0))
            .rust(E(&[
                "3 level(s) would make a result of 21528 bytes",
                "limit of 1000 bytes",
                "maxBytes",
            ]))
            .js(E(&[
                "3 level(s) would make a result of 21528 bytes",
                "limit of 1000 bytes",
                "maxBytes",
            ]))
            .cli(E(&[
                "3 level(s) would make a result of 21528 bytes",
                "limit of 1000 bytes",
                "--max-bytes",
            ])),
        Case::new("result_beyond_wasm_memory", cube_with(|_, _, _| {}), Stage::Subdivide, &[])
            .opt("levels", Num(16.0))
            .opt("maxFaces", Num(9_007_199_254_740_991.0))
            .rust(NA("native memory is not limited to 4 GiB"))
            .cli(NA("native memory is not limited to 4 GiB"))
            .js(E(&[
                "16 level(s) would make a result of",
                "limit of 1073741824 bytes",
                "maxBytes",
            ])),
        // -- JS mesh objects
        Case::new(
            "indices_as_float32array",
            {
                let (p, i, s) = js_cube_fields();
                let JsField::Uint32(i) = i else { unreachable!() };
                js_mesh(p, JsField::Float32(i.iter().map(|&x| x as f32).collect()), s)
            },
            Stage::Mesh,
            &["mesh.indices must be a Uint32Array, got Float32Array", "new Uint32Array"],
        )
        .only_js("Rust and OBJ have no typed arrays"),
        Case::new(
            "indices_as_int32array",
            {
                let (p, i, s) = js_cube_fields();
                let JsField::Uint32(i) = i else { unreachable!() };
                js_mesh(p, JsField::Int32(i.iter().map(|&x| x as i32).collect()), s)
            },
            Stage::Mesh,
            &["mesh.indices must be a Uint32Array, got Int32Array"],
        )
        .only_js("Rust and OBJ have no typed arrays"),
        Case::new(
            "face_sizes_as_uint8array",
            {
                let (p, i, _) = js_cube_fields();
                js_mesh(p, i, JsField::Uint8(vec![4; 6]))
            },
            Stage::Mesh,
            &["mesh.faceSizes must be a Uint32Array, got Uint8Array"],
        )
        .only_js("Rust and OBJ have no typed arrays"),
        Case::new(
            "face_sizes_as_plain_array",
            {
                let (p, i, _) = js_cube_fields();
                js_mesh(p, i, JsField::Plain(vec![4.0; 6]))
            },
            Stage::Mesh,
            &["mesh.faceSizes must be a Uint32Array, got Array", "new Uint32Array"],
        )
        .only_js("Rust and OBJ have no typed arrays"),
        Case::new(
            "positions_as_float64array",
            {
                let (p, i, s) = js_cube_fields();
                let JsField::Float32(p) = p else { unreachable!() };
                js_mesh(JsField::Float64(p.iter().map(|&x| x as f64).collect()), i, s)
            },
            Stage::Mesh,
            &["mesh.positions must be a Float32Array, got Float64Array"],
        )
        .only_js("Rust and OBJ have no typed arrays"),
        Case::new(
            "positions_missing",
            {
                let (_, i, s) = js_cube_fields();
                js_mesh(JsField::Missing, i, s)
            },
            Stage::Mesh,
            &["mesh.positions is missing", "Float32Array"],
        )
        .only_js("Rust and OBJ have no missing fields"),
        Case::new(
            "indices_missing",
            {
                let (p, _, s) = js_cube_fields();
                js_mesh(p, JsField::Missing, s)
            },
            Stage::Mesh,
            &["mesh.indices is missing", "Uint32Array"],
        )
        .only_js("Rust and OBJ have no missing fields"),
        Case::new(
            "mesh_field_typo",
            {
                let (p, i, _) = js_cube_fields();
                Input::Js(JsMesh {
                    positions: p,
                    indices: i,
                    face_sizes: JsField::Missing,
                    extra: Some("faceSize"),
                    not_an_object: None,
                })
            },
            Stage::Mesh,
            &["unknown mesh field 'faceSize'", "did you mean 'faceSizes'"],
        )
        .only_js("Rust and OBJ have no field names"),
        Case::new(
            "mesh_not_an_object",
            Input::Js(JsMesh {
                positions: JsField::Missing,
                indices: JsField::Missing,
                face_sizes: JsField::Missing,
                extra: None,
                not_an_object: Some(Num(7.0)),
            }),
            Stage::Mesh,
            &["mesh must be an object", "got 7"],
        )
        .only_js("Rust and OBJ have no such value"),
        // -- OBJ files
        Case::new(
            "obj_empty_file",
            Input::Obj(String::new()),
            Stage::Obj,
            &["OBJ line 1", "no 'v' lines"],
        ),
        Case::new(
            "obj_garbage_text",
            Input::Obj("hello world\nthis is not an OBJ file\n".into()),
            Stage::Obj,
            &["OBJ line 2", "no 'v' lines"],
        ),
        Case::new(
            "obj_binary_garbage",
            Input::ObjBytes(vec![0x7f, b'E', b'L', b'F', 0xff, 0xfe, 0x00, b'\n', b'v', 0xc3]),
            Stage::Obj,
            &[],
        )
        .rust(NA("read_obj takes a &str"))
        .js(NA("a JS string is always text"))
        .cli(E(&["cannot read", "valid UTF-8"])),
        Case::new(
            "obj_truncated_vertex_line",
            Input::Obj("v 0 0 0\nv 1 0 0\nv 0 1\nf 1 2 3\n".into()),
            Stage::Obj,
            &["OBJ line 3", "vertex has 2 coordinates", "x y z"],
        ),
        Case::new(
            "obj_truncated_face_line",
            obj_triangle_then("f 1 2"),
            Stage::Obj,
            &["OBJ line 4", "face has 2 vertices"],
        ),
        Case::new(
            "obj_face_index_zero",
            obj_triangle_then("f 0 1 2"),
            Stage::Obj,
            &["OBJ line 4", "face index 0", "start at 1"],
        ),
        Case::new(
            "obj_face_refers_to_a_missing_vertex",
            obj_triangle_then("f 1 2 7"),
            Stage::Obj,
            &["OBJ line 4", "vertex 7", "only 3 vertices"],
        ),
        Case::new(
            "obj_relative_index_before_the_first_vertex",
            obj_triangle_then("f -1 -2 -5"),
            Stage::Obj,
            &["OBJ line 4", "relative index -5", "3 defined so far"],
        ),
        Case::new(
            "obj_face_index_beyond_u32",
            obj_triangle_then("f 1 2 4294967297"),
            Stage::Obj,
            &["OBJ line 4", "face index 4294967297 is too large"],
        ),
        Case::new(
            "obj_face_index_beyond_i64",
            obj_triangle_then("f 1 2 99999999999999999999999"),
            Stage::Obj,
            &["OBJ line 4", "'99999999999999999999999'"],
        ),
        Case::new(
            "obj_huge_coordinate",
            Input::Obj("v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n".into()),
            Stage::Obj,
            &["OBJ line 2", "'1e39'", "not a finite"],
        ),
        Case::new(
            "obj_nan_coordinate",
            Input::Obj("v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n".into()),
            Stage::Obj,
            &["OBJ line 3", "'nan'", "not a finite"],
        ),
        Case::new(
            "obj_coordinate_not_a_number",
            Input::Obj("v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n".into()),
            Stage::Obj,
            &["OBJ line 2", "'x' is not a number"],
        ),
        Case::new(
            "obj_face_word_not_an_index",
            obj_triangle_then("f 1 2 three"),
            Stage::Obj,
            &["OBJ line 4", "'three' is not a face index"],
        ),
        Case::new(
            "obj_face_repeats_a_vertex_doo_sabin",
            obj_triangle_then("f 1 2 1"),
            Stage::Subdivide,
            &["face 0 repeats vertex 0", "doo-sabin needs faces with distinct vertices"],
        )
        .opt("scheme", Str("doo-sabin")),
        // -- OBJ texture coordinates (the face-varying channel 'uv')
        Case::new(
            "obj_vt_missing_on_some_corners",
            Input::Obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nf 1/1 2 3/2\n".into()),
            Stage::Obj,
            &["OBJ line 6", "corner '2'", "no texture coordinate", "attribute 'uv'"],
        ),
        Case::new(
            "obj_vt_missing_on_a_later_face",
            Input::Obj(
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 2 4 3\n".into(),
            ),
            Stage::Obj,
            &["OBJ line 7", "corner '2'", "'uv'", "face on line 6 gives them"],
        ),
        Case::new(
            "obj_vt_index_out_of_range",
            Input::Obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nf 1/1 2/2 3/5\n".into()),
            Stage::Obj,
            &["OBJ line 6", "texture coordinate 5", "'uv'", "only 2 'vt' lines"],
        ),
        Case::new(
            "obj_vt_relative_index_before_the_first",
            obj_triangle_then("vt 0 0\nf 1/-1 2/-2 3/-1"),
            Stage::Obj,
            &["OBJ line 5", "relative texture coordinate index -2", "1 defined so far"],
        ),
        Case::new(
            "obj_vt_coordinate_not_a_number",
            Input::Obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 x\nf 1/1 2/1 3/1\n".into()),
            Stage::Obj,
            &["OBJ line 4", "'x' is not a number"],
        ),
        // -- attribute channels (the cube: 8 vertices, 24 face corners)
        attribute_case(
            "channel_wrong_length",
            channel("color", 3.0, JsField::Float32(vec![0.5; 21]), None),
            &["attribute 'color'", "7 values", "8 vertices"],
        ),
        attribute_case(
            "channel_not_a_multiple_of_item_size",
            channel("color", 3.0, JsField::Float32(vec![0.5; 23]), None),
            &["attribute 'color'", "23 values", "multiple of itemSize 3"],
        ),
        attribute_case(
            "channel_item_size_zero",
            channel("w", 0.0, JsField::Float32(vec![]), None),
            &["attribute 'w'", "itemSize", "1 to 16"],
        ),
        attribute_case(
            "channel_item_size_above_16",
            channel("w", 17.0, JsField::Float32(vec![0.0; 17 * 8]), None),
            &["attribute 'w'", "itemSize", "17"],
        ),
        attribute_case(
            "channel_item_size_not_whole",
            channel("w", 2.5, JsField::Float32(vec![0.0; 20]), None),
            &["attribute 'w'", "itemSize must be a whole number", "2.5"],
        )
        .rust(NA(JS_ONLY_CHANNEL)),
        attribute_case(
            "channel_array_of_the_wrong_type",
            channel("color", 3.0, JsField::Float64(vec![0.5; 24]), None),
            &["attributes.color.array must be a Float32Array", "Float64Array"],
        )
        .rust(NA(JS_ONLY_CHANNEL)),
        attribute_case(
            "channel_nan",
            channel(
                "w",
                1.0,
                JsField::Float32([vec![0.0; 5], vec![f32::NAN], vec![0.0; 2]].concat()),
                None,
            ),
            &["attribute 'w'", "value 5", "NaN", "finite"],
        ),
        attribute_case(
            "channel_infinity",
            channel(
                "w",
                1.0,
                JsField::Float32([vec![0.0; 2], vec![f32::INFINITY], vec![0.0; 5]].concat()),
                None,
            ),
            &["attribute 'w'", "value 2", "inf"],
        ),
        attribute_case(
            "channel_too_large",
            channel(
                "w",
                1.0,
                JsField::Float32([vec![0.0; 3], vec![-1e35], vec![0.0; 4]].concat()),
                None,
            ),
            &["attribute 'w'", "value 3", "within ±1e30"],
        ),
        attribute_case(
            "channel_unknown_field",
            Input::Channel(Channel {
                name: "uv",
                item_size: 2.0,
                array: JsField::Float32(vec![0.0; 16]),
                indices: None,
                extra: Some("indice"),
            }),
            &["attribute 'uv'", "unknown channel field 'indice'", "did you mean 'indices'"],
        )
        .rust(NA(JS_ONLY_CHANNEL)),
        attribute_case(
            "channel_indices_wrong_length",
            channel("uv", 2.0, JsField::Float32(vec![0.0; 8]), Some(JsField::Uint32(vec![0; 23]))),
            &["attribute 'uv'", "23 indices", "24 face corners"],
        ),
        attribute_case(
            "channel_indices_out_of_range",
            channel(
                "uv",
                2.0,
                JsField::Float32(vec![0.0; 8]),
                Some(JsField::Uint32([vec![0; 23], vec![4]].concat())),
            ),
            &["attribute 'uv'", "index 23 is 4", "4 values (0..3)"],
        ),
        attribute_case(
            "channel_indices_of_the_wrong_type",
            channel("uv", 2.0, JsField::Float32(vec![0.0; 8]), Some(JsField::Int32(vec![0; 24]))),
            &["attributes.uv.indices must be a Uint32Array", "Int32Array"],
        )
        .rust(NA(JS_ONLY_CHANNEL)),
        Case::new(
            "obj_valid_file_but_loop_on_a_quad",
            Input::Obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n".into()),
            Stage::Subdivide,
            &["loop is defined on triangles only", "face 0", "has 4 vertices"],
        )
        .opt("scheme", Str("loop")),
    ]
}

impl Case {
    fn with_options_value(mut self, value: Val) -> Self {
        self.options.not_an_object = Some(value);
        self
    }
}
