//! Face-varying values against OpenSubdiv 3.5's `PrimvarRefiner::InterpolateFaceVarying`: every
//! row of `tests/fixtures/osd_fvar/MANIFEST.tsv` (Catmull-Clark, Loop and bilinear; the six
//! modes; levels 1-3; untagged and with the shapes' creases, corners, holes and boundary modes)
//! runs through `subdivide_with_attributes` with the input's `vt` as a face-varying channel,
//! and each face corner's value is compared with OpenSubdiv's at the same corner (faces paired
//! as the position comparison pairs them). `OSD_FIXTURE_FILTER=catmark_cube` runs matching rows.

#[path = "common/osd.rs"]
mod osd;
#[path = "common/osd_fvar.rs"]
mod osd_fvar;

use osd::{face_pairs, our_faces, ours, root, Entry, Set};
use osd_fvar::{input_uvs, read_fvar_fixture, read_fvar_manifest, FvarEntry};
use std::collections::BTreeSet;
use subsurf::{FVarLinear, Scheme};

/// Compares `scheme`'s values (by default the manifest's own scheme) with the fixture.
fn compare(e: &FvarEntry, scheme: Option<Scheme>) -> Result<f64, String> {
    let scheme = match (scheme, e.scheme.as_str()) {
        (Some(scheme), _) => scheme,
        (None, "catmark") => Scheme::CatmullClark,
        (None, "loop") => Scheme::Loop,
        (None, "bilinear") => Scheme::Bilinear,
        (None, other) => return Err(format!("unknown scheme {other}")),
    };
    let mode: FVarLinear = e.mode.parse().map_err(|e| format!("{e}"))?;
    let entry = Entry {
        fixture: e.fixture.clone(),
        // The bilinear faces split as Catmull-Clark's do.
        scheme: if e.scheme == "loop" { "loop".into() } else { "catmark".into() },
        boundary: e.boundary.clone(),
        level: e.level,
        input: e.input.clone(),
    };
    let set = if e.tagged { Set::Tagged } else { Set::Untagged };
    let run = ours(&entry, scheme, set, &input_uvs, mode)?;
    let (pairs, kept) = face_pairs(&entry, &run);
    let reference = read_fvar_fixture(&root().join("tests/fixtures/osd_fvar").join(&e.fixture));
    let faces = our_faces(&run.result);
    if faces.len() != kept || reference.faces.len() != kept {
        return Err(format!(
            "face counts differ: ours {}, OpenSubdiv {}, {kept} expected",
            faces.len(),
            reference.faces.len()
        ));
    }
    let uv = &run.channels[0];
    let indices = uv.indices.as_ref().ok_or("the channel came back without indices")?;
    if indices.len() != run.result.indices.len() {
        return Err(format!(
            "{} uv indices for {} face corners",
            indices.len(),
            run.result.indices.len()
        ));
    }
    let (mut worst, mut start, mut bad) = (0.0f64, 0usize, 0usize);
    let mut worst_at = String::new();
    for (i, (face, (q, r))) in faces.iter().zip(&pairs).enumerate() {
        let theirs = &reference.faces[*q];
        for m in 0..face.len() {
            let value = indices[start + m] as usize;
            let ours = [uv.values[2 * value] as f64, uv.values[2 * value + 1] as f64];
            let expected = reference.values[theirs[(m + r) % face.len()].1 as usize];
            let d = ((ours[0] - expected[0]).powi(2) + (ours[1] - expected[1]).powi(2)).sqrt();
            let d = if d.is_nan() { f64::INFINITY } else { d };
            if d > 1e-5 {
                bad += 1;
            }
            if d > worst {
                worst = d;
                worst_at = format!("our face {i} corner {m}: {ours:?}, OpenSubdiv {expected:?}");
            }
        }
        start += face.len();
    }
    if bad > 0 {
        return Err(format!(
            "{bad} corners differ by more than 1e-5; worst {worst:.3e} at {worst_at}"
        ));
    }
    Ok(worst)
}

/// Shapes with a face that repeats a vertex (see DEVELOPERS.md, "Non-manifold input"):
/// compared like the others, and left out of the Quad/Triangle comparison (it refuses them).
const REPEATED_VERTEX_SHAPES: &[&str] = &["catmark_nonman_edges", "loop_nonman_edges"];

#[test]
fn face_varying_values_match_opensubdiv_in_every_mode() {
    let dir = root().join("tests/fixtures/osd_fvar");
    let filter = std::env::var("OSD_FIXTURE_FILTER").unwrap_or_default();
    let entries: Vec<FvarEntry> =
        read_fvar_manifest(&dir).into_iter().filter(|e| e.label().contains(&filter)).collect();
    let mut failures = Vec::new();
    let (mut shapes, mut worst) = (BTreeSet::new(), (0.0f64, String::new()));
    for e in &entries {
        shapes.insert(e.input.clone());
        match compare(e, None) {
            Ok(d) if d >= worst.0 => worst = (d, e.label()),
            Ok(_) => {}
            Err(message) => failures.push(format!("{}: {message}", e.label())),
        }
    }
    println!(
        "osd_fvar_agreement: {} comparisons on {} shapes, {} passed, {} failed; largest difference {:.2e} ({})",
        entries.len(),
        shapes.len(),
        entries.len() - failures.len(),
        failures.len(),
        worst.0,
        worst.1
    );
    if filter.is_empty() {
        assert!(entries.len() > 3000, "{} rows", entries.len());
        assert!(shapes.len() >= 105, "{} shapes", shapes.len());
    }
    assert!(
        failures.is_empty(),
        "{} of {} disagree with OpenSubdiv:\n  {}",
        failures.len(),
        entries.len(),
        failures.iter().take(60).cloned().collect::<Vec<_>>().join("\n  ")
    );
}

/// Quad/Triangle is Catmull-Clark on quads and Loop on triangles, face-varying values too: on
/// every untagged all-quad Catmull-Clark row and all-triangle Loop row it equals OpenSubdiv
/// (non-manifold shapes included; not the shapes with a face that repeats a vertex, which
/// Quad/Triangle refuses).
#[test]
fn quad_triangle_face_varying_values_match_catmull_clark_and_loop() {
    let dir = root().join("tests/fixtures/osd_fvar");
    let filter = std::env::var("OSD_FIXTURE_FILTER").unwrap_or_default();
    let uniform = |e: &FvarEntry, size: u32| {
        let text = std::fs::read_to_string(root().join(&e.input)).unwrap_or_default();
        subsurf::io::read_obj(&text).is_ok_and(|m| m.face_sizes.iter().all(|&n| n == size))
    };
    let entries: Vec<FvarEntry> = read_fvar_manifest(&dir)
        .into_iter()
        .filter(|e| !e.tagged && e.label().contains(&filter))
        .filter(|e| !REPEATED_VERTEX_SHAPES.iter().any(|s| e.input.contains(s)))
        .filter(|e| match e.scheme.as_str() {
            "catmark" => uniform(e, 4),
            "loop" => uniform(e, 3),
            _ => false,
        })
        .collect();
    let failures: Vec<String> = entries
        .iter()
        .filter_map(|e| {
            compare(e, Some(Scheme::QuadTriangle)).err().map(|m| format!("{}: {m}", e.label()))
        })
        .collect();
    println!(
        "quad-triangle face-varying: {} comparisons, {} failed",
        entries.len(),
        failures.len()
    );
    if filter.is_empty() {
        assert!(entries.len() > 500, "{} rows", entries.len());
    }
    assert!(
        failures.is_empty(),
        "{}",
        failures.iter().take(40).cloned().collect::<Vec<_>>().join("\n")
    );
}
