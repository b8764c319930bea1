//! One Catmull-Clark call on the benchmark torus (1M quads) at level 1, positions only or with
//! a face-varying `uv` and a vertex-varying `color`: the case of the attributes' speed target,
//! for an instruction count that does not drift with the shared machine's load (timings here
//! vary by 10-30 % from run to run). `bench/callgrind.sh` runs it under callgrind.
//!
//!     cargo run --release --example attribute_call -- [plain|color|uv|uv-color|mix] [CALLS]
//!
//! `mix` runs the three cases in turn, as `cargo bench --bench table` does
//! (`SUBSURF_BENCH_ATTRIBUTES_ONLY`): the allocator's state between calls, and so the page faults
//! of each, is then the benchmark's. Each call prints its minor page faults (Linux).
use subsurf::attributes::Attribute;
use subsurf::scheme::subdivide_with_attributes;
use subsurf::shapes::{torus, torus_uv};
use subsurf::{Options, Scheme, Tags};

fn main() {
    let cases: &[(bool, bool)] = match std::env::args().nth(1).as_deref() {
        None | Some("uv-color") => &[(true, true)],
        Some("color") => &[(false, true)],
        Some("uv") => &[(true, false)],
        Some("plain") => &[(false, false)],
        Some("mix") => &[(false, false), (false, true), (true, true)],
        Some(other) => {
            eprintln!(
                "attribute_call: unknown case '{other}'; use plain, color, uv, uv-color or mix"
            );
            std::process::exit(2);
        }
    };
    // More than one call, for a profiler's view of calls in one process (as a benchmark's).
    let calls: usize = std::env::args().nth(2).and_then(|n| n.parse().ok()).unwrap_or(1);
    let quads = torus(1000, 1000, 1.0, 0.25);
    let color: Vec<f32> = (0..quads.positions.len()).map(|i| (i % 7) as f32 / 7.0).collect();
    // Built once, as in the benchmark: a copy per call would add its own page faults.
    let both = [torus_uv(1000, 1000), Attribute::vertex("color", 3, color)];
    let options = Options::new(Scheme::CatmullClark, 1);
    for _ in 0..calls {
        for &(textured, colored) in cases {
            let channels = match (textured, colored) {
                (true, true) => &both[..],
                (true, false) => &both[..1],
                (false, true) => &both[1..],
                (false, false) => &[],
            };
            let faults = minor_faults();
            let start = std::time::Instant::now();
            let (mesh, attributes) =
                subdivide_with_attributes(&quads, channels, &options, &Tags::default())
                    .unwrap_or_else(|e| panic!("{e}"));
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let (vertices, count) = (mesh.num_vertices(), attributes.len());
            // Timed apart, as `cargo bench --bench table` does: the memory goes back to the
            // kernel whenever the caller lets the result go.
            let start = std::time::Instant::now();
            drop((mesh, attributes));
            let drop_ms = start.elapsed().as_secs_f64() * 1e3;
            let faults = minor_faults().saturating_sub(faults);
            println!(
                "{vertices} vertices, {count} channels, {ms:.1} ms, {faults} page faults, drop {drop_ms:.1} ms"
            );
        }
    }
}

/// Minor page faults of this process so far (0 where /proc is not there).
fn minor_faults() -> u64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // Field 10; the command name (field 2) is in parentheses and may hold spaces.
    let after_name = stat.rsplit_once(')').map_or("", |(_, rest)| rest);
    after_name.split_whitespace().nth(7).and_then(|n| n.parse().ok()).unwrap_or(0)
}
