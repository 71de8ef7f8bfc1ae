//! Vehicles on the bridge: bodies on spring–dampers riding on point wheels over the deck and
//! a profile. Verified
//! - against the same system written directly (the Euler–Bernoulli beam's sine modes and the
//!   vehicle's coordinates, integrated here by the classical Runge–Kutta method at a step far
//!   below the periods): the benchmark of Biggs and of Yang and Yau, with a wheel of its own
//!   mass and as a moving mass alone, and VBI-2D's pitching truck on hubs and tyres over a
//!   raised deck;
//! - in the limits: a stiff suspension is the moving mass of the vehicle's weight, a soft one
//!   its moving force;
//! - against the closed form of a sprung mass driven over a ramp on the rigid approach, and
//!   its rest to round-off on the level track before it;
//! - by the energy balance with dampers, a random profile and braking, which shrinks with rtol;
//! - and by its refusals: a wheel that lifts off stops the run and is named.

use crate::common;

use common::{at_defaults, load, mid_headlines, parse, run_beam, runge_kutta};
use rollbeam::ode::Method;
use rollbeam::run::beam::BeamRun;
use rollbeam::scene::Scene;

/// The benchmark's bridge (see `studies/vehicle-sprung.yaml`).
const BRIDGE: &str = "track:
  beam:
    from: [0.0, 0.0]
    to: [25.0, 0.0]
    E: 2.87e9
    G: 1.0e12
    rho: 2.303
    A: 1000.0
    Av: 1000.0
    I: 2.9
    depth: 0.01
    supports: {from: pinned, to: roller}
";

fn scene(name: &str, duration: f64, rest: &str) -> Scene {
    parse(&format!(
        "name: {name}\nduration: {duration}\n{BRIDGE}{rest}output:\n  probes: [{{name: mid, x: 12.5}}]\n"
    ))
}

/// A one-wheel vehicle: `mass` kg on a spring of `k` N/m, from `x0` at `speed`.
fn sprung(mass: f64, k: f64, x0: f64, speed: f64) -> String {
    format!(
        "vehicles:
  - name: car
    x0: {x0}
    speed: {speed}
    bodies: [{{name: body, mass: {mass}}}]
    axles: [{{name: wheel, x: 0.0}}]
    springs: [{{upper: body, lower: wheel, x: 0.0, k: {k}}}]
"
    )
}

fn column(r: &BeamRun, f: impl Fn(&rollbeam::run::beam::BeamRow) -> f64) -> Vec<(f64, f64)> {
    r.rows.iter().map(|row| (row.t, f(row))).collect()
}

fn body_y(row: &rollbeam::run::beam::BeamRow) -> f64 {
    row.vehicles.as_ref().expect("vehicles observed").bodies[0][0][0]
}

/// Biggs' sprung mass written directly: the beam's first `modes` sine modes of an
/// Euler–Bernoulli beam (EI, m per length, span L) and the body's displacement y, the wheel
/// on the beam while 0 ≤ v t ≤ L; classical Runge–Kutta with step `h`. A `wheel` of mass
/// m_w of its own follows the deck, d = φᵀq, with d̈ = φᵀq̈ + 2v φ'ᵀq̇ + v² φ''ᵀq: its inertia
/// couples the modes through the rank-one mass m_w φφᵀ, solved for by Sherman–Morrison.
/// Without a body (`mass` 0, `k` 0) the wheel is a moving mass. Returns per step (t, w at
/// midspan, y, ÿ).
#[allow(clippy::too_many_arguments)]
fn direct(
    ei: f64,
    m: f64,
    length: f64,
    (mass, wheel): (f64, f64),
    k: f64,
    speed: f64,
    modes: usize,
    h: f64,
    until: f64,
) -> Vec<[f64; 4]> {
    let g = 9.81;
    let weight = (mass + wheel) * g;
    let pi = std::f64::consts::PI;
    let wave = |j: usize| j as f64 * pi / length;
    let omega2: Vec<f64> = (1..=modes).map(|j| wave(j).powi(4) * ei / m).collect();
    // State: q_1..q_n, y, then their rates.
    let n = modes + 1;
    let rhs = |t: f64, s: &[f64]| -> Vec<f64> {
        let x = speed * t;
        let on = f64::from(u8::from((0.0..=length).contains(&x)));
        let shape: Vec<f64> = (1..=modes).map(|j| on * (wave(j) * x).sin()).collect();
        let w: f64 = shape.iter().zip(&s[..modes]).map(|(a, b)| a * b).sum();
        let convective: f64 = (1..=modes)
            .map(|j| {
                let (slope, curvature) = (
                    wave(j) * (wave(j) * x).cos(),
                    -wave(j).powi(2) * (wave(j) * x).sin(),
                );
                on * (2.0 * speed * slope * s[n + j - 1] + speed * speed * curvature * s[j - 1])
            })
            .sum();
        let spring = k * (s[modes] - w);
        // The wheel bears R = W − k (y − w) + m_w d̈; the beam feels −R.
        let on_beam = -weight + spring - wheel * convective;
        let mut d = vec![0.0; 2 * n];
        d[..n].copy_from_slice(&s[n..]);
        let scale = 2.0 / (m * length);
        for j in 0..modes {
            d[n + j] = -omega2[j] * s[j] + scale * shape[j] * on_beam;
        }
        let along: f64 = shape.iter().zip(&d[n..n + modes]).map(|(a, b)| a * b).sum();
        let norm: f64 = shape.iter().map(|a| a * a).sum();
        let deck = along / (1.0 + scale * wheel * norm);
        for j in 0..modes {
            d[n + j] -= scale * wheel * shape[j] * deck;
        }
        if mass > 0.0 {
            d[n + modes] = -spring / mass;
        }
        d
    };
    let mut out = Vec::new();
    runge_kutta(rhs, 2 * n, h, until, |t, s, d| {
        let mid: f64 = (1..=modes)
            .map(|j| (j as f64 * pi / 2.0).sin() * s[j - 1])
            .sum();
        out.push([t, mid, s[modes], d[n + modes]]);
    });
    out
}

/// Linear interpolation of (t, v) at t.
fn at(series: &[(f64, f64)], t: f64) -> f64 {
    let i = series
        .partition_point(|p| p.0 < t)
        .clamp(1, series.len() - 1);
    let (a, b) = (series[i - 1], series[i]);
    a.1 + (b.1 - a.1) * (t - a.0) / (b.0 - a.0)
}

/// The benchmark at its own inputs, at the defaults, against the same system written directly
/// with 20 sine modes and a Runge–Kutta step of 20 µs (its error below 10⁻⁸ of the response):
/// the midspan deflection and the body's displacement agree within the accuracy asked
/// (10⁻³ of each one's largest value) over the crossing and the free vibration after it.
/// What separates the two besides integration is the finite-element modes against the sine
/// modes (the planner's mesh holds the static deflection to 2.5·10⁻⁴) and the wheel's
/// patch of ±6 mm. Measured: 1.4·10⁻⁴ in the deflection, 1.6·10⁻⁵ in the body's displacement.
#[test]
fn the_sprung_mass_agrees_with_the_same_system_written_directly() {
    let r = at_defaults(&load("vehicle-sprung.yaml"));
    let until = r.header.t_end;
    let reference = direct(
        2.87e9 * 2.9,
        2303.0,
        25.0,
        (5750.0, 0.0),
        1595.0e3,
        27.78,
        20,
        2e-5,
        until,
    );
    let w: Vec<(f64, f64)> = reference.iter().map(|p| (p[0], p[1])).collect();
    let y: Vec<(f64, f64)> = reference.iter().map(|p| (p[0], p[2])).collect();
    let ours_w = column(&r, |row| row.probes[0].w);
    let ours_y = column(&r, body_y);
    let largest = |s: &[(f64, f64)]| s.iter().fold(0.0_f64, |m, p| m.max(p.1.abs()));
    let worst = |ours: &[(f64, f64)], theirs: &[(f64, f64)]| {
        ours.iter()
            .fold(0.0_f64, |m, &(t, v)| m.max((v - at(theirs, t)).abs()))
            / largest(theirs)
    };
    let (ew, ey) = (worst(&ours_w, &w), worst(&ours_y, &y));
    eprintln!("the sprung mass against the direct system: midspan w {ew:.2e}, body y {ey:.2e}");
    assert!(
        ew < 1e-3,
        "midspan deflection off by {ew:.2e} of its largest"
    );
    assert!(
        ey < 1e-3,
        "body displacement off by {ey:.2e} of its largest"
    );
}

/// Biggs' sprung mass over a wheel of 2000 kg of its own, which follows the deck and adds its
/// inertia, 2v ẇ' and v² w'' included, at the defaults against the same system written
/// directly (20 sine modes, the wheel's mass coupling them, Runge–Kutta at 20 µs): the
/// midspan deflection, the body's displacement and its acceleration agree within the accuracy
/// asked (10⁻³ of each one's largest) at every output time, and so does the body's largest
/// acceleration the summary reports. Besides integration, the finite-element modes and the
/// patch the wheel's convective terms are read over separate the two from sine modes and a
/// point. Measured at the defaults: 2.1·10⁻⁴ in the deflection, 1.6·10⁻⁵ in the body's
/// displacement, 4.2·10⁻⁴ in its acceleration along the run, 3.2·10⁻⁵ in its largest.
#[test]
fn an_unsprung_wheel_agrees_with_the_same_system_written_directly() {
    let car = sprung(5750.0, 1595.0e3, 0.0, 27.78).replace(
        "axles: [{name: wheel, x: 0.0}]",
        "axles: [{name: wheel, x: 0.0, mass: 2000.0}]",
    );
    let r = at_defaults(&scene("unsprung", 1.0, &car));
    let reference = direct(
        2.87e9 * 2.9,
        2303.0,
        25.0,
        (5750.0, 2000.0),
        1595.0e3,
        27.78,
        20,
        2e-5,
        r.header.t_end,
    );
    let series = |k: usize| -> Vec<(f64, f64)> { reference.iter().map(|p| (p[0], p[k])).collect() };
    let largest = |s: &[(f64, f64)]| s.iter().fold(0.0_f64, |m, p| m.max(p.1.abs()));
    let body_a = |row: &rollbeam::run::beam::BeamRow| {
        row.vehicles.as_ref().expect("vehicles observed").bodies[0][0][2]
    };
    let along = [
        ("midspan w", column(&r, |row| row.probes[0].w), 1e-3),
        ("body y", column(&r, body_y), 1e-3),
        ("body a", column(&r, body_a), 1e-3),
    ];
    for (i, (name, ours, within)) in along.iter().enumerate() {
        let theirs = series(i + 1);
        let off = ours
            .iter()
            .fold(0.0_f64, |m, &(t, v)| m.max((v - at(&theirs, t)).abs()))
            / largest(&theirs);
        eprintln!("a wheel of its own mass against the direct system: {name} {off:.2e}");
        assert!(off < *within, "{name} off by {off:.2e} of its largest");
    }
    let theirs = largest(&series(3));
    let a_max = r.extremes.vehicles[0].max;
    let off = (a_max - theirs).abs() / theirs;
    eprintln!("a wheel of its own mass against the direct system: the body's a_max {off:.2e}");
    assert!(off < 1e-3, "the body's a_max {a_max} against {theirs}");
}

/// A train of one moving mass (`train.model: moving-mass`, 2000 kg) over Biggs' bridge at the
/// defaults against the same wheel written directly without a body: its inertia and its
/// convective terms 2v ẇ' and v² w'' (20 sine modes, Runge–Kutta at 20 µs). The midspan
/// deflection agrees within the accuracy at every output time, over the crossing and the free
/// vibration after it. Measured: 2.3·10⁻⁴ (what separates the two is the finite-element modes
/// and the patch against sine modes and a point, as for the sprung mass).
#[test]
fn a_moving_mass_agrees_with_the_same_system_written_directly() {
    let train = "train: {axles: [0.0], load: 19620.0, speed: 27.78, model: moving-mass}\n";
    let r = at_defaults(&scene("moving-mass", 1.0, train));
    let reference = direct(
        2.87e9 * 2.9,
        2303.0,
        25.0,
        (0.0, 2000.0),
        0.0,
        27.78,
        20,
        2e-5,
        r.header.t_end,
    );
    let theirs: Vec<(f64, f64)> = reference.iter().map(|p| (p[0], p[1])).collect();
    let largest = theirs.iter().fold(0.0_f64, |m, p| m.max(p.1.abs()));
    let off = column(&r, |row| row.probes[0].w)
        .iter()
        .fold(0.0_f64, |m, &(t, v)| m.max((v - at(&theirs, t)).abs()))
        / largest;
    eprintln!("a moving mass against the direct system: midspan w {off:.2e}");
    assert!(
        off < 1e-3,
        "midspan deflection off by {off:.2e} of its largest"
    );
}

/// VBI-2D's verification truck over its raised deck (`studies/vehicle-truck.yaml`) written
/// directly: the Euler–Bernoulli beam's first `modes` sine modes with Rayleigh damping of
/// ζ = 3 % at the first two, the body's bounce y and pitch θ (nose up), the hubs' bounce
/// y₁, y₂, each hub on an undamped tyre over a massless wheel that follows the deck and the
/// profile, every coordinate measured from the static equilibrium on a level rigid track.
/// Classical Runge–Kutta with step `h`; returns per step (t, w at midspan, y, ÿ, ÿ₁, ÿ₂, the
/// front and the rear wheel's force).
fn direct_truck(modes: usize, h: f64, until: f64) -> Vec<[f64; 8]> {
    let (length, ei, m) = (25.0, 3.5e10 * 1.3901, 18.358 * 1000.0);
    let (body, pitch, hub) = (10500.0, 50000.0, 900.0);
    let (suspension, suspension_c, tyre) = (6.0e6, 1.0e4, 1.75e6);
    let (speed, x0) = (19.4444, -10.0);
    let (behind, lever) = ([0.0, 5.0], [2.5, -2.5]);
    let static_load = (0.5 * body + hub) * 9.81;
    let pi = std::f64::consts::PI;
    let omega2: Vec<f64> = (1..=modes)
        .map(|j| (j as f64 * pi / length).powi(4) * ei / m)
        .collect();
    let (w1, w2) = (omega2[0].sqrt(), omega2[1].sqrt());
    // ζ = α/(2ω) + βω/2 at ω₁ and ω₂.
    let beta = 2.0 * 0.03 / (w1 + w2);
    let alpha = beta * w1 * w2;
    let profile = |x: f64| 0.01 * ((x + 1.0).clamp(0.0, 1.0) - (x - 25.0).clamp(0.0, 1.0));
    let shape = |x: f64| -> Vec<f64> {
        (1..=modes)
            .map(|j| {
                if (0.0..=length).contains(&x) {
                    (j as f64 * pi * x / length).sin()
                } else {
                    0.0
                }
            })
            .collect()
    };
    let n = modes + 4;
    // The tyres' forces on the hubs (up) at (t, state): each compressed by the track's rise
    // above its hub.
    let tyres = |t: f64, s: &[f64]| -> [(f64, Vec<f64>); 2] {
        [0, 1].map(|a| {
            let x = x0 + speed * t - behind[a];
            let phi = shape(x);
            let w: f64 = phi.iter().zip(&s[..modes]).map(|(p, q)| p * q).sum();
            (tyre * (w + profile(x) - s[modes + 2 + a]), phi)
        })
    };
    let rhs = |t: f64, s: &[f64]| -> Vec<f64> {
        let (y, theta, rate) = (s[modes], s[modes + 1], &s[n..]);
        let mut d = vec![0.0; 2 * n];
        d[..n].copy_from_slice(rate);
        let mut on_modes = vec![0.0; modes];
        for (a, (on_hub, phi)) in tyres(t, s).into_iter().enumerate() {
            let stretch = y + lever[a] * theta - s[modes + 2 + a];
            let stretch_rate = rate[modes] + lever[a] * rate[modes + 1] - rate[modes + 2 + a];
            let pull = suspension * stretch + suspension_c * stretch_rate;
            d[n + modes] -= pull / body;
            d[n + modes + 1] -= lever[a] * pull / pitch;
            d[n + modes + 2 + a] = (on_hub + pull) / hub;
            for (f, p) in on_modes.iter_mut().zip(&phi) {
                *f -= p * (static_load + on_hub);
            }
        }
        for j in 0..modes {
            d[n + j] = 2.0 / (m * length) * on_modes[j]
                - omega2[j] * s[j]
                - (alpha + beta * omega2[j]) * rate[j];
        }
        d
    };
    let mut out = Vec::new();
    runge_kutta(rhs, 2 * n, h, until, |t, s, d| {
        let mid: f64 = (1..=modes)
            .map(|j| (j as f64 * pi / 2.0).sin() * s[j - 1])
            .sum();
        let [front, rear] = tyres(t, s).map(|(on_hub, _)| static_load + on_hub);
        out.push([
            t,
            mid,
            s[modes],
            d[n + modes],
            d[n + modes + 2],
            d[n + modes + 3],
            front,
            rear,
        ]);
    });
    out
}

