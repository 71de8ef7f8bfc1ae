//! The energy budget of a beam run: kinetic + strain + potential − work + dissipated, checked at
//! every step and written at every output time. The work of the scene's point loads is exact
//! (within a step the active set is fixed, so each load adds P·Δd and M_z Δφ at its point), and so
//! is the work of the beam's own weight (a constant load: its dot product with the displacement
//! since the start); the work of a prescribed moving load is its power on the beam, and the energy
//! damping takes is its power vᵀCv, both by the trapezoidal rule over the steps, or over a long
//! step by the Gauss–Lobatto rule on pieces of it (`pending`), a second-order method's damping
//! by the midpoint rule on the mean of its steps' ends (`Ledger::step_mean_state`); where the
//! integrator holds the motion in closed form (`exact-modal`, the beam alone under moving
//! forces) both are its closed-form integrals. A disk that leaves the beam takes its energy with
//! it, which the budget keeps from then on; so does a disk that flies over it, whose flight keeps
//! it constant, until it lands, and what a landing takes is booked as `impact`.

use super::phase::Phase;
use crate::beam::load::PointLoad;
use crate::beam::{Beam, PointDisplacement};
use crate::coupling::DiskOnBeam;
use crate::disk::DiskObservation;
use crate::ode::second_order::Structure;
use crate::ode::PowerIntegrals;
use crate::run::EnergyCheck;

/// The energy terms at one time.
pub(super) struct Energy {
    pub kinetic: f64,
    pub strain: f64,
    pub potential: f64,
    pub work: f64,
    pub dissipated: f64,
    /// What the landings have taken.
    pub impact: f64,
}

pub(super) struct Ledger<'a> {
    loads: &'a [PointLoad],
    /// Work of the point loads up to the last step, that step's time, and the loads'
    /// displacements then.
    done: f64,
    t: f64,
    at_loads: Vec<PointDisplacement>,
    /// Work of a moving load, by the trapezoidal rule over the steps: (t, power, work).
    moving: (f64, f64, f64),
    /// The energy of the disks that have left, as they left (they leave the model with it),
    /// or of the disk flying: (kinetic, potential).
    left_with: (f64, f64),
    /// The beam's weight dotted with the start's displacements.
    weight0: f64,
    /// Energy taken by damping, by the trapezoidal rule over the steps: (t, power, energy).
    damped: (f64, f64, f64),
    /// Kinetic energy the landings took.
    impact: f64,
    /// Pieces of the step under way, their powers read at their Lobatto points, booked as the
    /// run passes their ends.
    pending: std::collections::VecDeque<Piece>,
    /// Pieces from a booked piece's start to an output time inside it, read for that output's
    /// row alone: the booking never splits at output times, so that the output grid moves no
    /// number the run reports.
    to_outputs: std::collections::VecDeque<Piece>,
    /// The end of the step just taken read on that step's side of its breakpoints: where a
    /// vehicle's wheel crosses a kink of the profile the drive's power jumps, and so does the
    /// vertical speed of its unsprung mass; a train's axle leaves the deck; and by the time
    /// the step is booked the run has entered the next stretch. (t, the stretch, the moving
    /// loads' power, the vehicles' kinetic energy.)
    end_power: Option<StepEnd>,
    pub check: EnergyCheck,
    /// The integrator's order (`Method::order`): how a step is booked.
    pub order: u32,
    /// The integrator leaves the modes its steps pass over ringing, their velocity flipping
    /// sign from step to step (generalized-α, which damps them by ρ∞ a step where TR-BDF2's
    /// BDF2 stage quiets them): its damping is booked at its steps' mean states.
    pub leaves_fast_modes_ringing: bool,
    /// The integrator is implicit, and its steps may pass over fast modes it damps: inside a
    /// step the powers read the velocities from the positions (`recorder::BookedStep`).
    pub steps_over_fast_modes: bool,
    /// The powers at the midpoint of the step under way, where it is booked by Simpson's rule.
    mid: Option<Midpoint>,
    /// The step under way (t0, t1) and the damping's power at the mean of its ends' states,
    /// where it books the damping by the midpoint rule ([`Ledger::step_mean_state`]).
    mean_damping: Option<(f64, f64, f64)>,
}

/// The end of a step on its own stretch (`Ledger::end_power`).
struct StepEnd {
    t: f64,
    stretch: f64,
    power: f64,
    /// The damping's power: the dampers' ė jumps with the track's speed.
    damping: f64,
    kinetic: f64,
}

