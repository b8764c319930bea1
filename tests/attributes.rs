//! Vertex-varying attributes: every scheme refines them with the same weights as the positions.
//!
//! The rules are affine (their weights sum to 1), so a channel that holds an affine function
//! `A p + b` of the positions must come out as the same function of the refined positions, at
//! every level, through creases, holes and lists of schemes. That is a closed-form expectation
//! that needs no reference implementation; it fails if a rule gives a channel other weights than
//! the positions, or weights that do not sum to 1.

mod common;

use common::sample_meshes;
use subsurf::attributes::Attribute;
use subsurf::scheme::{subdivide_with_attributes, subdivide_with_tags};
use subsurf::shapes::{cube, grid};
use subsurf::{Crease, Error, Options, PolyMesh, Scheme, Tags};

/// A 4-component affine function of a position, and a 1-component one.
fn affine4(p: &[f32]) -> [f32; 4] {
    let [x, y, z] = [p[0], p[1], p[2]];
    [0.5 * x - 2.0 * y + 0.25 * z + 3.0, x + y + z, -1.5 * z + 0.125, 2.0 * x - 0.75 * y + 7.0]
}

fn affine1(p: &[f32]) -> f32 {
    3.0 * p[0] - 0.5 * p[1] + 2.0 * p[2] - 1.0
}

fn channels(mesh: &PolyMesh) -> Vec<Attribute> {
    let points = mesh.positions.chunks_exact(3);
    let four: Vec<f32> = points.clone().flat_map(affine4).collect();
    let one: Vec<f32> = points.map(affine1).collect();
    let constant = [0.25f32, -4.0].repeat(mesh.num_vertices());
    vec![
        Attribute::vertex("four", 4, four),
        Attribute::vertex("one", 1, one),
        Attribute::vertex("constant", 2, constant),
    ]
}

/// Checks the refined channels against the refined positions; `what` names the case.
fn check(out: &PolyMesh, attributes: &[Attribute], what: &str) {
    assert_eq!(attributes.len(), 3, "{what}");
    let scale = out.positions.iter().fold(1.0f32, |m, x| m.max(x.abs()));
    let tolerance = 1e-5 * 8.0 * scale;
    for (v, p) in out.positions.chunks_exact(3).enumerate() {
        let four = &attributes[0].values[4 * v..4 * v + 4];
        for (k, (got, want)) in four.iter().zip(affine4(p)).enumerate() {
            assert!(
                (got - want).abs() <= tolerance,
                "{what}: vertex {v} four[{k}] {got} vs {want}"
            );
        }
        let (got, want) = (attributes[1].values[v], affine1(p));
        assert!((got - want).abs() <= tolerance, "{what}: vertex {v} one {got} vs {want}");
        let constant = &attributes[2].values[2 * v..2 * v + 2];
        assert!(
            (constant[0] - 0.25).abs() < 1e-6 && (constant[1] + 4.0).abs() < 1e-5,
            "{what}: vertex {v} constant {constant:?}"
        );
    }
    for a in attributes {
        assert_eq!(a.len(), out.num_vertices(), "{what}: {}", a.name);
    }
}

fn input_for(scheme: Scheme, mesh: &PolyMesh) -> Option<PolyMesh> {
    let triangles = mesh.face_sizes.iter().all(|&n| n == 3);
    (!scheme.triangles_only() || triangles).then(|| mesh.clone())
}

#[test]
fn affine_channels_follow_the_positions_in_every_scheme() {
    let mut checked = 0;
    for (name, mesh) in sample_meshes() {
        for &scheme in Scheme::ALL {
            let Some(mesh) = input_for(scheme, &mesh) else { continue };
            for levels in 1..=3 {
                let options = Options::new(scheme, levels);
                let what = format!("{name} {scheme} L{levels}");
                let (out, attributes) =
                    subdivide_with_attributes(&mesh, &channels(&mesh), &options, &Tags::default())
                        .unwrap_or_else(|e| panic!("{what}: {e}"));
                check(&out, &attributes, &what);
                // The positions are those of a call without attributes, bit for bit.
                let plain = subdivide_with_tags(&mesh, &options, &Tags::default()).unwrap();
                assert_eq!(plain, out, "{what}");
                checked += 1;
            }
        }
    }
    assert!(checked > 100, "{checked}");
}

