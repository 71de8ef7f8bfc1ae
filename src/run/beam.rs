//! A run of a loaded beam: integrate, and record probe histories, envelopes along the beam,
//! deformed shapes and the energy budget (kinetic + strain − work of the loads).

use super::{EnergyCheck, Overrides, Progress, Stop};
use crate::beam::dynamics::LoadedBeam;
use crate::beam::{Beam, PointDisplacement};
use crate::error::Error;
use crate::linalg::{self, SparseLu};
use crate::ode::second_order::SecondOrderProblem;
use crate::ode::second_order::{solve_genalpha, FirstOrder};
use crate::ode::{self, Method, Observer, Stats};
use crate::scene::{BeamScene, PointLoad, Scene};

/// Points along the beam where envelopes and shapes are sampled.
pub const SAMPLES: usize = 201;

#[derive(Clone, Debug)]
pub struct BeamRow {
    pub t: f64,
    /// One per probe, in the scene's order.
    pub probes: Vec<PointDisplacement>,
    pub kinetic: f64,
    pub strain: f64,
    pub work: f64,
    /// What the supports exert on the beam, global (fx, fy, mz), at `from` and at `to`.
    pub reactions: [[f64; 3]; 2],
}

impl BeamRow {
    pub fn total(&self) -> f64 {
        self.kinetic + self.strain - self.work
    }
}

/// Min and max over time of u, w and φ at each sample point.
#[derive(Clone, Debug)]
pub struct Envelope {
    pub x: Vec<f64>,
    pub min: Vec<PointDisplacement>,
    pub max: Vec<PointDisplacement>,
}

pub struct BeamRun {
    pub scene: Scene,
    pub setup: BeamScene,
    pub beam: Beam,
    pub method: Method,
    pub rtol: f64,
    pub atol: f64,
    pub rows: Vec<BeamRow>,
    pub envelope: Envelope,
    /// Displacements at the sample points at each requested shape time.
    pub shapes: Vec<(f64, Vec<PointDisplacement>)>,
    pub stop: Stop,
    pub t_end: f64,
    /// (q, v) at the end of the run.
    pub y_end: Vec<f64>,
    pub stats: Stats,
    pub energy: EnergyCheck,
}

/// Work of constant point loads, exact: within a step the active set is fixed, so each load
/// adds P·Δd (and M_z Δφ) at its point.
struct Work {
    t: f64,
    done: f64,
    at_loads: Vec<PointDisplacement>,
}

fn load_displacements(beam: &Beam, loads: &[PointLoad], q: &[f64]) -> Vec<PointDisplacement> {
    loads.iter().map(|l| beam.displacement_at(q, l.x)).collect()
}

fn work_since(
    loads: &[PointLoad],
    t0: f64,
    t1: f64,
    from: &[PointDisplacement],
    to: &[PointDisplacement],
) -> f64 {
    let mid = 0.5 * (t0 + t1);
    loads
        .iter()
        .zip(from.iter().zip(to))
        .filter(|(l, _)| l.active(mid))
        .map(|(l, (a, b))| {
            l.force[0] * (b.u - a.u) + l.force[1] * (b.w - a.w) + l.mz * (b.phi - a.phi)
        })
        .sum()
}

struct Recorder<'a> {
    beam: &'a Beam,
    loaded: &'a LoadedBeam<'a>,
    /// The mass matrix, factorised once: accelerations for the support reactions.
    mass_lu: SparseLu,
    setup: &'a BeamScene,
    xs: Vec<f64>,
    rows: Vec<BeamRow>,
    envelope: Envelope,
    shapes: Vec<(f64, Vec<PointDisplacement>)>,
    work: Work,
    energy: EnergyCheck,
    progress: Option<Progress>,
    mv: Vec<f64>,
}

impl Recorder<'_> {
    fn energies(&mut self, y: &[f64]) -> (f64, f64) {
        let n = self.beam.dim();
        linalg::mul(self.beam.mass(), &y[n..], &mut self.mv);
        let kinetic = 0.5 * y[n..].iter().zip(&self.mv).map(|(a, b)| a * b).sum::<f64>();
        (kinetic, self.beam.strain_energy(&y[..n]))
    }
}

