//! Creases, corners, holes and the other tags: the OBJ `t` lines, the Rust API's validation,
//! the rules' properties (sharp loops stay planar, corners stay, sharpness decays by one per
//! level, Chaikin equals uniform for equal sharpness, holes drop faces but no vertex), scheme
//! lists and refusals, and the command line. Agreement with OpenSubdiv on its tagged regression
//! shapes is in `tests/osd_agreement.rs`.

use std::process::Command;
use subsurf::io::{read_obj, read_obj_with_tags, write_obj};
use subsurf::shapes::{cube, grid, triangulate_quads};
use subsurf::{
    subdivide, subdivide_with_tags, Boundary, Corner, Crease, CreaseMethod, Error, Options,
    PolyMesh, Scheme, Tags,
};

fn crease(a: u32, b: u32, sharpness: f32) -> Crease {
    Crease { vertices: [a, b], sharpness }
}

fn max_distance(a: &PolyMesh, b: &PolyMesh) -> f32 {
    assert_eq!(a.positions.len(), b.positions.len());
    a.positions.iter().zip(&b.positions).map(|(x, y)| (x - y).abs()).fold(0.0, f32::max)
}

fn run(mesh: &PolyMesh, scheme: Scheme, levels: u32, tags: &Tags) -> PolyMesh {
    subdivide_with_tags(mesh, &Options::new(scheme, levels), tags).unwrap()
}

/// The z coordinate of the cube's vertex 1, on its top face.
const TOP_Z: usize = 3 + 2;

/// The cube of `shapes::cube` has its top face (z = 1) on vertices 1, 3, 5, 7.
fn top_loop(sharpness: f32) -> Tags {
    Tags {
        creases: vec![
            crease(1, 5, sharpness),
            crease(5, 7, sharpness),
            crease(7, 3, sharpness),
            crease(3, 1, sharpness),
        ],
        ..Tags::default()
    }
}

