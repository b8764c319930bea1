//! Agreement with OpenSubdiv at the limit: every row of `tests/fixtures/osd_limit/MANIFEST.tsv`
//! (written by `tools/osd/make_limit_fixtures.sh`: `osd_refine --limit`, i.e. OpenSubdiv's
//! `PrimvarRefiner::Limit` on the last level) is recomputed with [`subdivide_limit`] and compared
//! vertex by vertex, the vertices paired through the face lists as in `tests/osd_agreement.rs`
//! (`tests/common/osd.rs`):
//!
//! - limit positions within `1e-5` × the bounding-box diagonal of OpenSubdiv's result;
//! - normals: ours unit length (or zero where our tangents are degenerate), and within
//!   [`MAX_ANGLE`] of OpenSubdiv's `tan1 × tan2`, normalised; vertices where OpenSubdiv's
//!   tangents are degenerate (its fixture says `vn 0 0 0`) are skipped and counted. On the
//!   shapes of [`OTHER_SPAN`] the normals that differ are counted instead (see there).
//!
//! `OSD_FIXTURE_FILTER=catmark_cube` runs only matching fixtures; `-- --nocapture` prints the
//! counts.

mod common;
#[path = "common/osd.rs"]
mod osd;

use common::OTHER_SPAN;

use osd::{
    bounding_diagonal, face_pairs, our_scheme, ours, read_fixture, read_manifest, root, vertex_map,
    Entry, Set, NO_VERTEX, RELATIVE_TOLERANCE,
};
use std::fmt::Write as _;
use std::path::PathBuf;
use subsurf::io::{read_obj, read_obj_with_tags};
use subsurf::scheme::subdivide_limit;
use subsurf::{Boundary, FVarLinear, Options, PolyMesh, Tags};

/// The largest angle between our normal and OpenSubdiv's, in radians. Our tangents are sums of
/// `f32` positions with weights summing to 0: where a one-ring is small against the coordinates
/// (the bishop's small faces) the cancellation costs up to 1e-3 rad (OpenSubdiv sums doubles);
/// almost every normal agrees within 1e-4.
const MAX_ANGLE: f64 = 2e-3;

fn dir() -> PathBuf {
    root().join("tests/fixtures/osd_limit")
}

/// One manifest row: the common columns, and whether the input's tags are used.
fn entries() -> Vec<(Entry, bool)> {
    let text = std::fs::read_to_string(dir().join("MANIFEST.tsv")).unwrap();
    let tagged: Vec<bool> = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| l.split('\t').nth(5) == Some("yes"))
        .collect();
    let entries = read_manifest(&dir());
    assert_eq!(entries.len(), tagged.len());
    entries.into_iter().zip(tagged).collect()
}

/// The `vn` lines of a fixture.
fn read_normals(text: &str) -> Vec<[f64; 3]> {
    text.lines()
        .filter_map(|l| l.strip_prefix("vn "))
        .map(|l| {
            let mut p = [0.0; 3];
            for (c, w) in p.iter_mut().zip(l.split_whitespace()) {
                *c = w.parse().unwrap();
            }
            p
        })
        .collect()
}

/// Our limit result for `entry`.
fn our_limit(entry: &Entry, tagged: bool) -> Result<(PolyMesh, Vec<f32>, Vec<f32>), String> {
    let text = std::fs::read_to_string(root().join(&entry.input)).map_err(|e| e.to_string())?;
    let boundary: Boundary = entry.boundary.parse().map_err(|e| format!("{e}"))?;
    let scheme = our_scheme(&entry.scheme);
    let options = Options::new(scheme, entry.level).with_boundary(boundary);
    let result = if tagged {
        let obj = read_obj_with_tags(&text).map_err(|e| e.to_string())?;
        subdivide_limit(&obj.mesh, &options, &obj.tags)
    } else {
        let mesh = read_obj(&text).map_err(|e| e.to_string())?;
        subdivide_limit(&mesh, &options, &Tags::default())
    }
    .map_err(|e| format!("subdivide_limit failed: {e}"))?;
    let normals = result.normals().ok_or("no normals")?.to_vec();
    let first = result.tangents().ok_or("no tangents")?[0].to_vec();
    Ok((result.into_poly(), normals, first))
}

#[derive(Default)]
struct Counts {
    vertices: usize,
    normals: usize,
    /// Normals of [`OTHER_SPAN`] shapes that differ.
    other_span: usize,
    degenerate: usize,
    worst_position: f64,
    worst_angle: f64,
}