/// Every boundary mode moves boundary vertices by its own rule; the channels follow.
#[test]
fn affine_channels_follow_every_boundary_mode() {
    for &boundary in subsurf::Boundary::ALL {
        for (scheme, mesh) in [
            (Scheme::CatmullClark, grid(4, 3)),
            (Scheme::Loop, subsurf::shapes::triangulate_quads(&grid(4, 3))),
            (Scheme::DooSabin, grid(4, 3)),
        ] {
            let options = Options::new(scheme, 2).with_boundary(boundary);
            let what = format!("{scheme} boundary {boundary}");
            let (out, attributes) =
                subdivide_with_attributes(&mesh, &channels(&mesh), &options, &Tags::default())
                    .unwrap_or_else(|e| panic!("{what}: {e}"));
            check(&out, &attributes, &what);
        }
    }
}

/// Semi-sharp and sharp creases, a corner and a hole change the weights (transitions blend two
/// rules); the channels still follow.
#[test]
fn affine_channels_follow_creases_corners_and_holes() {
    let mesh = grid(5, 4);
    let creases =
        (0..4u32).map(|i| Crease { vertices: [6 + i, 7 + i], sharpness: 0.5 + i as f32 }).collect();
    let tags = Tags {
        creases,
        corners: vec![subsurf::Corner { vertex: 14, sharpness: 2.5 }],
        holes: vec![0],
        ..Tags::default()
    };
    for scheme in [Scheme::CatmullClark, Scheme::Bilinear] {
        for levels in 1..=3 {
            let options = Options::new(scheme, levels);
            let what = format!("tagged {scheme} L{levels}");
            let (out, attributes) =
                subdivide_with_attributes(&mesh, &channels(&mesh), &options, &tags)
                    .unwrap_or_else(|e| panic!("{what}: {e}"));
            check(&out, &attributes, &what);
        }
    }
    let tris = subsurf::shapes::triangulate_quads(&mesh);
    for levels in 1..=3 {
        let options = Options::new(Scheme::Loop, levels);
        let (out, attributes) =
            subdivide_with_attributes(&tris, &channels(&tris), &options, &tags).unwrap();
        check(&out, &attributes, &format!("tagged loop L{levels}"));
    }
}

/// A list of schemes, one per level, carries the channels from host to host.
#[test]
fn affine_channels_follow_a_list_of_schemes() {
    let tris = subsurf::shapes::triangulate_quads(&cube());
    let lists: [&[Scheme]; 4] = [
        &[Scheme::QuadTriangle, Scheme::CatmullClark, Scheme::DooSabin],
        &[Scheme::Loop, Scheme::Sqrt3, Scheme::Sqrt3, Scheme::Midpoint],
        &[Scheme::Bilinear, Scheme::CatmullClark],
        &[Scheme::Sqrt3, Scheme::Loop, Scheme::QuadTriangle],
    ];
    for schemes in lists {
        let options = Options { schemes: schemes.to_vec(), ..Options::default() };
        let what = format!("{schemes:?}");
        let (out, attributes) =
            subdivide_with_attributes(&tris, &channels(&tris), &options, &Tags::default())
                .unwrap_or_else(|e| panic!("{what}: {e}"));
        check(&out, &attributes, &what);
    }
}

/// A face-varying `uv` with one value per face corner, none shared (every edge is a seam): float
/// `k` of the values is `(k % period) * step`.
fn uv_on_every_corner(mesh: &PolyMesh, period: usize, step: f32) -> Attribute {
    let corners = mesh.indices.len();
    let values: Vec<f32> = (0..2 * corners).map(|i| (i % period) as f32 * step).collect();
    Attribute::face_varying("uv", 2, values, (0..corners as u32).collect())
}

/// Face 1 a hole (when there are more than two faces) and the first face's first edge a crease
/// of `sharpness`.
fn hole_and_crease(mesh: &PolyMesh, sharpness: f32) -> Tags {
    let mut tags = Tags::default();
    if mesh.face_sizes.len() > 2 {
        tags.holes = vec![1];
    }
    let [a, b] = [mesh.indices[0], mesh.indices[1]];
    tags.creases = vec![Crease { vertices: [a, b], sharpness }];
    tags
}

