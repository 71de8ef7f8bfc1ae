//! A run of a disk on a rigid curve.

use super::{EnergyCheck, Overrides, Progress, RunHeader, Stop};
use crate::error::Error;
use crate::ode::{self, Observer};
use crate::rolling::minimal::Minimal;
use crate::rolling::thesis::Thesis;
use crate::rolling::{DiskObservation, RollingModel};
use crate::scene::{Formulation, RollingScene, Scene};

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

pub struct RunResult {
    pub header: RunHeader,
    pub setup: RollingScene,
    pub rows: Vec<Row>,
    pub last: Row,
}

pub fn model(setup: &RollingScene) -> Box<dyn RollingModel> {
    match setup.formulation {
        Formulation::Minimal => Box::new(Minimal {
            rolling: setup.rolling.clone(),
        }),
        Formulation::Thesis => Box::new(Thesis {
            rolling: setup.rolling.clone(),
        }),
    }
}

fn energy_of(d: &DiskObservation) -> (f64, f64) {
    (d.kinetic + d.potential, d.kinetic.abs() + d.potential.abs())
}

struct Recorder<'a> {
    model: &'a dyn RollingModel,
    rows: Vec<Row>,
    energy: EnergyCheck,
    progress: Option<Progress>,
}

impl Observer for Recorder<'_> {
    fn output(&mut self, t: f64, y: &[f64]) {
        let disk = self.model.observe(t, y);
        let (total, scale) = energy_of(&disk);
        self.energy.record(total, scale);
        self.rows.push(Row { t, disk });
    }

    fn step(&mut self, t: f64, y: &[f64]) {
        let disk = self.model.observe(t, y);
        let (total, scale) = energy_of(&disk);
        self.energy.record(total, scale);
        if let Some(p) = &mut self.progress {
            p.update(t);
        }
    }
}

pub fn run(
    scene: &Scene,
    setup: &RollingScene,
    over: &Overrides,
    show_progress: bool,
) -> Result<RunResult, Error> {
    let model = model(setup);
    let y0 = model.initial_state();
    let opts = over.options(scene);
    let outputs = super::output_times(scene);
    let first = model.observe(0.0, &y0);
    let mut rec = Recorder {
        model: model.as_ref(),
        rows: Vec::with_capacity(outputs.len() + 1),
        energy: {
            let (total, scale) = energy_of(&first);
            EnergyCheck::new(total, scale)
        },
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
        p.finish();
    }
    let last = Row {
        t: out.t,
        disk: model.observe(out.t, &out.y),
    };
    if rec.rows.last().is_none_or(|r| r.t < out.t) {
        rec.rows.push(last);
    }
    let stop = match &out.stopped_by {
        Some(hit) => Stop::Event(hit.reason),
        None => Stop::End,
    };
    Ok(RunResult {
        header: RunHeader {
            scene: scene.clone(),
            method: opts.method,
            rtol: opts.rtol,
            atol: opts.atol,
            unknowns: y0.len(),
            stop,
            t_end: out.t,
            stats: out.stats,
            energy: rec.energy,
        },
        setup: setup.clone(),
        rows: rec.rows,
        last,
    })
}
