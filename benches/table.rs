//! Every scheme on the benchmark meshes, as a table: median of 5 runs of the whole `subdivide`
//! call (build + refine) and of refinement alone, in ms and million output faces per second.
//! Run with `cargo bench --bench table`. Figures, not assertions: speed targets live here.

use std::time::{Duration, Instant};
use subsurf::scheme::subdivide_mesh;
use subsurf::shapes::{torus, torus_triangles};
use subsurf::{subdivide, HalfEdgeMesh, Options, PolyMesh, Scheme};

fn median(mut f: impl FnMut() -> Duration) -> Duration {
    let mut times: Vec<Duration> = (0..5).map(|_| f()).collect();
    times.sort();
    times[2]
}

fn main() {
    // Same meshes as tools/osd/far_perf.sh (torus R = 1, r = 0.25).
    let quads = torus(1000, 1000, 1.0, 0.25);
    let tris = torus_triangles(250, 200, 1.0, 0.25);
    let cases: Vec<(&str, &PolyMesh, u32)> = vec![
        ("torus 1M quads", &quads, 1),
        ("torus 100k tris", &tris, 1),
        ("torus 100k tris", &tris, 2),
        ("torus 100k tris", &tris, 3),
    ];
    println!("| scheme | mesh | level | faces out | total ms | refine ms | M faces/s total | M faces/s refine |");
    println!("|---|---|---|---|---|---|---|---|");
    for &scheme in Scheme::ALL {
        for &(name, mesh, levels) in &cases {
            let triangles = mesh.face_sizes.iter().all(|&n| n == 3);
            if scheme.triangles_only() && !triangles {
                continue;
            }
            let options = Options::new(scheme, levels);
            let mut faces = 0;
            let total = median(|| {
                let t = Instant::now();
                faces = subdivide(mesh, &options).map(|m| m.num_faces()).unwrap_or(0);
                t.elapsed()
            });
            let base = HalfEdgeMesh::from_poly(mesh).expect("benchmark meshes are valid");
            let refine = median(|| {
                let m = base.clone();
                let t = Instant::now();
                let out = subdivide_mesh(m, &options);
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
}
