//! Studies 2 and 3 (thesis 4.2): the clamped–pinned beam under a sudden load (B1–B3) and the
//! cantilever whose tip load is removed (C1–C3). Checked here: the energy budget, momentum of a
//! free beam, mesh convergence of the headline deflection, and snapshots of converged
//! headline numbers. The thesis' claims are checked with these numbers in REPORT.md.

use crate::common;

use common::converged;
use common::{changed, hann_mean, load, parse, run_beam, Set};
use rollbeam::ode::Method;
use rollbeam::run::beam::BeamRun;
use rollbeam::scene::Scene;

const STUDIES: [&str; 6] = [
    "beam-b1",
    "beam-b2",
    "beam-b3",
    "cantilever-c1",
    "cantilever-c2",
    "cantilever-c3",
];

/// A study scene run for `duration` at `rho_inf`, without shape snapshots, on the mesh given.
fn modified(
    name: &str,
    duration: f64,
    rho_inf: f64,
    elements: Option<usize>,
    order: Option<usize>,
) -> Scene {
    let mut changes = vec![
        Set::Number("duration", duration),
        Set::Number("solver.rho_inf", rho_inf),
        Set::LeftOut("output.shapes"),
    ];
    if let Some(e) = elements {
        changes.push(Set::Number("track.beam.elements", e as f64));
    }
    if let Some(p) = order {
        changes.push(Set::Number("track.beam.order", p as f64));
    }
    changed(&format!("{name}.yaml"), &changes)
}

/// Largest downward deflection at the first probe (under the load).
fn peak(r: &BeamRun) -> f64 {
    r.rows
        .iter()
        .map(|row| row.probes[0].w)
        .fold(f64::INFINITY, f64::min)
}

/// Kinetic + strain − work of the loads is constant for the undamped beam. With ρ∞ = 1 the
/// scheme conserves the energy of a linear system exactly, so what drifts comes from the
/// geometric nonlinearity and the Newton tolerance, both of which shrink with the step: the
/// drift stays below the tolerance itself at rtol 1e-6, and falls with rtol (measured slopes
/// 1.4–1.5 per decade, faster than the tol^{2/3} of the displacement error itself: C1–C3
/// drift 4.0–4.3·10⁻⁶ at 1e-5 and 1.4–1.6·10⁻⁷ at 1e-6, B1–B3 4.5–7.0·10⁻⁷ and 1.6–2.6·10⁻⁸).
/// The sudden load excites the beam's thickness-shear motion (√(GAv/ρI) ≈ 9·10⁵ rad/s), which a
/// tight tolerance must follow, so each study is checked over a window that keeps CI short:
/// the first 0.2 s of B1–B3 (three periods of the first mode), and C1–C3 with their tip load
/// taken off at 0.4 s instead of 1 s, to 0.5 s (full runs in REPORT.md). For the same reason the
/// tight tolerance is 1e-6: at 1e-7 the drifts are 4·10⁻¹⁰–10⁻⁸ and the test takes twice as
/// long.
#[test]
fn energy_balance_every_study() {
    let (tight_rtol, loose_rtol) = (1e-6, 1e-5);
    for name in STUDIES {
        let scene = if name.starts_with("beam") {
            modified(name, 0.2, 1.0, None, None)
        } else {
            released_early(name)
        };
        let tight = run_beam(&scene, Method::GenAlpha, tight_rtol, tight_rtol * 1e-4)
            .header
            .energy
            .max_rel_drift();
        let loose = run_beam(&scene, Method::GenAlpha, loose_rtol, loose_rtol * 1e-4)
            .header
            .energy
            .max_rel_drift();
        let slope = (loose / tight).log10() / (loose_rtol / tight_rtol).log10();
        eprintln!(
            "{name}: drift {loose:.2e} at rtol {loose_rtol:.0e}, {tight:.2e} at {tight_rtol:.0e}: slope {slope:.2}"
        );
        assert!(tight <= tight_rtol, "{name}: drift {tight:.2e}");
        assert!(
            slope > 0.4,
            "{name}: drift does not fall with rtol ({loose:.2e} → {tight:.2e})"
        );
    }
}

