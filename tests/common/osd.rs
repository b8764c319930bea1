//! The OpenSubdiv comparison shared by `tests/osd_agreement.rs` and `tests/nonmanifold.rs`:
//! fixture manifests, the face correspondence and the vertex-by-vertex comparison. See the
//! module docs of `tests/osd_agreement.rs` for how our output corresponds to OpenSubdiv's.
#![allow(dead_code)]

use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use subsurf::attributes::Attribute;
use subsurf::io::{read_obj, read_obj_with_tags};
use subsurf::scheme::subdivide_with_attributes;
use subsurf::{Boundary, FVarLinear, HalfEdgeMesh, Options, PolyMesh, Scheme, Tags};

pub const RELATIVE_TOLERANCE: f64 = 1e-5;

pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// One row of a fixture manifest.
#[derive(Clone, Debug)]
pub struct Entry {
    pub fixture: String,
    pub scheme: String,
    pub boundary: String,
    pub level: u32,
    pub input: String,
}

impl Entry {
    pub fn label(&self) -> String {
        let shape = Path::new(&self.input).file_stem().unwrap().to_string_lossy().into_owned();
        format!("{shape} [{} boundary, level {}] ({})", self.boundary, self.level, self.fixture)
    }
}

pub fn read_manifest(dir: &Path) -> Vec<Entry> {
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
pub struct RefMesh {
    pub positions: Vec<[f64; 3]>,
    pub faces: Vec<Vec<u32>>,
}

pub fn read_fixture(path: &Path) -> RefMesh {
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

pub fn our_faces(mesh: &PolyMesh) -> Vec<&[u32]> {
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
pub fn face_correspondence(base_face_sizes: &[u32], levels: u32) -> Vec<(usize, usize)> {
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

pub fn bounding_diagonal(points: &[[f64; 3]]) -> f64 {
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
pub struct Compared {
    pub worst_distance: f64,
    pub tolerance: f64,
}

/// Which fixture set a comparison reads.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Set {
    /// `tests/fixtures/osd/`: tags ignored, boundary from the manifest.
    Untagged,
    /// `tests/fixtures/osd_tagged/`: tags and boundary from the input OBJ (edge-only when it has
    /// no `interpolateboundary`, as OpenSubdiv's regression suite).
    Tagged,
    /// `tests/fixtures/osd_nonmanifold/`: the non-manifold shapes, read as `Tagged`.
    NonManifold,
    /// `tests/fixtures/osd_nonmanifold_untagged/`: the non-manifold shapes, read as `Untagged`,
    /// with rows for the linear schemes too (`bilinear`; `midpoint`, which OpenSubdiv made as
    /// Loop's topology with positions interpolated as varying data).
    NonManifoldUntagged,
}

impl Set {
    pub fn dir(self) -> PathBuf {
        root().join(match self {
            Set::Untagged => "tests/fixtures/osd",
            Set::Tagged => "tests/fixtures/osd_tagged",
            Set::NonManifold => "tests/fixtures/osd_nonmanifold",
            Set::NonManifoldUntagged => "tests/fixtures/osd_nonmanifold_untagged",
        })
    }

    pub fn name(self) -> &'static str {
        match self {
            Set::Untagged => "untagged",
            Set::Tagged => "tagged",
            Set::NonManifold => "non-manifold",
            Set::NonManifoldUntagged => "non-manifold untagged",
        }
    }
}

/// Our scheme for a manifest's scheme column: OpenSubdiv's `catmark`, `loop` and `bilinear`, and
/// `midpoint` (Loop's topology, linear positions).
pub fn our_scheme(manifest_scheme: &str) -> Scheme {
    match manifest_scheme {
        "catmark" => Scheme::CatmullClark,
        "loop" => Scheme::Loop,
        "bilinear" => Scheme::Bilinear,
        "midpoint" => Scheme::Midpoint,
        other => panic!("unknown manifest scheme {other}"),
    }
}

/// The base face of each face of a level-`levels` result, in our (full, hole-free) numbering,
/// which is also OpenSubdiv's numbering up to permutations inside each base face's block.
pub fn base_faces(base_face_sizes: &[u32], levels: u32, loop_scheme: bool) -> Vec<usize> {
    let mut map: Vec<usize> = if loop_scheme {
        (0..base_face_sizes.len()).collect()
    } else {
        base_face_sizes
            .iter()
            .enumerate()
            .flat_map(|(f, &n)| std::iter::repeat_n(f, n as usize))
            .collect()
    };
    let first = if loop_scheme { 0 } else { 1 };
    for _ in first..levels {
        map = map.iter().flat_map(|&f| [f; 4]).collect();
    }
    map
}

/// Our result for a fixture's input, with the input, the refined attribute channels and which
/// base faces are holes.
pub struct Ours {
    pub input: PolyMesh,
    pub result: PolyMesh,
    pub channels: Vec<Attribute>,
    pub holes: Vec<bool>,
}

/// Runs `scheme` on `entry`'s input as set `set` reads it, with the channels `attributes` makes
/// from the input's text, under `fvar_linear`.
pub fn ours(
    entry: &Entry,
    scheme: Scheme,
    set: Set,
    attributes: &dyn Fn(&str) -> Vec<Attribute>,
    fvar_linear: FVarLinear,
) -> Result<Ours, String> {
    let manifest_boundary: Boundary =
        entry.boundary.parse().map_err(|e| format!("manifest boundary: {e}"))?;
    let input_path = root().join(&entry.input);
    let text = std::fs::read_to_string(&input_path)
        .map_err(|e| format!("cannot read {}: {e}", input_path.display()))?;
    let channels = attributes(&text);
    let run = |mesh: &PolyMesh, options: Options, tags: &Tags| {
        let options = options.with_fvar_linear(fvar_linear);
        subdivide_with_attributes(mesh, &channels, &options, tags)
            .map_err(|e| format!("subdivide failed: {e}"))
    };
    match set {
        Set::Untagged | Set::NonManifoldUntagged => {
            let input = read_obj(&text).map_err(|e| format!("{}: {e}", input_path.display()))?;
            let options = Options::new(scheme, entry.level).with_boundary(manifest_boundary);
            let (result, channels) = run(&input, options, &Tags::default())?;
            let holes = vec![false; input.num_faces()];
            Ok(Ours { input, result, channels, holes })
        }
        Set::Tagged | Set::NonManifold => {
            let obj =
                read_obj_with_tags(&text).map_err(|e| format!("{}: {e}", input_path.display()))?;
            let boundary = obj.boundary.unwrap_or(Boundary::EdgeOnly);
            if boundary != manifest_boundary {
                return Err(format!(
                    "the OBJ's boundary mode {boundary} differs from the manifest's {manifest_boundary}"
                ));
            }
            let options = Options::new(scheme, entry.level).with_boundary(boundary);
            let (result, channels) = run(&obj.mesh, options, &obj.tags)?;
            // Hole base faces: the tagged ones, and under 'none' those at a boundary vertex.
            let mut holes = vec![false; obj.mesh.num_faces()];
            for &f in &obj.tags.holes {
                holes[f as usize] = true;
            }
            if boundary == Boundary::None {
                // A face at a vertex with a boundary edge that is not tagged infinitely sharp.
                let he = HalfEdgeMesh::from_poly(&obj.mesh).map_err(|e| e.to_string())?;
                let infinite = |a: u32, b: u32| {
                    obj.tags.creases.iter().any(|c| {
                        (c.vertices == [a, b] || c.vertices == [b, a]) && c.sharpness >= 10.0
                    })
                };
                let mut excluded = vec![false; he.num_vertices()];
                for h in he.half_edge_indices() {
                    let h = he.half_edge(h).unwrap();
                    let (a, b) = (h.from_vertex_index(), h.to_vertex_index());
                    if h.is_boundary() && !infinite(a, b) {
                        excluded[a as usize] = true;
                        excluded[b as usize] = true;
                    }
                }
                for c in he.cell_indices() {
                    let cell = he.cell(c).unwrap();
                    if cell.vertex_indices().iter().any(|&v| excluded[v as usize]) {
                        holes[c as usize] = true;
                    }
                }
            }
            Ok(Ours { input: obj.mesh, result, channels, holes })
        }
    }
}

/// For each of our result's faces (holes left out), OpenSubdiv's fixture face and the rotation
/// (our corner `m` is its corner `(m + r) mod n`); and how many faces the fixture must have.
pub fn face_pairs(entry: &Entry, ours: &Ours) -> (Vec<(usize, usize)>, usize) {
    // Loop and midpoint split triangles; the others split into quads.
    let loop_scheme = entry.scheme == "loop" || entry.scheme == "midpoint";
    let base_of = base_faces(&ours.input.face_sizes, entry.level, loop_scheme);
    let is_hole = |full: usize| ours.holes[base_of[full]];
    // Our triangle split orders children as OpenSubdiv's Loop does: face i is face i.
    let correspondence = if loop_scheme {
        (0..base_of.len()).map(|i| (i, 0)).collect()
    } else {
        face_correspondence(&ours.input.face_sizes, entry.level)
    };
    assert_eq!(correspondence.len(), base_of.len(), "correspondence covers every face");
    // OpenSubdiv's fixture index of each of its faces (in full numbering) that is not a hole.
    let mut fixture_index = vec![usize::MAX; base_of.len()];
    let mut kept = 0usize;
    for (q, slot) in fixture_index.iter_mut().enumerate() {
        if !is_hole(q) {
            *slot = kept;
            kept += 1;
        }
    }
    let pairs = (0..base_of.len())
        .filter(|&full| !is_hole(full))
        .map(|full| {
            let (q, r) = correspondence[full];
            (fixture_index[q], r)
        })
        .collect();
    (pairs, kept)
}

/// The vertex map our result -> OpenSubdiv's fixture, read off the face lists (`pairs` from
/// [`face_pairs`]); `NO_VERTEX` for our vertices that only hole faces use.
pub fn vertex_map(
    ours: &PolyMesh,
    reference: &RefMesh,
    pairs: Vec<(usize, usize)>,
    holes: &[bool],
) -> Result<Vec<u32>, String> {
    let our_faces = our_faces(ours);
    let mut to_osd = vec![NO_VERTEX; ours.num_vertices()];
    let mut from_osd = vec![NO_VERTEX; reference.positions.len()];
    for (i, (face, (q, r))) in our_faces.iter().zip(pairs).enumerate() {
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
            if to_osd[v as usize] == NO_VERTEX && from_osd[w as usize] == NO_VERTEX {
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
    let any_holes = holes.iter().any(|&h| h);
    if any_holes {
        // Vertices only hole faces use cannot be paired: their numbers must agree.
        let ours_unpaired = to_osd.iter().filter(|&&w| w == NO_VERTEX).count();
        let theirs_unpaired = from_osd.iter().filter(|&&v| v == NO_VERTEX).count();
        if ours_unpaired != theirs_unpaired {
            return Err(format!(
                "{ours_unpaired} of our vertices are in no face, but {theirs_unpaired} of OpenSubdiv's"
            ));
        }
    } else {
        // Vertices that no face uses: isolated in both, same index.
        for v in 0..to_osd.len() {
            if to_osd[v] == NO_VERTEX {
                if from_osd[v] != NO_VERTEX {
                    return Err(format!(
                        "our vertex {v} is in no face, but OpenSubdiv's vertex {v} is"
                    ));
                }
                to_osd[v] = v as u32;
                from_osd[v] = v as u32;
            }
        }
        if let Some(w) = from_osd.iter().position(|&v| v == NO_VERTEX) {
            return Err(format!("OpenSubdiv vertex {w} has no counterpart"));
        }
    }

    Ok(to_osd)
}

/// Our vertices that [`vertex_map`] cannot pair.
pub const NO_VERTEX: u32 = u32::MAX;

/// Compares one fixture with our result; `Err` says what differs.
pub fn compare(entry: &Entry, scheme: Scheme, set: Set) -> Result<Compared, String> {
    let no_channels = |_: &str| Vec::new();
    let run = ours(entry, scheme, set, &no_channels, FVarLinear::default())?;
    let (pairs, kept) = face_pairs(entry, &run);
    let (ours, holes) = (run.result, run.holes);
    let reference = read_fixture(&set.dir().join(&entry.fixture));

    let our_faces = our_faces(&ours);
    if our_faces.len() != reference.faces.len()
        || our_faces.len() != kept
        || ours.num_vertices() != reference.positions.len()
    {
        return Err(format!(
            "counts differ: ours {} vertices, {} faces; OpenSubdiv {} vertices, {} faces; {kept} faces expected without holes",
            ours.num_vertices(),
            our_faces.len(),
            reference.positions.len(),
            reference.faces.len()
        ));
    }
    let to_osd = vertex_map(&ours, &reference, pairs, &holes)?;
    let tolerance = RELATIVE_TOLERANCE * bounding_diagonal(&reference.positions);
    // Distance of each of our vertices to its counterpart; NaN counts as infinitely far.
    let distances: Vec<f64> = ours
        .positions
        .chunks_exact(3)
        .zip(&to_osd)
        .map(|(p, &w)| {
            if w == NO_VERTEX {
                return 0.0;
            }
            let q = reference.positions[w as usize];
            let d = (0..3).map(|k| (p[k] as f64 - q[k]).powi(2)).sum::<f64>().sqrt();
            if d.is_nan() {
                f64::INFINITY
            } else {
                d
            }
        })
        .collect();
    if ours.positions.iter().any(|x| !x.is_finite()) {
        return Err("our result has a NaN or infinite coordinate".into());
    }
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

/// Runs every fixture of set `set`, OpenSubdiv scheme `osd_scheme` ("catmark" or "loop") and
/// `boundary` (any boundary when `None`) through our `scheme`, and fails listing all that
/// disagree. `only` keeps the fixtures whose input passes it (Quad/Triangle equals Catmull-Clark
/// only on all-quad inputs).
pub fn run_group(
    set: Set,
    osd_scheme: &str,
    scheme: Scheme,
    boundary: Option<&str>,
    only: fn(&PolyMesh) -> bool,
) {
    let dir = set.dir();
    let filter = std::env::var("OSD_FIXTURE_FILTER").unwrap_or_default();
    let boundary_name = boundary.unwrap_or("any");
    let entries: Vec<Entry> = read_manifest(&dir)
        .into_iter()
        .filter(|e| {
            e.scheme == osd_scheme
                && boundary.is_none_or(|b| e.boundary == b)
                && e.fixture.contains(&filter)
        })
        .filter(|e| {
            let text = std::fs::read_to_string(root().join(&e.input)).unwrap_or_default();
            read_obj(&text).is_ok_and(|m| only(&m))
        })
        .collect();
    if filter.is_empty() {
        assert!(
            !entries.is_empty(),
            "no {osd_scheme} {boundary_name} fixtures in {}/MANIFEST.tsv",
            dir.display()
        );
    }
    let mut failures = Vec::new();
    let mut shapes = BTreeSet::new();
    let mut worst_ratio = (0.0f64, String::new());
    for entry in &entries {
        shapes.insert(entry.input.clone());
        match compare(entry, scheme, set) {
            Ok(c) => {
                let ratio = if c.tolerance > 0.0 { c.worst_distance / c.tolerance } else { 0.0 };
                if ratio >= worst_ratio.0 {
                    worst_ratio = (ratio, entry.label());
                }
            }
            Err(message) => failures.push(format!("{}: {message}", entry.label())),
        }
    }
    let set_name = set.name();
    println!(
        "osd_agreement {set_name} {scheme} vs {osd_scheme} {boundary_name}: {} comparisons on {} shapes, {} passed, {} failed; closest pass to the tolerance: \
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
            "{} of {} {set_name} {boundary_name} comparisons disagree with OpenSubdiv:\n",
            failures.len(),
            entries.len()
        );
        for f in &failures {
            let _ = writeln!(message, "  {f}");
        }
        panic!("{message}");
    }
}

pub fn any(_: &PolyMesh) -> bool {
    true
}

pub fn all_quads(m: &PolyMesh) -> bool {
    m.face_sizes.iter().all(|&n| n == 4)
}
