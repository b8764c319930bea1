//! Stencil tables (`scheme::stencil_table`) on the benchmark tori: the time to build a table
//! against one `subdivide` call, the time of `StencilTable::evaluate` (positions, width 3) per
//! output point, and the table's bytes per output point. Median of 5 runs (3 for the builds).
//! Then the frames of `Evaluator::evaluate` per output point, refined and limit with normals,
//! median of 15: the torus, and a torus of triangles (Catmull-Clark there takes the steps and
//! the last level's rings, as on the horse; Loop its closed forms from the level before).
//! Run with `cargo bench --bench stencil`. Figures, not assertions.

use std::time::{Duration, Instant};
use subsurf::scheme::stencil_table;
use subsurf::shapes::{torus, torus_triangles};
use subsurf::{subdivide, Evaluator, HalfEdgeMesh, Options, PolyMesh, Scheme, Tags};

fn median(runs: usize, mut f: impl FnMut() -> Duration) -> Duration {
    let mut times: Vec<Duration> = (0..runs).map(|_| f()).collect();
    times.sort();
    times[runs / 2]
}

/// The median time of `frame` over `runs` frames, each on the control positions scaled a
/// little more (a deformation per frame), the scaling not timed.
fn median_frame(runs: usize, mesh: &PolyMesh, mut frame: impl FnMut(&[f32])) -> Duration {
    let mut count = 0;
    median(runs, || {
        count += 1;
        let s = 1.0 + 0.01 * count as f32;
        let control: Vec<f32> = mesh.positions.iter().map(|&x| x * s).collect();
        let start = Instant::now();
        frame(&control);
        start.elapsed()
    })
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn main() {
    let cases: Vec<(&str, PolyMesh, u32)> = vec![
        ("torus 1M quads", torus(1000, 1000, 1.0, 0.25), 1),
        ("torus 100k quads", torus(400, 250, 1.0, 0.25), 2),
    ];
    println!("| mesh | level | points out | subdivide ms | build ms | build / subdivide | evaluate ms | ns / point | bytes / point | entries / point |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (name, mesh, level) in &cases {
        let options = Options::new(Scheme::CatmullClark, *level);
        let tags = Tags::default();
        let subdivide_time = median(3, || {
            let start = Instant::now();
            let out = subdivide(mesh, &options).unwrap();
            let t = start.elapsed();
            drop(out);
            t
        });
        let build_time = median(3, || {
            let start = Instant::now();
            let built = stencil_table(mesh, &options, &tags).unwrap();
            let t = start.elapsed();
            drop(built);
            t
        });
        let (table, mut out) = stencil_table(mesh, &options, &tags).unwrap();
        let evaluate_time = median_frame(5, mesh, |control| {
            table.evaluate(control, 3, &mut out.positions).unwrap();
        });
        let points = table.num_stencils();
        println!(
            "| {name} | {level} | {points} | {:.0} | {:.0} | {:.1} | {:.1} | {:.1} | {:.1} | {:.2} |",
            ms(subdivide_time),
            ms(build_time),
            build_time.as_secs_f64() / subdivide_time.as_secs_f64(),
            ms(evaluate_time),
            evaluate_time.as_secs_f64() * 1e9 / points as f64,
            table.bytes() as f64 / points as f64,
            table.indices().len() as f64 / points as f64,
        );
    }
    frames();
}

/// Evaluator frames: what an animation pays per frame, natively.
fn frames() {
    let cases: Vec<(&str, PolyMesh, Scheme)> = vec![
        ("torus 100k quads", torus(400, 250, 1.0, 0.25), Scheme::CatmullClark),
        ("torus 100k triangles", torus_triangles(250, 200, 1.0, 0.25), Scheme::CatmullClark),
        ("torus 100k triangles", torus_triangles(250, 200, 1.0, 0.25), Scheme::Loop),
    ];
    println!();
    println!(
        "| mesh | scheme | level | points out | refined ns / point | limit + normals ns / point |"
    );
    println!("|---|---|---|---|---|---|");
    for (name, mesh, scheme) in &cases {
        let base = HalfEdgeMesh::from_poly(mesh).unwrap();
        let ns = |limit: bool| {
            let options = Options { limit, normals: limit, ..Options::new(*scheme, 2) };
            let evaluator = Evaluator::new(&base, &[], &options, &Tags::default()).unwrap();
            let points = evaluator.num_vertices();
            let mut positions = vec![0.0; 3 * points];
            let mut normals = vec![0.0; if limit { 3 * points } else { 0 }];
            let time = median_frame(15, mesh, |control| {
                let normals = limit.then_some(&mut normals[..]);
                evaluator.evaluate(control, &mut positions, normals).unwrap();
            });
            (points, time.as_secs_f64() * 1e9 / points as f64)
        };
        let ((points, refined), (_, limit)) = (ns(false), ns(true));
        println!("| {name} | {scheme} | 2 | {points} | {refined:.1} | {limit:.1} |");
    }
}
