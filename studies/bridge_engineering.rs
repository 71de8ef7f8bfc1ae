//! The bridge engineer's workflow, verified: Rayleigh damping on every beam model,
//! the beam's own weight, and the deck acceleration.
//!
//! - The damped moving force on the bridge (Euler–Bernoulli limit) against Frýba's series with
//!   modal damping, on the exact, linear and modal beams; the energy damping takes booked so
//!   that the balance closes.
//! - The damping ratio recovered from the logarithmic decrement of free vibration of each
//!   anchor mode.
//! - A force crossing two continuous spans, and one dropping off a cantilever's tip, against
//!   the series of their own modes.
//! - The static sag under self-weight against 5qL⁴/(384EI) + qL²/(8GAv).
//! - The recorded acceleration against the second derivative of the recorded deflection.

use crate::common;

use common::{at_defaults, changed, run_beam, Set};
use rollbeam::analysis::statics;
use rollbeam::beam::Beam;
use rollbeam::ode::Method;
use rollbeam::run::beam::{BeamRow, BeamRun};

fn probe(r: &BeamRun, name: &str) -> usize {
    r.setup
        .probes
        .iter()
        .position(|p| p.name == name)
        .expect("a probe of that name")
}

/// D44's moving force with shear made stiff, damped by 2 % at modes 1 and 2, against the
/// damped modal series, during the crossing and for 2 s after it: within 0.5 % of the peak
/// (the tolerance of the undamped comparison: rotary inertia, the ±5 cm patch and rtol 1e-6
/// move the response by far less). The damping the run anchors on the mesh's modes gives the
/// series its α and β, so what is compared is the response to the same damped system. The
/// energy balance closes with what damping took booked (drift below 1e-4 of the energy, while
/// the damping took over a hundred times that), and without the booking it would not.
#[test]
fn damped_moving_force_matches_the_damped_series_on_every_model() {
    for model in ["exact", "linear", "modal"] {
        let scene = changed(
            "bridge-d44.yaml",
            &[
                common::FRYBA_BRIDGE.as_slice(),
                &[
                    Set::Name("track.beam.model", model),
                    Set::Number("track.beam.damping.ratio", 0.02),
                    Set::Number("duration", 3.0),
                ],
            ]
            .concat(),
        );
        let r = run_beam(&scene, Method::GenAlpha, 1e-6, 1e-10);
        let damping = r.damping.expect("the run is damped");
        let series = common::fryba_bridge();
        let (worst, peak) = common::midspan_against(&r, |t| {
            series.deflection_damped(10.0, t, 301, damping.alpha, damping.beta)
        });
        assert!(peak > 0.0, "{model}: the series is {peak}");
        let last = r.rows.last().unwrap();
        let scale = r.rows.iter().map(|row| row.work.abs()).fold(0.0, f64::max);
        let drift = r.header.energy.max_rel_drift();
        eprintln!(
            "{model}: off the series by {:.2e} of the peak; dissipated {:.3e} J of {scale:.3e} J of work, drift {drift:.2e}",
            worst / peak,
            last.dissipated
        );
        assert!(
            worst <= 5e-3 * peak,
            "{model}: {worst:.3e} against {peak:.3e}"
        );
        assert!(drift < 1e-4, "{model}: drift {drift:.3e}");
        assert!(
            last.dissipated > 100.0 * drift * scale,
            "{model}: damping took {:.3e} J",
            last.dissipated
        );
    }
}

/// A mode of a series: its wavenumber β and its shape.
type Mode = (f64, Box<dyn Fn(f64) -> f64>);

/// Two equal spans' Euler–Bernoulli modes, span L (pinned, bearing at L, roller at 2L): the
/// antisymmetric sin(nπx/L) and the symmetric ones, each span clamped at the bearing and
/// pinned at its end, φ(ξ) = cosh βξ − cos βξ − σ (sinh βξ − sin βξ) with ξ the distance from
/// the bearing, tan βL = tanh βL and σ = (cosh βL − cos βL)/(sinh βL − sin βL). Each `count`
/// of a family, as (β, the shape at x); the hyperbolic terms written as exponentials of
/// β(ξ − L) and −βξ, which stay bounded where cosh and sinh would cancel.
fn two_span_modes(span: f64, count: usize) -> Vec<Mode> {
    let pi = std::f64::consts::PI;
    let mut modes: Vec<Mode> = Vec::new();
    for n in 1..=count {
        let beta = n as f64 * pi / span;
        modes.push((beta, Box::new(move |x: f64| (beta * x).sin())));
    }
    for k in 1..=count {
        let mut bl = (4 * k + 1) as f64 * pi / 4.0;
        for _ in 0..50 {
            bl -= (bl.tan() - bl.tanh()) / (1.0 / bl.cos().powi(2) - 1.0 / bl.cosh().powi(2));
        }
        let (beta, e) = (bl / span, (-bl).exp());
        // 2 (sinh βL − sin βL) e^{−βL}, and σ and (1 − σ) e^{βL} / 2 over it.
        let scaled = 1.0 - e * e - 2.0 * bl.sin() * e;
        let sigma = (1.0 + e * e - 2.0 * bl.cos() * e) / scaled;
        let rising = (bl.cos() - bl.sin() - e) / scaled;
        modes.push((
            beta,
            Box::new(move |x: f64| {
                let xi = beta * (x - span).abs();
                rising * (xi - bl).exp() + 0.5 * (1.0 + sigma) * (-xi).exp() - xi.cos()
                    + sigma * xi.sin()
            }),
        ));
    }
    modes
}

