//! Wavefront OBJ: `v`, `vt` and `f` lines in and out; OpenSubdiv's `t` tag lines in.
//!
//! Faces may use the `v`, `v/vt`, `v//vn` and `v/vt/vn` forms and negative (relative) indices.
//! [`read_obj_with_tags`] (and [`read_obj_with`] when asked) reads the texture coordinates into
//! a face-varying channel named `uv`: the `vt` lines are its values (`u` and `v`; a third
//! component `w` is dropped, a missing `v` is 0), and each face corner's `vt` index is its value
//! index, so a vertex on a UV seam has one value per side. Either every face corner of a file
//! gives a `vt` index or none does. [`read_obj`] reads positions and faces only. Comments and
//! every other line (`vn`, `g`, `o`, `s`, `usemtl`, ...) are skipped; `t` lines are read by
//! [`read_obj_with_tags`] (syntax in `DEVELOPERS.md`, section "OBJ tags"). Errors give the
//! 1-based line number.

use super::text;
use crate::attributes::{self, Attribute};
use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use crate::options::Boundary;
use crate::tags::{Corner, Crease, CreaseMethod, Tags};
use std::collections::HashSet;

/// The name of the face-varying channel that holds an OBJ file's texture coordinates.
pub const UV: &str = "uv";

fn obj_error(line: usize, message: impl Into<String>) -> Error {
    Error::Obj { line, message: message.into() }
}

/// An OBJ file's mesh with the OpenSubdiv tags and the texture coordinates it carries.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ObjMesh {
    pub mesh: PolyMesh,
    /// Creases, corners, holes, `creasemethod` and `smoothtriangles`.
    pub tags: Tags,
    /// The file's `interpolateboundary` tag: 0 `None`, 1 `EdgeAndCorner`, 2 `EdgeOnly`; `None`
    /// (no value) when the file has no such tag.
    pub boundary: Option<Boundary>,
    /// The face-varying channel [`UV`] (2 floats per value, one index per face corner) when the
    /// file's faces give `vt` indices; empty otherwise. Ready for
    /// [`crate::scheme::subdivide_with_attributes`].
    pub attributes: Vec<Attribute>,
}

/// What [`read_obj_with`] reads besides the `v` and `f` lines.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ObjReadOptions {
    /// OpenSubdiv's `t` tag lines; skipped (even malformed ones) when false.
    pub tags: bool,
    /// `vt` lines and the `vt` indices of face corners, as the channel [`UV`]; skipped when false.
    pub uv: bool,
}

/// Parses OBJ text into a [`PolyMesh`]. Structural checks (face sizes, indices, NaN) happen here
/// too, so that the error can name the line. A face may repeat a vertex (as OpenSubdiv's
/// regression shapes do; see [`crate::HalfEdgeMesh`]). `t` and `vt` lines and the `vt` indices
/// of face corners are skipped.
pub fn read_obj(text: &str) -> Result<PolyMesh> {
    read_obj_with(text, ObjReadOptions::default()).map(|obj| obj.mesh)
}

/// Parses OBJ text, its OpenSubdiv `t` tags (`crease`, `corner`, `hole`,
/// `interpolateboundary`, `creasemethod`, `smoothtriangles`) and its texture coordinates (the
/// face-varying channel [`UV`]). Hierarchical edits (`vertexedit`, `edgeedit`, `faceedit`),
/// face-varying tags and unknown tag names are skipped. A malformed tag (counts that do not
/// match its values, a vertex, edge or face the file does not have, a negative or NaN
/// sharpness, an unknown option value), a malformed `vt` line, a `vt` index the file does not
/// have, or faces that give `vt` indices on some corners and not on others are errors naming
/// the line.
pub fn read_obj_with_tags(text: &str) -> Result<ObjMesh> {
    read_obj_with(text, ObjReadOptions { tags: true, uv: true })
}

/// Parses OBJ text, reading tags and texture coordinates as `options` says (the command line's
/// `--ignore-tags` reads the UVs but not the tags).
pub fn read_obj_with(text: &str, options: ObjReadOptions) -> Result<ObjMesh> {
    read(text, options)
}

