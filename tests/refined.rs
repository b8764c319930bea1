//! `subdivide_refined`: the pieces a result hands over (indices, face sizes, the fan
//! triangulation) join up to the arrays of `into_poly`, whichever form the result takes (the
//! implicit faces of a last untagged quad split, or flat arrays), across piece boundaries, and
//! the fan of the implicit faces is `PolyMesh::triangles` of the flat ones.

use subsurf::scheme::{subdivide_mesh_borrowed, subdivide_refined, Refined};
use subsurf::shapes::{cube, grid, prism, torus, torus_triangles};
use subsurf::{Crease, HalfEdgeMesh, Options, PolyMesh, Scheme, Tags};

fn joined(len: usize, fill: impl FnOnce(&mut dyn FnMut(&[u32]))) -> Vec<u32> {
    let mut out = Vec::new();
    fill(&mut |chunk: &[u32]| out.extend_from_slice(chunk));
    assert_eq!(out.len(), len, "the pieces add up to the announced length");
    out
}

fn check(mesh: &PolyMesh, options: &Options, tags: &Tags, what: &str) {
    let refined: Refined = subdivide_refined(mesh, options, tags).expect(what);
    let (mut indices, mut triangles) = (Vec::new(), Vec::new());
    refined.index_and_triangle_chunks(
        |c| indices.extend_from_slice(c),
        |c| triangles.extend_from_slice(c),
    );
    assert_eq!(indices.len(), refined.num_indices(), "{what}: index count");
    assert_eq!(triangles.len(), refined.num_triangle_indices(), "{what}: triangle count");
    let sizes = joined(refined.num_faces(), |sink| refined.face_size_chunks(sink));
    if let Some(n) = refined.uniform_face_size() {
        assert!(sizes.iter().all(|&s| s == n), "{what}: every face has {n} corners");
    }
    let positions = refined.positions().to_vec();
    let poly = refined.into_poly();
    assert_eq!(positions, poly.positions, "{what}: positions");
    assert_eq!(indices, poly.indices, "{what}: indices");
    assert_eq!(sizes, poly.face_sizes, "{what}: face sizes");
    // The fan of the flat arrays (checked face by face in src/mesh/poly.rs's unit tests).
    assert_eq!(triangles, poly.triangles(), "{what}: triangles");
    // The same call through the flat-array API gives the same arrays.
    assert_eq!(subsurf::subdivide_with_tags(mesh, options, tags).expect(what), poly, "{what}");
}

#[test]
fn pieces_join_up_to_the_flat_arrays() {
    // 40 x 40 quads: 6,400 child quads at level 1 (25,600 indices), 25,600 at level 2: the
    // implicit quads span one and several pieces of 49,152 indices.
    let meshes = [
        ("cube", cube()),
        ("grid", grid(40, 40)),
        ("torus", torus(40, 40, 1.0, 0.25)),
        ("triangle torus", torus_triangles(20, 20, 1.0, 0.25)),
        ("prism", prism(7)),
    ];
    let mut crease = Tags::default();
    crease.creases.push(Crease { vertices: [0, 1], sharpness: 2.0 });
    for (name, mesh) in &meshes {
        let triangles = mesh.face_sizes.iter().all(|&n| n == 3);
        for &scheme in Scheme::ALL {
            if scheme.triangles_only() && !triangles {
                continue;
            }
            for levels in 1..=2 {
                let options = Options::new(scheme, levels);
                check(mesh, &options, &Tags::default(), &format!("{name} {scheme} {levels}"));
                if matches!(scheme, Scheme::CatmullClark | Scheme::Loop) {
                    let what = format!("{name} {scheme} {levels} creased");
                    check(mesh, &options, &crease, &what);
                }
            }
        }
    }
}

/// `subdivide_mesh_borrowed` runs the same levels on a base it leaves as it was: its results are
/// those of the flat-array API, call after call, with tags and without, for a single quad split
/// (whose implicit faces follow from the borrowed base) and for more levels; and after
/// `set_positions`, those of the flat API on the moved mesh.
#[test]
fn a_borrowed_base_gives_the_same_results_and_stays() {
    let mut crease = Tags::default();
    crease.creases.push(Crease { vertices: [0, 1], sharpness: 2.0 });
    for (name, mesh) in [("cube", cube()), ("triangle torus", torus_triangles(8, 8, 1.0, 0.25))] {
        let mut base = HalfEdgeMesh::from_poly(&mesh).expect(name);
        let kept = base.clone();
        let triangles = mesh.face_sizes.iter().all(|&n| n == 3);
        for &scheme in Scheme::ALL.iter().filter(|s| triangles || !s.triangles_only()) {
            for levels in 0..=2 {
                let options = Options::new(scheme, levels);
                let tagged = matches!(scheme, Scheme::CatmullClark | Scheme::Loop);
                for tags in [&Tags::default(), &crease].into_iter().take(1 + tagged as usize) {
                    let what = format!("{name} {scheme} {levels} {tags:?}");
                    let expected =
                        subsurf::subdivide_with_tags(&mesh, &options, tags).expect(&what);
                    for _ in 0..2 {
                        let got = subdivide_mesh_borrowed(&base, &options, tags).expect(&what);
                        assert_eq!(got.into_poly(), expected, "{what}");
                    }
                    assert_eq!(base, kept, "{what}: the base is unchanged");
                }
            }
        }
        let moved: Vec<[f32; 3]> =
            base.positions().iter().map(|p| p.map(|x| 3.0 * x - 0.5)).collect();
        let moved_poly = PolyMesh { positions: moved.as_flattened().to_vec(), ..mesh.clone() };
        base.set_positions(moved).expect(name);
        let options = Options::new(Scheme::CatmullClark, 2);
        let expected = subsurf::subdivide(&moved_poly, &options).expect(name);
        let got = subdivide_mesh_borrowed(&base, &options, &Tags::default()).expect(name);
        assert_eq!(got.into_poly(), expected, "{name}: moved");
    }
}