/// A force crossing two continuous spans of D44's section (20 m each over a bearing; shear and
/// rotary inertia made negligible, so that the beam is Euler–Bernoulli's) at 16 m/s, at the defaults,
/// against the series of the two spans' own modes (20 antisymmetric and 20 symmetric, each
/// mode's equation integrated by the classical Runge–Kutta method at 50 µs): both midspans'
/// deflections at every output time, over the crossing and a second of free vibration,
/// within the accuracy asked of the peak (the series' truncation is below 4·10⁻⁵ of it).
/// Measured: 4.2·10⁻⁵; with the symmetric modes' σ sin βξ term of the wrong sign, 0.43.
#[test]
fn a_force_over_two_spans_matches_the_series_of_their_modes() {
    follows_its_modes(
        "supports: {from: pinned, to: roller, intermediate: [20.0]}",
        40.0,
        &two_span_modes(20.0, 20),
        &[10.0, 30.0],
        5e-5,
    );
}

/// D44's section as an Euler–Bernoulli beam: the area and the shear area raised a
/// thousandfold at the same mass per length, so that the shear (3.7·10⁻⁶ of the 10 m
/// cantilever's tip deflection) and the sections' rotary inertia are gone. Made stiff by G
/// instead (× 10⁴), the plan measured the exact beam's static deflection 5·10⁻⁴ off the
/// linear one where it is 3·10⁻⁵, and stepped the exact beam.
const EULER_BERNOULLI_D44: &str =
    "    E: 210.0e9\n    G: 81.0e9\n    rho: 7.85\n    A: 18.1\n    Av: 9.05\n    I: 43190.0e-8\n";

/// A force crossing a 10 m cantilever of D44's section from its clamped end and dropping off
/// its free tip, at the defaults, against the series of the cantilever's own 30 modes (each
/// integrated by Runge–Kutta at 25 µs, the drop on a step's end): the tip's and midspan's
/// deflections at every output time, over the crossing and a second of free vibration after
/// the drop, within the accuracy of the peak. The drop sets every mode swinging by its whole
/// static part about zero; the plan keeps the modes that carry it, the static correction of
/// the others leaving with the force. Measured: 7.5·10⁻⁴ on the plan's modal beam (8.8·10⁻⁵ on
/// the exact beam, whose time steps cost 500 times as much).
#[test]
fn a_force_dropping_off_a_cantilever_matches_the_series_of_its_modes() {
    follows_its_modes(
        "supports: {from: clamped, to: free}",
        10.0,
        &cantilever_modes(10.0, 30),
        &[5.0, 10.0],
        2.5e-5,
    );
}

/// D44's weight (1500 kg) crossing a beam of `length` of D44's section made Euler–Bernoulli's,
/// on `supports`, at 16 m/s and the defaults, against the series of `modes` integrated at step
/// `h`: the deflection at each of `probes` at every output time, over the crossing and a second
/// of free vibration, within the accuracy asked (10⁻³) of the series' peak.
fn follows_its_modes(supports: &str, length: f64, modes: &[Mode], probes: &[f64], h: f64) {
    let (p, v) = (1500.0 * 9.81, 16.0);
    let named: Vec<String> = (probes.iter().enumerate())
        .map(|(k, x)| format!("{{name: p{k}, x: {x}}}"))
        .collect();
    let scene = common::parse(&format!(
        "name: series\nduration: 1.0\ntrack:\n  beam:\n    from: [0.0, 0.0]\n    to: [{length}, 0.0]\n{EULER_BERNOULLI_D44}    {supports}\ntrain: {{axles: [0.0], load: {p}, speed: {v}}}\noutput:\n  probes: [{}]\n",
        named.join(", ")
    ));
    let r = common::at_defaults(&scene);
    let section = (210.0e9 * 43190.0e-8, 7850.0 * 181.0e-4);
    let series = series_of_modes(modes, length, section, (p, v), probes, h, r.header.t_end);
    let (worst, peak) = against_series(&r, &series);
    eprintln!(
        "{supports}: off the series of its modes by {:.2e} of the peak {peak:.4e} m",
        worst / peak
    );
    assert!(
        worst < 1e-3 * peak,
        "{supports}: {worst:.3e} against the peak {peak:.3e}"
    );
}

