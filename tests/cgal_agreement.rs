//! Agreement with CGAL's `Subdivision_method_3`: every fixture in `tests/fixtures/cgal/`
//! (`SCHEME.MESH.LN.obj`, written by `tools/cgal/make_fixtures.sh` from
//! `tests/meshes/cgal/MESH.obj`) is recomputed with [`subdivide`] and compared.
//!
//! CGAL numbers vertices and starts faces its own way, so the comparison is order-independent:
//! every vertex of ours is matched to the CGAL vertex nearest to it, which must lie within
//! `1e-5` × the bounding-box diagonal of CGAL's result; the matching must be a bijection; then
//! the faces, as cyclic vertex sequences in CGAL's numbering (same orientation, any rotation),
//! must be the same multiset.
//!
//! Options per CGAL scheme: Catmull-Clark and Loop with [`Boundary::EdgeOnly`] (CGAL's border
//! masks apply the crease rule to every boundary vertex), Doo-Sabin with [`Boundary::None`]
//! (CGAL drops the faces of boundary edges and vertices), √3 with the default options.
//!
//! Set `CGAL_FIXTURE_FILTER=substring` to run only the fixtures whose file name contains it.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use subsurf::io::read_obj;
use subsurf::{subdivide, Boundary, Options, PolyMesh, Scheme};

const RELATIVE_TOLERANCE: f64 = 1e-5;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A fixture named `SCHEME.MESH.LN.obj`.
struct Fixture {
    path: PathBuf,
    file: String,
    scheme: String,
    mesh: String,
    level: u32,
}

fn fixtures() -> Vec<Fixture> {
    let dir = root().join("tests/fixtures/cgal");
    let filter = std::env::var("CGAL_FIXTURE_FILTER").unwrap_or_default();
    let mut list: Vec<Fixture> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()))
        .filter_map(|entry| {
            let path = entry.ok()?.path();
            let file = path.file_name()?.to_str()?.to_string();
            let stem = file.strip_suffix(".obj")?;
            let mut parts = stem.split('.');
            let (scheme, mesh, level) = (parts.next()?, parts.next()?, parts.next()?);
            let level = level.strip_prefix('L')?.parse().ok()?;
            Some(Fixture { scheme: scheme.to_string(), mesh: mesh.to_string(), level, file, path })
        })
        .filter(|f| f.file.contains(&filter))
        .collect();
    list.sort_by(|a, b| a.file.cmp(&b.file));
    list
}

/// CGAL's output, coordinates read as `f64`.
struct Reference {
    positions: Vec<[f64; 3]>,
    faces: Vec<Vec<u32>>,
}

fn read_reference(path: &Path) -> Reference {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let mut reference = Reference { positions: Vec::new(), faces: Vec::new() };
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let c: Vec<f64> = words.map(|w| w.parse().expect("a number")).collect();
                reference.positions.push([c[0], c[1], c[2]]);
            }
            Some("f") => reference
                .faces
                .push(words.map(|w| w.parse::<u32>().expect("an index") - 1).collect()),
            _ => {}
        }
    }
    reference
}

fn options_for(scheme: &str, level: u32) -> Options {
    let parsed: Scheme = scheme.parse().expect("a scheme name");
    let options = Options::new(parsed, level);
    match parsed {
        Scheme::CatmullClark | Scheme::Loop => options.with_boundary(Boundary::EdgeOnly),
        Scheme::DooSabin => options.with_boundary(Boundary::None),
        _ => options,
    }
}

