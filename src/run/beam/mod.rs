//! A run of a loaded beam, with or without a disk on it: integrate, and record probe histories,
//! envelopes along the beam, deformed shapes, the disk's quantities and the energy budget
//! (kinetic + strain + potential − work of the loads).
//!
//! With a disk the run has two phases: the coupled one, until the disk leaves the beam at an
//! end (or stops at a physical event), then the beam alone, vibrating freely to the end.

use super::{EnergyCheck, Overrides, Progress, Stop};
use crate::analysis::statics;
use crate::beam::dynamics::LoadedBeam;
use crate::beam::load::{BeamStart, PointLoad};
use crate::beam::{Beam, PointDisplacement, Stations};
use crate::coupling::thesis_system::ThesisSystem;
use crate::coupling::{Coupling, DiskOnBeam};
use crate::error::Error;
use crate::linalg::{self, SparseLu};
use crate::ode::second_order::FirstOrder;
use crate::ode::second_order::{SecondOrderProblem, Structure};
use crate::ode::{self, Method, Observer, Stats};
use crate::rolling::{DiskObservation, StopReason};
use crate::scene::{BeamScene, Scene};

/// Points along the beam where envelopes and shapes are sampled.
pub const SAMPLES: usize = 201;
/// Frames an animation of a run holds at most.
pub const FRAMES: usize = 240;

#[derive(Clone, Debug)]
pub struct Frame {
    pub t: f64,
    pub along: Vec<PointDisplacement>,
    /// Contact point s and the angle the disk has turned through, while it is on the beam.
    pub disk: Option<(f64, f64)>,
}

#[derive(Clone, Debug)]
pub struct BeamRow {
    pub t: f64,
    /// One per probe, in the scene's order.
    pub probes: Vec<PointDisplacement>,
    /// While the disk is on the beam.
    pub disk: Option<DiskObservation>,
    /// Deflection w of the beam under the disk (NaN without one).
    pub w_under: f64,
    pub kinetic: f64,
    pub strain: f64,
    /// The disk's gravity potential (zero without a disk in the system).
    pub potential: f64,
    pub work: f64,
    /// What the supports exert on the beam, global (fx, fy, mz), at `from` and at `to`.
    pub reactions: [[f64; 3]; 2],
}

impl BeamRow {
    pub fn total(&self) -> f64 {
        self.kinetic + self.strain + self.potential - self.work
    }
}

/// Min and max over time of u, w and φ at each sample point.
#[derive(Clone, Debug)]
pub struct Envelope {
    pub x: Vec<f64>,
    pub min: Vec<PointDisplacement>,
    pub max: Vec<PointDisplacement>,
    /// The largest length the deformed axis reached minus L (over the sample polyline).
    pub stretch_max: f64,
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
    /// Displacements at the sample points on a coarse grid of times (at most [`FRAMES`]),
    /// with the disk's contact point and turned angle while it is on the beam: the animation.
    pub frames: Vec<Frame>,
    pub stop: Stop,
    pub t_end: f64,
    /// When the disk left the beam, if it did.
    pub left_track_t: Option<f64>,
    /// Unknowns of the coupled model (beam, and the contact point where it is one).
    pub unknowns: usize,
    /// (q, v) at the end of the run.
    pub y_end: Vec<f64>,
    pub stats: Stats,
    pub energy: EnergyCheck,
}