/// The texture coordinates of a file as they are read: the `vt` values, the value index of each
/// face corner, and whether the corners give one (decided by the first face, with its line).
#[derive(Default)]
struct UvReader {
    values: Vec<f32>,
    indices: Vec<u32>,
    /// `(corners give vt indices, line of the first face)`.
    form: Option<(bool, usize)>,
}

impl UvReader {
    /// `vt u [v [w]]`: `v` defaults to 0 and `w` is dropped, as the channel has two floats.
    fn value(&mut self, mut words: std::str::SplitWhitespace, line: usize) -> Result<()> {
        let u = words.next().ok_or_else(|| {
            obj_error(line, "texture coordinate has no values; 'vt' needs u [v [w]]")
        })?;
        self.values.push(parse_coordinate(u, line)?);
        let v = match words.next() {
            Some(word) => parse_coordinate(word, line)?,
            None => 0.0,
        };
        self.values.push(v);
        if let Some(w) = words.next() {
            parse_coordinate(w, line)?;
        }
        Ok(())
    }

    /// The `vt` part of face corner `word` (`7/2`, `7/2/3`, `7//3`, `7`), if any.
    fn corner(&mut self, word: &str, line: usize) -> Result<()> {
        let vt = word.split('/').nth(1).filter(|t| !t.is_empty());
        let (given, first_line) = *self.form.get_or_insert((vt.is_some(), line));
        match (vt, given) {
            (Some(vt), true) => {
                let count = self.values.len() / 2;
                let index = resolve_index(vt, word, count, line, "texture coordinate", "'vt' line")?;
                self.indices.push(index);
            }
            (None, false) => {}
            (Some(_), false) => {
                return Err(obj_error(
                    line,
                    format!(
                        "face corner '{word}' gives a texture coordinate (attribute '{UV}'), but the face on line {first_line} gives none; give every face corner a vt index (v/vt) or none"
                    ),
                ))
            }
            (None, true) => {
                return Err(obj_error(
                    line,
                    format!(
                        "face corner '{word}' has no texture coordinate (attribute '{UV}'), but the face on line {first_line} gives them; give every face corner a vt index (v/vt) or none"
                    ),
                ))
            }
        }
        Ok(())
    }

    /// The channel, once every `vt` line is known: each index is checked against them.
    fn finish(self, face_sizes: &[u32], face_lines: &[usize]) -> Result<Vec<Attribute>> {
        if self.form.is_none_or(|(given, _)| !given) {
            return Ok(Vec::new());
        }
        let count = self.values.len() / 2;
        if let Some(k) = self.indices.iter().position(|&t| t as usize >= count) {
            // The face of corner k: the first whose corners reach past it.
            let mut end = 0usize;
            let face = face_sizes.iter().position(|&n| {
                end += n as usize;
                end > k
            });
            let line = face.map_or(1, |f| face_lines[f]);
            return Err(obj_error(
                line,
                format!(
                    "face refers to texture coordinate {} (attribute '{UV}'), but the file has only {count} 'vt' lines",
                    self.indices[k] as u64 + 1
                ),
            ));
        }
        Ok(vec![Attribute::face_varying(UV, 2, self.values, self.indices)])
    }
}