/// A cantilever's Euler–Bernoulli modes (clamped at x = 0, free at L): φ = cosh βx − cos βx
/// − σ (sinh βx − sin βx), cos βL cosh βL = −1, σ = (sinh βL − sin βL)/(cosh βL + cos βL),
/// the hyperbolic terms written as bounded exponentials; `count` of them as (β, the shape).
fn cantilever_modes(length: f64, count: usize) -> Vec<Mode> {
    let pi = std::f64::consts::PI;
    (1..=count)
        .map(|k| {
            let mut bl = (2 * k - 1) as f64 * pi / 2.0;
            for _ in 0..50 {
                let f = bl.cos() * bl.cosh() + 1.0;
                let df = bl.cos() * bl.sinh() - bl.sin() * bl.cosh();
                bl -= f / df;
            }
            let (beta, e) = (bl / length, (-bl).exp());
            // 2 (cosh βL + cos βL) e^{−βL}, and σ and (1 − σ) e^{βL} / 2 over it.
            let scaled = 1.0 + e * e + 2.0 * bl.cos() * e;
            let sigma = (1.0 - e * e - 2.0 * bl.sin() * e) / scaled;
            let rising = (e + bl.cos() + bl.sin()) / scaled;
            let shape: Box<dyn Fn(f64) -> f64> = Box::new(move |x: f64| {
                let bx = beta * x;
                rising * (bx - bl).exp() + 0.5 * (1.0 + sigma) * (-bx).exp() - bx.cos()
                    + sigma * bx.sin()
            });
            (beta, shape)
        })
        .collect()
}

/// The series of `modes` (β, shape) over [0, length] of a beam of EI and mass per length μ
/// under a force p moving at v from x = 0 until it leaves at `length`: each mode's equation by
/// the classical Runge–Kutta method at step `h` up to `until`, the deflection read at each of
/// `xs` every step as (t, w at each).
#[allow(clippy::too_many_arguments)]
fn series_of_modes(
    modes: &[Mode],
    length: f64,
    (ei, mu): (f64, f64),
    (p, v): (f64, f64),
    xs: &[f64],
    h: f64,
    until: f64,
) -> Vec<(f64, Vec<f64>)> {
    // ∫ φ² over the beam by Simpson's rule on 16000 intervals.
    let norms: Vec<f64> = modes
        .iter()
        .map(|(_, phi)| {
            let n = 16000;
            let step = length / n as f64;
            let weight = |i: usize| match i {
                0 => 1.0,
                i if i == n => 1.0,
                i if i % 2 == 1 => 4.0,
                _ => 2.0,
            };
            (0..=n)
                .map(|i| weight(i) * phi(i as f64 * step).powi(2))
                .sum::<f64>()
                * step
                / 3.0
        })
        .collect();
    let omega2: Vec<f64> = modes.iter().map(|(b, _)| b.powi(4) * ei / mu).collect();
    let m = modes.len();
    let rhs = |t: f64, s: &[f64]| -> Vec<f64> {
        let x = v * t;
        let mut d = vec![0.0; 2 * m];
        d[..m].copy_from_slice(&s[m..]);
        for k in 0..m {
            let force = if (0.0..=length).contains(&x) {
                -p * (modes[k].1)(x) / (mu * norms[k])
            } else {
                0.0
            };
            d[m + k] = force - omega2[k] * s[k];
        }
        d
    };
    let mut out = Vec::new();
    common::runge_kutta(rhs, 2 * m, h, until, |t, s, _| {
        let at = |x: f64| (0..m).map(|k| (modes[k].1)(x) * s[k]).sum::<f64>();
        out.push((t, xs.iter().map(|&x| at(x)).collect()));
    });
    out
}

/// The largest difference between the run's probes and a series at its output times (the
/// series interpolated linearly between its steps), and the series' largest |w|.
fn against_series(r: &BeamRun, series: &[(f64, Vec<f64>)]) -> (f64, f64) {
    let interpolate = |t: f64, k: usize| {
        let i = series
            .partition_point(|p| p.0 < t)
            .clamp(1, series.len() - 1);
        let (a, b) = (&series[i - 1], &series[i]);
        a.1[k] + (b.1[k] - a.1[k]) * (t - a.0) / (b.0 - a.0)
    };
    let probes = series[0].1.len();
    let peak = series
        .iter()
        .fold(0.0_f64, |m, q| q.1.iter().fold(m, |m, w| m.max(w.abs())));
    let worst = r.rows.iter().fold(0.0_f64, |m, row| {
        (0..probes).fold(m, |m, k| {
            m.max((row.probes[k].w - interpolate(row.t, k)).abs())
        })
    });
    (worst, peak)
}

