//! Stencil tables (`scheme::stencil_table`): for every scheme, levels 1-3, boundary mode, tags and
//! holes, on the sample shapes and OpenSubdiv's regression shapes, the table evaluated for the
//! control positions gives `subdivide`'s positions, and again after the control positions move
//! (the table is built once); every row is affine (weights summing to 1, ascending control
//! indices); a vertex-varying channel evaluated through the table equals
//! `subdivide_with_attributes`' channel; and the guards refuse what does not fit.

mod common;

use common::{diagonal, sample_meshes};
use subsurf::attributes::Attribute;
use subsurf::io::obj::read_obj_with_tags;
use subsurf::scheme::{predict, predict_counts, stencil_table_mesh, subdivide_with_attributes};
use subsurf::shapes::{cube, grid, grid_with_hole, torus};
use subsurf::{
    stencil_table, subdivide_with_tags, Boundary, Corner, Crease, Error, Evaluator, HalfEdgeMesh,
    Options, PolyMesh, Scheme, StencilTable, Tags,
};

/// A small deterministic generator (xorshift), for deformations and channel values.
struct Random(u64);

impl Random {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
    }
}

/// `got` equals `want` within `1e-5 × scale` everywhere.
fn assert_close(got: &[f32], want: &[f32], scale: f32, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: lengths");
    let tolerance = 1e-5 * scale;
    let worst = got
        .iter()
        .zip(want)
        .enumerate()
        .max_by(|a, b| (a.1 .0 - a.1 .1).abs().total_cmp(&(b.1 .0 - b.1 .1).abs()));
    if let Some((i, (g, w))) = worst {
        assert!(
            (g - w).abs() <= tolerance,
            "{what}: value {i} (vertex {}) is {g}, subdivide gives {w} (tolerance {tolerance})",
            i / 3
        );
    }
}

/// Every row: distinct control indices below the control count, weights summing to 1.
fn check_rows(table: &StencilTable, what: &str) {
    assert_eq!(table.offsets().len(), table.num_stencils() + 1, "{what}");
    assert_eq!(table.offsets()[0], 0, "{what}");
    assert_eq!(*table.offsets().last().unwrap() as usize, table.indices().len(), "{what}");
    assert_eq!(table.indices().len(), table.weights().len(), "{what}");
    for i in 0..table.num_stencils() {
        let (indices, weights) = table.stencil(i).unwrap();
        assert!(!indices.is_empty(), "{what}: stencil {i} is empty");
        let mut sorted = indices.to_vec();
        sorted.sort_unstable();
        assert!(sorted.windows(2).all(|w| w[0] < w[1]), "{what}: stencil {i} {indices:?}");
        assert!((*sorted.last().unwrap() as usize) < table.num_control_vertices(), "{what}");
        let total: f64 = weights.iter().map(|&w| f64::from(w)).sum();
        assert!((total - 1.0).abs() < 1e-5, "{what}: stencil {i} sums to {total}");
    }
    assert!(table.stencil(table.num_stencils()).is_none(), "{what}");
}