fn read(text: &str, options: ObjReadOptions) -> Result<ObjMesh> {
    let mut mesh = PolyMesh::default();
    // Line of each face, to name it when a later check fails.
    let mut face_lines: Vec<usize> = Vec::new();
    let mut tags: Vec<RawTag> = Vec::new();
    let mut uv = UvReader::default();
    for (number, raw) in text.lines().enumerate() {
        let line_no = number + 1;
        let line = before(raw, b'#').trim();
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let mut xyz = [0.0f32; 3];
                for (k, slot) in xyz.iter_mut().enumerate() {
                    let word = words.next().ok_or_else(|| {
                        obj_error(line_no, format!("vertex has {k} coordinates; 'v' needs x y z"))
                    })?;
                    *slot = parse_coordinate(word, line_no)?;
                }
                mesh.positions.extend_from_slice(&xyz);
            }
            Some("vt") if options.uv => uv.value(words, line_no)?,
            Some("f") => {
                let vertex_count = mesh.positions.len() / 3;
                let start = mesh.indices.len();
                for word in words {
                    let index = parse_face_index(word, vertex_count, line_no)?;
                    mesh.indices.push(index);
                    if options.uv {
                        uv.corner(word, line_no)?;
                    }
                }
                let n = mesh.indices.len() - start;
                if n < 3 {
                    return Err(obj_error(
                        line_no,
                        format!("face has {n} vertices; a face needs at least 3"),
                    ));
                }
                mesh.face_sizes.push(n as u32);
                face_lines.push(line_no);
            }
            Some("t") if options.tags => {
                if let Some(tag) = parse_tag(words, line_no)? {
                    tags.push(tag);
                }
            }
            _ => {}
        }
    }
    let vertex_count = mesh.num_vertices();
    let mut start = 0usize;
    for (f, &n) in mesh.face_sizes.iter().enumerate() {
        let face = &mesh.indices[start..start + n as usize];
        if let Some(&bad) = face.iter().find(|&&i| i as usize >= vertex_count) {
            return Err(obj_error(
                face_lines[f],
                format!(
                    "face refers to vertex {}, but the file has only {vertex_count} vertices",
                    bad as u64 + 1
                ),
            ));
        }
        start += n as usize;
    }
    if vertex_count == 0 {
        return Err(obj_error(
            text.lines().count().max(1),
            "the file has no 'v' lines; a mesh needs vertices",
        ));
    }
    let attributes = uv.finish(&mesh.face_sizes, &face_lines)?;
    let mut obj = ObjMesh { mesh, attributes, ..ObjMesh::default() };
    apply_tags(&mut obj, &tags)?;
    Ok(obj)
}

/// One `t NAME nint/nfloat/nstring ints... floats... strings...` line.
struct RawTag<'a> {
    line: usize,
    name: &'a str,
    ints: Vec<i64>,
    floats: Vec<f32>,
    strings: Vec<&'a str>,
}

/// Tags that are read elsewhere or not at all: skipped without looking at their values.
const SKIPPED_TAGS: &[&str] = &[
    "vertexedit",
    "edgeedit",
    "faceedit",
    "facevaryinginterpolateboundary",
    "facevaryingpropagatecorners",
];
const KNOWN_TAGS: &[&str] =
    &["crease", "corner", "hole", "interpolateboundary", "creasemethod", "smoothtriangles"];

fn parse_tag<'a>(
    mut words: std::str::SplitWhitespace<'a>,
    line: usize,
) -> Result<Option<RawTag<'a>>> {
    let name = words
        .next()
        .ok_or_else(|| obj_error(line, "'t' needs a tag name, e.g. 't crease 2/1/0 0 1 2.5'"))?;
    if SKIPPED_TAGS.contains(&name) || !KNOWN_TAGS.contains(&name) {
        return Ok(None);
    }
    let counts = words.next().ok_or_else(|| {
        obj_error(line, format!("tag '{name}' needs its counts 'nint/nfloat/nstring'"))
    })?;
    // Counts as u32 (summed in u64): no count from a file can overflow anything.
    let parsed: Vec<Option<u32>> = counts.split('/').map(|c| c.parse().ok()).collect();
    let [Some(ni), Some(nf), Some(ns)] = parsed[..] else {
        return Err(obj_error(
            line,
            format!("tag '{name}': counts '{counts}' are not 'nint/nfloat/nstring' (e.g. 2/1/0)"),
        ));
    };
    let values: Vec<&str> = words.collect();
    let declared = ni as u64 + nf as u64 + ns as u64;
    if values.len() as u64 != declared {
        return Err(obj_error(
            line,
            format!(
                "tag '{name}' declares {ni} integers, {nf} floats and {ns} strings ({declared} values) but has {} values",
                values.len()
            ),
        ));
    }
    let (ni, nf) = (ni as usize, nf as usize);
    let ints = values[..ni]
        .iter()
        .map(|w| {
            w.parse::<i64>()
                .map_err(|_| obj_error(line, format!("tag '{name}': '{w}' is not an integer")))
        })
        .collect::<Result<Vec<_>>>()?;
    let floats = values[ni..ni + nf]
        .iter()
        .map(|w| {
            let x: f32 = w
                .parse()
                .map_err(|_| obj_error(line, format!("tag '{name}': '{w}' is not a number")))?;
            if x.is_nan() {
                return Err(obj_error(line, format!("tag '{name}': sharpness '{w}' is NaN")));
            }
            if x < 0.0 {
                return Err(obj_error(
                    line,
                    format!(
                        "tag '{name}': sharpness {w} is negative; give 0 (smooth) to 10 (infinitely sharp)"
                    ),
                ));
            }
            Ok(x)
        })
        .collect::<Result<Vec<_>>>()?;
    let strings = values[ni + nf..].to_vec();
    Ok(Some(RawTag { line, name, ints, floats, strings }))
}

