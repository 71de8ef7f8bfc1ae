//! Vehicles on the bridge (the targets in REPORT.md's performance table):
//! - the sprung mass crossing the 25 m bridge (`studies/vehicle-sprung.yaml`) at the defaults,
//!   against D44 at its defaults, side by side in one run;
//! - one railway car (the first of `studies/vehicle-railcar.yaml`) swept over 100 speeds from
//!   40 to 130 m/s on the machine's cores, as `rollbeam sweep` runs it;
//! - how the cost grows with the number of vehicles: one, two and four of the railway cars.

use std::path::Path;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use rollbeam::run::{run, Overrides};
use rollbeam::scene::{Scene, SceneSpec};
use rollbeam::workflows::sweep::{run_sweep, Setting};

#[path = "d44.rs"]
mod d44;

/// Every key the plan chooses left out of D44: its defaults, as `bridge-d44-models/automatic`.
const CHOSEN: [&str; 8] = [
    "elements:",
    "order:",
    "rtol:",
    "atol:",
    "shapes:",
    "method:",
    "rho_inf:",
    "model:",
];

fn study(file: &str) -> Scene {
    Scene::load(
        &Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("studies")
            .join(file),
    )
    .expect("a valid study")
}

/// The railway study with its first `cars` cars.
fn cars(cars: usize) -> SceneSpec {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("studies/vehicle-railcar.yaml");
    let text = std::fs::read_to_string(&path).expect("the study");
    let cut = ["  - name: car2", "  - name: car3", "  - name: car4"]
        .get(cars - 1)
        .and_then(|c| text.find(c));
    let text = match cut {
        Some(at) => format!(
            "{}{}",
            &text[..at],
            &text[text.find("output:").expect("output")..]
        ),
        None => text,
    };
    SceneSpec::parse(&text, "vehicle-railcar.yaml", "vehicle-railcar").expect("valid")
}

fn crossing(c: &mut Criterion) {
    let mut group = c.benchmark_group("vehicles-crossing");
    group.sample_size(20);
    let over = Overrides::default();
    for (name, scene) in [
        ("vehicle-sprung", study("vehicle-sprung.yaml")),
        ("bridge-d44-defaults", d44::d44_without(&CHOSEN)),
    ] {
        group.bench_with_input(BenchmarkId::from_parameter(name), &scene, |b, s| {
            b.iter(|| run(s, &over, false).expect("runs"))
        });
    }
    group.finish();
}

fn railcar_sweep(c: &mut Criterion) {
    let mut group = c.benchmark_group("vehicles-railcar-sweep");
    group.sample_size(10);
    let spec = cars(1);
    let setting = Setting::parse("vehicles.*.speed=40:130:100").expect("a setting");
    group.bench_function("100 speeds", |b| {
        b.iter(|| run_sweep(&spec, &setting, &Overrides::default(), false).expect("runs"))
    });
    group.finish();
}

fn growth(c: &mut Criterion) {
    let mut group = c.benchmark_group("vehicles-growth");
    group.sample_size(10);
    for n in [1, 2, 4] {
        let scene = rollbeam::plan::Planner::default()
            .plan(&cars(n))
            .expect("a scene");
        group.bench_with_input(BenchmarkId::from_parameter(n), &scene, |b, s| {
            b.iter(|| run(s, &Overrides::default(), false).expect("runs"))
        });
    }
    group.finish();
}

criterion_group!(benches, crossing, railcar_sweep, growth);
criterion_main!(benches);
