//! A run of a loaded beam, with or without a disk on it: integrate, and record probe histories,
//! envelopes along the beam, deformed shapes, the disk's quantities and the energy budget
//! (kinetic + strain + potential − work of the loads).
//!
//! With a disk the run has two phases (`phase.rs`): the coupled one, until the disk leaves the
//! beam at an end (or stops at a physical event), then the beam alone, vibrating freely to the
//! end. The energy budget is kept by `ledger.rs`; the outputs are recorded by the sensors of
//! `sensors.rs`, which observe and compute nothing, gathered with the extremes watched over
//! every step by `recorder.rs` (a rolling disk's contact force also averaged over the
//! acceleration cutoff's period by `contact_mean.rs`, the support reactions counted to that
//! cutoff by `reactions.rs`) until a free vibration can move none of
//! them (`settled.rs`); the disks ride through the disk's life at its track
//! (`disk::life`), the beam's side of it in `ride.rs` and its flights and landings in
//! `fly.rs`; the vehicles' drive over the whole run is `vehicles.rs`, whose wheels' events the
//! disks' ride meets too where vehicles ride beside them (the disks then leave without ending
//! it). [`run`] names the steps of a run: build the model, the start state, ride (integrate
//! while the disk is on), vibrate alone, collect; what it hands back, and the warnings read
//! from it, is `result.rs`.

mod acceleration;
mod contact_mean;
mod flight;
mod fly;
mod ledger;
mod modal_probes;
mod phase;
mod reactions;
mod recorder;
mod result;
mod ride;
mod sensors;
mod settled;
mod vehicles;
mod watch;

use super::extremes::{Range, Turning, Watch};
use super::{FlightRecord, Overrides, Progress, RunHeader, Stop, MAX_FLIGHTS};
use crate::analysis::modes::modes;
use crate::analysis::statics;
use crate::beam::damping::Rayleigh;
use crate::beam::dynamics::LoadedBeam;
use crate::beam::load::BeamStart;
use crate::beam::modal::ModalBasis;
use crate::beam::supports::statically_supported;
use crate::beam::{Beam, BeamModel, PointDisplacement, Stations};
use crate::coupling::landing::Landing;
use crate::coupling::thesis_system::{integrates_as_published, ThesisSystem};
use crate::coupling::vehicles::{VehicleObservation, VehiclesOnBeam};
use crate::coupling::{Coupling, DiskEvent, DiskOnBeam};
use crate::disk::flight::Flight;
use crate::disk::life::{self, Next};
use crate::disk::{ContactLoss, StopReason};
use crate::error::Error;
use crate::linalg::SparseLu;
use crate::ode::second_order::FirstOrder;
use crate::ode::second_order::{SecondOrderProblem, Structure};
use crate::ode::{self, Dense, Method, Observer, Stats};
use crate::recent::Recent;
use crate::scene::{BeamScene, Model, Scene};
use acceleration::AccelerationFilter;
pub use acceleration::CutoffReport;
use flight::{BeneathFlight, FlightEvent, FlyingDisk};
use ledger::Ledger;
use phase::Phase;
pub use sensors::MEAN_WINDOWS;
use sensors::{History, Pictures, Sample, WindowedMeans};
use std::rc::Rc;
use std::sync::Arc;

use fly::*;
use recorder::*;
pub use result::{BeamRow, BeamRun, Envelope, Extremes, Frame};
use ride::*;
use vehicles::*;
pub use vehicles::{AxleFlight, VehicleReport};
use watch::*;

/// Points along the beam where envelopes and shapes are sampled.
pub const SAMPLES: usize = 201;

/// Frames an animation of a run holds at most.
pub const FRAMES: usize = 240;

/// Modal bases kept for the beams and mode counts last asked on this thread: a sweep's cases
/// share their beam, and a basis fills its residual flexibility's columns as runs ask for them
/// (per thread: that filling is not shared).
const KEPT_BASES: usize = 8;
/// Largest mesh (unknowns) whose basis is kept: its residual flexibility fills up to n² doubles.
const KEPT_BASIS_LIMIT: usize = 400;

thread_local! {
    static BASES: std::cell::RefCell<Recent<Rc<ModalBasis>>> =
        const { std::cell::RefCell::new(Recent::new(KEPT_BASES)) };
}