impl BeamRun {
    /// Half the range of w at probe k after the disk left the beam: the residual vibration.
    /// `None` without an exit, or with no output row after it.
    pub fn amplitude_after_exit(&self, k: usize) -> Option<f64> {
        let te = self.left_track_t?;
        let (lo, hi) = self
            .rows
            .iter()
            .filter(|row| row.t > te)
            .map(|row| row.probes[k].w)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            });
        (hi >= lo).then(|| 0.5 * (hi - lo))
    }
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
    /// The disk while it is on the beam; the state is then (z, ż) with z = (q, s) or q.
    coupled: Option<&'a DiskOnBeam<'a>>,
    nz: usize,
    /// The mass matrix, factorised once: accelerations for the support reactions.
    mass_lu: SparseLu,
    setup: &'a BeamScene,
    xs: Vec<f64>,
    /// The beam's axis sampled at xs.
    stations: Stations,
    rows: Vec<BeamRow>,
    envelope: Envelope,
    shapes: Vec<(f64, Vec<PointDisplacement>)>,
    frames: Vec<Frame>,
    frame_every: f64,
    /// The disk's turned angle, by the trapezoidal rule on the output rows: (t, Ω, angle).
    turned: (f64, f64, f64),
    work: Work,
    /// Work of a moving load, by the trapezoidal rule over the steps: (t, power, work).
    moving: (f64, f64, f64),
    /// The disk's energy when it left (it leaves the model with it): (kinetic, potential).
    disk_energy: (f64, f64),
    energy: EnergyCheck,
    progress: Option<Progress>,
    mv: Vec<f64>,
}

impl Recorder<'_> {
    fn beam_state<'y>(&self, y: &'y [f64]) -> (&'y [f64], &'y [f64]) {
        let n = self.beam.dim();
        (&y[..n], &y[self.nz..self.nz + n])
    }

    fn energies(&mut self, y: &[f64]) -> (f64, f64) {
        let n = self.beam.dim();
        let v = y[self.nz..self.nz + n].to_vec();
        linalg::mul(self.beam.mass(), &v, &mut self.mv);
        let kinetic = 0.5 * v.iter().zip(&self.mv).map(|(a, b)| a * b).sum::<f64>();
        (kinetic, self.beam.strain_energy(&y[..n]))
    }

    fn disk(&self, t: f64, y: &[f64]) -> Option<DiskObservation> {
        self.coupled
            .map(|c| c.observe(t, &y[..self.nz], &y[self.nz..]))
    }

    /// Kinetic and potential energy of the disk, as far as it belongs to the system.
    fn disk_energies(&self, disk: Option<&DiskObservation>) -> (f64, f64) {
        match (disk, self.coupled) {
            (Some(d), Some(c)) if c.disk_in_system() => (d.kinetic, d.potential),
            (Some(_), Some(_)) => (0.0, 0.0),
            _ => self.disk_energy,
        }
    }

    fn moving_work(&self, t: f64, y: &[f64]) -> f64 {
        let (t0, p0, done) = self.moving;
        match self.coupled {
            Some(c) if !c.disk_in_system() => {
                let p = c.power_on_beam(t, &y[..self.nz], &y[self.nz..]);
                done + 0.5 * (p0 + p) * (t - t0)
            }
            _ => done,
        }
    }
}

