//! Every scheme through the JS API, in Node and in Chromium: counts formulas and one position
//! per scheme from its closed-form stencil.

use super::*;

fn run(mesh: &JsValue, scheme: JsValue, levels_: f64) -> JsValue {
    ok(subdivide(mesh, &object(&[("scheme", scheme), ("levels", JsValue::from_f64(levels_))])))
}

fn name(s: &str) -> JsValue {
    JsValue::from_str(s)
}

fn tetrahedron() -> JsValue {
    let (p, i) = tetrahedron_arrays();
    js_mesh(&p, &i, None)
}

fn has_point(positions: &[f32], expected: [f32; 3]) -> bool {
    positions.chunks_exact(3).any(|p| close(p, &expected))
}

/// Counts per scheme: (mesh, scheme, vertices, faces) from the formulas of each scheme.
#[wasm_bindgen_test]
fn every_scheme_counts() {
    let cases: [(&str, JsValue, &str, usize, usize); 7] = [
        ("cube", cube(), "catmull-clark", 8 + 12 + 6, 24),
        ("cube", cube(), "bilinear", 8 + 12 + 6, 24),
        ("cube", cube(), "quad-triangle", 8 + 12 + 6, 24),
        ("cube", cube(), "doo-sabin", 24, 8 + 12 + 6),
        ("tetrahedron", tetrahedron(), "loop", 4 + 6, 16),
        ("tetrahedron", tetrahedron(), "midpoint", 4 + 6, 16),
        ("tetrahedron", tetrahedron(), "sqrt3", 4 + 4, 12),
    ];
    for (mesh_name, mesh, scheme, v, f) in cases {
        let out = run(&mesh, name(scheme), 1.0);
        let positions = f32s(&out, "positions");
        assert_eq!(positions.len() / 3, v, "{scheme} on the {mesh_name}: vertices");
        assert_eq!(u32s(&out, "faceSizes").len(), f, "{scheme} on the {mesh_name}: faces");
        assert!(positions.iter().all(|x| x.is_finite()), "{scheme}: finite");
        let triangles = u32s(&out, "triangles");
        let expected: u32 = u32s(&out, "faceSizes").iter().map(|n| n - 2).sum();
        assert_eq!(triangles.len() as u32, 3 * expected, "{scheme}: triangle list");
    }
}

/// One point per scheme from its stencil, worked out by hand:
/// Loop, tetrahedron vertex (1,1,1), valence 3, β = 3/16: 7/16·v + 3/16·Σ = (1/4, 1/4, 1/4);
/// √3, same vertex, α = (4 - 2cos(2π/3))/9 = 5/9: 4/9·v + 5/27·Σ = (7/27, 7/27, 7/27);
/// Doo-Sabin, cube corner (-1,-1,-1) in face z = -1: (9, 3, 1, 3)/16 gives (-1/2, -1/2, -1);
/// bilinear and midpoint keep the old vertices; Quad/Triangle on quads is Catmull-Clark (±5/9).
#[wasm_bindgen_test]
fn every_scheme_closed_form_points() {
    let q = 0.25f32;
    assert!(has_point(&f32s(&run(&tetrahedron(), name("loop"), 1.0), "positions"), [q, q, q]));
    let s = 7.0 / 27.0;
    assert!(has_point(&f32s(&run(&tetrahedron(), name("sqrt3"), 1.0), "positions"), [s, s, s]));
    assert!(has_point(
        &f32s(&run(&cube(), name("doo-sabin"), 1.0), "positions"),
        [-0.5, -0.5, -1.0]
    ));
    assert!(has_point(&f32s(&run(&cube(), name("bilinear"), 1.0), "positions"), [1.0, 1.0, 1.0]));
    assert!(has_point(
        &f32s(&run(&tetrahedron(), name("midpoint"), 1.0), "positions"),
        [1.0, 1.0, 1.0]
    ));
    let c = 5.0 / 9.0;
    assert!(has_point(&f32s(&run(&cube(), name("quad-triangle"), 1.0), "positions"), [c, c, c]));
}

