//! Helpers shared by the study tests: load a scene of `studies/`, run it with chosen solver
//! settings, read the history at given times.
#![allow(dead_code)]

pub mod converged;

use std::path::{Path, PathBuf};

use rollbeam::analysis::moving_load::MovingForce;
use rollbeam::ode::Method;
use rollbeam::plan::Planner;
use rollbeam::run::beam::BeamRun;
use rollbeam::run::{self, Overrides, RollingRun, Row};
use rollbeam::scene::{Scene, SceneSpec};

pub fn studies_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("studies")
}

pub fn load(file: &str) -> Scene {
    Scene::load(&studies_dir().join(file)).expect("study scenes are valid")
}

/// A study scene's text, for a test that edits it as a user would.
pub fn study_text(file: &str) -> String {
    std::fs::read_to_string(studies_dir().join(file)).expect("study scenes are readable")
}

/// One key of a scene changed as the scene format holds it: a number, a name, or left out.
#[derive(Clone, Copy, Debug)]
pub enum Set<'a> {
    Number(&'a str, f64),
    Name(&'a str, &'a str),
    LeftOut(&'a str),
}

/// A study scene with some keys changed, checked and planned again.
pub fn changed(file: &str, changes: &[Set]) -> Scene {
    let mut spec = SceneSpec::load(&studies_dir().join(file)).expect("study scenes are valid");
    for change in changes {
        match *change {
            Set::Number(key, value) => spec.set(key, value),
            Set::Name(key, value) => spec.set_name(key, value),
            Set::LeftOut(key) => spec.unset(key),
        }
        .expect("a key of the scene format");
    }
    Planner::default()
        .plan(&spec)
        .expect("the changed scene is valid")
}

/// Two independent runs side by side, one a core: a test that compares a run against its
/// converged twin takes as long as the longer of the two.
pub fn side_by_side<A: Send, B: Send>(
    a: impl FnOnce() -> A + Send,
    b: impl FnOnce() -> B + Send,
) -> (A, B) {
    std::thread::scope(|scope| {
        let first = scope.spawn(a);
        let second = b();
        (first.join().expect("the first run"), second)
    })
}

pub fn parse(text: &str) -> Scene {
    Scene::parse(text, "test scene", "test").expect("test scene is valid")
}

pub fn run_with(scene: &Scene, method: Method, rtol: f64, atol: f64) -> RollingRun {
    let over = Overrides {
        method: Some(method),
        rtol: Some(rtol),
        atol: Some(atol),
        fixed_step: None,
        ..Default::default()
    };
    run::run(scene, &over, false)
        .expect("the run completes")
        .rolling()
        .expect("a rolling scene")
}

/// The run as planned: the solver's choices from the scene's accuracy, or the scene's own.
pub fn at_defaults(scene: &Scene) -> BeamRun {
    run::run(scene, &Overrides::default(), false)
        .expect("the run completes")
        .beam()
        .expect("a beam scene")
}

pub fn run_beam(scene: &Scene, method: Method, rtol: f64, atol: f64) -> BeamRun {
    let over = Overrides {
        method: Some(method),
        rtol: Some(rtol),
        atol: Some(atol),
        fixed_step: None,
        ..Default::default()
    };
    run::run(scene, &over, false)
        .expect("the run completes")
        .beam()
        .expect("a beam scene")
}

/// Fixed steps of size h. The tolerances then only stop Newton iterations: they are tight so
/// that what is measured is the method's truncation error, not the nonlinear solve's.
pub fn run_fixed(scene: &Scene, method: Method, h: f64) -> RollingRun {
    let over = Overrides {
        method: Some(method),
        rtol: Some(1e-13),
        atol: Some(1e-15),
        fixed_step: Some(h),
        ..Default::default()
    };
    run::run(scene, &over, false)
        .expect("the run completes")
        .rolling()
        .expect("a rolling scene")
}

/// The history row at time t (output times are multiples of the scene's interval).
pub fn at(r: &RollingRun, t: f64) -> Row {
    *r.rows
        .iter()
        .min_by(|a, b| (a.t - t).abs().total_cmp(&(b.t - t).abs()))
        .expect("rows")
}

/// Least-squares slope of log(y) against log(x).
pub fn log_slope(x: &[f64], y: &[f64]) -> f64 {
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let ly: Vec<f64> = y.iter().map(|v| v.ln()).collect();
    let n = lx.len() as f64;
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = lx.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}

/// D44 made the setting of Frýba's moving force: shear made stiff (G × 10⁴, the
/// Euler–Bernoulli limit), the disk's weight as a moving force over a ±5 cm patch.
pub const FRYBA_BRIDGE: [Set<'static>; 3] = [
    Set::Number("track.beam.G", 81.0e13),
    Set::Name("disk.coupling", "moving-force"),
    Set::Number("disk.patch", 0.05),
];

/// Frýba's series for that bridge: D44's weight, speed, span and section.
pub fn fryba_bridge() -> MovingForce {
    MovingForce {
        p: 1500.0 * 9.81,
        span: 20.0,
        ei: 210.0e9 * 43190.0e-8,
        mu: 7850.0 * 181.0e-4,
        v: 17.6,
    }
}

/// The run's midspan deflection against a closed form of it (positive downwards, as Frýba
/// writes it): (largest difference, largest closed-form value), m.
pub fn midspan_against(r: &BeamRun, midspan: impl Fn(f64) -> f64) -> (f64, f64) {
    let k = r
        .setup
        .probes
        .iter()
        .position(|p| p.name == "mid")
        .expect("a probe named mid");
    let peak = r
        .rows
        .iter()
        .map(|row| midspan(row.t).abs())
        .fold(0.0, f64::max);
    let worst = r
        .rows
        .iter()
        .map(|row| (row.probes[k].w + midspan(row.t)).abs())
        .fold(0.0, f64::max);
    (worst, peak)
}

/// The same against Frýba's undamped series.
pub fn midspan_against_fryba(r: &BeamRun) -> (f64, f64) {
    let series = fryba_bridge();
    midspan_against(r, |t| series.deflection(10.0, t, 301))
}

/// The first probe's deflection averaged over [0, until] under a Hann window
/// (w̄ = ∫ w h dt / ∫ h dt, h = sin²(π t / until)): the vibration about the slowly varying
/// response, whose phase at any moment depends on the mesh's frequencies, averages out (the
/// window's leakage falls as the cube of the frequency), which leaves the mesh's static
/// flexibility: a well-conditioned headline where the peak is not.
pub fn hann_mean(r: &BeamRun, until: f64) -> f64 {
    let h = |t: f64| (std::f64::consts::PI * t / until).sin().powi(2);
    let (mut num, mut den) = (0.0, 0.0);
    for pair in r.rows.windows(2).filter(|p| p[1].t <= until + 1e-12) {
        let dt = pair[1].t - pair[0].t;
        num += 0.5 * dt * (h(pair[0].t) * pair[0].probes[0].w + h(pair[1].t) * pair[1].probes[0].w);
        den += 0.5 * dt * (h(pair[0].t) + h(pair[1].t));
    }
    num / den
}

/// The 15 m concrete bridge of the HSLM study under `train`, run for `duration` s after it;
/// `beam` adds keys to the beam (e.g. "    model: modal\n").
pub fn hslm_bridge(train: &str, duration: f64, beam: &str) -> Scene {
    hslm_bridge_probed(train, duration, beam, "[{name: mid, x: 7.5}]")
}

/// [`hslm_bridge`] with the probes `probes` (a YAML list).
pub fn hslm_bridge_probed(train: &str, duration: f64, beam: &str, probes: &str) -> Scene {
    parse(&hslm_bridge_text(train, duration, beam, probes))
}

/// The text of [`hslm_bridge_probed`]'s scene.
pub fn hslm_bridge_text(train: &str, duration: f64, beam: &str, probes: &str) -> String {
    format!(
        "name: hslm-bridge
duration: {duration}
track:
  beam:
    from: [0.0, 0.0]
    to: [15.0, 0.0]
    E: 35.0e9
    G: 14.5833e9
    rho: 2500
    A: 6.0
    Av: 5.0
    I: 0.219830886
    supports: {{from: pinned, to: roller}}
    damping: {{ratio: 0.0185, modes: [1, 2]}}
{beam}train: {train}
output:
  probes: {probes}
"
    )
}

/// Probe `mid`'s w extremes, residual amplitude and largest acceleration.
pub fn mid_headlines(r: &BeamRun) -> [f64; 4] {
    let k = r
        .setup
        .probes
        .iter()
        .position(|p| p.name == "mid")
        .expect("mid");
    let [_, w, _, a] = r.extremes.probes[k];
    [
        w.min,
        w.max,
        r.amplitude_after_exit(k).unwrap_or(f64::NAN),
        a.largest_magnitude().0,
    ]
}

/// How far the first probe's deflection in `full` is from the sum of it in `parts` at every
/// output time, and the largest deflection: (worst, peak), m. The runs share their clock.
pub fn superposition_error(full: &BeamRun, parts: &[BeamRun]) -> (f64, f64) {
    let peak = full
        .rows
        .iter()
        .map(|r| r.probes[0].w.abs())
        .fold(0.0, f64::max);
    let worst = full
        .rows
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let sum: f64 = parts.iter().map(|p| p.rows[i].probes[0].w).sum();
            (r.probes[0].w - sum).abs()
        })
        .fold(0.0, f64::max);
    (worst, peak)
}