/// Cantilever study `name` undamped (ρ∞ = 1), its tip load taken off at 0.4 s instead of 1 s
/// (eight periods of the first mode), and run to 0.5 s.
fn released_early(name: &str) -> Scene {
    let text = common::study_text(&format!("{name}.yaml"));
    let early: Vec<&str> = (text.lines())
        .filter(|l| !l.trim_start().starts_with("shapes:"))
        .collect();
    let early = early
        .join("\n")
        .replace("until: 1.0}", "until: 0.4}")
        .replace("duration: 3.0", "duration: 0.5")
        .replace("rho_inf: 0.8", "rho_inf: 1.0");
    for given in ["until: 0.4}", "duration: 0.5", "rho_inf: 1.0"] {
        assert!(early.contains(given), "{name}: {given}");
    }
    parse(&early)
}

/// A free–free beam struck by a short transverse force F for τ: afterwards its linear momentum
/// is F τ and its angular momentum about the origin is F τ times the arm, and both stay. The
/// momenta are integrated from the finite-element velocity field (1e-6: the rtol of the run).
#[test]
fn free_beam_keeps_the_momentum_it_was_given() {
    let (force, tau, x) = (1.0e3, 1.0e-3, 3.0);
    let scene = parse(&format!(
        "duration: 0.05\ntrack:\n  beam:\n    from: [0, 0]\n    to: [4, 0]\n    E: 210e9\n    G: 81e9\n    rho: 7850\n    A: 59.8e-4\n    Av: 29.9e-4\n    I: 3620e-8\n    supports: {{from: free, to: free}}\n    elements: 8\n    order: 3\nloads:\n  - {{x: {x}, fy: {force}, from: 0, until: {tau}}}\nsolver:\n  rho_inf: 1.0\n"
    ));
    let r = run_beam(&scene, Method::GenAlpha, 1e-8, 1e-12);
    let b = &r.beam;
    let n = b.dim();
    let (q, v) = (&r.y_end[..n], &r.y_end[n..]);
    let sec = b.spec.section;
    let samples = 4000;
    let (mut px, mut py, mut lz) = (0.0, 0.0, 0.0);
    for k in 0..samples {
        let s = (k as f64 + 0.5) * b.length / samples as f64;
        let (d, vel) = (b.displacement_at(q, s), b.displacement_at(v, s));
        let dx = b.length / samples as f64;
        px += sec.rho_a * vel.u * dx;
        py += sec.rho_a * vel.w * dx;
        lz += (sec.rho_a * ((s + d.u) * vel.w - d.w * vel.u) + sec.rho_i * vel.phi) * dx;
    }
    let impulse = force * tau;
    eprintln!("p = ({px:.6e}, {py:.6e}), L = {lz:.6e}; impulse {impulse}");
    assert!(
        (py / impulse - 1.0).abs() < 1e-5 && px.abs() < 1e-5 * impulse,
        "p = ({px}, {py})"
    );
    // The force acts at x while the beam barely moves (w ≪ x), so L = F τ x to O(w/x).
    assert!(
        (lz / (impulse * x) - 1.0).abs() < 1e-4,
        "L = {lz} vs {}",
        impulse * x
    );
}

