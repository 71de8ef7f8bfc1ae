//! The beam while a disk flies over it: the beam integrated alone, or with the other disks
//! rolling on it, watched for the disk touching it again (or passing beyond an end), and the
//! flying disk as the outputs see it.
//! The disk's flight is the closed form of `rolling/flight.rs`; its gap to the beam's
//! averaged track is `coupling/landing.rs`.

use std::borrow::Cow;
use std::cell::Cell;
use std::ops::Range;

use crate::beam::dynamics::LoadedBeam;
use crate::coupling::{DiskEvent, DiskOnBeam};
use crate::disk::flight::Flight;
use crate::disk::DiskObservation;
use crate::linalg::Sparse;
use crate::ode::second_order::{SecondOrderProblem, Structure};
use crate::ode::EventSpec;

/// The disk in the air over the beam.
#[derive(Clone)]
pub(super) struct FlyingDisk<'a> {
    pub coupled: &'a DiskOnBeam<'a>,
    /// Which of the disks it is.
    pub k: usize,
    pub flight: Flight,
    /// The last nearest point, where the next search starts.
    pub s: Cell<f64>,
}

impl FlyingDisk<'_> {
    /// The disk at t over the beam displaced `q` (the model's unknowns), and its gap.
    pub fn observe(&self, t: f64, q: &[f64]) -> (DiskObservation, f64) {
        let c = self.flight.centre(t);
        let v = self.flight.velocity(t);
        let near = self.coupled.gap(self.k, q, c, self.s.get());
        self.s.set(near.s);
        let disk = self.coupled.spec_of(self.k).disk;
        let omega = self.flight.omega;
        let observation = DiskObservation {
            s: near.s,
            x: c[0],
            y: c[1],
            vx: v[0],
            vy: v[1],
            omega,
            phi: 0.0,
            rt: 0.0,
            rn: 0.0,
            kinetic: 0.5 * disk.mass * (v[0] * v[0] + v[1] * v[1])
                + 0.5 * disk.inertia() * omega * omega,
            potential: disk.mass * self.coupled.spec_of(self.k).gravity * c[1],
        };
        (observation, near.gap.max(0.0))
    }
}

/// How a flight over the beam ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum FlightEvent {
    /// The gap closed: the disk touches the beam again.
    Lands,
    /// The centre passed beyond an end of the beam.
    PassesEnd,
}

/// The gap is watched for falling below minus this share of the radius: it starts at zero at
/// the lift-off, where a watch for zero itself would fire at once, and a penetration this deep
/// is round-off of the nearest-point search.
const CONTACT: f64 = 1e-10;

const EVENTS: [EventSpec<FlightEvent>; 2] = [
    EventSpec {
        reason: FlightEvent::Lands,
        terminal: true,
    },
    EventSpec {
        reason: FlightEvent::PassesEnd,
        terminal: true,
    },
];

/// The loaded beam alone, with the flying disk's landing as its events.
pub(super) struct BeneathFlight<'a> {
    pub loaded: &'a LoadedBeam<'a>,
    pub disk: FlyingDisk<'a>,
}

impl Structure for BeneathFlight<'_> {
    fn dim(&self) -> usize {
        self.loaded.dim()
    }
    fn mass(&self, t: f64, q: &[f64]) -> Cow<'_, Sparse> {
        self.loaded.mass(t, q)
    }
    fn force(&self, t: f64, q: &[f64], v: &[f64], f: &mut [f64]) {
        self.loaded.force(t, q, v, f)
    }
    fn stiffness(&self, t: f64, q: &[f64]) -> Sparse {
        self.loaded.stiffness(t, q)
    }
    fn damping(&self) -> Option<Cow<'_, Sparse>> {
        self.loaded.damping()
    }
    fn norm_groups(&self) -> Vec<Range<usize>> {
        self.loaded.norm_groups()
    }
    fn norm_weights(&self) -> Option<Vec<f64>> {
        self.loaded.norm_weights()
    }
    fn norm_rows(&self) -> Option<crate::ode::ModeRows> {
        self.loaded.norm_rows()
    }
}

impl SecondOrderProblem for BeneathFlight<'_> {
    type Event = FlightEvent;
    fn max_step(&self, t: f64, _q: &[f64], _v: &[f64]) -> f64 {
        self.loaded.load_step_bound(t)
    }
    fn breakpoints(&self) -> Vec<f64> {
        self.loaded.breakpoints()
    }
    fn enter_segment(&self, start: f64, end: f64) {
        self.loaded.enter_segment(start, end)
    }
    fn events(&self) -> &[EventSpec<FlightEvent>] {
        &EVENTS
    }
    fn event(&self, index: usize, t: f64, q: &[f64], _v: &[f64]) -> f64 {
        self.disk.event(EVENTS[index].reason, t, q)
    }
}

