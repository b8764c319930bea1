//! Face-varying values at the limit against OpenSubdiv 3.5's `PrimvarRefiner::LimitFaceVarying`:
//! every row of `tests/fixtures/osd_limit_fvar/MANIFEST.tsv` (written by
//! `tools/osd/make_limit_fvar_fixtures.sh`: `osd_refine --limit --fvar-linear MODE`; Catmull-Clark
//! and Loop, the six modes, levels 1-3, untagged and with the shapes' own tags) runs through
//! [`subdivide_limit_with`] with the input's `vt` as a face-varying channel. The faces are paired
//! with OpenSubdiv's as in `tests/osd_agreement.rs` (`tests/common/osd.rs`); then
//!
//! - limit positions, vertex by vertex, within `1e-5` × the bounding-box diagonal of
//!   OpenSubdiv's result;
//! - limit UVs, face corner by face corner (each library numbers its values its own way), within
//!   [`UV_TOLERANCE`].
//!
//! The two are separate tests, so that one can pass while the other does not. `-- --nocapture`
//! prints the counts; `OSD_FIXTURE_FILTER=catmark_cube` runs the rows whose label contains it.

#[path = "common/osd.rs"]
mod osd;
#[path = "common/osd_fvar.rs"]
mod osd_fvar;

use osd::{
    bounding_diagonal, face_pairs, our_faces, ours, root, vertex_map, Entry, RefMesh, Set,
    NO_VERTEX, RELATIVE_TOLERANCE,
};
use osd_fvar::{input_uvs, read_fvar_manifest, FvarEntry, FvarFixture};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use subsurf::attributes::Attribute;
use subsurf::io::{read_obj, read_obj_with_tags};
use subsurf::scheme::subdivide_limit_with;
use subsurf::{Boundary, FVarLinear, Options, PolyMesh, Scheme, Tags};

/// UVs are compared absolutely: the shapes' UVs lie in the unit square.
const UV_TOLERANCE: f64 = 1e-5;

/// How many disagreeing rows a failure lists.
const LISTED: usize = 40;

fn dir() -> PathBuf {
    root().join("tests/fixtures/osd_limit_fvar")
}

/// A fixture holds both what the position fixtures and the face-varying fixtures hold: `v`,
/// `vt` and `f v/vt` lines.
fn read_fixture(path: &Path) -> (RefMesh, FvarFixture) {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let mut mesh = RefMesh { positions: Vec::new(), faces: Vec::new() };
    let mut uvs = FvarFixture { values: Vec::new(), faces: Vec::new() };
    for (n, line) in text.lines().enumerate() {
        let bad = || format!("{}:{}: cannot parse '{line}'", path.display(), n + 1);
        let mut words = line.split_whitespace();
        let keyword = words.next();
        let numbers = |count: usize| -> Vec<f64> {
            let parsed: Vec<f64> = words.clone().map(|w| w.parse().unwrap_or(f64::NAN)).collect();
            assert!(parsed.len() == count && parsed.iter().all(|x| !x.is_nan()), "{}", bad());
            parsed
        };
        match keyword {
            Some("v") => {
                let p = numbers(3);
                mesh.positions.push([p[0], p[1], p[2]]);
            }
            Some("vt") => {
                let t = numbers(2);
                uvs.values.push([t[0], t[1]]);
            }
            Some("f") => {
                let index = |s: &str| {
                    s.parse::<u32>()
                        .ok()
                        .and_then(|i| i.checked_sub(1))
                        .unwrap_or_else(|| panic!("{}", bad()))
                };
                let corners: Vec<(u32, u32)> = words
                    .clone()
                    .map(|w| {
                        let (v, t) = w.split_once('/').unwrap_or_else(|| panic!("{}", bad()));
                        (index(v), index(t))
                    })
                    .collect();
                mesh.faces.push(corners.iter().map(|c| c.0).collect());
                uvs.faces.push(corners);
            }
            _ => panic!("{}", bad()),
        }
    }
    (mesh, uvs)
}