/// Mesh convergence of the headline quantity, the largest deflection under the load, with
/// linear elements (p = 1, reduced integration) against a p = 4 reference at the same time
/// settings (over the first 0.1 s, which holds the first peak): the error falls at a measured
/// order near 2, for B1, B2 and B3. (The cantilevers are left out: their first tip peak under a
/// sudden tip load carries percent-level ripples from the highest modes each mesh has, so it
/// moves with h without converging smoothly: 2, 4, 8 linear elements give −18.20, −19.07,
/// −19.20 mm and quadratic ones −19.39, −19.02, −19.04 mm.)
#[test]
fn mesh_convergence_of_the_peak_deflection() {
    for name in ["beam-b1", "beam-b2", "beam-b3"] {
        let duration = 0.1;
        let reference = peak(&run_beam(
            &modified(name, duration, 0.8, Some(16), Some(4)),
            Method::GenAlpha,
            1e-7,
            1e-12,
        ));
        let meshes = [4, 8, 16];
        let errors: Vec<f64> = meshes
            .iter()
            .map(|&e| {
                (peak(&run_beam(
                    &modified(name, duration, 0.8, Some(e), Some(1)),
                    Method::GenAlpha,
                    1e-7,
                    1e-12,
                )) / reference
                    - 1.0)
                    .abs()
            })
            .collect();
        let order = (errors[0] / errors[2]).log2() / 2.0;
        eprintln!("{name}: peak {reference:.6e}, p = 1 errors {errors:?}, order {order:.2}");
        assert!(order > 1.5, "{name}: errors {errors:?}");
    }
}

/// Mesh convergence of the cantilevers (C1–C3): the windowed mean tip deflection under the load
/// ([`hann_mean`]; the first mode makes some 30 periods in the window, so its vibration
/// averages out to a part in 10⁶) with linear elements (p = 1, reduced integration) on 4, 8
/// and 16 elements against p = 4 on 16, at the study's time settings. Linear Timoshenko
/// elements with reduced integration converge at order 2 in the displacements; the test asks
/// for a measured order above 1.8. The references, twice as long to run as their sequences,
/// are stored ([`make_converged_cantilever_means`]).
#[test]
fn mesh_convergence_of_the_cantilevers_mean_deflection() {
    for name in CANTILEVERS {
        let reference = converged::Number::stored(
            &format!("{name}-windowed-mean"),
            &format!("{name}.yaml"),
            "make_converged_cantilever_means",
        );
        let errors: Vec<f64> = [4, 8, 16]
            .iter()
            .map(|&e| (cantilever_mean(name, e, 1) / reference - 1.0).abs())
            .collect();
        let orders: Vec<f64> = errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
        eprintln!("{name}: mean tip deflection {reference:.6e}, p = 1 errors {errors:?}, orders {orders:?}");
        assert!(
            orders.iter().all(|&o| o > 1.8),
            "{name}: errors {errors:?}, orders {orders:?}"
        );
    }
}

const CANTILEVERS: [&str; 3] = ["cantilever-c1", "cantilever-c2", "cantilever-c3"];

/// Cantilever `name`'s windowed mean tip deflection over its loaded second, on `elements` of
/// degree `p`, at ρ∞ 0.8 and rtol 10⁻⁶.
fn cantilever_mean(name: &str, elements: usize, p: usize) -> f64 {
    let until = 1.0;
    let scene = modified(name, until, 0.8, Some(elements), Some(p));
    hann_mean(&run_beam(&scene, Method::GenAlpha, 1e-6, 1e-12), until)
}

/// Remakes the cantilevers' stored references:
/// `cargo test --release --test studies -- --ignored make_converged_cantilever_means`.
#[test]
#[ignore = "remakes stored references: forty seconds of a core"]
fn make_converged_cantilever_means() {
    for name in CANTILEVERS {
        converged::Number::store(
            &format!("{name}-windowed-mean"),
            &format!("{name}.yaml"),
            "degree 4 on 16 elements, generalized-α at ρ∞ 0.8, rtol 1e-6".to_string(),
            cantilever_mean(name, 16, 4),
        );
    }
}

