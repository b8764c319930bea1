//! Refinement throughput on the benchmark meshes: a 1 M-quad torus (level 1) and a
//! 100 k-triangle torus (levels 1-3). `build` is the half-edge mesh from flat arrays, `refine`
//! is subdivision of an already built mesh, `total` is the whole `subdivide` call that a JS user
//! makes. Output faces per second = faces / time, printed by criterion as elements/s.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use subsurf::scheme::{predict_counts, subdivide_mesh};
use subsurf::shapes::{torus, torus_triangles};
use subsurf::{subdivide, HalfEdgeMesh, Options, PolyMesh, Scheme};

fn cases() -> Vec<(&'static str, PolyMesh, u32)> {
    let quads = torus(1000, 1000, 3.0, 1.0);
    let tris = torus_triangles(250, 200, 3.0, 1.0);
    vec![
        ("torus-1M-quads", quads, 1),
        ("torus-100k-tris", tris.clone(), 1),
        ("torus-100k-tris", tris.clone(), 2),
        ("torus-100k-tris", tris, 3),
    ]
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("catmull-clark");
    group.sample_size(10);
    for (name, mesh, levels) in cases() {
        let options = Options::new(Scheme::CatmullClark, levels);
        let base = HalfEdgeMesh::from_poly(&mesh).unwrap();
        let (_, faces) = predict_counts(&base, &options);
        group.throughput(Throughput::Elements(faces));
        let id = format!("{name}/L{levels}");
        group.bench_function(BenchmarkId::new("refine", &id), |b| {
            b.iter_batched(
                || base.clone(),
                |m| black_box(subdivide_mesh(m, &options).unwrap()),
                criterion::BatchSize::LargeInput,
            )
        });
        group.bench_function(BenchmarkId::new("total", &id), |b| {
            b.iter(|| black_box(subdivide(&mesh, &options).unwrap()))
        });
        if levels == 1 {
            group.throughput(Throughput::Elements(mesh.num_faces() as u64));
            group.bench_function(BenchmarkId::new("build", name), |b| {
                b.iter(|| black_box(HalfEdgeMesh::from_poly(&mesh).unwrap()))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
