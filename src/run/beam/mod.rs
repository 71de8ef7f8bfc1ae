//! A run of a loaded beam, with or without a disk on it: integrate, and record probe histories,
//! envelopes along the beam, deformed shapes, the disk's quantities and the energy budget
//! (kinetic + strain + potential − work of the loads).
//!
//! With a disk the run has two phases (`phase.rs`): the coupled one, until the disk leaves the
//! beam at an end (or stops at a physical event), then the beam alone, vibrating freely to the
//! end. The energy budget is kept by `ledger.rs`; the outputs are recorded by the sensors of
//! `sensors.rs`, which observe and compute nothing, gathered with the extremes watched over
//! every step by `recorder.rs` (a rolling disk's contact force also averaged over the
//! acceleration cutoff's period by `contact_mean.rs`) until a free vibration can move none of
//! them (`settled.rs`); the disks ride through the disk's life at its track
//! (`disk::life`), the beam's side of it here and its flights and landings in `fly.rs`; the
//! vehicles' drive over the whole run is `vehicles.rs`. [`run`] names the steps of a run: build the model,
//! the start state, ride (integrate while the disk is on), vibrate alone, collect.

mod acceleration;
mod contact_mean;
mod flight;
mod fly;
mod ledger;
mod modal_probes;
mod phase;
mod recorder;
mod sensors;
mod settled;
mod vehicles;
mod watch;

use super::extremes::{Range, Turning, Watch};
use super::{FlightRecord, Overrides, Progress, RunHeader, Stop, MAX_FLIGHTS};
use crate::analysis::model_choice::SHARE;
use crate::analysis::modes::modes;
use crate::analysis::statics;
use crate::beam::damping::Rayleigh;
use crate::beam::dynamics::LoadedBeam;
use crate::beam::load::BeamStart;
use crate::beam::modal::ModalBasis;
use crate::beam::{Beam, BeamModel, PointDisplacement, Stations};
use crate::coupling::landing::Landing;
use crate::coupling::thesis_system::ThesisSystem;
use crate::coupling::vehicles::{VehicleObservation, VehiclesOnBeam};
use crate::coupling::{Coupling, DiskEvent, DiskOnBeam};
use crate::disk::flight::Flight;
use crate::disk::life::{self, Next};
use crate::disk::{ContactLoss, DiskObservation, StopReason};
use crate::error::Error;
use crate::linalg::SparseLu;
use crate::ode::second_order::FirstOrder;
use crate::ode::second_order::{SecondOrderProblem, Structure};
use crate::ode::{self, Dense, Method, Observer, Stats};
use crate::scene::{BeamScene, Scene};
use acceleration::AccelerationFilter;
pub use acceleration::CutoffReport;
use flight::{BeneathFlight, FlightEvent, FlyingDisk};
use ledger::Ledger;
use phase::Phase;
pub use sensors::MEAN_WINDOWS;
use sensors::{History, Pictures, Sample, WindowedMeans};

use fly::*;
use recorder::*;
use vehicles::*;
pub use vehicles::{AxleFlight, VehicleReport};
use watch::*;

/// Points along the beam where envelopes and shapes are sampled.
pub const SAMPLES: usize = 201;

/// Frames an animation of a run holds at most.
pub const FRAMES: usize = 240;

#[derive(Clone, Debug)]
pub struct Frame {
    pub t: f64,
    pub along: Vec<PointDisplacement>,
    /// Per disk, while it is on or over the beam: its contact point s (in flight, the nearest
    /// point), the angle it has turned through, and its gap to the beam (0 while it rolls).
    pub disks: Vec<Option<(f64, f64, f64)>>,
    /// Where every vehicle's every wheel is along the beam (on the deck or off it).
    pub wheels: Vec<f64>,
}

#[derive(Clone, Debug)]
pub struct BeamRow {
    pub t: f64,
    /// One per probe, in the scene's order.
    pub probes: Vec<PointDisplacement>,
    /// Each disk, while it is on or over the beam (`None` once it has left; empty without
    /// disks, or once they have all left).
    pub disks: Vec<Option<DiskObservation>>,
    /// Deflection w of the beam under each disk (NaN while it is not on the beam).
    pub w_under: Vec<f64>,
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
    /// Which disk flies, while one does.
    pub flying: Option<usize>,
    /// One per probe: the vertical (global Y) acceleration, with the modes above the cutoff
    /// left out (see [`AccelerationFilter`]).
    pub accelerations: Vec<f64>,
    /// What the supports exert on the beam, global (fx, fy, mz), at `from` and at `to`.
    pub reactions: [[f64; 3]; 2],
    /// The vehicles, where the scene has them.
    pub vehicles: Option<VehicleObservation>,
}