/// Peaks of a sampled signal, each refined by the parabola through it and its neighbours.
fn peaks(t: &[f64], y: &[f64]) -> Vec<(f64, f64)> {
    (1..y.len() - 1)
        .filter(|&i| y[i] > y[i - 1] && y[i] >= y[i + 1] && y[i] > 0.0)
        .map(|i| {
            let (a, b, c) = (y[i - 1], y[i], y[i + 1]);
            let d = 0.5 * (a - c) / (a - 2.0 * b + c);
            (t[i] + d * (t[i + 1] - t[i]), b - 0.25 * (a - c) * d)
        })
        .collect()
}

/// Free vibration of the bridge (no disk) after a load is taken off at t = 0.05 s: a force at
/// midspan sets the symmetric modes swinging, a pair of opposite forces at the quarter points
/// the antisymmetric ones. The higher modes of each family are damped more (Rayleigh: ζ grows
/// with ω past the anchors) and die out first; the logarithmic decrement of the rest,
/// δ = ln(A_n/A_{n+k})/k and ζ = δ/√(4π² + δ²), recovers the 2 % at each anchor mode within 1 %.
#[test]
fn damping_ratio_from_the_logarithmic_decrement_of_each_anchor_mode() {
    let text = std::fs::read_to_string(common::studies_dir().join("bridge-d44.yaml")).unwrap();
    for (mode, loads, probe_x, period) in [
        (1, "  - {x: 10.0, fy: -1.0e5, until: 0.05}\n", 10.0, 0.32),
        (
            2,
            "  - {x: 5.0, fy: -1.0e5, until: 0.05}\n  - {x: 15.0, fy: 1.0e5, until: 0.05}\n",
            5.0,
            0.081,
        ),
    ] {
        let body: String = text
            .lines()
            .take_while(|l| !l.starts_with("disk:"))
            .map(|l| format!("{l}\n"))
            .collect::<String>()
            .replace("duration: 3.0", &format!("duration: {}", 12.0 * period))
            .replace(
                "    model: exact",
                "    model: linear\n    damping: {ratio: 0.02, modes: [1, 2]}",
            );
        let scene = common::parse(&format!(
            "{body}loads:\n{loads}solver: {{method: genalpha, rho_inf: 1.0}}\noutput:\n  interval: {}\n  probes: [{{name: p, x: {probe_x}}}]\n",
            period / 200.0
        ));
        let r = run_beam(&scene, Method::GenAlpha, 1e-8, 1e-12);
        let (t, w): (Vec<f64>, Vec<f64>) = r
            .rows
            .iter()
            .filter(|row| row.t > 0.05 + 4.0 * period)
            .map(|row| (row.t, row.probes[0].w))
            .unzip();
        let p = peaks(&t, &w);
        let k = p.len() - 1;
        let delta = (p[0].1 / p[k].1).ln() / k as f64;
        let zeta = delta / (4.0 * std::f64::consts::PI.powi(2) + delta * delta).sqrt();
        eprintln!("mode {mode}: {} peaks, ζ = {zeta:.5}", p.len());
        assert!(k >= 4, "mode {mode}: {} peaks", p.len());
        assert!(
            (zeta - 0.02).abs() <= 0.01 * 0.02,
            "mode {mode}: ζ = {zeta:.5}"
        );
    }
}

/// D44's bridge (HEB 360, 20 m, simply supported) under its own weight q = ρ A g: the
/// midspan sag 5qL⁴/(384EI) + qL²/(8 G Av), bending and shear.
fn sag_of_the_bridge() -> f64 {
    let (l, e, g, rho, a, av, i): (f64, f64, f64, f64, f64, f64, f64) =
        (20.0, 210.0e9, 81.0e9, 7850.0, 181.0e-4, 46.8e-4, 43190.0e-8);
    let q = rho * a * 9.81;
    5.0 * q * l.powi(4) / (384.0 * e * i) + q * l * l / (8.0 * g * av)
}

/// The bridge under its own weight, statically: a simply supported beam under q = ρ A g sags
/// 5qL⁴/(384EI) + qL²/(8 G Av) at midspan (bending and shear). Degree-4 elements hold the
/// quartic bending line exactly, so the linear beam meets it to round-off (1e-9); the exact
/// beam adds what its geometry does, second order in the slopes (w/L ~ 2e-3): measured
/// 1.3e-5, held to 5e-5.
#[test]
fn self_weight_sag_matches_the_closed_form() {
    let closed = sag_of_the_bridge();
    for (model, tolerance) in [("linear", 1e-9), ("exact", 5e-5)] {
        let scene = changed(
            "bridge-d44.yaml",
            &[
                Set::Name("track.beam.model", model),
                Set::Name("track.beam.self_weight", "true"),
            ],
        );
        let spec = scene.beam().unwrap().beam.clone();
        let beam = Beam::new(spec);
        let mut f = vec![0.0; beam.dim()];
        beam.add_weight(&mut f);
        let sol = statics::solve(&beam, &f).expect("the bridge carries its weight");
        let sag = -beam.displacement_at(&sol.q, 10.0).w;
        eprintln!("{model}: sag {sag:.9e} m against {closed:.9e} m");
        assert!(
            (sag - closed).abs() <= tolerance * closed,
            "{model}: {sag:.9e} against {closed:.9e}"
        );
    }
}

