//! The beam: cost per generalized-α step against the number of unknowns (30 … 3000, should be
//! linear: banded matrices through a sparse LU), one step of each integrator, and study B1
//! whole with the study settings.

use std::path::Path;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use rollbeam::ode::Method;
use rollbeam::run::{run, Overrides};
use rollbeam::scene::{Model, Scene};

fn b1() -> Scene {
    Scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("studies/beam-b1.yaml"))
        .expect("B1 is valid")
}

/// B1 with `elements` elements of degree 4 (12 unknowns per element) for `steps` fixed steps.
fn sized(elements: usize, steps: usize, h: f64) -> Scene {
    let mut scene = b1();
    scene.duration = steps as f64 * h;
    scene.interval = scene.duration;
    if let Model::Beam(b) = &mut scene.model {
        b.beam.elements = elements;
        b.shapes.clear();
    }
    scene
}

fn per_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("beam-step-genalpha");
    group.sample_size(10);
    let (steps, h) = (20, 1e-4);
    for elements in [3, 8, 25, 83, 250] {
        let scene = sized(elements, steps, h);
        let over = Overrides {
            method: Some(Method::GenAlpha),
            rtol: Some(1e-6),
            atol: Some(1e-9),
            fixed_step: Some(h),
            ..Default::default()
        };
        group.bench_with_input(
            BenchmarkId::from_parameter(12 * elements),
            &scene,
            |b, s| b.iter(|| run(s, &over, false).expect("runs")),
        );
    }
    group.finish();

    let mut group = c.benchmark_group("beam-one-step");
    group.sample_size(10);
    let scene = sized(16, 1, 1e-5);
    for method in Method::ALL {
        let over = Overrides {
            method: Some(method),
            rtol: Some(1e-6),
            atol: Some(1e-9),
            fixed_step: Some(1e-5),
            ..Default::default()
        };
        group.bench_function(method.name(), |b| {
            b.iter(|| run(&scene, &over, false).expect("runs"))
        });
    }
    group.finish();
}

fn study(c: &mut Criterion) {
    let mut group = c.benchmark_group("beam-b1-whole");
    group.sample_size(10);
    let scene = b1();
    group.bench_function("genalpha-study-settings", |b| {
        b.iter(|| run(&scene, &Overrides::default(), false).expect("runs"))
    });
    group.finish();
}

criterion_group!(benches, per_step, study);
criterion_main!(benches);
