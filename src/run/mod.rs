//! One run of a scene: build the model the scene names (a disk on a rigid curve, or a loaded
//! beam), integrate it, watch its energy, and collect what the outputs need.

pub mod beam;
pub mod extremes;
pub mod rolling;

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

pub use rolling::{model, RollingRun, Row};

use crate::disk::StopReason;
use crate::error::Error;
use crate::ode::Method;
use crate::scene::{Model, Scene};

/// How a run ended: at its duration, or at a physical event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    End,
    Event(StopReason),
}

impl Stop {
    /// Every way a run ends.
    pub const ALL: [Stop; 5] = [
        Stop::End,
        Stop::Event(StopReason::ContactLost),
        Stop::Event(StopReason::Slip),
        Stop::Event(StopReason::NoFit),
        Stop::Event(StopReason::LeftTrack),
    ];

    pub fn name(self) -> &'static str {
        match self {
            Stop::End => "end",
            Stop::Event(r) => r.name(),
        }
    }

    /// What a user reads on the terminal; `disk` names the disk the event was its.
    pub fn sentence(self, disk: &str, t: f64) -> String {
        match self {
            Stop::End => format!("reached the end of the run at t = {t:.6} s"),
            Stop::Event(StopReason::ContactLost) => format!(
                "{disk} lost contact with the track at t = {t:.6} s (normal reaction fell to zero)"
            ),
            Stop::Event(StopReason::Slip) => {
                format!("{disk} started to slip at t = {t:.6} s (|R_t| reached mu R_n)")
            }
            Stop::Event(StopReason::NoFit) => format!(
                "{disk} no longer fits the curve at t = {t:.6} s (radius × curvature reached 1)"
            ),
            Stop::Event(StopReason::LeftTrack) => {
                format!("{disk} ran off the end of the track at t = {t:.6} s")
            }
        }
    }
}

/// What every run reports, on a rigid curve or on a beam: the scene, the integrator with its
/// settings and what it did, the model's size, how and when the run ended, and the energy
/// balance.
#[derive(Clone, Debug)]
pub struct RunHeader {
    pub scene: Scene,
    pub method: Method,
    pub rtol: f64,
    pub atol: f64,
    /// Unknowns of the model integrated.
    pub unknowns: usize,
    pub stop: Stop,
    pub t_end: f64,
    pub stats: crate::ode::Stats,
    pub energy: EnergyCheck,
}

/// Energy bookkeeping: the drift of total = kinetic + strain + potential − work, relative to the
/// largest |kinetic| + |strain| + |potential| met in the run.
#[derive(Clone, Copy, Debug, Default)]
pub struct EnergyCheck {
    pub initial: f64,
    pub last: f64,
    pub max_abs_drift: f64,
    pub scale: f64,
}

impl EnergyCheck {
    pub fn new(total: f64, scale: f64) -> Self {
        EnergyCheck {
            initial: total,
            last: total,
            max_abs_drift: 0.0,
            scale,
        }
    }

    pub fn record(&mut self, total: f64, scale: f64) {
        self.last = total;
        self.max_abs_drift = self.max_abs_drift.max((total - self.initial).abs());
        self.scale = self.scale.max(scale);
    }

    pub fn max_rel_drift(&self) -> f64 {
        if self.scale > 0.0 {
            self.max_abs_drift / self.scale
        } else {
            0.0
        }
    }
}

/// Overrides of the scene's solver settings from the command line.
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    pub method: Option<Method>,
    pub rtol: Option<f64>,
    pub atol: Option<f64>,
    /// Fixed step size (no error control), for convergence studies.
    pub fixed_step: Option<f64>,
    /// Give up after this many steps (a budget, for `tradeoff`).
    pub max_steps: Option<usize>,
    /// Spend the whole budget, not giving up on the pace of the first steps
    /// (`ode::Options::whole_budget`).
    pub whole_budget: bool,
    /// Read a modal beam's displacements without the static correction of the modes left
    /// out: what the correction does, measured.
    pub uncorrected_modes: bool,
    /// Keep the animation's frames (`--animate`, and the studies): up to [`beam::FRAMES`]
    /// copies of the beam's displaced samples, which a run that draws no animation never reads.
    pub animate: bool,
    /// Record the probes' windowed means (`BeamRun::windowed_means`), for `tradeoff` where its
    /// reference has them: three dense-output evaluations a step that a run scored otherwise
    /// would pay for nothing (a third more time on the bridge, more with a train).
    pub windowed_means: bool,
    /// Leave the envelope along the beam unwatched: a sweep's case reports its probes and its
    /// disk alone, and the envelope's stations, watched at every step end, are most of what
    /// such a run costs.
    pub no_envelope: bool,
    /// Record no history between the run's first and last output times: a sweep's case
    /// writes none, and its extremes are watched on the steps, not read off the rows.
    pub no_history: bool,
}