/// The bridge dropped under its own weight from rest, undeformed, with everything else left to
/// the plan: the plan reads the weight as the load it is. The response size that sets atol is
/// the static sag under it, the closed form 5qL⁴/(384EI) + qL²/(8 G Av) to 1e-3 (a linear
/// solve on degree-4 elements, which hold it to round-off); the mesh is chosen from the modes
/// the weight excites;
/// and the run lands within the accuracy asked, 1e-3, of the largest midspan deflection of
/// the exact beam on 20 elements at rtol 1e-9 (which rtol 1e-10 moves by 5e-7). Measured:
/// 6 elements, a modal beam of 6 modes, 4.2e-4 off. (Before the weight counted, the plan fell
/// back to its default mesh, with the reason that the loads do not deflect the probes.)
#[test]
fn the_plan_counts_the_beams_own_weight() {
    let closed = sag_of_the_bridge();
    let text = |beam_extra: &str| {
        format!(
            "name: dropped
duration: 0.5
track:
  beam:
    from: [0.0, 0.0]
    to: [20.0, 0.0]
    E: 210.0e9
    G: 81.0e9
    rho: 7850
    A: 181.0e-4
    Av: 46.8e-4
    I: 43190.0e-8
    supports: {{from: pinned, to: roller}}
    self_weight: true
{beam_extra}output:
  probes: [{{name: mid, x: 10.0}}]
"
        )
    };
    let planned = common::parse(&text(""));
    let b = planned.beam().expect("a beam scene");
    let response = b.response.expect("the weight deflects the probe");
    let d = b.discretisation.as_ref().expect("the mesh was chosen");
    eprintln!(
        "planned: response {response:.6e} m against the sag {closed:.6e} m; {} elements, {:?}; {}",
        d.elements, b.beam.model, d.why
    );
    assert!((response - closed).abs() <= 1e-3 * closed, "{response:e}");
    assert!(d.excited_modes > 0, "{}", d.why);
    let deepest = |r: &BeamRun| {
        r.rows
            .iter()
            .map(|row| -row.probes[0].w)
            .fold(0.0, f64::max)
    };
    let auto = rollbeam::run::run(&planned, &Default::default(), false)
        .expect("runs")
        .beam()
        .expect("a beam");
    let reference = common::parse(&text("    model: exact\n    elements: 20\n"));
    let converged = run_beam(&reference, Method::GenAlpha, 1e-9, 1e-13);
    let off = (deepest(&auto) - deepest(&converged)).abs() / deepest(&converged);
    eprintln!(
        "largest deflection {:.6e} m against {:.6e} m: {off:.1e}",
        deepest(&auto),
        deepest(&converged)
    );
    assert!(off <= 1e-3, "{off:.2e}");
}

/// The recorded acceleration is the second time derivative of the recorded deflection where
/// nothing is filtered out: on a modal beam whose modes all lie below the cutoff, the central
/// difference of w over the output grid (error h² w''''/12, a few 1e-4 of the peak at the
/// grid of D44 / 4) matches `<probe>.a` within 1 % of the largest acceleration.
#[test]
fn recorded_acceleration_is_the_deflection_differentiated_twice() {
    let scene = changed(
        "bridge-d44.yaml",
        &[
            Set::Name("track.beam.model", "modal"),
            Set::Number("track.beam.modes", 3.0),
            Set::Number("output.acceleration_cutoff_hz", 1000.0),
            Set::Number("output.interval", 0.00125),
            Set::LeftOut("output.shapes"),
        ],
    );
    let r = run_beam(&scene, Method::GenAlpha, 1e-9, 1e-13);
    let k = probe(&r, "mid");
    let rows = &r.rows;
    let exit = r.left_track_t.expect("the disk leaves");
    let largest = rows
        .iter()
        .map(|row| row.accelerations[k].abs())
        .fold(0.0, f64::max);
    let worst = rows
        .windows(3)
        .filter(|w| w[0].t > exit + 0.01)
        .map(|w| {
            let h = w[1].t - w[0].t;
            let second = (w[2].probes[k].w - 2.0 * w[1].probes[k].w + w[0].probes[k].w) / (h * h);
            (second - w[1].accelerations[k]).abs()
        })
        .fold(0.0, f64::max);
    eprintln!(
        "acceleration off the differenced deflection by {:.2e} of {largest:.3e}",
        worst / largest
    );
    assert!(worst <= 1e-2 * largest, "{worst:.3e} against {largest:.3e}");
}