/// The checks of one call; false when `subdivide` refuses it (and the table is refused alike).
fn check_call(mesh: &PolyMesh, options: &Options, tags: &Tags, what: &str) -> bool {
    let expected = subdivide_with_tags(mesh, options, tags);
    let built = stencil_table(mesh, options, tags);
    let (expected, (table, out)) = match (expected, built) {
        (Ok(expected), Ok(built)) => (expected, built),
        (Err(e), Err(f)) => {
            assert_eq!(e, f, "{what}: different errors");
            return false;
        }
        (expected, built) => {
            panic!("{what}: subdivide {:?}, stencil table {:?}", expected.err(), built.err())
        }
    };
    // The topology is subdivide's, and the build-time positions are (to rounding: they come
    // from the table).
    assert_eq!(out.indices, expected.indices, "{what}: output faces");
    assert_eq!(out.face_sizes, expected.face_sizes, "{what}: output faces");
    let scale = diagonal(&mesh.positions);
    assert_close(
        &out.positions,
        &expected.positions,
        scale,
        &format!("{what}: build-time positions"),
    );
    assert_eq!(table.num_stencils(), expected.num_vertices(), "{what}: rows");
    assert_eq!(table.num_control_vertices(), mesh.num_vertices(), "{what}: controls");
    check_rows(&table, what);
    let mut positions = vec![f32::NAN; 3 * table.num_stencils()];
    table.evaluate(&mesh.positions, 3, &mut positions).unwrap();
    assert_close(&positions, &expected.positions, scale, &format!("{what}: control positions"));

    // Move the control vertices: the same table gives subdivide's result on the moved mesh.
    let mut random = Random(0x9e37_79b9_7f4a_7c15 ^ mesh.positions.len() as u64);
    let moved = PolyMesh {
        positions: mesh.positions.iter().map(|&x| x + 0.3 * scale * random.next()).collect(),
        ..mesh.clone()
    };
    let expected = subdivide_with_tags(&moved, options, tags).unwrap();
    table.evaluate(&moved.positions, 3, &mut positions).unwrap();
    let scale = diagonal(&moved.positions);
    assert_close(&positions, &expected.positions, scale, &format!("{what}: moved positions"));

    // A vertex-varying channel (random values, width 5: the general path) and a scalar.
    for width in [5usize, 1] {
        let values: Vec<f32> = (0..width * mesh.num_vertices()).map(|_| random.next()).collect();
        let channel = [Attribute::vertex("channel", width, values.clone())];
        let (_, refined) = subdivide_with_attributes(mesh, &channel, options, tags).unwrap();
        let mut out = vec![f32::NAN; width * table.num_stencils()];
        table.evaluate(&values, width, &mut out).unwrap();
        assert_close(&out, &refined[0].values, 1.0, &format!("{what}: channel of width {width}"));
    }
    true
}

/// Levels 1-3 of `scheme` (as far as the result stays small); returns how many calls ran.
fn check_levels(
    mesh: &PolyMesh,
    scheme: Scheme,
    boundary: Boundary,
    tags: &Tags,
    name: &str,
) -> usize {
    let mut ran = 0;
    for levels in 1..=3 {
        let options = Options::new(scheme, levels).with_boundary(boundary);
        let base = HalfEdgeMesh::from_poly(mesh).unwrap();
        if predict_counts(&base, &options).1 > 40_000 {
            break;
        }
        let what = format!("{name}, {scheme} × {levels}, boundary {}", boundary.name());
        ran += usize::from(check_call(mesh, &options, tags, &what));
    }
    ran
}

#[test]
fn every_scheme_and_boundary_on_the_sample_shapes() {
    let mut ran = 0;
    for (name, mesh) in sample_meshes() {
        for &scheme in Scheme::ALL {
            for &boundary in Boundary::ALL {
                ran += check_levels(&mesh, scheme, boundary, &Tags::default(), name);
            }
        }
    }
    eprintln!("{ran} calls compared");
    assert!(ran > 400, "only {ran} calls ran");
}

#[test]
fn scheme_lists() {
    let lists = [
        "bilinear,catmull-clark",
        "catmull-clark,doo-sabin",
        "doo-sabin,catmull-clark",
        "loop,sqrt3,sqrt3",
        "sqrt3,sqrt3,sqrt3",
        "midpoint,loop",
        "quad-triangle,loop",
        "catmull-clark,quad-triangle",
    ];
    let mut ran = 0;
    for (name, mesh) in sample_meshes() {
        for list in lists {
            let schemes = Scheme::parse_list(list).unwrap();
            let options = Options { schemes, ..Options::default() };
            ran += usize::from(check_call(
                &mesh,
                &options,
                &Tags::default(),
                &format!("{name}, {list}"),
            ));
        }
    }
    eprintln!("{ran} calls compared");
    assert!(ran > 40, "only {ran} calls ran");
}