/// A face-varying channel beside them changes nothing in the vertex-varying channels, bit for
/// bit, through creases and holes too. (These channels are wider than one packed walk with the
/// positions, `primvar::MAX_PACKED`: each kind walks the rules on its own.)
#[test]
fn a_face_varying_channel_leaves_the_vertex_varying_ones_alone() {
    let mut checked = 0;
    for (name, mesh) in sample_meshes() {
        let uv = uv_on_every_corner(&mesh, 11, 0.125);
        // And one that follows the vertices: no seam at all.
        let smooth =
            Attribute::face_varying("w", 1, vec![0.5; mesh.num_vertices()], mesh.indices.clone());
        let tags = hole_and_crease(&mesh, 1.5);
        for scheme in [Scheme::CatmullClark, Scheme::Loop, Scheme::Bilinear] {
            let Some(mesh) = input_for(scheme, &mesh) else { continue };
            for (levels, tags) in [(1, Tags::default()), (2, tags.clone())] {
                let options = Options::new(scheme, levels);
                let what = format!("{name} {scheme} L{levels}");
                let alone = channels(&mesh);
                let (_, want) = subdivide_with_attributes(&mesh, &alone, &options, &tags)
                    .unwrap_or_else(|e| panic!("{what}: {e}"));
                let mut beside = alone.clone();
                beside.extend([uv.clone(), smooth.clone()]);
                let (_, got) = subdivide_with_attributes(&mesh, &beside, &options, &tags)
                    .unwrap_or_else(|e| panic!("{what}: {e}"));
                assert_eq!(&got[..3], &want[..], "{what}");
                // The seamless channel keeps its constant.
                assert!(got[4].values.iter().all(|&x| x == 0.5), "{what}");
                checked += 1;
            }
        }
    }
    assert!(checked > 20, "{checked}");
}

/// Narrow channels are refined packed beside the positions in one walk of the rules
/// (`primvar::pack_points`): every float sums as it would alone, so the positions are bit for bit
/// those of a call without channels, a colour is the same with or without a UV beside it, and
/// an affine colour stays the same function of the refined positions. Through creases, holes and
/// seams on every edge.
#[test]
fn packed_channels_sum_as_they_would_alone() {
    let mut checked = 0;
    for (name, mesh) in sample_meshes() {
        let colour: Vec<f32> =
            mesh.positions.chunks_exact(3).flat_map(|p| affine4(p)[..3].to_vec()).collect();
        let colour = Attribute::vertex("colour", 3, colour);
        let uv = uv_on_every_corner(&mesh, 13, 0.0625);
        let tags = hole_and_crease(&mesh, 2.5);
        for scheme in [Scheme::CatmullClark, Scheme::Loop, Scheme::Bilinear] {
            let Some(mesh) = input_for(scheme, &mesh) else { continue };
            for (levels, tags) in [(1, Tags::default()), (2, tags.clone())] {
                let options = Options::new(scheme, levels);
                let what = format!("{name} {scheme} L{levels}");
                let plain = subdivide_with_tags(&mesh, &options, &tags)
                    .unwrap_or_else(|e| panic!("{what}: {e}"));
                let both = [colour.clone(), uv.clone()];
                let (out, got) = subdivide_with_attributes(&mesh, &both, &options, &tags)
                    .unwrap_or_else(|e| panic!("{what}: {e}"));
                assert_eq!(out.positions, plain.positions, "{what}: positions");
                let (_, alone) = subdivide_with_attributes(&mesh, &both[..1], &options, &tags)
                    .unwrap_or_else(|e| panic!("{what}: {e}"));
                assert_eq!(got[0].values, alone[0].values, "{what}: colour");
                let scale = out.positions.iter().fold(1.0f32, |m, x| m.max(x.abs()));
                let points = out.positions.chunks_exact(3);
                for (v, (p, c)) in points.zip(got[0].values.chunks_exact(3)).enumerate() {
                    for (k, (got, want)) in c.iter().zip(affine4(p)).enumerate() {
                        let close = (got - want).abs() <= 8e-5 * scale;
                        assert!(close, "{what}: vertex {v} colour[{k}] {got} vs {want}");
                    }
                }
                checked += 1;
            }
        }
    }
    assert!(checked > 20, "{checked}");
}

/// Zero levels give the channels back unchanged; no channel gives no channel.
#[test]
fn zero_levels_and_no_channels() {
    let mesh = cube();
    let given = channels(&mesh);
    let options = Options { schemes: vec![], ..Options::default() };
    let (out, attributes) =
        subdivide_with_attributes(&mesh, &given, &options, &Tags::default()).unwrap();
    assert_eq!(out, mesh);
    assert_eq!(attributes, given);
    let (_, none) =
        subdivide_with_attributes(&mesh, &[], &Options::new(Scheme::Loop, 0), &Tags::default())
            .unwrap();
    assert!(none.is_empty());
}

fn error(attributes: Vec<Attribute>) -> String {
    let mesh = cube();
    match subdivide_with_attributes(&mesh, &attributes, &Options::default(), &Tags::default()) {
        Err(e @ (Error::InvalidAttribute(_) | Error::Unsupported(_))) => e.to_string(),
        other => panic!("expected an attribute error, got {other:?}"),
    }
}