/// The bridge (D44's beam, of the given model) carrying a train instead of the disk, as scene
/// text: `train` is the train block's body.
fn bridge_with_train(model: &str, train: &str, duration: f64) -> rollbeam::scene::Scene {
    let body = common::d44_bridge_text(model, duration);
    common::parse(&format!(
        "{body}train:\n{train}output:\n  interval: 0.005\n  probes: [{{name: mid, x: 10.0}}]\n"
    ))
}

/// On the linear beam the response is linear in the loads, so a train of three unequal axles
/// is the sum of three runs with one axle each, at the same fixed steps: equal to round-off
/// (1e-9 of the peak; the fixed step makes every run take the same time grid, and Newton on a
/// linear system is exact after one iteration).
#[test]
fn a_train_is_the_superposition_of_its_axles() {
    let run = |train: &str| {
        let scene = bridge_with_train("linear", train, 0.5);
        let over = rollbeam::run::Overrides {
            method: Some(Method::GenAlpha),
            fixed_step: Some(1e-3),
            rtol: Some(1e-10),
            atol: Some(1e-14),
            ..Default::default()
        };
        rollbeam::run::run(&scene, &over, false)
            .expect("runs")
            .beam()
            .expect("a beam")
    };
    let full = run("  axles: [0.0, 3.0, 14.0]\n  load: [1.0e5, 2.0e5, 1.5e5]\n  speed: 50.0\n");
    // Each axle alone, the others weightless: the same train length, so the same clock and
    // the same end of the run.
    let parts: Vec<BeamRun> = [
        "[1.0e5, 0.0, 0.0]",
        "[0.0, 2.0e5, 0.0]",
        "[0.0, 0.0, 1.5e5]",
    ]
    .iter()
    .map(|load| {
        run(&format!(
            "  axles: [0.0, 3.0, 14.0]\n  load: {load}\n  speed: 50.0\n"
        ))
    })
    .collect();
    let (worst, peak) = common::superposition_error(&full, &parts);
    eprintln!(
        "superposition off by {:.2e} of the peak {peak:.3e} m",
        worst / peak
    );
    assert!(worst <= 1e-9 * peak, "{worst:.3e} of {peak:.3e}");
}

/// Twenty equal loads D = 18 m apart crossing the undamped bridge: the free vibration they
/// leave, against speed, peaks where the loads come once per period of the first mode,
/// v = f1 D (f1 from the beam's own modes), and vanishes where a single load leaves none,
/// v = 2 f1 L/3 (Frýba §1.3: the first mode's free vibration after one load is
/// ∝ |cos(π/(2α))|, α = v/(2 f1 L)); both within the sweep's resolution of 0.5 m/s.
#[test]
fn resonance_and_cancellation_speeds_of_a_train() {
    let axles: Vec<String> = (0..20).map(|k| format!("{}", 18.0 * k as f64)).collect();
    let residual = |v: f64| {
        let train = format!(
            "  axles: [{}]\n  load: 1.0e5\n  speed: {v}\n",
            axles.join(", ")
        );
        let scene = bridge_with_train("modal\n    modes: 8", &train, 1.0);
        let gone = (18.0 * 19.0 + 20.0) / v;
        let r = run_beam(&scene, Method::GenAlpha, 1e-6, 1e-10);
        r.rows
            .iter()
            .filter(|row| row.t > gone)
            .map(|row| row.probes[0].w.abs())
            .fold(0.0, f64::max)
    };
    let beam = Beam::new(
        bridge_with_train("linear", "  hslm: A1\n  speed: 50.0\n", 1.0)
            .beam()
            .unwrap()
            .beam
            .clone(),
    );
    let f1 = rollbeam::analysis::modes::modes(&beam, 1).unwrap().omega[0] / std::f64::consts::TAU;
    // Two windows of 0.5 m/s around the speeds sought.
    let speeds: Vec<f64> = (0..=14)
        .map(|k| 38.0 + 0.5 * k as f64)
        .chain((0..=14).map(|k| 52.0 + 0.5 * k as f64))
        .collect();
    let amplitudes: Vec<f64> = speeds.iter().map(|&v| residual(v)).collect();
    let (peak, _) = speeds
        .iter()
        .zip(&amplitudes)
        .filter(|(v, _)| **v > 50.0)
        .fold(
            (0.0, 0.0),
            |best, (v, a)| if *a > best.1 { (*v, *a) } else { best },
        );
    let (quiet, _) = speeds
        .iter()
        .zip(&amplitudes)
        .filter(|(v, _)| **v < 50.0)
        .fold((0.0, f64::INFINITY), |best, (v, a)| {
            if *a < best.1 {
                (*v, *a)
            } else {
                best
            }
        });
    let (resonant, cancelling) = (f1 * 18.0, 2.0 * f1 * 20.0 / 3.0);
    eprintln!("f1 {f1:.4} Hz: peak at {peak} m/s (f1 D = {resonant:.2}), least at {quiet} m/s (2 f1 L/3 = {cancelling:.2})");
    assert!(
        (peak - resonant).abs() <= 0.5,
        "peak at {peak}, f1 D = {resonant}"
    );
    assert!(
        (quiet - cancelling).abs() <= 0.5,
        "least at {quiet}, 2 f1 L/3 = {cancelling}"
    );
}

