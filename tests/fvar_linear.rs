//! Face-varying invariants where no reference implementation exists, by closed forms on a flat
//! grid whose channel is an affine function of the position, cut by a seam into two charts
//! with their own affine maps:
//!
//! - mode `all` is piecewise linear: every refined value is its chart's map at the position
//!   the linear split of the same topology gives (bilinear for quads, midpoint for triangles);
//!   for Quad/Triangle that is checked on all-quad and all-triangle grids against bilinear and
//!   midpoint;
//! - midpoint is linear in every mode;
//! - a constant channel stays constant in every mode and scheme.

use subsurf::attributes::Attribute;
use subsurf::scheme::subdivide_with_attributes;
use subsurf::shapes::{grid, triangulate_quads};
use subsurf::{subdivide, FVarLinear, Options, PolyMesh, Scheme, Tags};

/// The chart maps: left of x = 0.5 one map, right of it another.
fn chart_map(chart: usize, p: &[f32]) -> [f32; 2] {
    match chart {
        0 => [2.0 * p[0] + 0.5 * p[1] + 1.0, -p[0] + 3.0 * p[1]],
        _ => [-p[0] + 7.0, 0.25 * p[0] + p[1] - 2.0],
    }
}

/// A face-varying channel on `mesh` (a flat grid on [0,1]²): faces whose centroid lies left of
/// x = 0.5 see chart 0's map, the others chart 1's; the vertical line x = 0.5 is a seam. Also
/// the chart of each face.
fn two_charts(mesh: &PolyMesh) -> (Attribute, Vec<usize>) {
    let (mut values, mut indices, mut charts) = (Vec::new(), Vec::new(), Vec::new());
    let mut start = 0usize;
    for &n in &mesh.face_sizes {
        let face = &mesh.indices[start..start + n as usize];
        let cx = face.iter().map(|&v| mesh.positions[3 * v as usize]).sum::<f32>() / n as f32;
        let chart = usize::from(cx > 0.5);
        for &v in face {
            let p = &mesh.positions[3 * v as usize..3 * v as usize + 3];
            indices.push((values.len() / 2) as u32);
            values.extend_from_slice(&chart_map(chart, p));
        }
        charts.push(chart);
        start += n as usize;
    }
    (Attribute::face_varying("uv", 2, values, indices), charts)
}

/// Checks that every corner of `out` sees its face's chart map at `linear`'s position of the
/// same vertex; `charts_out[f]` is the chart of output face `f`.
fn assert_piecewise_linear(
    what: &str,
    out: &PolyMesh,
    uv: &Attribute,
    linear: &PolyMesh,
    charts_out: &[usize],
) {
    // The same faces, corner by corner (vertex numbers may differ: a rebuilt level numbers
    // its edges, and so its edge points, its own way).
    assert_eq!(out.face_sizes, linear.face_sizes, "{what}: the linear split has the same faces");
    let indices = uv.indices.as_ref().unwrap();
    // The face of each corner.
    let faces =
        out.face_sizes.iter().enumerate().flat_map(|(f, &n)| std::iter::repeat_n(f, n as usize));
    for (k, ((f, &v), &i)) in faces.zip(&linear.indices).zip(indices).enumerate() {
        let (v, i) = (v as usize, i as usize);
        let want = chart_map(charts_out[f], &linear.positions[3 * v..3 * v + 3]);
        let got = [uv.values[2 * i], uv.values[2 * i + 1]];
        assert!(
            (got[0] - want[0]).abs() < 1e-5 && (got[1] - want[1]).abs() < 1e-5,
            "{what}: face {f} corner {k}: {got:?}, expected {want:?}"
        );
    }
}

/// The chart of each output face: that of its base face (children of quads are four per
/// parent half-edge... the splits keep a parent's children together, `per_face` per parent).
fn child_charts(charts: &[usize], sizes: &[u32], levels: u32, triangles: bool) -> Vec<usize> {
    let mut out: Vec<usize> = if triangles {
        charts.iter().flat_map(|&c| [c; 4]).collect()
    } else {
        charts.iter().zip(sizes).flat_map(|(&c, &n)| std::iter::repeat_n(c, n as usize)).collect()
    };
    for _ in 1..levels {
        out = out.iter().flat_map(|&c| [c; 4]).collect();
    }
    out
}

#[test]
fn mode_all_and_midpoint_are_piecewise_linear() {
    let quads = grid(4, 4);
    let tris = triangulate_quads(&quads);
    for levels in 1..=3 {
        for (mesh, triangles, linear_scheme, schemes) in [
            (
                &quads,
                false,
                Scheme::Bilinear,
                vec![Scheme::CatmullClark, Scheme::Bilinear, Scheme::QuadTriangle],
            ),
            (
                &tris,
                true,
                Scheme::Midpoint,
                vec![Scheme::Loop, Scheme::Midpoint, Scheme::QuadTriangle],
            ),
        ] {
            let (uv, charts) = two_charts(mesh);
            let linear = subdivide(mesh, &Options::new(linear_scheme, levels)).unwrap();
            let charts_out = child_charts(&charts, &mesh.face_sizes, levels, triangles);
            for scheme in schemes {
                for &mode in FVarLinear::ALL {
                    // Midpoint is linear in every mode; the others in mode `all`.
                    if mode != FVarLinear::All && scheme != Scheme::Midpoint {
                        continue;
                    }
                    let options = Options::new(scheme, levels).with_fvar_linear(mode);
                    let (out, channels) = subdivide_with_attributes(
                        mesh,
                        std::slice::from_ref(&uv),
                        &options,
                        &Tags::default(),
                    )
                    .unwrap();
                    let what = format!("{scheme} {mode} level {levels}");
                    assert_piecewise_linear(&what, &out, &channels[0], &linear, &charts_out);
                }
            }
        }
    }
}

#[test]
fn a_constant_channel_stays_constant_in_every_mode() {
    let quads = grid(3, 5);
    let tris = triangulate_quads(&quads);
    for &scheme in Scheme::ALL {
        let mesh = if scheme.triangles_only() { &tris } else { &quads };
        let (cut, _) = two_charts(mesh);
        let count = cut.len();
        let constant = Attribute::face_varying(
            "c",
            2,
            [0.3f32, -4.0].repeat(count),
            cut.indices.clone().unwrap(),
        );
        for &mode in FVarLinear::ALL {
            let options = Options::new(scheme, 2).with_fvar_linear(mode);
            let result = subdivide_with_attributes(
                mesh,
                std::slice::from_ref(&constant),
                &options,
                &Tags::default(),
            );
            let Ok((_, channels)) = result else {
                // Schemes that do not refine face-varying channels yet say so.
                let message = result.err().unwrap().to_string();
                assert!(message.contains("face-varying"), "{scheme}: {message}");
                continue;
            };
            for v in channels[0].values.chunks(2) {
                assert!(
                    (v[0] - 0.3).abs() < 1e-6 && (v[1] + 4.0).abs() < 1e-6,
                    "{scheme} {mode}: {v:?}"
                );
            }
        }
    }
}