impl Observer for Recorder<'_> {
    fn output(&mut self, t: f64, y: &[f64]) {
        let n = self.beam.dim();
        let (q, v) = self.beam_state(y);
        let (kinetic, strain) = self.energies(y);
        let disk = self.disk(t, y);
        let (disk_kinetic, potential) = self.disk_energies(disk.as_ref());
        let kinetic = kinetic + disk_kinetic;
        let now = load_displacements(self.beam, &self.setup.loads, q);
        let work = self.work.done
            + work_since(&self.setup.loads, self.work.t, t, &self.work.at_loads, &now)
            + self.moving_work(t, y);
        self.energy.record(
            kinetic + strain + potential - work,
            kinetic + strain + potential.abs(),
        );
        let probes = self
            .setup
            .probes
            .iter()
            .map(|p| self.beam.displacement_at(q, p.x))
            .collect();
        let mut acting: Vec<(f64, [f64; 2], f64)> = self
            .loaded
            .active(t)
            .map(|l| (l.x, l.force, l.mz))
            .collect();
        let a = match self.coupled {
            Some(c) => {
                let d = disk.expect("observed while coupled");
                let z = &y[..self.nz];
                let at_s = c.contact_frame(t, z, &y[self.nz..]);
                let on_disk = [
                    d.rt * at_s[0][0] + d.rn * at_s[1][0],
                    d.rt * at_s[0][1] + d.rn * at_s[1][1],
                ];
                acting.push((d.s, [-on_disk[0], -on_disk[1]], 0.0));
                c.observe_with_acceleration(t, z, &y[self.nz..])
                    .1
                    .map(|a| a[..n].to_vec())
                    .unwrap_or_else(|| vec![f64::NAN; n])
            }
            None => {
                let mut a = vec![0.0; n];
                self.loaded.force(t, q, v, &mut a);
                self.mass_lu.solve_in_place(&mut a);
                a
            }
        };
        let reactions = self.beam.support_reactions(q, &acting, Some(&a));
        let w_under = disk.map_or(f64::NAN, |d| self.beam.displacement_at(q, d.s).w);
        self.rows.push(BeamRow {
            t,
            probes,
            disk,
            w_under,
            kinetic,
            strain,
            potential,
            work,
            reactions,
        });
        let along = self.beam.displacements(&self.stations, q);
        let length: f64 = self
            .xs
            .windows(2)
            .zip(along.windows(2))
            .map(|(x, d)| (x[1] + d[1].u - x[0] - d[0].u).hypot(d[1].w - d[0].w))
            .sum();
        self.envelope.stretch_max = self.envelope.stretch_max.max(length - self.beam.length);
        for (k, d) in along.iter().enumerate() {
            let (lo, hi) = (&mut self.envelope.min[k], &mut self.envelope.max[k]);
            lo.u = lo.u.min(d.u);
            lo.w = lo.w.min(d.w);
            lo.phi = lo.phi.min(d.phi);
            hi.u = hi.u.max(d.u);
            hi.w = hi.w.max(d.w);
            hi.phi = hi.phi.max(d.phi);
        }
        if let Some(d) = disk {
            let (t0, w0, angle) = self.turned;
            self.turned = (t, d.omega, angle + 0.5 * (w0 + d.omega) * (t - t0));
        }
        if self
            .frames
            .last()
            .is_none_or(|f| t >= f.t + self.frame_every - 1e-9)
        {
            self.frames.push(Frame {
                t,
                along: along.clone(),
                disk: disk.map(|d| (d.s, self.turned.2)),
            });
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
        if let Some(c) = self.coupled.filter(|c| !c.disk_in_system()) {
            let p = c.power_on_beam(t, &y[..self.nz], &y[self.nz..]);
            let w = self.moving_work(t, y);
            self.moving = (t, p, w);
        }
        let (kinetic, strain) = self.energies(y);
        let disk = if self.coupled.is_some_and(|c| c.disk_in_system()) {
            self.disk(t, y)
        } else {
            None
        };
        let (disk_kinetic, potential) = match disk {
            Some(d) => (d.kinetic, d.potential),
            None if self.coupled.is_some() => (0.0, 0.0),
            None => self.disk_energy,
        };
        let kinetic = kinetic + disk_kinetic;
        self.energy.record(
            kinetic + strain + potential - self.work.done - self.moving.2,
            kinetic + strain + potential.abs(),
        );
        if let Some(p) = &mut self.progress {
            p.update(t);
        }
    }
}

/// Hands the recorder the reduced state (q, s; v, ṡ) of the literal thesis system.
struct Literal<'a, 'r> {
    sys: &'a ThesisSystem<'a>,
    rec: &'a mut Recorder<'r>,
}

impl Observer for Literal<'_, '_> {
    fn output(&mut self, t: f64, y: &[f64]) {
        let r = self.sys.reduced(t, y);
        self.rec.output(t, &r);
    }
    fn step(&mut self, t: f64, y: &[f64]) {
        let r = self.sys.reduced(t, y);
        self.rec.step(t, &r);
    }
}

