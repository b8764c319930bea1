//! The command line, run as a user runs it.

use std::process::Command;
use subsurf::io::{read_obj, write_obj};
use subsurf::shapes::cube;

fn subsurf(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_subsurf")).args(args).output().expect("binary runs")
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("subsurf-cli-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn subdivides_a_file() {
    let dir = temp_dir("ok");
    let input = dir.join("cube.obj");
    let output = dir.join("out.obj");
    std::fs::write(&input, write_obj(&cube())).unwrap();
    let run = subsurf(&[
        "--scheme",
        "catmull-clark",
        "--levels",
        "2",
        "--boundary",
        "edge-only",
        input.to_str().unwrap(),
        "-o",
        output.to_str().unwrap(),
        "--stats",
    ]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let mesh = read_obj(&std::fs::read_to_string(&output).unwrap()).unwrap();
    // Cube: 6 · 4² faces, 8 + 12·4... V2 = 98 (V1 = 26, E1 = 48, F1 = 24).
    assert_eq!((mesh.num_vertices(), mesh.num_faces()), (98, 96));
    let stats = String::from_utf8_lossy(&run.stderr);
    assert!(stats.contains("output      98 vertices, 96 faces"), "{stats}");
    assert!(stats.contains("subdivide"), "{stats}");
}

#[test]
fn bad_input_exits_non_zero_with_a_message() {
    let dir = temp_dir("bad");
    let input = dir.join("bad.obj");
    std::fs::write(&input, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 5\n").unwrap();
    let path = input.to_str().unwrap();
    let cases: [(&[&str], &str); 6] = [
        (&[path], "OBJ line 4: face refers to vertex 5"),
        (&["--scheme", "loopy", path], "unknown scheme 'loopy'; use one of 'catmull-clark'"),
        (&["--boundary", "nope", path], "unknown boundary 'nope'"),
        (&["--levels", "-1", path], "--levels '-1' is not a whole number"),
        (&["--frobnicate", path], "unknown option '--frobnicate'"),
        (&["/nonexistent/x.obj"], "cannot read '/nonexistent/x.obj'"),
    ];
    for (args, expected) in cases {
        let run = subsurf(args);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(!run.status.success(), "{args:?} should fail");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
    }
}

// ---------------------------------------------------------------------------------------------
// Texture coordinates and --fvar-linear

use subsurf::io::read_obj_with_tags;

/// The cube with every face mapped onto the unit square: four `vt` lines, each face's corners
/// take them in order, so every edge is a UV seam.
fn cube_with_square_uvs() -> String {
    let mesh = cube();
    let mut text = String::new();
    for p in mesh.positions.chunks(3) {
        text += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    text += "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
    for face in mesh.indices.chunks(4) {
        text +=
            &format!("f {}/1 {}/2 {}/3 {}/4\n", face[0] + 1, face[1] + 1, face[2] + 1, face[3] + 1);
    }
    text
}

/// Runs the CLI on `input` with `args` and reads its output back with its UVs.
fn run_on(name: &str, input: &str, args: &[&str]) -> subsurf::io::ObjMesh {
    let dir = temp_dir(name);
    let (path, output) = (dir.join("in.obj"), dir.join("out.obj"));
    std::fs::write(&path, input).unwrap();
    let mut all: Vec<&str> = args.to_vec();
    all.extend([path.to_str().unwrap(), "-o", output.to_str().unwrap()]);
    let run = subsurf(&all);
    assert!(run.status.success(), "{args:?}: {}", String::from_utf8_lossy(&run.stderr));
    read_obj_with_tags(&std::fs::read_to_string(&output).unwrap()).unwrap()
}

#[test]
fn fvar_linear_parsing_and_help() {
    let dir = temp_dir("fvar-args");
    let input = dir.join("cube.obj");
    std::fs::write(&input, write_obj(&cube())).unwrap();
    let path = input.to_str().unwrap();
    for (args, expected) in [
        (&["--fvar-linear", "corners", path][..], "unknown face-varying linear mode 'corners'"),
        (
            &["--fvar-linear", "ALL", path],
            "'none', 'corners-only', 'corners-plus1', 'corners-plus2', 'boundaries', 'all'",
        ),
        (&[path, "--fvar-linear"], "--fvar-linear needs a value"),
    ] {
        let run = subsurf(args);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
    }
    // Every mode is accepted (a file without UVs ignores it).
    for mode in ["none", "corners-only", "corners-plus1", "corners-plus2", "boundaries", "all"] {
        let out = run_on(&format!("mode-{mode}"), &write_obj(&cube()), &["--fvar-linear", mode]);
        assert_eq!(out.mesh.num_faces(), 24, "{mode}");
        assert!(out.attributes.is_empty(), "{mode}: no vt in, none out");
    }
    let help = subsurf(&["--help"]);
    let text = String::from_utf8_lossy(&help.stdout);
    assert!(help.status.success());
    for part in ["--fvar-linear MODE", "corners-plus1 (default)", "--ignore-uv"] {
        assert!(text.contains(part), "--help should mention {part:?}: {text}");
    }
}

#[test]
fn uv_errors_name_the_file_and_line() {
    let dir = temp_dir("uv-bad");
    let input = dir.join("mixed.obj");
    std::fs::write(&input, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3/1\n").unwrap();
    let run = subsurf(&[input.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success());
    for part in ["mixed.obj: OBJ line 5", "corner '2'", "no texture coordinate", "'uv'"] {
        assert!(stderr.contains(part), "{part:?}: {stderr}");
    }
    // --ignore-uv reads the same file as one without texture coordinates.
    let out = run_on(
        "uv-ignored",
        &std::fs::read_to_string(&input).unwrap(),
        &["--ignore-uv", "--levels", "0"],
    );
    assert!(out.attributes.is_empty());
    assert_eq!(out.mesh.num_faces(), 1);
}

#[test]
fn every_scheme_keeps_the_uvs() {
    // Doo-Sabin on the cube: F' = V + E + F = 26 faces, every corner with a vt; each face's
    // corner points lie inside its unit square (Doo-Sabin weights are convex within a face).
    let dir = temp_dir("uv-doo-sabin");
    let (input, output) = (dir.join("in.obj"), dir.join("out.obj"));
    std::fs::write(&input, cube_with_square_uvs()).unwrap();
    let run = subsurf(&[
        "--scheme",
        "doo-sabin",
        input.to_str().unwrap(),
        "-o",
        output.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success() && stderr.is_empty(), "{stderr}");
    let out = read_obj_with_tags(&std::fs::read_to_string(&output).unwrap()).unwrap();
    assert_eq!(out.mesh.num_faces(), 26);
    let uv = &out.attributes[0];
    assert_eq!(uv.indices.as_ref().map(Vec::len), Some(out.mesh.indices.len()));
    assert!(uv.values.iter().all(|&x| (0.0..=1.0).contains(&x)), "{:?}", uv.values);
    for scheme in ["sqrt3", "quad-triangle", "loop,catmull-clark"] {
        let run = subsurf(&["--scheme", scheme, input.to_str().unwrap()]);
        let stdout = String::from_utf8_lossy(&run.stdout);
        let stderr = String::from_utf8_lossy(&run.stderr);
        if scheme == "quad-triangle" {
            assert!(run.status.success(), "{scheme}: {stderr}");
            assert!(stdout.lines().any(|l| l.starts_with("vt ")), "{scheme}: no vt");
        } else {
            // Loop and sqrt3 on the cube's quads are refused as without UVs.
            assert!(!run.status.success() && stderr.contains("triangles only"), "{stderr}");
        }
    }
}

#[test]
fn ignore_uv_writes_no_vt() {
    let out = run_on("no-uv", &cube_with_square_uvs(), &["--ignore-uv", "--levels", "1"]);
    assert!(out.attributes.is_empty());
    assert_eq!(out.mesh.num_faces(), 24);
}

/// The (s, t) of `p` on the cube face (corners `face`, UVs (0,0), (1,0), (1,1), (0,1) in
/// order) whose plane holds `p`: the bilinear parameters, here affine since the faces are
/// squares.
fn square_uv(mesh: &subsurf::PolyMesh, face: &[u32], p: [f32; 3]) -> [f32; 2] {
    let at = |v: u32| [0, 1, 2].map(|k| mesh.positions[3 * v as usize + k]);
    let (p0, p1, p3) = (at(face[0]), at(face[1]), at(face[3]));
    let along = |q: [f32; 3]| {
        let d = [0, 1, 2].map(|k| q[k] - p0[k]);
        let dot: f32 = (0..3).map(|k| d[k] * (p[k] - p0[k])).sum();
        dot / (0..3).map(|k| d[k] * d[k]).sum::<f32>()
    };
    [along(p1), along(p3)]
}

#[test]
fn refined_uvs_follow_the_closed_form() {
    // Bilinear level 1 of the square-mapped cube: every child quad is a quarter of its parent's
    // square, so each corner's vt is the bilinear parameter of its position on the parent face
    // (values 0, 0.5 and 1 only), and each vertex on an edge has one vt per face.
    let cube = cube();
    let out =
        run_on("uv-bilinear", &cube_with_square_uvs(), &["--scheme", "bilinear", "--levels", "1"]);
    let uv = &out.attributes[0];
    let indices = uv.indices.as_ref().unwrap();
    assert_eq!(indices.len(), out.mesh.indices.len());
    let mut seen = std::collections::BTreeSet::new();
    for (f, corners) in out.mesh.indices.chunks(4).enumerate() {
        let p = |v: u32| [0, 1, 2].map(|k| out.mesh.positions[3 * v as usize + k]);
        // The parent face: the cube face whose plane holds all four corners.
        let parent = cube
            .indices
            .chunks(4)
            .find(|face| {
                corners.iter().all(|&v| {
                    let [s, t] = square_uv(&cube, face, p(v));
                    let back = [0, 1, 2].map(|k| {
                        let at = |i: usize| cube.positions[3 * face[i] as usize + k];
                        at(0) + s * (at(1) - at(0)) + t * (at(3) - at(0))
                    });
                    (0..3).all(|k| (back[k] - p(v)[k]).abs() < 1e-5)
                })
            })
            .unwrap_or_else(|| panic!("face {f} lies on no cube face"));
        for (k, &v) in corners.iter().enumerate() {
            let want = square_uv(&cube, parent, p(v));
            let t = indices[4 * f + k] as usize;
            let got = [uv.values[2 * t], uv.values[2 * t + 1]];
            assert!(
                (got[0] - want[0]).abs() < 1e-6 && (got[1] - want[1]).abs() < 1e-6,
                "face {f} corner {k}: {got:?} vs {want:?}"
            );
            seen.insert(((got[0] * 2.0) as u32, (got[1] * 2.0) as u32));
        }
    }
    assert_eq!(seen.len(), 9, "the values are {{0, 0.5, 1}}²: {seen:?}");
    // The file's vt lines: exactly the values the faces use, 0, 0.5 and 1.
    assert!(uv.values.iter().all(|&x| x == 0.0 || x == 0.5 || x == 1.0), "{:?}", uv.values);

    // Catmull-Clark with --fvar-linear all takes the same values as bilinear, corner by corner
    // (the same child faces in the same order), at level 2 the quarter grid.
    let value = |mesh: &subsurf::io::ObjMesh, c: usize| {
        let uv = &mesh.attributes[0];
        let t = uv.indices.as_ref().unwrap()[c] as usize;
        [uv.values[2 * t], uv.values[2 * t + 1]]
    };
    let linear =
        run_on("uv-all", &cube_with_square_uvs(), &["--levels", "2", "--fvar-linear", "all"]);
    let bilinear =
        run_on("uv-bilinear2", &cube_with_square_uvs(), &["--scheme", "bilinear", "--levels", "2"]);
    for c in 0..bilinear.mesh.indices.len() {
        assert_eq!(value(&linear, c), value(&bilinear, c), "corner {c}");
    }
    let on_grid = |x: f32| (x * 4.0 - (x * 4.0).round()).abs() < 1e-6;
    assert!(linear.attributes[0].values.iter().all(|&x| on_grid(x)));

    // The modes differ at each square's corners, where a value has one face: the default
    // (corners-plus1) keeps them sharp, so Catmull-Clark level 1 has the bilinear values
    // {0, 0.5, 1}; 'none' moves them by the boundary rule 3/4 c + 1/8 (a + b) along the seams,
    // (0, 0) to (1/8, 1/8), (1, 0) to (7/8, 1/8); edge points on seams are midpoints either way.
    let components = |mesh: &subsurf::io::ObjMesh| {
        let mut set: Vec<u32> =
            mesh.attributes[0].values.iter().map(|&x| (x * 8.0).round() as u32).collect();
        assert!(mesh.attributes[0]
            .values
            .iter()
            .all(|&x| (x * 8.0 - (x * 8.0).round()).abs() < 1e-6));
        set.sort_unstable();
        set.dedup();
        set
    };
    let sharp = run_on("uv-plus1", &cube_with_square_uvs(), &["--levels", "1"]);
    assert_eq!(components(&sharp), [0, 4, 8], "eighths");
    let smooth =
        run_on("uv-none", &cube_with_square_uvs(), &["--levels", "1", "--fvar-linear", "none"]);
    assert_eq!(components(&smooth), [0, 1, 4, 7, 8], "eighths");
}

/// The `vn` lines of an OBJ text, and the normal index of every face corner.
fn normals_of(text: &str) -> (Vec<[f32; 3]>, Vec<(u32, u32)>) {
    let mut normals = Vec::new();
    let mut corners = Vec::new();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("vn") => {
                let n: Vec<f32> = words.map(|w| w.parse().unwrap()).collect();
                normals.push([n[0], n[1], n[2]]);
            }
            Some("f") => {
                for corner in words {
                    let parts: Vec<&str> = corner.split('/').collect();
                    assert_eq!(parts.len(), 3, "corner {corner} should name its normal");
                    corners.push((parts[0].parse().unwrap(), parts[2].parse().unwrap()));
                }
            }
            _ => {}
        }
    }
    (normals, corners)
}

#[test]
fn limit_and_normals_write_one_normal_per_vertex() {
    use subsurf::scheme::subdivide_limit_with;
    use subsurf::{Options, Scheme, Tags};
    let input = cube_with_square_uvs();
    let dir = temp_dir("limit");
    let (path, output) = (dir.join("in.obj"), dir.join("out.obj"));
    std::fs::write(&path, &input).unwrap();
    let obj = read_obj_with_tags(&input).unwrap();
    let want = subdivide_limit_with(
        &obj.mesh,
        &obj.attributes,
        &Options::new(Scheme::CatmullClark, 2),
        &Tags::default(),
    )
    .unwrap();
    for (flag, moved) in [("--limit", true), ("--normals", false)] {
        let args = ["--levels", "2", flag, path.to_str().unwrap(), "-o", output.to_str().unwrap()];
        let run = subsurf(&args);
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        let text = std::fs::read_to_string(&output).unwrap();
        let got = read_obj_with_tags(&text).unwrap();
        let (normals, corners) = normals_of(&text);
        // One vn per vertex, each corner naming its own vertex's (f v/vt/vn).
        assert_eq!(normals.len(), got.mesh.num_vertices(), "{flag}");
        assert!(corners.iter().all(|&(v, n)| v == n), "{flag}");
        // The library's limit normals, and its limit positions and UVs with --limit only.
        for (n, m) in normals.iter().zip(want.normals().unwrap().chunks_exact(3)) {
            assert!((0..3).all(|k| (n[k] - m[k]).abs() < 1e-6), "{flag}: {n:?} against {m:?}");
        }
        let plain = subsurf::subdivide(&obj.mesh, &Options::new(Scheme::CatmullClark, 2)).unwrap();
        let positions = if moved { want.positions() } else { &plain.positions[..] };
        assert_eq!(got.mesh.positions, positions, "{flag}");
        let uv = &got.attributes[0].values;
        let plain_uv = run_on("plain", &input, &["--levels", "2"]).attributes[0].values.clone();
        let want_uv = if moved { &want.attributes()[0].values } else { &plain_uv };
        assert_eq!(uv, want_uv, "{flag}: UVs");
    }
    // Without UVs: f v//vn.
    let run = subsurf(&["--levels", "1", "--normals", "--ignore-uv", path.to_str().unwrap()]);
    let text = String::from_utf8(run.stdout).unwrap();
    assert!(text.lines().any(|l| l.starts_with("f ") && l.contains("//")), "f v//vn");
    // Doo-Sabin has no limit: a message, and a failure exit.
    let run = subsurf(&["--scheme", "doo-sabin", "--limit", path.to_str().unwrap()]);
    assert!(!run.status.success());
    assert!(String::from_utf8_lossy(&run.stderr).contains("normals: true"));
}