impl RawTag<'_> {
    fn error(&self, message: impl std::fmt::Display) -> Error {
        obj_error(self.line, format!("tag '{}': {message}", self.name))
    }

    /// Checks the number of integers (`ints` says which counts are fine), floats and strings.
    fn check_counts(&self, ints_ok: bool, ints: &str, floats: usize, strings: usize) -> Result<()> {
        if !ints_ok {
            return Err(self.error(format!("needs {ints}, got {}", self.ints.len())));
        }
        if self.floats.len() != floats || self.strings.len() != strings {
            return Err(self.error(format!(
                "needs {floats} float(s) and {strings} string(s), got {} and {}",
                self.floats.len(),
                self.strings.len()
            )));
        }
        Ok(())
    }

    /// One sharpness per item, or one for all.
    fn sharpness(&self, items: usize) -> Result<impl Fn(usize) -> f32 + '_> {
        if self.floats.len() != 1 && self.floats.len() != items {
            return Err(self.error(format!(
                "needs one sharpness for all, or one per item ({items}), got {}",
                self.floats.len()
            )));
        }
        Ok(move |i: usize| self.floats[if self.floats.len() == 1 { 0 } else { i }])
    }

    fn index(&self, value: i64, count: usize, what: &str) -> Result<u32> {
        if value < 0 || value as u64 >= count as u64 {
            let range = if count == 0 { "none".to_string() } else { format!("0..{}", count - 1) };
            return Err(self.error(format!(
                "{what} {value} does not exist; the file has {count} {what}s ({range}, 0-based)"
            )));
        }
        Ok(value as u32)
    }

    fn string(&self, allowed: &[&str]) -> Result<&str> {
        let s = self.strings[0];
        if allowed.contains(&s) {
            Ok(s)
        } else {
            let list: Vec<String> = allowed.iter().map(|a| format!("'{a}'")).collect();
            Err(self.error(format!("unknown value '{s}'; use {}", list.join(" or "))))
        }
    }
}

