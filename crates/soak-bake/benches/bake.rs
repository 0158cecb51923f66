//! Baking at 256², 1024², 2048², the deformation refresh, and unwrapping.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use soak_bake::{Atlas, BakeOptions, UnwrapOptions, builtin, unwrap};

fn bake(c: &mut Criterion) {
    let mut g = c.benchmark_group("bake");
    g.sample_size(10);
    let boat = builtin::boat(4.0, 1.2, 0.6);
    for res in [256u32, 1024, 2048] {
        g.bench_with_input(BenchmarkId::new("boat", res), &res, |b, &res| {
            b.iter(|| Atlas::bake(&boat, BakeOptions::square(res)).unwrap())
        });
    }
    for res in [256u32, 1024, 2048] {
        let mut atlas = Atlas::bake(&boat, BakeOptions::square(res)).unwrap();
        let moved: Vec<_> = boat.positions.iter().map(|p| p * 1.01).collect();
        g.bench_with_input(BenchmarkId::new("refresh_boat", res), &res, |b, _| {
            b.iter(|| atlas.refresh(&moved).unwrap())
        });
    }
    g.finish();
}

fn unwrapping(c: &mut Criterion) {
    let mut g = c.benchmark_group("unwrap");
    g.sample_size(10);
    // 316 × 158 segments: 99,224 triangles.
    let sphere = builtin::sphere(0.5, 316, 158).without_uvs();
    g.bench_function("sphere_99k_triangles", |b| {
        b.iter(|| unwrap(&sphere, UnwrapOptions::default()).unwrap())
    });
    g.finish();
}

criterion_group!(benches, bake, unwrapping);
criterion_main!(benches);
