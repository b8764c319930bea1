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

// ---------------------------------------------------------------------------------------------
// Texture coordinates: `vt` lines and `f v/vt` corners as the face-varying channel `uv`

use subsurf::attributes::Attribute;
use subsurf::io::{read_obj_with, read_obj_with_tags, write_obj_with, ObjReadOptions, UV};

/// Two unit squares side by side in xy whose UVs do not meet: the shared edge 1–4 is a seam
/// (vertices 1 and 4 have one value on each side).
const SEAM: &str = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n\
                    vt 0 0\nvt 0.5 0\nvt 0.5 1\nvt 0 1\nvt 0.5 0 7\nvt 1 0\nvt 1 1\nvt 0.5 1\n\
                    f 1/1 2/2 5/3 4/4\nf 2/5/1 3/6/1 6/7/1 5/8/1\n";

fn uv_of(text: &str) -> Attribute {
    let obj = read_obj_with_tags(text).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(obj.attributes.len(), 1, "one channel");
    obj.attributes[0].clone()
}

#[test]
fn vt_lines_and_corners_become_the_face_varying_uv_channel() {
    let uv = uv_of(SEAM);
    assert_eq!((uv.name.as_str(), uv.item_size), (UV, 2));
    // The third component of `vt 0.5 0 7` is dropped.
    assert_eq!(uv.values, [0., 0., 0.5, 0., 0.5, 1., 0., 1., 0.5, 0., 1., 0., 1., 1., 0.5, 1.]);
    assert_eq!(uv.indices, Some(vec![0, 1, 2, 3, 4, 5, 6, 7]));
    // The mesh is the one read_obj reads, which skips the UVs.
    assert_eq!(read_obj_with_tags(SEAM).unwrap().mesh, read_obj(SEAM).unwrap());
    // Options: tags without UVs, UVs without tags.
    let plain = read_obj_with(SEAM, ObjReadOptions { tags: true, uv: false }).unwrap();
    assert!(plain.attributes.is_empty());
    let untagged = format!("{SEAM}t crease 2/1/0 0 99 1\n");
    let uv_only = read_obj_with(&untagged, ObjReadOptions { tags: false, uv: true }).unwrap();
    assert_eq!(uv_only.attributes, vec![uv]);
}

#[test]
fn vt_forms_relative_indices_and_a_missing_v() {
    // `vt u` alone has v = 0; `v/vt/vn` and relative vt indices (-1 is the last vt so far).
    let text =
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.25\nvt 1 0\nvt 0 1\nvn 0 0 1\nf 1/-3/1 2/-2/1 -1/-1/1\n";
    let uv = uv_of(text);
    assert_eq!(uv.values, [0.25, 0., 1., 0., 0., 1.]);
    assert_eq!(uv.indices, Some(vec![0, 1, 2]));
    // vt lines may come after the faces that use them (positive indices).
    let uv = uv_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/3 2/2 3/1\nvt 0 0\nvt 1 0\nvt 0 1\n");
    assert_eq!(uv.indices, Some(vec![2, 1, 0]));
}

#[test]
fn files_without_face_vt_indices_have_no_channel() {
    for text in [
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1//1 2//1 3//1\n",
    ] {
        assert!(read_obj_with_tags(text).unwrap().attributes.is_empty(), "{text}");
    }
}

#[test]
fn uv_round_trip_through_write_obj_with() {
    let obj = read_obj_with_tags(SEAM).unwrap();
    let text = write_obj_with(&obj.mesh, &obj.attributes).unwrap();
    assert!(text.contains("vt 0.5 1\n"), "{text}");
    assert!(text.contains("\nf 2/5 3/6 6/7 5/8\n"), "{text}");
    let again = read_obj_with_tags(&text).unwrap();
    assert_eq!((again.mesh, again.attributes), (obj.mesh.clone(), obj.attributes.clone()));

    // A vertex-varying `uv` is written with one vt per vertex; other channels are left out.
    let mesh = cube();
    let values: Vec<f32> = mesh.positions.chunks(3).flat_map(|p| [p[0], p[1]]).collect();
    let channels =
        [Attribute::vertex("color", 1, vec![0.0; 8]), Attribute::vertex(UV, 2, values.clone())];
    let text = write_obj_with(&mesh, &channels).unwrap();
    assert_eq!(text.matches("vt ").count(), 8);
    assert!(text.contains("\nf 1/1 5/5 6/6 2/2\n"), "{text}");
    let back = uv_of(&text);
    assert_eq!(back.values, values);
    assert_eq!(back.indices.as_deref(), Some(&mesh.indices[..]));
    // Without a uv channel, write_obj_with is write_obj.
    assert_eq!(write_obj_with(&mesh, &channels[..1]).unwrap(), write_obj(&mesh));
}

#[test]
fn write_obj_with_refuses_a_uv_channel_that_does_not_fit() {
    let mesh = cube();
    let short = Attribute::face_varying(UV, 2, vec![0.0; 8], vec![0; 23]);
    let wide = Attribute::vertex(UV, 4, vec![0.0; 32]);
    let far = Attribute::face_varying(UV, 2, vec![0.0; 8], vec![4; 24]);
    for (channel, expected) in [
        (short, &["'uv'", "23 indices", "24 face corners"][..]),
        (wide, &["'uv'", "itemSize is 4", "1 to 3"]),
        (far, &["'uv'", "index 0 is 4", "4 values"]),
    ] {
        let message = write_obj_with(&mesh, &[channel]).unwrap_err().to_string();
        for part in expected {
            assert!(message.contains(part), "{message:?} should mention {part:?}");
        }
    }
}

