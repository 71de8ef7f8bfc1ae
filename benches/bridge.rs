//! Study D44 (the disk crossing the bridge, consistent coupling) whole, with the default
//! solver (generalized-α, the scene's ρ∞ = 0.8) at rtol 10⁻⁶ and 10⁻⁸: the cost of accuracy
//! on the coupled problem. Ten samples each.
//!
//! D44 at 0.1 % of the converged peak midspan deflection.
//! `rollbeam tradeoff` names rtol 10⁻³ on 6 elements of degree 4 for it (0.02 % measured);
//! REPORT.md's performance table gives the target for the whole run on one core. The
//! automatic defaults (test `defaults_land_within_the_accuracy_asked`) are measured both ways
//! a user meets them: the solver block left empty (ρ∞ = 1, atol from the response's size: the
//! defaults proper) and the mesh and tolerances left out (the study's ρ∞ = 0.8, atol 10⁻⁹).
//!
//! The same with the beam model left out too (the automatic choice, a modal beam of 16 modes),
//! and the exact beam with its defaults at the real shear modulus and at G × 10⁴ (what an
//! undamped stiff shear costs).
//!
//! The HSLM study's whole sweep, A1–A10 at 40–120 m/s (810 cases on the automatic modal beam,
//! integrated exactly as the plan chooses), on the machine's cores as `rollbeam sweep` runs
//! it, beside the same cases time-stepped by generalized-α at the plan's rtol.
//!
//! How one HSLM case's cost grows (HSLM-A1 at 90 m/s, the defaults, integrated exactly):
//! with the modes kept, and with the train's axles (trains of equal axles 4 m apart).

use std::path::Path;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use rollbeam::run::{run, Overrides};
use rollbeam::scene::{Model, Scene};

#[path = "d44.rs"]
mod d44;
use d44::{d44_text_without, d44_without};

fn d44() -> Scene {
    let mut scene =
        Scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("studies/bridge-d44.yaml"))
            .expect("D44 is valid");
    if let Model::Beam(b) = &mut scene.model {
        b.shapes.clear();
    }
    scene
}

fn whole(c: &mut Criterion) {
    let mut group = c.benchmark_group("bridge-d44-whole");
    group.sample_size(10);
    let scene = d44();
    for rtol in [1e-6, 1e-8] {
        let over = Overrides {
            rtol: Some(rtol),
            ..Default::default()
        };
        group.bench_with_input(BenchmarkId::from_parameter(rtol), &scene, |b, s| {
            b.iter(|| run(s, &over, false).expect("runs"))
        });
    }
    group.finish();
}

fn at_a_tenth_of_a_percent(c: &mut Criterion) {
    let mut group = c.benchmark_group("bridge-d44-0.1%");
    group.sample_size(20);
    let mut scene = d44();
    if let Model::Beam(b) = &mut scene.model {
        b.beam.elements = 6;
    }
    let over = Overrides {
        rtol: Some(1e-3),
        ..Default::default()
    };
    group.bench_function("genalpha-rtol1e-3-6el", |b| {
        b.iter(|| run(&scene, &over, false).expect("runs"))
    });
    group.finish();
}

fn with_the_defaults(c: &mut Criterion) {
    let mut group = c.benchmark_group("bridge-d44-defaults");
    group.sample_size(10);
    let mesh = ["elements:", "order:", "rtol:", "atol:", "shapes:"];
    let every = [&mesh[..], &["method:", "rho_inf:"]].concat();
    for (name, keys) in [
        ("mesh-and-tolerances", &mesh[..]),
        ("empty-solver", &every[..]),
    ] {
        let scene = d44_without(keys);
        group.bench_function(name, |b| {
            b.iter(|| run(&scene, &Overrides::default(), false).expect("runs"))
        });
    }
    group.finish();
}

fn beam_models(c: &mut Criterion) {
    let mut group = c.benchmark_group("bridge-d44-models");
    group.sample_size(10);
    let defaults = [
        "elements:",
        "order:",
        "rtol:",
        "atol:",
        "shapes:",
        "method:",
        "rho_inf:",
    ];
    let automatic = [&defaults[..], &["model:"]].concat();
    for (name, keys, shear) in [
        ("automatic", &automatic[..], 1.0),
        ("exact", &defaults[..], 1.0),
        ("exact-shear-x1e4", &defaults[..], 1e4),
    ] {
        let scene = d44_text_without(keys, shear);
        group.bench_function(name, |b| {
            b.iter(|| run(&scene, &Overrides::default(), false).expect("runs"))
        });
    }
    group.finish();
}

fn hslm_sweep(c: &mut Criterion) {
    use rollbeam::scene::SceneSpec;
    use rollbeam::workflows::sweep::{run_grid, Setting};
    let mut group = c.benchmark_group("hslm-15m-sweep");
    group.sample_size(10);
    let spec =
        SceneSpec::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("studies/hslm-15m.yaml"))
            .expect("the HSLM study is valid");
    let settings = [
        Setting::parse("train.speed=40:120:81").expect("a range"),
        Setting::parse("train.hslm=A1,A2,A3,A4,A5,A6,A7,A8,A9,A10").expect("a list"),
    ];
    group.bench_function("810-cases", |b| {
        b.iter(|| run_grid(&spec, &settings, &Overrides::default(), false).expect("runs"))
    });
    let stepped = Overrides {
        method: Some(rollbeam::ode::Method::GenAlpha),
        ..Default::default()
    };
    group.bench_function("810-cases-genalpha", |b| {
        b.iter(|| run_grid(&spec, &settings, &stepped, false).expect("runs"))
    });
    group.finish();
}

/// The HSLM study's text with the beam's modes or the train replaced.
fn hslm_text(beam_model: &str, train: &str) -> String {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("studies/hslm-15m.yaml"),
    )
    .expect("the HSLM study");
    text.replace("    damping:", &format!("{beam_model}    damping:"))
        .replace("  hslm: A1\n", train)
}

fn hslm_growth(c: &mut Criterion) {
    let mut group = c.benchmark_group("hslm-15m-growth");
    group.sample_size(20);
    for modes in [6, 12, 24, 48, 96] {
        let text = hslm_text(
            &format!("    model: modal\n    modes: {modes}\n"),
            "  hslm: A1\n",
        );
        let scene = Scene::parse(&text, "hslm-15m", "benches").expect("valid");
        group.bench_with_input(BenchmarkId::new("modes", modes), &scene, |b, s| {
            b.iter(|| run(s, &Overrides::default(), false).expect("runs"))
        });
    }
    for axles in [1, 10, 100, 1000] {
        let at: Vec<String> = (0..axles).map(|k| format!("{}", 4 * k)).collect();
        let train = format!("  axles: [{}]\n  load: 170.0e3\n", at.join(", "));
        let scene = Scene::parse(&hslm_text("", &train), "hslm-15m", "benches").expect("valid");
        group.bench_with_input(BenchmarkId::new("axles", axles), &scene, |b, s| {
            b.iter(|| run(s, &Overrides::default(), false).expect("runs"))
        });
    }
    group.finish();
}

criterion_group!(
    benches,
    whole,
    at_a_tenth_of_a_percent,
    with_the_defaults,
    beam_models,
    hslm_sweep,
    hslm_growth
);
criterion_main!(benches);
