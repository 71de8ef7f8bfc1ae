//! `exact-modal`: a modal beam under moving forces integrated in closed form between the
//! axles' crossings of the mesh's nodes, verified
//! - against the time-stepped modal run of the same modes at rtol 10⁻¹⁰ (the same model, so
//!   only the integration differs),
//! - against the superposition of single-axle runs (the response is linear in the loads, and
//!   each run is exact whatever its steps),
//! - against Frýba's series, undamped and damped, in the Euler–Bernoulli limit (shear made
//!   stiff), as the time-stepped runs are,
//! - and refused, with the reason, where it does not apply.

use crate::common;

use common::{hslm_bridge, mid_headlines, parse, run_beam, superposition_error};
use rollbeam::ode::Method;
use rollbeam::run::beam::BeamRun;
use rollbeam::run::{self, Overrides};
use rollbeam::scene::Scene;

/// D44's bridge, shear made stiff, as a modal beam under `train`, for `duration` s after it.
fn fryba_bridge(train: &str, damping: &str, duration: f64) -> Scene {
    parse(&format!(
        "name: fryba-bridge
duration: {duration}
track:
  beam:
    from: [0.0, 0.0]
    to: [20.0, 0.0]
    E: 210.0e9
    G: 81.0e13
    rho: 7850
    A: 181.0e-4
    Av: 46.8e-4
    I: 43190.0e-8
    supports: {{from: pinned, to: roller}}
    model: modal
{damping}train: {train}
output:
  interval: 0.005
  probes: [{{name: mid, x: 10.0}}]
"
    ))
}

fn exact(scene: &Scene) -> BeamRun {
    let over = Overrides {
        method: Some(Method::ExactModal),
        ..Default::default()
    };
    run::run(scene, &over, false)
        .expect("the run completes")
        .beam()
        .expect("a beam scene")
}

/// HSLM-A3 at 103 m/s, where the time-stepped default run is 2.4·10⁻³ off in its lowest
/// deflection: at its default tolerance the exact run agrees with generalized-α at rtol
/// 10⁻¹⁰ (204 000 steps) to 10⁻⁵ of each headline (measured: 2·10⁻⁶ in w_min, 10⁻⁷ in the
/// acceleration; what is left is generalized-α's own), in a few hundred steps that take every
/// node crossing, none rejected; and the energy balance, its work and damping taken in closed
/// form, closes to round-off (measured 3.1·10⁻¹⁴).
#[test]
fn agrees_with_the_time_stepped_modal_run_at_rtol_1e_10() {
    let scene = hslm_bridge("{hslm: A3, speed: 103.0}", 0.5, "    model: modal\n");
    let closed = exact(&scene);
    let stepped = run_beam(&scene, Method::GenAlpha, 1e-10, 1e-15);
    let (a, b) = (mid_headlines(&closed), mid_headlines(&stepped));
    for (k, name) in ["w_min", "w_max", "amplitude after exit", "a_max"]
        .iter()
        .enumerate()
    {
        let off = (a[k] - b[k]).abs() / b[k].abs();
        eprintln!(
            "{name}: exact {:.9e}, genalpha 1e-10 {:.9e}, off {off:.1e}",
            a[k], b[k]
        );
        assert!(off < 1e-5, "{name}: {off:.2e}");
    }
    let stats = &closed.header.stats;
    assert!(stats.rejected == 0 && stats.steps < 2_000, "{stats:?}");
    let drift = closed.header.energy.max_rel_drift();
    assert!(drift < 1e-12, "drift {drift:.2e}");
}

