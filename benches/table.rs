//! Every scheme on the benchmark meshes, as a table: median of 5 runs of the whole `subdivide`
//! call (build + refine) and of refinement alone, in ms and million output faces per second.
//! Run with `cargo bench --bench table` (`SUBSURF_BENCH_SCHEMES=catmull-clark,loop` for some
//! schemes only). Figures, not assertions: speed targets live here. The Catmull-Clark and Loop
//! rows end with the same meshes fully creased (every edge sharpness 2.5): the tagged path,
//! whose target is at most 1.5× the untagged time.

use std::time::{Duration, Instant};
use subsurf::attributes::Attribute;
use subsurf::scheme::{subdivide_mesh_with_tags, subdivide_with_attributes};
use subsurf::shapes::{torus, torus_triangles, torus_uv};
use subsurf::{subdivide_with_tags, Crease, HalfEdgeMesh, Options, PolyMesh, Scheme, Tags};

fn median(mut f: impl FnMut() -> Duration) -> Duration {
    let mut times: Vec<Duration> = (0..5).map(|_| f()).collect();
    times.sort();
    times[2]
}

/// Every edge of `mesh` as a crease of sharpness `sharpness`.
fn all_edges_creased(mesh: &PolyMesh, sharpness: f32) -> Tags {
    let mut creases = Vec::with_capacity(mesh.indices.len() / 2);
    let mut start = 0usize;
    for &n in &mesh.face_sizes {
        let face = &mesh.indices[start..start + n as usize];
        for (k, &a) in face.iter().enumerate() {
            let b = face[(k + 1) % face.len()];
            if a < b {
                creases.push(Crease { vertices: [a, b], sharpness });
            }
        }
        start += n as usize;
    }
    Tags { creases, ..Tags::default() }
}

fn main() {
    if std::env::var("SUBSURF_BENCH_ATTRIBUTES_ONLY").is_ok() {
        return attribute_cost(&torus(1000, 1000, 1.0, 0.25));
    }
    let only: Vec<Scheme> = std::env::var("SUBSURF_BENCH_SCHEMES")
        .ok()
        .map(|list| Scheme::parse_list(&list).expect("SUBSURF_BENCH_SCHEMES: scheme names"))
        .unwrap_or_default();
    // Same meshes as tools/osd/far_perf.sh (torus R = 1, r = 0.25).
    let quads = torus(1000, 1000, 1.0, 0.25);
    let tris = torus_triangles(250, 200, 1.0, 0.25);
    let (none, quads_creased, tris_creased) =
        (Tags::default(), all_edges_creased(&quads, 2.5), all_edges_creased(&tris, 2.5));
    let cases: Vec<(&str, &PolyMesh, u32, &Tags)> = vec![
        ("torus 1M quads", &quads, 1, &none),
        ("torus 100k tris", &tris, 1, &none),
        ("torus 100k tris", &tris, 2, &none),
        ("torus 100k tris", &tris, 3, &none),
        ("torus 1M quads, creased 2.5", &quads, 1, &quads_creased),
        ("torus 100k tris, creased 2.5", &tris, 3, &tris_creased),
    ];
    println!("| scheme | mesh | level | faces out | total ms | refine ms | M faces/s total | M faces/s refine |");
    println!("|---|---|---|---|---|---|---|---|");
    for &scheme in Scheme::ALL {
        if !only.is_empty() && !only.contains(&scheme) {
            continue;
        }
        for &(name, mesh, levels, tags) in &cases {
            let triangles = mesh.face_sizes.iter().all(|&n| n == 3);
            if scheme.triangles_only() && !triangles {
                continue;
            }
            let creased = !tags.is_trivial();
            if creased && !matches!(scheme, Scheme::CatmullClark | Scheme::Loop) {
                continue;
            }
            let options = Options::new(scheme, levels);
            let mut faces = 0;
            let total = median(|| {
                let t = Instant::now();
                faces =
                    subdivide_with_tags(mesh, &options, tags).map(|m| m.num_faces()).unwrap_or(0);
                t.elapsed()
            });
            let base = HalfEdgeMesh::from_poly(mesh).expect("benchmark meshes are valid");
            let refine = median(|| {
                let m = base.clone();
                let t = Instant::now();
                let out = subdivide_mesh_with_tags(m, &options, tags);
                let elapsed = t.elapsed();
                drop(out);
                elapsed
            });
            let rate = |d: Duration| faces as f64 / d.as_secs_f64() / 1e6;
            println!(
                "| {scheme} | {name} | {levels} | {faces} | {:.1} | {:.1} | {:.1} | {:.1} |",
                total.as_secs_f64() * 1e3,
                refine.as_secs_f64() * 1e3,
                rate(total),
                rate(refine)
            );
        }
    }
    attribute_cost(&quads);
}