/// The row as the position comparison's [`Entry`], and the set whose reading of the input it
/// follows.
fn entry_of(e: &FvarEntry) -> (Entry, Set) {
    let entry = Entry {
        fixture: e.fixture.clone(),
        scheme: e.scheme.clone(),
        boundary: e.boundary.clone(),
        level: e.level,
        input: e.input.clone(),
    };
    (entry, if e.tagged { Set::Tagged } else { Set::Untagged })
}

/// Our limit result for the row: the mesh and the UV channel.
fn our_limit(
    e: &FvarEntry,
    scheme: Scheme,
    mode: FVarLinear,
) -> Result<(PolyMesh, Attribute), String> {
    let text = std::fs::read_to_string(root().join(&e.input)).map_err(|e| e.to_string())?;
    let attributes = input_uvs(&text);
    let boundary: Boundary = e.boundary.parse().map_err(|e| format!("{e}"))?;
    let options = Options::new(scheme, e.level).with_boundary(boundary).with_fvar_linear(mode);
    let result = if e.tagged {
        let obj = read_obj_with_tags(&text).map_err(|e| e.to_string())?;
        subdivide_limit_with(&obj.mesh, &attributes, &options, &obj.tags)
    } else {
        let mesh = read_obj(&text).map_err(|e| e.to_string())?;
        subdivide_limit_with(&mesh, &attributes, &options, &Tags::default())
    }
    .map_err(|e| format!("subdivide_limit_with failed: {e}"))?;
    let (poly, mut channels) = result.into_parts();
    if channels.len() != 1 {
        return Err(format!("{} channels came back for 1", channels.len()));
    }
    Ok((poly, channels.remove(0)))
}

/// What one row compared: the worst difference, relative to its tolerance, and how many items
/// (vertices or corners) were compared.
struct Agreement {
    worst: f64,
    compared: usize,
}

/// Compares one row's positions (`uvs` false) or UVs (`uvs` true).
fn compare(e: &FvarEntry, uvs: bool) -> Result<Agreement, String> {
    let scheme = match e.scheme.as_str() {
        "catmark" => Scheme::CatmullClark,
        "loop" => Scheme::Loop,
        other => return Err(format!("unknown scheme {other}")),
    };
    let mode: FVarLinear = e.mode.parse().map_err(|e| format!("{e}"))?;
    let (entry, set) = entry_of(e);
    // The refined (not limit) run gives the hole faces and the face pairing.
    let run = ours(&entry, scheme, set, &input_uvs, mode)?;
    let (pairs, kept) = face_pairs(&entry, &run);
    let (limit, uv) = our_limit(e, scheme, mode)?;
    if limit.indices != run.result.indices || limit.face_sizes != run.result.face_sizes {
        return Err("the limit's faces are not those of subdivide".into());
    }
    let (reference, reference_uvs) = read_fixture(&dir().join(&e.fixture));
    if reference.faces.len() != kept || our_faces(&limit).len() != kept {
        return Err(format!(
            "face counts differ: ours {}, OpenSubdiv {}, {kept} expected",
            our_faces(&limit).len(),
            reference.faces.len()
        ));
    }
    if !uvs {
        let to_osd = vertex_map(&limit, &reference, pairs, &run.holes)?;
        let tolerance = RELATIVE_TOLERANCE * bounding_diagonal(&reference.positions);
        let (mut worst, mut compared, mut bad) = (0.0f64, 0usize, Vec::new());
        for (v, &w) in to_osd.iter().enumerate() {
            if w == NO_VERTEX {
                continue;
            }
            compared += 1;
            let p = &limit.positions[3 * v..3 * v + 3];
            let q = reference.positions[w as usize];
            let d = (0..3).map(|k| (p[k] as f64 - q[k]).powi(2)).sum::<f64>().sqrt();
            let d = if d.is_nan() { f64::INFINITY } else { d };
            worst = worst.max(d / tolerance.max(f64::MIN_POSITIVE));
            if d > tolerance {
                bad.push(format!("our {v} {p:?} vs their {w} {q:?} ({d:.2e})"));
            }
        }
        if !bad.is_empty() {
            return Err(format!(
                "{} of {compared} positions differ by more than {tolerance:.2e}; first: {}",
                bad.len(),
                bad[0]
            ));
        }
        return Ok(Agreement { worst, compared });
    }
    let indices = uv.indices.as_ref().ok_or("the channel came back without indices")?;
    if indices.len() != limit.indices.len() {
        return Err(format!(
            "{} uv indices for {} face corners",
            indices.len(),
            limit.indices.len()
        ));
    }
    let (mut worst, mut start, mut bad, mut worst_at) = (0.0f64, 0usize, 0usize, String::new());
    for (i, (face, (q, r))) in our_faces(&limit).iter().zip(&pairs).enumerate() {
        let theirs = &reference_uvs.faces[*q];
        if theirs.len() != face.len() {
            return Err(format!(
                "our face {i} has {} corners, OpenSubdiv's {q} {}",
                face.len(),
                theirs.len()
            ));
        }
        for m in 0..face.len() {
            let value = indices[start + m] as usize;
            let ours = [uv.values[2 * value] as f64, uv.values[2 * value + 1] as f64];
            let expected = reference_uvs.values[theirs[(m + r) % face.len()].1 as usize];
            let d = ((ours[0] - expected[0]).powi(2) + (ours[1] - expected[1]).powi(2)).sqrt();
            let d = if d.is_nan() { f64::INFINITY } else { d };
            if d > UV_TOLERANCE {
                bad += 1;
            }
            if d / UV_TOLERANCE > worst {
                worst = d / UV_TOLERANCE;
                worst_at = format!("our face {i} corner {m}: {ours:?}, OpenSubdiv {expected:?}");
            }
        }
        start += face.len();
    }
    if bad > 0 {
        return Err(format!(
            "{bad} of {start} corners differ by more than {UV_TOLERANCE:e}; worst {:.3e} at {worst_at}",
            worst * UV_TOLERANCE
        ));
    }
    Ok(Agreement { worst, compared: start })
}

