//! One run of a scene: build the model the scene names, integrate it, watch the energy, and
//! collect what the outputs need.

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::error::Error;
use crate::ode::{self, Method, Observer, Stats};
use crate::rolling::minimal::Minimal;
use crate::rolling::thesis::Thesis;
use crate::rolling::{DiskObservation, RollingModel, StopReason};
use crate::scene::{Formulation, Scene};

/// How a run ended: at its duration, or at a physical event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    End,
    Event(StopReason),
}

impl Stop {
    pub fn name(self) -> &'static str {
        match self {
            Stop::End => "end",
            Stop::Event(r) => r.name(),
        }
    }

    /// What a user reads on the terminal.
    pub fn sentence(self, t: f64) -> String {
        match self {
            Stop::End => format!("reached the end of the run at t = {t:.6} s"),
            Stop::Event(StopReason::ContactLost) => format!("the disk lost contact with the track at t = {t:.6} s (normal reaction fell to zero)"),
            Stop::Event(StopReason::Slip) => format!("the disk started to slip at t = {t:.6} s (|R_t| reached mu R_n)"),
            Stop::Event(StopReason::NoFit) => format!("the disk no longer fits the curve at t = {t:.6} s (radius × curvature reached 1)"),
            Stop::Event(StopReason::LeftTrack) => format!("the disk ran off the end of the track at t = {t:.6} s"),
        }
    }
}

#[derive(Clone, Copy, Debug)]
pub struct Row {
    pub t: f64,
    pub disk: DiskObservation,
}

impl Row {
    pub fn energy(&self) -> f64 {
        self.disk.kinetic + self.disk.potential
    }
}

/// Energy bookkeeping: drift of the total relative to the largest energy scale met.
#[derive(Clone, Copy, Debug, Default)]
pub struct EnergyCheck {
    pub initial: f64,
    pub last: f64,
    pub max_abs_drift: f64,
    pub scale: f64,
}

impl EnergyCheck {
    fn new(d: &DiskObservation) -> Self {
        let e = d.kinetic + d.potential;
        EnergyCheck {
            initial: e,
            last: e,
            max_abs_drift: 0.0,
            scale: d.kinetic.abs() + d.potential.abs(),
        }
    }

    fn record(&mut self, d: &DiskObservation) {
        let e = d.kinetic + d.potential;
        self.last = e;
        self.max_abs_drift = self.max_abs_drift.max((e - self.initial).abs());
        self.scale = self.scale.max(d.kinetic.abs() + d.potential.abs());
    }

    pub fn max_rel_drift(&self) -> f64 {
        if self.scale > 0.0 {
            self.max_abs_drift / self.scale
        } else {
            0.0
        }
    }
}

pub struct RunResult {
    pub scene: Scene,
    pub method: Method,
    pub rtol: f64,
    pub atol: f64,
    pub unknowns: usize,
    pub rows: Vec<Row>,
    pub last: Row,
    pub stop: Stop,
    pub stats: Stats,
    pub energy: EnergyCheck,
}

/// Overrides of the scene's solver settings from the command line.
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    pub method: Option<Method>,
    pub rtol: Option<f64>,
    pub atol: Option<f64>,
    /// Fixed step size (no error control), for convergence studies.
    pub fixed_step: Option<f64>,
}

pub fn model(scene: &Scene) -> Box<dyn RollingModel> {
    match scene.formulation {
        Formulation::Minimal => Box::new(Minimal {
            rolling: scene.rolling.clone(),
        }),
        Formulation::Thesis => Box::new(Thesis {
            rolling: scene.rolling.clone(),
        }),
    }
}

struct Recorder<'a> {
    model: &'a dyn RollingModel,
    rows: Vec<Row>,
    energy: EnergyCheck,
    progress: Option<Progress>,
}

/// A progress bar on a terminal, shown only once a run has taken more than a second.
struct Progress {
    bar: ProgressBar,
    started: Instant,
    shown: bool,
    duration: f64,
}

impl Progress {
    fn new(duration: f64) -> Option<Progress> {
        if !std::io::stderr().is_terminal() || std::env::var_os("CI").is_some() {
            return None;
        }
        let bar = ProgressBar::with_draw_target(Some(1000), ProgressDrawTarget::hidden());
        bar.set_style(
            ProgressStyle::with_template("{bar:40} t = {msg} s  ({elapsed}, eta {eta})")
                .expect("the template is valid"),
        );
        bar.set_message(format!("0 / {duration}"));
        Some(Progress {
            bar,
            started: Instant::now(),
            shown: false,
            duration,
        })
    }

    fn update(&mut self, t: f64) {
        let duration = self.duration;
        if !self.shown && self.started.elapsed() > Duration::from_secs(1) {
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
            self.shown = true;
        }
        self.bar.set_position((1000.0 * t / duration) as u64);
        self.bar.set_message(format!("{t:.3} / {duration}"));
    }
}

impl Observer for Recorder<'_> {
    fn output(&mut self, t: f64, y: &[f64]) {
        let disk = self.model.observe(t, y);
        self.energy.record(&disk);
        self.rows.push(Row { t, disk });
    }

    fn step(&mut self, t: f64, y: &[f64]) {
        let disk = self.model.observe(t, y);
        self.energy.record(&disk);
        if let Some(p) = &mut self.progress {
            p.update(t);
        }
    }
}

pub fn run(scene: &Scene, over: &Overrides, show_progress: bool) -> Result<RunResult, Error> {
    let model = model(scene);
    let y0 = model.initial_state();
    let method = over.method.unwrap_or(scene.solver.method);
    let rtol = over.rtol.unwrap_or(scene.solver.rtol);
    let atol = over.atol.unwrap_or(scene.solver.atol);
    let opts = ode::Options {
        method,
        rtol,
        atol,
        fixed_step: over.fixed_step,
        ..Default::default()
    };
    let count = (scene.duration / scene.interval + 1e-9).floor() as usize;
    let outputs: Vec<f64> = (0..=count).map(|i| i as f64 * scene.interval).collect();
    let first = model.observe(0.0, &y0);
    let mut rec = Recorder {
        model: model.as_ref(),
        rows: Vec::with_capacity(outputs.len() + 1),
        energy: EnergyCheck::new(&first),
        progress: if show_progress {
            Progress::new(scene.duration)
        } else {
            None
        },
    };
    let out = ode::solve(
        model.as_ref(),
        0.0,
        &y0,
        scene.duration,
        &outputs,
        &opts,
        &mut rec,
    )
    .map_err(|e| Error::Solver(format!("scene {}: the solver failed: {e}", scene.name)))?;
    if let Some(p) = &rec.progress {
        p.bar.finish_and_clear();
    }
    let last = Row {
        t: out.t,
        disk: model.observe(out.t, &out.y),
    };
    if rec.rows.last().is_none_or(|r| r.t < out.t) {
        rec.rows.push(last);
    }
    let stop = match &out.stopped_by {
        Some(hit) => {
            Stop::Event(StopReason::from_name(hit.name).expect("rolling events are stop reasons"))
        }
        None => Stop::End,
    };
    Ok(RunResult {
        scene: scene.clone(),
        method,
        rtol,
        atol,
        unknowns: y0.len(),
        rows: rec.rows,
        last,
        stop,
        stats: out.stats,
        energy: rec.energy,
    })
}
