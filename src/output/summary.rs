//! `summary.yaml`: how the run ended, the model, what the solver did, the energy balance and the
//! disk's final state and extremes.

use serde::Serialize;

use crate::run::{RollingRun, RunHeader};

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
    /// Of several disks on a beam, the one whose event stopped the run.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub disk: Option<String>,
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
    /// The friction coefficient rolling needed: max |R_t| / R_n over the times the disk
    /// pressed on the track; null if it never did.
    pub mu_needed_max: Option<f64>,
    pub left_track_t: Option<f64>,
    /// One entry per flight: lift-off, landing (null if it never landed), largest gap and the
    /// energy the landing took.
    pub flights: Vec<crate::run::FlightRecord>,
}

impl Stopped {
    pub fn of(h: &RunHeader) -> Stopped {
        Stopped {
            reason: h.stop.name().into(),
            t: h.t_end,
            disk: None,
        }
    }
}

impl Solver {
    pub fn of(h: &RunHeader) -> Solver {
        let s = &h.stats;
        Solver {
            method: h.method.name().into(),
            rtol: h.rtol,
            atol: h.atol,
            steps: s.steps,
            rejected: s.rejected,
            rhs_evals: s.rhs_evals,
            jacobians: s.jacobians,
            factorizations: s.factorizations,
            newton_iterations: s.newton_iterations,
            wall_s: s.wall_s,
        }
    }
}

impl Energy {
    pub fn of(h: &RunHeader) -> Energy {
        Energy {
            initial: h.energy.initial,
            last: h.energy.last,
            max_rel_drift: h.energy.max_rel_drift(),
        }
    }
}

impl Summary {
    pub fn from_run(r: &RollingRun) -> Summary {
        let d = &r.last.disk;
        let [rn, rt, mu] = r.contact;
        let left = matches!(
            r.header.stop,
            crate::run::Stop::Event(crate::disk::StopReason::LeftTrack)
        );
        Summary {
            scene: r.header.scene.name.clone(),
            stopped: Stopped::of(&r.header),
            model: Model {
                track: r.setup.rolling.curve.kind().into(),
                unknowns: r.header.unknowns,
                formulation: r.setup.formulation.name().into(),
            },
            solver: Solver::of(&r.header),
            energy: Energy::of(&r.header),
            disk: DiskSummary {
                s: d.s,
                x: d.x,
                y: d.y,
                vx: d.vx,
                vy: d.vy,
                omega: d.omega,
                rn_min: rn.min,
                rn_max: rn.max,
                rt_min: rt.min,
                rt_max: rt.max,
                mu_needed_max: (mu.seen()
                    && !crate::run::lifted_off_rolling(&r.flights, r.header.stop))
                .then_some(mu.max),
                left_track_t: left.then_some(r.last.t),
                flights: r.flights.clone(),
            },
        }
    }
}
