//! The beam while the disk flies over it: the beam integrated alone, watched for the disk
//! touching it again (or passing beyond an end), and the flying disk as the outputs see it.
//! The disk's flight is the closed form of `rolling/flight.rs`; its gap to the beam's
//! averaged track is `coupling/landing.rs`.

use std::borrow::Cow;
use std::cell::Cell;
use std::ops::Range;

use crate::beam::dynamics::LoadedBeam;
use crate::coupling::DiskOnBeam;
use crate::disk::flight::Flight;
use crate::disk::DiskObservation;
use crate::linalg::Sparse;
use crate::ode::second_order::{SecondOrderProblem, Structure};
use crate::ode::EventSpec;

/// The disk in the air over the beam.
#[derive(Clone)]
pub(super) struct FlyingDisk<'a> {
    pub coupled: &'a DiskOnBeam<'a>,
    pub flight: Flight,
    /// The last nearest point, where the next search starts.
    pub s: Cell<f64>,
}

impl FlyingDisk<'_> {
    /// The disk at t over the beam displaced `q` (the model's unknowns), and its gap.
    pub fn observe(&self, t: f64, q: &[f64]) -> (DiskObservation, f64) {
        let c = self.flight.centre(t);
        let v = self.flight.velocity(t);
        let near = self.coupled.gap(q, c, self.s.get());
        self.s.set(near.s);
        let disk = self.coupled.spec().disk;
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
            potential: disk.mass * self.coupled.spec().gravity * c[1],
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
        let a = self.disk.coupled.spec().disk.radius;
        match EVENTS[index].reason {
            FlightEvent::Lands => {
                let near = self
                    .disk
                    .coupled
                    .gap(q, self.disk.flight.centre(t), self.disk.s.get());
                self.disk.s.set(near.s);
                near.gap + CONTACT * a
            }
            FlightEvent::PassesEnd => {
                let beam = self.disk.coupled.beam();
                let c = self.disk.flight.centre(t);
                let origin = beam.spec.from;
                let x = beam.to_local([c[0] - origin[0], c[1] - origin[1]])[0];
                x.min(beam.length - x)
            }
        }
    }
}