impl Observer for Recorder<'_> {
    fn output(&mut self, t: f64, y: &[f64]) {
        let n = self.beam.dim();
        let q = &y[..n];
        let (kinetic, strain) = self.energies(y);
        let now = load_displacements(self.beam, &self.setup.loads, q);
        let work = self.work.done
            + work_since(&self.setup.loads, self.work.t, t, &self.work.at_loads, &now);
        self.energy
            .record(kinetic + strain - work, kinetic + strain);
        let probes = self
            .setup
            .probes
            .iter()
            .map(|p| self.beam.displacement_at(q, p.x))
            .collect();
        let mut a = vec![0.0; n];
        self.loaded.force(t, q, &y[n..], &mut a);
        self.mass_lu.solve_in_place(&mut a);
        let acting: Vec<(f64, [f64; 2], f64)> = self
            .loaded
            .active(t)
            .map(|l| (l.x, l.force, l.mz))
            .collect();
        let reactions = self.beam.support_reactions(q, &acting, Some(&a));
        self.rows.push(BeamRow {
            t,
            probes,
            kinetic,
            strain,
            work,
            reactions,
        });
        let along: Vec<PointDisplacement> = self
            .xs
            .iter()
            .map(|&x| self.beam.displacement_at(q, x))
            .collect();
        for (k, d) in along.iter().enumerate() {
            let (lo, hi) = (&mut self.envelope.min[k], &mut self.envelope.max[k]);
            lo.u = lo.u.min(d.u);
            lo.w = lo.w.min(d.w);
            lo.phi = lo.phi.min(d.phi);
            hi.u = hi.u.max(d.u);
            hi.w = hi.w.max(d.w);
            hi.phi = hi.phi.max(d.phi);
        }
        if self.setup.shapes.iter().any(|&s| (s - t).abs() < 1e-9) {
            self.shapes.push((t, along));
        }
    }

    fn step(&mut self, t: f64, y: &[f64]) {
        let n = self.beam.dim();
        let now = load_displacements(self.beam, &self.setup.loads, &y[..n]);
        self.work.done += work_since(&self.setup.loads, self.work.t, t, &self.work.at_loads, &now);
        self.work.t = t;
        self.work.at_loads = now;
        let (kinetic, strain) = self.energies(y);
        self.energy
            .record(kinetic + strain - self.work.done, kinetic + strain);
        if let Some(p) = &mut self.progress {
            p.update(t);
        }
    }
}

pub fn run(
    scene: &Scene,
    setup: &BeamScene,
    over: &Overrides,
    show_progress: bool,
) -> Result<BeamRun, Error> {
    let beam = Beam::new(setup.beam.clone());
    let loaded = LoadedBeam::new(&beam, &setup.loads);
    let n = beam.dim();
    let opts = over.options(scene);
    let (method, rtol, atol) = (opts.method, opts.rtol, opts.atol);
    let mut outputs = super::output_times(scene);
    outputs.extend(setup.shapes.iter().copied());
    outputs.sort_by(f64::total_cmp);
    outputs.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let xs: Vec<f64> = (0..SAMPLES)
        .map(|k| beam.length * k as f64 / (SAMPLES - 1) as f64)
        .collect();
    let zero = PointDisplacement::default();
    let big = PointDisplacement {
        u: f64::INFINITY,
        w: f64::INFINITY,
        phi: f64::INFINITY,
    };
    let small = PointDisplacement {
        u: f64::NEG_INFINITY,
        w: f64::NEG_INFINITY,
        phi: f64::NEG_INFINITY,
    };
    let mass_lu = SparseLu::factor(beam.mass(), None).ok_or_else(|| {
        Error::Solver(format!("scene {}: the mass matrix is singular", scene.name))
    })?;
    let mut rec = Recorder {
        beam: &beam,
        loaded: &loaded,
        mass_lu,
        setup,
        envelope: Envelope {
            x: xs.clone(),
            min: vec![big; SAMPLES],
            max: vec![small; SAMPLES],
        },
        xs,
        rows: Vec::with_capacity(outputs.len()),
        shapes: Vec::new(),
        work: Work {
            t: 0.0,
            done: 0.0,
            at_loads: vec![zero; setup.loads.len()],
        },
        energy: EnergyCheck::new(0.0, 0.0),
        progress: if show_progress {
            Progress::new(scene.duration)
        } else {
            None
        },
        mv: vec![0.0; n],
    };
    let zeros = vec![0.0; n];
    let out = match method {
        Method::GenAlpha => solve_genalpha(
            &loaded,
            setup.rho_inf,
            0.0,
            &zeros,
            &zeros,
            scene.duration,
            &outputs,
            &opts,
            &mut rec,
        ),
        Method::Dopri5 | Method::TrBdf2 => {
            let first = FirstOrder::new(&loaded);
            ode::solve(
                &first,
                0.0,
                &vec![0.0; 2 * n],
                scene.duration,
                &outputs,
                &opts,
                &mut rec,
            )
        }
    }
    .map_err(|e| Error::Solver(format!("scene {}: the solver failed: {e}", scene.name)))?;
    if let Some(p) = &rec.progress {
        p.finish();
    }
    Ok(BeamRun {
        scene: scene.clone(),
        setup: setup.clone(),
        method,
        rtol,
        atol,
        rows: rec.rows,
        envelope: rec.envelope,
        shapes: rec.shapes,
        stop: Stop::End,
        t_end: out.t,
        y_end: out.y,
        stats: out.stats,
        energy: rec.energy,
        beam,
    })
}