#[test]
fn creases_corners_and_holes() {
    let crease = |a, b, sharpness| Crease { vertices: [a, b], sharpness };
    let cube_tags = Tags {
        creases: vec![crease(0, 1, 1.5), crease(1, 2, 4.0), crease(2, 3, 0.5)],
        corners: vec![Corner { vertex: 6, sharpness: 2.0 }],
        holes: vec![5],
        ..Tags::default()
    };
    let grid_tags = Tags {
        creases: vec![crease(6, 7, 10.0), crease(7, 8, 1.0)],
        corners: vec![Corner { vertex: 12, sharpness: 0.5 }],
        holes: vec![4, 9],
        ..Tags::default()
    };
    let holes_only = Tags { holes: vec![0, 3], ..Tags::default() };
    let cases = [
        ("cube", cube(), cube_tags),
        ("grid", grid(5, 4), grid_tags),
        ("grid-with-hole", grid_with_hole(5, 5, 2..3, 1..3), holes_only.clone()),
        ("torus", torus(6, 5, 2.0, 0.5), holes_only),
    ];
    let mut ran = 0;
    for (name, mesh, tags) in &cases {
        for scheme in [Scheme::CatmullClark, Scheme::Bilinear] {
            for &boundary in Boundary::ALL {
                ran += check_levels(mesh, scheme, boundary, tags, name);
            }
        }
        let triangles = subsurf::shapes::triangulate_quads(mesh);
        for scheme in [Scheme::Loop, Scheme::Midpoint] {
            for &boundary in Boundary::ALL {
                ran += check_levels(&triangles, scheme, boundary, tags, name);
            }
        }
        // Zero levels with holes: the identity, the holes' faces left out.
        ran += usize::from(check_call(mesh, &Options::new(Scheme::CatmullClark, 0), tags, name));
    }
    eprintln!("{ran} calls compared");
    assert!(ran > 100, "only {ran} calls ran");
}

/// OpenSubdiv's regression shapes with their tags (creases, corners, holes, boundary modes,
/// non-manifold and degenerate faces), in their own scheme.
#[test]
fn opensubdiv_shapes() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/meshes/osd");
    let mut files: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    let (mut ran, mut shapes) = (0, 0);
    for path in files.iter().filter(|p| p.extension().is_some_and(|e| e == "obj")) {
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        let scheme = match name.split('_').next() {
            Some("catmark") => Scheme::CatmullClark,
            Some("loop") => Scheme::Loop,
            Some("bilinear") => Scheme::Bilinear,
            _ => continue,
        };
        let obj = read_obj_with_tags(&std::fs::read_to_string(path).unwrap()).unwrap();
        let boundary = obj.boundary.unwrap_or(Boundary::EdgeOnly);
        let count = check_levels(&obj.mesh, scheme, boundary, &obj.tags, &name);
        shapes += usize::from(count > 0);
        ran += count;
    }
    eprintln!("{shapes} shapes, {ran} calls compared");
    assert!(shapes > 90, "only {shapes} shapes ran");
}

