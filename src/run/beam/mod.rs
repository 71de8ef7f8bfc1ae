//! A run of a loaded beam, with or without a disk on it: integrate, and record probe histories,
//! envelopes along the beam, deformed shapes, the disk's quantities and the energy budget
//! (kinetic + strain + potential − work of the loads).
//!
//! With a disk the run has two phases (`phase.rs`): the coupled one, until the disk leaves the
//! beam at an end (or stops at a physical event), then the beam alone, vibrating freely to the
//! end. The energy budget is kept by `ledger.rs`; the outputs are recorded by the sensors of
//! `sensors.rs`, which observe and compute nothing. [`run`] names the phases of a run.

mod acceleration;
mod flight;
mod ledger;
mod phase;
mod sensors;

use super::extremes::{Range, Turning, Watch};
use acceleration::AccelerationFilter;
pub use acceleration::CutoffReport;
use flight::{BeneathFlight, FlightEvent, FlyingDisk};
use ledger::Ledger;
use phase::Phase;
pub use sensors::MEAN_WINDOWS;
use sensors::{History, Pictures, Sample, WindowedMeans};

use super::{FlightRecord, Overrides, Progress, RunHeader, Stop, MAX_FLIGHTS};
use crate::analysis::modes::modes;
use crate::analysis::statics;
use crate::beam::damping::Rayleigh;
use crate::beam::dynamics::LoadedBeam;
use crate::beam::load::BeamStart;
use crate::beam::modal::ModalBasis;
use crate::beam::{Beam, BeamModel, PointDisplacement, Stations};
use crate::coupling::landing::Landing;
use crate::coupling::thesis_system::ThesisSystem;
use crate::coupling::{Coupling, DiskOnBeam};
use crate::error::Error;
use crate::linalg::SparseLu;
use crate::ode::second_order::FirstOrder;
use crate::ode::second_order::{SecondOrderProblem, Structure};
use crate::ode::{self, Dense, Method, Observer, Stats};
use crate::rolling::flight::Flight;
use crate::rolling::{ContactLoss, DiskObservation, StopReason};
use crate::scene::{BeamScene, Scene};

/// Points along the beam where envelopes and shapes are sampled.
pub const SAMPLES: usize = 201;
/// Frames an animation of a run holds at most.
pub const FRAMES: usize = 240;
/// Samples of the extremes' watch a period of the acceleration's cutoff, where the steps are
/// shorter (see `Recorder::watch`).
const SAMPLES_PER_CUTOFF_PERIOD: f64 = 32.0;
/// Samples of the watch, where the steps are shorter, to the time a disk takes to cross its
/// contact patch's half-width.
const SAMPLES_PER_PATCH: f64 = 20.0;

#[derive(Clone, Debug)]
pub struct Frame {
    pub t: f64,
    pub along: Vec<PointDisplacement>,
    /// Contact point s (in flight, the nearest point), the angle the disk has turned through,
    /// and its gap to the beam (0 while it rolls), while it is on or over the beam.
    pub disk: Option<(f64, f64, f64)>,
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
    /// What damping has taken since the start.
    pub dissipated: f64,
    /// What the disk's landings have taken since the start.
    pub impact: f64,
    /// The flying disk's gap to the beam (0 while it rolls).
    pub gap: f64,
    /// One per probe: the vertical (global Y) acceleration, with the modes above the cutoff
    /// left out (see [`AccelerationFilter`]).
    pub accelerations: Vec<f64>,
    /// What the supports exert on the beam, global (fx, fy, mz), at `from` and at `to`.
    pub reactions: [[f64; 3]; 2],
}