impl BeamRow {
    /// The first disk (the disk, where it is alone) while it is on or over the beam.
    pub fn disk(&self) -> Option<DiskObservation> {
        self.disks.first().copied().flatten()
    }

    /// The deflection under the first disk (NaN while it is not on the beam).
    pub fn w_under_disk(&self) -> f64 {
        self.w_under.first().copied().unwrap_or(f64::NAN)
    }

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
    /// When the last disk left the beam, if it did.
    pub left_track_t: Option<f64>,
    /// When each disk left the beam, if it did.
    pub disks_left_t: Vec<Option<f64>>,
    /// The disk (in the scene's order) whose event stopped the run: it lost contact, slipped
    /// or no longer fitted.
    pub stopped_disk: Option<usize>,
    /// The disk's flights over the beam.
    pub flights: Vec<FlightRecord>,
    /// (q, v) at the end of the run.
    pub y_end: Vec<f64>,
    /// What the recorded accelerations count.
    pub acceleration: Option<CutoffReport>,
    /// The Rayleigh damping the run had, α and β resolved.
    pub damping: Option<Rayleigh>,
    /// Each vehicle's extremes, in the scene's order.
    pub vehicles: Vec<VehicleReport>,
}

/// The extremes over the run of what the summary reports, each located on the solution
/// ([`super::extremes`]).
#[derive(Clone, Debug, Default)]
pub struct Extremes {
    /// Per probe: u, w, φ and the vertical acceleration (filtered as recorded).
    pub probes: Vec<[Range; 4]>,
    /// Per probe: w after the last load left the beam (the disk, or a train's last axle).
    pub after_exit: Option<Vec<Range>>,
    /// Per disk, its normal and tangential contact force, the friction coefficient its
    /// rolling needs and the deflection under it, while it is on or over the beam (`None`
    /// for a disk never watched there).
    pub disks: Vec<Option<[Range; 4]>>,
    /// Per vehicle, each body's vertical acceleration then each axle's contact force, from
    /// the time the vehicle came onto the deck.
    pub vehicles: Vec<Range>,
    /// Per disk, its normal and tangential contact force averaged over a period of the
    /// acceleration's cutoff ([`contact_mean`]) and the friction coefficient those need, for
    /// the consistent coupling on the beam a whole window (`None` otherwise; empty without a
    /// cutoff).
    pub contact_means: Vec<Option<[Range; 3]>>,
}

impl Extremes {
    /// The first disk's (the disk's, where it is alone), if it was watched on the beam.
    pub fn disk(&self) -> Option<[Range; 4]> {
        self.disks.first().copied().flatten()
    }
}

impl BeamRun {
    /// Half the range of w at probe k after the last load left the beam: the residual
    /// vibration. `None` without an exit, or with nothing of the run after it.
    pub fn amplitude_after_exit(&self, k: usize) -> Option<f64> {
        self.extremes.after_exit.as_ref()?.get(k)?.half_range()
    }

    /// What the results depend on beyond the accuracy asked: the scene's (`BeamScene::warnings`)
    /// and what the run itself met.
    pub fn warnings(&self) -> Vec<String> {
        let mut out = self.setup.warnings();
        if let [first, _, ..] = &self.flights[..] {
            let who = if self.setup.disks.len() > 1 {
                "the disks"
            } else {
                "the disk"
            };
            out.push(format!(
                "{who} lifted off the beam {} times: each landing's time and impulse, and the motion after it, carry the error of every step before it, so the extremes from the first lift-off at t = {:.6} s on are not held to the accuracy (a 5 t disk hopping on the HSLM bridge under A1: 15 flights at the defaults against 16 at rtol 1e-8, the deck's largest acceleration 7.7 % apart)",
                self.flights.len(),
                first.lift_off_t
            ));
        }
        out.extend(self.suspensions_outrun());
        out.extend(self.nonlinearity_outgrown());
        if let Some(c) = self.acceleration.as_ref().filter(|c| c.below > c.modes) {
            out.push(format!(
                "the modal beam keeps {} modes, fewer than the {} at or below the deck acceleration's cutoff ({:.2} Hz): the accelerations leave the others out; `track.beam.modes: {}` or more counts them all",
                c.modes, c.below, c.cutoff_hz, c.below
            ));
        }
        out
    }