/// A piece of a long step, read when the step is taken (the loads on the beam are those of
/// its stretch between breakpoints): its end, how the moving loads' work and the damping's
/// energy over it are booked, and the point loads' displacements at its end.
pub(super) struct Piece {
    end: f64,
    moving: Booking,
    damping: Booking,
    at_loads: Vec<PointDisplacement>,
}

/// What a piece adds to an energy: by the [`LOBATTO`] rule from the power at the rule's
/// interior points and the piece's end, or known (in closed form, or integrated to a
/// tolerance), with the power at the end.
enum Booking {
    Lobatto([f64; 3], f64),
    Exact { energy: f64, power: f64 },
}

/// The powers at the midpoint of the step ending at `end`, for Simpson's rule
/// ([`Ledger::step_midpoint`]).
struct Midpoint {
    end: f64,
    moving: f64,
    damping: f64,
}

/// What [`Ledger::adaptive_pieces`] may err by, of the step's ∫|power| dt: the balance then
/// closes well inside the fourth-order integrator's own error at a thousandth of the accuracy.
const ADAPTIVE_TOLERANCE: f64 = 1e-7;

/// Halvings [`adaptive_simpson`] goes to at the most: a step's power holds a jump where a wheel
/// bridges a hollow between events, which no halving smooths, and the error left there shrinks
/// with the last half's length.
const ADAPTIVE_DEPTH: u32 = 12;

/// A stretch [a, b] of a step adaptive Simpson's rule settled on: f at a, and ∫ f over it.
struct Leaf {
    a: f64,
    b: f64,
    fa: [f64; 2],
    integral: [f64; 2],
}

fn simpson(h: f64, p: [f64; 2], q: [f64; 2], r: [f64; 2]) -> [f64; 2] {
    [0, 1].map(|k| h * (p[k] + 4.0 * q[k] + r[k]) / 6.0)
}

/// ∫ f over [a, b], `ends` f at a, the middle and b, by Simpson's rule on halves of halves
/// until a half's two estimates agree within its share of `tolerance` (then extrapolated by
/// Richardson's rule), or `depth` halvings: the stretches settled on, in order, into `leaves`.
fn adaptive_simpson(
    f: &dyn Fn(f64) -> [f64; 2],
    a: f64,
    b: f64,
    [fa, fm, fb]: [[f64; 2]; 3],
    tolerance: f64,
    depth: u32,
    leaves: &mut Vec<Leaf>,
) {
    let m = 0.5 * (a + b);
    let (fl, fr) = (f(0.5 * (a + m)), f(0.5 * (m + b)));
    let whole = simpson(b - a, fa, fm, fb);
    let (left, right) = (simpson(m - a, fa, fl, fm), simpson(b - m, fm, fr, fb));
    let halves = [0, 1].map(|k| left[k] + right[k]);
    let error = (0..2)
        .map(|k| (halves[k] - whole[k]).abs())
        .fold(0.0, f64::max);
    if depth == 0 || error <= 15.0 * tolerance || !(m > a && m < b) {
        let integral = [0, 1].map(|k| halves[k] + (halves[k] - whole[k]) / 15.0);
        leaves.push(Leaf { a, b, fa, integral });
        return;
    }
    adaptive_simpson(f, a, m, [fa, fl, fm], 0.5 * tolerance, depth - 1, leaves);
    adaptive_simpson(f, m, b, [fm, fr, fb], 0.5 * tolerance, depth - 1, leaves);
}

/// The five-point Gauss–Lobatto rule on a piece [0, 1]: its interior points and their
/// weights, and the weight of either end (shared with the next piece). Exact to degree 7, it
/// errs by about 7.0·10⁻¹⁰ (ωh)⁸ of a power oscillating at ω over a piece h, where Simpson's
/// rule errs by (ωh)⁴/2880: at ωh = 1, 7·10⁻¹⁰ against 3.5·10⁻⁴.
pub(super) const LOBATTO: ([f64; 3], [f64; 3], f64) = (
    [0.172_673_164_646_011_43, 0.5, 0.827_326_835_353_988_6],
    [49.0 / 180.0, 16.0 / 45.0, 49.0 / 180.0],
    1.0 / 20.0,
);

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