impl BeamRow {
    pub fn total(&self) -> f64 {
        self.kinetic + self.strain + self.potential - self.work + self.dissipated + self.impact
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
    /// The largest vertical acceleration over the sample points (filtered as the probes'),
    /// with where and when: (|a|, x, t).
    pub a_max: (f64, f64, f64),
}

pub struct BeamRun {
    pub header: RunHeader,
    pub setup: BeamScene,
    pub beam: Beam,
    pub rows: Vec<BeamRow>,
    pub envelope: Envelope,
    /// Displacements at the sample points at each requested shape time.
    pub shapes: Vec<(f64, Vec<PointDisplacement>)>,
    /// Displacements at the sample points on a coarse grid of times (at most [`FRAMES`]),
    /// with the disk's contact point and turned angle while it is on the beam: the animation.
    /// Empty unless [`Overrides::animate`] asked for them.
    pub frames: Vec<Frame>,
    /// Each probe's Hann-windowed mean deflection over [`MEAN_WINDOWS`] equal windows of the
    /// run, probe-major, for the windows the run covered whole: a headline the fast modes'
    /// phase leaves alone. Empty unless [`Overrides::windowed_means`] asked for them.
    pub windowed_means: Vec<f64>,
    /// The extremes of what the run reports, located on the solution.
    pub extremes: Extremes,
    /// When the disk left the beam, if it did.
    pub left_track_t: Option<f64>,
    /// The disk's flights over the beam.
    pub flights: Vec<FlightRecord>,
    /// (q, v) at the end of the run.
    pub y_end: Vec<f64>,
    /// What the recorded accelerations count.
    pub acceleration: Option<CutoffReport>,
    /// The Rayleigh damping the run had, α and β resolved.
    pub damping: Option<Rayleigh>,
}

/// The extremes over the run of what the summary reports, each located on the solution
/// ([`super::extremes`]).
#[derive(Clone, Debug, Default)]
pub struct Extremes {
    /// Per probe: u, w, φ and the vertical acceleration (filtered as recorded).
    pub probes: Vec<[Range; 4]>,
    /// Per probe: w after the last load left the beam (the disk, or a train's last axle).
    pub after_exit: Option<Vec<Range>>,
    /// The disk's normal and tangential contact force, the friction coefficient its rolling
    /// needs and the deflection under it, while it is on or over the beam.
    pub disk: Option<[Range; 4]>,
}

impl BeamRun {
    /// Half the range of w at probe k after the last load left the beam: the residual
    /// vibration. `None` without an exit, or with nothing of the run after it.
    pub fn amplitude_after_exit(&self, k: usize) -> Option<f64> {
        self.extremes.after_exit.as_ref()?.get(k)?.half_range()
    }
}

/// What the watches see of the run at one time: each probe's (u, w, φ, a); the disk's (rn,
/// rt, μ needed, w under it, gap) while it is on or over the beam; and when asked, the
/// envelope's stations' (u, w, φ, a) and the stretch of the axis.
struct Snapshot {
    probes: Vec<f64>,
    disk: Option<[f64; 5]>,
    along: Vec<f64>,
}

impl Snapshot {
    /// Each probe's w.
    fn deflections(&self) -> Vec<f64> {
        self.probes.iter().skip(1).step_by(4).copied().collect()
    }
}

/// The quantities watched for their extremes (`extremes.rs`); `along` takes the parabola's
/// turning values, as it holds every station of the envelope.
struct Watches {
    probes: Watch,
    after_exit: Watch,
    disk: Watch,
    /// The gap of the current flight.
    gap: Watch,
    along: Watch,
}

impl Watches {
    fn new(probes: usize, stations: usize) -> Self {
        Watches {
            probes: Watch::new(4 * probes, Turning::OnTheSolution),
            after_exit: Watch::new(probes, Turning::OnTheSolution),
            disk: Watch::new(4, Turning::OnTheSolution),
            gap: Watch::new(1, Turning::OnTheSolution),
            along: Watch::new(4 * stations + 1, Turning::OnTheParabola),
        }
    }
}

/// The run's observer: at every output time the phase gives the disk and the reactions, the
/// ledger the energies, and the sensors record them; at every step the ledger books the work.
struct Recorder<'a> {
    phase: Phase<'a>,
    ledger: Ledger<'a>,
    /// The beam's axis at the envelope's sample points.
    stations: Stations,
    /// What of the acceleration is recorded.
    filter: Option<AccelerationFilter>,
    history: History<'a>,
    envelope: Envelope,
    pictures: Pictures<'a>,
    means: Option<WindowedMeans>,
    watches: Watches,
    /// The snapshot at the end of the last step watched.
    last: Option<(f64, Snapshot)>,
    /// The snapshot before that: with the stations, the start of the last step watched.
    before: Option<(f64, Snapshot)>,
    /// The least time between samples of steps far shorter than it (see `Recorder::watch`).
    spacing: f64,
    /// When the last load left the beam: from then on the residual vibration is watched.
    exit_t: Option<f64>,
    progress: Option<Progress>,
}

