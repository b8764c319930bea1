//! OBJ reading and writing.

use subsurf::io::{read_obj, write_obj};
use subsurf::shapes::cube;
use subsurf::Error;

#[test]
fn reads_all_face_forms_and_skips_other_lines() {
    let text = "# a comment\nmtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0 # trailing\nv 1 1 0\nv 0 1 0 1.0\nvt 0 0\nvn 0 0 1\ns off\n\
                g group\nf 1/1/1 2//1 3/2 4\nf -4 -2 -1\nt crease 2/1/0 0 1 5.0\n";
    let mesh = read_obj(text).unwrap();
    assert_eq!(mesh.num_vertices(), 4);
    assert_eq!(mesh.face_sizes, vec![4, 3]);
    assert_eq!(mesh.indices, vec![0, 1, 2, 3, 0, 2, 3]);
    assert_eq!(&mesh.positions[3..6], &[1.0, 0.0, 0.0]);
}

#[test]
fn round_trip() {
    let mesh = cube();
    assert_eq!(read_obj(&write_obj(&mesh)).unwrap(), mesh);
}

fn obj_error(text: &str) -> (usize, String) {
    match read_obj(text) {
        Err(Error::Obj { line, message }) => (line, message),
        other => panic!("expected an OBJ error, got {other:?}"),
    }
}

/// A face may repeat a vertex, as OpenSubdiv's regression shapes do: read as it is.
#[test]
fn faces_that_repeat_a_vertex_are_read() {
    let mesh = read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\nf 1 3 -1 2\n").unwrap();
    assert_eq!(mesh.indices, vec![0, 1, 1, 0, 2, 2, 1]);
    assert_eq!(mesh.face_sizes, vec![3, 4]);
}

#[test]
fn errors_name_the_line() {
    let v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    assert_eq!(obj_error(&format!("{v}f 1 2 0\n")).0, 4);
    assert!(obj_error(&format!("{v}f 1 2 0\n")).1.contains("index 0"));
    let (line, msg) = obj_error(&format!("{v}f 1 2 9\n"));
    assert!(line == 4 && msg.contains("vertex 9"), "{line} {msg}");
    let (line, msg) = obj_error("v 0 0\n");
    assert!(line == 1 && msg.contains("2 coordinates"), "{msg}");
    assert!(obj_error("v 0 zero 0\n").1.contains("'zero' is not a number"));
    assert!(obj_error("v 0 1e999 0\n").1.contains("not a finite"));
    assert!(obj_error(&format!("{v}f 1 2\n")).1.contains("2 vertices"));
    assert!(obj_error(&format!("{v}f 1 2 x\n")).1.contains("'x' is not a face index"));
    assert!(obj_error(&format!("{v}f 1 -7 2\n")).1.contains("before the first vertex"));
    assert!(obj_error(&format!("{v}f 1 2 99999999999\n")).1.contains("too large"));
    assert!(obj_error("# nothing\n").1.contains("no 'v' lines"));
}