/// VBI-2D's verification truck over the raised deck (`studies/vehicle-truck.yaml`: a pitching
/// body on damped suspensions over two hubs on tyres, ramps of 1 cm at the abutments) at the
/// defaults, against the same system written directly with 20 sine modes and a Runge–Kutta
/// step of 20 µs: at every output time the midspan deflection, the body's displacement and
/// acceleration, the hubs' accelerations and the wheels' forces agree within the accuracy
/// asked (10⁻³ of each one's largest), and so do the summary's extremes of each, located on
/// the solution, against the direct run's largest and least over its steps. What separates
/// the two besides integration is the finite-element modes against the sine modes and the
/// wheel's patch of ±5 cm (the approaches' kinks reach the hubs through the tyres as kinks
/// in their accelerations, which both read alike). Measured: 6.1·10⁻⁵ in the deflection,
/// 1.4·10⁻⁵ in the body's acceleration, 1.3·10⁻⁴ in a hub's, 6·10⁻⁶ in the wheels' forces;
/// the extremes within 3.9·10⁻⁵.
#[test]
fn the_truck_over_a_raised_deck_agrees_with_the_same_system_written_directly() {
    let r = at_defaults(&load("vehicle-truck.yaml"));
    let reference = direct_truck(20, 2e-5, r.header.t_end);
    let series = |k: usize| -> Vec<(f64, f64)> { reference.iter().map(|p| (p[0], p[k])).collect() };
    let observed = |row: &rollbeam::run::beam::BeamRow| {
        let v = row.vehicles.as_ref().expect("vehicles observed");
        [
            row.probes[0].w,
            v.bodies[0][0][0],
            v.bodies[0][0][2],
            v.bodies[0][1][2],
            v.bodies[0][2][2],
            v.rn[0][0],
            v.rn[0][1],
        ]
    };
    let names = [
        "midspan w",
        "body y",
        "body a",
        "front hub a",
        "rear hub a",
        "front wheel force",
        "rear wheel force",
    ];
    let vehicle = &r.extremes.vehicles;
    // The summary's extremes of each quantity the body's y aside (not reported).
    let reported = [
        Some(r.extremes.probes[0][1]),
        None,
        Some(vehicle[0]),
        Some(vehicle[1]),
        Some(vehicle[2]),
        Some(vehicle[3]),
        Some(vehicle[4]),
    ];
    for (i, name) in names.iter().enumerate() {
        let theirs = series(i + 1);
        let largest = theirs.iter().fold(0.0_f64, |m, p| m.max(p.1.abs()));
        let along = r.rows.iter().fold(0.0_f64, |m, row| {
            m.max((observed(row)[i] - at(&theirs, row.t)).abs())
        }) / largest;
        let (least, most) = theirs
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p.1), b.max(p.1))
            });
        let extremes = reported[i].map_or(0.0, |e| {
            (e.min - least).abs().max((e.max - most).abs()) / largest
        });
        eprintln!("the truck against the direct system: {name} {along:.2e} along the run, {extremes:.2e} in its extremes");
        assert!(along < 1e-3, "{name} off by {along:.2e} of its largest");
        assert!(
            extremes < 1e-3,
            "{name}'s extremes off by {extremes:.2e} of its largest"
        );
    }
}

fn peak_mid(r: &BeamRun) -> f64 {
    r.extremes.probes[0][1].min
}

/// As the suspension stiffens the body follows the wheel, and the vehicle is the moving mass of
/// its weight; as it softens the body floats still, and the vehicle is the moving force of its
/// weight. At k = 10¹² N/m (the body's frequency 2 kHz, far above the bridge's) and at k = 1
/// N/m (0.002 Hz) the lowest midspan deflection comes within 10⁻⁴ of the train model's, run
/// at the same tolerances (measured 3·10⁻⁷ and 6·10⁻⁸); what is left is the body's own motion, of order the frequency
/// ratio squared, and the wheel's patch against the moving force's point.
#[test]
fn a_stiff_suspension_is_the_moving_mass_and_a_soft_one_the_moving_force() {
    let weight = 5750.0 * 9.81;
    let train = |model: &str| {
        scene(
            "train",
            0.5,
            &format!("train: {{axles: [0.0], load: {weight}, speed: 27.78, model: {model}}}\n"),
        )
    };
    let run = |s: &Scene| run_beam(s, Method::GenAlpha, 1e-8, 1e-12);
    let stiff = run(&scene("stiff", 0.5, &sprung(5750.0, 1e12, 0.0, 27.78)));
    let soft = run(&scene("soft", 0.5, &sprung(5750.0, 1.0, 0.0, 27.78)));
    let mass = run(&train("moving-mass"));
    let force = run(&train("moving-force"));
    let off = |a: &BeamRun, b: &BeamRun| (peak_mid(a) / peak_mid(b) - 1.0).abs();
    assert!(
        off(&stiff, &mass) < 1e-4,
        "stiff: {:.2e}",
        off(&stiff, &mass)
    );
    assert!(
        off(&soft, &force) < 1e-4,
        "soft: {:.2e}",
        off(&soft, &force)
    );
}

/// A suspension faster than the steps is said to be. Biggs' sprung mass on springs 10³ and 10⁴
/// times as stiff (84 and 266 Hz) at the defaults takes 0.25 and 0.45 rad of that vibration a
/// step on average; its largest acceleration, set ringing by the wheel's passage over the
/// deck's ends, lands within 1.7·10⁻⁴ of the run at rtol 10⁻⁸ at 84 Hz and 2.7·10⁻² at
/// 266 Hz. The run warns of the second alone, and Biggs' own (2.65 Hz) is quiet.
#[test]
fn a_suspension_faster_than_the_steps_is_said_to_be() {
    let warned = |k: f64| {
        at_defaults(&scene("stiffened", 1.0, &sprung(5750.0, k, 0.0, 27.78)))
            .warnings()
            .iter()
            .any(|w| w.contains("ring on their springs"))
    };
    assert!(!warned(1.595e6), "Biggs' own suspension");
    assert!(!warned(1.595e9), "84 Hz, resolved");
    assert!(warned(1.595e10), "266 Hz, not resolved");
}

/// A vehicle beside a train of moving forces on one beam, the benchmark's bridge reduced to 8
/// modes. The beam, the suspension and the massless wheel's contact are linear and the axles'
/// loads prescribed, so the deflection is linear in the axle load P: w(2P) − 2 w(P) + w(0) = 0
/// at every output time, to 1e-8 of the peak (round-off and rtol 1e-10). That alone would hold
/// with the train ignored, so on a suspension of 1 N/m (the vehicle the moving force of its
/// weight, see above) the train's share w(P) − w(0) is also the train's deflection on the bare
/// bridge, within 1e-4 of the peak (measured 2.8·10⁻⁸). The train runs faster and leaves first:
/// the runs share their length.
#[test]
fn a_vehicle_beside_a_train_is_linear_in_the_train() {
    let bridge = BRIDGE.replace(
        "    supports:",
        "    model: modal\n    modes: 8\n    supports:",
    );
    let with = |duration: f64, riders: String| {
        parse(&format!(
            "name: both\nduration: {duration}\n{bridge}{riders}output:\n  probes: [{{name: mid, x: 12.5}}]\n"
        ))
    };
    let train = |load: f64| format!("train: {{axles: [0.0, 3.0], load: {load}, speed: 40.0}}\n");
    let run = |s: &Scene| run_beam(s, Method::Esdirk4, 1e-10, 1e-14);
    // The largest |Σ c_i w_i| over the output times, and the largest |w| of the first run.
    let combined = |runs: &[(f64, &BeamRun)]| {
        let rows = runs[0].1.rows.len();
        assert!(runs.iter().all(|(_, r)| r.rows.len() == rows));
        let mut worst = 0.0_f64;
        for i in 0..rows {
            let t = runs[0].1.rows[i].t;
            assert!(runs.iter().all(|(_, r)| (r.rows[i].t - t).abs() < 1e-9));
            let sum: f64 = runs.iter().map(|(c, r)| c * r.rows[i].probes[0].w).sum();
            worst = worst.max(sum.abs());
        }
        let peak = runs[0]
            .1
            .rows
            .iter()
            .map(|r| r.probes[0].w.abs())
            .fold(0.0, f64::max);
        (worst, peak)
    };
    for k in [1595.0e3, 1.0] {
        let car = sprung(5750.0, k, 0.0, 27.78);
        let [none, once, twice] =
            [0.0, 5.0e4, 1.0e5].map(|p| run(&with(0.3, format!("{car}{}", train(p)))));
        let (worst, peak) = combined(&[(1.0, &twice), (-2.0, &once), (1.0, &none)]);
        eprintln!(
            "k = {k} N/m: w(2P) − 2 w(P) + w(0) off by {:.2e} of the peak",
            worst / peak
        );
        assert!(worst <= 1e-8 * peak, "k = {k}: {worst:.3e} of {peak:.3e}");
        if k == 1.0 {
            let bare = run(&with(once.header.t_end - 28.0 / 40.0, train(5.0e4)));
            let (worst, peak) = combined(&[(1.0, &once), (-1.0, &none), (-1.0, &bare)]);
            eprintln!(
                "the train's share against the bare bridge: {:.2e} of the peak",
                worst / peak
            );
            assert!(worst <= 1e-4 * peak, "{worst:.3e} of {peak:.3e}");
        }
    }
}

/// The sprung mass driven over a ramp of height h = 10 mm and length 5 m on the rigid
/// approach, at 20 m/s: the base moves by h t/T over the ramp's T = 0.25 s, and the body,
/// undamped at ω, follows x = (h/T)(t − sin ωt / ω) on it and
/// x = h − h/(ωT) (sin ωt − sin ω(t − T)) after it. At the defaults the body's displacement
/// stays within the accuracy (10⁻³ of its largest) of that over the six periods before the
/// bridge (measured 2.2·10⁻⁵); and before the ramp, on the level track, it stays at rest to
/// round-off.
#[test]
fn a_sprung_mass_over_a_ramp_follows_its_closed_form() {
    let text = sprung(5750.0, 1595.0e3, -60.0, 20.0);
    let with_profile =
        BRIDGE.to_string() + "  profile:\n    points: [[-50.0, 0.0], [-45.0, 0.01]]\n";
    let s = parse(&format!(
        "name: ramp\nduration: 0.1\n{with_profile}{text}output:\n  probes: [{{name: mid, x: 12.5}}]\n"
    ));
    let r = at_defaults(&s);
    let omega = (1595.0e3_f64 / 5750.0).sqrt();
    let (h, ramp, start) = (0.01, 0.25, 0.5);
    let closed = |t: f64| {
        let t = t - start;
        if t < 0.0 {
            0.0
        } else if t <= ramp {
            h / ramp * (t - (omega * t).sin() / omega)
        } else {
            h - h / (omega * ramp) * ((omega * t).sin() - (omega * (t - ramp)).sin())
        }
    };
    let on_approach = column(&r, body_y)
        .into_iter()
        .filter(|p| p.0 < 60.0 / 20.0)
        .collect::<Vec<_>>();
    let largest = on_approach
        .iter()
        .fold(0.0_f64, |m, p| m.max(closed(p.0).abs()));
    let worst = on_approach
        .iter()
        .fold(0.0_f64, |m, &(t, y)| m.max((y - closed(t)).abs()))
        / largest;
    let before = on_approach
        .iter()
        .filter(|p| p.0 < start)
        .fold(0.0_f64, |m, p| m.max(p.1.abs()));
    assert!(
        worst < 1e-3,
        "off the closed form by {worst:.2e} of its largest"
    );
    assert!(
        before < 1e-15,
        "the body moved by {before:e} m on the level track"
    );
}

/// A two-axle truck: a pitching body on suspensions over two hubs, each hub on a tyre over an
/// axle with a wheel mass of its own; dampers everywhere. `extra` adds keys to the vehicle.
fn truck(x0: f64, speed: f64, extra: &str) -> String {
    format!(
        "vehicles:
  - name: truck
    x0: {x0}
    speed: {speed}
{extra}    bodies:
      - {{name: body, mass: 15000.0, inertia: 1.4e5, x: 2.0}}
      - {{name: front_hub, mass: 700.0, x: 0.0}}
      - {{name: rear_hub, mass: 1100.0, x: 4.5}}
    axles:
      - {{name: front, x: 0.0, mass: 50.0}}
      - {{name: rear, x: 4.5, mass: 50.0}}
    springs:
      - {{upper: body, lower: front_hub, x: 0.0, k: 4.0e5, c: 1.0e4}}
      - {{upper: body, lower: rear_hub, x: 4.5, k: 8.0e5, c: 2.0e4}}
      - {{upper: front_hub, lower: front, x: 0.0, k: 1.75e6, c: 3.0e3}}
      - {{upper: rear_hub, lower: rear, x: 4.5, k: 3.5e6, c: 6.0e3}}
"
    )
}

/// The energy balance with everything that moves energy about: the beam's Rayleigh damping,
/// the suspension's and tyres' dampers, unsprung wheel masses riding on a random ISO 8608
/// class A profile (whose curvature they feel), and the truck braking at 1.5 m/s² across the
/// deck. Kinetic, strain, spring and weight energy less the drive's work plus what the
/// dampers took stays at its start within the integration's error, which shrinks as rtol
/// does: from 10⁻⁶ to 10⁻⁸ the steps shrink by 100^(1/3) and the second-order method's error
/// by about 20 (measured 7.6·10⁻⁵ to 3.4·10⁻⁶).
#[test]
fn the_energy_balance_closes_with_dampers_a_profile_and_braking() {
    let text = BRIDGE.replace(
        "    supports: {from: pinned, to: roller}\n",
        "    supports: {from: pinned, to: roller}\n    damping: {ratio: 0.02, modes: [1, 2]}\n  profile:\n    iso8608: {class: A, seed: 3}\n",
    );
    let s = parse(&format!(
        "name: energy\nduration: 0.5\n{text}{}output:\n  probes: [{{name: mid, x: 12.5}}]\n",
        truck(-5.0, 25.0, "    acceleration: -1.5\n")
    ));
    let drift = |rtol: f64| {
        run_beam(&s, Method::GenAlpha, rtol, 1e-14)
            .header
            .energy
            .max_rel_drift()
    };
    let (coarse, fine) = (drift(1e-6), drift(1e-8));
    eprintln!(
        "{}: energy drift {coarse:.2e} at rtol 1e-6, {fine:.2e} at 1e-8",
        s.name
    );
    assert!(fine < 5e-5, "the balance drifts by {fine:.2e}");
    assert!(
        coarse / fine > 10.0,
        "the drift went from {coarse:.2e} to {fine:.2e}"
    );
}