fn obj_tags_error(text: &str) -> (usize, String) {
    match read_obj_with_tags(text) {
        Err(Error::Obj { line, message }) => (line, message),
        other => panic!("expected an OBJ error, got {other:?}"),
    }
}

#[test]
fn uv_errors_name_the_line_and_the_attribute() {
    let v = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
    let vt = "vt 0 0\nvt 1 0\nvt 0 1\n";
    // Some corners give vt, others do not: within a face and across faces.
    let (line, message) = obj_tags_error(&format!("{v}{vt}f 1/1 2 3/3\n"));
    assert_eq!(line, 8);
    for part in ["corner '2'", "no texture coordinate", "attribute 'uv'", "line 8"] {
        assert!(message.contains(part), "{message:?} should mention {part:?}");
    }
    let (line, message) = obj_tags_error(&format!("{v}{vt}f 1 2 3\nf 2/2 4/3 3/1\n"));
    assert_eq!(line, 9);
    for part in ["corner '2/2'", "gives a texture coordinate", "'uv'", "face on line 8"] {
        assert!(message.contains(part), "{message:?} should mention {part:?}");
    }
    let (line, message) = obj_tags_error(&format!("{v}{vt}f 1/1 2/2 3/3\nf 2//1 4//1 3//1\n"));
    assert!(line == 9 && message.contains("'2//1'") && message.contains("'uv'"), "{message}");
    // Indices that do not exist.
    let (line, message) = obj_tags_error(&format!("{v}{vt}f 1/1 2/2 3/4\n"));
    assert!(line == 8 && message.contains("texture coordinate 4"), "{line} {message}");
    assert!(message.contains("only 3 'vt' lines") && message.contains("'uv'"), "{message}");
    let (line, message) = obj_tags_error(&format!("{v}{vt}f 1/1 2/2 3/3\nf 2/1 4/9 3/3\n"));
    assert!(line == 9 && message.contains("texture coordinate 9"), "{line} {message}");
    let (line, message) = obj_tags_error(&format!("{v}{vt}f 1/1 2/0 3/3\n"));
    assert!(line == 8 && message.contains("texture coordinate index 0"), "{message}");
    let (_, message) = obj_tags_error(&format!("{v}{vt}f 1/1 2/-4 3/3\n"));
    assert!(message.contains("relative texture coordinate index -4"), "{message}");
    assert!(message.contains("before the first 'vt' line (3 defined so far)"), "{message}");
    let (_, message) = obj_tags_error(&format!("{v}{vt}f 1/1 2/x 3/3\n"));
    assert!(message.contains("'2/x' is not a face index"), "{message}");
    let (_, message) = obj_tags_error(&format!("{v}{vt}f 1/1 2/99999999999 3/3\n"));
    assert!(message.contains("texture coordinate index 99999999999 is too large"), "{message}");
    // Bad vt lines.
    let (line, message) = obj_tags_error(&format!("{v}vt\nf 1 2 3\n"));
    assert!(line == 5 && message.contains("'vt' needs u [v [w]]"), "{line} {message}");
    assert!(obj_tags_error(&format!("{v}vt 0 nan\n")).1.contains("'nan'"));
    assert!(obj_tags_error(&format!("{v}vt 0 0 zero\n")).1.contains("'zero' is not a number"));
    // read_obj skips all of this, as it skips vt lines.
    assert!(read_obj(&format!("{v}vt\nf 1/1 2 3/9\n")).is_ok());
}

/// `write_obj_to` hands the text on in pieces as it is made: the pieces put together are
/// `write_obj_with_normals`'s text, byte for byte (a torus with a seamed uv channel and normals,
/// about 2 MB: some thirty pieces). A bad channel is refused before anything is written,
/// and a writer's error comes back as `Error::Io` with its message.
#[test]
fn write_obj_to_streams_the_same_text() {
    use subsurf::io::{write_obj_to, write_obj_with_normals};
    use subsurf::shapes::{torus, torus_uv};
    let mesh = torus(120, 100, 1.0, 0.25);
    let uv = torus_uv(120, 100);
    let normals: Vec<f32> = mesh.positions.iter().map(|x| x * 0.5).collect();
    let whole = write_obj_with_normals(&mesh, std::slice::from_ref(&uv), Some(&normals)).unwrap();
    assert!(whole.len() > 1 << 20, "{} bytes", whole.len());
    let mut pieces = Vec::new();
    write_obj_to(&mut pieces, &mesh, std::slice::from_ref(&uv), Some(&normals)).unwrap();
    assert_eq!(String::from_utf8(pieces).unwrap(), whole);

    let bad = Attribute::vertex(UV, 4, vec![0.0; mesh.positions.len() / 3 * 4]);
    let mut nothing = Vec::new();
    let refused = write_obj_to(&mut nothing, &mesh, &[bad], None).unwrap_err();
    assert!(matches!(refused, Error::InvalidAttribute(_)), "{refused:?}");
    assert!(nothing.is_empty());

    /// Takes 100 KB, then fails.
    struct Full(usize);
    impl std::io::Write for Full {
        fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
            if self.0 + bytes.len() > 100_000 {
                return Err(std::io::Error::other("the disk is full"));
            }
            self.0 += bytes.len();
            Ok(bytes.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    let mut full = Full(0);
    let error = write_obj_to(&mut full, &mesh, &[uv], Some(&normals)).unwrap_err();
    assert_eq!(error, Error::Io("the disk is full".into()));
    assert!(full.0 > 0, "the first piece went through");
}
