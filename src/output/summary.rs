//! `summary.yaml`: how the run ended, the model, what the solver did, the energy balance and the
//! disk's final state and extremes.

use serde::Serialize;

use crate::run::RunResult;

#[derive(Serialize)]
pub struct Summary {
    pub scene: String,
    pub stopped: Stopped,
    pub model: Model,
    pub solver: Solver,
    pub energy: Energy,
    pub disk: DiskSummary,
}

#[derive(Serialize)]
pub struct Stopped {
    pub reason: String,
    pub t: f64,
}

#[derive(Serialize)]
pub struct Model {
    pub track: String,
    pub unknowns: usize,
    pub formulation: String,
}

#[derive(Serialize)]
pub struct Solver {
    pub method: String,
    pub rtol: f64,
    pub atol: f64,
    pub steps: usize,
    pub rejected: usize,
    pub rhs_evals: usize,
    pub jacobians: usize,
    pub factorizations: usize,
    pub newton_iterations: usize,
    pub wall_s: f64,
}

#[derive(Serialize)]
pub struct Energy {
    pub initial: f64,
    #[serde(rename = "final")]
    pub last: f64,
    pub max_rel_drift: f64,
}

#[derive(Serialize)]
pub struct DiskSummary {
    pub s: f64,
    pub x: f64,
    pub y: f64,
    pub vx: f64,
    pub vy: f64,
    pub omega: f64,
    pub rn_min: f64,
    pub rn_max: f64,
    pub rt_min: f64,
    pub rt_max: f64,
    /// The friction coefficient rolling needed: max |R_t| / R_n.
    pub mu_needed_max: f64,
    pub left_track_t: Option<f64>,
}

impl Summary {
    pub fn from_run(r: &RunResult) -> Summary {
        let d = &r.last.disk;
        let fold = |f: fn(&crate::rolling::DiskObservation) -> f64| {
            r.rows
                .iter()
                .map(|row| f(&row.disk))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                    (lo.min(v), hi.max(v))
                })
        };
        let (rn_min, rn_max) = fold(|d| d.rn);
        let (rt_min, rt_max) = fold(|d| d.rt);
        let mu_needed_max = r
            .rows
            .iter()
            .map(|row| row.disk.rt.abs() / row.disk.rn)
            .fold(0.0, f64::max);
        let left = matches!(
            r.stop,
            crate::run::Stop::Event(crate::rolling::StopReason::LeftTrack)
        );
        Summary {
            scene: r.scene.name.clone(),
            stopped: Stopped {
                reason: r.stop.name().into(),
                t: r.last.t,
            },
            model: Model {
                track: r.setup.rolling.curve.kind().into(),
                unknowns: r.unknowns,
                formulation: r.setup.formulation.name().into(),
            },
            solver: Solver {
                method: r.method.name().into(),
                rtol: r.rtol,
                atol: r.atol,
                steps: r.stats.steps,
                rejected: r.stats.rejected,
                rhs_evals: r.stats.rhs_evals,
                jacobians: r.stats.jacobians,
                factorizations: r.stats.factorizations,
                newton_iterations: r.stats.newton_iterations,
                wall_s: r.stats.wall_s,
            },
            energy: Energy {
                initial: r.energy.initial,
                last: r.energy.last,
                max_rel_drift: r.energy.max_rel_drift(),
            },
            disk: DiskSummary {
                s: d.s,
                x: d.x,
                y: d.y,
                vx: d.vx,
                vy: d.vy,
                omega: d.omega,
                rn_min,
                rn_max,
                rt_min,
                rt_max,
                mu_needed_max,
                left_track_t: left.then_some(r.last.t),
            },
        }
    }
}