/// A list of schemes, one per level: Doo-Sabin then Catmull-Clark on the cube. Doo-Sabin gives
/// V = 24, E = 48, F = 26 (Σ sizes 96); Catmull-Clark then gives 24 + 48 + 26 vertices, 96 faces.
#[wasm_bindgen_test]
fn scheme_per_level() {
    let list: JsValue = Array::of2(&name("doo-sabin"), &name("catmull-clark")).into();
    let out = ok(subdivide(&cube(), &object(&[("scheme", list)])));
    assert_eq!(f32s(&out, "positions").len() / 3, 98);
    assert_eq!(u32s(&out, "faceSizes").len(), 96);
}

/// Loop on quads names the face and suggests what to do; the module keeps working.
#[wasm_bindgen_test]
fn triangle_schemes_refuse_quads() {
    for scheme in ["loop", "midpoint", "sqrt3"] {
        let message = thrown(subdivide(&cube(), &object(&[("scheme", name(scheme))])));
        assert_mentions(&message, &[scheme, "face 0", "4 vertices", "quad-triangle"]);
    }
    let out = run(&cube(), name("catmull-clark"), 1.0);
    assert_eq!(u32s(&out, "faceSizes").len(), 24);
}

/// Tags through the JS API. Every cube edge infinitely sharp: each corner has three sharp edges,
/// so OpenSubdiv's corner rule keeps it at (1, 1, 1), and every edge point is a midpoint. A hole
/// leaves out the four children of face 0. Bad tag options name the option.
#[wasm_bindgen_test]
fn creases_corners_and_holes() {
    let (_, indices, _) = cube_arrays();
    let mut pairs = Vec::new();
    for face in indices.chunks_exact(4) {
        for k in 0..4 {
            let (a, b) = (face[k], face[(k + 1) % 4]);
            if a < b {
                pairs.extend_from_slice(&[a, b]);
            }
        }
    }
    assert_eq!(pairs.len(), 24, "the cube has 12 edges");
    let creases = object(&[
        ("edges", Uint32Array::from(&pairs[..]).into()),
        ("sharpness", Float32Array::from(&[10.0f32][..]).into()),
    ]);
    let out = ok(subdivide(&cube(), &object(&[("creases", creases.clone())])));
    let positions = f32s(&out, "positions");
    assert!(has_point(&positions, [1.0, 1.0, 1.0]));
    assert!(has_point(&positions, [1.0, 1.0, 0.0]), "an edge point is the midpoint");

    let corners = object(&[
        ("vertices", Uint32Array::from(&[7u32][..]).into()),
        ("sharpness", Float32Array::from(&[10.0f32][..]).into()),
    ]);
    let out = ok(subdivide(&cube(), &object(&[("corners", corners)])));
    assert!(has_point(&f32s(&out, "positions"), [1.0, 1.0, 1.0]), "vertex 7 is a corner");

    let holes: JsValue = Uint32Array::from(&[0u32][..]).into();
    let out = ok(subdivide(&cube(), &object(&[("holes", holes)])));
    assert_eq!(u32s(&out, "faceSizes").len(), 20);

    let bad = object(&[
        ("edges", Uint32Array::from(&pairs[..]).into()),
        ("sharpness", Float32Array::from(&[1.0f32, 2.0][..]).into()),
    ]);
    assert_mentions(
        &thrown(subdivide(&cube(), &object(&[("creases", bad)]))),
        &["creases.sharpness has 2 entries", "12 creases"],
    );
    assert_mentions(
        &thrown(subdivide(&cube(), &object(&[("creaseMethod", name("fast"))]))),
        &["creaseMethod must be 'uniform' or 'chaikin'"],
    );
    let message =
        thrown(subdivide(&cube(), &object(&[("creases", creases), ("scheme", name("doo-sabin"))])));
    assert_mentions(&message, &["doo-sabin"]);
}
