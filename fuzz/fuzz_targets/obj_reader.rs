//! The OBJ reader on arbitrary text: it returns a valid mesh or an error naming a line of the
//! file; an accepted mesh builds, writes and reads back unchanged, and subdivides. The reader
//! with tags and UVs too: its `uv` channel fits the mesh and writes and reads back unchanged (the
//! text written in pieces by `write_obj_to` being the same).
#![no_main]

use libfuzzer_sys::fuzz_target;
use subsurf::io::{read_obj, read_obj_with_tags, write_obj, write_obj_to, write_obj_with};
use subsurf::{subdivide, Error, HalfEdgeMesh, Options, Scheme};
use subsurf_fuzz::{
    check_connectivity, check_error, check_poly, check_result, MAX_ELEMENTS, MAX_FACES,
};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    match read_obj_with_tags(text) {
        Ok(obj) => {
            let (vertices, corners) = (obj.mesh.num_vertices(), obj.mesh.indices.len());
            subsurf::attributes::validate(&obj.attributes, vertices, corners)
                .unwrap_or_else(|e| panic!("the uv channel does not fit the mesh: {e}"));
            let written =
                write_obj_with(&obj.mesh, &obj.attributes).expect("a read uv channel writes");
            let mut streamed = Vec::new();
            write_obj_to(&mut streamed, &obj.mesh, &obj.attributes, None)
                .expect("a read uv channel streams");
            assert_eq!(streamed, written.as_bytes(), "write_obj_to against write_obj_with");
            let again = read_obj_with_tags(&written).expect("write_obj_with's output reads back");
            assert_eq!(
                (&again.mesh, &again.attributes),
                (&obj.mesh, &obj.attributes),
                "UV round trip"
            );
        }
        Err(Error::Obj { line, message }) => {
            let lines = text.lines().count().max(1);
            assert!((1..=lines).contains(&line), "line {line} of a {lines}-line file: {message}");
        }
        Err(other) => panic!("read_obj_with_tags returned a non-OBJ error: {other:?}"),
    }
    match read_obj(text) {
        Ok(mesh) => {
            check_poly(&mesh, "read_obj");
            let again = read_obj(&write_obj(&mesh)).expect("write_obj's output reads back");
            assert_eq!(again, mesh, "write_obj → read_obj round trip");
            if mesh.num_faces() <= MAX_ELEMENTS && mesh.num_vertices() <= 4 * MAX_ELEMENTS {
                check_connectivity(&HalfEdgeMesh::from_poly(&mesh).unwrap());
                let options =
                    Options { max_faces: MAX_FACES, ..Options::new(Scheme::CatmullClark, 1) };
                match subdivide(&mesh, &options) {
                    Ok(out) => check_result(&out, "catmull-clark of an OBJ mesh"),
                    Err(e) => {
                        assert!(matches!(e, Error::TooLarge(_)), "catmull-clark refused: {e}")
                    }
                }
            }
        }
        Err(Error::Obj { line, message }) => {
            let lines = text.lines().count().max(1);
            assert!((1..=lines).contains(&line), "line {line} of a {lines}-line file: {message}");
            check_error(&Error::Obj { line, message }, "read_obj");
        }
        Err(other) => panic!("read_obj returned a non-OBJ error: {other:?}"),
    }
});