/// The moving-mass train is checked against the moving-mass disk: one axle of load m g
/// riding on D44's exact beam (the train's axle inertia, `beam/dynamics.rs`) and the disk of
/// mass m under the `moving-mass` coupling (`coupling/moving_mass.rs`) on the same patch, two
/// codings of one system. While both ride on the beam (until the axle's patch reaches the far
/// support; then the disk is stopped at L and the axle rolls on over the approach) the midspan
/// deflection agrees to 2e-5 of its peak: each run is held to rtol 1e-8, whose error is some
/// 1e-6 of the peak, and the steps differ. The train's energy balance closes to 1e-6.
/// (The support reactions are not compared: they hold the whole beam's inertia M a, whose
/// stiff modes the interpolated output state excites; the disk's own reaction moves by 5 %
/// between rtol 1e-8 and 1e-9.)
#[test]
fn a_moving_mass_axle_is_the_moving_mass_disk() {
    let (mass, speed, depth) = (1500.0, 17.6, 0.36);
    let half = rollbeam::coupling::patch::dispersed_half_width(depth);
    let disk = changed(
        "bridge-d44.yaml",
        &[
            Set::Name("disk.coupling", "moving-mass"),
            Set::Number("disk.patch", half),
            Set::Number("duration", 1.2),
            Set::LeftOut("output.shapes"),
        ],
    );
    let train = bridge_with_train(
        "exact",
        &format!(
            "  axles: [0.0]\n  load: {}\n  speed: {speed}\n  model: moving-mass\n",
            mass * 9.81
        ),
        0.1,
    );
    let a = run_beam(&disk, Method::GenAlpha, 1e-8, 1e-12);
    let b = run_beam(&train, Method::GenAlpha, 1e-8, 1e-12);
    let until = (20.0 - half) / speed;
    let midspan = |r: &BeamRun| -> Vec<(f64, f64)> {
        let k = probe(r, "mid");
        r.rows
            .iter()
            .filter(|row| row.t <= until)
            .map(|row| (row.t, row.probes[k].w))
            .collect()
    };
    let (x, y) = (midspan(&a), midspan(&b));
    assert_eq!(x.len(), y.len(), "the two runs share the output grid");
    let peak = x.iter().map(|r| r.1.abs()).fold(0.0, f64::max);
    let off = x
        .iter()
        .zip(&y)
        .map(|(p, q)| {
            assert!((p.0 - q.0).abs() < 1e-9);
            (p.1 - q.1).abs()
        })
        .fold(0.0, f64::max)
        / peak;
    let drift = b.header.energy.max_rel_drift();
    eprintln!("moving-mass axle against the moving-mass disk: midspan {off:.2e} of the peak; train's energy drift {drift:.2e}");
    assert!(off <= 2e-5, "midspan {off:.3e}");
    assert!(drift <= 1e-6, "drift {drift:.3e}");
}

/// The energy balance of the undamped HSLM bridge under a moving-mass train (HSLM-A1 at
/// 60 m/s, modal beam of 16 modes): the axles' power on the beam, m (g − d²r/dt²) · ṙ,
/// booked as the loads' work, closes the balance, and its drift falls as rtol does (measured
/// 1.9e-4 → 1.1e-5 from rtol 1e-5 to 1e-6: asserted at least fivefold, and below 1e-4).
#[test]
fn a_moving_mass_train_keeps_the_energy_balance() {
    let scene = changed(
        "hslm-15m.yaml",
        &[
            Set::LeftOut("track.beam.damping"),
            Set::Name("track.beam.model", "modal"),
            Set::Number("track.beam.modes", 16.0),
            Set::Number("train.speed", 60.0),
            Set::Name("train.model", "moving-mass"),
            Set::Number("duration", 0.1),
        ],
    );
    let drift = |rtol: f64| {
        run_beam(&scene, Method::GenAlpha, rtol, rtol * 1e-4)
            .header
            .energy
            .max_rel_drift()
    };
    let (coarse, fine) = (drift(1e-5), drift(1e-6));
    eprintln!("drift {coarse:.2e} at rtol 1e-5, {fine:.2e} at 1e-6");
    assert!(
        fine < 1e-4 && fine * 5.0 < coarse,
        "{coarse:.3e} → {fine:.3e}"
    );
}