impl<'a> Ledger<'a> {
    /// The budget from the start state y0 (at rest): its strain energy, and the disk's energy
    /// where it belongs to the system.
    pub fn new(phase: &Phase, loads: &'a [PointLoad], y0: &[f64]) -> Self {
        let strain0 = Self::beam_energies(phase, y0).1;
        let (vk, vs, vp) = Self::vehicle_energies(phase, 0.0, y0);
        let mut check = EnergyCheck::new(strain0 + vk + vs + vp, strain0 + vk + vs + vp.abs());
        let mut moving = (0.0, 0.0, 0.0);
        if let Some(c) = phase.coupled {
            let (z0, zd0) = phase.split(y0);
            let (dk, dp) = Self::in_system(c, &c.observe_all(0.0, z0, zd0));
            let (dk, dp) = (dk + vk + vs, dp + vp);
            check = EnergyCheck::new(dk + dp + strain0, dk + dp.abs() + strain0);
        }
        moving.1 = Self::moving_power(phase, 0.0, y0);
        let n = phase.loaded.dim();
        let z0 = phase.split(y0).0;
        let mut ledger = Ledger {
            loads,
            done: 0.0,
            t: 0.0,
            at_loads: Vec::new(),
            moving,
            left_with: (0.0, 0.0),
            weight0: phase.loaded.weight_dot(&z0[..n]),
            damped: (0.0, Self::damping_power(phase, 0.0, y0), 0.0),
            impact: 0.0,
            pending: std::collections::VecDeque::new(),
            to_outputs: std::collections::VecDeque::new(),
            end_power: None,
            check,
            order: 2,
            leaves_fast_modes_ringing: false,
            steps_over_fast_modes: false,
            mid: None,
            mean_damping: None,
        };
        ledger.at_loads = ledger.at_loads(phase, y0);
        ledger
    }

    /// The beam's kinetic and strain energy, in the model's unknowns.
    fn beam_energies(phase: &Phase, y: &[f64]) -> (f64, f64) {
        let n = phase.loaded.dim();
        let (z, zd) = phase.split(y);
        phase.loaded.energies(&z[..n], &zd[..n])
    }

    /// The vehicles' kinetic, spring and potential energy (`coupling::vehicles`).
    fn vehicle_energies(phase: &Phase, t: f64, y: &[f64]) -> (f64, f64, f64) {
        match phase.vehicles {
            Some(v) => {
                let (z, zd) = phase.split(y);
                v.energies(t, z, zd)
            }
            None => (0.0, 0.0, 0.0),
        }
    }

    /// The stretch between breakpoints whose moving loads the powers read, where the loads
    /// on the deck change at breakpoints: vehicles' wheels, and a train's axles (a moving
    /// force leaving a cantilever's tip takes its power there with it, which the step ending
    /// on that breakpoint still has: read on the next stretch, HSLM-A1 over a cantilever's
    /// free end drifted by 1e-2).
    fn stretch(phase: &Phase) -> Option<f64> {
        match phase.vehicles {
            Some(v) => Some(v.stretch()),
            None => phase.loaded.train.is_some().then(|| phase.loaded.stretch()),
        }
    }

    /// The displacements at the loads' points (none to read without loads).
    fn at_loads(&self, phase: &Phase, y: &[f64]) -> Vec<PointDisplacement> {
        if self.loads.is_empty() {
            return Vec::new();
        }
        let (q, _) = phase.beam_state(y);
        load_displacements(phase.beam, self.loads, &q)
    }

    /// The kinetic and potential energy of the disks observed as `disks` that belong to the
    /// system (the rolling ones on the beam, not one flying over it).
    fn in_system(c: &DiskOnBeam, disks: &[Option<DiskObservation>]) -> (f64, f64) {
        disks
            .iter()
            .enumerate()
            .filter(|&(k, _)| c.in_system(k) && !c.has_left(k))
            .filter_map(|(_, d)| d.as_ref())
            .fold((0.0, 0.0), |(k, p), d| (k + d.kinetic, p + d.potential))
    }

    /// The disks' kinetic and potential energy, as far as it belongs to the system: those on
    /// the beam as observed in `disks`, and what those that left took with them.
    fn disk_energies(&self, phase: &Phase, disks: &[Option<DiskObservation>]) -> (f64, f64) {
        let (k, p) = phase
            .coupled
            .map_or((0.0, 0.0), |c| Self::in_system(c, disks));
        (k + self.left_with.0, p + self.left_with.1)
    }