    /// Where the plan chose a linear or modal beam from the exact beam's static gap g at a
    /// static deflection s, and the response grew to W at the probes: about how far the exact
    /// beam's would lie from it, of it, g (W/s)³. The static gap grows as the square of the
    /// amplitude, and a resonant build-up amplifies it as much again as it amplified the
    /// response: over HSLM's bridge (s = 1.56 mm under one axle, g = 4.4·10⁻⁸) it foresees
    /// 3·10⁻⁶, 9·10⁻⁵ and 1.1·10⁻³ for A1 at 60 m/s, A10 at 67 and A7 at 120, where the exact
    /// beam lies 2.2·10⁻⁶, 1.2·10⁻⁴ and 8.3·10⁻⁴ from the linear one in deflection (7.6·10⁻⁶,
    /// 1.6·10⁻⁴ and 9.9·10⁻⁴ in acceleration).
    pub fn nonlinear_gap_foreseen(&self) -> Option<f64> {
        self.growth().map(|(ratio, g)| g * ratio.powi(3))
    }

    /// W/s and g of [`Self::nonlinear_gap_foreseen`].
    fn growth(&self) -> Option<(f64, f64)> {
        let (s, g) = self.setup.static_gap?;
        let peak = (self.extremes.probes.iter())
            .map(|p| p[1].min.abs().max(p[1].max.abs()))
            .filter(|w| w.is_finite())
            .fold(0.0_f64, f64::max);
        (s > 0.0 && peak > 0.0).then_some((peak / s, g))
    }

    /// A warning where [`Self::nonlinear_gap_foreseen`] passes the share of the accuracy the
    /// plan chose the model by.
    fn nonlinearity_outgrown(&self) -> Option<String> {
        let (ratio, g) = self.growth()?;
        let gap = g * ratio.powi(3);
        let accuracy = self.setup.accuracy;
        (gap > SHARE * accuracy).then(|| format!(
            "the response grew to {ratio:.1} times the static deflection the plan judged the {} beam by: the geometric nonlinearity it leaves out grows about as the cube of that, here to some {gap:.1e} of the response, past a quarter of the accuracy {accuracy:e} (HSLM's bridge at A7's resonance: 1.1e-3 foreseen, the exact beam 8.3e-4 off in deflection, 9.9e-4 in acceleration); `track.beam.model: exact` holds it",
            self.setup.beam.model.name()
        ))
    }

