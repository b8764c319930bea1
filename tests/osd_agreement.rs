//! Agreement with OpenSubdiv: every untagged Catmull-Clark and Loop fixture in
//! `tests/fixtures/osd/`, and every tagged one in `tests/fixtures/osd_tagged/` (creases, corners,
//! holes, crease method, smooth triangles and boundary mode read from the OBJ's `t` lines), each
//! listed in its directory's `MANIFEST.tsv` (written by `tools/osd/make_fixtures.sh`), is
//! recomputed with [`subdivide`] / [`subdivide_with_tags`] and compared vertex by vertex.
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
//! Holes: neither output lists the descendants of a hole face (a base face tagged `hole`, or
//! under boundary `none` a base face at a vertex with a boundary edge not tagged infinitely
//! sharp). Both libraries keep the
//! descendants of one base face contiguous, so the correspondence above is computed over all
//! faces and then both sides skip the faces whose base face is a hole. Vertices that only hole
//! faces use appear in no face list and cannot be paired; their numbers must agree, and they are
//! not compared.
//!
//! Set `OSD_FIXTURE_FILTER=substring` to run only the fixtures whose file name contains it.

#[path = "common/osd.rs"]
mod osd;

use osd::{all_quads, any, face_correspondence, read_manifest, root, run_group, Set};
use subsurf::Scheme;

#[test]
fn catmull_clark_edge_and_corner_matches_opensubdiv() {
    run_group(Set::Untagged, "catmark", Scheme::CatmullClark, Some("edge-and-corner"), any);
}

#[test]
fn loop_matches_opensubdiv() {
    run_group(Set::Untagged, "loop", Scheme::Loop, Some("edge-and-corner"), any);
    run_group(Set::Untagged, "loop", Scheme::Loop, Some("edge-only"), any);
}

/// Quad/Triangle is Catmull-Clark on all-quad meshes and Loop on all-triangle meshes.
#[test]
fn quad_triangle_matches_opensubdiv_catmull_clark_and_loop() {
    for boundary in ["edge-and-corner", "edge-only"] {
        run_group(Set::Untagged, "catmark", Scheme::QuadTriangle, Some(boundary), all_quads);
        run_group(Set::Untagged, "loop", Scheme::QuadTriangle, Some(boundary), any);
    }
}

#[test]
fn catmull_clark_edge_only_matches_opensubdiv() {
    run_group(Set::Untagged, "catmark", Scheme::CatmullClark, Some("edge-only"), any);
}

/// Creases, corners, holes, Chaikin, smooth triangles and the three boundary modes (the tags of
/// OpenSubdiv's regression shapes), Catmull-Clark.
#[test]
fn tagged_catmull_clark_matches_opensubdiv() {
    run_group(Set::Tagged, "catmark", Scheme::CatmullClark, None, any);
}

/// The same for Loop.
#[test]
fn tagged_loop_matches_opensubdiv() {
    run_group(Set::Tagged, "loop", Scheme::Loop, None, any);
}

#[test]
fn manifests_name_existing_files() {
    for dir in [
        "tests/fixtures/osd",
        "tests/fixtures/osd_tagged",
        "tests/fixtures/osd_nonmanifold",
        "tests/fixtures/osd_nonmanifold_untagged",
    ] {
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
                ["catmark", "loop", "bilinear", "midpoint"].contains(&e.scheme.as_str()),
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