fn compare(entry: &Entry, tagged: bool, counts: &mut Counts) -> Result<(), String> {
    let set = if tagged { Set::Tagged } else { Set::Untagged };
    let no_channels = |_: &str| Vec::new();
    let run = ours(entry, our_scheme(&entry.scheme), set, &no_channels, FVarLinear::default())?;
    let (pairs, kept) = face_pairs(entry, &run);
    let path = dir().join(&entry.fixture);
    let reference = read_fixture(&path);
    let reference_normals = read_normals(&std::fs::read_to_string(&path).unwrap());
    let (limit, normals, _) = our_limit(entry, tagged)?;
    if limit.indices != run.result.indices || limit.face_sizes != run.result.face_sizes {
        return Err("the limit's faces are not those of subdivide".into());
    }
    if reference.faces.len() != kept
        || limit.num_vertices() != reference.positions.len()
        || reference_normals.len() != reference.positions.len()
        || normals.len() != limit.positions.len()
    {
        return Err(format!(
            "counts differ: ours {} vertices, OpenSubdiv {} vertices and {} normals, {} faces ({kept} expected)",
            limit.num_vertices(),
            reference.positions.len(),
            reference_normals.len(),
            reference.faces.len()
        ));
    }
    let to_osd = vertex_map(&limit, &reference, pairs, &run.holes)?;
    let tolerance = RELATIVE_TOLERANCE * bounding_diagonal(&reference.positions);
    let other_span = OTHER_SPAN.iter().any(|s| entry.input.ends_with(&format!("/{s}.obj")));
    let mut bad_positions = Vec::new();
    let mut bad_normals = Vec::new();
    for (v, &w) in to_osd.iter().enumerate() {
        if w == NO_VERTEX {
            continue;
        }
        counts.vertices += 1;
        let p = &limit.positions[3 * v..3 * v + 3];
        let q = reference.positions[w as usize];
        let d = (0..3).map(|k| (p[k] as f64 - q[k]).powi(2)).sum::<f64>().sqrt();
        let d = if d.is_nan() { f64::INFINITY } else { d };
        counts.worst_position = counts.worst_position.max(d / tolerance.max(f64::MIN_POSITIVE));
        if d > tolerance {
            bad_positions.push(format!("our {v} {p:?} vs their {w} {q:?} ({d:.2e})"));
        }
        let n = &normals[3 * v..3 * v + 3];
        let length = n.iter().map(|&x| (x as f64).powi(2)).sum::<f64>().sqrt();
        let m = reference_normals[w as usize];
        if m == [0.0; 3] {
            counts.degenerate += 1;
            continue;
        }
        counts.normals += 1;
        if (length - 1.0).abs() > 1e-5 {
            if length == 0.0 && other_span {
                // Our tangents are degenerate where OpenSubdiv's other edges are not.
                counts.other_span += 1;
            } else {
                bad_normals.push(format!("our {v}: normal {n:?} is not unit length"));
            }
            continue;
        }
        // The angle from the cross and dot products (acos near 1 would amplify rounding).
        let n = [n[0] as f64, n[1] as f64, n[2] as f64];
        let cross =
            [n[1] * m[2] - n[2] * m[1], n[2] * m[0] - n[0] * m[2], n[0] * m[1] - n[1] * m[0]];
        let sin = cross.iter().map(|x| x * x).sum::<f64>().sqrt();
        let cos: f64 = (0..3).map(|k| n[k] * m[k]).sum();
        let angle = sin.atan2(cos);
        if !other_span || angle <= MAX_ANGLE {
            counts.worst_angle = counts.worst_angle.max(angle);
        }
        // NaN counts as a disagreement.
        let agrees = angle <= MAX_ANGLE;
        if !agrees && other_span {
            counts.other_span += 1;
        } else if !agrees {
            bad_normals.push(format!("our {v} {n:?} vs their {w} {m:?} ({angle:.2e} rad)"));
        }
    }
    if bad_positions.is_empty() && bad_normals.is_empty() {
        return Ok(());
    }
    let mut message = format!(
        "{} positions (tolerance {tolerance:.2e}) and {} normals of {} vertices differ",
        bad_positions.len(),
        bad_normals.len(),
        to_osd.len()
    );
    for line in bad_positions.iter().chain(&bad_normals).take(4) {
        let _ = write!(message, "; {line}");
    }
    Err(message)
}

#[test]
fn limit_positions_and_normals_agree_with_opensubdiv() {
    let filter = std::env::var("OSD_FIXTURE_FILTER").unwrap_or_default();
    let entries: Vec<_> =
        entries().into_iter().filter(|(e, _)| e.fixture.contains(&filter)).collect();
    assert!(!filter.is_empty() || entries.len() > 500, "{} rows", entries.len());
    let mut counts = Counts::default();
    let mut failures = Vec::new();
    for (entry, tagged) in &entries {
        if let Err(message) = compare(entry, *tagged, &mut counts) {
            let tags = if *tagged { "tagged" } else { "untagged" };
            failures.push(format!("{} {tags}: {message}", entry.label()));
        }
    }
    // The worst angle over the normals required to agree.
    println!(
        "osd_limit_agreement: {} of {} rows agree; {} vertices, {} normals compared, {} skipped \
         (OpenSubdiv's tangents degenerate), {} from another span on the listed shapes; worst \
         position {:.3} x tolerance, worst normal angle {:.2e} rad",
        entries.len() - failures.len(),
        entries.len(),
        counts.vertices,
        counts.normals,
        counts.degenerate,
        counts.other_span,
        counts.worst_position,
        counts.worst_angle
    );
    assert!(failures.is_empty(), "{} rows disagree:\n{}", failures.len(), failures.join("\n"));
}