    /// The work of the beam's own weight since the start.
    fn weight_work(&self, phase: &Phase, y: &[f64]) -> f64 {
        let n = phase.loaded.dim();
        phase.loaded.weight_dot(&phase.split(y).0[..n]) - self.weight0
    }

    /// The energy damping has taken up to (t, y), and its power there.
    fn dissipated(&self, phase: &Phase, t: f64, y: &[f64]) -> (f64, f64) {
        let p = Self::damping_power(phase, t, y);
        let (t0, p0, done) = self.damped;
        (done + 0.5 * (p0 + p) * (t - t0), p)
    }

    /// The power the beam's damping and the vehicles' dampers take at (t, y).
    fn damping_power(phase: &Phase, t: f64, y: &[f64]) -> f64 {
        let n = phase.loaded.dim();
        let (z, zd) = phase.split(y);
        let vehicles = phase.vehicles.map_or(0.0, |v| v.damper_power(t, z, zd));
        phase.loaded.dissipation(&zd[..n]) + vehicles
    }

    /// The power of the prescribed moving loads on the beam at (t, y): a disk carried at its
    /// speed, a train's axles, and the drive of the vehicles.
    fn moving_power(phase: &Phase, t: f64, y: &[f64]) -> f64 {
        let disk = match phase.coupled {
            Some(c) => {
                let (z, zd) = phase.split(y);
                c.power_on_beam(t, z, zd)
            }
            None => 0.0,
        };
        let train = if phase.loaded.train.is_some() {
            let n = phase.loaded.dim();
            let (z, zd) = phase.split(y);
            let a = (!phase.loaded.riding(t).is_empty()).then(|| phase.acceleration(t, y));
            phase.loaded.train_power(t, &z[..n], &zd[..n], a.as_deref())
        } else {
            0.0
        };
        let drive = phase.vehicles.map_or(0.0, |v| {
            let (z, zd) = phase.split(y);
            v.drive_power(t, z, zd, &v.acceleration_the_wheels_feel(t, z, zd))
        });
        disk + train + drive
    }

    /// The moving loads' work until t, where their power is `power`: the trapezoidal rule
    /// over the stretch since the last step.
    fn moving_work(&self, t: f64, power: f64) -> f64 {
        let (t0, p0, done) = self.moving;
        done + 0.5 * (p0 + power) * (t - t0)
    }

    /// The terms at an output time, with the disk as observed there. The check reads the
    /// steps alone: an output's interpolated state carries the dense output's error into the
    /// balance, and the output grid would move the drift.
    pub fn at_output(
        &mut self,
        phase: &Phase,
        t: f64,
        y: &[f64],
        disks: &[Option<DiskObservation>],
    ) -> Energy {
        self.catch_up(t);
        let (kinetic, strain) = Self::beam_energies(phase, y);
        let (disk_kinetic, potential) = self.disk_energies(phase, disks);
        let (vk, vs, vp) = Self::vehicle_energies(phase, t, y);
        let (kinetic, strain, potential) =
            (kinetic + disk_kinetic + vk, strain + vs, potential + vp);
        while self.to_outputs.front().is_some_and(|p| p.end < t) {
            self.to_outputs.pop_front();
        }
        let (work, dissipated) = match self.to_outputs.front().filter(|p| p.end == t) {
            Some(piece) => {
                let (moving, damped) = (
                    Self::booked(self.moving, &piece.moving, piece.end).2,
                    Self::booked(self.damped, &piece.damping, piece.end).2,
                );
                let done =
                    self.done + work_since(self.loads, self.t, t, &self.at_loads, &piece.at_loads);
                (done + moving + self.weight_work(phase, y), damped)
            }
            None => {
                let now = self.at_loads(phase, y);
                let work = self.done
                    + work_since(self.loads, self.t, t, &self.at_loads, &now)
                    + self.moving_work(t, Self::moving_power(phase, t, y))
                    + self.weight_work(phase, y);
                (work, self.dissipated(phase, t, y).0)
            }
        };
        Energy {
            kinetic,
            strain,
            potential,
            work,
            dissipated,
            impact: self.impact,
        }
    }

