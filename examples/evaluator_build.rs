//! Builds the evaluator of the limit with normals for the 100k-quad torus at Catmull-Clark level
//! 2, CALLS times, and one `subdivide` with the same options before each, printing both times:
//! for a profiler's view of the build that the limit-surface issue holds to 3× a `subdivide`.
//!
//!     cargo run --release --example evaluator_build -- [CALLS]
use std::time::Instant;
use subsurf::shapes::torus;
use subsurf::{Evaluator, HalfEdgeMesh, Options, Scheme, Tags};

fn main() {
    let calls: usize = std::env::args().nth(1).and_then(|n| n.parse().ok()).unwrap_or(3);
    let mesh = torus(400, 250, 1.0, 0.25);
    let mut options = Options::new(Scheme::CatmullClark, 2);
    options.limit = true;
    options.normals = true;
    for _ in 0..calls {
        let start = Instant::now();
        let out = subsurf::scheme::subdivide_limit(&mesh, &options, &Tags::default());
        let subdivide = start.elapsed().as_secs_f64() * 1e3;
        drop(out);
        let start = Instant::now();
        let base = HalfEdgeMesh::from_poly(&mesh).unwrap_or_else(|e| panic!("{e}"));
        let evaluator = Evaluator::new(&base, &[], &options, &Tags::default())
            .unwrap_or_else(|e| panic!("{e}"));
        let build = start.elapsed().as_secs_f64() * 1e3;
        println!(
            "subdivide {subdivide:.1} ms, build {build:.1} ms ({:.2}x), {} points",
            build / subdivide,
            evaluator.num_vertices()
        );
    }
}