/// The beam's displacements at t = 0: undeformed, or in static equilibrium under the loads
/// active at t = 0 and the disk resting at s0. The disk's force follows the beam's slope under
/// it, so the equilibrium is found by repeating the static solve with the force re-taken on the
/// last shape, until the shape settles to round-off (it moves by the square of the slopes).
fn start_state(
    scene: &Scene,
    setup: &BeamScene,
    loaded: &LoadedBeam,
    coupled: Option<&DiskOnBeam>,
) -> Result<Vec<f64>, Error> {
    let beam = loaded.beam;
    let n = beam.dim();
    let mut q = vec![0.0; n];
    if setup.start == BeamStart::Rest {
        return Ok(q);
    }
    let mut loads = vec![0.0; n];
    loaded.external(0.0, &mut loads);
    for _ in 0..START_ITERATIONS {
        let mut f = loads.clone();
        if let Some(c) = coupled {
            c.add_weight_at_rest(&q, &mut f);
        }
        let next = statics::solve(beam, &f)
            .map_err(|e| Error::Solver(format!("scene {}: the static start: {e}", scene.name)))?
            .q;
        let size = next.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let change = next
            .iter()
            .zip(&q)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        q = next;
        if coupled.is_none() || change <= 1e-12 * size {
            return Ok(q);
        }
    }
    Err(Error::Solver(format!(
        "scene {}: the static start did not settle in {START_ITERATIONS} solves: the disk's weight turns the beam too far for a resting start",
        scene.name
    )))
}

/// Static solves the resting start may take (each moves the shape by the square of the last
/// change in slope, so a few suffice unless the disk overturns the beam).
const START_ITERATIONS: usize = 8;

fn solver_error(scene: &Scene, e: ode::SolveError) -> Error {
    Error::Solver(format!("scene {}: the solver failed: {e}", scene.name))
}

/// Integrate one structural problem from (q0, v0) at t0 with the run's method.
#[allow(clippy::too_many_arguments)]
fn integrate<E: Copy + std::fmt::Debug>(
    p: &dyn SecondOrderProblem<Event = E>,
    t0: f64,
    q0: &[f64],
    v0: &[f64],
    t_end: f64,
    outputs: &[f64],
    opts: &ode::Options,
    rec: &mut Recorder,
) -> Result<ode::Outcome<E>, ode::SolveError> {
    let y0: Vec<f64> = q0.iter().chain(v0).copied().collect();
    ode::solve(&FirstOrder::new(p), t0, &y0, t_end, outputs, opts, rec)
}

fn add_stats(total: &mut Stats, more: &Stats) {
    total.steps += more.steps;
    total.rejected += more.rejected;
    total.rhs_evals += more.rhs_evals;
    total.jacobians += more.jacobians;
    total.factorizations += more.factorizations;
    total.newton_iterations += more.newton_iterations;
    total.wall_s += more.wall_s;
}