    /// The work and the damping's energy booked up to (t, y) by the trapezoidal rule from the
    /// last point booked.
    fn book(&mut self, phase: &Phase, t: f64, y: &[f64]) {
        let now = self.at_loads(phase, y);
        self.done += work_since(self.loads, self.t, t, &self.at_loads, &now);
        self.t = t;
        self.at_loads = now;
        let stretch = Self::stretch(phase);
        // Across a kink the wheel's track turns at once: its unsprung mass takes a vertical
        // impulse, whose energy the drive delivers through the wheel's contact, booked with
        // the drive's work.
        let end = self.end_power.take().filter(|e| e.t == t);
        let (end_power, power, kick) = match &end {
            Some(e) if Some(e.stretch) == stretch => (e.power, e.power, 0.0),
            Some(e) => (
                e.power,
                Self::moving_power(phase, t, y),
                Self::vehicle_energies(phase, t, y).0 - e.kinetic,
            ),
            None => {
                let p = Self::moving_power(phase, t, y);
                (p, p, 0.0)
            }
        };
        let mid = self.mid.take().filter(|m| m.end == t);
        let over_step = |(t0, p0, done): (f64, f64, f64), at_mid: Option<f64>, p1: f64| {
            done + match at_mid {
                Some(pm) => (t - t0) * (p0 + 4.0 * pm + p1) / 6.0,
                None => 0.5 * (p0 + p1) * (t - t0),
            }
        };
        let moving_done = over_step(self.moving, mid.as_ref().map(|m| m.moving), end_power);
        self.moving = (t, power, moving_done + kick);
        let now = Self::damping_power(phase, t, y);
        let p1 = end.as_ref().map_or(now, |e| e.damping);
        let damped_done = match self.damping_at_mean(self.damped.0, t) {
            Some(p) => self.damped.2 + (t - self.damped.0) * p,
            None => over_step(self.damped, mid.as_ref().map(|m| m.damping), p1),
        };
        self.damped = (t, now, damped_done);
    }

    /// The step just taken ends at (t, y), read on its own stretch (with vehicles or a train
    /// only: see `end_power`).
    pub fn step_ends(&mut self, phase: &Phase, t: f64, y: &[f64]) {
        if let Some(stretch) = Self::stretch(phase) {
            self.end_power = Some(StepEnd {
                t,
                stretch,
                power: Self::moving_power(phase, t, y),
                damping: Self::damping_power(phase, t, y),
                kinetic: Self::vehicle_energies(phase, t, y).0,
            });
        }
    }

    /// Book the step under way by Simpson's rule on these pieces, each as the run passes its
    /// end (a long step: `exact-modal`'s span many watched samples, over which the powers are
    /// smooth and the trapezoidal rule over the whole step would not be).
    pub fn book_in_pieces(&mut self, pieces: Vec<Piece>) {
        self.pending.extend(pieces);
    }

    /// Pieces from a booked piece's start to each output time inside it, for the rows alone.
    pub fn to_outputs(&mut self, pieces: Vec<Piece>) {
        self.to_outputs.extend(pieces);
    }

    /// The piece of a step from `start`, the last point read, to (t, y), through the states
    /// at its interior [`LOBATTO`] points.
    pub fn piece(
        &self,
        phase: &Phase,
        start: f64,
        inner: [(f64, &[f64]); 3],
        t: f64,
        y: &[f64],
    ) -> Piece {
        let inner = inner.map(|(ti, yi)| Self::powers(phase, ti, yi));
        let end = Self::powers(phase, t, y);
        let damping = match self.damping_at_mean(start, t) {
            Some(p) => Booking::Exact {
                energy: (t - start) * p,
                power: p,
            },
            None => Booking::Lobatto(inner.map(|p| p[1]), end[1]),
        };
        Piece {
            end: t,
            moving: Booking::Lobatto(inner.map(|p| p[0]), end[0]),
            damping,
            at_loads: self.at_loads(phase, y),
        }
    }

    /// The step under way, from t0 to t1, has the mean of its ends' states `y_mean`: the
    /// damping's energy over it, and over each piece of it, is booked as the time times the
    /// power there. Generalized-α leaves a mode its steps pass over with a velocity that flips
    /// sign from step to step, and damps it by what the mean of the ends shows (Newmark's
    /// trapezoidal rule balances so exactly on a linear beam); the ends' powers, or a dense
    /// output's between them, count it at its full velocity: HSLM-A1 running onto a free–free
    /// deck under β damping, at rtol 3.3e-6, booked a drift of 13.9 so, 3·10⁻⁴ by the mean
    /// (ESDIRK4: 10⁻⁴). Where the steps resolve every mode the mean is a second-order rule
    /// beside the dense output's fourth: the same deck pinned, under α damping, drifts by
    /// 4.7·10⁻⁴ against 5·10⁻⁵, its loss within 5·10⁻⁵ of ESDIRK4's at 10⁻⁹ either way.
    pub fn step_mean_state(&mut self, phase: &Phase, (t0, t1): (f64, f64), y_mean: &[f64]) {
        let p = Self::damping_power(phase, 0.5 * (t0 + t1), y_mean);
        self.mean_damping = Some((t0, t1, p));
    }