#[test]
fn bad_channels_are_errors_naming_the_channel() {
    let ok = || Attribute::vertex("color", 3, vec![0.5; 24]);
    let cases: Vec<(Attribute, &[&str])> = vec![
        (Attribute::vertex("color", 3, vec![0.5; 21]), &["'color'", "7 values", "8 vertices"]),
        (
            Attribute::vertex("color", 3, vec![0.5; 23]),
            &["'color'", "23 values", "multiple of itemSize 3"],
        ),
        (Attribute::vertex("w", 0, vec![]), &["'w'", "itemSize is 0", "1 to 16"]),
        (Attribute::vertex("w", 17, vec![0.0; 17 * 8]), &["'w'", "itemSize is 17"]),
        (
            Attribute { values: [vec![0.5; 10], vec![f32::NAN], vec![0.5; 13]].concat(), ..ok() },
            &["'color'", "value 3 has component 1 = NaN", "finite"],
        ),
        (
            Attribute {
                values: [vec![0.5; 4], vec![f32::INFINITY], vec![0.5; 19]].concat(),
                ..ok()
            },
            &["'color'", "value 1 has component 1 = inf"],
        ),
        (
            Attribute::face_varying("uv", 2, vec![0.0; 8], vec![0; 23]),
            &["'uv'", "23 indices", "24 face corners"],
        ),
        (
            Attribute::face_varying("uv", 2, vec![0.0; 8], [vec![0; 23], vec![4]].concat()),
            &["'uv'", "index 23 is 4", "4 values (0..3)"],
        ),
    ];
    for (attribute, fragments) in cases {
        let message = error(vec![attribute]);
        for f in fragments {
            assert!(message.contains(f), "{message:?} lacks {f:?}");
        }
    }
    let message = error(vec![ok(), ok()]);
    assert!(message.contains("'color'") && message.contains("twice"), "{message}");
}

/// The caller's arrays are only read.
#[test]
fn inputs_are_not_modified() {
    let mesh = cube();
    let given = channels(&mesh);
    let copy = given.clone();
    let _ = subdivide_with_attributes(
        &mesh,
        &given,
        &Options::new(Scheme::CatmullClark, 2),
        &Tags::default(),
    )
    .unwrap();
    assert_eq!(given, copy);
}

/// The byte guard counts attribute channels: a cube at level 3 fits a budget set just above its
/// plain result, and the same call with a 16-float channel of each kind is refused, naming the
/// attributes (closed form: `Prediction::bytes` and `attribute_bytes`).
#[test]
fn the_byte_guard_counts_attributes() {
    use subsurf::scheme::{predict, AttributeSizes};
    let cube = subsurf::shapes::cube();
    let base = subsurf::HalfEdgeMesh::from_poly(&cube).unwrap();
    let mut options = Options::new(Scheme::CatmullClark, 3);
    let predicted = predict(&base, &options);
    options.max_bytes = predicted.bytes() + 16;
    assert!(subsurf::subdivide(&cube, &options).is_ok());
    let wide = Attribute::vertex("w", 16, vec![0.5; 16 * 8]);
    let uv = Attribute::face_varying("uv", 16, vec![0.5; 16], vec![0; 24]);
    let sizes = AttributeSizes { vertex_width: 16, face_varying: vec![16] };
    // 386 vertices and 1536 corners at level 3: 4·16·386 + 4·1536 + 4·16·(1536 + 386).
    assert_eq!(predicted.attribute_bytes(&sizes), 4 * 16 * 386 + 4 * 1536 + 4 * 16 * (1536 + 386));
    let refused =
        subdivide_with_attributes(&cube, &[wide, uv], &options, &Tags::default()).unwrap_err();
    let message = refused.to_string();
    assert!(message.contains("attributes") && message.contains("maxBytes"), "{message}");
    options.max_bytes += predicted.attribute_bytes(&sizes);
    let wide = Attribute::vertex("w", 16, vec![0.5; 16 * 8]);
    let uv = Attribute::face_varying("uv", 16, vec![0.5; 16], vec![0; 24]);
    assert!(subdivide_with_attributes(&cube, &[wide, uv], &options, &Tags::default()).is_ok());
}

