//! Agreement with OpenSubdiv: every untagged Catmull-Clark fixture in `tests/fixtures/osd/`
//! (listed in its `MANIFEST.tsv`, written by `tools/osd/make_fixtures.sh`) is recomputed with
//! [`subdivide`] and compared vertex by vertex.
//!
//! The two outputs number their vertices differently (OpenSubdiv numbers the edges of a refined
//! level its own way), so the vertex correspondence is read off the face lists:
//!
//! - Level 1: our child face `h` (parent half-edge `h`, corner `k` of a parent face of `n` sides)
//!   is OpenSubdiv's child face `h`. Ours starts at the corner vertex, `(v, e_k, f, e_k-1)`;
//!   OpenSubdiv keeps a quad parent's orientation and puts the corner vertex at position `k` (the
//!   same four vertices, rotated by `k`), and does not rotate the children of a non-quad (`k` = 0).
//! - Level `l + 1`: our face `4p + j` is the child of our face `p` at its corner `j`. If our face
//!   `p` is OpenSubdiv's face `q` rotated by `r`, that corner is OpenSubdiv's corner `k = (j + r)
//!   mod 4`, so the child is OpenSubdiv's face `4q + k`, rotated by `k`.
//!
//! "Rotated by `r`" means vertex `m` of our face is vertex `(m + r) mod 4` of OpenSubdiv's. The
//! map built this way must be a consistent bijection; vertices no face uses (isolated input
//! vertices) must be isolated in both and keep their index. Positions must agree within
//! `1e-5` × the bounding-box diagonal of OpenSubdiv's result.
//!
//! Set `OSD_FIXTURE_FILTER=substring` to run only the fixtures whose file name contains it.

use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use subsurf::io::read_obj;
use subsurf::{subdivide, Boundary, Options, PolyMesh, Scheme};

const RELATIVE_TOLERANCE: f64 = 1e-5;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// One row of a fixture manifest.
#[derive(Clone, Debug)]
struct Entry {
    fixture: String,
    scheme: String,
    boundary: String,
    level: u32,
    input: String,
}

impl Entry {
    fn label(&self) -> String {
        let shape = Path::new(&self.input).file_stem().unwrap().to_string_lossy().into_owned();
        format!("{shape} [{} boundary, level {}] ({})", self.boundary, self.level, self.fixture)
    }
}

fn read_manifest(dir: &Path) -> Vec<Entry> {
    let path = dir.join("MANIFEST.tsv");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| {
        panic!("cannot read {}: {e}; run tools/osd/make_fixtures.sh", path.display())
    });
    let mut entries = Vec::new();
    for (n, line) in text.lines().enumerate() {
        if line.starts_with('#') || line.trim().is_empty() {
            continue;
        }
        let cols: Vec<&str> = line.split('\t').collect();
        assert!(cols.len() >= 5, "{}:{}: expected 5 tab-separated columns", path.display(), n + 1);
        entries.push(Entry {
            fixture: cols[0].to_string(),
            scheme: cols[1].to_string(),
            boundary: cols[2].to_string(),
            level: cols[3].parse().unwrap_or_else(|_| {
                panic!("{}:{}: bad level '{}'", path.display(), n + 1, cols[3])
            }),
            input: cols[4].to_string(),
        });
    }
    entries
}

/// A fixture: positions in double precision, faces as index lists.
struct RefMesh {
    positions: Vec<[f64; 3]>,
    faces: Vec<Vec<u32>>,
}

fn read_fixture(path: &Path) -> RefMesh {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let mut mesh = RefMesh { positions: Vec::new(), faces: Vec::new() };
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let bad = || format!("{}:{}: cannot parse '{line}'", path.display(), n + 1);
        match words.next() {
            Some("v") => {
                let mut p = [0.0f64; 3];
                for c in &mut p {
                    *c = words
                        .next()
                        .and_then(|w| w.parse().ok())
                        .unwrap_or_else(|| panic!("{}", bad()));
                }
                mesh.positions.push(p);
            }
            Some("f") => {
                let face: Vec<u32> = words
                    .map(|w| {
                        w.parse::<u32>()
                            .ok()
                            .and_then(|i| i.checked_sub(1))
                            .unwrap_or_else(|| panic!("{}", bad()))
                    })
                    .collect();
                mesh.faces.push(face);
            }
            _ => {}
        }
    }
    mesh
}

