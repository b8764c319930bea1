//! Wavefront OBJ: `v` and `f` lines in, `v` and `f` lines out.
//!
//! Faces may use the `v`, `v/vt`, `v//vn` and `v/vt/vn` forms and negative (relative) indices;
//! only the position index is used. Comments and every other line (`vt`, `vn`, `g`, `o`, `s`,
//! `usemtl`, OpenSubdiv's `t` tags, ...) are skipped. Errors give the 1-based line number.

use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use std::fmt::Write as _;

fn obj_error(line: usize, message: impl Into<String>) -> Error {
    Error::Obj { line, message: message.into() }
}

/// Parses OBJ text into a [`PolyMesh`]. Structural checks (face sizes, repeated vertices, NaN)
/// happen here too, so that the error can name the line.
pub fn read_obj(text: &str) -> Result<PolyMesh> {
    let mut mesh = PolyMesh::default();
    // Line of each face, to name it when a later check fails.
    let mut face_lines: Vec<usize> = Vec::new();
    for (number, raw) in text.lines().enumerate() {
        let line_no = number + 1;
        let line = raw.split('#').next().unwrap_or("").trim();
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
            Some("f") => {
                let vertex_count = mesh.positions.len() / 3;
                let start = mesh.indices.len();
                for word in words {
                    let index = parse_face_index(word, vertex_count, line_no)?;
                    if mesh.indices[start..].contains(&index) {
                        return Err(obj_error(
                            line_no,
                            format!(
                                "face uses vertex {} twice; a face must not repeat a vertex",
                                index + 1
                            ),
                        ));
                    }
                    mesh.indices.push(index);
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
    Ok(mesh)
}

fn parse_coordinate(word: &str, line: usize) -> Result<f32> {
    let value: f32 =
        word.parse().map_err(|_| obj_error(line, format!("'{word}' is not a number")))?;
    if !value.is_finite() {
        return Err(obj_error(line, format!("coordinate '{word}' is not a finite 32-bit number")));
    }
    Ok(value)
}

/// The 0-based position index of a face corner such as `7`, `7/2`, `7//3`, `-1/2/3`.
fn parse_face_index(word: &str, vertex_count: usize, line: usize) -> Result<u32> {
    let first = word.split('/').next().unwrap_or("");
    let value: i64 =
        first.parse().map_err(|_| obj_error(line, format!("'{word}' is not a face index")))?;
    let resolved = match value {
        0 => return Err(obj_error(line, "face index 0 is not allowed; OBJ indices start at 1")),
        v if v > 0 => v - 1,
        v => {
            let r = vertex_count as i64 + v;
            if r < 0 {
                return Err(obj_error(
                    line,
                    format!("relative index {v} reaches before the first vertex ({vertex_count} defined so far)"),
                ));
            }
            r
        }
    };
    u32::try_from(resolved)
        .ok()
        .filter(|&i| i < u32::MAX)
        .ok_or_else(|| obj_error(line, format!("face index {value} is too large")))
}

/// Writes `v` and `f` lines (1-based indices).
pub fn write_obj(mesh: &PolyMesh) -> String {
    let mut out = String::with_capacity(mesh.positions.len() * 12 + mesh.indices.len() * 8);
    for p in mesh.positions.chunks_exact(3) {
        let _ = writeln!(out, "v {} {} {}", p[0], p[1], p[2]);
    }
    let mut start = 0usize;
    for &n in &mesh.face_sizes {
        let Some(face) = mesh.indices.get(start..start + n as usize) else {
            break;
        };
        out.push('f');
        for &i in face {
            let _ = write!(out, " {}", i as u64 + 1);
        }
        out.push('\n');
        start += n as usize;
    }
    out
}