    /// A warning for each vehicle whose bodies ring on their springs faster than the run's
    /// steps follow: more than a third of a radian of that vibration a step on average. What a
    /// kink of the track sets ringing is then carried with the error of steps that do not
    /// resolve it, and the bodies' accelerations with it: Biggs' sprung mass on springs 10³,
    /// 10⁴ and 10⁶ times as stiff (84 Hz, 266 Hz, 2.65 kHz) takes 0.25, 0.45 and 0.95 rad a
    /// step at the defaults, and its largest acceleration lands within 1.7·10⁻⁴, 2.7·10⁻² and
    /// 0.21 of the run at rtol 10⁻⁸ (itself 0.11 from the run at 10⁻⁹).
    fn suspensions_outrun(&self) -> Vec<String> {
        let steps = self.header.stats.steps;
        if steps == 0 {
            return Vec::new();
        }
        let mean = self.header.t_end / steps as f64;
        self.setup
            .vehicles
            .iter()
            .filter_map(|v| {
                let f = v.fastest_suspension_hz();
                let turn = std::f64::consts::TAU * f * mean;
                (turn > 1.0 / 3.0).then(|| format!(
                    "vehicle {}'s bodies ring on their springs at up to {f:.4e} Hz (the axles held), faster than the steps follow ({mean:.2e} s on average, {turn:.1} rad of that vibration a step): their accelerations are not held to the accuracy (Biggs' sprung mass on a spring 10⁴ times as stiff, 266 Hz, 0.45 rad a step: its largest acceleration 0.895 m/s² at the defaults, 0.871 at rtol 1e-8); a tighter `solver.rtol` follows it, and a spring that stiff is close to a rigid attachment",
                    v.name
                ))
            })
            .collect()
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
    vehicles: Option<&VehiclesOnBeam>,
) -> Result<Vec<f64>, Error> {
    let beam = loaded.beam;
    let n = beam.dim();
    let mut q = vec![0.0; n];
    if setup.start == BeamStart::Rest {
        return Ok(q);
    }
    let mut loads = vec![0.0; n];
    loaded.external(0.0, &mut loads);
    if let Some(v) = vehicles {
        v.add_weights_at_rest(&mut loads);
    }
    let mut last_change = f64::INFINITY;
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
        // Each solve leaves the shape moving by the round-off of the last: about 1e-12 of
        // it where several disks' forces each follow the slope under them, and up to 2e-8
        // on a linear beam whose shear stiffness dwarfs its bending one (D44 with G × 10⁴,
        // whose assembled K q loses the shear strain to cancellation). Settled once the
        // change no longer shrinks; a change that stops far above round-off is a shape that
        // does not settle.
        let stalled = change <= 1e-6 * size && change >= 0.5 * last_change;
        if coupled.is_none() || change <= 1e-12 * size || stalled {
            return Ok(q);
        }
        last_change = change;
    }
    Err(Error::Solver(format!(
        "scene {}: the static start did not settle in {START_ITERATIONS} solves: the disk's weight turns the beam too far for a resting start",
        scene.name
    )))
}

/// Static solves the resting start may take: each moves the shape by a share of the last
/// change, the square of its change in slope and what the disk's speed over the change in
/// curvature presses (m v² κ: on D44 each solve leaves 4 % of the last change), so a dozen
/// suffice unless the disk overturns the beam.
const START_ITERATIONS: usize = 16;

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
    rec.ledger.order = opts.method.order();
    ode::solve(&FirstOrder::new(p), t0, &y0, t_end, outputs, opts, rec)
}

/// How the coupled phase ended.
enum CoupledEnd {
    /// At the end of the run, or at a physical event: the run ends here. `disk`: the disk
    /// whose event it was.
    Stopped {
        t: f64,
        y: Vec<f64>,
        stop: Stop,
        disk: Option<usize>,
    },
    /// A disk left the beam at an end (`disk`: the rolling one that ran off, none for a
    /// prescribed load at its exit time).
    Left {
        t: f64,
        y: Vec<f64>,
        disk: Option<usize>,
    },
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
        .next_exit()
        .map_or(scene.duration, |(te, _)| te.min(scene.duration));
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
        let mut through = ThesisSystemObserver { sys: &sys, rec };
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
        // The literal system holds the lone disk.
        let hit = out.stopped_by.map(|h| ode::EventHit {
            reason: DiskEvent {
                disk: 0,
                reason: h.reason,
            },
            t: h.t,
        });
        (out.t, hit, sys.reduced(out.t, &out.y))
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
    stopped_by: Option<ode::EventHit<DiskEvent>>,
    y: Vec<f64>,
) -> CoupledEnd {
    let disk = stopped_by.as_ref().map(|hit| hit.reason.disk);
    let stop = match stopped_by {
        None if t < scene.duration => None,
        None => Some(Stop::End),
        Some(hit) if hit.reason.reason == StopReason::LeftTrack => None,
        Some(hit) => Some(Stop::Event(hit.reason.reason)),
    };
    match stop {
        None => CoupledEnd::Left { t, y, disk },
        Some(stop) => CoupledEnd::Stopped { t, y, stop, disk },
    }
}

/// What the riders' phase left for the rest of the run.
struct Ridden {
    stop: Stop,
    left_track_t: Option<f64>,
    /// When each disk left the beam.
    disks_left: Vec<Option<f64>>,
    flights: Vec<FlightRecord>,
    then: Then,
    /// The vehicle and axle whose wheel lost contact, where one did.
    lost_contact: Option<(usize, String)>,
    /// The disk whose event (contact lost, slip, no fit) stopped the run, where one did.
    stopped_disk: Option<usize>,
    /// The vehicles' wheels' flights.
    wheel_flights: Vec<WheelFlight>,
}