fn apply_tags(obj: &mut ObjMesh, raw: &[RawTag]) -> Result<()> {
    let (vertices, faces) = (obj.mesh.num_vertices(), obj.mesh.num_faces());
    let mut edges: Option<HashSet<(u32, u32)>> = None;
    for t in raw {
        match t.name {
            "crease" => {
                let n = t.ints.len();
                t.check_counts(
                    n >= 2 && n % 2 == 0,
                    "vertex pairs (an even number of integers)",
                    t.floats.len(),
                    0,
                )?;
                let sharpness = t.sharpness(n / 2)?;
                let edges = edges.get_or_insert_with(|| face_edges(&obj.mesh));
                for (i, pair) in t.ints.chunks_exact(2).enumerate() {
                    let a = t.index(pair[0], vertices, "vertex")?;
                    let b = t.index(pair[1], vertices, "vertex")?;
                    if !edges.contains(&(a.min(b), a.max(b))) {
                        return Err(t.error(format!(
                            "vertices {a} and {b} are not joined by an edge; a crease names the two vertices of an edge"
                        )));
                    }
                    obj.tags.creases.push(Crease { vertices: [a, b], sharpness: sharpness(i) });
                }
            }
            "corner" => {
                let n = t.ints.len();
                t.check_counts(n >= 1, "one or more vertices", t.floats.len(), 0)?;
                let sharpness = t.sharpness(n)?;
                for (i, &v) in t.ints.iter().enumerate() {
                    let vertex = t.index(v, vertices, "vertex")?;
                    obj.tags.corners.push(Corner { vertex, sharpness: sharpness(i) });
                }
            }
            "hole" => {
                t.check_counts(!t.ints.is_empty(), "one or more faces", 0, 0)?;
                for &f in &t.ints {
                    obj.tags.holes.push(t.index(f, faces, "face")?);
                }
            }
            "interpolateboundary" => {
                t.check_counts(t.ints.len() == 1, "one integer (0, 1 or 2)", 0, 0)?;
                obj.boundary = Some(match t.ints[0] {
                    0 => Boundary::None,
                    1 => Boundary::EdgeAndCorner,
                    2 => Boundary::EdgeOnly,
                    other => {
                        return Err(t.error(format!(
                            "{other} is not a boundary mode; use 0 (none), 1 (edge-and-corner) or 2 (edge-only)"
                        )))
                    }
                });
            }
            "creasemethod" => {
                t.check_counts(t.ints.is_empty(), "no integers", 0, 1)?;
                obj.tags.crease_method = match t.string(&["normal", "uniform", "chaikin"])? {
                    "chaikin" => CreaseMethod::Chaikin,
                    _ => CreaseMethod::Uniform,
                };
            }
            "smoothtriangles" => {
                t.check_counts(t.ints.is_empty(), "no integers", 0, 1)?;
                obj.tags.smooth_triangles = t.string(&["catmark", "smooth"])? == "smooth";
            }
            _ => {}
        }
    }
    Ok(())
}

/// Every edge of the faces, as (smaller, larger) vertex pairs.
fn face_edges(mesh: &PolyMesh) -> HashSet<(u32, u32)> {
    let mut edges = HashSet::with_capacity(mesh.indices.len());
    let mut start = 0usize;
    for &n in &mesh.face_sizes {
        let face = &mesh.indices[start..start + n as usize];
        for (k, &a) in face.iter().enumerate() {
            let b = face[(k + 1) % face.len()];
            edges.insert((a.min(b), a.max(b)));
        }
        start += n as usize;
    }
    edges
}

fn parse_coordinate(word: &str, line: usize) -> Result<f32> {
    let value: f32 =
        word.parse().map_err(|_| obj_error(line, format!("'{word}' is not a number")))?;
    if !value.is_finite() {
        return Err(obj_error(line, format!("coordinate '{word}' is not a finite 32-bit number")));
    }
    if !crate::mesh::usable(value) {
        let why = crate::mesh::unusable_because(value, "coordinate");
        return Err(obj_error(line, format!("coordinate '{word}' is too large: {why}")));
    }
    Ok(value)
}

/// `text` up to the first `byte` (an ASCII character), or all of it: a byte search (`split` with
/// a `char` pattern was about a tenth of the CLI's time on an 80 MB file).
fn before(text: &str, byte: u8) -> &str {
    match text.bytes().position(|b| b == byte) {
        // An ASCII byte is always a character boundary.
        Some(end) => text.get(..end).unwrap_or(text),
        None => text,
    }
}

/// The 0-based position index of a face corner such as `7`, `7/2`, `7//3`, `-1/2/3`.
fn parse_face_index(word: &str, vertex_count: usize, line: usize) -> Result<u32> {
    let first = before(word, b'/');
    resolve_index(first, word, vertex_count, line, "vertex", "vertex")
}