/// A last Catmull-Clark or bilinear level keeps its faces implicit, and the face-varying indices
/// with them: the faces' own indices, patched near seams (`Refined::attributes_in_pieces`), as
/// the wasm bindings copy them out piece by piece. Patched in pieces of any size at their place,
/// joined, they are the list `Refined::attributes` gives, which is the list a listed level gives
/// (a last level with a hole is listed). The demo cube's UV cross has seams on 7 of its edges;
/// every corner of the other UV is its own value.
#[test]
fn implicit_face_varying_indices_patch_in_any_pieces() {
    use subsurf::scheme::subdivide_refined_with;
    let cube = cube();
    let cross = subsurf::shapes::demo_shape_uv("cube").expect("the demo cube has UVs");
    let mut every = uv_on_every_corner(&cube, 7, 0.25);
    every.name = "st".into();
    let colour = Attribute::vertex("colour", 3, cube.positions.clone());
    let mut checked = 0;
    for scheme in [Scheme::CatmullClark, Scheme::Bilinear] {
        for levels in [1, 2] {
            let options = Options::new(scheme, levels);
            let channels = [cross.clone(), colour.clone(), every.clone()];
            let refined = subdivide_refined_with(&cube, &channels, &options, &Tags::default())
                .unwrap_or_else(|e| panic!("{scheme} L{levels}: {e}"));
            let (kept, seam_corners) = refined.attributes_in_pieces();
            assert_eq!(seam_corners.len(), 2, "{scheme} L{levels}: both UVs in pieces");
            let mut faces = Vec::new();
            refined.index_and_triangle_chunks(|c| faces.extend_from_slice(c), |_| {});
            for (i, seams) in seam_corners {
                assert_eq!(kept[*i].indices.as_deref(), Some(&[][..]));
                let want = refined.attributes()[*i].indices.clone().expect("face-varying");
                assert_ne!(want, faces, "{scheme} L{levels}: the seams change some corners");
                for piece in [1, 3, 4, 5, 17, 64, faces.len()] {
                    let mut got = Vec::new();
                    for (k, chunk) in faces.chunks(piece).enumerate() {
                        let untouched = !seams.touches(k * piece, chunk.len());
                        let mut patched = chunk.to_vec();
                        seams.patch(k * piece, &mut patched);
                        // A piece `touches` passes over goes out unpatched: it must need none.
                        assert!(!untouched || patched == chunk, "{scheme} L{levels}, piece {k}");
                        got.extend(patched);
                    }
                    assert_eq!(got, want, "{scheme} L{levels}, pieces of {piece}");
                }
                checked += 1;
            }
            // A level with a hole is listed whole (`FVarLevel::child_topology`): its corners
            // are those of the implicit level, but for the hole's children.
            let hole = Tags { holes: vec![5], ..Tags::default() };
            let (_, listed) = subdivide_with_attributes(&cube, &channels, &options, &hole)
                .unwrap_or_else(|e| panic!("{scheme} L{levels}: {e}"));
            let hole_corners = 4 * 4usize.pow(levels);
            let kept_faces = refined.num_indices() - hole_corners;
            for (i, _) in seam_corners {
                let all = refined.attributes()[*i].indices.clone().expect("face-varying");
                assert_eq!(listed[*i].indices.as_deref(), Some(&all[..kept_faces]));
                assert_eq!(listed[*i].values, refined.attributes()[*i].values);
            }
        }
    }
    assert_eq!(checked, 8);
}

/// A result can be shared between threads (its index lists are made once, on first use).
#[test]
fn a_result_is_send_and_sync() {
    fn shared<T: Send + Sync>() {}
    shared::<subsurf::refined::Refined<'static>>();
}

/// The benchmarks' textured torus (`shapes::torus_uv`): one value per point of the
/// `(rings + 1) × (segments + 1)` parameter grid, so the two closing loops are seams, and they
/// stay seams: after a level the values are those of the refined grid, `(2 rings + 1) ×
/// (2 segments + 1)` (a vertex on one loop has two values, the one where they cross four).
#[test]
fn the_benchmark_torus_uv_is_cut_along_both_loops() {
    use subsurf::shapes::{torus, torus_uv};
    let (rings, segments) = (6, 4);
    let uv = torus_uv(rings, segments);
    assert_eq!(uv.len(), 7 * 5);
    assert_eq!(uv.indices.as_ref().map(Vec::len), Some(4 * 6 * 4));
    let mesh = torus(rings, segments, 1.0, 0.25);
    let options = Options::new(Scheme::CatmullClark, 1);
    let (out, channels) = subdivide_with_attributes(&mesh, &[uv], &options, &Tags::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(out.num_vertices(), 12 * 8);
    assert_eq!(channels[0].len(), 13 * 9);
}