/// The modes of a modal beam, from its linear stiffness and mass.
fn modal_basis(scene: &Scene, beam: &Beam) -> Result<Option<Rc<ModalBasis>>, Error> {
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
    let key = format!("{:?}", beam.spec);
    let kept = BASES.with_borrow(|b| b.get(&key));
    if let Some(basis) = kept {
        return Ok(Some(basis));
    }
    let m = modes(beam, count).ok_or_else(|| {
        Error::Solver(format!(
            "scene {}: the natural modes of the modal beam could not be computed",
            scene.name
        ))
    })?;
    let basis = Rc::new(ModalBasis::new(
        m.shapes,
        m.omega,
        &beam.tangent(&vec![0.0; n]),
        beam.mass(),
    ));
    if n > KEPT_BASIS_LIMIT {
        return Ok(Some(basis));
    }
    BASES.with_borrow_mut(|b| b.keep(key, basis.clone()));
    Ok(Some(basis))
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

/// The solver's failure as the run's sentence. Where Newton's iteration gave up under the
/// method the scene names (`method`, the one the run used), the plan's own choice is named as what to try: generalized-α at
/// rtol 10⁻⁵ and 10⁻⁷ gave up on a 150 kg rolling disk beside a 10 t moving mass on D44's
/// mesh, which the plan's ESDIRK4 runs.
///
/// Where the step budget ran out on the exact beam the plan kept because the supports leave a
/// mechanism (no static response to choose a lighter model by), the modal beam is named: the
/// exact beam steps with every mode of its mesh, the stiff shear and axial ones included. A car
/// set down on a free–free deck as stiff in shear as Biggs' beam: TR-BDF2 gave up at
/// t = 5.5·10⁻⁵ s on the exact beam and finished in 3848 steps on the modal; ESDIRK4 took
/// 149 646 steps on the exact beam and 545 on the modal, the body's largest acceleration within
/// 6·10⁻⁵ of the exact's.
fn solver_error(scene: &Scene, method: Method, e: ode::SolveError) -> Error {
    let named = scene.solver.method_chosen.is_none() && method == scene.solver.method;
    let kept_exact_for_a_mechanism = matches!(&scene.model, Model::Beam(b)
        if b.beam.model == BeamModel::Exact
            && b.model_choice.is_some()
            && !statically_supported(b.beam.supports, b.beam.bearings.len()));
    let hint = match e {
        ode::SolveError::NewtonFailed { .. } if named => format!(
            "; the scene names the method ({}), whose iteration may not follow this coupling: leave `solver.method` out for the plan's choice",
            scene.solver.method.name()
        ),
        ode::SolveError::TooManySteps { .. } if kept_exact_for_a_mechanism => "; the supports leave a mechanism, so the plan kept the exact beam, which steps with every mode of its mesh: `track.beam.model: modal` keeps those the loads excite".to_string(),
        _ => String::new(),
    };
    Error::Solver(format!(
        "scene {}: the solver failed: {e}{hint}",
        scene.name
    ))
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
    rec.ledger.leaves_fast_modes_ringing = opts.method == ode::Method::GenAlpha;
    rec.ledger.steps_over_fast_modes = matches!(
        opts.method,
        ode::Method::Esdirk4 | ode::Method::TrBdf2 | ode::Method::GenAlpha
    );
    let view = FirstOrder::new(p).measuring_velocities_at(opts.velocity_rate);
    ode::solve(&view, t0, &y0, t_end, outputs, opts, rec)
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
    /// The vehicles beside the disks met their event `wheel` (`VehiclesOnBeam`'s numbering).
    Wheel { t: f64, y: Vec<f64>, wheel: usize },
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
        // From the start itself where a vehicle's wheel beside the disks set off in the air.
        let ahead: Vec<f64> = (outputs.iter().copied())
            .filter(|&o| o > t0 || t0 == 0.0)
            .collect();
        let out = integrate(c, t0, &z0, &zd0, until, &ahead, opts, rec)
            .map_err(|e| solver_error(scene, opts.method, e))?;
        stats.add(&out.stats);
        return Ok(coupled_end(scene, out.t, out.stopped_by, out.y));
    }
    let (z0, zd0) = c.initial_state(start);
    let (t, stopped_by, y) = if literal {
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
        .map_err(|e| solver_error(scene, opts.method, e))?;
        stats.add(&out.stats);
        // The literal system holds the lone disk.
        let hit = out.stopped_by.map(|h| ode::EventHit {
            reason: DiskEvent::Disk {
                disk: 0,
                reason: h.reason,
            },
            t: h.t,
        });
        (out.t, hit, sys.reduced(out.t, &out.y))
    } else {
        let out = integrate(c, 0.0, &z0, &zd0, until, outputs, opts, rec)
            .map_err(|e| solver_error(scene, opts.method, e))?;
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
    let (disk, stop) = match stopped_by.map(|hit| hit.reason) {
        Some(DiskEvent::Wheel(wheel)) => return CoupledEnd::Wheel { t, y, wheel },
        None if t < scene.duration => (None, None),
        None => (None, Some(Stop::End)),
        Some(DiskEvent::Disk {
            disk,
            reason: StopReason::LeftTrack,
        }) => (Some(disk), None),
        Some(DiskEvent::Disk { disk, reason }) => (Some(disk), Some(Stop::Event(reason))),
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
    let beam = Beam::shared(&setup.beam);
    let (modal, damping, lowest) = modes_and_damping(scene, &beam)?;
    let exact = over.options(scene).method == Method::ExactModal;
    let (loaded, filter) = loaded_beam(&beam, setup, modal.as_deref(), (damping, lowest), exact);
    let mut opts = ode::Options {
        rho_inf: setup.rho_inf,
        ..over.options(scene)
    };
    let first = loaded.dim() + DiskOnBeam::contact_coordinates(&setup.disks);
    let vehicles = vehicles_on(scene, setup, &loaded, first)?;
    let coupled = (!setup.disks.is_empty())
        .then(|| DiskOnBeam::new(&loaded, setup.disks.clone(), vehicles.as_ref()));
    if let (Some(c), Some(v)) = (&coupled, &vehicles) {
        v.ride_beside(c);
    }
    steps_within_budget(scene, &loaded, vehicles.as_ref(), &opts)?;
    let given = setup.acceleration_cutoff_hz.is_some();
    watch::grid_within_budget(scene, &loaded, filter.as_ref(), (exact, given))?;
    let outputs = output_times(scene, setup, over.no_history);
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

/// The beam under the scene's loads (resolved for its lowest circular frequency, stepped
/// exactly where `exact`) and the deck acceleration's filter: the beam reports the modes below
/// the cutoff, and where its loads only move, weighs them in the error norm.
fn loaded_beam<'a>(
    beam: &'a Beam,
    setup: &'a BeamScene,
    modal: Option<&'a ModalBasis>,
    (damping, lowest): (Option<Rayleigh>, f64),
    exact: bool,
) -> (LoadedBeam<'a>, Option<AccelerationFilter>) {
    let loaded = LoadedBeam::new(beam, &setup.loads, modal, damping, setup.train.as_ref())
        .resolving(lowest)
        .stepped_exactly(exact);
    let filter = AccelerationFilter::new(beam, &loaded, setup.acceleration_cutoff_hz);
    let mut loaded = loaded.reporting_accelerations_below(
        filter
            .as_ref()
            .map_or(0.0, |f| std::f64::consts::TAU * f.cutoff_hz),
    );
    if let Some((shapes, omega)) = filter.as_ref().and_then(|f| f.mesh_modes()) {
        if loads_only_move(setup) || quiets_what_strikes_it(setup, damping) {
            loaded = loaded.weighing_reported_modes(shapes, omega);
        }
    }
    (loaded, filter)
}

/// Whether the beam's loads only move over it, none switched and nothing riding with inertia:
/// its accelerations are then a small share of ω₁² times its deflections (2 % under a 10 t
/// force crossing a 30 m steel deck at 3 m/s), which the nodal displacements' atol does not
/// hold, and a mesh weighs its reported modes in the error norm. A switched load or a rider
/// with inertia rings the mesh's modes far above the lowest, which hold the steps short enough
/// for the nodal atol to hold the accelerations while they ring (B1–C3, undamped, within
/// 3.9·10⁻⁴ of their peaks at the defaults; where they die out, see
/// [`quiets_what_strikes_it`]), and the rows took 1.2 to 3.2 times the steps of the
/// studies given their own tolerances.
fn loads_only_move(setup: &BeamScene) -> bool {
    !setup.load_switched()
        && !setup.carries_moving_masses()
        && setup.vehicles.is_empty()
        && setup
            .disks
            .iter()
            .all(|d| d.coupling == Coupling::MovingForce)
}

/// Whether what strikes the beam (a load switched on it, a wheel with a mass turned at a kink of
/// the track or dropping off the deck) rings modes that the damping's stiffness term quiets: ζ
/// grows with ω, the highest modes of the mesh die within a few of their periods, the steps then
/// grow to what the lowest modes need, and their accelerations carry the error those steps leave in
/// the displacements, up to (ω_k/ω₁)² times it. A 100 kN load released on a 25 m steel beam (ζ 0.02
/// at modes 1 and 2), at rtol a thirtieth of the accuracy, read midspan's largest acceleration
/// 2.1·10⁻³ off in 118 steps with the nodal displacements within 8·10⁻⁵; with the reported modes
/// weighed, 7.7·10⁻⁵ in 263 steps (ζ 0.005: the envelope's 5.6·10⁻³ off, 2.8·10⁻⁴ with). A car on
/// two 510 kg wheels over a 5 mm ramp on a soft 30 m deck (ζ 0.05) read the quarter point 1 ms past
/// the ramp's top 2.3·10⁻³ of the deck's largest acceleration off, and under β = 5·10⁻⁴ s alone
/// 1.9·10⁻³ off after the car had left; with the modes weighed, every row within 1.8·10⁻⁵, in 1.16
/// and 1.74 times the steps. Undamped, the ringing holds the step down for the whole run and the
/// same rows change no step.
fn quiets_what_strikes_it(setup: &BeamScene, damping: Option<Rayleigh>) -> bool {
    let strikes = setup.load_switched() || setup.vehicles.iter().any(|v| v.has_unsprung_mass());
    strikes && damping.is_some_and(|d| d.beta > 0.0)
}

/// Refuses, before the run, a time-stepped run that its step budget cannot cover even at the
/// longest step the beam allows, a sixteenth of its lowest period, over the time it is surely
/// stepped: the whole run on a mesh, and on a modal beam (whose free vibration after the riders
/// is integrated exactly) until the last vehicle has left. Without it a vehicle started
/// 10 000 km before the deck rolls on the level approach for minutes until the budget stops it.
fn steps_within_budget(
    scene: &Scene,
    loaded: &LoadedBeam,
    vehicles: Option<&VehiclesOnBeam>,
    opts: &ode::Options,
) -> Result<(), Error> {
    if opts.method == Method::ExactModal || opts.whole_budget {
        return Ok(());
    }
    let ride = "the vehicles' ride (their approach to the deck included)";
    let (stepped, why) = match (loaded.modal, vehicles) {
        (None, _) => (scene.duration, "the run"),
        (Some(_), Some(v)) => (
            v.gone().map_or(scene.duration, |t| t.min(scene.duration)),
            ride,
        ),
        (Some(_), None) => return Ok(()),
    };
    let longest = loaded.longest_step();
    let steps = stepped / longest;
    if !(steps > opts.max_steps as f64) {
        return Ok(());
    }
    let nearer = if vehicles.is_some() {
        " or start the vehicles nearer the deck"
    } else {
        ""
    };
    Err(Error::Solver(format!(
        "scene {}: {why} takes {stepped:.3e} s, at least {steps:.1e} steps of a sixteenth of the lowest mode's period ({:.4} Hz), past the budget of {:.0e} steps: shorten the run{nearer}",
        scene.name,
        1.0 / (crate::beam::dynamics::STEPS_PER_PERIOD * longest),
        opts.max_steps as f64
    )))
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

/// A modal beam's basis, the damping resolved, and the lowest circular frequency.
type ModesAndDamping = (Option<Rc<ModalBasis>>, Option<Rayleigh>, f64);

/// The modes of a modal beam, the damping resolved, and the lowest circular frequency (0
/// where none could be computed).
fn modes_and_damping(scene: &Scene, beam: &Beam) -> Result<ModesAndDamping, Error> {
    let modal = modal_basis(scene, beam)?;
    let damping = crate::analysis::modes::rayleigh(beam)
        .map_err(|why| Error::Input(format!("scene {}: {why}", scene.name)))?;
    let lowest = match &modal {
        Some(m) => m.omega.first().copied(),
        None => modes(beam, 1).and_then(|m| m.omega.first().copied()),
    };
    Ok((modal, damping, lowest.unwrap_or(0.0)))
}

/// The run's output times and the shapes' times, sorted, each once; with `no_history`, the
/// first and the last of them alone.
fn output_times(scene: &Scene, setup: &BeamScene, no_history: bool) -> Vec<f64> {
    let mut outputs = super::output_times(scene);
    outputs.extend(setup.shapes.iter().copied());
    outputs.sort_by(f64::total_cmp);
    outputs.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    if no_history && outputs.len() > 2 {
        outputs.drain(1..outputs.len() - 1);
    }
    outputs
}

/// Whether the run integrates the thesis coupling as the published 3n + 6 system, which
/// transcribes the exact beam only.
fn thesis_system(
    scene: &Scene,
    setup: &BeamScene,
    coupled: Option<&DiskOnBeam>,
    opts: &ode::Options,
) -> Result<bool, Error> {
    let literal = coupled.is_some_and(|c| c.spec().coupling == Coupling::Thesis)
        && integrates_as_published(opts.method);
    if literal && !setup.vehicles.is_empty() {
        return Err(Error::Input(format!(
            "scene {}: {} integrates the thesis coupling as the published 3n + 6 system, which holds the disk and the beam alone; beside vehicles use genalpha or esdirk4",
            scene.name,
            opts.method.name()
        )));
    }
    if literal && setup.beam.model != BeamModel::Exact {
        return Err(Error::Input(format!(
            "scene {}: {} integrates the thesis coupling as the published 3n + 6 system, which transcribes the exact beam; use `model: exact`, or genalpha or esdirk4 for the thesis coupling on a {} beam",
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
    if let (Some(v), None) = (vehicles, coupled) {
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
        .map_err(|e| solver_error(scene, opts.method, e))?;
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
    beam: Arc<Beam>,
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::Planner;
    use crate::scene::SceneSpec;

    /// A train's force on the modes over a stretch between two kinks, in closed form (each
    /// axle's mode shapes along its element, ξ linear in time), against the force sampled at
    /// rest within the stretch: on the HSLM bridge as a modal beam, level (the axles' forces
    /// across the axis alone) and inclined (along it as well). Within 10⁻¹² of the force's size, the
    /// round-off of the shapes' powers of ξ.
    #[test]
    fn a_train_s_modal_force_over_a_stretch_is_its_samples() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/studies/hslm-15m.yaml");
        let text = std::fs::read_to_string(path).expect("the study is readable");
        for to in ["[15.0, 0.0]", "[14.0, 5.0]"] {
            let text = text
                .replace("to: [15.0, 0.0]", &format!("to: {to}"))
                .replace("    damping:", "    model: modal\n    damping:");
            let spec = SceneSpec::parse(&text, "test", "hslm").expect("a valid scene");
            let scene = Planner::default().plan(&spec).expect("planned");
            let setup = scene.beam().expect("a beam scene");
            let beam = Beam::shared(&setup.beam);
            let (modal, damping, lowest) = modes_and_damping(&scene, &beam).expect("modes");
            let (loaded, _) = loaded_beam(&beam, setup, modal.as_deref(), (damping, lowest), true);
            let mut kinks = loaded.kinks();
            kinks.extend(loaded.breakpoints());
            kinks.sort_by(f64::total_cmp);
            kinks.dedup();
            let n = loaded.dim();
            let (zeros, mut f) = (vec![0.0; n], vec![0.0; n]);
            let mut checked = 0;
            for stretch in kinks.windows(2).step_by(7) {
                let (t0, h) = (stretch[0], stretch[1] - stretch[0]);
                if !(h > 1e-9) {
                    continue;
                }
                // Which axles are on is the stretch's, as the run decides it.
                loaded.enter_segment(t0, t0 + h);
                let g = loaded.force_at_rest_over(t0, h).expect("a closed form");
                for sigma in [0.0, 0.3, 0.77, 1.0] {
                    loaded.force(t0 + sigma * h, &zeros, &zeros, &mut f);
                    let size: f64 = f.iter().map(|v| v.abs()).sum::<f64>().max(1.0);
                    for (gk, fk) in g.iter().zip(&f) {
                        let read = gk.iter().rev().fold(0.0, |acc, c| acc * sigma + c);
                        assert!(
                            (read - fk).abs() <= 1e-12 * size,
                            "to {to}, t {t0} + {sigma}·{h}: {read} against {fk}"
                        );
                    }
                }
                checked += 1;
            }
            assert!(checked > 20, "to {to}: {checked} stretches");
        }
    }
}