/// D44's bridge (`bridge-d44.yaml` up to its disk) of the given model, running `duration` s:
/// the scene text a test puts its own riders and outputs after.
pub fn d44_bridge_text(model: &str, duration: f64) -> String {
    let text = std::fs::read_to_string(studies_dir().join("bridge-d44.yaml")).unwrap();
    text.lines()
        .take_while(|l| !l.starts_with("disk:"))
        .map(|l| format!("{l}\n"))
        .collect::<String>()
        .replace("duration: 3.0", &format!("duration: {duration}"))
        .replace("    model: exact", &format!("    model: {model}"))
}

/// The classical Runge–Kutta method from rest (a state of `dim` zeros) with step `h` up to
/// `until`, handing `record` each step's (t, state, rate).
pub fn runge_kutta(
    rhs: impl Fn(f64, &[f64]) -> Vec<f64>,
    dim: usize,
    h: f64,
    until: f64,
    mut record: impl FnMut(f64, &[f64], &[f64]),
) {
    let mut s = vec![0.0; dim];
    let steps = (until / h).round() as usize;
    for i in 0..=steps {
        let t = i as f64 * h;
        let k1 = rhs(t, &s);
        record(t, &s, &k1);
        let step = |k: &[f64], c: f64| -> Vec<f64> {
            s.iter().zip(k).map(|(a, b)| a + c * h * b).collect()
        };
        let k2 = rhs(t + 0.5 * h, &step(&k1, 0.5));
        let k3 = rhs(t + 0.5 * h, &step(&k2, 0.5));
        let k4 = rhs(t + h, &step(&k3, 1.0));
        for j in 0..dim {
            s[j] += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
        }
    }
}