/// Headline numbers of each study, rounded to the digits on which two runs agree: the study
/// settings (ρ∞ 0.8, rtol 1e-4) and a ten times tighter tolerance (three quarters of the
/// test's time, so stored: [`make_converged_tighter_peaks`]). Only two or three digits
/// survive: the largest deflection over 3 s of undamped motion is where several modes happen
/// to line up, and a small phase error moves it (when it occurs is not converged at all, so it
/// is not kept). A fourth agreeing digit is kept as three: where it occurs (C3) the two runs
/// peak at different times, so it agrees by chance and a change at round-off can take it away.
#[test]
fn snapshots_of_headline_numbers() {
    #[derive(serde::Serialize)]
    struct Headline {
        peak_w: String,
    }
    let round = |v: f64, d: usize| format!("{:.*e}", d - 1, v);
    for name in STUDIES {
        let (wa, ta) = deepest_row(&run_beam(
            &load(&format!("{name}.yaml")),
            Method::GenAlpha,
            1e-4,
            1e-9,
        ));
        let wb = converged::Number::stored(
            &tighter_peak_name(name),
            &format!("{name}.yaml"),
            "make_converged_tighter_peaks",
        );
        let digits = (2..=3)
            .rev()
            .find(|&d| round(wa, d) == round(wb, d))
            .expect("two runs agree to two digits");
        eprintln!("{name}: peak {wa:.6e} at {ta} s vs {wb:.6e}: {digits} digits");
        let h = Headline {
            peak_w: round(wa, digits),
        };
        insta::with_settings!({snapshot_path => "../snapshots", prepend_module_to_snapshot => false}, {
            insta::assert_yaml_snapshot!(name.to_string(), h);
        });
    }
}

/// The least deflection of the first probe over the output rows, and when.
fn deepest_row(r: &BeamRun) -> (f64, f64) {
    r.rows.iter().fold((0.0, 0.0), |(w, t), row| {
        if row.probes[0].w < w {
            (row.probes[0].w, row.t)
        } else {
            (w, t)
        }
    })
}

/// The name study `name`'s peak at a tenth of its rtol is stored by.
fn tighter_peak_name(name: &str) -> String {
    format!("{name}-peak-at-rtol-1e-5")
}

/// Remakes the studies' peaks at a tenth of their rtol:
/// `cargo test --release --test studies -- --ignored make_converged_tighter_peaks`.
#[test]
#[ignore = "remakes stored references: forty-five seconds of a core"]
fn make_converged_tighter_peaks() {
    for name in STUDIES {
        let scene = load(&format!("{name}.yaml"));
        let (w, _) = deepest_row(&run_beam(&scene, Method::GenAlpha, 1e-5, 1e-10));
        converged::Number::store(
            &tighter_peak_name(name),
            &format!("{name}.yaml"),
            "the study's settings at rtol 1e-5, atol 1e-10: its first probe's least deflection over the output rows".to_string(),
            w,
        );
    }
}

/// The support reactions of a dynamic run carry the beam's inertia as well as the load; the
/// undamped beam oscillates about its static equilibrium, so over the last two seconds of B1
/// (about 30 periods of the first mode) their mean is the static reaction (2 % allows for the
/// finite window and the slight numerical damping of ρ∞ = 0.8), and they swing about it with
/// the vibration the sudden load started.
#[test]
fn dynamic_reactions_average_to_the_static_ones() {
    use rollbeam::analysis::statics;
    let r = run_beam(&load("beam-b1.yaml"), Method::GenAlpha, 1e-4, 1e-9);
    let b = &r.beam;
    let loads: Vec<(f64, [f64; 2], f64)> =
        r.setup.loads.iter().map(|l| (l.x, l.force, l.mz)).collect();
    let mut f = vec![0.0; b.dim()];
    for &(x, force, mz) in &loads {
        b.add_point_load(x, force, mz, &mut f);
    }
    let q = statics::solve(b, &f).expect("converges").q;
    let [clamp, pin] = b.support_reactions(&q, &loads, None);
    let late: Vec<_> = r.rows.iter().filter(|row| row.t >= 1.0).collect();
    let mean = |f: &dyn Fn(&rollbeam::run::beam::BeamRow) -> f64| {
        late.iter().map(|row| f(row)).sum::<f64>() / late.len() as f64
    };
    for (name, dynamic, static_value) in [
        ("clamp R_Y", mean(&|row| row.reactions[0][1]), clamp[1]),
        ("pin R_Y", mean(&|row| row.reactions[1][1]), pin[1]),
        ("clamp M", mean(&|row| row.reactions[0][2]), clamp[2]),
    ] {
        eprintln!("{name}: mean {dynamic:.1} vs static {static_value:.1}");
        assert!(
            (dynamic / static_value - 1.0).abs() < 0.02,
            "{name}: mean {dynamic} vs static {static_value}"
        );
    }
    let swing = late
        .iter()
        .map(|row| row.reactions[1][1])
        .fold(0.0_f64, |m, v| m.max((v - pin[1]).abs()));
    assert!(
        swing > 0.5 * pin[1].abs(),
        "the pin reaction does not oscillate: {swing}"
    );
}

