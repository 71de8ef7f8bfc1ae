//! Study 1, case P1: a whole 5 s run with each integrator at a loose and a tight tolerance.

use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use rollbeam::ode::Method;
use rollbeam::run::{run, Overrides};
use rollbeam::scene::Scene;

fn p1(c: &mut Criterion) {
    let scene =
        Scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("studies/parabola-p1.yaml"))
            .expect("P1 is valid");
    let mut group = c.benchmark_group("parabola-p1");
    for method in Method::FIRST_ORDER {
        for rtol in [1e-6, 1e-10] {
            let over = Overrides {
                method: Some(method),
                rtol: Some(rtol),
                atol: Some(rtol * 1e-2),
                fixed_step: None,
                ..Default::default()
            };
            group.bench_function(format!("{}-rtol{rtol:e}", method.name()), |b| {
                b.iter(|| run(&scene, &over, false).expect("P1 runs"))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, p1);
criterion_main!(benches);