impl FlyingDisk<'_> {
    /// The flight's event `which` at t over the beam displaced `q` (the beam's unknowns of
    /// the model), zero where it is met.
    fn event(&self, which: FlightEvent, t: f64, q: &[f64]) -> f64 {
        let c = self.coupled;
        match which {
            FlightEvent::Lands => {
                let near = c.gap(self.k, q, self.flight.centre(t), self.s.get());
                self.s.set(near.s);
                near.gap + CONTACT * c.spec_of(self.k).disk.radius
            }
            FlightEvent::PassesEnd => {
                let beam = c.beam();
                let centre = self.flight.centre(t);
                let origin = beam.spec.from;
                let x = beam.to_local([centre[0] - origin[0], centre[1] - origin[1]])[0];
                x.min(beam.length - x)
            }
        }
    }
}

/// What stops the integration while a disk flies beside others rolling on the beam: one of
/// theirs, or the flight's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum BesideEvent {
    Rolling(DiskEvent),
    Flight(FlightEvent),
}

/// The disks rolling on the beam (the flying one left out of their equations) with the flying
/// disk's landing and passing an end as further events.
pub(super) struct BesideFlight<'a> {
    pub coupled: &'a DiskOnBeam<'a>,
    pub disk: FlyingDisk<'a>,
    events: Vec<EventSpec<BesideEvent>>,
}

impl<'a> BesideFlight<'a> {
    pub fn new(coupled: &'a DiskOnBeam<'a>, disk: FlyingDisk<'a>) -> Self {
        let rolling = coupled.events().iter().map(|e| EventSpec {
            reason: BesideEvent::Rolling(e.reason),
            terminal: e.terminal,
        });
        let flight = EVENTS.iter().map(|e| EventSpec {
            reason: BesideEvent::Flight(e.reason),
            terminal: e.terminal,
        });
        BesideFlight {
            coupled,
            disk,
            events: rolling.chain(flight).collect(),
        }
    }
}

impl Structure for BesideFlight<'_> {
    fn dim(&self) -> usize {
        self.coupled.dim()
    }
    fn mass(&self, t: f64, q: &[f64]) -> Cow<'_, Sparse> {
        self.coupled.mass(t, q)
    }
    fn mass_is_constant(&self) -> bool {
        self.coupled.mass_is_constant()
    }
    fn mass_split(&self, t: f64, q: &[f64]) -> Option<(&Sparse, crate::linalg::LowRank)> {
        self.coupled.mass_split(t, q)
    }
    fn mass_mul(&self, t: f64, q: &[f64], a: &[f64], out: &mut [f64]) {
        self.coupled.mass_mul(t, q, a, out)
    }
    fn force(&self, t: f64, q: &[f64], v: &[f64], f: &mut [f64]) {
        self.coupled.force(t, q, v, f)
    }
    fn stiffness(&self, t: f64, q: &[f64]) -> Sparse {
        self.coupled.stiffness(t, q)
    }
    fn damping(&self) -> Option<Cow<'_, Sparse>> {
        self.coupled.damping()
    }
    fn norm_groups(&self) -> Vec<Range<usize>> {
        self.coupled.norm_groups()
    }
    fn norm_weights(&self) -> Option<Vec<f64>> {
        self.coupled.norm_weights()
    }
    fn norm_rows(&self) -> Option<crate::ode::ModeRows> {
        self.coupled.norm_rows()
    }
}

impl SecondOrderProblem for BesideFlight<'_> {
    type Event = BesideEvent;
    fn max_step(&self, t: f64, q: &[f64], v: &[f64]) -> f64 {
        self.coupled.max_step(t, q, v)
    }
    fn breakpoints(&self) -> Vec<f64> {
        self.coupled.breakpoints()
    }
    fn enter_segment(&self, start: f64, end: f64) {
        self.coupled.enter_segment(start, end)
    }
    fn events(&self) -> &[EventSpec<BesideEvent>] {
        &self.events
    }
    fn event(&self, index: usize, t: f64, q: &[f64], v: &[f64]) -> f64 {
        match self.events[index].reason {
            BesideEvent::Rolling(_) => self.coupled.event(index, t, q, v),
            BesideEvent::Flight(which) => {
                self.disk.event(which, t, &q[..self.coupled.loaded.dim()])
            }
        }
    }
}