impl Ridden {
    /// A beam nothing rides on: it vibrates alone from the start, in displacements `q` at
    /// rest (`n` the model's unknowns).
    fn nothing(q: Vec<f64>, n: usize) -> Ridden {
        Ridden {
            stop: Stop::End,
            left_track_t: None,
            disks_left: Vec::new(),
            flights: Vec::new(),
            then: Then::Alone {
                t: 0.0,
                q,
                v: vec![0.0; n],
            },
            lost_contact: None,
            stopped_disk: None,
            wheel_flights: Vec::new(),
        }
    }
}

/// How the run goes on after the riders' phase.
enum Then {
    /// It ended at t in state y (a stop, or the end of the run with the disk on).
    Ended { t: f64, y: Vec<f64> },
    /// The beam vibrates alone from (t, q, v).
    Alone { t: f64, q: Vec<f64>, v: Vec<f64> },
}

pub fn run(
    scene: &Scene,
    setup: &BeamScene,
    over: &Overrides,
    show_progress: bool,
) -> Result<BeamRun, Error> {
    let beam = Beam::new(setup.beam.clone());
    let (modal, damping, lowest) = modes_and_damping(scene, &beam)?;
    let loaded = LoadedBeam::new(
        &beam,
        &setup.loads,
        modal.as_ref(),
        damping,
        setup.train.as_ref(),
    )
    .resolving(lowest);
    let filter = AccelerationFilter::new(&beam, &loaded, setup.acceleration_cutoff_hz);
    let loaded = loaded.reporting_accelerations_below(
        filter
            .as_ref()
            .map_or(0.0, |f| std::f64::consts::TAU * f.cutoff_hz),
    );
    let coupled = (!setup.disks.is_empty()).then(|| DiskOnBeam::new(&loaded, setup.disks.clone()));
    let vehicles = vehicles_on(scene, setup, &loaded)?;
    let mut opts = ode::Options {
        rho_inf: setup.rho_inf,
        ..over.options(scene)
    };
    let outputs = output_times(scene, setup);
    let mass_lu = SparseLu::factor(loaded.model_mass(), None).ok_or_else(|| {
        Error::Solver(format!("scene {}: the mass matrix is singular", scene.name))
    })?;
    if let Some(why) = setup
        .exact_modal_refusal()
        .filter(|_| opts.method == Method::ExactModal)
    {
        return Err(Error::Input(format!("scene {}: {why}", scene.name)));
    }
    let literal = thesis_system(scene, setup, coupled.as_ref(), &opts)?;

    let start = start_state(scene, setup, &loaded, coupled.as_ref(), vehicles.as_ref())?;
    let phase = Phase {
        beam: &beam,
        loaded: &loaded,
        coupled: coupled.as_ref(),
        nz: unknowns_of(&loaded, coupled.as_ref(), vehicles.as_ref()),
        mass_lu: &mass_lu,
        correct: !over.uncorrected_modes,
        flying: None,
        vehicles: vehicles.as_ref(),
    };
    let y0 = initial_state(&loaded, coupled.as_ref(), vehicles.as_ref(), &start);
    let mut rec = recorder(
        scene,
        setup,
        over,
        phase,
        filter,
        &y0,
        &outputs,
        show_progress,
    );

    let mut stats = Stats::default();
    let ridden = match (&coupled, &vehicles) {
        (Some(c), _) => ride(
            scene, setup, &loaded, c, literal, &start, &outputs, &mut opts, &mut rec, &mut stats,
        )?,
        (None, Some(v)) => drive(scene, v, &y0, &outputs, &opts, &mut rec, &mut stats)?,
        (None, None) => Ridden::nothing(loaded.from_mesh(&start), loaded.dim()),
    };
    let (t_end, y_end) = match &ridden.then {
        Then::Ended { t, y } => (*t, y.clone()),
        Then::Alone { t, q, v } => vibrate_alone(
            scene,
            &loaded,
            (*t, q, v),
            &outputs,
            &opts,
            &mut rec,
            &mut stats,
        )?,
    };

    let unknowns = if literal {
        loaded.dim() + 6
    } else {
        unknowns_of(&loaded, coupled.as_ref(), vehicles.as_ref())
    };
    let recorded = Recorded::from(rec, &y_end);
    Ok(collect(
        scene, setup, &opts, unknowns, ridden, t_end, stats, recorded, damping, beam,
    ))
}