fn diagonal(points: &[[f64; 3]]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt()
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

/// The face as a cyclic sequence, rotated to start at its smallest index.
fn canonical(face: &[u32]) -> Vec<u32> {
    let start = (0..face.len()).min_by_key(|&i| face[i]).unwrap_or(0);
    face[start..].iter().chain(&face[..start]).copied().collect()
}

/// Compares one fixture; `Err` says what differs. `Ok` returns the largest vertex distance
/// relative to the diagonal.
fn compare(fixture: &Fixture) -> Result<f64, String> {
    let input_path = root().join(format!("tests/meshes/cgal/{}.obj", fixture.mesh));
    let input = std::fs::read_to_string(&input_path)
        .map_err(|e| format!("cannot read {}: {e}", input_path.display()))?;
    let input = read_obj(&input).map_err(|e| format!("input: {e}"))?;
    let ours: PolyMesh = subdivide(&input, &options_for(&fixture.scheme, fixture.level))
        .map_err(|e| format!("subdivide failed: {e}"))?;
    let cgal = read_reference(&fixture.path);

    let our_points: Vec<[f64; 3]> =
        ours.positions.chunks_exact(3).map(|p| [p[0] as f64, p[1] as f64, p[2] as f64]).collect();
    if our_points.len() != cgal.positions.len() || ours.num_faces() != cgal.faces.len() {
        return Err(format!(
            "counts differ: ours {} vertices, {} faces; CGAL {} vertices, {} faces",
            our_points.len(),
            ours.num_faces(),
            cgal.positions.len(),
            cgal.faces.len()
        ));
    }
    let diag = diagonal(&cgal.positions).max(f64::MIN_POSITIVE);
    let tolerance = RELATIVE_TOLERANCE * diag;

    // Nearest CGAL vertex for each of ours: CGAL's vertices sorted by x, searched in the window
    // x ± tolerance; vertices with nothing in the window get a full search for the report.
    let mut by_x: Vec<u32> = (0..cgal.positions.len() as u32).collect();
    by_x.sort_by(|&a, &b| cgal.positions[a as usize][0].total_cmp(&cgal.positions[b as usize][0]));
    let nearest = |p: [f64; 3]| -> (u32, f64) {
        let start = by_x.partition_point(|&i| cgal.positions[i as usize][0] < p[0] - tolerance);
        let window = by_x[start..]
            .iter()
            .take_while(|&&i| cgal.positions[i as usize][0] <= p[0] + tolerance);
        let best = window
            .map(|&i| (i, distance(p, cgal.positions[i as usize])))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        match best {
            Some(found) if found.1 <= tolerance => found,
            _ => (0..cgal.positions.len() as u32)
                .map(|i| (i, distance(p, cgal.positions[i as usize])))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap_or((0, f64::INFINITY)),
        }
    };
    let matched: Vec<(u32, f64)> = our_points.iter().map(|&p| nearest(p)).collect();
    let (worst, &(worst_cgal, worst_distance)) =
        matched.iter().enumerate().max_by(|a, b| a.1 .1.total_cmp(&b.1 .1)).ok_or("empty mesh")?;
    if worst_distance > tolerance {
        let far = matched.iter().filter(|m| m.1 > tolerance).count();
        return Err(format!(
            "{far} of {} vertices have no CGAL vertex within {RELATIVE_TOLERANCE:e} × diagonal; worst: our vertex {worst} at {:?}, nearest CGAL vertex {worst_cgal} at {:?}, distance {:.3e} × diagonal",
            our_points.len(),
            our_points[worst],
            cgal.positions[worst_cgal as usize],
            worst_distance / diag
        ));
    }
    let mut used_by = vec![u32::MAX; cgal.positions.len()];
    for (v, &(c, _)) in matched.iter().enumerate() {
        if used_by[c as usize] != u32::MAX {
            return Err(format!(
                "not a bijection: our vertices {} and {v} both match CGAL vertex {c} at {:?}",
                used_by[c as usize], cgal.positions[c as usize]
            ));
        }
        used_by[c as usize] = v as u32;
    }

    // Faces as multisets of canonical cycles in CGAL's numbering.
    let mut counts: BTreeMap<Vec<u32>, i64> = BTreeMap::new();
    let mut start = 0usize;
    for &n in &ours.face_sizes {
        let face: Vec<u32> = ours.indices[start..start + n as usize]
            .iter()
            .map(|&v| matched[v as usize].0)
            .collect();
        *counts.entry(canonical(&face)).or_default() += 1;
        start += n as usize;
    }
    for face in &cgal.faces {
        *counts.entry(canonical(face)).or_default() -= 1;
    }
    let differing: Vec<_> = counts.iter().filter(|(_, &n)| n != 0).collect();
    if !differing.is_empty() {
        let show = |(face, n): &(&Vec<u32>, &i64)| {
            let side = if **n > 0 { "only ours" } else { "only CGAL's" };
            let at: Vec<_> = face.iter().map(|&c| cgal.positions[c as usize]).collect();
            format!("{side}: {face:?} at {at:?}")
        };
        let listed: Vec<String> = differing.iter().take(4).map(show).collect();
        return Err(format!(
            "{} face cycles differ (CGAL numbering), e.g. {}",
            differing.len(),
            listed.join("; ")
        ));
    }
    Ok(worst_distance / diag)
}

#[test]
fn agrees_with_cgal() {
    let list = fixtures();
    assert!(
        !list.is_empty() || std::env::var("CGAL_FIXTURE_FILTER").is_ok(),
        "no fixtures in tests/fixtures/cgal; run tools/cgal/make_fixtures.sh"
    );
    let mut failures = String::new();
    let mut summary: BTreeMap<&str, (usize, f64)> = BTreeMap::new();
    for fixture in &list {
        match compare(fixture) {
            Ok(error) => {
                let entry = summary.entry(&fixture.scheme).or_default();
                entry.0 += 1;
                entry.1 = entry.1.max(error);
            }
            Err(message) => {
                let _ = writeln!(
                    failures,
                    "{} on {} level {} ({}): {message}",
                    fixture.scheme, fixture.mesh, fixture.level, fixture.file
                );
            }
        }
    }
    for (scheme, (count, error)) in &summary {
        println!("{scheme}: {count} fixtures agree, largest distance {error:.2e} × diagonal");
    }
    assert!(
        failures.is_empty(),
        "{} of {} CGAL fixtures disagree:\n{failures}",
        failures.lines().count(),
        list.len()
    );
}