/// The budget's own quadrature stays below the fourth-order method's error. The drive's work
/// and the dampers' energy are booked by Simpson's rule over each step (its error h⁵ a step),
/// so Biggs' sprung mass (`studies/vehicle-sprung.yaml`) by ESDIRK4 balances to 1e-8 at rtol
/// 10⁻⁸ and its balance shrinks from rtol 10⁻⁶ by more than 25 (measured 2.2·10⁻⁸ to 8.5·10⁻¹¹).
/// Booked by the trapezoidal rule (h³ a step) it shrank as rtol^½, from 2.1·10⁻⁶ to
/// 1.8·10⁻⁷: the quadrature's error, not the solution's, would be what the summary reports.
#[test]
fn a_sprung_mass_balances_its_energy_to_the_fourth_order_method_s_error() {
    let s = load("vehicle-sprung.yaml");
    let drift = |rtol: f64| {
        run_beam(&s, Method::Esdirk4, rtol, rtol * 2.2e-3)
            .header
            .energy
            .max_rel_drift()
    };
    let (coarse, fine) = (drift(1e-6), drift(1e-8));
    eprintln!(
        "{}: energy drift {coarse:.2e} at rtol 1e-6, {fine:.2e} at 1e-8",
        s.name
    );
    assert!(fine < 1e-8, "the balance drifts by {fine:.2e}");
    assert!(
        coarse / fine > 25.0,
        "the drift went from {coarse:.2e} to {fine:.2e}"
    );
}

/// A bump of 5 cm over 0.5 m at 30 m/s throws the two-axle truck's rear wheel off the deck
/// (its stiffer tyre): the run stops at the loss of contact, says so, and names the wheel. Its
/// 50 kg wheels take a vertical impulse at each of the bump's kinks, whose energy the drive
/// delivers: booked with the drive's work, the balance closes to a hundredth of the accuracy
/// (measured 7.8·10⁻⁸; unbooked, the impulses left 3·10⁻²).
#[test]
fn a_wheel_that_lifts_off_stops_the_run_and_is_named() {
    let text = BRIDGE.replace(
        "    supports: {from: pinned, to: roller}\n",
        "    supports: {from: pinned, to: roller}\n  profile:\n    points: [[10.0, 0.0], [10.5, 0.05], [11.0, 0.0]]\n",
    );
    let s = parse(&format!(
        "name: bump\nduration: 0.5\n{text}{}output:\n  probes: [{{name: mid, x: 12.5}}]\n",
        truck(0.0, 30.0, "")
    ));
    let r = at_defaults(&s);
    assert_eq!(r.header.stop.name(), "contact-lost");
    let lost = r.vehicles[0].lost_contact.as_deref();
    assert!(matches!(lost, Some("rear")), "{lost:?}");
    let summary = rollbeam::output::beam::summary_yaml(&r).expect("a summary");
    assert!(summary.contains("contact_lost: rear"), "{summary}");
    let drift = r.header.energy.max_rel_drift();
    eprintln!("the truck over a bump: energy drift {drift:.2e}");
    assert!(drift < 1e-5, "the balance drifts by {drift:.2e}");
}

/// The truck on point wheels over 500 kg axles at 30 m/s, starting on the deck over an ISO
/// class E road (seed 43, waves 0.2-20 m): the rear wheel's track turns so sharply under it
/// that its contact force is −501 kN at once, and a point wheel cannot fly. The run stops at
/// t = 0 with contact-lost and names the wheel, and that is all it says of it: the warning
/// for a wheel seen pulling between two looks for a lift-off (which then was stepped over)
/// does not stand beside the stop it caused.
#[test]
fn a_wheel_that_cannot_hold_the_road_at_the_start_stops_the_run_at_once() {
    let text = truck_on_disks(
        30.0,
        500.0,
        "{class: E, seed: 43, wavelengths: [0.2, 20.0]}",
    )
    .replace("    wheel: disk\n    radius: 0.4\n", "")
    .replace("x0: -10.0", "x0: 5.0");
    let r = at_defaults(&parse(&text));
    assert_eq!(r.header.stop.name(), "contact-lost");
    assert_eq!(r.header.t_end, 0.0);
    let lost = r.vehicles[0].lost_contact.as_deref();
    assert!(matches!(lost, Some("rear")), "{lost:?}");
    let summary = rollbeam::output::beam::summary_yaml(&r).expect("a summary");
    assert!(!summary.contains("pulled on the track"), "{summary}");
}

/// The truck over the raised deck (`studies/vehicle-truck.yaml`): its massless wheels cross
/// the profile's four kinks, where the drive's power jumps; each step's work is booked on its
/// own side of them, and the balance closes at the defaults within a thousandth of the
/// accuracy (measured 3.7·10⁻⁹; read on the next stretch's side, it drifted by 2.5·10⁻³).
#[test]
fn the_energy_balance_closes_over_the_kinks_of_a_raised_deck() {
    let r = at_defaults(&load("vehicle-truck.yaml"));
    let drift = r.header.energy.max_rel_drift();
    eprintln!("the truck over the raised deck: energy drift {drift:.2e}");
    assert!(drift < 1e-6, "the balance drifts by {drift:.2e}");
}

/// `vehicles.*.speed` sets every vehicle's speed: a train of cars is swept at one speed.
#[test]
fn a_train_of_vehicles_is_swept_at_one_speed() {
    let mut spec =
        rollbeam::scene::SceneSpec::load(&common::studies_dir().join("vehicle-railcar.yaml"))
            .expect("the study");
    spec.set("vehicles.*.speed", 80.0).expect("a key");
    let scene = rollbeam::plan::Planner::default()
        .plan(&spec)
        .expect("a scene");
    let speeds: Vec<f64> = scene
        .beam()
        .expect("a beam")
        .vehicles
        .iter()
        .map(|v| v.speed)
        .collect();
    assert_eq!(speeds, vec![80.0; 4]);
    assert!(spec.set("vehicles.tram.speed", 80.0).is_err());
    assert!(spec.set_name("vehicles.tram.wheel", "disk").is_err());
}

/// The railway cars on 0.46 m disk wheels at their resonance, 121 m/s: where point wheels
/// lift off at the far abutment (the deck's end rotation against the rigid approach), a
/// wheelset hops there and lands within a metre (measured 0.26–0.62 m), and the run goes on to the end with the balance closed to
/// the accuracy's order (measured 9.6·10⁻⁶ at the defaults).
#[test]
fn railway_cars_on_disk_wheels_hop_at_the_abutment_and_ride_on() {
    let mut spec =
        rollbeam::scene::SceneSpec::load(&common::studies_dir().join("vehicle-railcar.yaml"))
            .expect("the study");
    spec.set("vehicles.*.speed", 121.0).expect("a key");
    spec.set_name("vehicles.*.wheel", "disk").expect("a key");
    spec.set("vehicles.*.radius", 0.46).expect("a key");
    let scene = rollbeam::plan::Planner::default()
        .plan(&spec)
        .expect("a scene");
    let r = at_defaults(&scene);
    assert_eq!(r.header.stop, rollbeam::run::Stop::End);
    let hops: Vec<_> = r
        .vehicles
        .iter()
        .flat_map(|v| v.flights.iter().flatten())
        .collect();
    assert!(!hops.is_empty());
    for f in &hops {
        assert!((f.lift_off_x - 15.0).abs() < 0.5, "{f:?}");
        assert!(f.land_x.is_some_and(|x| x - f.lift_off_x < 1.0), "{f:?}");
    }
    let drift = r.header.energy.max_rel_drift();
    assert!(drift < 1e-4, "the balance drifts by {drift:.2e}");
}

/// A damped sprung mass (1000 kg on 100 kN/m, ζ = 0.2) driven at 20 m/s over a sinusoidal
/// profile (10 mm, wavelength 10 m: 2 Hz against its 1.59 Hz) on the rigid approach. Once the
/// start has died away (e^(−ζω t) < 10⁻⁴ after the first 5 s), the body's amplitude is the
/// base-excited oscillator's transmissibility T = √((1 + (2ζr)²) / ((1 − r²)² + (2ζr)²)),
/// r = ω/ωn, times the profile's fundamental: the profile is given as points 0.1 m apart, and
/// linear interpolation keeps a sine's fundamental to sin²(πh/λ)/(πh/λ)² (1 − 3.3·10⁻⁴).
/// At the defaults the two agree within the accuracy asked (measured 7.1·10⁻⁵).
#[test]
fn a_quarter_car_over_a_sine_follows_its_transmissibility() {
    let (amplitude, wavelength, speed) = (0.01_f64, 10.0_f64, 20.0_f64);
    let (mass, k, zeta) = (1000.0_f64, 1.0e5_f64, 0.2_f64);
    let c = 2.0 * zeta * (k * mass).sqrt();
    let spacing = 0.1;
    let points: Vec<String> = (0..=3000)
        .map(|i| {
            let x = -400.0 + i as f64 * spacing;
            let r = amplitude * (std::f64::consts::TAU * x / wavelength).sin();
            format!("[{x}, {r}]")
        })
        .collect();
    let text = BRIDGE.to_string() + &format!("  profile:\n    points: [{}]\n", points.join(", "));
    let vehicle = format!(
        "vehicles:
  - name: car
    x0: -400.0
    speed: {speed}
    bodies: [{{name: body, mass: {mass}}}]
    axles: [{{name: wheel, x: 0.0}}]
    springs: [{{upper: body, lower: wheel, x: 0.0, k: {k}, c: {c}}}]
"
    );
    let s = parse(&format!(
        "name: sine\nduration: 0.1\n{text}{vehicle}output:\n  interval: 0.002\n  probes: [{{name: mid, x: 12.5}}]\n"
    ));
    let r = at_defaults(&s);
    let steady = column(&r, body_y)
        .into_iter()
        .filter(|&(t, _)| t > 7.5 && t < 14.5)
        .fold(0.0_f64, |m, (_, y)| m.max(y.abs()));
    let ratio = std::f64::consts::TAU * speed / wavelength / (k / mass).sqrt();
    let two = 2.0 * zeta * ratio;
    let transmissibility = ((1.0 + two * two) / ((1.0 - ratio * ratio).powi(2) + two * two)).sqrt();
    let u = std::f64::consts::PI * spacing / wavelength;
    let expected = transmissibility * amplitude * (u.sin() / u).powi(2);
    let off = (steady / expected - 1.0).abs();
    assert!(
        off < 1e-3,
        "steady amplitude {steady:e} against {expected:e}: {off:.2e}"
    );
}

/// `exact-modal` integrates uncoupled modes under a force of time alone: a vehicle couples
/// its bodies to the deck, so the plan refuses it in one sentence (an input error, exit 1),
/// rather than letting the solver fail.
#[test]
fn exact_modal_is_refused_with_vehicles() {
    let over = rollbeam::run::Overrides {
        method: Some(Method::ExactModal),
        ..Default::default()
    };
    let err = match rollbeam::run::run(&load("vehicle-sprung.yaml"), &over, false) {
        Err(e) => e,
        Ok(_) => panic!("exact-modal ran with a vehicle"),
    };
    assert!(matches!(err, rollbeam::error::Error::Input(_)), "{err}");
    assert!(err.to_string().contains("this scene has vehicles"), "{err}");
}

/// A disk wheel rests where it lifts its centre highest: on a smooth profile its centre rides
/// a/2 f'² above the track, so as its radius shrinks it becomes the point wheel, to first
/// order in the radius, with or without an unsprung mass (whose inertia then follows the
/// disk's centre). The sprung mass over an ISO 8608 class A profile (wavelengths from 0.5 m),
/// at rtol 10⁻⁷: the body's largest acceleration differs from the point wheel's by a tenth as
/// much at each tenth of the radius, and by less than 10⁻⁴ at 3 mm (measured 4.3·10⁻⁴,
/// 4.1·10⁻⁵, 1.8·10⁻⁶ without, 4.3·10⁻⁴, 4.0·10⁻⁵, 1.5·10⁻⁶ with 700 kg). At 3 mm the
/// difference sits at the integration's own error: 2.0·10⁻⁶ at rtol 3·10⁻⁸, 3.8·10⁻⁶ at
/// 10⁻⁸, so the test asks each decade of the radius for a fivefold fall. The two unsprung
/// masses run side by side: the suite runs this test among its last.
#[test]
fn disk_wheels_become_the_point_wheel_as_their_radius_shrinks() {
    let bridge = BRIDGE.replace(
        "    supports: {from: pinned, to: roller}\n",
        "    supports: {from: pinned, to: roller}\n  profile:\n    iso8608: {class: A, seed: 5, wavelengths: [0.5, 30.0]}\n",
    );
    let against_the_point_wheel = |unsprung: f64| {
        let body_a = |wheel: &str| {
            let s = parse(&format!(
                "name: disk\nduration: 0.5\n{bridge}{}output:\n  probes: [{{name: mid, x: 12.5}}]\n",
                sprung(5750.0, 1595.0e3, -10.0, 27.78)
                    .replace("    speed:", &format!("{wheel}    speed:"))
                    .replace(
                        "{name: wheel, x: 0.0}",
                        &format!("{{name: wheel, x: 0.0, mass: {unsprung}}}")
                    )
            ));
            let r = run_beam(&s, Method::GenAlpha, 1e-7, 1e-11);
            r.vehicles[0].bodies[0].1.largest_magnitude().0
        };
        let point = body_a("");
        [0.3, 0.03, 0.003]
            .map(|a| (body_a(&format!("    wheel: disk\n    radius: {a}\n")) / point - 1.0).abs())
    };
    let (without, with) = common::side_by_side(
        || against_the_point_wheel(0.0),
        || against_the_point_wheel(700.0),
    );
    for (unsprung, off) in [(0.0, without), (700.0, with)] {
        assert!(
            off[0] / off[1] > 5.0 && off[1] / off[2] > 5.0,
            "{unsprung} kg: {off:?}"
        );
        assert!(off[2] < 1e-4, "{unsprung} kg: {off:?}");
    }
}

/// Disk wheels of 0.5 m on the truck over the raised deck: they pivot over the crests and
/// change faces in the hollows at breakpoints, and the balance closes as the point wheels'
/// does (measured 9.5·10⁻⁷ at the defaults).
#[test]
fn the_energy_balance_closes_for_disk_wheels_over_kinks() {
    let path = common::studies_dir().join("vehicle-truck.yaml");
    let text = std::fs::read_to_string(path).expect("the study").replace(
        "    speed: 19.4444\n",
        "    speed: 19.4444\n    wheel: disk\n    radius: 0.5\n",
    );
    let r = at_defaults(&parse(&text));
    let drift = r.header.energy.max_rel_drift();
    eprintln!("the truck on 0.5 m disks over the ramps: energy drift {drift:.2e}");
    assert!(drift < 1e-5, "the balance drifts by {drift:.2e}");
}