    /// The damping's power at the mean state of the step under way, where the stretch from
    /// `start` to t lies inside it.
    fn damping_at_mean(&self, start: f64, t: f64) -> Option<f64> {
        self.mean_damping
            .filter(|&(t0, t1, _)| t0 <= start && t <= t1)
            .map(|(_, _, p)| p)
    }

    /// The moving loads' power and the damping's at (t, y), read one after the other: what
    /// rides the beam is found once for both.
    fn powers(phase: &Phase, t: f64, y: &[f64]) -> [f64; 2] {
        [
            Self::moving_power(phase, t, y),
            Self::damping_power(phase, t, y),
        ]
    }

    /// The step under way, ending at `end`, passes its midpoint (t, y): its powers there, so
    /// that the step is booked by Simpson's rule when it ends (its error h⁵ a step where the
    /// trapezoidal rule's is h³). The budget's quadrature then shrinks faster than the
    /// fourth-order integrator's own error: by the trapezoidal rule a vehicle's balance
    /// shrank as rtol^½, the quadrature's error, not the solution's.
    pub fn step_midpoint(&mut self, phase: &Phase, end: f64, t: f64, y: &[f64]) {
        self.mid = Some(Midpoint {
            end,
            moving: Self::moving_power(phase, t, y),
            damping: Self::damping_power(phase, t, y),
        });
    }

    /// Whether a step is booked by Simpson's rule ([`Self::step_midpoint`]): where the
    /// integrator's order is above two, and something works on the model or takes its energy
    /// at a rate the budget integrates (moving loads, a train, vehicles, damping). A
    /// second-order method's own error is of the trapezoidal rule's order, and
    /// generalized-α's discrete energy balance is the trapezoidal rule's: D44's damped moving
    /// force on the exact beam, by Simpson's rule, read a drift of 2.9e-4 where the
    /// trapezoidal rule reads 8.0e-6.
    pub fn books_by_simpson(&self, phase: &Phase) -> bool {
        self.order > 2 && self.has_powers(phase)
    }

    /// Whether a step books the damping, the beam's and the vehicles' dampers', at its mean
    /// state ([`Self::step_mean_state`]): where the integrator leaves the fast modes ringing
    /// (a truck's dampers over the bridge by generalized-α: a drift of 1.4·10⁻⁶ by the ends'
    /// powers, 4·10⁻⁸ by the mean).
    pub fn damps_at_mean_state(&self, phase: &Phase) -> bool {
        self.leaves_fast_modes_ringing
            && (phase.vehicles.is_some() || phase.loaded.damping().is_some())
    }

    /// Something works on the model or takes its energy at a rate the budget integrates.
    fn has_powers(&self, phase: &Phase) -> bool {
        phase.vehicles.is_some()
            || phase.loaded.train.is_some()
            || phase.loaded.damping().is_some()
            || phase.coupled.is_some_and(|c| c.carries_prescribed())
    }

    /// Whether the integrator's own force is the moving loads' alone, so that its work in
    /// closed form ([`PowerIntegrals`]) is theirs: the beam alone under a train of moving
    /// forces, no point load and no weight (whose work the ledger books from displacements).
    pub fn books_in_closed_form(&self, phase: &Phase) -> bool {
        self.loads.is_empty()
            && phase.coupled.is_none()
            && phase.vehicles.is_none()
            && phase.flying.is_none()
            && phase.loaded.beam.weight().is_none()
    }

