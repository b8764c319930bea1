//! The level loop's progress hook: told after each level in order, the last after the limit,
//! nothing for 0 levels; a `Break` stops the call with `Error::Cancelled`.

use std::ops::ControlFlow;
use subsurf::scheme::{self, Options, Progress, Scheme};
use subsurf::{Error, HalfEdgeMesh, PolyMesh, Tags};

fn cube() -> HalfEdgeMesh {
    let positions = vec![
        -1., -1., -1., 1., -1., -1., -1., 1., -1., 1., 1., -1., -1., -1., 1., 1., -1., 1., -1., 1.,
        1., 1., 1., 1.,
    ];
    let indices = vec![0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5];
    HalfEdgeMesh::from_poly(&PolyMesh { positions, indices, face_sizes: vec![4; 6] }).unwrap()
}

fn run(options: &Options, stop_at: usize) -> (Vec<Progress>, subsurf::Result<usize>) {
    let mut told = Vec::new();
    let mut tell = |p: Progress| {
        told.push(p);
        if p.level == stop_at {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    };
    let result = scheme::subdivide_mesh_refined_with_progress(
        cube(),
        &[],
        options,
        &Tags::default(),
        &mut tell,
    )
    .map(|r| r.num_faces());
    (told, result)
}

fn p(level: usize, levels: usize, faces: usize, vertices: usize) -> Progress {
    Progress { level, levels, faces, vertices }
}

#[test]
fn told_after_each_level_in_order() {
    let (told, faces) = run(&Options::new(Scheme::CatmullClark, 3), 0);
    assert_eq!(told, [p(1, 3, 24, 26), p(2, 3, 96, 98), p(3, 3, 384, 386)]);
    assert_eq!(faces, Ok(384));

    let limit = Options { limit: true, normals: true, ..Options::new(Scheme::CatmullClark, 2) };
    let (told, _) = run(&limit, 0);
    assert_eq!(told, [p(1, 2, 24, 26), p(2, 2, 96, 98)]);

    // Mixed schemes: Doo-Sabin's level 1 makes 26 faces on 24 vertices.
    let mixed = Options { schemes: vec![Scheme::DooSabin, Scheme::CatmullClark], ..limit };
    let (told, _) = run(&Options { limit: false, ..mixed }, 0);
    assert_eq!(told, [p(1, 2, 26, 24), p(2, 2, 96, 98)]);

    let (told, _) = run(&Options::new(Scheme::CatmullClark, 0), 0);
    assert!(told.is_empty());
}

#[test]
fn break_stops_the_call() {
    let (told, result) = run(&Options::new(Scheme::CatmullClark, 4), 2);
    assert_eq!(told.len(), 2);
    let Err(Error::Cancelled(message)) = result else { panic!("expected Cancelled: {result:?}") };
    assert!(message.contains("after level 2 of 4"), "{message}");
    // Breaking at the last level still refuses the result: the caller asked to stop.
    let (_, result) = run(&Options::new(Scheme::CatmullClark, 2), 2);
    assert!(matches!(result, Err(Error::Cancelled(_))));
}