impl Recorder<'_> {
    /// What the watches see at (t, y); the stations only when `along` asks for them.
    fn snapshot(&self, t: f64, y: &[f64], rate: Option<&[f64]>, along: bool) -> Snapshot {
        let phase = &self.phase;
        let (disk, gap) = phase.disk(t, y);
        let q = phase.displaced(t, y, disk.as_ref());
        // The beam alone takes its accelerations from the dense output, without a solve for
        // them. With the disk on, the observation has solved for them already, and the
        // contact force, which the beam's acceleration under the disk enters, is sensitive
        // to it: the dense output's derivative moved D44's lowest contact force by 2e-3 of
        // the disk's weight against the acceleration of the interpolated state.
        let a = match (phase.coupled, rate) {
            (None, Some(yp)) => phase.split(yp).1[..phase.loaded.dim()].to_vec(),
            _ => phase.acceleration(t, y),
        };
        let a = match &self.filter {
            Some(f) => f.filtered(phase.loaded, &a),
            None => phase.loaded.to_mesh(&a).into_owned(),
        };
        let beam = phase.beam;
        let probes = self
            .history
            .probes
            .iter()
            .flat_map(|p| {
                let d = beam.displacement_at(&q, p.x);
                [d.u, d.w, d.phi, beam.displacement_at(&a, p.x).w]
            })
            .collect();
        let disk = disk.map(|d| {
            [
                d.rn,
                d.rt,
                d.mu_needed().unwrap_or(f64::NAN),
                beam.displacement_at(&q, d.s).w,
                gap,
            ]
        });
        let along = if along {
            let displaced = beam.displacements(&self.stations, &q);
            let accelerations = beam.deflections(&self.stations, &a);
            stations_watched(&self.envelope.x, &displaced, &accelerations)
        } else {
            Vec::new()
        };
        Snapshot {
            probes,
            disk,
            along,
        }
    }

    /// Take in the step [t0, t1] of the dense output `dense`: its start, middle and end, and
    /// the turning points between them that set an extreme.
    fn watch(&mut self, t0: f64, t1: f64, dense: &dyn Dense) {
        if !(t1 > t0) {
            return;
        }
        // Steps far shorter than the fastest thing reported (a sudden load's, at the defaults)
        // are watched at their ends only, every `spacing` s, the parabola through the last
        // three samples taken as it is: at 32 samples a period of the acceleration's cutoff
        // it is within 10⁻⁴ of that mode's amplitude, and on every step and middle the
        // watching cost a third of such a run. A disk's contact force also holds the crossing
        // of its patch over each node, faster than the cutoff: sampled every millisecond, D44's lowest
        // contact force moved by 1.4·10⁻³ of the weight; with a disk on or over the beam the
        // samples are also [`SAMPLES_PER_PATCH`] to the patch's crossing.
        let riding = (self.phase.coupled).or(self.phase.flying.as_ref().map(|f| f.coupled));
        let spacing = riding.map_or(self.spacing, |c| {
            let crossing = c.spec.patch / c.spec.v0().abs();
            self.spacing.min(crossing / SAMPLES_PER_PATCH)
        });
        if t1 - t0 < spacing {
            if self.last.as_ref().is_some_and(|(t, _)| t1 - t < spacing) {
                return;
            }
            let end = self.snapshot(t1, &dense.at(t1), dense.rate(t1).as_deref(), true);
            self.sampled(end, t1);
            return;
        }
        let mut w = std::mem::replace(&mut self.watches, Watches::new(0, 0));
        let last = self.last.take();
        let before = self.before.take();
        let flying = self.phase.flying.is_some();
        let after = self.exit_t.is_some_and(|te| t0 >= te);
        let see =
            |t: f64, along: bool| self.snapshot(t, &dense.at(t), dense.rate(t).as_deref(), along);
        // The stations are watched on the step ends alone, the parabola through the last
        // three (`before`, t0, t1): on every station at the middle too, they would cost more
        // than the rest of the run.
        let (start, before) = match last {
            Some((t, s)) if t == t0 => (s, before),
            _ => ((see(t0, true)), None),
        };
        let tm = 0.5 * (t0 + t1);
        let (middle, end) = (see(tm, false), see(t1, true));
        let t = [t0, tm, t1];
        let [s0, s1, s2] = [&start, &middle, &end];
        w.probes
            .record_step(t, [&s0.probes, &s1.probes, &s2.probes], |tt| {
                see(tt, false).probes
            });
        match before {
            Some((tb, b)) => {
                w.along
                    .record_step([tb, t0, t1], [&b.along, &s0.along, &s2.along], |_| {
                        Vec::new()
                    })
            }
            None => w.along.record_point(t1, &s2.along),
        }
        if after {
            w.after_exit.record_step(
                t,
                [&s0.deflections(), &s1.deflections(), &s2.deflections()],
                |tt| see(tt, false).deflections(),
            );
        }
        match (s0.disk, s1.disk, s2.disk) {
            (Some(d0), Some(d1), Some(d2)) => {
                let disk_at = |tt: f64| {
                    see(tt, false)
                        .disk
                        .map_or(vec![f64::NAN; 5], |d| d.to_vec())
                };
                w.disk
                    .record_step(t, [&d0[..4], &d1[..4], &d2[..4]], &disk_at);
                if flying {
                    w.gap.record_step(t, [&d0[4..], &d1[4..], &d2[4..]], |tt| {
                        disk_at(tt)[4..].to_vec()
                    });
                }
            }
            disks => {
                for (tt, d) in t.iter().zip([disks.0, disks.1, disks.2]) {
                    if let Some(d) = d {
                        w.disk.record_point(*tt, &d[..4]);
                    }
                }
            }
        }
        self.watches = w;
        self.before = Some((t0, start));
        self.last = Some((t1, end));
    }

    /// Take in a sample at t of the beam alone, on its own (a short step's end): with the
    /// two before it, the parabola through the three.
    fn sampled(&mut self, end: Snapshot, t: f64) {
        let w = &mut self.watches;
        let after = self.exit_t.is_some_and(|te| t >= te);
        match (self.before.take(), self.last.take()) {
            (Some((ta, a)), Some((tb, b))) => {
                let times = [ta, tb, t];
                w.probes
                    .record_parabola(times, [&a.probes, &b.probes, &end.probes]);
                w.along
                    .record_parabola(times, [&a.along, &b.along, &end.along]);
                if after && ta >= self.exit_t.unwrap_or(f64::INFINITY) {
                    w.after_exit.record_parabola(
                        times,
                        [&a.deflections(), &b.deflections(), &end.deflections()],
                    );
                }
                if let (Some(da), Some(db), Some(de)) = (a.disk, b.disk, end.disk) {
                    w.disk
                        .record_parabola(times, [&da[..4], &db[..4], &de[..4]]);
                    if self.phase.flying.is_some() {
                        w.gap.record_parabola(times, [&da[4..], &db[4..], &de[4..]]);
                    }
                }
                self.before = Some((tb, b));
            }
            (_, last) => {
                w.probes.record_point(t, &end.probes);
                w.along.record_point(t, &end.along);
                self.before = last;
            }
        }
        if after {
            w.after_exit.record_point(t, &end.deflections());
        }
        if let Some(d) = end.disk {
            w.disk.record_point(t, &d[..4]);
            if self.phase.flying.is_some() {
                w.gap.record_point(t, &d[4..]);
            }
        }
        self.last = Some((t, end));
    }

    /// The extremes watched, and the envelope from the stations'.
    fn extremes(&self) -> (Extremes, Envelope) {
        let w = &self.watches;
        let probes = w
            .probes
            .ranges
            .chunks(4)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect();
        let extremes = Extremes {
            probes,
            after_exit: self
                .exit_t
                .map(|_| w.after_exit.ranges.clone())
                .filter(|r| r.iter().all(Range::seen)),
            // Any value watched says the disk was on or over the beam.
            disk: w.disk.ranges.iter().any(Range::seen).then(|| {
                let r = &w.disk.ranges;
                [r[0], r[1], r[2], r[3]]
            }),
        };
        (extremes, self.envelope.from_stations(&w.along.ranges))
    }
}