/// A disk wheel with unsprung mass m under a body M on a spring so soft that it holds the
/// body's weight unchanged while the wheel flies: the axle falls at G = (M + m) g / m. Rolling
/// level at V onto a downhill face of slope s, it pivots over the crest with Ḧ = −V²/a, beyond
/// G, so it lifts off at the crest; it flies the parabola −G τ²/2 and lands on the face (a
/// disk resting on a line has its centre a √(1 + s²) above the line's height under it),
/// plastically: the impact takes m (ḣ + s V)²/2. Lift-off, landing and the loss against those
/// closed forms (measured: the landing 4·10⁻¹⁰ s late, the gap the landing is watched for
/// being a billionth of the radius, at 0.9 m/s; the loss 1.3·10⁻⁷ off), and the balance
/// closes through the flight (4.7·10⁻⁸).
#[test]
fn a_disk_wheel_flies_off_a_crest_and_lands_as_a_projectile() {
    let (big, m, speed, a, s, crest) = (1000.0, 100.0, 20.0, 0.4, 0.05, -5.0);
    let g = 9.81;
    let scene = parse(&format!(
        "name: hop\nduration: 0.1\n{}  profile:\n    points: [[{crest}, 0.0], [0.0, {}]]\n\
vehicles:
  - name: car
    x0: -7.0
    speed: {speed}
    wheel: disk
    radius: {a}
    bodies: [{{name: body, mass: {big}}}]
    axles: [{{name: wheel, x: 0.0, mass: {m}}}]
    springs: [{{upper: body, lower: wheel, x: 0.0, k: 1.0e-3}}]
output:\n  probes: [{{name: mid, x: 12.5}}]\n",
        BRIDGE,
        s * crest
    ));
    let r = run_beam(&scene, Method::GenAlpha, 1e-10, 1e-14);
    let flights = &r.vehicles[0].flights[0];
    assert_eq!(flights.len(), 1, "{flights:?}");
    let f = flights[0];
    let fall = (big + m) * g / m;
    assert!(speed * speed / a > fall);
    let t_crest = (crest + 7.0) / speed;
    assert!((f.lift_off_t - t_crest).abs() < 1e-9, "{f:?}");
    // Where the parabola meets the face: −G τ²/2 = −s V τ + a (√(1 + s²) − 1).
    let lift = (1.0 + s * s).sqrt();
    let gap = |tau: f64| -0.5 * fall * tau * tau + s * speed * tau - a * (lift - 1.0);
    let (mut lo, mut hi) = (1e-3, 1.0);
    while hi - lo > 1e-15 {
        let mid = 0.5 * (lo + hi);
        if gap(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let tau = 0.5 * (lo + hi);
    let land = f.land_t.expect("it lands");
    assert!(
        (land - t_crest - tau).abs() < 1e-8 * tau.max(1.0),
        "{} vs {tau}",
        land - t_crest
    );
    let lost = 0.5 * m * (-fall * tau + s * speed).powi(2);
    let off = (f.energy_lost.expect("a landing") / lost - 1.0).abs();
    assert!(off < 1e-6, "lost {:?} vs {lost}: {off:.1e}", f.energy_lost);
    let drift = r.header.energy.max_rel_drift();
    assert!(drift < 1e-6, "the balance drifts by {drift:.2e}");
}

/// Biggs' sprung mass on a 500 kg wheel of its own, crawling over its bridge at 5 m/s: the
/// wheel's impulses where the deck's slope turns set every mode ringing for the five seconds
/// of the crossing. At the defaults midspan's largest acceleration, the envelope's and the
/// body's lie within the accuracy of ESDIRK4 at rtol 10⁻⁸ (which agrees with itself at 10⁻¹¹
/// to 10⁻⁸; measured 6.4·10⁻⁵ of the largest). Generalized-α at a three-thousandth of the
/// accuracy, the plan's choice for such wheels before, read midspan's 8.7·10⁻³ off, and
/// still 1.5·10⁻³ at rtol 10⁻⁹.
#[test]
fn a_slow_wheel_of_its_own_mass_holds_the_accuracy() {
    let text = std::fs::read_to_string(common::studies_dir().join("vehicle-sprung.yaml"))
        .expect("the study")
        .replace("    speed: 27.78\n", "    speed: 5.0\n")
        .replace(
            "{name: wheel, x: 0.0}",
            "{name: wheel, x: 0.0, mass: 500.0}",
        );
    assert!(text.contains("speed: 5.0") && text.contains("mass: 500.0"));
    let scene = parse(&text);
    let (planned, converged) = common::side_by_side(
        || at_defaults(&scene),
        || run_beam(&scene, Method::Esdirk4, 1e-8, 1e-12),
    );
    let headlines = |r: &BeamRun| {
        [
            r.extremes.probes[0][3].largest_magnitude().0,
            r.envelope.a_max.0,
            r.vehicles[0].bodies[0].1.largest_magnitude().0,
        ]
    };
    for (name, (x, y)) in ["midspan", "envelope", "body"]
        .iter()
        .zip(headlines(&planned).into_iter().zip(headlines(&converged)))
    {
        let off = (x / y - 1.0).abs();
        assert!(off < 1e-3, "{name}: a_max {x} against {y}: {off:.1e}");
    }
}

/// A van on 0.35 m disk wheels with 150 kg axles at 30 m/s reaches the crest where a pothole
/// starts: pivoting over it would take the axle down at V²/a, 2571 m/s², so each wheel's
/// contact force drops at once from its load to −386 kN and the wheel flies. The deck's
/// largest acceleration from two methods that meet the drop differently, the fourth-order
/// ESDIRK (its stages read the problem) at rtol 10⁻⁷ and the plan's generalized-α, must agree
/// within the accuracy asked (measured 3.4·10⁻⁶): where the run watched the state a tenth of
/// a nanosecond past the crest, the wheel still held to the track, ESDIRK4 read 6.154 m/s²
/// against 3.675, and the rows recorded at the lift-offs held contact forces of −365 kN.
#[test]
fn a_disk_wheel_lifting_off_a_crest_pulls_on_nothing() {
    let scene = parse(
        "name: pothole
duration: 0.05
track:
  beam:
    from: [0.0, 0.0]
    to: [20.0, 0.0]
    E: 3.0e10
    G: 1.2e10
    rho: 2500
    A: 4.0
    Av: 3.3
    I: 0.8
    supports: {from: pinned, to: roller}
    damping: {ratio: 0.02, modes: [1, 2]}
  profile:
    points: [[-5.0, 0.0], [8.0, 0.0], [8.05, -0.03], [8.5, -0.03], [8.55, 0.0], [30.0, 0.0]]
vehicles:
  - name: van
    x0: -3.0
    speed: 30.0
    wheel: disk
    radius: 0.35
    bodies: [{name: body, mass: 3000.0, inertia: 4000.0, x: 1.5}]
    axles: [{name: front, x: 0.0, mass: 150.0}, {name: rear, x: 3.0, mass: 150.0}]
    springs:
      - {upper: body, lower: front, x: 0.0, k: 1.5e5, c: 4.0e3}
      - {upper: body, lower: rear, x: 3.0, k: 1.5e5, c: 4.0e3}
output:
  probes: [{name: mid, x: 10.0}]
",
    );
    let planned = at_defaults(&scene);
    let fourth = run_beam(&scene, Method::Esdirk4, 1e-7, 1e-11);
    for r in [&planned, &fourth] {
        let flights: Vec<f64> = r.vehicles[0]
            .flights
            .iter()
            .flatten()
            .map(|f| f.lift_off_t)
            .collect();
        assert_eq!(
            flights.len(),
            2,
            "each wheel lifts off at the crest: {flights:?}"
        );
        let least = r
            .rows
            .iter()
            .filter_map(|row| row.vehicles.as_ref())
            .flat_map(|v| v.rn.iter().flatten().copied())
            .fold(f64::INFINITY, f64::min);
        assert!(least >= 0.0, "a wheel pulls on the deck with {least:.0} N");
    }
    let (a, b) = (
        planned.extremes.probes[0][3].max,
        fourth.extremes.probes[0][3].max,
    );
    let off = (a / b - 1.0).abs();
    assert!(off < 1e-3, "{a} against {b} m/s²: {off:.1e}");
}

/// The sprung mass on disk wheels with 700 kg of unsprung mass, started on the deck over an
/// ISO 8608 class B profile: the wheel hops, lands on the deck and the impact moves the beam
/// through the wheel's row; the balance, with what the landings took and the drive's work
/// against their impulses, shrinks with rtol as a second-order method's error does (measured
/// 2.1·10⁻⁵ at 10⁻⁷, 4.7·10⁻⁶ at 10⁻⁸).
#[test]
fn the_energy_balance_closes_through_wheel_hops_on_the_deck() {
    let bridge = BRIDGE.replace(
        "    supports: {from: pinned, to: roller}\n",
        "    supports: {from: pinned, to: roller}\n  profile:\n    iso8608: {class: B, seed: 5, wavelengths: [0.5, 30.0]}\n",
    );
    let s = parse(&format!(
        "name: hop\nduration: 0.05\n{bridge}{}output:\n  probes: [{{name: mid, x: 12.5}}]\n",
        sprung(5750.0, 1595.0e3, 15.0, 27.78)
            .replace("    speed:", "    wheel: disk\n    radius: 0.4\n    speed:")
            .replace(
                "{name: wheel, x: 0.0}",
                "{name: wheel, x: 0.0, mass: 700.0}"
            )
    ));
    let drift = |rtol: f64| {
        let r = run_beam(&s, Method::GenAlpha, rtol, rtol * 2.5e-3);
        assert!(
            !r.warnings().iter().any(|w| w.contains("may bend by up to")),
            "a disk that follows the road's waves is not warned of"
        );
        let flights = &r.vehicles[0].flights[0];
        assert!(
            flights
                .iter()
                .any(|f| f.land_x.is_some_and(|x| x > 0.0 && x < 25.0)),
            "{flights:?}"
        );
        r.header.energy.max_rel_drift()
    };
    let (coarse, fine) = (drift(1e-7), drift(1e-8));
    eprintln!("hops on a class B deck: energy drift {coarse:.2e} at rtol 1e-7, {fine:.2e} at 1e-8");
    assert!(
        fine < coarse / 3.0 && fine < 1e-5,
        "{coarse:.2e} then {fine:.2e}"
    );
}

/// Over a speed sweep the vehicles' bodies are charted against EN 1990's comfort levels
/// (`comfort.svg`), one series per body and value of the other keys, each point the body's
/// `a_max` in `sweep.csv`.
#[test]
fn a_vehicle_sweep_charts_the_bodies_against_the_comfort_levels() {
    use rollbeam::workflows::sweep::{run_grid, write_grid, Setting};
    let spec = rollbeam::scene::SceneSpec::load(&common::studies_dir().join("vehicle-sprung.yaml"))
        .expect("the study");
    let settings = [
        Setting::parse("vehicles.car.speed=20:30:2").expect("a range"),
        Setting::parse("vehicles.car.springs.0.k=1e6:2e6:2").expect("a range"),
    ];
    let rows = run_grid(&spec, &settings, &Default::default(), false).expect("the sweep");
    let dir = std::env::temp_dir().join(format!("rollbeam-comfort-{}", std::process::id()));
    write_grid(&rows, &settings, &dir).expect("written");
    let chart = std::fs::read_to_string(dir.join("comfort.svg")).expect("the chart");
    let csv = std::fs::read_to_string(dir.join("sweep.csv")).expect("the table");
    std::fs::remove_dir_all(&dir).ok();
    assert!(chart.contains("very good (EN 1990 A2)"), "no comfort level");
    for k in ["1000000", "2000000"] {
        assert!(
            chart.contains(&format!("car.body (vehicles.car.springs.0.k = {k})")),
            "no series for k = {k}"
        );
    }
    assert!(csv
        .lines()
        .next()
        .is_some_and(|h| h.contains("car.body.a_max")));
}

/// A car on stiff tyres over D44's section at 30 m/s (hubs of 400 kg on 10⁸ N/m, ringing at up
/// to 80 Hz, faster than the steps follow: warned), until a wheel lifts off and stops the run,
/// every setting left to the plan. Each body's largest acceleration and root mean square lie
/// within the accuracy of those of its history written every 10 µs (measured 1.4·10⁻⁷ and
/// 2.1·10⁻⁶). On the watch's grid at the cutoff's pace a hub's largest acceleration came out
/// 2.0·10⁻³ low, and the root mean squares, whose last interval up to the stop the grid left
/// out, 1.4·10⁻³ low.
#[test]
fn a_car_on_stiff_tyres_reads_the_bodies_its_history_writes() {
    let beam = "name: stiff-tyres\nduration: 0.5\ntrack:\n  beam:\n    from: [0.0, 0.0]\n    to: [20.0, 0.0]\n    E: 210.0e9\n    G: 81.0e9\n    rho: 7850\n    A: 181.0e-4\n    Av: 46.8e-4\n    I: 43190.0e-8\n    depth: 0.36\n    supports: {from: pinned, to: roller}\n";
    let scene = parse(&format!(
        "{beam}vehicles:\n  - name: car\n    speed: 30.0\n    x0: 0.0\n    bodies:\n      - {{name: body, mass: 5000.0, inertia: 8000.0, x: 1.5}}\n      - {{name: h1, mass: 400.0, x: 0.0}}\n      - {{name: h2, mass: 400.0, x: 3.0}}\n    axles: [{{name: a1, x: 0.0}}, {{name: a2, x: 3.0}}]\n    springs:\n      - {{upper: body, lower: h1, x: 0.0, k: 4.0e5, c: 8.0e3}}\n      - {{upper: body, lower: h2, x: 3.0, k: 4.0e5, c: 8.0e3}}\n      - {{upper: h1, lower: a1, x: 0.0, k: 1.0e8}}\n      - {{upper: h2, lower: a2, x: 3.0, k: 1.0e8}}\noutput:\n  interval: 0.00001\n  probes: [{{name: mid, x: 10.0}}]\n",
    ));
    reads_the_bodies_its_history_writes(&at_defaults(&scene), |_, own| own);
}

/// A railway car at 1000 m/s, whose rear wheelset loses contact at the near abutment and stops
/// the run, its front bogie peaking as the second wheelset leaves the far abutment, every
/// setting left to the plan. Each body's largest acceleration and root mean square lie within
/// the accuracy of those of its history written every 2 µs, against the largest of the car's
/// (a body's own barely moves; measured 2.8·10⁻⁷ and 3.8·10⁻⁶). On the deck's grid of samples
/// the front bogie's peak, between the last sample and a wheel's kink, came out 5.8·10⁻³ low,
/// and the rear bogie's root mean square, over the steep rise of its last tenth of a
/// millisecond, 7.7·10⁻³ high; where the vehicles' accelerations were generalized-α's own, the
/// rear bogie's peak at the lift-off read 1.3·10⁻³ high.
#[test]
fn a_railway_car_at_speed_reads_the_bodies_its_history_writes() {
    let text = one_railcar_text(1000.0, 0.0).replace("output:\n", "output:\n  interval: 2.0e-6\n");
    let run = at_defaults(&parse(&text));
    assert!(
        run.vehicles[0].lost_contact.is_some(),
        "the run stops at the lift-off"
    );
    reads_the_bodies_its_history_writes(&run, |largest, _| largest);
}

/// Each body's largest acceleration and root mean square in the summary against those of its
/// history (the largest row, and the trapezoidal rule over the rows), within 10⁻³ of the scale
/// `scale` gives of (the largest of the bodies', the body's own).
fn reads_the_bodies_its_history_writes(r: &BeamRun, scale: impl Fn(f64, f64) -> f64) {
    let rows: Vec<_> = r
        .rows
        .iter()
        .map(|row| {
            let v = row.vehicles.as_ref().expect("the car");
            (
                row.t,
                v.bodies[0].iter().map(|b| b[2]).collect::<Vec<f64>>(),
            )
        })
        .collect();
    let written: Vec<(f64, f64)> = (0..r.vehicles[0].bodies.len())
        .map(|k| {
            let peak = rows.iter().map(|(_, a)| a[k].abs()).fold(0.0, f64::max);
            let squares: f64 = rows
                .windows(2)
                .map(|w| 0.5 * (w[1].0 - w[0].0) * (w[0].1[k].powi(2) + w[1].1[k].powi(2)))
                .sum();
            (
                peak,
                (squares / (rows[rows.len() - 1].0 - rows[0].0)).sqrt(),
            )
        })
        .collect();
    let largest = |f: fn(&(f64, f64)) -> f64| written.iter().map(f).fold(0.0, f64::max);
    let (a_largest, rms_largest) = (largest(|w| w.0), largest(|w| w.1));
    for ((name, a, rms), (peak_written, rms_written)) in r.vehicles[0].bodies.iter().zip(&written) {
        let peak = a.largest_magnitude().0;
        assert!(
            (peak - peak_written).abs() < 1e-3 * scale(a_largest, *peak_written),
            "{name}: a_max {peak} reported, {peak_written} written"
        );
        assert!(
            (rms - rms_written).abs() < 1e-3 * scale(rms_largest, *rms_written),
            "{name}: a_rms {rms} reported, {rms_written} written"
        );
    }
}

/// The accuracy the scene asks for (10⁻³ at the defaults) holds for every number the run
/// reports of its vehicles, not only the deck's: the truck over the raised deck (ramps, a
/// pitching body on hubs on tyres) at the defaults against the same scene at rtol 10⁻¹⁰, each
/// body's largest acceleration and root mean square against its own converged value, each
/// wheel's extreme contact forces against its static load (measured at most 4.9·10⁻⁷, a
/// hub's a_rms).
#[test]
fn every_vehicle_number_holds_the_accuracy_asked() {
    let scene = load("vehicle-truck.yaml");
    let (fast, converged) = (
        at_defaults(&scene),
        run_beam(&scene, Method::GenAlpha, 1e-10, 1e-15),
    );
    let accuracy = 1e-3;
    let statics = &scene.beam().expect("a beam").vehicles[0].static_loads;
    for (v, c) in fast.vehicles.iter().zip(&converged.vehicles) {
        for ((name, a, rms), (_, ca, crms)) in v.bodies.iter().zip(&c.bodies) {
            let (peak, cpeak) = (a.largest_magnitude().0, ca.largest_magnitude().0);
            assert!(
                (peak / cpeak - 1.0).abs() < accuracy,
                "{name}: a_max {peak} against {cpeak}"
            );
            assert!(
                (rms / crms - 1.0).abs() < accuracy,
                "{name}: a_rms {rms} against {crms}"
            );
        }
        for (((name, r), (_, cr)), p) in v.axles.iter().zip(&c.axles).zip(statics) {
            for (x, y) in [(r.min, cr.min), (r.max, cr.max)] {
                assert!((x - y).abs() < accuracy * p, "{name}: {x} against {y}");
            }
        }
    }
}

/// Biggs' sprung mass at 10 000 and 1 000 000 m/s: on the deck for 2.5 ms and 25 µs, short
/// against the bridge's first period (0.21 s), an impulse that leaves the deck vibrating at a
/// small share of the static deflection under the vehicle. The plan measures each step's error
/// (atol = rtol × a size) against that response, the static deflection times (2/π) ω₁ T
/// (`analysis::discretisation::passage_share`): the size lies within 10 % of the largest |w| at
/// midspan converged (ESDIRK4 at rtol 10⁻¹⁰), where the static deflection is 21 and 2100 times
/// it, so an atol from it would let through errors as large as the response. A quarter of the
/// first period after the crossing holds the first swing.
#[test]
fn a_crossing_shorter_than_the_first_period_is_measured_against_its_impulse() {
    for speed in [1.0e4, 1.0e6] {
        let s = scene("impulse", 0.06, &sprung(5750.0, 1595.0e3, 0.0, speed));
        let planned = at_defaults(&s).header;
        let size = planned.atol / planned.rtol;
        let converged = mid_headlines(&run_beam(&s, Method::Esdirk4, 1e-10, 1e-20));
        let largest = converged[0].abs().max(converged[1].abs());
        assert!(
            (size / largest - 1.0).abs() < 0.1,
            "{speed} m/s: atol measured against {size:e} m, the response is {largest:e} m"
        );
    }
}

/// Biggs' sprung mass at 100, 1000 and 10 000 m/s, and at 10⁶ m/s (on the deck for 25 µs), at
/// the defaults against the same scene by ESDIRK4 at rtol 10⁻¹⁰: midspan's extreme
/// deflections, its residual amplitude and the envelope's extreme deflections within the
/// accuracy of the largest |w|, midspan's and the envelope's extreme rotations within it of
/// the largest |φ|, midspan's largest acceleration within it of its own (measured 3.3·10⁻⁷
/// and 1.5·10⁻¹⁰ at 100 and 10⁶ m/s), the body's largest acceleration and root mean square
/// within twice the accuracy of their own (at 10⁶ m/s the body barely moves, 6.6·10⁻⁵ m/s²,
/// measured 3.9·10⁻⁷ off), and the energy balance within the accuracy. At 100 m/s the deck's largest
/// acceleration comes in the free vibration after the wheel has left, which carries every
/// step's phase error; at 10⁶ m/s the acceleration under the wheel is a pulse as short as its
/// passage, between samples at the cutoff's pace, and the deck's deflection turns sharply
/// where it enters and leaves, which a parabola through samples on both sides overshoots. A
/// wheel that crosses the deck faster than the modes the rotations carry vibrate rings them
/// all at once: at a thousandth of the accuracy the rotation at a support came out 4.9·10⁻³ of
/// the largest off at 1000 m/s and 1.6·10⁻³ at 10 000, and the balance drifted by 2.1·10⁻²
/// at 10⁶ m/s; with rtol tightened by 150 m/s over the speed, 4.4·10⁻⁴, 1.6·10⁻⁴ and 8.8·10⁻⁸.
#[test]
fn a_sprung_mass_at_speed_holds_the_accuracy_on_every_number() {
    let accuracy = 1e-3;
    for (speed, duration) in [(100.0, 1.0), (1.0e3, 1.0), (1.0e4, 1.0), (1.0e6, 0.06)] {
        let s = scene("fast", duration, &sprung(5750.0, 1595.0e3, 0.0, speed));
        let (fast, converged) = common::side_by_side(
            || at_defaults(&s),
            || run_beam(&s, Method::Esdirk4, 1e-10, 1e-20),
        );
        let (m, c) = (mid_headlines(&fast), mid_headlines(&converged));
        let (got, want) = (extreme_w_and_phi(&fast), extreme_w_and_phi(&converged));
        let w_scale = want[0].iter().fold(0.0_f64, |l, v| l.max(v.abs()));
        for (kind, (x, y)) in ["w", "phi"].iter().zip(got.iter().zip(&want)) {
            let scale = y.iter().fold(0.0_f64, |l, v| l.max(v.abs()));
            for (a, b) in x.iter().zip(y) {
                assert!(
                    (a - b).abs() < accuracy * scale,
                    "{speed} m/s: {kind} {a:e} against {b:e}"
                );
            }
        }
        assert!(
            (m[2] - c[2]).abs() < accuracy * w_scale,
            "{speed} m/s: residual {:e} against {:e}",
            m[2],
            c[2]
        );
        assert!(
            (m[3] / c[3] - 1.0).abs() < accuracy,
            "{speed} m/s: a_max {} against {}",
            m[3],
            c[3]
        );
        let ((_, a, rms), (_, ca, crms)) = (
            &fast.vehicles[0].bodies[0],
            &converged.vehicles[0].bodies[0],
        );
        let (peak, cpeak) = (a.largest_magnitude().0, ca.largest_magnitude().0);
        assert!(
            (peak / cpeak - 1.0).abs() < 2.0 * accuracy && (rms / crms - 1.0).abs() < 2.0 * accuracy,
            "{speed} m/s: the body's a_max {peak:e} against {cpeak:e}, a_rms {rms:e} against {crms:e}"
        );
        let drift = fast.header.energy.max_rel_drift();
        assert!(
            drift < accuracy,
            "{speed} m/s: the balance drifts by {drift:.1e}"
        );
    }
}

/// The support reactions count the modes up to the acceleration's cutoff (43 Hz, three modes
/// on Biggs' bridge) with their inertia and those above it at their static response to what
/// acts (the mode-acceleration method; `run/beam/reactions.rs`). Biggs' sprung mass at its
/// speed: each end's vertical reaction at every output row at the defaults (14 modes) within
/// the accuracy of the largest against ESDIRK4 at rtol 10⁻¹⁰ (measured 1.5·10⁻⁶; the modes
/// above the cutoff taken with their inertia, the steps' error reaches 6.2·10⁻³ of it, a
/// support's shear weighing mode k as about k³); on 28 modes within a hundredth of the
/// accuracy (measured 2.9·10⁻⁷, against 1.9·10⁻³ with their inertia); and on the linear mesh
/// of 8 elements, whose reactions come from the residual's solve with K₀ instead of the modes'
/// static amplitudes, within the quarter of the accuracy the plan keeps a mesh's shapes to
/// (measured 4.9·10⁻⁵).
#[test]
fn the_support_reactions_hold_the_accuracy_whatever_the_model() {
    let accuracy = 1e-3;
    let on = |model: &str| {
        let riders = sprung(5750.0, 1595.0e3, 0.0, 27.78);
        let bridge = BRIDGE.replace("    supports:", &format!("{model}    supports:"));
        parse(&format!(
            "name: reactions\nduration: 1.0\n{bridge}{riders}output:\n  probes: [{{name: mid, x: 12.5}}]\n"
        ))
    };
    let s = on("");
    let converged = run_beam(&s, Method::Esdirk4, 1e-10, 1e-20);
    let more_modes = run_beam(
        &on("    model: modal\n    modes: 28\n"),
        Method::Esdirk4,
        1e-10,
        1e-20,
    );
    let mesh = at_defaults(&on("    model: linear\n    elements: 8\n"));
    for (what, r, tolerance) in [
        ("the defaults", at_defaults(&s), accuracy),
        ("28 modes", more_modes, 0.01 * accuracy),
        ("the linear mesh", mesh, 0.25 * accuracy),
    ] {
        assert_eq!(r.rows.len(), converged.rows.len(), "{what}");
        for end in 0..2 {
            let fy = |r: &BeamRun| -> Vec<f64> {
                r.rows.iter().map(|row| row.reactions[end][1]).collect()
            };
            let (got, want) = (fy(&r), fy(&converged));
            let scale = want.iter().fold(0.0_f64, |l, v| l.max(v.abs()));
            let worst = got
                .iter()
                .zip(&want)
                .fold(0.0_f64, |l, (a, b)| l.max((a - b).abs()));
            assert!(
                worst < tolerance * scale,
                "{what}: support {end}'s reaction {:.1e} of its largest off",
                worst / scale
            );
        }
    }
}

/// Midspan's least and largest w, and the envelope's, then the same of φ.
fn extreme_w_and_phi(r: &BeamRun) -> [[f64; 4]; 2] {
    let [_, w, phi, _] = r.extremes.probes[0];
    let e = &r.envelope;
    let least = |f: fn(&rollbeam::beam::PointDisplacement) -> f64| {
        e.min.iter().map(f).fold(f64::INFINITY, f64::min)
    };
    let largest = |f: fn(&rollbeam::beam::PointDisplacement) -> f64| {
        e.max.iter().map(f).fold(f64::NEG_INFINITY, f64::max)
    };
    [
        [w.min, w.max, least(|p| p.w), largest(|p| p.w)],
        [phi.min, phi.max, least(|p| p.phi), largest(|p| p.phi)],
    ]
}

/// The first railway car of `vehicle-railcar.yaml` alone, starting at `speed` m/s and
/// speeding up at `acceleration` m/s², without shapes.
fn one_railcar(speed: f64, acceleration: f64) -> Scene {
    parse(&one_railcar_text(speed, acceleration))
}

/// The scene file of [`one_railcar`].
fn one_railcar_text(speed: f64, acceleration: f64) -> String {
    let text = std::fs::read_to_string(common::studies_dir().join("vehicle-railcar.yaml"))
        .expect("the study");
    let (cars, output) = (
        text.find("  - name: car2").expect("a second car"),
        text.find("output:").expect("an output section"),
    );
    let one: String = format!("{}{}", &text[..cars], &text[output..])
        .lines()
        .filter(|l| !l.trim_start().starts_with("shapes:"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert!(one.contains("    speed: 100.0\n"), "the study's speed");
    one.replace(
        "    speed: 100.0\n",
        &format!("    speed: {speed:?}\n    acceleration: {acceleration:?}\n"),
    )
}

/// Wheels with a mass of their own (a railway car's wheelsets) take an impulse wherever the
/// deck turns under them, at its ends above all, and it grows with the speed: generalized-α
/// at a three-thousandth of the accuracy read one car's least rotation of the deck at 600 m/s
/// 1.5·10⁻³ off, at 3000 m/s its rear bogie's largest acceleration 13 times the converged. At
/// 300, 1000 and 3000 m/s the defaults (ESDIRK4 at a thousandth of the accuracy times 150 m/s
/// over the speed) hold every number the car
/// reports against the same scene by ESDIRK4 at rtol 10⁻¹⁰, each within the accuracy of its
/// family's scale (measured at most 5.4·10⁻⁵): the bodies' largest accelerations
/// and root mean squares against the largest of the car's converged (a bogie over the far
/// abutment barely moves, and its own value is not settled even between the two converged
/// methods: 5.7·10⁻³ apart at 3000 m/s), each wheel's contact force against its static load,
/// midspan's extremes of w and of φ, each pair against its larger. A car that speeds up on
/// the deck, entering at 300 m/s and leaving at 3000 (at 1.255·10⁵ m/s²), holds the accuracy
/// too. Past 3000 m/s, the fastest measured, the scene says so.
#[test]
fn a_railway_car_holds_the_accuracy_at_speed() {
    let accuracy = 1e-3;
    for (speed, acceleration) in [(300.0, 0.0), (1000.0, 0.0), (3000.0, 0.0), (300.0, 1.255e5)] {
        let scene = one_railcar(speed, acceleration);
        let (fast, converged) = common::side_by_side(
            || at_defaults(&scene),
            || run_beam(&scene, Method::Esdirk4, 1e-10, 1e-13),
        );
        let statics = &scene.beam().expect("a beam").vehicles[0].static_loads;
        let (v, c) = (&fast.vehicles[0], &converged.vehicles[0]);
        let largest =
            |f: &dyn Fn(&(String, _, f64)) -> f64| c.bodies.iter().map(f).fold(0.0, f64::max);
        let (a_scale, rms_scale) = (
            largest(&|(_, a, _)| a.largest_magnitude().0),
            largest(&|(_, _, rms)| *rms),
        );
        for ((name, a, rms), (_, ca, crms)) in v.bodies.iter().zip(&c.bodies) {
            let (peak, cpeak) = (a.largest_magnitude().0, ca.largest_magnitude().0);
            assert!(
                (peak - cpeak).abs() < accuracy * a_scale
                    && (rms - crms).abs() < accuracy * rms_scale,
                "{speed} m/s, {name}: a_max {peak} against {cpeak}, a_rms {rms} against {crms}"
            );
        }
        for (((name, r), (_, cr)), p) in v.axles.iter().zip(&c.axles).zip(statics) {
            for (x, y) in [(r.min, cr.min), (r.max, cr.max)] {
                assert!(
                    (x - y).abs() < accuracy * p,
                    "{speed} m/s, {name}: {x} against {y}"
                );
            }
        }
        let mid = |r: &BeamRun| {
            let [_, w, phi, _] = r.extremes.probes[0];
            [[w.min, w.max], [phi.min, phi.max]]
        };
        for (pair, converged) in mid(&fast).iter().zip(mid(&converged)) {
            let scale = converged[0].abs().max(converged[1].abs());
            for (x, y) in pair.iter().zip(converged) {
                assert!(
                    (x - y).abs() < accuracy * scale,
                    "{speed} m/s: midspan {x:e} against {y:e}"
                );
            }
        }
    }
    let warned = |speed: f64| {
        one_railcar(speed, 0.0)
            .beam()
            .expect("a beam")
            .warnings()
            .iter()
            .any(|w| w.contains("mass of their own"))
    };
    assert!(!warned(3000.0) && warned(6000.0));
}

/// A disk wheel rolling up a face of slope s = tan β towards the corner where a pothole starts
/// rests on the face until its contact reaches the corner, at the centre X_c = x_c − a sin β,
/// and pivots on the corner after: its centre rises at s before and at
/// −(X − x_c)/√(a² − (X − x_c)²) after, which is s at X_c. Near X_c the face and the corner
/// lift the centre to heights round-off cannot tell apart; taking whichever came out higher,
/// the contact flickered onto the corner and back, and with it the axle's curvature, from the
/// face's to the corner's 1/a: a van's wheel at 30 m/s read a contact force of −366 kN at one
/// such instant of an ESDIRK4 run at rtol 10⁻¹⁰. At 2000 centres within 10⁻⁸ m of X_c on
/// either side, over the deck at rest: one switch, onto the corner, within a billionth of the
/// radius of X_c (the side a contact is on is settled that far ahead of the centre), and the
/// rise within 10⁻⁸ of the closed form.
#[test]
fn a_disk_wheel_reaches_a_corner_on_its_face_and_pivots_past_it() {
    let (a, corner, slope) = (0.35, 8.0, 1e-3_f64);
    let profile = format!("points: [[-5.0, {:?}], [{corner:?}, 0.0], [8.05, -0.03], [8.5, -0.03], [8.55, 0.0], [30.0, 0.0]]", -slope * (corner + 5.0));
    on_a_disk_wheel(&profile, a, (3000.0, 1.5e5, 1.0), |on, q, _| {
        let reaches = corner - a * slope.atan().sin();
        let mut switches = Vec::new();
        let mut was_on_the_corner = false;
        for k in 0..=2000 {
            // At 1 m/s from x0 = 0 the wheel's centre is at t.
            let centre = reaches + 1e-8 * (k as f64 / 1000.0 - 1.0);
            let contact = on.contacts(centre, q)[0].disk.expect("a disk wheel");
            let rise = if centre < reaches {
                slope
            } else {
                -(centre - corner) / (a * a - (centre - corner).powi(2)).sqrt()
            };
            assert!(
                (contact.rise - rise).abs() < 1e-8,
                "{:e} m past X_c: rising {:e}, not {rise:e}",
                centre - reaches,
                contact.rise
            );
            if contact.pivot != was_on_the_corner {
                switches.push((centre - reaches, contact.pivot));
                was_on_the_corner = contact.pivot;
            }
        }
        assert!(
            switches.len() == 1 && switches[0].1 && switches[0].0.abs() <= 1.01e-9 * a,
            "onto the corner (true) and off it (false), by the centre's distance past X_c: {switches:?}"
        );
    });
}

/// A disk wheel rests on the crest under it that lifts its centre highest, H(X) = max over x
/// of r(x) + √(a² − (x − X)²). On a profile that bends faster than the disk (an ISO 8608
/// class H road of wavelengths down to 0.1 m under a 0.4 m wheel: its curvature reaches tens
/// of 1/m against the disk's 2.5) H has several local maxima within the wheel's reach. Over
/// the deck at rest, at 400 places, the contact the run uses against a scan of the reach at
/// 4000 points (a 500th of the shortest wave) refined by golden section: the same height, to
/// 10⁻⁹ m (the search stops at a billionth of the radius).
#[test]
fn a_disk_wheel_rests_on_the_highest_crest_of_a_rough_road() {
    let a = 0.4;
    let profile = "iso8608: {class: H, seed: 3, wavelengths: [0.1, 50.0]}";
    on_a_disk_wheel(profile, a, (5750.0, 1595.0e3, 27.78), |on, q, setup| {
        let speed = 27.78;
        let highest = |centre: f64| -> f64 {
            let lift = |x: f64| {
                let u = (x - centre) / a;
                setup.profile.at(x, x)[0] + a * (1.0 - u * u).max(0.0).sqrt()
            };
            let n = 4000;
            let at = |k: usize| centre + a * (2.0 * k as f64 / n as f64 - 1.0);
            let best = (0..=n)
                .max_by(|&i, &j| lift(at(i)).total_cmp(&lift(at(j))))
                .unwrap();
            let (mut lo, mut hi) = (at(best.saturating_sub(1)), at((best + 1).min(n)));
            let golden = 0.5 * (5.0_f64.sqrt() - 1.0);
            for _ in 0..100 {
                let (m1, m2) = (hi - golden * (hi - lo), lo + golden * (hi - lo));
                if lift(m1) < lift(m2) {
                    lo = m1;
                } else {
                    hi = m2;
                }
            }
            lift(0.5 * (lo + hi)) - a
        };
        let mut worst: (f64, f64) = (0.0, 0.0);
        for k in 0..400 {
            let centre = 1.0 + 23.0 * k as f64 / 400.0;
            let contacts = on.contacts(centre / speed, q);
            let rest = contacts[0].disk.expect("a disk wheel").rest;
            let off = (rest - highest(centre)).abs();
            if off > worst.0 {
                worst = (off, centre);
            }
        }
        assert!(
            worst.0 < 1e-9,
            "{:.3e} m below the highest crest at X = {}",
            worst.0,
            worst.1
        );
    });
}

/// A sprung mass (`mass` kg on `k` N/m at `speed` m/s) on a disk wheel of radius `a`, over the
/// deck at rest whose track has the scene's `profile:` entry `profile`: its model on the beam,
/// the deck's unknowns and the scene, handed to `check`.
fn on_a_disk_wheel(
    profile: &str,
    a: f64,
    (mass, k, speed): (f64, f64, f64),
    check: impl FnOnce(
        &rollbeam::coupling::vehicles::VehiclesOnBeam,
        &[f64],
        &rollbeam::scene::BeamScene,
    ),
) {
    use rollbeam::beam::dynamics::LoadedBeam;
    use rollbeam::beam::Beam;
    use rollbeam::coupling::vehicles::VehiclesOnBeam;
    let bridge = BRIDGE.replace(
        "    supports: {from: pinned, to: roller}\n",
        &format!("    supports: {{from: pinned, to: roller}}\n  profile:\n    {profile}\n"),
    );
    let s = parse(&format!(
        "name: disk-wheel\nduration: 0.1\n{bridge}{}output:\n  probes: [{{name: mid, x: 12.5}}]\n",
        sprung(mass, k, 0.0, speed).replace(
            "    speed:",
            &format!("    wheel: disk\n    radius: {a}\n    speed:")
        )
    ));
    let setup = s.beam().expect("a beam scene");
    let beam = Beam::shared(&setup.beam);
    let loaded = LoadedBeam::new(&beam, &[], None, None, None);
    let patch = rollbeam::coupling::patch::dispersed_half_width(setup.beam.depth);
    let on = VehiclesOnBeam::new(&loaded, &setup.vehicles, &setup.profile, patch, beam.dim())
        .expect("the vehicle on the beam");
    check(&on, &vec![0.0; beam.dim()], setup);
}

/// The truck on disk wheels (`truck_on_disks`) from x0 for `duration` s, over the ISO 8608
/// road `class` (its class, seed and wavelengths).
fn truck_on_a_rough_road(speed: f64, axle_mass: f64, class: &str, x0: f64, duration: f64) -> Scene {
    let text = truck_on_disks(speed, axle_mass, &format!("{{class: {class}}}"))
        .replace("duration: 1.0", &format!("duration: {duration}"))
        .replace("x0: -10.0", &format!("x0: {x0}"));
    parse(&text)
}

/// Each wheel's least and largest contact force of the run `fast` against those of ESDIRK4 at
/// rtol 10⁻⁸ (whose balance closes to a few 10⁻⁷ on these scenes): within the accuracy (10⁻³) of
/// the wheel's static load, the scale the contact forces are held to.
fn contact_forces_converge(scene: &Scene, fast: &BeamRun) {
    let converged = run_beam(scene, Method::Esdirk4, 1e-8, 4e-12);
    let accuracy = 1e-3;
    let statics = &scene.beam().expect("a beam").vehicles[0].static_loads;
    let pairs = fast.vehicles[0]
        .axles
        .iter()
        .zip(&converged.vehicles[0].axles);
    for (((name, r), (_, cr)), p) in pairs.zip(statics) {
        for (x, y) in [(r.min, cr.min), (r.max, cr.max)] {
            assert!((x - y).abs() < accuracy * p, "{name}: {x} against {y}");
        }
    }
}

/// The truck's study (`studies/vehicle-truck.yaml`) at `speed` on 0.4 m disk wheels whose
/// axles weigh `axle_mass`, over the ISO 8608 road `iso8608` instead of the raised deck.
fn truck_on_disks(speed: f64, axle_mass: f64, iso8608: &str) -> String {
    let path = common::studies_dir().join("vehicle-truck.yaml");
    std::fs::read_to_string(path)
        .expect("the truck's scene")
        .replace(
            "speed: 19.4444",
            &format!("speed: {speed}\n    wheel: disk\n    radius: 0.4"),
        )
        .replace(
            "{name: front, x: 0.0}",
            &format!("{{name: front, x: 0.0, mass: {axle_mass}}}"),
        )
        .replace(
            "{name: rear, x: 5.0}",
            &format!("{{name: rear, x: 5.0, mass: {axle_mass}}}"),
        )
        .replace(
            "points: [[-1.0, 0.0], [0.0, 0.01], [25.0, 0.01], [26.0, 0.0]]",
            &format!("iso8608: {iso8608}"),
        )
}

/// A truck on disk wheels (0.4 m) over axles of 1 kg at 300 m/s on an ISO class D road of
/// waves from 0.2 to 5 m, every setting left to the plan. Each crest sharper than the disk
/// follows lifts the wheel for the 7.5 to 24 mm of travel it pivots over it (λ/27 to λ/8),
/// shorter than the steps (about 16 mm), which follow the hubs' and the deck's motion. Looked
/// for at the steps' ends only, the lift-offs there were stepped over and the wheels held to
/// the road pulling on it, down to −1.3 kN against a static 60 kN. Now no wheel's contact force
/// reads below zero, the run lands every flight it lifts off for, and none is warned of; a
/// road bending faster than the disk is.
#[test]
fn a_wheel_over_sharp_crests_at_speed_never_pulls_on_the_road() {
    let text = truck_on_disks(300.0, 1.0, "{class: D, seed: 2, wavelengths: [0.2, 5.0]}")
        .replace("duration: 1.0", "duration: 0.01");
    let run = at_defaults(&parse(&text));
    let flights: usize = run.vehicles[0].flights.iter().map(Vec::len).sum();
    assert!(
        flights > 100,
        "the wheels hop over the crests ({flights} flights)"
    );
    for (axle, range) in &run.vehicles[0].axles {
        assert!(
            range.min >= 0.0,
            "wheel {axle} pulls on the road with {} N",
            range.min
        );
    }
    let warnings = run.warnings();
    let pulling = warnings
        .iter()
        .filter(|w| w.contains("pulled on the track"));
    assert_eq!(pulling.count(), 0);
    assert!(
        warnings.iter().any(|w| w.contains("may bend by up to")),
        "the road bends faster than the disk, whose crests are met as impacts: {warnings:?}"
    );
}

/// A disk wheel on a road that bends faster than it (ISO class H waves of 0.1-5 m under 0.4 m
/// disks on the truck's 100 kg axles, at 30 m/s over the last 10 m of the deck) rests on one
/// crest until the crest ahead comes level, then meets it: the axle lands on it plastically,
/// its impulse shared with the deck, and the impact's loss booked. Carried from crest to crest
/// at once instead, without the impact, the balance drifted by 0.16 of the energies' scale;
/// now it closes to a tenth of the accuracy (4.5·10⁻⁶ measured), the fourth-order steps at
/// rtol 10⁻⁶ and the impacts located to round-off. Both wheels start on crests they cannot
/// hold at that speed, and fly from the first row: no contact force below zero is read (the
/// first row read −261 kN, taken before the lift-off at t = 0).
#[test]
fn a_disk_wheel_meets_each_crest_ahead_as_an_impact_and_the_balance_closes() {
    let text = truck_on_disks(30.0, 100.0, "{class: H, seed: 2, wavelengths: [0.1, 5.0]}")
        .replace("duration: 1.0", "duration: 0.02")
        .replace("x0: -10.0", "x0: 20.0");
    let run = at_defaults(&parse(&text));
    let drift = run.header.energy.max_rel_drift();
    eprintln!("disks meeting class H crests, 100 kg axles: energy drift {drift:.2e}");
    assert!(drift < 1e-4, "the balance drifts by {drift:.2e}");
    for (axle, range) in &run.vehicles[0].axles {
        assert!(
            range.min >= 0.0,
            "wheel {axle} pulls on the road with {} N at t = {} s",
            range.min,
            range.min_t
        );
    }
}

/// The truck on 0.4 m disk wheels over 100 kg axles at 30 m/s on an ISO class H road of waves
/// 0.1-5 m (seed 3), on the rigid road past the deck: the wheels fly from crest to crest. A
/// wheel that lands holds to the crest it landed on, as after every step: searched afresh
/// within the step after a landing, the rear disk's contact passed to a crest rising ahead
/// without its impact, the balance drifted by 0.22 of its scale and the rear wheel's largest
/// contact force read 328 kN against 483 kN converged. Now the balance closes within a tenth of
/// the accuracy (3.2·10⁻⁵ measured) and each wheel's extreme contact forces lie within the
/// accuracy of its static load of the run at rtol 10⁻⁸ (measured 3 N of 60 kN).
#[test]
fn a_disk_wheel_landing_on_a_rough_road_holds_to_its_crest() {
    let scene = truck_on_a_rough_road(
        30.0,
        100.0,
        "H, seed: 3, wavelengths: [0.1, 5.0]",
        30.0,
        0.3,
    );
    let fast = at_defaults(&scene);
    let drift = fast.header.energy.max_rel_drift();
    eprintln!("disks landing on a class H road: energy drift {drift:.2e}");
    assert!(drift < 1e-4, "the balance drifts by {drift:.2e}");
    contact_forces_converge(&scene, &fast);
}

/// The same truck and road at seed 10: the rear wheel lands and then rolls up a crest whose
/// contact force rises from 191 to 417 kN within 0.8 ms, to a crest meeting that cuts the
/// next step to 36 µs. Between two steps the largest and least contact forces are looked for
/// on the parabola through the last sample before the junction and the first two after it,
/// whose solution before the junction is no longer at hand; that far from its closely spaced
/// samples the parabola turned at −107 kN where the solution bore 200 kN, and the run
/// reported a wheel pulling on the road and a lift-off stepped over that the run at rtol
/// 10⁻⁸ does not have. Now each wheel's extreme contact forces lie within the accuracy of its
/// static load of that run's (measured 0.6 N of 60 kN).
#[test]
fn a_contact_force_between_two_steps_is_read_where_its_samples_hold_it() {
    let scene = truck_on_a_rough_road(
        30.0,
        100.0,
        "H, seed: 10, wavelengths: [0.1, 5.0]",
        30.0,
        0.05,
    );
    let fast = at_defaults(&scene);
    contact_forces_converge(&scene, &fast);
}

/// The truck on 0.4 m disk wheels over 500 kg axles at 50 m/s on an ISO class B road of
/// waves 0.2-5 m (seed 23), from x0 = 26 m past the deck: the wheels hop from crest to crest,
/// and a landing restarts the watch of their contact forces at a force still rising to its
/// peak. Watched in the deck's pairs of samples alone, that peak fell between samples where
/// no parabola turns: the front wheel's largest force read 132 N (2·10⁻³ of its static load)
/// below the run at rtol 10⁻⁸, and over the whole crossing from x0 = 5 m the rear's 10 kN
/// low. On a random road the vehicles' values are also watched at the pace the events are
/// looked at (`crest_pace`); each wheel's extremes now lie within the accuracy of its static
/// load of the converged run's (measured 1 N).
#[test]
fn a_contact_force_rising_past_a_landing_is_read_at_its_peak() {
    let scene = truck_on_a_rough_road(
        50.0,
        500.0,
        "B, seed: 23, wavelengths: [0.2, 5.0]",
        26.0,
        0.05,
    );
    let fast = at_defaults(&scene);
    contact_forces_converge(&scene, &fast);
}

/// The truck on 0.4 m disk wheels with 1 kg axles at 30 m/s over ISO class D waves of 0.2-5 m,
/// from the approach across the deck. Where a hollow bends nearly as fast as the disk its
/// contact sweeps across it within a fraction of a step (at up to 60 times the speed), and the
/// drive's power swings with it, unseen by steps that follow the bodies: booked by Simpson's
/// rule over each step the balance drifts by 1.4·10⁻³. At one hollow a crest rises ahead,
/// comes level with the one the rear disk rests on and swallows it within 0.2 mm of travel,
/// between two looks of the events: a disk carried onto it without its impact drifts by
/// 9.2·10⁻⁴. The ledger integrates the powers within each step, and the disk follows its own
/// crest and knows when it has gone, so that the impact is found where the crests came level:
/// the balance closes within a tenth of the accuracy (1.2·10⁻⁵ measured).
#[test]
fn a_disk_wheel_sweeping_hollows_keeps_the_balance() {
    let text = truck_on_disks(30.0, 1.0, "{class: D, seed: 2, wavelengths: [0.2, 5.0]}")
        .replace("duration: 1.0", "duration: 0.02");
    let run = at_defaults(&parse(&text));
    let drift = run.header.energy.max_rel_drift();
    eprintln!("disks sweeping class D hollows, 1 kg axles: energy drift {drift:.2e}");
    assert!(drift < 1e-4, "the balance drifts by {drift:.2e}");
}

/// `rollbeam static` with a vehicle parked on the deck loads it with the wheels' loads at
/// rest, as `initial: static` does: Biggs' sprung mass standing at midspan deflects the
/// Euler–Bernoulli bridge by P L³/(48 EI) to 10⁻⁵ (the shear the scene's stiff section keeps
/// adds 10⁻⁶, the geometrically exact beam's axial terms less; 6·10⁻⁷ is measured), the
/// bearings carry the weight to 10⁻⁷ (read from the internal forces of a section whose shear
/// stiffness is held at 10⁸ times E I/L², which cost digits: 1.1·10⁻⁸ is measured), and
/// standing before the deck it loads nothing.
#[test]
fn a_vehicle_parked_on_the_deck_weighs_on_it_statically() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/studies/vehicle-sprung.yaml"
    ))
    .expect("the sprung mass's scene");
    let static_w = |x0: f64| -> (f64, f64) {
        let scene = parse(&text.replace("speed: 27.78", &format!("speed: 27.78\n    x0: {x0}")));
        let file =
            rollbeam::workflows::analyses::static_solution(&scene, scene.beam().expect("a beam"))
                .expect("static solution");
        (
            file.probes["mid"].w,
            file.reactions["from"].fy + file.reactions["to"].fy,
        )
    };
    let p = 5750.0 * 9.81;
    let (w, carried) = static_w(12.5);
    let closed = -p * 25.0_f64.powi(3) / (48.0 * 2.87e9 * 2.9);
    assert!((w / closed - 1.0).abs() < 1e-5, "w = {w} against {closed}");
    assert!(
        (carried / p - 1.0).abs() < 1e-7,
        "the bearings carry {carried} N of {p}"
    );
    assert_eq!(static_w(-10.0), (0.0, 0.0));
}

/// An unsprung mass rides the deck as a moving mass does, and the deck's accelerations under it
/// move with the modes kept: a 40 t body on an 8 Hz suspension over a 400 kg wheel at 10 m/s
/// across a soft 15 m steel beam of 4.3 t (93 mm under the vehicle). On twice the 22 modes
/// planned, midspan's largest acceleration and the wheel's largest contact force move by more
/// than the accuracy (measured 3 % and 2 %), and the scene says so; the same vehicle on a
/// massless wheel is not warned.
#[test]
fn unsprung_masses_on_the_modal_beam_are_said_to_move_with_the_modes() {
    let soft = |wheel: f64, beam: &str| {
        parse(&format!(
            "name: soft-steel
duration: 0.3
track:
  beam:
    from: [0.0, 0.0]
    to: [15.0, 0.0]
    E: 210.0e9
    G: 81.0e9
    rho: 7850
    A: 0.0362
    Av: 0.00936
    I: 0.0017276
    depth: 0.509
    supports: {{from: pinned, to: roller}}
{beam}vehicles:
  - name: car
    speed: 10.0
    bodies: [{{name: body, mass: 40000.0}}]
    axles: [{{name: w, x: 0.0, mass: {wheel}}}]
    springs: [{{upper: body, lower: w, x: 0.0, k: 1.0106e8}}]
output:
  probes: [{{name: mid, x: 7.5}}, {{name: q, x: 3.75}}]
"
        ))
    };
    let warned = |s: &Scene| {
        (s.beam().expect("a beam").warnings().iter()).any(|w| w.contains("unsprung masses"))
    };
    assert!(warned(&soft(400.0, "")) && !warned(&soft(0.0, "")));
    let planned = at_defaults(&soft(400.0, ""));
    let more = at_defaults(&soft(400.0, "    model: modal\n    modes: 44\n"));
    let (a, b) = (mid_headlines(&planned)[3], mid_headlines(&more)[3]);
    assert!(
        (a - b).abs() > 1e-3 * b,
        "midspan's largest acceleration {a} as planned, {b} on 44 modes"
    );
    let (r, s) = (
        planned.vehicles[0].axles[0].1.max,
        more.vehicles[0].axles[0].1.max,
    );
    assert!(
        (r - s).abs() > 1e-3 * s,
        "the wheel's largest contact force {r} N as planned, {s} on 44 modes"
    );
}

/// Without damping the modes above those the loads excite ring for the whole run, and a
/// suspension hands them to its body: a 40 t body on an 8 Hz suspension (ζ 10 %) at 20 m/s over
/// a stiff 20 m clamped concrete deck (0.24 mm under it). On twice the 46 modes planned, on the
/// same mesh, the body's largest acceleration moves by more than the accuracy (4.5·10⁻³), and
/// the scene says so; with 0.1 % Rayleigh damping it is not warned. The warning is the class's:
/// Biggs' sprung mass, on an undamped deck too, holds within 2·10⁻⁵ on half its modes (its body's
/// acceleration, 0.16 m/s², thirty times this one's), and is warned all the same.
#[test]
fn vehicles_over_an_undamped_deck_are_said_to_move_with_the_modes() {
    let deck = |damping: &str, beam: &str| {
        let section = "    E: 35.0e9\n    G: 14.58e9\n    rho: 2500\n    A: 18.0\n    Av: 15.0\n    I: 1.98\n    supports: {from: clamped, to: clamped}\n";
        let car = [40000.0, 1.0106e8, 402124.0, 20.0];
        one_car(
            "stiff-clamped",
            0.1,
            20.0,
            &format!("{section}{damping}{beam}"),
            car,
        )
    };
    let warned = |s: &Scene| {
        (s.beam().expect("a beam").warnings().iter())
            .any(|w| w.contains("without stiffness-proportional damping"))
    };
    let damped = "    damping: {ratio: 0.001, modes: [1, 2]}\n";
    assert!(warned(&deck("", "")) && !warned(&deck(damped, "")));
    body_moves_on_twice_the_modes(|beam| deck("", beam));
}

/// The static correction of the modes left out follows the wheels' static loads: of a wheel
/// force's swing about them those modes hold nothing. A 40 t body on a 3 Hz suspension (ζ 10 %)
/// at 80 m/s over a 30 m steel beam of 5.6 t (2 % damping) swings its wheel's force from 0 to
/// 4.1 times its static load, and the modes past the 24 planned add 4.2·10⁻⁴ of the static
/// deflection: the run says so, and on twice the modes the body's largest acceleration moves
/// by more than the accuracy (1.9·10⁻³ measured). Biggs' sprung mass (a swing of 0.02) and the
/// railway study (0.57, its left-out modes' share 2.2·10⁻⁴) are not warned.
#[test]
fn wheel_forces_swinging_past_the_static_correction_are_said_to_move_with_the_modes() {
    let heavy = |beam: &str| {
        let section = "    E: 210.0e9\n    G: 81.0e9\n    rho: 7850\n    A: 0.0724\n    Av: 0.01872\n    I: 0.0069104\n    depth: 0.72\n    supports: {from: clamped, to: roller}\n    damping: {ratio: 0.02, modes: [1, 2]}\n";
        let car = [40000.0, 1.4212e7, 150796.0, 80.0];
        one_car(
            "heavy-on-steel",
            1.0,
            30.0,
            &format!("{section}{beam}"),
            car,
        )
    };
    let says =
        |r: &BeamRun| (r.warnings().iter()).any(|w| w.contains("follows the static loads alone"));
    assert!(says(&at_defaults(&heavy(""))));
    body_moves_on_twice_the_modes(heavy);
    for study in ["vehicle-sprung.yaml", "vehicle-railcar.yaml"] {
        let run = at_defaults(&load(study));
        assert!(!says(&run), "{study} warned");
    }
}

/// One car over a straight deck from (0, 0) to (`length`, 0) with the lines `beam` (its
/// section, supports and what else the deck has): a body of `mass` on a spring `k` and a damper
/// `c` over a massless point wheel at `speed`, probes at midspan and the quarter.
fn one_car(name: &str, duration: f64, length: f64, beam: &str, car: [f64; 4]) -> Scene {
    let [mass, k, c, speed] = car;
    let (mid, quarter) = (length / 2.0, length / 4.0);
    parse(&format!(
        "name: {name}
duration: {duration}
track:
  beam:
    from: [0.0, 0.0]
    to: [{length}, 0.0]
{beam}vehicles:
  - name: car
    speed: {speed}
    bodies: [{{name: body, mass: {mass}}}]
    axles: [{{name: w, x: 0.0}}]
    springs: [{{upper: body, lower: w, x: 0.0, k: {k}, c: {c}}}]
output:
  probes: [{{name: mid, x: {mid}}}, {{name: q, x: {quarter}}}]
"
    ))
}

/// The body's largest acceleration at the defaults of the modal beam the plan chooses for
/// `scene("")`, and on twice its modes (`scene` given the lines that ask for them), moves by
/// more than the accuracy.
fn body_moves_on_twice_the_modes(scene: impl Fn(&str) -> Scene) {
    let planned = scene("");
    let modes = match planned.beam().expect("a beam").beam.model {
        rollbeam::beam::BeamModel::Modal { modes } => 2 * modes,
        other => panic!("planned {other:?}, not the modal beam"),
    };
    let more = scene(&format!("    model: modal\n    modes: {modes}\n"));
    let (planned, more) = common::side_by_side(|| at_defaults(&planned), || at_defaults(&more));
    let body = |r: &BeamRun| r.vehicles[0].bodies[0].1.largest_magnitude().0;
    let (a, b) = (body(&planned), body(&more));
    assert!(
        (a - b).abs() > 1e-3 * b,
        "the body's largest acceleration {a} as planned, {b} on {modes} modes"
    );
}

/// A 10 t body on an 8 Hz suspension (ζ 5 %) at `speed` over a 20 m concrete span of 0.5 %
/// Rayleigh damping, probes at midspan and the quarter; `beam` adds lines to the beam's.
fn damped_car(speed: f64, beam: &str) -> Scene {
    let section = "    E: 35.0e9\n    G: 14.58e9\n    rho: 2500\n    A: 6.0\n    Av: 5.0\n    I: 0.22\n    supports: {from: pinned, to: roller}\n    damping: {ratio: 0.005, modes: [1, 2]}\n";
    let car = [10000.0, 2.5266e7, 50265.0, speed];
    one_car("damped-car", 1.0, 20.0, &format!("{section}{beam}"), car)
}

/// A wheel reads the modes' shapes everywhere along the span, and between the nodes they
/// converge far more slowly than the frequencies the mesh is first chosen by. The car of
/// `point_wheels_on_the_modal_beam_ride_its_static_correction` at its defaults, at 6 and
/// 20 m/s (where the mesh of 8 elements the frequencies alone choose read the body's largest
/// acceleration 5.5·10⁻³ and 3.5·10⁻³ off), against the linear beam on 32 elements (every
/// mode of a mesh four times finer, no modal truncation) at rtol 10⁻⁸: the body's and both
/// probes' largest accelerations and deepest deflections within the accuracy asked, 10⁻³
/// (measured at 6 to 40 m/s: 4.5·10⁻⁴ at most). The plan's mesh is finer than 8 elements, and
/// on 8 the defaults miss at 20 m/s: the check could fail.
#[test]
fn a_vehicle_s_body_at_the_defaults_holds_the_accuracy_whatever_its_speed() {
    let headlines = |r: &BeamRun| {
        let mut h = vec![r.vehicles[0].bodies[0].1.largest_magnitude().0];
        for p in &r.extremes.probes {
            h.extend([p[1].min, p[3].largest_magnitude().0]);
        }
        h
    };
    let off = |a: &[f64], b: &[f64]| {
        (a.iter().zip(b))
            .map(|(x, y)| (x / y - 1.0).abs())
            .fold(0.0, f64::max)
    };
    for speed in [6.0, 20.0] {
        let planned = damped_car(speed, "");
        let elements = planned.beam().expect("a beam").beam.elements;
        assert!(
            elements > 8,
            "{speed} m/s: the plan meshed {elements} elements"
        );
        let converged = headlines(&run_beam(
            &damped_car(speed, "    elements: 32\n    model: linear\n"),
            Method::Esdirk4,
            1e-8,
            1e-12,
        ));
        let defaults = headlines(&at_defaults(&planned));
        let miss = off(&defaults, &converged);
        assert!(
            miss < 1e-3,
            "{speed} m/s on {elements} elements: {defaults:?} against {converged:?}, {miss:.1e}"
        );
        if speed == 20.0 {
            let coarse = headlines(&at_defaults(&damped_car(speed, "    elements: 8\n")));
            let miss = off(&coarse, &converged);
            assert!(
                miss > 1e-3,
                "on 8 elements the defaults miss by {miss:.1e} only"
            );
        }
    }
}

/// On a modal beam a point wheel rides on Φη plus the static response R P of the modes left
/// out to the wheels' static loads, as the outputs read the deck: without it, the wheel's track
/// lacks the short waves of the deflection under it, which a suspension passes to the body
/// and back to the deck. A 10 t body on an 8 Hz suspension (ζ 5 %) at 20 m/s over a 20 m
/// concrete span, on the plan's mesh of 8 elements: the modal beam of 13 modes (the plan's)
/// and of 26 against the linear beam on the same mesh, which holds every mode the mesh has
/// (an independent set of equations, no static correction). Without the correction the 13
/// modes read the body's largest acceleration 2.1·10⁻³ and the quarter-span's 2.0·10⁻³ off
/// the mesh's; with it both lie within 10⁻⁴, so a quarter of the accuracy is a margin of two.
#[test]
fn point_wheels_on_the_modal_beam_ride_its_static_correction() {
    let car = |beam: &str| damped_car(20.0, &format!("    elements: 8\n{beam}"));
    let headlines = |r: &BeamRun| {
        [
            r.vehicles[0].bodies[0].1.largest_magnitude().0,
            r.extremes.probes[1][3].largest_magnitude().0,
        ]
    };
    let mesh = headlines(&run_beam(
        &car("    model: linear\n"),
        Method::Esdirk4,
        1e-8,
        1e-12,
    ));
    for modes in [13, 26] {
        let modal = headlines(&run_beam(
            &car(&format!("    model: modal\n    modes: {modes}\n")),
            Method::Esdirk4,
            1e-8,
            1e-12,
        ));
        for (name, (x, y)) in ["body", "quarter span"]
            .iter()
            .zip(modal.into_iter().zip(mesh))
        {
            let off = (x / y - 1.0).abs();
            assert!(
                off < 2.5e-4,
                "{name} on {modes} modes: a_max {x} against the mesh's {y}: {off:.1e}"
            );
        }
    }
}

/// A random road's seed and class are sweep keys, as the file gives them: each case of a
/// sweep over `track.profile.iso8608.seed` and `.class` reports, to the last bit, what a
/// one-case sweep of the scene with that seed and class written in the file does; different
/// seeds give different roads (the body's largest acceleration moves by more than a tenth),
/// so the key reaches the road. A Monte Carlo estimate over roads is one sweep.
#[test]
fn a_road_s_seed_and_class_are_swept_as_the_file_gives_them() {
    use rollbeam::workflows::sweep::{run_grid, Setting, SweepRow};
    let road = |class: &str, seed: u64| {
        let path = common::studies_dir().join("vehicle-truck.yaml");
        let text = std::fs::read_to_string(path)
            .expect("the truck's scene")
            .replace(
                "points: [[-1.0, 0.0], [0.0, 0.01], [25.0, 0.01], [26.0, 0.0]]",
                &format!("iso8608: {{class: {class}, seed: {seed}}}"),
            )
            .replace("duration: 1.0", "duration: 0.6");
        assert!(
            text.contains("iso8608"),
            "the truck's road was not replaced"
        );
        rollbeam::scene::SceneSpec::parse(&text, "road.yaml", "road").expect("the scene")
    };
    let bodies = |row: &SweepRow| -> Vec<(String, f64)> {
        row.outcome
            .as_ref()
            .expect("a case that ran")
            .bodies
            .clone()
    };
    let swept = run_grid(
        &road("A", 0),
        &[
            Setting::parse("track.profile.iso8608.seed=3,4").expect("seeds"),
            Setting::parse("track.profile.iso8608.class=B,C").expect("classes"),
        ],
        &Default::default(),
        false,
    )
    .expect("the sweep");
    assert_eq!(swept.len(), 4);
    let same = Setting::parse("duration=0.6").expect("one case");
    for row in &swept {
        let (seed, class) = (row.values[0].to_string(), row.values[1].to_string());
        let given = road(&class, seed.parse().expect("a seed"));
        let one = run_grid(
            &given,
            std::slice::from_ref(&same),
            &Default::default(),
            false,
        )
        .expect("the scene as written");
        assert_eq!(bodies(row), bodies(&one[0]), "seed {seed}, class {class}");
    }
    let a = |row: &SweepRow| bodies(row)[0].1;
    let (three, four) = (a(&swept[0]), a(&swept[2]));
    assert!(
        (three - four).abs() > 0.1 * three.max(four),
        "seeds 3 and 4 on class B: {three} and {four} m/s²"
    );
}

/// A disk wheel pivots over a crest of the profile where the faces' slopes, the deck's added,
/// put the pivot: a 510 kg wheel of 0.3 m at 8 m/s over a 5 mm ramp's top, on a 30 m steel beam
/// of 6.6 t sloping about 0.015 there, pivots a few millimetres past where the profile alone
/// puts it, and dips by about m V²/a, past its load: both wheels lift off. At the defaults the
/// rear wheel's pivot lay inside a step, and its lift-off went unseen. Both lift off where a
/// run at a hundredth of the accuracy finds them, within 10 µs (measured 0.12 µs). Both land
/// plastically, and the contact force's spike at a landing grows with the resolution (30.2 MN
/// at the defaults, 48.5 at a thousandth of the accuracy): the run says so.
#[test]
fn a_disk_wheel_lifts_off_where_it_pivots_over_a_crest_of_a_deflected_deck() {
    let ramp = |solver: &str| {
        parse(&car_over_a_ramp(
            "    wheel: disk\n    radius: 0.3\n",
            solver,
        ))
    };
    let lift_offs = |r: &BeamRun| -> Vec<Vec<f64>> {
        (r.vehicles[0].flights.iter())
            .map(|f| f.iter().map(|g| g.lift_off_t).collect())
            .collect()
    };
    let (planned_run, finer_run) = common::side_by_side(
        || at_defaults(&ramp("")),
        || at_defaults(&ramp("solver: {accuracy: 1.0e-5}\n")),
    );
    assert!(
        (planned_run.warnings().iter()).any(|w| w.contains("wheels front, rear landed 2 times")),
        "the landings' impacts unsaid: {:?}",
        planned_run.warnings()
    );
    let (planned, finer) = (lift_offs(&planned_run), lift_offs(&finer_run));
    eprintln!("lift-offs {planned:?} at the defaults, {finer:?} finer");
    assert!(
        finer.iter().all(|f| f.len() == 1),
        "each wheel lifts off once: {finer:?}"
    );
    assert_eq!(planned.len(), finer.len());
    for (p, f) in planned.iter().zip(&finer) {
        assert!(
            p.len() == 1 && (p[0] - f[0]).abs() < 1e-5,
            "lift-offs {planned:?} at the defaults, {finer:?} at a thousandth of the accuracy"
        );
    }
}

/// The car of the test above on point wheels, over the same ramp and deck. Each wheel's mass
/// bears the deck's acceleration under it, which every mode of the mesh carries, and under
/// β damping the implicit steps pass over the fast ones. Read through the problem at the dense
/// output's states, the deck's largest acceleration came out 1705 m/s² where a run at a
/// thousandth of the accuracy finds 7.43, and the wheels' contact forces −5.3·10⁵ N after
/// each kink's impulse. Held to four steps an element and read off the cubics through the
/// ends, the largest contact force was still 2.8 % high. The deck's largest acceleration,
/// each probe's, and each wheel's least and largest contact force must lie within the
/// accuracy of the scale of a run at a hundredth of it (measured 6.4·10⁻⁵ in the deck,
/// 7.6·10⁻⁵ in the contact forces). So must each probe's acceleration at every
/// row of the history: the impulse at each kink rings modes that the damping's stiffness term
/// quiets within a few of their periods, and with the nodes alone in the error norm the
/// steps then grow past what the accelerations need (a row 1 ms past the ramp's top was
/// 2.3·10⁻³ off; with the modes below the cutoff weighed, every row within 4.6·10⁻⁴).
#[test]
fn a_wheel_with_a_mass_reads_the_deck_inside_the_step() {
    let ramp = |solver: &str| parse(&car_over_a_ramp("", solver));
    let (planned, finer) = common::side_by_side(
        || at_defaults(&ramp("")),
        || at_defaults(&ramp("solver: {accuracy: 1.0e-5}\n")),
    );
    common::assert_deck_accelerations_within(&planned, &finer, 1e-3);
    let scale = finer.envelope.a_max.0;
    assert_eq!(planned.rows.len(), finer.rows.len());
    for (p, f) in planned.rows.iter().zip(&finer.rows) {
        for (x, y) in p.accelerations.iter().zip(&f.accelerations) {
            assert!(
                (x - y).abs() < 1e-3 * scale,
                "at t = {} s the probes' accelerations {:?} at the defaults, {:?} at a hundredth of the accuracy",
                p.t,
                p.accelerations,
                f.accelerations
            );
        }
    }
    for ((name, p), (_, f)) in planned.vehicles[0]
        .axles
        .iter()
        .zip(&finer.vehicles[0].axles)
    {
        let scale = f.largest_magnitude().0;
        assert!(
            (p.min - f.min).abs() < 1e-3 * scale && (p.max - f.max).abs() < 1e-3 * scale,
            "wheel {name}'s contact force from {} to {} N at the defaults, {} to {} at a hundredth of the accuracy",
            p.min,
            p.max,
            f.min,
            f.max
        );
    }
}

/// A car of 5 t on two 510 kg wheels 3 m apart at 8 m/s over a 5 mm ramp at 10 m on the soft
/// deck, its wheels as `wheel` lines give them.
fn car_over_a_ramp(wheel: &str, solver: &str) -> String {
    let car = format!(
        "vehicles:
  - name: car
    x0: -2.0
    speed: 8.0
    bodies: [{{name: body, mass: 5096.84, inertia: 5096.84, x: 1.5}}]
    axles: [{{name: front, x: 0.0, mass: 509.684}}, {{name: rear, x: 3.0, mass: 509.684}}]
    springs:
      - {{upper: body, lower: front, x: 0.0, k: 1177042.3, c: 10953.7}}
      - {{upper: body, lower: rear, x: 3.0, k: 1177042.3, c: 5476.9}}
{wheel}"
    );
    let ramp = "  profile:\n    points: [[0.0, 0.0], [10.0, 0.0], [10.5, 0.005], [30.0, 0.005]]\n";
    format!(
        "name: car-over-a-ramp\n{}",
        common::soft_deck_text(ramp, &car, solver)
    )
}

/// D44's bridge on 8 modes with a disk rolling from the left support at 17.6 m/s and a 3 t
/// car on a damped suspension starting there at 20 m/s: `disk` is the disk's line.
fn beside_a_disk(name: &str, disk: &str) -> Scene {
    parse(&format!(
        "name: {name}
duration: 0.05
track:
  beam: {{from: [0.0, 0.0], to: [20.0, 0.0], E: 210.0e9, G: 81.0e9, rho: 7850, A: 181.0e-4, Av: 46.8e-4, I: 43190.0e-8, depth: 0.36, model: modal, modes: 8, supports: {{from: pinned, to: roller}}}}
{disk}
vehicles:
  - name: car
    speed: 20.0
    bodies: [{{name: body, mass: 3000.0}}]
    axles: [{{name: wheel, x: 0.0}}]
    springs: [{{upper: body, lower: wheel, x: 0.0, k: 1.0e6, c: 1.0e4}}]
output: {{interval: 0.005, probes: [{{name: mid, x: 10.0}}]}}
"
    ))
}

/// A disk beside a vehicle, against an independent formulation of the same system: the disk
/// as a moving mass (`coupling: moving-mass`, the disks' equations holding the car's) and as
/// a train of one moving-mass axle of its weight (the car's own equations holding the axle's
/// inertia), over the same patch. Compared while both are on the deck: the deflection, the
/// car's displacement and its wheel's force agree within 1e-6 of their largest, the car's
/// acceleration within 1e-4 and the deck's within 1e-3 at rtol 10⁻⁸ (measured 3.9·10⁻⁸,
/// 5.7·10⁻¹⁰, 9.1·10⁻⁷, 3.2·10⁻⁶ and 1.3·10⁻⁴; each about ten times larger at rtol 10⁻⁷: the
/// integration's error, not the formulations'). The deck's acceleration is bounded by how the
/// two read it off a mass that turns with the axis, 1.8·10⁻⁴ apart without the car.
#[test]
fn a_moving_mass_disk_beside_a_car_is_a_one_axle_train_beside_it() {
    let patch = rollbeam::coupling::patch::dispersed_half_width(0.36);
    let disk = beside_a_disk(
        "disk",
        &format!("disk: {{mass: 1500, radius: 0.4, s0: 0.0, omega0: -44, coupling: moving-mass, patch: {patch}}}"),
    );
    let train = beside_a_disk(
        "train",
        "train: {axles: [0.0], load: 14715.0, speed: 17.6, model: moving-mass}",
    );
    let run = |s: &Scene| run_beam(s, Method::Esdirk4, 1e-8, 5.45e-10);
    let (a, b) = (run(&disk), run(&train));
    let on = |t: f64| t <= 1.13;
    let gap = |f: &dyn Fn(&rollbeam::run::beam::BeamRow) -> f64| {
        let mut worst = 0.0_f64;
        let mut largest = 0.0_f64;
        let mut shared = 0;
        for ra in a.rows.iter().filter(|r| on(r.t)) {
            // The output grid's times; the last row of each run is its end.
            let Some(rb) = b.rows.iter().find(|r| (r.t - ra.t).abs() < 1e-9) else {
                continue;
            };
            shared += 1;
            worst = worst.max((f(ra) - f(rb)).abs());
            largest = largest.max(f(rb).abs());
        }
        assert!(shared > 200, "{shared} times shared");
        worst / largest
    };
    let car = |r: &rollbeam::run::beam::BeamRow, i: usize| {
        r.vehicles.as_ref().expect("the car observed").bodies[0][0][i]
    };
    let wheel = |r: &rollbeam::run::beam::BeamRow| r.vehicles.as_ref().expect("the car").rn[0][0];
    let gaps = [
        ("midspan's w", gap(&|r| r.probes[0].w), 1e-6),
        ("the car's y", gap(&|r| car(r, 0)), 1e-6),
        ("the wheel's force", gap(&wheel), 1e-6),
        ("the car's acceleration", gap(&|r| car(r, 2)), 1e-4),
        ("midspan's acceleration", gap(&|r| r.accelerations[0]), 1e-3),
    ];
    for (what, off, tol) in gaps {
        eprintln!("{what}: {off:.2e} of its largest apart");
        assert!(off < tol, "{what}: {off:.2e}");
    }
}

/// A rolling disk beside a car on a damped suspension: the energy balance (the beam's, the
/// disk's and the car's energies against the drive's work and the damper's) closes to the
/// fourth-order method's error, and shrinks with it (measured 2.3·10⁻⁹ at rtol 10⁻⁶, 7.2·10⁻¹¹
/// at 10⁻⁸). A term of the coupling seen from one side only (the car's wheel force on the
/// beam, its inertia in the disks' mass) would leave the work it does unbooked.
#[test]
fn a_rolling_disk_beside_a_car_balances_its_energy() {
    let s = beside_a_disk(
        "rolling",
        "disk: {mass: 1500, radius: 0.4, s0: 0.0, omega0: -44, coupling: consistent}",
    );
    let drift = |rtol: f64| {
        let r = run_beam(&s, Method::Esdirk4, rtol, rtol * 5.45e-2);
        assert_eq!(r.header.stop.name(), "end");
        r.header.energy.max_rel_drift()
    };
    let (coarse, fine) = (drift(1e-6), drift(1e-8));
    eprintln!("a disk beside a car: energy drift {coarse:.2e} at rtol 1e-6, {fine:.2e} at 1e-8");
    assert!(fine < 1e-9, "the balance drifts by {fine:.2e}");
    assert!(
        coarse / fine > 10.0,
        "the drift went from {coarse:.2e} to {fine:.2e}"
    );
}

/// Beside vehicles a disk does not fly: where its contact force falls to zero the run stops
/// there, says so and names it, the vehicles reported up to then. At 32 m/s over the deck the
/// car bends, the disk leaves the track at about 0.62 s.
#[test]
fn a_disk_that_lifts_off_beside_a_car_stops_the_run() {
    let s = beside_a_disk(
        "fast",
        "disk: {mass: 1500, radius: 0.4, s0: 0.0, omega0: -80, coupling: consistent}",
    );
    let r = at_defaults(&s);
    assert_eq!(r.header.stop.name(), "contact-lost");
    assert_eq!(r.stopped_disk, Some(0));
    assert!(
        r.header.t_end > 0.5 && r.header.t_end < 0.7,
        "{}",
        r.header.t_end
    );
    assert!(r.flights.is_empty());
    assert!(r.vehicles[0].lost_contact.is_none());
    let summary = rollbeam::output::beam::summary_yaml(&r).expect("a summary");
    assert!(summary.contains("vehicles:"), "{summary}");
}
