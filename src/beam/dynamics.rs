//! The loaded beam as a structural problem M q'' = F_ext(t) − F_int(q) for the integrators.
//! Loads switch on and off at their `from`/`until` times: those are breakpoints, and within
//! each stretch between them the set of active loads is fixed (the integrator names the
//! stretch), so no stage ever sees a load on the wrong side of its jump.

use std::borrow::Cow;
use std::cell::{Cell, RefCell};

use super::load::PointLoad;
use super::Beam;
use crate::linalg::Sparse;
use crate::ode::second_order::{SecondOrderProblem, Structure};
use crate::ode::NoEvent;

pub struct LoadedBeam<'a> {
    pub beam: &'a Beam,
    pub loads: &'a [PointLoad],
    /// Midpoint of the current stretch between breakpoints; NaN outside a run.
    segment: Cell<f64>,
    /// Internal forces, kept so that each force evaluation does not allocate.
    scratch: RefCell<Vec<f64>>,
}

impl<'a> LoadedBeam<'a> {
    pub fn new(beam: &'a Beam, loads: &'a [PointLoad]) -> Self {
        LoadedBeam {
            beam,
            loads,
            segment: Cell::new(f64::NAN),
            scratch: RefCell::new(vec![0.0; beam.dim()]),
        }
    }

    /// The loads acting at time t (within the current stretch, if one is set).
    pub fn active(&self, t: f64) -> impl Iterator<Item = &PointLoad> {
        let when = if self.segment.get().is_nan() {
            t
        } else {
            self.segment.get()
        };
        self.loads.iter().filter(move |l| l.active(when))
    }

    /// F_ext at time t.
    pub fn external(&self, t: f64, f: &mut [f64]) {
        f.fill(0.0);
        for l in self.active(t) {
            self.beam.add_point_load(l.x, l.force, l.mz, f);
        }
    }
}

impl Structure for LoadedBeam<'_> {
    fn dim(&self) -> usize {
        self.beam.dim()
    }
    fn mass(&self, _t: f64, _q: &[f64]) -> Cow<'_, Sparse> {
        Cow::Borrowed(self.beam.mass())
    }
    fn force(&self, t: f64, q: &[f64], _v: &[f64], f: &mut [f64]) {
        self.external(t, f);
        let mut fi = self.scratch.borrow_mut();
        self.beam.internal_force(q, &mut fi);
        f.iter_mut().zip(fi.iter()).for_each(|(a, b)| *a -= b);
    }
    fn stiffness(&self, _t: f64, q: &[f64]) -> Sparse {
        self.beam.tangent(q)
    }
}

impl SecondOrderProblem for LoadedBeam<'_> {
    type Event = NoEvent;
    fn breakpoints(&self) -> Vec<f64> {
        self.loads
            .iter()
            .flat_map(|l| [l.from, l.until])
            .filter(|t| t.is_finite())
            .collect()
    }
    fn enter_segment(&self, start: f64, end: f64) {
        self.segment.set(0.5 * (start + end));
    }
}