/// The stations' (u, w, φ, a), then the stretch of the axis through them.
fn stations_watched(
    x: &[f64],
    along: &[crate::beam::PointDisplacement],
    accelerations: &[f64],
) -> Vec<f64> {
    let mut out: Vec<f64> = along
        .iter()
        .zip(accelerations)
        .flat_map(|(d, a)| [d.u, d.w, d.phi, *a])
        .collect();
    out.push(sensors::stretch(x, along));
    out
}

impl Observer for Recorder<'_> {
    fn output(&mut self, t: f64, y: &[f64]) {
        let phase = &self.phase;
        let (disk, gap) = phase.disk(t, y);
        let energy = self.ledger.at_output(phase, t, y, disk.as_ref());
        let q = phase.displaced(t, y, disk.as_ref());
        let a = phase.acceleration(t, y);
        let reactions = phase.reactions(t, y, &q, &a, disk.as_ref());
        let along = phase.beam.displacements(&self.stations, &q);
        let a = match &self.filter {
            Some(f) => f.filtered(phase.loaded, &a),
            None => phase.loaded.to_mesh(&a).into_owned(),
        };
        let along_a = phase.beam.deflections(&self.stations, &a);
        let sample = Sample {
            t,
            q: &q,
            a: &a,
            along: &along,
            disk,
            gap,
            energy,
            reactions,
        };
        self.history.record(&sample);
        self.pictures.record(&sample);
        let row = self.history.rows.last().expect("recorded above");
        let probes: Vec<f64> = row
            .probes
            .iter()
            .zip(&row.accelerations)
            .flat_map(|(d, a)| [d.u, d.w, d.phi, *a])
            .collect();
        self.watches.probes.record_point(t, &probes);
        self.watches
            .along
            .record_point(t, &stations_watched(&self.envelope.x, &along, &along_a));
        if self.exit_t.is_some_and(|te| t >= te) {
            let w: Vec<f64> = row.probes.iter().map(|d| d.w).collect();
            self.watches.after_exit.record_point(t, &w);
        }
        if self.phase.flying.is_some() {
            self.watches.gap.record_point(t, &[gap]);
        }
        if let Some(d) = row.disk {
            self.watches.disk.record_point(
                t,
                &[d.rn, d.rt, d.mu_needed().unwrap_or(f64::NAN), row.w_under],
            );
        }
    }

    fn step(&mut self, t: f64, y: &[f64]) {
        self.ledger.at_step(&self.phase, t, y);
        if let Some(p) = &mut self.progress {
            p.update(t);
        }
    }

    fn span(&mut self, t0: f64, t1: f64, dense: &dyn Dense) {
        self.watch(t0, t1, dense);
        let (phase, history) = (&self.phase, &self.history);
        let Some(means) = &mut self.means else {
            return;
        };
        means.record_span(t0, t1, |t| {
            let y = dense.at(t);
            let (disk, _) = phase.disk(t, &y);
            let q = phase.displaced(t, &y, disk.as_ref());
            history
                .probes
                .iter()
                .map(|p| history.beam.displacement_at(&q, p.x).w)
                .collect()
        });
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
    fn span(&mut self, t0: f64, t1: f64, dense: &dyn Dense) {
        let sys = self.sys;
        self.rec.span(t0, t1, &|t| sys.reduced(t, &dense.at(t)));
    }
}

/// The modes of a modal beam, from its linear stiffness and mass.
fn modal_basis(scene: &Scene, beam: &Beam) -> Result<Option<ModalBasis>, Error> {
    let Some(count) = beam.spec.model.modes() else {
        return Ok(None);
    };
    let n = beam.dim();
    if count > n {
        return Err(Error::Input(format!(
            "scene {}: `track.beam.modes` = {count} is more than the mesh has: its {n} unknowns have {n} modes",
            scene.name
        )));
    }
    let m = modes(beam, count).ok_or_else(|| {
        Error::Solver(format!(
            "scene {}: the natural modes of the modal beam could not be computed",
            scene.name
        ))
    })?;
    Ok(Some(ModalBasis::new(
        m.shapes,
        m.omega,
        &beam.tangent(&vec![0.0; n]),
        beam.mass(),
    )))
}