/// The 0-based index that `text` (part of face corner `word`) names among the `count` items
/// (`what`, each defined by a `line_kind`) so far: 1-based, or negative for relative indices.
fn resolve_index(
    text: &str,
    word: &str,
    count: usize,
    line: usize,
    what: &str,
    line_kind: &str,
) -> Result<u32> {
    // Named only for a message: this runs for every face corner of a file.
    let index_name =
        || if what == "vertex" { "face index".to_string() } else { format!("{what} index") };
    let value: i64 =
        text.parse().map_err(|_| obj_error(line, format!("'{word}' is not a face index")))?;
    let resolved = match value {
        0 => {
            return Err(obj_error(
                line,
                format!("{} 0 is not allowed; OBJ indices start at 1", index_name()),
            ))
        }
        v if v > 0 => v - 1,
        v => {
            let r = count as i64 + v;
            if r < 0 {
                let relative = if what == "vertex" { String::new() } else { format!(" {what}") };
                return Err(obj_error(
                    line,
                    format!("relative{relative} index {v} reaches before the first {line_kind} ({count} defined so far)"),
                ));
            }
            r
        }
    };
    u32::try_from(resolved)
        .ok()
        .filter(|&i| i < u32::MAX)
        .ok_or_else(|| obj_error(line, format!("{} {value} is too large", index_name())))
}

/// Writes `v` and `f` lines (1-based indices).
pub fn write_obj(mesh: &PolyMesh) -> String {
    // No channel and no normals: nothing to check.
    write_obj_with_normals(mesh, &[], None).unwrap_or_default()
}

/// Writes `v` and `f` lines and, when `attributes` has a channel named [`UV`], its values as
/// `vt` lines and the faces as `f v/vt` corners: a face-varying channel gives each corner its
/// own value index, a vertex-varying one the vertex's. Other channels are left out (OBJ has no
/// place for them). The `uv` channel is checked against the mesh first (its lengths and
/// indices, and an item size of 1 to 3, the components a `vt` line holds).
pub fn write_obj_with(mesh: &PolyMesh, attributes: &[Attribute]) -> Result<String> {
    write_obj_with_normals(mesh, attributes, None)
}

/// [`write_obj_with`], and with `normals` (3 floats per vertex) one `vn` line per vertex, in
/// vertex order, each corner naming its vertex's (`f v/vt/vn`, or `f v//vn` without UVs).
pub fn write_obj_with_normals(
    mesh: &PolyMesh,
    attributes: &[Attribute],
    normals: Option<&[f32]>,
) -> Result<String> {
    let uv = checked_uv(mesh, attributes, normals)?;
    // The pieces go into one buffer with room for the whole text, so that it is not moved.
    let mut out = Vec::with_capacity(text_size(mesh, uv, normals));
    write_pieces(&mut out, mesh, uv, normals).map_err(|e| Error::Io(e.to_string()))?;
    // Every byte written is ASCII.
    Ok(String::from_utf8(out)
        .unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned()))
}

/// [`write_obj_with_normals`] into `out`, in pieces of about 64 KB as they are made: the text of
/// a large mesh is never held whole (the horse at Catmull-Clark level 2 with normals is 160 MB
/// of it). The mesh, the `uv` channel and the normals are checked before anything is written;
/// an error of `out` is an [`Error::Io`] with its message, and `out` then holds part of the text.
pub fn write_obj_to(
    out: &mut (impl std::io::Write + ?Sized),
    mesh: &PolyMesh,
    attributes: &[Attribute],
    normals: Option<&[f32]>,
) -> Result<()> {
    let uv = checked_uv(mesh, attributes, normals)?;
    write_pieces(out, mesh, uv, normals).map_err(|e| Error::Io(e.to_string()))
}

/// The text of `mesh` with its checked `uv` channel and normals, handed to `out` in pieces of
/// about [`PIECE`] bytes.
fn write_pieces(
    out: &mut (impl std::io::Write + ?Sized),
    mesh: &PolyMesh,
    uv: Option<&Attribute>,
    normals: Option<&[f32]>,
) -> std::io::Result<()> {
    let mut piece = Vec::with_capacity(PIECE + 4096);
    let mut spill = |piece: &mut Vec<u8>| {
        out.write_all(piece)?;
        piece.clear();
        Ok(())
    };
    write(mesh, uv, normals, &mut piece, &mut spill)
        .and_then(|()| spill(&mut piece))
        .and_then(|()| out.flush())
}