/// The unknowns z of the model that rides first: the disks' (the beam's and their contact
/// coordinates), the vehicles' (the beam's and their bodies'), or the beam's alone.
fn unknowns_of(
    loaded: &LoadedBeam,
    coupled: Option<&DiskOnBeam>,
    vehicles: Option<&VehiclesOnBeam>,
) -> usize {
    match (coupled, vehicles) {
        (Some(c), _) => c.dim(),
        (None, Some(v)) => v.dim(),
        (None, None) => loaded.dim(),
    }
}

/// The modes of a modal beam, the damping resolved, and the lowest circular frequency (0
/// where none could be computed).
fn modes_and_damping(
    scene: &Scene,
    beam: &Beam,
) -> Result<(Option<ModalBasis>, Option<Rayleigh>, f64), Error> {
    let modal = modal_basis(scene, beam)?;
    let damping = crate::analysis::modes::rayleigh(beam)
        .map_err(|why| Error::Input(format!("scene {}: {why}", scene.name)))?;
    let lowest = match &modal {
        Some(m) => m.omega.first().copied(),
        None => modes(beam, 1).and_then(|m| m.omega.first().copied()),
    };
    Ok((modal, damping, lowest.unwrap_or(0.0)))
}

/// The run's output times and the shapes' times, sorted, each once.
fn output_times(scene: &Scene, setup: &BeamScene) -> Vec<f64> {
    let mut outputs = super::output_times(scene);
    outputs.extend(setup.shapes.iter().copied());
    outputs.sort_by(f64::total_cmp);
    outputs.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    outputs
}

/// Whether the run integrates the thesis coupling as the published 3n + 6 system (a
/// first-order method), which transcribes the exact beam only.
fn thesis_system(
    scene: &Scene,
    setup: &BeamScene,
    coupled: Option<&DiskOnBeam>,
    opts: &ode::Options,
) -> Result<bool, Error> {
    let literal = coupled.is_some_and(|c| c.spec().coupling == Coupling::Thesis)
        && opts.method != Method::GenAlpha;
    if literal && setup.beam.model != BeamModel::Exact {
        return Err(Error::Input(format!(
            "scene {}: {} integrates the thesis coupling as the published 3n + 6 system, which transcribes the exact beam; use `model: exact`, or genalpha for the thesis coupling on a {} beam",
            scene.name,
            opts.method.name(),
            setup.beam.model.name()
        )));
    }
    Ok(literal)
}

/// The model's state (z, ż) at the start, the beam in `start` and at rest (the vehicles'
/// bodies settled on it).
fn initial_state(
    loaded: &LoadedBeam,
    coupled: Option<&DiskOnBeam>,
    vehicles: Option<&VehiclesOnBeam>,
    start: &[f64],
) -> Vec<f64> {
    if let Some(v) = vehicles {
        return v.initial_state(&loaded.from_mesh(start));
    }
    match coupled {
        Some(c) => {
            let (z0, zd0) = c.initial_state(start);
            z0.into_iter().chain(zd0).collect()
        }
        None => loaded
            .from_mesh(start)
            .into_iter()
            .chain(vec![0.0; loaded.dim()])
            .collect(),
    }
}

/// Integrate while a disk is on the beam: rolling, and flying and landing where a disk
/// loses contact and flies, until the last leaves the beam, one stops, or the run ends.
#[allow(clippy::too_many_arguments)]
fn ride<'a>(
    scene: &Scene,
    setup: &BeamScene,
    loaded: &'a LoadedBeam<'a>,
    c: &'a DiskOnBeam<'a>,
    literal: bool,
    start: &[f64],
    outputs: &[f64],
    opts: &mut ode::Options,
    rec: &mut Recorder<'a>,
    stats: &mut Stats,
) -> Result<Ridden, Error> {
    let mut on = OnTheBeam {
        scene,
        setup,
        loaded,
        c,
        literal,
        start,
        outputs,
        opts,
        rec,
        stats,
        flights: Vec::new(),
        left: vec![None; c.count()],
    };
    life::live(&mut on, Next::Rolls(None))
}