/// The response is linear in the loads: three unequal axles are the sum of three runs with one
/// axle loaded each (same train, same clock), at every output time to 10⁻¹⁰ of the peak, though
/// each run chooses its own steps (exact between node crossings, they do not matter).
#[test]
fn a_train_is_the_superposition_of_its_axles() {
    let run = |load: &str| {
        exact(&fryba_bridge(
            &format!("{{axles: [0.0, 3.0, 14.0], load: {load}, speed: 50.0}}"),
            "    damping: {ratio: 0.02, modes: [1, 2]}\n",
            0.5,
        ))
    };
    let full = run("[1.0e5, 2.0e5, 1.5e5]");
    let parts: Vec<BeamRun> = [
        "[1.0e5, 0.0, 0.0]",
        "[0.0, 2.0e5, 0.0]",
        "[0.0, 0.0, 1.5e5]",
    ]
    .iter()
    .map(|load| run(load))
    .collect();
    let (worst, peak) = superposition_error(&full, &parts);
    eprintln!(
        "superposition off by {:.2e} of the peak {peak:.3e} m",
        worst / peak
    );
    assert!(worst <= 1e-10 * peak, "{worst:.3e} of {peak:.3e}");
}

/// D44's weight crossing at 17.6 m/s, undamped and damped by 2 % at modes 1 and 2, against
/// Frýba's series (301 terms) during the crossing and for a second after: within 0.5 % of the
/// peak, the tolerance the time-stepped runs are held to (rotary inertia and the mesh move the
/// response by less; the integration by nothing).
#[test]
fn follows_frybas_series_undamped_and_damped() {
    let series = common::fryba_bridge();
    let train = "{axles: [0.0], load: 14715.0, speed: 17.6}";
    for damped in [false, true] {
        let damping = if damped {
            "    damping: {ratio: 0.02, modes: [1, 2]}\n"
        } else {
            ""
        };
        let r = exact(&fryba_bridge(train, damping, 1.0));
        let (worst, peak) = match r.damping {
            Some(d) => common::midspan_against(&r, |t| {
                series.deflection_damped(10.0, t, 301, d.alpha, d.beta)
            }),
            None => common::midspan_against_fryba(&r),
        };
        eprintln!(
            "damped {damped}: off the series by {:.2e} of the peak",
            worst / peak
        );
        assert!(
            worst <= 5e-3 * peak,
            "damped {damped}: {worst:.3e} of {peak:.3e}"
        );
    }
}

/// Where the structure is not uncoupled oscillators under a force of time alone, the run is
/// refused before it starts, saying why: a disk, moving masses, a mesh model, a rigid curve.
#[test]
fn refused_where_it_does_not_apply() {
    let refused = |scene: &Scene, needle: &str| {
        let over = Overrides {
            method: Some(Method::ExactModal),
            ..Default::default()
        };
        match run::run(scene, &over, false) {
            Ok(_) => panic!("exact-modal ran where it does not apply ({needle})"),
            Err(e) => assert!(
                e.to_string().contains("exact-modal") && e.to_string().contains(needle),
                "{e}"
            ),
        }
    };
    refused(&common::load("bridge-d44.yaml"), "a disk");
    refused(
        &hslm_bridge(
            "{hslm: A1, speed: 90.0, model: moving-mass}",
            0.5,
            "    model: modal\n",
        ),
        "moving masses",
    );
    refused(
        &parse(
            &std::fs::read_to_string(common::studies_dir().join("hslm-15m.yaml"))
                .unwrap()
                .replace("    damping:", "    model: linear\n    damping:"),
        ),
        "a linear beam",
    );
    // Named by the scene, it is refused when the scene is planned: `check` says so too.
    let named = rollbeam::scene::SceneSpec::parse(
        &std::fs::read_to_string(common::studies_dir().join("hslm-15m.yaml"))
            .unwrap()
            .replace("    damping:", "    model: linear\n    damping:")
            .replace("train:", "solver: {method: exact-modal}\ntrain:"),
        "named",
        "named",
    )
    .expect("the scene reads");
    let e = rollbeam::plan::Planner::default()
        .plan(&named)
        .err()
        .expect("the plan refuses it");
    assert!(
        e.to_string().contains("`solver.method`") && e.to_string().contains("a linear beam"),
        "{e}"
    );
    let curve = rollbeam::scene::SceneSpec::parse(
        "duration: 1\ntrack:\n  curve:\n    parabola: {k: 1}\ndisk: {mass: 1, radius: 0.1, s0: -1}\nsolver: {method: exact-modal}\n",
        "curve",
        "curve",
    );
    let e = curve.err().expect("a rigid curve is refused");
    assert!(
        e.to_string().contains("exact-modal integrates structural"),
        "{e}"
    );
}