/// Runs every (filtered) row, prints the counts and fails listing the first rows that disagree.
fn run_all(uvs: bool) {
    let what = if uvs { "UVs" } else { "positions" };
    let filter = std::env::var("OSD_FIXTURE_FILTER").unwrap_or_default();
    let entries: Vec<FvarEntry> =
        read_fvar_manifest(&dir()).into_iter().filter(|e| e.label().contains(&filter)).collect();
    if filter.is_empty() {
        assert!(entries.len() > 1500, "{} rows", entries.len());
    }
    let (mut shapes, mut compared, mut worst) = (BTreeSet::new(), 0usize, (0.0f64, String::new()));
    let mut failures = Vec::new();
    for e in &entries {
        shapes.insert(e.input.clone());
        match compare(e, uvs) {
            Ok(a) => {
                compared += a.compared;
                if a.worst >= worst.0 {
                    worst = (a.worst, e.label());
                }
            }
            Err(message) => failures.push(format!("{}: {message}", e.label())),
        }
    }
    println!(
        "osd_limit_fvar_agreement ({what}): {} of {} rows on {} shapes agree ({} {} compared in \
         them); worst {:.3} x tolerance ({})",
        entries.len() - failures.len(),
        entries.len(),
        shapes.len(),
        compared,
        if uvs { "corners" } else { "vertices" },
        worst.0,
        worst.1
    );
    assert!(
        failures.is_empty(),
        "{} of {} rows disagree with OpenSubdiv on the limit {what}; the first {}:\n  {}",
        failures.len(),
        entries.len(),
        failures.len().min(LISTED),
        failures.iter().take(LISTED).cloned().collect::<Vec<_>>().join("\n  ")
    );
}

#[test]
fn limit_positions_with_face_varying_channels_agree_with_opensubdiv() {
    run_all(false);
}

#[test]
fn limit_face_varying_values_agree_with_opensubdiv() {
    run_all(true);
}
