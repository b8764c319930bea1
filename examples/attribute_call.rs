//! One Catmull-Clark call on the benchmark torus (1M quads) at level 1, positions only or with
//! a face-varying `uv` and a vertex-varying `color`: the case of the attributes' speed target,
//! for an instruction count that does not drift with the shared machine's load (timings here
//! vary by 10-30 % from run to run). `bench/callgrind.sh` runs it under callgrind.
//!
//!     cargo run --release --example attribute_call -- [plain|color|uv-color] [CALLS]
use subsurf::attributes::Attribute;
use subsurf::scheme::subdivide_with_attributes;
use subsurf::shapes::{torus, torus_uv};
use subsurf::{Options, Scheme, Tags};

fn main() {
    let (uv, colored) = match std::env::args().nth(1).as_deref() {
        None | Some("uv-color") => (true, true),
        Some("color") => (false, true),
        Some("plain") => (false, false),
        Some(other) => {
            eprintln!("attribute_call: unknown case '{other}'; use plain, color or uv-color");
            std::process::exit(2);
        }
    };
    // More than one call, for a profiler's view of calls in one process (as a benchmark's).
    let calls: usize = std::env::args().nth(2).and_then(|n| n.parse().ok()).unwrap_or(1);
    let quads = torus(1000, 1000, 1.0, 0.25);
    let color: Vec<f32> = (0..quads.positions.len()).map(|i| (i % 7) as f32 / 7.0).collect();
    let mut channels = Vec::new();
    if uv {
        channels.push(torus_uv(1000, 1000));
    }
    if colored {
        channels.push(Attribute::vertex("color", 3, color));
    }
    let options = Options::new(Scheme::CatmullClark, 1);
    for _ in 0..calls {
        let start = std::time::Instant::now();
        let (mesh, attributes) =
            subdivide_with_attributes(&quads, &channels, &options, &Tags::default())
                .unwrap_or_else(|e| panic!("{e}"));
        let ms = start.elapsed().as_secs_f64() * 1e3;
        println!("{} vertices, {} channels, {ms:.1} ms", mesh.num_vertices(), attributes.len());
    }
}