/// A lone axle far faster than any train (1000 and 10 000 m/s: the span in 15 and 1.5 ms)
/// over the HSLM bridge: its power on the modes changes as fast as it passes the highest
/// mode's half-wave, and it leaves every mode ringing; the energy budget, the work and the
/// damping's energy taken in closed form from the exact steps, closes to round-off (measured
/// 2.4·10⁻¹⁵ and 2.5·10⁻¹⁵; 10⁻¹² allows for the sums of a long run).
#[test]
fn a_fast_axle_s_energy_balance_closes() {
    for speed in [1000.0, 10_000.0] {
        let scene = hslm_bridge(
            &format!("{{axles: [0.0], load: 170.0e3, speed: {speed}}}"),
            0.5,
            "",
        );
        let drift = exact(&scene).header.energy.max_rel_drift();
        assert!(drift <= 1e-12, "{speed} m/s: drift {drift:.2e}");
    }
}

/// A sweep's cases share the assembled beam and the modal basis with the cases before them on
/// the same beam (the last eight of each kept, the bases per thread). A sweep over ten meshes,
/// more than are kept, in one process, against each case swept alone in a process of its own,
/// which finds nothing kept: every column of `sweep.csv` but the wall time is the same text.
#[test]
fn a_sweep_reports_what_each_case_does_alone() {
    let study = common::studies_dir().join("hslm-15m.yaml");
    let dir = std::env::temp_dir().join(format!("rollbeam-shared-{}", std::process::id()));
    let sweep = |out: &str, speeds: &str, elements: &str| -> Vec<String> {
        let folder = dir.join(out);
        let status = std::process::Command::new(env!("CARGO_BIN_EXE_rollbeam"))
            .arg("sweep")
            .arg(&study)
            .args(["--set", &format!("train.speed={speeds}")])
            .args(["--set", &format!("track.beam.elements={elements}")])
            .arg("--out")
            .arg(&folder)
            .output()
            .expect("rollbeam runs");
        assert!(status.status.success(), "{status:?}");
        let text = std::fs::read_to_string(folder.join("sweep.csv")).expect("sweep.csv");
        let mut lines = text.lines();
        let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
        let wall = header.iter().position(|c| *c == "wall_s").expect("wall_s");
        lines
            .map(|l| {
                let mut cells: Vec<&str> = l.split(',').collect();
                cells.remove(wall);
                cells.join(",")
            })
            .collect()
    };
    let elements = [4, 6, 8, 10, 12, 14, 16, 18, 20, 22];
    let list = elements.map(|e| e.to_string()).join(",");
    let together = sweep("together", "60,90", &list);
    let mut alone = Vec::new();
    for speed in ["60", "90"] {
        for e in elements {
            alone.extend(sweep(&format!("{speed}-{e}"), speed, &e.to_string()));
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(together.len(), 20);
    for (t, a) in together.iter().zip(&alone) {
        assert_eq!(t, a, "a case swept with the others and alone");
    }
    // Each case ran on its own mesh: no two meshes give the same numbers.
    let mut distinct: Vec<&str> = together
        .iter()
        .map(|l| l.split_once(',').expect("cells").1)
        .map(|l| l.split_once(',').expect("cells").1)
        .collect();
    distinct.sort_unstable();
    distinct.dedup();
    assert_eq!(distinct.len(), 20, "{together:#?}");
}