    /// The step from `start` to t as one piece, its moving loads' work and damping's energy
    /// integrated by adaptive Simpson's rule on the states `state` gives, and the pieces from
    /// `start` to each of the output times `rows` inside it (each the stretches settled on up
    /// to it and Simpson's rule over the rest of its own). A vehicle's axles
    /// follow their tracks with no unknowns of their own, so the steps, set by what the
    /// unknowns do, need not follow how fast the drive's power turns: where a disk wheel's
    /// contact sweeps a hollow that bends nearly as fast as the disk, the power swings within
    /// a fraction of a step, and Simpson's rule over the step missed it (a truck's 0.4 m disks
    /// at 30 m/s over ISO class D waves of 0.2–5 m: 3.5 J in one step, a balance of 1.4e-3).
    pub fn adaptive_pieces(
        &self,
        phase: &Phase,
        (start, t): (f64, f64),
        rows: &[f64],
        state: &dyn Fn(f64) -> Vec<f64>,
    ) -> (Piece, Vec<Piece>) {
        let powers = |ti: f64| Self::powers(phase, ti, &state(ti));
        let y = state(t);
        // The step's start is where the last was booked, and its end was read on its own
        // stretch (`step_ends`): their powers are the ledger's.
        let first = if self.moving.0 == start && self.damped.0 == start {
            [self.moving.1, self.damped.1]
        } else {
            powers(start)
        };
        let last = match &self.end_power {
            Some(e) if e.t == t => [e.power, e.damping],
            _ => Self::powers(phase, t, &y),
        };
        let ends = [first, powers(0.5 * (start + t)), last];
        let size: f64 = (0..2)
            .map(|k| (ends[0][k].abs() + 4.0 * ends[1][k].abs() + ends[2][k].abs()) / 6.0)
            .sum();
        let tolerance = ADAPTIVE_TOLERANCE * (t - start) * size;
        let mut leaves = Vec::new();
        adaptive_simpson(
            &powers,
            start,
            t,
            ends,
            tolerance,
            ADAPTIVE_DEPTH,
            &mut leaves,
        );
        let sum = |of: &[Leaf]| {
            of.iter().fold([0.0, 0.0], |s, l| {
                [s[0] + l.integral[0], s[1] + l.integral[1]]
            })
        };
        let whole = self.integrated(phase, t, &y, sum(&leaves), ends[2]);
        let rows = rows
            .iter()
            .map(|&o| {
                let yo = state(o);
                let at = Self::powers(phase, o, &yo);
                let settled = leaves.partition_point(|l| l.b <= o);
                let mut energy = sum(&leaves[..settled]);
                if let Some(l) = leaves.get(settled).filter(|l| o > l.a) {
                    let rest = simpson(o - l.a, l.fa, powers(0.5 * (l.a + o)), at);
                    energy = [energy[0] + rest[0], energy[1] + rest[1]];
                }
                self.integrated(phase, o, &yo, energy, at)
            })
            .collect();
        (whole, rows)
    }

    /// The piece ending at (t, y) that adds `energy` (the moving loads' work, the damping's),
    /// with the powers there.
    fn integrated(
        &self,
        phase: &Phase,
        t: f64,
        y: &[f64],
        energy: [f64; 2],
        power: [f64; 2],
    ) -> Piece {
        Piece {
            end: t,
            moving: Booking::Exact {
                energy: energy[0],
                power: power[0],
            },
            damping: Booking::Exact {
                energy: energy[1],
                power: power[1],
            },
            at_loads: self.at_loads(phase, y),
        }
    }

    /// The piece of a step from the last point booked to (t, y), whose moving loads' work and
    /// damping's energy the integrator knows in closed form; at the step's end its powers
    /// are those `step_ends` read there.
    pub fn exact_piece(&self, phase: &Phase, t: f64, y: &[f64], by: PowerIntegrals) -> Piece {
        let power = match &self.end_power {
            Some(e) if e.t == t => [e.power, e.damping],
            _ => Self::powers(phase, t, y),
        };
        self.integrated(phase, t, y, [by.work, by.dissipated], power)
    }

    /// An energy booked as (t, power, energy), carried on to the `end` of a piece that
    /// `booking` books from t.
    fn booked((t0, p0, done): (f64, f64, f64), booking: &Booking, end: f64) -> (f64, f64, f64) {
        match *booking {
            Booking::Lobatto(inner, p1) => {
                let (_, weights, ends) = LOBATTO;
                let sum: f64 = weights.iter().zip(inner).map(|(w, p)| w * p).sum();
                (end, p1, done + (end - t0) * (ends * (p0 + p1) + sum))
            }
            Booking::Exact { energy, power } => (end, power, done + energy),
        }
    }

    /// Book the pending pieces that end by t, by the Gauss–Lobatto rule.
    fn catch_up(&mut self, t: f64) {
        while let Some(piece) = self.pending.pop_front() {
            if piece.end > t {
                self.pending.push_front(piece);
                return;
            }
            self.moving = Self::booked(self.moving, &piece.moving, piece.end);
            self.damped = Self::booked(self.damped, &piece.damping, piece.end);
            self.done += work_since(
                self.loads,
                self.t,
                piece.end,
                &self.at_loads,
                &piece.at_loads,
            );
            self.t = piece.end;
            self.at_loads = piece.at_loads;
        }
    }

