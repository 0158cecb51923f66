//! Segmentation stages on a ~21k-triangle dumbbell:
//! `cargo bench -p soak-graph --bench segment`.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use soak_graph::segment::gmm::GaussianMixture;
use soak_graph::segment::sdf::shape_diameter;
use soak_graph::segment::{SegmentOptions, segment};

fn stages(c: &mut Criterion) {
    let mesh = soak_bake::builtin::parse("builtin:dumbbell:0.3:0.08:1.2:100").expect("builtin");
    let options = SegmentOptions::default();
    let once = segment(&mesh, &options).expect("segment");
    let t = once.timings;
    eprintln!(
        "{} triangles: SDF {:?}, EM {:?}, graph cut {:?}, total {:?}",
        mesh.triangles.len(),
        t.sdf,
        t.clustering,
        t.graph_cut,
        t.total()
    );

    let mut group = c.benchmark_group("segment_21k");
    group.sample_size(10);
    group.bench_function("sdf", |b| {
        b.iter(|| shape_diameter(black_box(&mesh), &options).expect("sdf"))
    });
    let sdf = shape_diameter(&mesh, &options).expect("sdf").normalized;
    group.bench_function("em", |b| {
        b.iter(|| {
            GaussianMixture::fit(
                black_box(&sdf),
                options.clusters,
                options.seed,
                options.em_tolerance,
                options.em_max_iterations,
            )
        })
    });
    group.bench_function("segment", |b| {
        b.iter(|| segment(black_box(&mesh), &options).expect("segment"))
    });
    group.finish();
}

criterion_group!(benches, stages);
criterion_main!(benches);