#[test]
fn obj_tags_are_read() {
    let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n\
                f 1 2 3 4\nf 2 5 6 3\n\
                t crease 2/1/0 0 1 2.5\n\
                t crease 4/2/0 1 2 2 3 1.0 10\n\
                t corner 2/1/0 0 4 3\n\
                t hole 1/0/0 1\n\
                t interpolateboundary 1/0/0 2\n\
                t creasemethod 0/0/1 chaikin\n\
                t smoothtriangles 0/0/1 smooth\n\
                t vertexedit 4/2/3 1 2 3 4 0.5 1 add P value\n\
                t facevaryinginterpolateboundary 1/0/0 1\n\
                t somethingnew 0/0/0\n";
    let obj = read_obj_with_tags(text).unwrap();
    assert_eq!(obj.mesh.num_faces(), 2);
    assert_eq!(obj.tags.creases, vec![crease(0, 1, 2.5), crease(1, 2, 1.0), crease(2, 3, 10.0)]);
    assert_eq!(
        obj.tags.corners,
        vec![Corner { vertex: 0, sharpness: 3.0 }, Corner { vertex: 4, sharpness: 3.0 }]
    );
    assert_eq!(obj.tags.holes, vec![1]);
    assert_eq!(obj.boundary, Some(Boundary::EdgeOnly));
    assert_eq!(obj.tags.crease_method, CreaseMethod::Chaikin);
    assert!(obj.tags.smooth_triangles);
    // The plain reader skips tag lines, even malformed ones.
    assert_eq!(read_obj(&format!("{text}t crease 3/0/0 1\n")).unwrap(), obj.mesh);
    for (value, boundary) in
        [(0, Boundary::None), (1, Boundary::EdgeAndCorner), (2, Boundary::EdgeOnly)]
    {
        let text =
            format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nt interpolateboundary 1/0/0 {value}\n");
        assert_eq!(read_obj_with_tags(&text).unwrap().boundary, Some(boundary));
    }
    let plain = read_obj_with_tags("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    assert_eq!((plain.boundary, plain.tags), (None, Tags::default()));
}

#[test]
fn malformed_tags_name_their_line() {
    let mesh = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"; // tags start on line 6
    let cases = [
        ("t crease 2/1/0 0 1\n", "declares 2 integers, 1 floats and 0 strings"),
        ("t crease 2/1/0 0 1 2 3\n", "has 4 values"),
        ("t crease 3/1/0 0 1 2 2.0\n", "vertex pairs"),
        ("t crease 4/3/0 0 1 1 2 1 2 3\n", "one per item (2)"),
        ("t crease 2/1/0 0 9 1.0\n", "vertex 9 does not exist"),
        ("t crease 2/1/0 0 -1 1.0\n", "vertex -1 does not exist"),
        ("t crease 2/1/0 0 2 1.0\n", "not joined by an edge"),
        ("t crease 2/1/0 0 1 -2\n", "negative"),
        ("t crease 2/1/0 0 1 nan\n", "NaN"),
        ("t crease 2/1/0 0 1 soft\n", "'soft' is not a number"),
        ("t crease 2/1/0 x 1 1.0\n", "'x' is not an integer"),
        ("t corner 1/1/0 4 1.0\n", "vertex 4 does not exist"),
        ("t corner 1/0/0 0\n", "one sharpness for all"),
        ("t hole 1/0/0 1\n", "face 1 does not exist"),
        ("t hole 0/0/0\n", "one or more faces"),
        ("t interpolateboundary 1/0/0 3\n", "3 is not a boundary mode"),
        ("t interpolateboundary 0/0/0\n", "one integer"),
        ("t creasemethod 0/0/1 sharpest\n", "unknown value 'sharpest'"),
        ("t smoothtriangles 0/0/1 yes\n", "unknown value 'yes'"),
        ("t crease 2-1-0 0 1 1.0\n", "are not 'nint/nfloat/nstring'"),
        ("t crease 4294967295/4294967295/4294967295 0\n", "has 1 values"),
        ("t crease 18446744073709551615/1/0 0 1 1\n", "are not 'nint/nfloat/nstring'"),
        ("t crease\n", "needs its counts"),
        ("t\n", "needs a tag name"),
    ];
    for (tag, expected) in cases {
        match read_obj_with_tags(&format!("{mesh}{tag}")) {
            Err(Error::Obj { line, message }) => {
                assert_eq!(line, 6, "{tag}: {message}");
                assert!(message.contains(expected), "{tag}: '{message}' lacks '{expected}'");
            }
            other => panic!("{tag}: expected an OBJ error, got {other:?}"),
        }
    }
}

#[test]
fn invalid_tags_are_errors_naming_the_tag() {
    let cube = cube();
    let cases = [
        (
            Tags { creases: vec![crease(0, 7, 1.0)], ..Tags::default() },
            "crease 0 (vertices 0, 7): the mesh has no edge",
        ),
        (
            Tags { creases: vec![crease(0, 1, 1.0), crease(0, 8, 1.0)], ..Tags::default() },
            "crease 1 (vertices 0, 8): vertex 8 does not exist",
        ),
        (Tags { creases: vec![crease(0, 1, -1.0)], ..Tags::default() }, "sharpness -1 is negative"),
        (Tags { creases: vec![crease(0, 1, f32::NAN)], ..Tags::default() }, "sharpness is NaN"),
        (Tags { creases: vec![crease(2, 2, 1.0)], ..Tags::default() }, "names one vertex twice"),
        (
            Tags { corners: vec![Corner { vertex: 8, sharpness: 1.0 }], ..Tags::default() },
            "corner 0 (vertex 8): vertex 8 does not exist",
        ),
        (
            Tags { corners: vec![Corner { vertex: 0, sharpness: f32::NAN }], ..Tags::default() },
            "corner 0 (vertex 0): sharpness is NaN",
        ),
        (Tags { holes: vec![0, 6], ..Tags::default() }, "hole 1 (face 6): face 6 does not exist"),
    ];
    for (tags, expected) in cases {
        // Even zero-sharpness tags and a scheme that refuses tags report the bad tag first.
        for scheme in [Scheme::CatmullClark, Scheme::Loop, Scheme::DooSabin] {
            match subdivide_with_tags(&cube, &Options::new(scheme, 1), &tags) {
                Err(Error::InvalidTag(message)) => {
                    assert!(message.contains(expected), "'{message}' lacks '{expected}'")
                }
                other => panic!("{expected}: expected an invalid tag error, got {other:?}"),
            }
        }
    }
    // A crease may name its edge either way round; a zero sharpness changes nothing.
    let either_way = Tags { creases: vec![crease(4, 0, 0.0)], ..Tags::default() };
    let plain = subdivide(&cube, &Options::new(Scheme::CatmullClark, 2)).unwrap();
    assert_eq!(run(&cube, Scheme::CatmullClark, 2, &either_way), plain);
}

#[test]
fn an_infinitely_sharp_loop_stays_in_its_plane() {
    // The loop around the cube's top face is a crease: its points are combinations of points
    // on the loop only, so they keep z = 1. Without the crease they sink.
    for scheme in [Scheme::CatmullClark, Scheme::Loop] {
        let mesh = if scheme == Scheme::Loop { triangulate_quads(&cube()) } else { cube() };
        for levels in 1..=3 {
            let sharp = run(&mesh, scheme, levels, &top_loop(10.0));
            let smooth = subdivide(&mesh, &Options::new(scheme, levels)).unwrap();
            for v in [1usize, 3, 5, 7] {
                assert!((sharp.positions[3 * v + 2] - 1.0).abs() < 1e-6, "{scheme} L{levels}");
                assert!(smooth.positions[3 * v + 2] < 0.9, "{scheme} L{levels}");
            }
            let on_top = sharp.positions.chunks_exact(3).filter(|p| (p[2] - 1.0).abs() < 1e-6);
            // The loop has 4 · 2^levels points (old vertices and edge points on it).
            assert!(on_top.count() >= 4 << levels, "{scheme} L{levels}");
        }
    }
}

#[test]
fn a_sharp_corner_stays_and_a_half_sharp_one_is_half_way() {
    let mesh = cube();
    let corner =
        |sharpness| Tags { corners: vec![Corner { vertex: 0, sharpness }], ..Tags::default() };
    for levels in 1..=3 {
        let out = run(&mesh, Scheme::CatmullClark, levels, &corner(10.0));
        assert_eq!(&out.positions[0..3], &mesh.positions[0..3]);
    }
    // Sharpness 0.5: corner rule now, smooth rule at the next level, blended half and half.
    let smooth = subdivide(&mesh, &Options::new(Scheme::CatmullClark, 1)).unwrap();
    let half = run(&mesh, Scheme::CatmullClark, 1, &corner(0.5));
    for k in 0..3 {
        let expected = 0.5 * mesh.positions[k] + 0.5 * smooth.positions[k];
        assert!((half.positions[k] - expected).abs() < 1e-6);
    }
}

#[test]
fn sharpness_decays_by_one_per_level() {
    // Sharpness 2 acts as infinite for two levels (the second one a transition of weight 1),
    // then the crease is smooth.
    let mesh = cube();
    for levels in 1..=3 {
        let two = run(&mesh, Scheme::CatmullClark, levels, &top_loop(2.0));
        let infinite = run(&mesh, Scheme::CatmullClark, levels, &top_loop(10.0));
        let d = max_distance(&two, &infinite);
        if levels <= 2 {
            assert!(d < 1e-6, "L{levels}: {d}");
        } else {
            assert!(d > 1e-3, "L{levels}: {d}");
        }
    }
    // Semi-sharp lies between smooth and sharp.
    let z = |tags: &Tags| run(&mesh, Scheme::CatmullClark, 3, tags).positions[TOP_Z];
    let (smooth, semi, sharp) = (z(&Tags::default()), z(&top_loop(1.5)), z(&top_loop(10.0)));
    assert!(smooth < semi && semi < sharp, "{smooth} {semi} {sharp}");
}

#[test]
fn chaikin_equals_uniform_for_equal_sharpness_only() {
    let mesh = cube();
    let with = |tags: Tags, method| Tags { crease_method: method, ..tags };
    let uniform = run(&mesh, Scheme::CatmullClark, 3, &with(top_loop(2.5), CreaseMethod::Uniform));
    let chaikin = run(&mesh, Scheme::CatmullClark, 3, &with(top_loop(2.5), CreaseMethod::Chaikin));
    assert!(max_distance(&uniform, &chaikin) < 1e-6);
    let mut uneven = top_loop(2.5);
    uneven.creases[0].sharpness = 0.5;
    let uniform = run(&mesh, Scheme::CatmullClark, 3, &with(uneven.clone(), CreaseMethod::Uniform));
    let chaikin = run(&mesh, Scheme::CatmullClark, 3, &with(uneven, CreaseMethod::Chaikin));
    assert!(max_distance(&uniform, &chaikin) > 1e-4);
}

#[test]
fn holes_drop_faces_but_no_vertex() {
    let mesh = grid(4, 3);
    let tags = Tags { holes: vec![5, 5, 0], ..Tags::default() };
    for (scheme, mesh) in
        [(Scheme::CatmullClark, mesh.clone()), (Scheme::Loop, triangulate_quads(&mesh))]
    {
        for levels in 0..=3 {
            let plain = subdivide(&mesh, &Options::new(scheme, levels)).unwrap();
            let holed = run(&mesh, scheme, levels, &tags);
            // Same vertices, same places: holes shape nothing.
            assert!(max_distance(&plain, &holed) < 1e-6, "{scheme} L{levels}");
            let per_face = plain.num_faces() / mesh.num_faces();
            assert_eq!(holed.num_faces(), plain.num_faces() - 2 * per_face, "{scheme} L{levels}");
        }
    }
}

#[test]
fn boundary_none_drops_the_faces_at_the_boundary() {
    // A 4 × 4 grid: only the four middle faces touch no boundary vertex.
    let mesh = grid(4, 4);
    for (scheme, mesh, per_face) in
        [(Scheme::CatmullClark, mesh.clone(), 4), (Scheme::Loop, triangulate_quads(&mesh), 8)]
    {
        for levels in 1..=3 {
            let none =
                subdivide(&mesh, &Options::new(scheme, levels).with_boundary(Boundary::None))
                    .unwrap();
            let edge_only =
                subdivide(&mesh, &Options::new(scheme, levels).with_boundary(Boundary::EdgeOnly))
                    .unwrap();
            assert!(max_distance(&none, &edge_only) < 1e-6, "{scheme} L{levels}");
            assert_eq!(
                none.num_faces(),
                4 * per_face * 4usize.pow(levels - 1),
                "{scheme} L{levels}"
            );
        }
    }
    // Boundary edges tagged infinitely sharp keep their faces.
    let mut boundary_creases = Vec::new();
    for i in 0..4 {
        boundary_creases.push(crease(i, i + 1, 10.0)); // bottom row
        boundary_creases.push(crease(20 + i, 21 + i, 10.0)); // top row
        boundary_creases.push(crease(5 * i, 5 * i + 5, 10.0)); // left column
        boundary_creases.push(crease(5 * i + 4, 5 * i + 9, 10.0)); // right column
    }
    let tags = Tags { creases: boundary_creases, ..Tags::default() };
    let options = Options::new(Scheme::CatmullClark, 1).with_boundary(Boundary::None);
    assert_eq!(subdivide_with_tags(&mesh, &options, &tags).unwrap().num_faces(), 64);
}

#[test]
fn scheme_lists_carry_tags_and_other_schemes_refuse_them() {
    let mesh = cube();
    let hole = Tags { holes: vec![2], ..Tags::default() };
    let list = |schemes: &[Scheme]| Options { schemes: schemes.to_vec(), ..Options::default() };
    // Bilinear carries the hole and the crease to the Catmull-Clark level.
    let out = subdivide_with_tags(&mesh, &list(&[Scheme::Bilinear, Scheme::CatmullClark]), &hole)
        .unwrap();
    assert_eq!(out.num_faces(), 5 * 16);
    let out = subdivide_with_tags(
        &mesh,
        &list(&[Scheme::Bilinear, Scheme::CatmullClark]),
        &top_loop(10.0),
    )
    .unwrap();
    assert!((out.positions[TOP_Z] - 1.0).abs() < 1e-6, "the loop stays flat");
    let triangles = triangulate_quads(&mesh);
    let out =
        subdivide_with_tags(&triangles, &list(&[Scheme::Midpoint, Scheme::Loop]), &hole).unwrap();
    assert_eq!(out.num_faces(), 11 * 16);
    for scheme in [Scheme::Sqrt3, Scheme::DooSabin, Scheme::QuadTriangle] {
        let mesh = if scheme == Scheme::Sqrt3 { triangles.clone() } else { mesh.clone() };
        for tags in [&hole, &top_loop(1.0)] {
            let err = subdivide_with_tags(&mesh, &list(&[Scheme::CatmullClark, scheme]), tags);
            let message = err.unwrap_err().to_string();
            assert!(
                message.contains(&format!(
                    "level 2: {scheme} does not support creases/corners/holes; remove them or use catmull-clark or loop"
                )),
                "{message}"
            );
        }
        // Trivial tags are fine.
        let trivial = Tags { creases: vec![crease(0, 1, 0.0)], ..Tags::default() };
        assert!(subdivide_with_tags(&mesh, &list(&[scheme]), &trivial).is_ok(), "{scheme}");
    }
}

#[test]
fn smooth_triangles_change_only_edges_next_to_triangles() {
    let smooth = Tags { smooth_triangles: true, ..Tags::default() };
    let quads = cube();
    let a = run(&quads, Scheme::CatmullClark, 2, &smooth);
    let b = subdivide(&quads, &Options::new(Scheme::CatmullClark, 2)).unwrap();
    assert!(max_distance(&a, &b) < 1e-6);
    let triangles = triangulate_quads(&quads);
    let a = run(&triangles, Scheme::CatmullClark, 2, &smooth);
    let b = subdivide(&triangles, &Options::new(Scheme::CatmullClark, 2)).unwrap();
    assert!(max_distance(&a, &b) > 1e-3);
    // Loop ignores the option.
    let a = run(&triangles, Scheme::Loop, 2, &smooth);
    let b = subdivide(&triangles, &Options::new(Scheme::Loop, 2)).unwrap();
    assert_eq!(a, b);
}

#[test]
fn tagged_path_matches_the_plain_path_where_tags_change_nothing() {
    // A hole forces the tagged path; positions must equal the plain path's.
    for (name, mesh) in [("cube", cube()), ("grid", grid(3, 2))] {
        for (scheme, mesh) in
            [(Scheme::CatmullClark, mesh.clone()), (Scheme::Loop, triangulate_quads(&mesh))]
        {
            for &boundary in
                &[Boundary::EdgeAndCorner, Boundary::EdgeOnly, Boundary::Fixed, Boundary::Average]
            {
                let options = Options::new(scheme, 3).with_boundary(boundary);
                let plain = subdivide(&mesh, &options).unwrap();
                let tagged = subdivide_with_tags(
                    &mesh,
                    &options,
                    &Tags { holes: vec![0], ..Tags::default() },
                )
                .unwrap();
                assert!(max_distance(&plain, &tagged) < 1e-5, "{name} {scheme} {boundary}");
            }
        }
    }
}

fn subsurf_cli(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_subsurf")).args(args).output().expect("binary runs")
}

#[test]
fn command_line_uses_tags_unless_told_not_to() {
    let dir = std::env::temp_dir().join(format!("subsurf-creases-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let input = dir.join("cube.obj");
    let tags = "t crease 2/1/0 1 5 10\nt crease 2/1/0 5 7 10\nt crease 2/1/0 7 3 10\n\
                t crease 2/1/0 3 1 10\nt hole 1/0/0 0\nt interpolateboundary 1/0/0 2\n";
    std::fs::write(&input, format!("{}{tags}", write_obj(&cube()))).unwrap();
    let output = dir.join("out.obj");
    let result = |extra: &[&str]| {
        let mut args =
            vec!["--levels", "2", input.to_str().unwrap(), "-o", output.to_str().unwrap()];
        args.extend_from_slice(extra);
        let run = subsurf_cli(&args);
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        read_obj(&std::fs::read_to_string(&output).unwrap()).unwrap()
    };
    let tagged = result(&[]);
    assert_eq!(tagged.num_faces(), 5 * 16, "the hole is used");
    assert!((tagged.positions[TOP_Z] - 1.0).abs() < 1e-6, "the crease is used");
    let ignored = result(&["--ignore-tags"]);
    assert_eq!(ignored.num_faces(), 6 * 16);
    assert!(ignored.positions[TOP_Z] < 0.9);
    // --boundary overrides the file's interpolateboundary (here both close the same cube).
    assert_eq!(result(&["--boundary", "edge-and-corner"]).num_faces(), 5 * 16);
    // --crease-method overrides creasemethod; equal sharpness: the same result.
    let chaikin = result(&["--crease-method", "chaikin"]);
    assert!(max_distance(&chaikin, &tagged) < 1e-6);
    // A malformed tag is an error naming the line.
    std::fs::write(&input, format!("{}t hole 1/0/0 99\n", write_obj(&cube()))).unwrap();
    let run = subsurf_cli(&[input.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        !run.status.success() && stderr.contains("OBJ line 15") && stderr.contains("face 99"),
        "{stderr}"
    );
    // ...unless tags are ignored.
    let run =
        subsurf_cli(&["--ignore-tags", input.to_str().unwrap(), "-o", output.to_str().unwrap()]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    std::fs::remove_dir_all(&dir).ok();
}

/// Pseudo-random tags (a fixed-seed generator) on every sample mesh, both methods, every
/// boundary rule, levels 1 to 3: no error, no NaN, hole faces gone.
#[test]
fn random_tags_never_give_nan() {
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut next = move |n: u32| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed % n as u64) as u32
    };
    let meshes = [cube(), grid(3, 3), subsurf::shapes::torus(5, 4, 2.0, 0.5)];
    for (m, quads) in meshes.iter().enumerate() {
        for (scheme, mesh) in
            [(Scheme::CatmullClark, quads.clone()), (Scheme::Loop, triangulate_quads(quads))]
        {
            let he = subsurf::HalfEdgeMesh::from_poly(&mesh).unwrap();
            for round in 0..8 {
                let sharpness = |k: u32| [0.0, 0.3, 1.0, 1.7, 2.5, 10.0, 25.0][k as usize];
                let mut tags = Tags::default();
                for _ in 0..next(2 * he.num_edges() as u32) {
                    let e = next(he.num_edges() as u32);
                    let [a, b] = he.edge_vertices(e).unwrap();
                    tags.creases.push(crease(a, b, sharpness(next(7))));
                }
                for _ in 0..next(4) {
                    let vertex = next(he.num_vertices() as u32);
                    tags.corners.push(Corner { vertex, sharpness: sharpness(next(7)) });
                }
                if round % 2 == 1 {
                    tags.holes.push(next(he.num_cells() as u32));
                }
                tags.crease_method =
                    if round % 4 < 2 { CreaseMethod::Uniform } else { CreaseMethod::Chaikin };
                tags.smooth_triangles = round % 3 == 0;
                for &boundary in Boundary::ALL {
                    for levels in 1..=3 {
                        let options = Options::new(scheme, levels).with_boundary(boundary);
                        let out = subdivide_with_tags(&mesh, &options, &tags)
                            .unwrap_or_else(|e| panic!("mesh {m} {scheme} {boundary}: {e}"));
                        assert!(out.positions.iter().all(|x| x.is_finite()), "mesh {m} {scheme}");
                        let plain = subdivide(&mesh, &options).unwrap();
                        assert_eq!(out.num_vertices(), plain.num_vertices());
                        // (Under 'none', infinitely sharp boundary creases keep faces.)
                        if boundary != Boundary::None {
                            assert!(out.num_faces() <= plain.num_faces());
                        }
                    }
                }
            }
        }
    }
}

/// Boundary 'none' in a list: the faces at the base mesh's boundary are dropped whether or not
/// there are other tags, and bilinear carries the holes to the Catmull-Clark level.
#[test]
fn boundary_none_in_a_list_is_decided_on_the_base_mesh() {
    let mesh = grid(4, 4);
    let options = Options {
        schemes: vec![Scheme::Bilinear, Scheme::CatmullClark],
        boundary: Boundary::None,
        ..Options::default()
    };
    let plain = subdivide(&mesh, &options).unwrap();
    let tagged = subdivide_with_tags(
        &mesh,
        &options,
        &Tags { corners: vec![Corner { vertex: 12, sharpness: 1.0 }], ..Tags::default() },
    )
    .unwrap();
    assert_eq!(plain.num_faces(), 4 * 16, "the four middle faces' grandchildren");
    assert_eq!(tagged.num_faces(), plain.num_faces());
}