/// Unit normals within `tolerance` rad of each other (or both zero).
fn assert_same_directions(got: &[f32], want: &[f32], tolerance: f64, what: &str) {
    for (v, (a, b)) in got.chunks_exact(3).zip(want.chunks_exact(3)).enumerate() {
        let [a, b] = [a, b].map(|n| n.iter().map(|&x| f64::from(x)).collect::<Vec<_>>());
        let dot: f64 = (0..3).map(|k| a[k] * b[k]).sum();
        let cross =
            [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
        let sin = cross.iter().map(|x| x * x).sum::<f64>().sqrt();
        let zero = |n: &[f64]| n.iter().all(|&x| x == 0.0);
        let same =
            if zero(&a) || zero(&b) { zero(&a) && zero(&b) } else { dot > 0.0 && sin <= tolerance };
        assert!(same, "{what}: normal {v}: {a:?} against {b:?} ({sin:.2e} rad apart)");
    }
}

/// At the limit, Catmull-Clark's regular faces are evaluated as bicubic patches
/// (`Evaluator::patch_vertices`); the others keep their rows. Both must give the positions and
/// normals of the rows composed through the levels, and of the evaluator's own table (whose
/// rows for the patches' points are the patches' B-spline weights): on every Catmull-Clark
/// shape of OpenSubdiv's (untagged: tags turn the patches off), at levels 1 to 3, with and
/// without normals, and on a torus, whose faces are all regular. The normals must agree to
/// 1e-5 rad, what the GPU evaluator (which runs the rows) must meet against the CPU's. With
/// both tangent sums taken on differences of points they are within 1e-6 rad; summed on the
/// points, f32 put them 1.2e-4 rad apart on `catmark_car` at level 3.
#[test]
fn regular_patches_give_the_tables_points_and_normals() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/meshes/osd");
    let mut files: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    let mut meshes = vec![("torus".to_string(), torus(12, 9, 2.0, 0.5))];
    for path in files.iter().filter(|p| p.extension().is_some_and(|e| e == "obj")) {
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        if name.starts_with("catmark") {
            let obj = read_obj_with_tags(&std::fs::read_to_string(path).unwrap()).unwrap();
            meshes.push((name, obj.mesh));
        }
    }
    let (mut patched, mut with_patches) = (0, 0);
    for (name, mesh) in &meshes {
        let Ok(base) = HalfEdgeMesh::from_poly(mesh) else { continue };
        let scale = diagonal(&mesh.positions);
        for levels in 1..=3 {
            for normals in [false, true] {
                let options =
                    Options { limit: true, normals, ..Options::new(Scheme::CatmullClark, levels) };
                let Ok(evaluator) = Evaluator::new(&base, &[], &options, &Tags::default()) else {
                    continue;
                };
                let n = 3 * evaluator.num_vertices();
                let (mut points, mut normal) = (vec![0.0; n], vec![0.0; n]);
                let (mut want, mut want_normal) = (vec![0.0; n], vec![0.0; n]);
                let out = normals.then_some(&mut normal[..]);
                evaluator.evaluate(&mesh.positions, &mut points, out).unwrap();
                // The rows composed through the levels (`stencil_table_mesh` makes no patches);
                // the evaluator's own table takes the patches' points' rows from the patches.
                let (composed, _) = stencil_table_mesh(&base, &options, &Tags::default()).unwrap();
                let what = format!("{name} level {levels} normals {normals}");
                for (table, which) in
                    [(&composed, "composed rows"), (evaluator.table().unwrap(), "table")]
                {
                    table
                        .evaluate_with_normals(&mesh.positions, &mut want, &mut want_normal)
                        .unwrap();
                    let what = format!("{what}, patches against the {which}");
                    assert_close(&points, &want, scale, &what);
                    if normals {
                        assert_same_directions(&normal, &want_normal, 1e-5, &what);
                    }
                }
                patched += evaluator.patch_vertices();
                with_patches += usize::from(evaluator.patch_vertices() > 0);
                if name == "torus" {
                    assert_eq!(evaluator.patch_vertices(), evaluator.num_vertices(), "{what}");
                }
            }
        }
    }
    eprintln!("{with_patches} evaluators with patches, {patched} vertices from patches");
    assert!(with_patches > 30, "only {with_patches} evaluators had patches");
}

#[test]
fn a_table_from_a_built_mesh_is_the_same() {
    let mesh = torus(6, 5, 2.0, 0.5);
    let options = Options::new(Scheme::CatmullClark, 2);
    let base = HalfEdgeMesh::from_poly(&mesh).unwrap();
    let from_poly = stencil_table(&mesh, &options, &Tags::default()).unwrap();
    let from_mesh = stencil_table_mesh(&base, &options, &Tags::default()).unwrap();
    assert_eq!(from_poly, from_mesh);
    // Catmull-Clark level 1 of a closed quad mesh: a face point has its 4 corners, an edge
    // point 6 vertices, a regular vertex point 9.
    let (table, _) =
        stencil_table(&mesh, &Options::new(Scheme::CatmullClark, 1), &Tags::default()).unwrap();
    let sizes: Vec<usize> =
        (0..table.num_stencils()).map(|i| table.stencil(i).unwrap().0.len()).collect();
    let (v, f) = (mesh.num_vertices(), mesh.num_faces());
    assert!(sizes[..v].iter().all(|&n| n == 9), "{:?}", &sizes[..v]);
    assert!(sizes[v..v + f].iter().all(|&n| n == 4));
    assert!(sizes[v + f..].iter().all(|&n| n == 6));
    assert_eq!(
        table.bytes(),
        4 * (table.num_stencils() as u64 + 1) + 8 * sizes.iter().sum::<usize>() as u64
    );
}

