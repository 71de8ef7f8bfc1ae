//! Automatic discretisation: a beam study with its mesh and tolerances left out gets them
//! from `solver.accuracy` (default 1e-3), and lands within that accuracy of the converged peak
//! deflection. Converged here means a mesh twice as fine as the chosen one at a tenth of its
//! rtol: the peak must agree with that reference to the accuracy asked, and the reference with
//! its own tenfold-tighter rerun to a tenth of it (so that it is a reference).
//!
//! The bridges are checked here. A sudden load's peak (studies 2 and 3) is only settled once
//! the thickness-shear motion it excites is resolved (ρ∞ = 1, rtol 1e-8: about a minute per
//! study), so those are checked by hand in REPORT.md against the converged values there.

mod common;

use common::{parse, run_beam, studies_dir};
use rollbeam::ode::Method;
use rollbeam::scene::{Model, Scene};

/// The study's text without `elements`, `order`, `rtol` and `atol`, and without shapes.
fn left_out(study: &str) -> Scene {
    let text = std::fs::read_to_string(studies_dir().join(study)).expect("study");
    let text: String = text
        .lines()
        .filter(|l| {
            let t = l.trim_start();
            !["elements:", "order:", "rtol:", "atol:", "shapes:"]
                .iter()
                .any(|k| t.starts_with(k))
        })
        .map(|l| format!("{l}\n"))
        .collect();
    parse(&text)
}

fn peak(r: &rollbeam::run::beam::BeamRun) -> f64 {
    r.rows
        .iter()
        .flat_map(|row| row.probes.iter().map(|p| p.w.abs()))
        .fold(0.0, f64::max)
}

fn refined(scene: &Scene, factor: usize) -> Scene {
    let mut s = scene.clone();
    if let Model::Beam(b) = &mut s.model {
        b.beam.elements *= factor;
    }
    s
}

#[test]
fn defaults_land_within_the_accuracy_asked() {
    for study in ["bridge-d44.yaml", "bridge-d50.yaml"] {
        let scene = left_out(study);
        let beam = scene.beam().expect("a beam study");
        let chosen = beam.discretisation.as_ref().expect("the mesh was chosen");
        assert!(scene.solver.rtol_from_accuracy);
        let accuracy = beam.accuracy;
        let rtol = scene.solver.rtol;
        let auto = run_beam(&scene, Method::GenAlpha, rtol, scene.solver.atol);
        let fine = refined(&scene, 2);
        let reference = run_beam(&fine, Method::GenAlpha, rtol / 10.0, 1e-12);
        let check = run_beam(&fine, Method::GenAlpha, rtol / 100.0, 1e-12);
        let (p, r, c) = (peak(&auto), peak(&reference), peak(&check));
        eprintln!(
            "{study}: {} elements, rtol {rtol:e}: peak {p:.6e}, reference {r:.6e} (settled to {:.1e}), error {:.1e}",
            chosen.elements,
            (r - c).abs() / c,
            (p - r).abs() / r
        );
        assert!(
            (r - c).abs() <= 0.1 * accuracy * c,
            "{study}: reference unsettled"
        );
        assert!(
            (p - r).abs() <= accuracy * r,
            "{study}: peak {p:e} against {r:e}"
        );
    }
}

/// What a scene names is kept: a given mesh is not replaced, and a given rtol is not either.
#[test]
fn what_the_scene_gives_is_kept() {
    let scene = common::load("bridge-d44.yaml");
    let beam = scene.beam().expect("beam");
    assert!(beam.discretisation.is_none());
    assert_eq!(beam.beam.elements, 10);
    assert!(!scene.solver.rtol_from_accuracy);
    assert_eq!(scene.solver.rtol, 1e-5);
}

/// A beam free at both ends has rigid-body modes and no static deflection to estimate from:
/// it keeps the default mesh and says why, rather than refining on round-off.
#[test]
fn a_free_beam_falls_back_to_the_default_mesh() {
    let scene = parse(
        "duration: 0.1\ntrack:\n  beam:\n    from: [0, 0]\n    to: [2, 0]\n    E: 2.1e11\n    G: 8.1e10\n    rho: 7850\n    A: 1e-3\n    Av: 8e-4\n    I: 1e-6\n    supports: {from: free, to: free}\nloads:\n  - {x: 1.0, fy: -100, until: 0.01}\n",
    );
    let d = scene
        .beam()
        .and_then(|b| b.discretisation.as_ref())
        .expect("chosen");
    assert_eq!(d.elements, 10);
    assert!(d.why.contains("rigid-body"), "{}", d.why);
}
