//! Builds an evaluator and then its stencil table (what `stencils()` and the GPU ask for) CALLS
//! times, each after one `subdivide` of the same options, and prints the three times: a
//! profiler's view of the table made on first use.
//!
//!     cargo run --release --example table_build -- CALLS FILE.obj SCHEME LEVELS [limit] [normals]
use std::time::Instant;
use subsurf::io::obj::read_obj;
use subsurf::{Evaluator, HalfEdgeMesh, Options, Scheme, Tags};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "CALLS FILE.obj SCHEME LEVELS [limit] [normals]";
    let [calls, path, scheme, levels, flags @ ..] = &args[..] else { panic!("{usage}") };
    let calls: usize = calls.parse().expect(usage);
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mesh = read_obj(&text).unwrap_or_else(|e| panic!("{e}"));
    let scheme: Scheme = scheme.parse().unwrap_or_else(|e| panic!("{e}"));
    let levels = levels.parse().expect(usage);
    let flag = |name: &str| flags.iter().any(|f| f == name);
    let options =
        Options { limit: flag("limit"), normals: flag("normals"), ..Options::new(scheme, levels) };
    for _ in 0..calls {
        let start = Instant::now();
        let out = subsurf::scheme::subdivide_refined(&mesh, &options, &Tags::default());
        let subdivide = start.elapsed().as_secs_f64() * 1e3;
        drop(out);
        let start = Instant::now();
        let base = HalfEdgeMesh::from_poly(&mesh).unwrap_or_else(|e| panic!("{e}"));
        let evaluator = Evaluator::new(&base, &[], &options, &Tags::default())
            .unwrap_or_else(|e| panic!("{e}"));
        let build = start.elapsed().as_secs_f64() * 1e3;
        let start = Instant::now();
        let bytes = evaluator.table().map(|t| t.bytes()).unwrap_or_else(|e| panic!("{e}"));
        let table = start.elapsed().as_secs_f64() * 1e3;
        println!(
            "subdivide {subdivide:.1} ms, build {build:.1} ms ({:.2}x), table {table:.1} ms ({:.2}x), {bytes} bytes",
            build / subdivide,
            table / subdivide,
        );
    }
}
