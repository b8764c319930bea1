//! The face-varying fixtures are whole and consistent with the position fixtures: every manifest
//! row's file parses with finite values and every value index in range, every mode of the
//! six appears for each case, and where the position fixture of the same shape, scheme, boundary
//! and level exists, the faces list the same vertices in the same order (so the comparisons of
//! face-varying results can reuse the position fixtures' face correspondence).

#[path = "common/osd.rs"]
mod osd;
#[path = "common/osd_fvar.rs"]
mod osd_fvar;

use osd::{read_fixture, read_manifest, root};
use osd_fvar::{read_fvar_fixture, read_fvar_manifest};
use std::collections::{BTreeMap, BTreeSet};

#[test]
fn fvar_fixtures_are_whole_and_match_the_position_fixtures() {
    let dir = root().join("tests/fixtures/osd_fvar");
    let entries = read_fvar_manifest(&dir);
    assert!(entries.len() > 2000, "{} rows", entries.len());
    let shapes: BTreeSet<&str> = entries.iter().map(|e| e.input.as_str()).collect();
    assert!(shapes.len() >= 100, "{} shapes", shapes.len());

    // The position fixtures, by (input, boundary, level), untagged and tagged apart.
    let mut positions = BTreeMap::new();
    for (set, tagged) in [("osd", false), ("osd_tagged", true), ("osd_nonmanifold", true)] {
        let set_dir = root().join("tests/fixtures").join(set);
        for e in read_manifest(&set_dir) {
            let key = (e.input.clone(), e.boundary.clone(), e.level, tagged);
            positions.insert(key, set_dir.join(&e.fixture));
        }
    }

    let mut modes_per_case: BTreeMap<(String, u32, bool), BTreeSet<String>> = BTreeMap::new();
    let mut matched = 0;
    for e in &entries {
        let fixture = read_fvar_fixture(&dir.join(&e.fixture));
        let what = e.label();
        assert!(!fixture.faces.is_empty(), "{what}: no faces");
        for corners in &fixture.faces {
            for &(_, t) in corners {
                assert!((t as usize) < fixture.values.len(), "{what}: vt {t} out of range");
            }
        }
        assert!(fixture.values.iter().flatten().all(|x| x.is_finite()), "{what}");
        modes_per_case
            .entry((e.input.clone(), e.level, e.tagged))
            .or_default()
            .insert(e.mode.clone());
        let key = (e.input.clone(), e.boundary.clone(), e.level, e.tagged);
        if let Some(path) = positions.get(&key) {
            let reference = read_fixture(path);
            assert_eq!(
                reference.faces.len(),
                fixture.faces.len(),
                "{what}: face count vs {}",
                path.display()
            );
            for (f, (a, b)) in reference.faces.iter().zip(&fixture.faces).enumerate() {
                let vertices: Vec<u32> = b.iter().map(|&(v, _)| v).collect();
                assert_eq!(a, &vertices, "{what}: face {f} vs {}", path.display());
            }
            matched += 1;
        }
    }
    for (case, modes) in &modes_per_case {
        assert_eq!(modes.len(), 6, "{case:?}: modes {modes:?}");
    }
    assert!(matched > 1000, "{matched} rows checked against position fixtures");
}