/// A state (z, ż) of the run's model with the beam's part on the mesh (q = Φ η on a modal
/// beam): what the run reports as its end state.
fn on_mesh(phase: &Phase, y: &[f64]) -> Vec<f64> {
    let n = phase.loaded.dim();
    let (z, zd) = phase.split(y);
    let (q, v) = phase.beam_state(y);
    q.iter()
        .chain(&z[n..])
        .chain(v.iter())
        .chain(&zd[n..])
        .copied()
        .collect()
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

/// How the coupled phase ended.
enum CoupledEnd {
    /// At the end of the run, or at a physical event: the run ends here.
    Stopped { t: f64, y: Vec<f64>, stop: Stop },
    /// The disk left the beam at an end; the beam goes on alone.
    Left { t: f64, y: Vec<f64> },
}

/// Integrate the disk on the beam until it leaves it, stops, or the run ends.
/// `from`: a restart (t, z, ż) after a landing; `None` for the run's start, the beam at rest
/// in `start`.
#[allow(clippy::too_many_arguments)]
fn integrate_coupled(
    scene: &Scene,
    c: &DiskOnBeam,
    literal: bool,
    start: &[f64],
    from: Option<(f64, Vec<f64>, Vec<f64>)>,
    outputs: &[f64],
    opts: &ode::Options,
    rec: &mut Recorder,
    stats: &mut Stats,
) -> Result<CoupledEnd, Error> {
    let until = c
        .exit_time()
        .map_or(scene.duration, |te| te.min(scene.duration));
    if let Some((t0, z0, zd0)) = from {
        let ahead: Vec<f64> = outputs.iter().copied().filter(|&o| o > t0).collect();
        let out = integrate(c, t0, &z0, &zd0, until, &ahead, opts, rec)
            .map_err(|e| solver_error(scene, e))?;
        stats.add(&out.stats);
        return Ok(coupled_end(scene, out.t, out.stopped_by, out.y));
    }
    let (z0, zd0) = c.initial_state(start);
    let (t, stopped_by, y) = if literal {
        // The thesis coupling with a first-order integrator is the published 3n + 6 system.
        let sys = ThesisSystem { coupled: c };
        let mut through = Literal { sys: &sys, rec };
        let out = ode::solve(
            &sys,
            0.0,
            &sys.initial_state(start),
            until,
            outputs,
            opts,
            &mut through,
        )
        .map_err(|e| solver_error(scene, e))?;
        stats.add(&out.stats);
        (out.t, out.stopped_by, sys.reduced(out.t, &out.y))
    } else {
        let out = integrate(c, 0.0, &z0, &zd0, until, outputs, opts, rec)
            .map_err(|e| solver_error(scene, e))?;
        stats.add(&out.stats);
        (out.t, out.stopped_by, out.y)
    };
    Ok(coupled_end(scene, t, stopped_by, y))
}

fn coupled_end(
    scene: &Scene,
    t: f64,
    stopped_by: Option<ode::EventHit<StopReason>>,
    y: Vec<f64>,
) -> CoupledEnd {
    let stop = match stopped_by {
        None if t < scene.duration => None,
        None => Some(Stop::End),
        Some(hit) if hit.reason == StopReason::LeftTrack => None,
        Some(hit) => Some(Stop::Event(hit.reason)),
    };
    match stop {
        None => CoupledEnd::Left { t, y },
        Some(stop) => CoupledEnd::Stopped { t, y, stop },
    }
}

/// How a flight over the beam ended.
enum Flown {
    /// The disk landed and rolls on from the coupled state (t, z, ż).
    Lands { t: f64, z: Vec<f64>, zd: Vec<f64> },
    /// The run ends in the air, or stops at the landing: y is the phase's state then.
    Stops { t: f64, y: Vec<f64>, stop: Stop },
    /// The disk flew beyond an end of the beam; the beam goes on alone from (q, v).
    Leaves { t: f64, q: Vec<f64>, v: Vec<f64> },
}

/// A disk leaving the beam: where and how it flies, over the beam's state then.
struct Launch {
    t: f64,
    q: Vec<f64>,
    v: Vec<f64>,
    flight: Flight,
    s: f64,
}

/// The disk lifts off at (t, y) of the coupled phase: it takes its energy with it into the
/// air, where the budget holds it constant.
fn lift_off(c: &DiskOnBeam, rec: &mut Recorder, t: f64, y: &[f64]) -> Launch {
    let n = c.loaded.dim();
    let (z, zd) = rec.phase.split(y);
    let d = c.observe(t, z, zd);
    let launch = Launch {
        t,
        q: z[..n].to_vec(),
        v: zd[..n].to_vec(),
        flight: Flight {
            t0: t,
            centre: [d.x, d.y],
            velocity: [d.vx, d.vy],
            omega: d.omega,
            gravity: c.spec.gravity,
        },
        s: d.s,
    };
    rec.ledger.disk_leaves(&rec.phase, t, y);
    launch
}

/// A bounce lower than this share of the radius is not flown: it ends as a plastic landing
/// (see the rigid curve's `RESOLVED_BOUNCE`).
const RESOLVED_BOUNCE: f64 = 1e-8;

/// From a lift-off at (t, y) of the coupled phase: the beam integrated alone under the disk's
/// flight until the disk lands (or passes an end, or the run ends), the landing, and the
/// bounces after it.
#[allow(clippy::too_many_arguments)]
fn fly<'a>(
    scene: &Scene,
    c: &'a DiskOnBeam<'a>,
    loaded: &'a LoadedBeam<'a>,
    t: f64,
    y: &[f64],
    outputs: &[f64],
    opts: &ode::Options,
    rec: &mut Recorder<'a>,
    stats: &mut Stats,
    flights: &mut Vec<FlightRecord>,
) -> Result<Flown, Error> {
    let n = loaded.dim();
    let restitution = match c.spec.contact_loss {
        ContactLoss::Fly { restitution } => restitution,
        ContactLoss::Stop => 0.0,
    };
    let mut launch = lift_off(c, rec, t, y);
    loop {
        if flights.len() >= MAX_FLIGHTS {
            return Err(Error::Solver(format!(
                "scene {}: the disk lifted off the beam {MAX_FLIGHTS} times by t = {:.6} s; the run stops rather than count more flights",
                scene.name, launch.t
            )));
        }
        let disk = FlyingDisk {
            coupled: c,
            flight: launch.flight,
            s: std::cell::Cell::new(launch.s),
        };
        rec.phase.free();
        rec.phase.flying = Some(disk.clone());
        flights.push(FlightRecord {
            lift_off_t: launch.t,
            lift_off_s: launch.s,
            land_t: None,
            land_s: None,
            max_gap: 0.0,
            energy_lost: None,
        });
        rec.watches.gap = Watch::new(1, Turning::OnTheSolution);
        let beneath = BeneathFlight { loaded, disk };
        let ahead: Vec<f64> = outputs.iter().copied().filter(|&o| o > launch.t).collect();
        let out = integrate(
            &beneath,
            launch.t,
            &launch.q,
            &launch.v,
            scene.duration,
            &ahead,
            opts,
            rec,
        )
        .map_err(|e| solver_error(scene, e))?;
        stats.add(&out.stats);
        let record = flights.last_mut().expect("pushed above");
        record.max_gap = rec.watches.gap.ranges[0].max.max(0.0);
        let hit = match out.stopped_by {
            None => {
                return Ok(Flown::Stops {
                    t: out.t,
                    y: out.y,
                    stop: Stop::End,
                })
            }
            Some(hit) => hit.reason,
        };
        let (q, v) = out.y.split_at(n);
        if hit == FlightEvent::PassesEnd {
            rec.phase.flying = None;
            return Ok(Flown::Leaves {
                t: out.t,
                q: q.to_vec(),
                v: v.to_vec(),
            });
        }
        let t = out.t;
        let flight = beneath.disk.flight;
        let near = c.gap(q, flight.centre(t), beneath.disk.s.get());
        let before = flight.velocity(t);
        let unsolved = || {
            Error::Solver(format!(
                "scene {}: the disk's landing on the beam at t = {t:.6} s could not be solved (the coupled mass matrix is singular there)",
                scene.name
            ))
        };
        let landing = c
            .land(t, q, v, near.s, before, flight.omega)
            .ok_or_else(unsolved)?;
        record.land_t = Some(t);
        record.land_s = Some(near.s);
        let bounce = if restitution > 0.0 {
            c.bounce(
                t,
                q,
                v,
                near.s,
                before,
                flight.omega,
                restitution,
                &landing,
                rec.phase.mass_lu,
            )
        } else {
            None
        };
        let gravity_n = c.spec.gravity * c.contact_frame(t, &landing.z, &landing.zd)[1][1];
        if let Some(b) = bounce.filter(|b| {
            gravity_n <= 0.0
                || b.leaving * b.leaving / (2.0 * gravity_n) >= RESOLVED_BOUNCE * c.spec.disk.radius
        }) {
            record.energy_lost = Some(b.energy_lost);
            let after = c.observe(t, &landing.z, &landing.zd);
            if slips(c, &landing, t, before, b.velocity) {
                rec.ledger.disk_lands(landing.energy_lost);
                rec.phase.couple(c);
                return Ok(Flown::Stops {
                    t,
                    y: landing.z.iter().chain(&landing.zd).copied().collect(),
                    stop: Stop::Event(StopReason::Slip),
                });
            }
            let m = c.spec.disk.mass;
            let kinetic = 0.5 * m * (b.velocity[0].powi(2) + b.velocity[1].powi(2))
                + 0.5 * c.spec.disk.inertia() * b.omega * b.omega;
            rec.ledger
                .disk_bounces(b.energy_lost, (kinetic, after.potential));
            launch = Launch {
                t,
                q: q.to_vec(),
                v: b.beam,
                flight: Flight {
                    t0: t,
                    centre: [after.x, after.y],
                    velocity: b.velocity,
                    omega: b.omega,
                    gravity: c.spec.gravity,
                },
                s: near.s,
            };
            continue;
        }
        record.energy_lost = Some(landing.energy_lost);
        rec.ledger.disk_lands(landing.energy_lost);
        rec.phase.couple(c);
        let after = c.observe(t, &landing.z, &landing.zd);
        let y: Vec<f64> = landing.z.iter().chain(&landing.zd).copied().collect();
        if slips(c, &landing, t, before, [after.vx, after.vy]) {
            return Ok(Flown::Stops {
                t,
                y,
                stop: Stop::Event(StopReason::Slip),
            });
        }
        // The disk rolls on from the landing, unless the beam falls away faster than it can
        // follow there, in which case it lifts off at once; but a disk that touches again the
        // instant it left, and then would have to be pulled to stay on, can neither roll nor
        // fly there, and the run stops at that contact loss.
        if after.rn > 0.0 {
            return Ok(Flown::Lands {
                t,
                z: landing.z,
                zd: landing.zd,
            });
        }
        if t <= launch.t + 1e-12 * (1.0 + t.abs()) {
            return Ok(Flown::Stops {
                t,
                y,
                stop: Stop::Event(StopReason::ContactLost),
            });
        }
        launch = lift_off(c, rec, t, &y);
    }
}