/// What attribute channels cost: Catmull-Clark on the 1M-quad torus at level 1, the whole
/// call, plain, with a vertex-varying `color` of 3 floats, and with that colour and a
/// face-varying `uv` (seams along both closing loops), alternating (the attributes issue's
/// target for uv + color is at most 1.6 times the plain time). Best and median of
/// `SUBSURF_BENCH_ROUNDS` rounds (7), with the ratios of each to the plain call's: the best
/// times are what `bench/attributes.mjs` compares in wasm; the medians take the VM's spikes in;
/// the median of each round's ratio to that round's plain call cancels the VM's drift.
///
/// The clock stops when the call returns, and the result is dropped after (criterion's
/// `iter_with_large_drop`): giving back a uv + colour result's 256 MB to the kernel takes
/// 10-20 ms here, which is the caller's whenever it lets the result go, and which the wasm
/// benchmark does not count either (V8 frees array buffers off the main thread). The second
/// line counts each drop in its call, as this benchmark did before the thirty-fourth session.
fn attribute_cost(quads: &PolyMesh) {
    let color: Vec<f32> = (0..quads.positions.len()).map(|i| (i % 7) as f32 / 7.0).collect();
    let color = Attribute::vertex("color", 3, color);
    let both = [torus_uv(1000, 1000), color.clone()];
    let cases: [&[Attribute]; 3] = [&[], std::slice::from_ref(&color), &both];
    let options = Options::new(Scheme::CatmullClark, 1);
    let none = Tags::default();
    let rounds: usize =
        std::env::var("SUBSURF_BENCH_ROUNDS").ok().and_then(|n| n.parse().ok()).unwrap_or(7).max(1);
    // Per case, each round's call alone and with its result's drop.
    let mut calls = [[Vec::new(), Vec::new()], [Vec::new(), Vec::new()], [Vec::new(), Vec::new()]];
    for _ in 0..rounds {
        for (channels, [alone, dropped]) in cases.iter().zip(&mut calls) {
            let t = Instant::now();
            let result = if channels.is_empty() {
                subdivide_with_tags(quads, &options, &none).map(|mesh| (mesh, Vec::new()))
            } else {
                subdivide_with_attributes(quads, channels, &options, &none)
            };
            alone.push(t.elapsed());
            drop(result);
            dropped.push(t.elapsed());
        }
    }
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    let line = |k: usize| {
        let plain = &calls[0][k];
        // Each round's call against the plain call of the same round: calls made side by side
        // share the machine's state of the moment, which separate best and median times do not.
        let per_round = |times: &[Duration]| {
            let mut ratios: Vec<f64> =
                times.iter().zip(plain).map(|(t, p)| t.as_secs_f64() / p.as_secs_f64()).collect();
            ratios.sort_by(f64::total_cmp);
            ratios[ratios.len() / 2]
        };
        let sorted = |times: &[Duration]| {
            let mut times = times.to_vec();
            times.sort();
            times
        };
        let plain_sorted = sorted(plain);
        let mid = plain.len() / 2;
        let stats = |times: &[Duration]| {
            let (paired, t) = (per_round(times), sorted(times));
            format!(
                "best {:.1} median {:.1} ms (ratios {:.2}, {:.2}; per round {paired:.2})",
                ms(t[0]),
                ms(t[mid]),
                t[0].as_secs_f64() / plain_sorted[0].as_secs_f64(),
                t[mid].as_secs_f64() / plain_sorted[mid].as_secs_f64()
            )
        };
        format!(
            "positions only best {:.1} median {:.1} ms | + color (3) {} | + uv (2, face-varying) and color {}",
            ms(plain_sorted[0]),
            ms(plain_sorted[mid]),
            stats(&calls[1][k]),
            stats(&calls[2][k])
        )
    };
    println!("\nattributes: catmull-clark torus 1M quads L1, {rounds} rounds: {}", line(0));
    println!("  each with its result's drop: {}", line(1));
}