/// The axis's stretch is the beam's own, whichever way the span points: a soft 1 m cantilever
/// bent and pulled at its tip by sudden forces (3 kN along it, 50 N across), level and laid at
/// 30° with its loads turned with it (no weight), reports the same largest stretch to 10⁻¹⁰ of
/// it (the two runs differ by round-off alone). Read from the global displacements against the
/// undeformed spacing, which counts an inclined chord's turning as growth, the inclined one
/// came out 16 % low (0.0712 against 0.0850 m).
#[test]
fn the_axis_stretches_the_same_whichever_way_the_span_points() {
    let stretch = |degrees: f64| {
        let (sin, cos) = degrees.to_radians().sin_cos();
        let (along, across) = (3.0e3, 50.0);
        let (fx, fy) = (along * cos - across * sin, along * sin + across * cos);
        let scene = parse(&format!(
            "name: turned\nduration: 0.03\ntrack:\n  beam:\n    from: [0.0, 0.0]\n    to: [{cos:?}, {sin:?}]\n    E: 7.0e6\n    G: 2.3e6\n    rho: 1100\n    A: 0.01\n    Av: 0.0083\n    I: 8.3e-6\n    supports: {{from: clamped, to: free}}\nloads:\n  - {{x: 1.0, fx: {fx:?}, fy: {fy:?}}}\noutput:\n  probes: [{{name: tip, x: 1.0}}]\n"
        ));
        common::at_defaults(&scene).envelope.stretch_max
    };
    let (level, turned) = (stretch(0.0), stretch(30.0));
    assert!(
        level > 0.0 && (turned - level).abs() <= 1e-10 * level,
        "stretch {turned:e} m at 30°, {level:e} m level"
    );
}

/// A soft 1 m cantilever pulled at its tip by a sudden axial force: EA = 7·10⁴ N, so 3·10⁴ N
/// stretches the axis by 0.43 statically and 0.86 at the wave's first return, and 3·10³ N by
/// 0.086 at most. Past a mean stretch of a tenth the run says its numbers are the model's, as
/// the beam's law is linear in its strains (a neo-Hookean solid's stress in tension lies 9 %
/// below it at a tenth); below it says nothing. What is compared is the largest stretch the
/// envelope measured against the threshold, on both sides.
#[test]
fn a_beam_stretched_past_small_strains_says_so() {
    let pulled = |force: f64| {
        let scene = parse(&format!(
            "name: pulled\nduration: 0.03\ntrack:\n  beam:\n    from: [0.0, 0.0]\n    to: [1.0, 0.0]\n    E: 7.0e6\n    G: 2.3e6\n    rho: 1100\n    A: 0.01\n    Av: 0.0083\n    I: 8.3e-6\n    supports: {{from: clamped, to: free}}\nloads:\n  - {{x: 1.0, fx: {force}}}\noutput:\n  probes: [{{name: tip, x: 1.0}}]\n"
        ));
        let run = common::at_defaults(&scene);
        let says = run
            .warnings()
            .iter()
            .any(|w| w.contains("times its length"));
        (run.envelope.stretch_max, says)
    };
    let (far, says_far) = pulled(3.0e4);
    let (near, says_near) = pulled(3.0e3);
    assert!(far > 0.4 && says_far, "stretch {far} m, warned: {says_far}");
    assert!(
        near < 0.1 && !says_near,
        "stretch {near} m, warned: {says_near}"
    );
}