/// Whether the impulse that took the disk from `before` to `after` (centre velocities,
/// global) needs more friction than the scene's `mu`: |Jₜ| > mu Jₙ in the track's frame.
fn slips(c: &DiskOnBeam, landing: &Landing, t: f64, before: [f64; 2], after: [f64; 2]) -> bool {
    let Some(mu) = c.spec.mu else {
        return false;
    };
    let [tg, nm] = c.contact_frame(t, &landing.z, &landing.zd);
    let m = c.spec.disk.mass;
    let dv = [after[0] - before[0], after[1] - before[1]];
    let jt = m * (dv[0] * tg[0] + dv[1] * tg[1]);
    let jn = m * (dv[0] * nm[0] + dv[1] * nm[1]);
    jt.abs() > mu * jn
}

pub fn run(
    scene: &Scene,
    setup: &BeamScene,
    over: &Overrides,
    show_progress: bool,
) -> Result<BeamRun, Error> {
    // Set up: the beam (and its modes, on a modal beam), its loads, the disk on it, and the
    // integrator.
    let beam = Beam::new(setup.beam.clone());
    let modal = modal_basis(scene, &beam)?;
    let damping = crate::analysis::modes::rayleigh(&beam)
        .map_err(|why| Error::Input(format!("scene {}: {why}", scene.name)))?;
    let lowest = match &modal {
        Some(m) => m.omega.first().copied(),
        None => modes(&beam, 1).and_then(|m| m.omega.first().copied()),
    };
    let loaded = LoadedBeam::new(
        &beam,
        &setup.loads,
        modal.as_ref(),
        damping,
        setup.train.as_ref(),
    )
    .resolving(lowest.unwrap_or(0.0));
    let coupled = setup
        .disk
        .clone()
        .map(|spec| DiskOnBeam::new(&loaded, spec));
    let n = loaded.dim();
    let mut opts = ode::Options {
        rho_inf: setup.rho_inf,
        ..over.options(scene)
    };
    let mut outputs = super::output_times(scene);
    outputs.extend(setup.shapes.iter().copied());
    outputs.sort_by(f64::total_cmp);
    outputs.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let mass_lu = SparseLu::factor(loaded.model_mass(), None).ok_or_else(|| {
        Error::Solver(format!("scene {}: the mass matrix is singular", scene.name))
    })?;
    let literal = coupled
        .as_ref()
        .is_some_and(|c| c.spec.coupling == Coupling::Thesis)
        && opts.method != Method::GenAlpha;
    if literal && setup.beam.model != BeamModel::Exact {
        return Err(Error::Input(format!(
            "scene {}: {} integrates the thesis coupling as the published 3n + 6 system, which transcribes the exact beam; use `model: exact`, or genalpha for the thesis coupling on a {} beam",
            scene.name,
            opts.method.name(),
            setup.beam.model.name()
        )));
    }
    let unknowns = match &coupled {
        None => n,
        Some(_) if literal => n + 6,
        Some(c) => c.dim(),
    };

    // The start state, and the observers from it.
    let start = start_state(scene, setup, &loaded, coupled.as_ref())?;
    let phase = Phase {
        beam: &beam,
        loaded: &loaded,
        coupled: coupled.as_ref(),
        nz: coupled.as_ref().map_or(n, |c| c.dim()),
        mass_lu: &mass_lu,
        correct: !over.uncorrected_modes,
        flying: None,
    };
    let y0: Vec<f64> = match &coupled {
        Some(c) => {
            let (z0, zd0) = c.initial_state(&start);
            z0.into_iter().chain(zd0).collect()
        }
        None => loaded
            .from_mesh(&start)
            .into_iter()
            .chain(vec![0.0; n])
            .collect(),
    };
    let xs: Vec<f64> = (0..SAMPLES)
        .map(|k| beam.length * k as f64 / (SAMPLES - 1) as f64)
        .collect();
    let filter = AccelerationFilter::new(&beam, &loaded, setup.acceleration_cutoff_hz);
    let spacing = filter
        .as_ref()
        .map_or(0.0, |f| 1.0 / (SAMPLES_PER_CUTOFF_PERIOD * f.cutoff_hz));
    let mut rec = Recorder {
        ledger: Ledger::new(&phase, &setup.loads, &y0),
        filter,
        phase,
        stations: beam.stations(&xs),
        history: History {
            beam: &beam,
            probes: &setup.probes,
            rows: Vec::with_capacity(outputs.len()),
        },
        envelope: Envelope::new(xs),
        pictures: Pictures {
            shape_times: &setup.shapes,
            frame_every: over.animate.then(|| scene.duration / (FRAMES - 1) as f64),
            shapes: Vec::new(),
            frames: Vec::new(),
            turned: (0.0, setup.disk.as_ref().map_or(0.0, |d| d.omega0), 0.0),
        },
        means: over
            .windowed_means
            .then(|| WindowedMeans::new(scene.duration, setup.probes.len())),
        watches: Watches::new(setup.probes.len(), SAMPLES),
        last: None,
        before: None,
        spacing,
        exit_t: setup.train.as_ref().map(|tr| tr.gone(beam.length)),
        progress: if show_progress {
            Progress::new(scene.duration)
        } else {
            None
        },
    };

    // Integrate while the disk is on the beam, then the beam alone.
    let mut stats = Stats::default();
    let mut stop = Stop::End;
    let mut left_track_t = None;
    let (mut t0, mut q0, mut v0) = (0.0, loaded.from_mesh(&start), vec![0.0; n]);
    let mut ended = None;
    let mut flights = Vec::new();
    if let Some(c) = &coupled {
        let mut from = None;
        loop {
            let end = integrate_coupled(
                scene,
                c,
                literal,
                &start,
                from.take(),
                &outputs,
                &opts,
                &mut rec,
                &mut stats,
            )?;
            let flies = matches!(c.spec.contact_loss, ContactLoss::Fly { .. });
            let (t, y, why) = match end {
                CoupledEnd::Stopped {
                    t,
                    y,
                    stop: Stop::Event(StopReason::ContactLost),
                } if flies => {
                    // The damping the plan chose is for loads that move: once the disk has
                    // left the beam, what it lands with or leaves behind vibrates freely.
                    if setup.rho_inf_chosen.is_some() {
                        opts.rho_inf = 1.0;
                    }
                    match fly(
                        scene,
                        c,
                        &loaded,
                        t,
                        &y,
                        &outputs,
                        &opts,
                        &mut rec,
                        &mut stats,
                        &mut flights,
                    )? {
                        Flown::Lands { t, z, zd } => {
                            from = Some((t, z, zd));
                            continue;
                        }
                        Flown::Leaves { t, q, v } => {
                            (t0, q0, v0) = (t, q, v);
                            left_track_t = Some(t);
                            rec.exit_t = Some(t);
                            break;
                        }
                        Flown::Stops { t, y, stop } => (t, y, stop),
                    }
                }
                CoupledEnd::Stopped { t, y, stop } => (t, y, stop),
                CoupledEnd::Left { t, y } => {
                    rec.ledger.disk_leaves(&rec.phase, t, &y);
                    let (z, zd) = rec.phase.split(&y);
                    (t0, q0, v0) = (t, z[..n].to_vec(), zd[..n].to_vec());
                    left_track_t = Some(t);
                    rec.exit_t = Some(t);
                    break;
                }
            };
            // The run stops between output times: its last row is the stop itself.
            if rec.history.rows.last().is_none_or(|r| r.t < t) {
                rec.output(t, &y);
            }
            stop = why;
            ended = Some((t, y));
            break;
        }
    }
    let (t_end, y_end) = match ended {
        Some(end) => end,
        None => {
            rec.phase.free();
            // The output times from here on that no phase has recorded yet: a run without a
            // disk records its start here, after the disk left its leaving time is recorded.
            let rest: Vec<f64> = outputs
                .iter()
                .copied()
                .filter(|&o| o >= t0 && rec.history.rows.last().is_none_or(|r| r.t < o))
                .collect();
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
            stats.add(&out.stats);
            (out.t, out.y)
        }
    };

    // Collect.
    if let Some(p) = &rec.progress {
        p.finish();
    }
    let y_end = on_mesh(&rec.phase, &y_end);
    let (extremes, envelope) = rec.extremes();
    Ok(BeamRun {
        header: RunHeader {
            scene: scene.clone(),
            method: opts.method,
            rtol: opts.rtol,
            atol: opts.atol,
            unknowns,
            stop,
            t_end,
            stats,
            energy: rec.ledger.check,
        },
        setup: setup.clone(),
        rows: rec.history.rows,
        envelope,
        extremes,
        shapes: rec.pictures.shapes,
        frames: rec.pictures.frames,
        windowed_means: rec.means.map_or_else(Vec::new, |m| m.means()),
        left_track_t,
        flights,
        y_end,
        acceleration: rec.filter.as_ref().map(|f| f.report()),
        damping,
        beam,
    })
}