/// Moving masses on the modal beam against the linear mesh its modes come from (HSLM-A1 at
/// 90 m/s over the 15 m bridge, the plan's 18 modes): what the outputs read off the mesh, the
/// probes' w and φ and the supports' forces, takes the modes left out static under every force
/// on the beam, and a moving mass's force carries its inertia, m (g − d²r/dt²), beside its
/// weight. The end element's shear reads that static share in full: with the weight alone the
/// pinned end's reaction at 1.03 s read 836 kN against the mesh's 663 (18 % of the largest
/// reaction off) and moved with the modes kept (760 kN on 36), and midspan's φ came 2.3·10⁻³
/// of its largest off. Every row of both ends' vertical reactions must lie within 2·10⁻³ of
/// the largest (measured 1.2·10⁻³; on 36 modes 2.7·10⁻⁴), midspan's w and φ within 10⁻³ of
/// theirs (measured 4.1·10⁻⁴ in φ): the two models' midspan acceleration differ by 6.3·10⁻⁴.
#[test]
fn moving_masses_on_the_modal_beam_read_as_on_the_mesh() {
    let scene = |model: &'static str| {
        changed(
            "hslm-15m.yaml",
            &[
                Set::Name("train.model", "moving-mass"),
                Set::Name("track.beam.model", model),
                Set::Number("track.beam.elements", 10.0),
            ],
        )
    };
    let (modal, mesh) = common::side_by_side(
        || at_defaults(&scene("modal")),
        || at_defaults(&scene("linear")),
    );
    assert_eq!(modal.rows.len(), mesh.rows.len());
    let kinds: [(&str, fn(&BeamRow) -> Vec<f64>, f64); 3] = [
        (
            "vertical reaction",
            |r| vec![r.reactions[0][1], r.reactions[1][1]],
            2e-3,
        ),
        ("w", |r| r.probes.iter().map(|p| p.w).collect(), 1e-3),
        ("phi", |r| r.probes.iter().map(|p| p.phi).collect(), 1e-3),
    ];
    for (kind, read, within) in kinds {
        let largest = (mesh.rows.iter())
            .flat_map(read)
            .fold(0.0, |m: f64, v| m.max(v.abs()));
        for (a, b) in modal.rows.iter().zip(&mesh.rows) {
            for (x, y) in read(a).iter().zip(read(b)) {
                assert!(
                    (x - y).abs() <= within * largest,
                    "at t = {} s the {kind} is {x} on the modal beam, {y} on the mesh, {:.1e} of the largest {largest:e}",
                    a.t,
                    (x - y).abs() / largest
                );
            }
        }
    }
}

/// Moving masses lower the bridge's first frequency by the mass they add to its first mode,
/// so the resonance of HSLM-A1 on the 15 m bridge (axles 18 m apart in pairs: on average
/// n̄ = 2 L/D of them on the span, each adding m φ² = m/2 on average to the modal mass
/// M = ρ A L/2) moves from the moving forces' v = f1 D down by √(M / (M + n̄ m/2)): the
/// moving-mass peak of the midspan deflection, over speeds 1 m/s apart, within 1 m/s of the
/// moving-force peak's speed so scaled (the sweep's resolution; the mass the axles add in fact
/// varies as they pass, which the mean does not hold).
#[test]
fn moving_masses_lower_the_resonant_speed_by_the_mass_they_add() {
    let peak_speed = |model: &str, speeds: std::ops::RangeInclusive<i32>| -> f64 {
        speeds
            .map(|v| {
                let scene = changed(
                    "hslm-15m.yaml",
                    &[
                        Set::Number("train.speed", f64::from(v)),
                        Set::Name("train.model", model),
                        Set::Number("duration", 0.05),
                        Set::LeftOut("solver.rtol"),
                    ],
                );
                let r = rollbeam::run::run(&scene, &Default::default(), false)
                    .expect("runs")
                    .beam()
                    .expect("a beam");
                let deepest = r
                    .rows
                    .iter()
                    .map(|row| -row.probes[0].w)
                    .fold(0.0, f64::max);
                (f64::from(v), deepest)
            })
            .fold((0.0, 0.0), |best, c| if c.1 > best.1 { c } else { best })
            .0
    };
    let (length, coach, mass_per_length): (f64, f64, f64) = (15.0, 18.0, 2500.0 * 6.0);
    let axle_mass = 170.0e3 / 9.81;
    let modal_mass = mass_per_length * length / 2.0;
    let added = 2.0 * length / coach * axle_mass / 2.0;
    let forces = peak_speed("moving-force", 86..=93);
    let expected = forces * (modal_mass / (modal_mass + added)).sqrt();
    let masses = peak_speed("moving-mass", 80..=88);
    eprintln!("resonance: moving forces at {forces} m/s, moving masses at {masses} m/s, {expected:.2} m/s expected");
    assert!(
        (masses - expected).abs() <= 1.0,
        "{masses} against {expected:.2}"
    );
}
