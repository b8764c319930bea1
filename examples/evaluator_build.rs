//! Builds the evaluator of the limit with normals CALLS times, with one `subdivide` of the same
//! options before each, and prints both times: a profiler's view of the build that the
//! limit-surface issue holds to 3× a `subdivide`. By default the 100k-quad torus at
//! Catmull-Clark level 2 (its faces are all regular patches); or an OBJ file, scheme and level,
//! then any of `refined` (the refined table instead of the limit's), `normals` (with `refined`:
//! the limit's normals too) and `table` (also time the stencil table's first use, which
//! `stencils()` and the GPU make: an evaluator whose closed forms give every point leaves it
//! out until then).
//!
//!     cargo run --release --example evaluator_build -- [CALLS] [FILE.obj SCHEME LEVELS [refined] [normals] [table]]
use std::time::Instant;
use subsurf::io::obj::read_obj;
use subsurf::shapes::torus;
use subsurf::{Evaluator, HalfEdgeMesh, Options, Scheme, Tags};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let calls: usize = args.first().and_then(|n| n.parse().ok()).unwrap_or(3);
    let rest = &args[1.min(args.len())..];
    let flag = |name: &str| rest.iter().skip(3).any(|f| f == name);
    let (refined, table) = (flag("refined"), flag("table"));
    let (mesh, options) = match &rest[..rest.len().min(3)] {
        [path, scheme, levels] => {
            let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
            let scheme: Scheme = scheme.parse().unwrap_or_else(|e| panic!("{e}"));
            let levels = levels.parse().unwrap_or_else(|e| panic!("{levels}: {e}"));
            (read_obj(&text).unwrap_or_else(|e| panic!("{e}")), Options::new(scheme, levels))
        }
        _ => (torus(400, 250, 1.0, 0.25), Options::new(Scheme::CatmullClark, 2)),
    };
    let options = Options { limit: !refined, normals: !refined || flag("normals"), ..options };
    for _ in 0..calls {
        let start = Instant::now();
        let out = if refined {
            subsurf::scheme::subdivide_refined(&mesh, &options, &Tags::default())
        } else {
            subsurf::scheme::subdivide_limit(&mesh, &options, &Tags::default())
        };
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
        if table {
            let start = Instant::now();
            let bytes = evaluator.table().map(|t| t.bytes()).unwrap_or_else(|e| panic!("{e}"));
            let ms = start.elapsed().as_secs_f64() * 1e3;
            println!("  table {ms:.1} ms ({:.2}x), {bytes} bytes", ms / subdivide);
        }
    }
}