impl Overrides {
    /// The integrator settings of a run: the scene's, overridden from the command line.
    pub(crate) fn options(&self, scene: &Scene) -> crate::ode::Options {
        let rtol = self.rtol.unwrap_or(scene.solver.rtol);
        // An atol chosen with the scene's rtol follows an rtol given here.
        let atol = scene
            .solver
            .atol_scale
            .map_or(scene.solver.atol, |size| rtol * size);
        crate::ode::Options {
            method: self.method.unwrap_or(scene.solver.method),
            rtol,
            atol: self.atol.unwrap_or(atol),
            velocity_rate: scene.solver.velocity_rate.filter(|_| self.atol.is_none()),
            fixed_step: self.fixed_step,
            max_steps: self
                .max_steps
                .unwrap_or(crate::ode::Options::default().max_steps),
            whole_budget: self.whole_budget,
            ..Default::default()
        }
    }
}

/// One flight of the disk, from lift-off to landing (`summary.yaml`, `disk.flights`).
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct FlightRecord {
    /// Which disk flew (of a beam's several; the summary lists each disk's own).
    #[serde(skip)]
    pub disk: usize,
    pub lift_off_t: f64,
    pub lift_off_s: f64,
    pub land_t: Option<f64>,
    pub land_s: Option<f64>,
    pub max_gap: f64,
    /// Kinetic energy the landing took (J); null without a landing.
    pub energy_lost: Option<f64>,
}

/// Whether the disk lifted off while rolling (not just bounced, or launched at the start):
/// there its normal force fell to zero with the track still pushing it along, so the friction
/// rolling needs grew without bound and no largest value is reported.
pub fn lifted_off_rolling(flights: &[FlightRecord], stop: Stop) -> bool {
    let mut landed: Option<f64> = None;
    let rolled_into_a_flight = flights.iter().any(|f| {
        let after_rolling = f.lift_off_t > 0.0 && landed != Some(f.lift_off_t);
        landed = f.land_t;
        after_rolling
    });
    rolled_into_a_flight || stop == Stop::Event(StopReason::ContactLost)
}

/// Most flights one run may take: a disk that lands and lifts off again without end (rolling
/// over a crest it cannot hold at a speed it keeps) is stopped with that reason.
pub const MAX_FLIGHTS: usize = 100_000;

/// The output grid: every `interval` from 0 to the duration.
pub(crate) fn output_times(scene: &Scene) -> Vec<f64> {
    let count = (scene.duration / scene.interval + 1e-9).floor() as usize;
    (0..=count).map(|i| i as f64 * scene.interval).collect()
}

/// A progress bar on a terminal, shown only once a run has taken more than a second.
pub(crate) struct Progress {
    bar: ProgressBar,
    started: Instant,
    shown: bool,
    duration: f64,
}

impl Progress {
    pub(crate) fn new(duration: f64) -> Option<Progress> {
        if !std::io::stderr().is_terminal() || std::env::var_os("CI").is_some() {
            return None;
        }
        let bar = ProgressBar::with_draw_target(Some(1000), ProgressDrawTarget::hidden());
        bar.set_style(
            ProgressStyle::with_template("{bar:40} t = {msg} s  ({elapsed}, eta {eta})")
                .expect("the template is valid"),
        );
        Some(Progress {
            bar,
            started: Instant::now(),
            shown: false,
            duration,
        })
    }

    pub(crate) fn update(&mut self, t: f64) {
        if !self.shown && self.started.elapsed() > Duration::from_secs(1) {
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
            self.shown = true;
        }
        self.bar.set_position((1000.0 * t / self.duration) as u64);
        self.bar.set_message(format!("{t:.3} / {}", self.duration));
    }

    pub(crate) fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

/// The result of a run, by kind of scene.
pub enum Run {
    Rolling(RollingRun),
    Beam(beam::BeamRun),
}

impl Run {
    pub fn header(&self) -> &RunHeader {
        match self {
            Run::Rolling(r) => &r.header,
            Run::Beam(b) => &b.header,
        }
    }

    /// The SVG figures the run writes (file stems).
    pub fn figures(&self) -> Vec<&'static str> {
        const BEAM: [&str; 7] = [
            "probes",
            "shapes",
            "envelope-u",
            "envelope-w",
            "envelope-phi",
            "energy",
            "reactions",
        ];
        const DISK_ON_BEAM: [&str; 4] = ["disk-velocity", "disk-omega", "disk-forces", "animation"];
        match self {
            Run::Rolling(_) => vec!["track", "velocities", "omega", "reactions", "energy"],
            Run::Beam(b) if b.setup.disk().is_some() => {
                BEAM.iter().chain(&DISK_ON_BEAM).copied().collect()
            }
            Run::Beam(b) if !b.setup.vehicles.is_empty() => BEAM
                .iter()
                .chain(&["vehicles", "wheels"])
                .copied()
                .collect(),
            Run::Beam(_) => BEAM.to_vec(),
        }
    }

    pub fn rolling(self) -> Option<RollingRun> {
        match self {
            Run::Rolling(r) => Some(r),
            Run::Beam(_) => None,
        }
    }

    pub fn beam(self) -> Option<beam::BeamRun> {
        match self {
            Run::Beam(b) => Some(b),
            Run::Rolling(_) => None,
        }
    }
}

pub fn run(scene: &Scene, over: &Overrides, show_progress: bool) -> Result<Run, Error> {
    match &scene.model {
        Model::Rolling(setup) => rolling::run(scene, setup, over, show_progress).map(Run::Rolling),
        Model::Beam(setup) => beam::run(scene, setup, over, show_progress).map(Run::Beam),
    }
}