/// The beam as a disk's life meets it (`disk::life`): what the riders' phases need of the
/// run, and what they keep. Its flights and landings are `fly.rs`.
struct OnTheBeam<'a, 'r> {
    scene: &'r Scene,
    setup: &'r BeamScene,
    loaded: &'a LoadedBeam<'a>,
    c: &'a DiskOnBeam<'a>,
    literal: bool,
    start: &'r [f64],
    outputs: &'r [f64],
    opts: &'r mut ode::Options,
    rec: &'r mut Recorder<'a>,
    stats: &'r mut Stats,
    flights: Vec<FlightRecord>,
    /// When each disk left the beam.
    left: Vec<Option<f64>>,
}

impl<'a> OnTheBeam<'a, '_> {
    /// Disk k flies where its scene lets it, beside disks that can ride on through its
    /// landing (`DiskOnBeam::rides_beside_a_flight`); beside others a lift-off stops the run.
    fn flies(&self, k: usize) -> bool {
        let c = self.c;
        matches!(c.spec_of(k).contact_loss, ContactLoss::Fly { .. })
            && (0..c.count()).all(|j| j == k || c.has_left(j) || c.rides_beside_a_flight(j))
    }

    /// The run stops at t in the state y of the coupled phase, for `stop`, where `disk`'s
    /// event stopped it.
    fn stopped(&mut self, t: f64, y: Vec<f64>, stop: Stop, disk: Option<usize>) -> Next<Self> {
        // The run stops between output times: its last row is the stop itself.
        if self.rec.history.rows.last().is_none_or(|r| r.t < t) {
            self.rec.output(t, &y);
        }
        Next::Ends(Ridden {
            stop,
            left_track_t: None,
            disks_left: self.left.clone(),
            flights: std::mem::take(&mut self.flights),
            then: Then::Ended { t, y },
            lost_contact: None,
            stopped_disk: disk.filter(|_| stop != Stop::End),
            wheel_flights: Vec::new(),
        })
    }

    /// The last disk has left the beam at t, the beam in (q, v): from then on the residual
    /// vibration is watched.
    fn left_beam(&mut self, t: f64, q: Vec<f64>, v: Vec<f64>) -> Next<Self> {
        for l in self.left.iter_mut().filter(|l| l.is_none()) {
            *l = Some(t);
        }
        self.rec.last_load_leaves(t);
        Next::Ends(Ridden {
            stop: Stop::End,
            left_track_t: Some(t),
            disks_left: self.left.clone(),
            flights: std::mem::take(&mut self.flights),
            then: Then::Alone { t, q, v },
            lost_contact: None,
            stopped_disk: None,
            wheel_flights: Vec::new(),
        })
    }
}

impl<'a> life::Track for OnTheBeam<'a, '_> {
    type Rolling = Option<(f64, Vec<f64>, Vec<f64>)>;
    type Launch = Launch;
    type Touch = Touch;
    type End = Ridden;

    /// The disks roll from `from` (the run's start where `None`) until one leaves the beam,
    /// stops, or lifts off, or the run ends.
    fn roll(&mut self, from: Self::Rolling) -> Result<Next<Self>, Error> {
        let end = integrate_coupled(
            self.scene,
            self.c,
            self.literal,
            self.start,
            from,
            self.outputs,
            self.opts,
            self.rec,
            self.stats,
        )?;
        Ok(match end {
            CoupledEnd::Stopped {
                t,
                y,
                stop: Stop::Event(StopReason::ContactLost),
                disk: Some(k),
            } if self.flies(k) => {
                // The damping the plan chose is for loads that move: once the disk has
                // left the beam, what it lands with or leaves behind vibrates freely.
                if self.setup.rho_inf_chosen.is_some() {
                    self.opts.rho_inf = 1.0;
                }
                Next::Flies(lift_off(self.c, self.rec, t, &y, k))
            }
            CoupledEnd::Stopped { t, y, stop, disk } => self.stopped(t, y, stop, disk),
            CoupledEnd::Left { t, y, disk } => {
                let c = self.c;
                let k = disk.unwrap_or_else(|| leaving(c, t));
                let on = (0..c.count()).filter(|&j| !c.has_left(j)).count();
                if on > 1 {
                    self.left[k] = Some(t);
                    return Ok(Next::Rolls(Some(one_leaves(c, k, self.rec, t, y))));
                }
                self.rec.ledger.disk_leaves(&self.rec.phase, t, &y);
                let n = self.loaded.dim();
                let (z, zd) = self.rec.phase.split(&y);
                let (q, v) = (z[..n].to_vec(), zd[..n].to_vec());
                self.left_beam(t, q, v)
            }
        })
    }

    fn fly(&mut self, launch: Launch) -> Result<Next<Self>, Error> {
        self.fly_once(launch)
    }

    fn land(&mut self, touch: Touch) -> Result<Next<Self>, Error> {
        self.touch_down(touch)
    }
}

