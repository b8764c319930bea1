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