pub fn run(
    scene: &Scene,
    setup: &BeamScene,
    over: &Overrides,
    show_progress: bool,
) -> Result<BeamRun, Error> {
    let beam = Beam::new(setup.beam.clone());
    let loaded = LoadedBeam::new(&beam, &setup.loads);
    let coupled = setup
        .disk
        .clone()
        .map(|spec| DiskOnBeam::new(&loaded, spec));
    let n = beam.dim();
    let opts = ode::Options {
        rho_inf: setup.rho_inf,
        ..over.options(scene)
    };
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
    // The thesis coupling with a first-order integrator is the published 3n + 6 system.
    let literal = coupled
        .as_ref()
        .is_some_and(|c| c.spec.coupling == Coupling::Thesis)
        && method != Method::GenAlpha;
    let unknowns = match &coupled {
        None => n,
        Some(_) if literal => n + 6,
        Some(c) => c.dim(),
    };
    let mut rec = Recorder {
        beam: &beam,
        loaded: &loaded,
        coupled: coupled.as_ref(),
        nz: coupled.as_ref().map_or(n, |c| c.dim()),
        mass_lu,
        setup,
        envelope: Envelope {
            x: xs.clone(),
            min: vec![big; SAMPLES],
            max: vec![small; SAMPLES],
            stretch_max: f64::NEG_INFINITY,
        },
        stations: beam.stations(&xs),
        xs,
        rows: Vec::with_capacity(outputs.len()),
        shapes: Vec::new(),
        frames: Vec::new(),
        frame_every: scene.duration / (FRAMES - 1) as f64,
        turned: (0.0, setup.disk.as_ref().map_or(0.0, |d| d.omega0), 0.0),
        work: Work {
            t: 0.0,
            done: 0.0,
            at_loads: vec![zero; setup.loads.len()],
        },
        moving: (0.0, 0.0, 0.0),
        disk_energy: (0.0, 0.0),
        energy: EnergyCheck::new(0.0, 0.0),
        progress: if show_progress {
            Progress::new(scene.duration)
        } else {
            None
        },
        mv: vec![0.0; n],
    };
    let mut stop = Stop::End;
    let mut left_track_t = None;
    let mut stats = Stats::default();
    let start = start_state(scene, setup, &loaded, coupled.as_ref())?;
    let strain0 = beam.strain_energy(&start);
    rec.energy = EnergyCheck::new(strain0, strain0);
    rec.work.at_loads = load_displacements(&beam, &setup.loads, &start);
    let (t_end, y_end) = 'phases: {
        let (mut t0, mut q0, mut v0) = (0.0, start.clone(), vec![0.0; n]);
        if let Some(c) = &coupled {
            let (z0, zd0) = c.initial_state(&start);
            let first = c.observe(0.0, &z0, &zd0);
            let (dk, dp) = if c.disk_in_system() {
                (first.kinetic, first.potential)
            } else {
                (0.0, 0.0)
            };
            rec.energy = EnergyCheck::new(dk + dp + strain0, dk + dp.abs() + strain0);
            if !c.spec.coupling.rolls() {
                rec.moving = (0.0, c.power_on_beam(0.0, &z0, &zd0), 0.0);
            }
            let until = c
                .exit_time()
                .map_or(scene.duration, |te| te.min(scene.duration));
            let (out, y_end) = if literal {
                let sys = ThesisSystem { coupled: c };
                let mut through = Literal {
                    sys: &sys,
                    rec: &mut rec,
                };
                let out = ode::solve(
                    &sys,
                    0.0,
                    &sys.initial_state(&start),
                    until,
                    &outputs,
                    &opts,
                    &mut through,
                )
                .map_err(|e| solver_error(scene, e))?;
                let y = sys.reduced(out.t, &out.y);
                (out, y)
            } else {
                let out = integrate(c, 0.0, &z0, &zd0, until, &outputs, &opts, &mut rec)
                    .map_err(|e| solver_error(scene, e))?;
                let y = out.y.clone();
                (out, y)
            };
            add_stats(&mut stats, &out.stats);
            let nz = c.dim();
            let (z, zd) = y_end.split_at(nz);
            let left = match &out.stopped_by {
                None => out.t < scene.duration,
                Some(hit) if hit.reason == StopReason::LeftTrack => true,
                Some(hit) => {
                    stop = Stop::Event(hit.reason);
                    false
                }
            };
            if !left {
                // The run stops between output times: its last row is the stop itself.
                if rec.rows.last().is_none_or(|r| r.t < out.t) {
                    rec.output(out.t, &y_end);
                }
                break 'phases (out.t, y_end.clone());
            }
            t0 = out.t;
            q0.copy_from_slice(&z[..n]);
            v0.copy_from_slice(&zd[..n]);
            left_track_t = Some(out.t);
            let d = c.observe(out.t, z, zd);
            rec.disk_energy = if c.disk_in_system() {
                (d.kinetic, d.potential)
            } else {
                (0.0, 0.0)
            };
            rec.work.done += rec.moving.2;
            rec.moving = (out.t, 0.0, 0.0);
        }
        rec.coupled = None;
        rec.nz = n;
        let rest: Vec<f64> = outputs.iter().copied().filter(|&o| o > t0).collect();
        let out = integrate(
            &loaded,
            t0,
            &q0,
            &v0,
            scene.duration,
            &rest,
            &opts,
            &mut rec,
        )
        .map_err(|e| solver_error(scene, e))?;
        add_stats(&mut stats, &out.stats);
        (out.t, out.y)
    };
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
        frames: rec.frames,
        stop,
        t_end,
        left_track_t,
        unknowns,
        y_end,
        stats,
        energy: rec.energy,
        beam,
    })
}