/// The bytes [`write_obj_to`] gathers before handing them on.
const PIECE: usize = 1 << 16;

/// The channel [`UV`] of `attributes`, when there is one, once it and `normals` are checked
/// against `mesh`.
fn checked_uv<'a>(
    mesh: &PolyMesh,
    attributes: &'a [Attribute],
    normals: Option<&[f32]>,
) -> Result<Option<&'a Attribute>> {
    if let Some(normals) = normals {
        if normals.len() != mesh.positions.len() {
            return Err(Error::InvalidAttribute(format!(
                "normals: {} floats for {} vertices; give 3 per vertex",
                normals.len(),
                mesh.num_vertices()
            )));
        }
    }
    let Some(uv) = attributes.iter().find(|a| a.name == UV) else {
        return Ok(None);
    };
    attributes::validate(std::slice::from_ref(uv), mesh.num_vertices(), mesh.indices.len())?;
    if uv.item_size > 3 {
        return Err(Error::InvalidAttribute(format!(
            "attribute '{UV}': itemSize is {}, but an OBJ 'vt' line holds 1 to 3 components",
            uv.item_size
        )));
    }
    Ok(Some(uv))
}

/// About how many bytes the text takes (13 a float, 8 an index), so that a buffer that holds
/// it whole is rarely moved while it grows.
fn text_size(mesh: &PolyMesh, uv: Option<&Attribute>, normals: Option<&[f32]>) -> usize {
    let floats =
        mesh.positions.len() + uv.map_or(0, |a| a.values.len()) + normals.map_or(0, <[_]>::len);
    let per_corner = 8 * (1 + usize::from(uv.is_some()) + usize::from(normals.is_some()));
    floats * 13 + mesh.indices.len() * per_corner
}

/// Hands `out` to `spill` once it holds a piece, [`PIECE`] bytes or more.
#[inline]
fn spill_full(
    out: &mut Vec<u8>,
    spill: &mut dyn FnMut(&mut Vec<u8>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    if out.len() >= PIECE {
        spill(out)?;
    }
    Ok(())
}

/// Appends the text of `mesh` (checked) to `out`, handing `out` to `spill` whenever it holds
/// [`PIECE`] bytes or more (`spill` empties it).
fn write(
    mesh: &PolyMesh,
    uv: Option<&Attribute>,
    normals: Option<&[f32]>,
    out: &mut Vec<u8>,
    spill: &mut dyn FnMut(&mut Vec<u8>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let mut floats_line = |out: &mut Vec<u8>, tag: &[u8], values: &[f32]| {
        out.extend_from_slice(tag);
        for &x in values {
            out.push(b' ');
            text::push_f32(out, x);
        }
        out.push(b'\n');
        spill_full(out, spill)
    };
    for p in mesh.positions.chunks_exact(3) {
        floats_line(out, b"v", p)?;
    }
    if let Some(uv) = uv {
        for value in uv.values.chunks_exact(uv.item_size) {
            floats_line(out, b"vt", value)?;
        }
    }
    for n in normals.unwrap_or_default().chunks_exact(3) {
        floats_line(out, b"vn", n)?;
    }
    let mut start = 0usize;
    for &n in &mesh.face_sizes {
        let Some(face) = mesh.indices.get(start..start + n as usize) else {
            break;
        };
        out.push(b'f');
        for (k, &i) in face.iter().enumerate() {
            let v = i as u64 + 1;
            let t =
                uv.map(|a| a.indices.as_ref().map_or(i, |indices| indices[start + k]) as u64 + 1);
            out.push(b' ');
            text::push_u64(out, v);
            if let Some(t) = t {
                out.push(b'/');
                text::push_u64(out, t);
            }
            if normals.is_some() {
                out.extend_from_slice(if t.is_some() { b"/" } else { b"//" });
                text::push_u64(out, v);
            }
        }
        out.push(b'\n');
        spill_full(out, spill)?;
        start += n as usize;
    }
    Ok(())
}