fn our_faces(mesh: &PolyMesh) -> Vec<&[u32]> {
    let mut out = Vec::with_capacity(mesh.face_sizes.len());
    let mut start = 0usize;
    for &n in &mesh.face_sizes {
        out.push(&mesh.indices[start..start + n as usize]);
        start += n as usize;
    }
    out
}

/// For every face of our level-`levels` result: OpenSubdiv's index of the same face and the
/// rotation `r` (our vertex `m` is OpenSubdiv's vertex `(m + r) mod 4`). See the module docs.
fn face_correspondence(base_face_sizes: &[u32], levels: u32) -> Vec<(usize, usize)> {
    let mut map = Vec::new();
    for &n in base_face_sizes {
        for k in 0..n as usize {
            let index = map.len();
            map.push((index, if n == 4 { k } else { 0 }));
        }
    }
    for _ in 1..levels {
        let mut next = Vec::with_capacity(4 * map.len());
        for &(q, r) in &map {
            for j in 0..4 {
                let k = (j + r) % 4;
                next.push((4 * q + k, k));
            }
        }
        map = next;
    }
    map
}

fn bounding_diagonal(points: &[[f64; 3]]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    if lo[0] > hi[0] {
        return 0.0;
    }
    (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt()
}

/// Outcome of one comparison that ran.
struct Compared {
    worst_distance: f64,
    tolerance: f64,
}

/// Compares one fixture with our result; `Err` says what differs.
fn compare(entry: &Entry, scheme: Scheme) -> Result<Compared, String> {
    let boundary: Boundary =
        entry.boundary.parse().map_err(|e| format!("manifest boundary: {e}"))?;
    let input_path = root().join(&entry.input);
    let text = std::fs::read_to_string(&input_path)
        .map_err(|e| format!("cannot read {}: {e}", input_path.display()))?;
    let input = read_obj(&text).map_err(|e| format!("{}: {e}", input_path.display()))?;
    let options = Options::new(scheme, entry.level).with_boundary(boundary);
    let ours = subdivide(&input, &options).map_err(|e| format!("subdivide failed: {e}"))?;
    let reference = read_fixture(&root().join("tests/fixtures/osd").join(&entry.fixture));

    let our_faces = our_faces(&ours);
    if our_faces.len() != reference.faces.len() || ours.num_vertices() != reference.positions.len()
    {
        return Err(format!(
            "counts differ: ours {} vertices, {} faces; OpenSubdiv {} vertices, {} faces",
            ours.num_vertices(),
            our_faces.len(),
            reference.positions.len(),
            reference.faces.len()
        ));
    }
    // Our triangle split orders children as OpenSubdiv's Loop does: face i is face i.
    let correspondence = if entry.scheme == "loop" {
        (0..our_faces.len()).map(|i| (i, 0)).collect()
    } else {
        face_correspondence(&input.face_sizes, entry.level)
    };
    assert_eq!(correspondence.len(), our_faces.len(), "correspondence covers every face");

    // Vertex map from the face lists.
    const NONE: u32 = u32::MAX;
    let mut to_osd = vec![NONE; ours.num_vertices()];
    let mut from_osd = vec![NONE; reference.positions.len()];
    for (i, (face, &(q, r))) in our_faces.iter().zip(&correspondence).enumerate() {
        let theirs = &reference.faces[q];
        if theirs.len() != face.len() {
            return Err(format!(
                "our face {i} has {} vertices, OpenSubdiv's face {q} has {}",
                face.len(),
                theirs.len()
            ));
        }
        for (m, &v) in face.iter().enumerate() {
            let w = theirs[(m + r) % face.len()];
            if to_osd[v as usize] == NONE && from_osd[w as usize] == NONE {
                to_osd[v as usize] = w;
                from_osd[w as usize] = v;
            } else if to_osd[v as usize] != w || from_osd[w as usize] != v {
                return Err(format!(
                    "vertex map is not a bijection: our face {i} corner {m} pairs our vertex {v} with OpenSubdiv \
                     vertex {w} (face {q}, rotation {r}), but our {v} was paired with {} and their {w} with {}",
                    to_osd[v as usize] as i64, from_osd[w as usize] as i64
                ));
            }
        }
    }
    // Vertices that no face uses: isolated in both, same index.
    for v in 0..to_osd.len() {
        if to_osd[v] == NONE {
            if from_osd[v] != NONE {
                return Err(format!(
                    "our vertex {v} is in no face, but OpenSubdiv's vertex {v} is"
                ));
            }
            to_osd[v] = v as u32;
            from_osd[v] = v as u32;
        }
    }
    if let Some(w) = from_osd.iter().position(|&v| v == NONE) {
        return Err(format!("OpenSubdiv vertex {w} has no counterpart"));
    }

    let tolerance = RELATIVE_TOLERANCE * bounding_diagonal(&reference.positions);
    // Distance of each of our vertices to its counterpart; NaN counts as infinitely far.
    let distances: Vec<f64> = ours
        .positions
        .chunks_exact(3)
        .zip(&to_osd)
        .map(|(p, &w)| {
            let q = reference.positions[w as usize];
            let d = (0..3).map(|k| (p[k] as f64 - q[k]).powi(2)).sum::<f64>().sqrt();
            if d.is_nan() {
                f64::INFINITY
            } else {
                d
            }
        })
        .collect();
    let worst =
        distances
            .iter()
            .enumerate()
            .fold((0.0f64, 0usize), |best, (v, &d)| if d > best.0 { (d, v) } else { best });
    if worst.0 > tolerance {
        let (v, w) = (worst.1, to_osd[worst.1] as usize);
        let p = &ours.positions[3 * v..3 * v + 3];
        let bad = distances.iter().filter(|&&d| d > tolerance).count();
        return Err(format!(
            "{bad} of {} vertices differ; worst: our vertex {v} = [{}, {}, {}], OpenSubdiv vertex {w} = {:?}, \
             distance {:.3e} > tolerance {:.3e}",
            ours.num_vertices(),
            p[0],
            p[1],
            p[2],
            reference.positions[w],
            worst.0,
            tolerance
        ));
    }
    Ok(Compared { worst_distance: worst.0, tolerance })
}

/// Runs every fixture of OpenSubdiv scheme `osd_scheme` ("catmark" or "loop") and `boundary`
/// through our `scheme`, and fails listing all that disagree. `only` keeps the fixtures whose
/// input passes it (Quad/Triangle equals Catmull-Clark only on all-quad inputs).
fn run_group(osd_scheme: &str, scheme: Scheme, boundary: &str, only: fn(&PolyMesh) -> bool) {
    let dir = root().join("tests/fixtures/osd");
    let filter = std::env::var("OSD_FIXTURE_FILTER").unwrap_or_default();
    let entries: Vec<Entry> = read_manifest(&dir)
        .into_iter()
        .filter(|e| e.scheme == osd_scheme && e.boundary == boundary && e.fixture.contains(&filter))
        .filter(|e| {
            let text = std::fs::read_to_string(root().join(&e.input)).unwrap_or_default();
            read_obj(&text).is_ok_and(|m| only(&m))
        })
        .collect();
    if filter.is_empty() {
        assert!(
            !entries.is_empty(),
            "no {osd_scheme} {boundary} fixtures in {}/MANIFEST.tsv",
            dir.display()
        );
    }
    let mut failures = Vec::new();
    let mut shapes = BTreeSet::new();
    let mut worst_ratio = (0.0f64, String::new());
    for entry in &entries {
        shapes.insert(entry.input.clone());
        match compare(entry, scheme) {
            Ok(c) => {
                let ratio = if c.tolerance > 0.0 { c.worst_distance / c.tolerance } else { 0.0 };
                if ratio >= worst_ratio.0 {
                    worst_ratio = (ratio, entry.label());
                }
            }
            Err(message) => failures.push(format!("{}: {message}", entry.label())),
        }
    }
    println!(
        "osd_agreement {scheme} vs {osd_scheme} {boundary}: {} comparisons on {} shapes, {} passed, {} failed; closest pass to the tolerance: \
         {:.3} x tolerance ({})",
        entries.len(),
        shapes.len(),
        entries.len() - failures.len(),
        failures.len(),
        worst_ratio.0,
        worst_ratio.1
    );
    if !failures.is_empty() {
        let mut message = format!(
            "{} of {} {boundary} comparisons disagree with OpenSubdiv:\n",
            failures.len(),
            entries.len()
        );
        for f in &failures {
            let _ = writeln!(message, "  {f}");
        }
        panic!("{message}");
    }
}

fn any(_: &PolyMesh) -> bool {
    true
}

fn all_quads(m: &PolyMesh) -> bool {
    m.face_sizes.iter().all(|&n| n == 4)
}

#[test]
fn catmull_clark_edge_and_corner_matches_opensubdiv() {
    run_group("catmark", Scheme::CatmullClark, "edge-and-corner", any);
}

#[test]
fn loop_matches_opensubdiv() {
    run_group("loop", Scheme::Loop, "edge-and-corner", any);
    run_group("loop", Scheme::Loop, "edge-only", any);
}

/// Quad/Triangle is Catmull-Clark on all-quad meshes and Loop on all-triangle meshes.
#[test]
fn quad_triangle_matches_opensubdiv_catmull_clark_and_loop() {
    for boundary in ["edge-and-corner", "edge-only"] {
        run_group("catmark", Scheme::QuadTriangle, boundary, all_quads);
        run_group("loop", Scheme::QuadTriangle, boundary, any);
    }
}

#[test]
fn catmull_clark_edge_only_matches_opensubdiv() {
    run_group("catmark", Scheme::CatmullClark, "edge-only", any);
}

#[test]
fn manifests_name_existing_files() {
    for dir in ["tests/fixtures/osd", "tests/fixtures/osd_tagged"] {
        let dir = root().join(dir);
        let entries = read_manifest(&dir);
        assert!(!entries.is_empty(), "{}/MANIFEST.tsv lists no fixtures", dir.display());
        for e in entries {
            assert!(
                dir.join(&e.fixture).is_file(),
                "{}: fixture {} is missing",
                dir.display(),
                e.fixture
            );
            assert!(
                root().join(&e.input).is_file(),
                "{}: input {} is missing",
                dir.display(),
                e.input
            );
            assert!(
                ["catmark", "loop", "bilinear"].contains(&e.scheme.as_str()),
                "unknown scheme {}",
                e.scheme
            );
            assert!(
                ["edge-and-corner", "edge-only", "none"].contains(&e.boundary.as_str()),
                "unknown boundary {}",
                e.boundary
            );
        }
    }
}

#[test]
fn face_correspondence_rule() {
    // A quad and a triangle at level 1: the quad's children rotate, the triangle's do not.
    assert_eq!(
        face_correspondence(&[4, 3], 1),
        vec![(0, 0), (1, 1), (2, 2), (3, 3), (4, 0), (5, 0), (6, 0)]
    );
    // Level 2 under the quad's second child (rotation 1): our corner j is their corner j + 1.
    let two = face_correspondence(&[4], 2);
    assert_eq!(&two[4..8], &[(5, 1), (6, 2), (7, 3), (4, 0)]);
}