/// The prescribed load that left the beam at t, its exit time, where no disk's event stopped
/// the integration.
fn leaving(c: &DiskOnBeam, t: f64) -> usize {
    match c.next_exit() {
        Some((te, k)) if (te - t).abs() <= 1e-12 * te.max(1.0) => k,
        _ => unreachable!("the coupled phase stops early only at an event or a load's exit"),
    }
}

/// Disk k leaves the beam at t, in the state y, while others ride on: the state they go on
/// from, with its contact coordinate at rest.
fn one_leaves(
    c: &DiskOnBeam,
    k: usize,
    rec: &mut Recorder,
    t: f64,
    y: Vec<f64>,
) -> (f64, Vec<f64>, Vec<f64>) {
    rec.ledger.one_disk_leaves(&rec.phase, t, &y, k);
    let (z, zd) = rec.phase.split(&y);
    let (z, mut zd) = (z.to_vec(), zd.to_vec());
    c.leave(k, &mut zd);
    let y: Vec<f64> = z.iter().chain(&zd).copied().collect();
    rec.ledger.restart(&rec.phase, t, &y);
    (t, z, zd)
}

/// Integrate the beam alone from where the riders left it to the end of the run.
fn vibrate_alone(
    scene: &Scene,
    loaded: &LoadedBeam,
    (t0, q0, v0): (f64, &[f64], &[f64]),
    outputs: &[f64],
    opts: &ode::Options,
    rec: &mut Recorder,
    stats: &mut Stats,
) -> Result<(f64, Vec<f64>), Error> {
    rec.phase.free();
    rec.train_goes_on(t0, &[q0, v0].concat());
    let exact = ode::Options {
        method: Method::ExactModal,
        ..opts.clone()
    };
    let planned_exact =
        scene.solver.free_vibration_chosen.is_some() && opts.method == scene.solver.method;
    let opts = if planned_exact { &exact } else { opts };
    // The output times from here on that no phase has recorded yet: a run without a disk
    // records its start here, after the disk left its leaving time is recorded.
    let rest: Vec<f64> = outputs
        .iter()
        .copied()
        .filter(|&o| o >= t0 && rec.history.rows.last().is_none_or(|r| r.t < o))
        .collect();
    let out = integrate(loaded, t0, q0, v0, scene.duration, &rest, opts, rec)
        .map_err(|e| solver_error(scene, e))?;
    stats.add(&out.stats);
    Ok((out.t, out.y))
}

/// The run's result.
#[allow(clippy::too_many_arguments)]
fn collect(
    scene: &Scene,
    setup: &BeamScene,
    opts: &ode::Options,
    unknowns: usize,
    ridden: Ridden,
    t_end: f64,
    stats: Stats,
    recorded: Recorded,
    damping: Option<Rayleigh>,
    beam: Beam,
) -> BeamRun {
    BeamRun {
        header: RunHeader {
            scene: scene.clone(),
            method: opts.method,
            rtol: opts.rtol,
            atol: opts.atol,
            unknowns,
            stop: ridden.stop,
            t_end,
            stats,
            energy: recorded.energy,
        },
        setup: setup.clone(),
        rows: recorded.rows,
        envelope: recorded.envelope,
        extremes: recorded.extremes.clone(),
        shapes: recorded.shapes,
        frames: recorded.frames,
        windowed_means: recorded.windowed_means,
        left_track_t: ridden.left_track_t,
        disks_left_t: ridden.disks_left,
        stopped_disk: ridden.stopped_disk,
        flights: ridden.flights,
        y_end: recorded.y_end,
        acceleration: recorded.acceleration,
        damping,
        vehicles: vehicle_reports(
            setup,
            &recorded.extremes.vehicles,
            &recorded.vehicle_rms,
            ridden.lost_contact,
            &ridden.wheel_flights,
            t_end,
            beam.length,
        ),
        beam,
    }
}