/// A limit table with tangents takes 16 bytes per entry (an index and three weights), and
/// `max_bytes` counts them so: the table is built at exactly its size and refused one byte below
/// (it once counted 8 and could grow to twice the limit, past wasm's memory), on its first use
/// (the torus's patches give every point, so no frame reads it).
#[test]
fn max_bytes_counts_a_limit_table_with_its_tangents() {
    let base = HalfEdgeMesh::from_poly(&torus(8, 6, 2.0, 0.5)).unwrap();
    let tags = Tags::default();
    let options = Options { limit: true, normals: true, ..Options::new(Scheme::CatmullClark, 2) };
    let evaluator = Evaluator::new(&base, &[], &options, &tags).unwrap();
    let table = evaluator.table().unwrap();
    assert!(table.tangent_weights().is_some());
    let entries = table.indices().len() as u64;
    assert_eq!(table.bytes(), 4 * (table.num_stencils() as u64 + 1) + 16 * entries);
    let just = Options { max_bytes: table.bytes(), ..options.clone() };
    assert_eq!(Evaluator::new(&base, &[], &just, &tags).unwrap().table().unwrap(), table);
    let below = Options { max_bytes: table.bytes() - 1, ..options.clone() };
    // The torus's patches give every point: its evaluator leaves the table out until first
    // use, and is refused there.
    let err = Evaluator::new(&base, &[], &below, &tags).unwrap().table().unwrap_err();
    assert!(matches!(&err, Error::TooLarge(m) if m.contains("stencil table")), "{err}");
}

#[test]
fn guards_and_wrong_lengths_are_errors() {
    let mesh = torus(8, 6, 2.0, 0.5);
    let tags = Tags::default();
    // A level-3 table takes more bytes than the result's arrays: with the limit at exactly the
    // result's size, subdivide runs and the table is refused (during the build).
    let options = Options::new(Scheme::CatmullClark, 3);
    let base = HalfEdgeMesh::from_poly(&mesh).unwrap();
    let exact = Options { max_bytes: predict(&base, &options).bytes(), ..options.clone() };
    assert!(subdivide_with_tags(&mesh, &exact, &tags).is_ok());
    let err = stencil_table(&mesh, &exact, &tags).unwrap_err();
    assert!(matches!(&err, Error::TooLarge(m) if m.contains("stencil table")), "{err}");
    let (table, out) = stencil_table(&mesh, &options, &tags).unwrap();
    assert!(table.bytes() > exact.max_bytes, "{} bytes", table.bytes());
    let just = Options { max_bytes: table.bytes(), ..options.clone() };
    assert_eq!(stencil_table(&mesh, &just, &tags).unwrap().0, table);
    // Wrong lengths: an error, the output untouched.
    let mut positions = out.positions.clone();
    for (control, width, out_len) in [
        (&mesh.positions[3..], 3, positions.len()),
        (&mesh.positions[..], 3, positions.len() - 1),
        (&mesh.positions[..], 2, positions.len()),
        (&mesh.positions[..], usize::MAX, positions.len()),
    ] {
        let err = table.evaluate(control, width, &mut positions[..out_len]).unwrap_err();
        assert!(matches!(err, Error::InvalidAttribute(_)), "{err}");
        assert_eq!(positions, out.positions);
    }
    // Width 0 is nothing to do.
    table.evaluate(&[], 0, &mut []).unwrap();
}