/// A soft 30 m pinned steel deck of 6.6 t under 5 % Rayleigh damping, its first mode at
/// 0.24 Hz, with probes at midspan and the quarter point: the scene's text after its `name`,
/// with `loads` (vehicles or a train) and `solver` lines added.
pub fn soft_deck_text(profile: &str, loads: &str, solver: &str) -> String {
    format!(
        "duration: 0.5
track:
  beam:
    from: [0.0, 0.0]
    to: [30.0, 0.0]
    E: 210.0e9
    G: 81.0e9
    rho: 7850
    A: 0.0278183
    Av: 0.0231819
    I: 1.91047e-5
    depth: 0.0907813
    supports: {{from: pinned, to: pinned}}
    damping: {{ratio: 0.05, modes: [1, 2]}}
{profile}{loads}{solver}output:
  probes: [{{name: mid, x: 15.0}}, {{name: q, x: 7.5}}]
"
    )
}

/// The envelope's largest acceleration, then each probe's.
pub fn deck_accelerations(r: &BeamRun) -> Vec<f64> {
    let probes = r.extremes.probes.iter();
    std::iter::once(r.envelope.a_max.0)
        .chain(probes.map(|p| p[3].largest_magnitude().0))
        .collect()
}

/// Asserts that every deck acceleration of `planned` lies within `accuracy` of `finer`'s
/// envelope from `finer`'s.
pub fn assert_deck_accelerations_within(planned: &BeamRun, finer: &BeamRun, accuracy: f64) {
    let (p, f) = (deck_accelerations(planned), deck_accelerations(finer));
    let scale = finer.envelope.a_max.0;
    assert!(
        p.iter()
            .zip(&f)
            .all(|(x, y)| (x - y).abs() < accuracy * scale),
        "the deck's largest accelerations {p:?} against {f:?}"
    );
}