    /// An accepted step ends at (t, y): the work so far is booked, and the balance checked.
    pub fn at_step(&mut self, phase: &Phase, t: f64, y: &[f64]) {
        self.catch_up(t);
        self.book(phase, t, y);
        let (kinetic, strain) = Self::beam_energies(phase, y);
        let (on, left) = (
            match phase.coupled {
                Some(c) if c.disk_in_system() => {
                    let (z, zd) = phase.split(y);
                    c.energies(t, z, zd)
                }
                _ => (0.0, 0.0),
            },
            self.left_with,
        );
        let (disk_kinetic, potential) = (on.0 + left.0, on.1 + left.1);
        let (vk, vs, vp) = Self::vehicle_energies(phase, t, y);
        let (kinetic, strain, potential) =
            (kinetic + disk_kinetic + vk, strain + vs, potential + vp);
        let dissipated = self.damped.2;
        self.check.record(
            kinetic + strain + potential - self.done - self.moving.2 - self.weight_work(phase, y)
                + dissipated
                + self.impact,
            kinetic + strain + potential.abs(),
        );
    }

    /// The last disks leave the beam at t, in the state y of the coupled phase: they take
    /// their energy with them, and the moving loads' work is closed.
    pub fn disk_leaves(&mut self, phase: &Phase, t: f64, y: &[f64]) {
        if let Some(c) = phase.coupled {
            let (z, zd) = phase.split(y);
            let (k, p) = Self::in_system(c, &c.observe_all(t, z, zd));
            self.left_with = (self.left_with.0 + k, self.left_with.1 + p);
        }
        self.done += self.moving.2;
        self.moving = (t, 0.0, 0.0);
    }

    /// Disk k leaves the beam at t, in the state y of the coupled phase, while others ride
    /// on: it takes its energy with it. The powers are read again once it has left
    /// ([`Self::restart`]).
    pub fn one_disk_leaves(&mut self, phase: &Phase, t: f64, y: &[f64], k: usize) {
        let Some(c) = phase.coupled else { return };
        if c.in_system(k) {
            let (z, zd) = phase.split(y);
            if let Some(d) = c.observe_all(t, z, zd)[k] {
                self.left_with = (self.left_with.0 + d.kinetic, self.left_with.1 + d.potential);
            }
        }
    }

    /// A disk lands on the beam at t and rides on it again, the landing having taken `lost`
    /// of the kinetic energy, and the train's moving masses having done `work` on the beam
    /// through the impulse: the energy it `carried` while it flew is the system's again,
    /// observed live.
    pub fn disk_lands(&mut self, lost: f64, work: f64, carried: (f64, f64)) {
        self.left_with = (self.left_with.0 - carried.0, self.left_with.1 - carried.1);
        self.impact += lost;
        self.moving.2 += work;
    }

    /// A vehicle's wheel lands at t: the impact took `lost`, and the drive, holding the
    /// wheel's horizontal motion against the impulse, did `work`.
    pub fn wheel_lands(&mut self, lost: f64, work: f64) {
        self.impact += lost;
        self.moving.2 += work;
    }

    /// The run goes on at t from y, where a wheel's law changed (it lifted off or landed):
    /// the powers booked from here are those after the change.
    pub fn restart(&mut self, phase: &Phase, t: f64, y: &[f64]) {
        self.mid = None;
        self.mean_damping = None;
        self.moving = (t, Self::moving_power(phase, t, y), self.moving.2);
        self.damped = (t, Self::damping_power(phase, t, y), self.damped.2);
        self.end_power = None;
    }

    /// A disk bounces off the beam at t: the impact took `lost` of the kinetic energy, the
    /// train's moving masses did `work` on the beam through it, and the disk, which `carried`
    /// its energy into the air, flies off again with `disk` (kinetic, potential), which the
    /// budget holds constant while it flies.
    pub fn disk_bounces(&mut self, lost: f64, work: f64, carried: (f64, f64), disk: (f64, f64)) {
        self.left_with = (
            self.left_with.0 - carried.0 + disk.0,
            self.left_with.1 - carried.1 + disk.1,
        );
        self.impact += lost;
        self.moving.2 += work;
    }
}
