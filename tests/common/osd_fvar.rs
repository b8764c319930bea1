//! The face-varying fixtures of `tests/fixtures/osd_fvar/` (made by
//! `tools/osd/make_fvar_fixtures.sh` with OpenSubdiv's `PrimvarRefiner::InterpolateFaceVarying`):
//! the manifest and a reader. Each fixture has `vt` lines (the last level's values in
//! OpenSubdiv's order) and `f v/vt` corners in OpenSubdiv's face order, holes left out; the
//! positions are in the matching position fixture.
#![allow(dead_code)]

use std::path::Path;
use subsurf::attributes::Attribute;

/// One row of `MANIFEST.tsv`.
#[derive(Clone, Debug)]
pub struct FvarEntry {
    pub fixture: String,
    /// OpenSubdiv's name: catmark, loop or bilinear.
    pub scheme: String,
    pub boundary: String,
    pub level: u32,
    pub input: String,
    /// The face-varying linear interpolation mode, in our names.
    pub mode: String,
    pub tagged: bool,
}

impl FvarEntry {
    pub fn label(&self) -> String {
        let shape = Path::new(&self.input).file_stem().unwrap().to_string_lossy().into_owned();
        let tags = if self.tagged { "tagged" } else { "untagged" };
        format!(
            "{shape} [{} {tags}, {}, level {}] ({})",
            self.scheme, self.mode, self.level, self.fixture
        )
    }
}

pub fn read_fvar_manifest(dir: &Path) -> Vec<FvarEntry> {
    let path = dir.join("MANIFEST.tsv");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| {
        panic!("cannot read {}: {e}; run tools/osd/make_fvar_fixtures.sh", path.display())
    });
    let mut entries = Vec::new();
    for (n, line) in text.lines().enumerate() {
        if line.starts_with('#') || line.trim().is_empty() {
            continue;
        }
        let cols: Vec<&str> = line.split('\t').collect();
        let bad = || format!("{}:{}: expected 7 tab-separated columns", path.display(), n + 1);
        assert_eq!(cols.len(), 7, "{}", bad());
        entries.push(FvarEntry {
            fixture: cols[0].to_string(),
            scheme: cols[1].to_string(),
            boundary: cols[2].to_string(),
            level: cols[3].parse().unwrap_or_else(|_| panic!("{}", bad())),
            input: cols[4].to_string(),
            mode: cols[5].to_string(),
            tagged: match cols[6] {
                "yes" => true,
                "no" => false,
                _ => panic!("{}", bad()),
            },
        });
    }
    entries
}

/// A face-varying fixture: the values, and per face its vertex and value indices (0-based).
pub struct FvarFixture {
    pub values: Vec<[f64; 2]>,
    pub faces: Vec<Vec<(u32, u32)>>,
}

pub fn read_fvar_fixture(path: &Path) -> FvarFixture {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let mut fixture = FvarFixture { values: Vec::new(), faces: Vec::new() };
    for (n, line) in text.lines().enumerate() {
        let bad = || format!("{}:{}: cannot parse '{line}'", path.display(), n + 1);
        let mut words = line.split_whitespace();
        match words.next() {
            Some("vt") => {
                let mut uv = [0.0f64; 2];
                for c in &mut uv {
                    *c = words
                        .next()
                        .and_then(|w| w.parse().ok())
                        .unwrap_or_else(|| panic!("{}", bad()));
                }
                fixture.values.push(uv);
            }
            Some("f") => {
                let corners = words
                    .map(|w| {
                        let (v, t) = w.split_once('/').unwrap_or_else(|| panic!("{}", bad()));
                        let index = |s: &str| {
                            s.parse::<u32>()
                                .ok()
                                .and_then(|i| i.checked_sub(1))
                                .unwrap_or_else(|| panic!("{}", bad()))
                        };
                        (index(v), index(t))
                    })
                    .collect();
                fixture.faces.push(corners);
            }
            _ => panic!("{}", bad()),
        }
    }
    fixture
}

/// The input's `vt` values and the `vt` index of every face corner, in face order.
pub fn input_uvs(text: &str) -> Vec<Attribute> {
    let (mut values, mut indices) = (Vec::new(), Vec::new());
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("vt") => {
                let uv: Vec<f32> = words.take(2).map(|w| w.parse().unwrap()).collect();
                values.extend_from_slice(&uv);
            }
            Some("f") => {
                for corner in words {
                    let t = corner.split('/').nth(1).expect("a vt index on every corner");
                    indices.push(t.parse::<u32>().unwrap() - 1);
                }
            }
            _ => {}
        }
    }
    vec![Attribute::face_varying("uv", 2, values, indices)]
}
