//! How the disks on the beam enter its equations of motion as the integrators see them: the
//! unknowns (the beam's, then each rolling disk's contact coordinate), the mass with the
//! riders' inertia as a low-rank part, the force, the beam's stiffness and damping bordered by
//! the contact coordinates, the error norm's groups, the step bound and every disk's events.

use std::borrow::Cow;
use std::ops::Range;

use super::contact::dot;
use super::{Coupling, DiskEvent, DiskOnBeam};
use crate::disk::FIT_MARGIN;
use crate::linalg::{self, Assembly, LowRank, Sparse};
use crate::ode::second_order::{SecondOrderProblem, Structure};
use crate::ode::EventSpec;

impl Structure for DiskOnBeam<'_> {
    fn dim(&self) -> usize {
        self.dim
    }

    fn mass(&self, t: f64, q: &[f64]) -> Cow<'_, Sparse> {
        Cow::Owned(self.mass_matrix(&self.inertia_at(t, q)))
    }

    fn mass_is_constant(&self) -> bool {
        false
    }

    /// The beam's mass, with a unit mass standing in on each contact coordinate that the
    /// low-rank part takes back out, plus the disks' inertia as seen by z.
    fn mass_split(&self, t: f64, q: &[f64]) -> Option<(&Sparse, LowRank)> {
        let added = (*self.inertia_at(t, q)).clone();
        Some((&self.base_mass, self.low_rank_mass(added)))
    }

    fn mass_mul(&self, t: f64, q: &[f64], a: &[f64], out: &mut [f64]) {
        linalg::mul(self.loaded.model_mass(), &a[..self.n], &mut out[..self.n]);
        out[self.n..].fill(0.0);
        for &(i, m) in self.beside.iter().flat_map(|b| &b.masses) {
            out[i] = m * a[i];
        }
        for (w, row) in self.inertia_at(t, q).iter() {
            let ga = w * dot(row, a);
            for &(i, gi) in row {
                out[i] += gi * ga;
            }
        }
    }

    fn force(&self, t: f64, q: &[f64], v: &[f64], f: &mut [f64]) {
        let force = self.force_row(t, q, v);
        self.force_from(t, q, v, &force, f);
    }

    fn stiffness(&self, t: f64, q: &[f64]) -> Sparse {
        let k = self.loaded.stiffness(t, &q[..self.n]);
        if self.dim() == self.n {
            return k;
        }
        let mut a = Assembly::new(self.dim());
        a.add_sparse(&k, 1.0, 0, 0);
        match &self.beside {
            // The springs couple the bodies to the beam under wheels that move along it.
            Some(b) => {
                b.vehicles.add_stiffness(t, q, &mut a);
                a.build()
            }
            None => self.stiffness_pattern.get_or_init(|| a.pattern()).build(&a),
        }
    }

    /// The beam's damping and the vehicles' dampers beside the disks; the contact
    /// coordinates are not damped.
    fn damping(&self) -> Option<Cow<'_, Sparse>> {
        if let Some(b) = &self.beside {
            let beam = self.loaded.damping();
            let dampers = b.vehicles.constant_terms().1;
            if beam.is_none() && dampers.is_none() {
                return None;
            }
            let mut a = Assembly::new(self.dim());
            if let Some(c) = beam {
                a.add_sparse(&c, 1.0, 0, 0);
            }
            if let Some(c) = dampers {
                a.add_sparse(c, 1.0, 0, 0);
            }
            b.vehicles.add_flying_dampers(&mut a);
            return Some(Cow::Owned(a.build()));
        }
        let c = self.loaded.damping()?;
        if self.dim() == self.n {
            return Some(c);
        }
        let mut a = Assembly::new(self.dim());
        a.add_sparse(&c, 1.0, 0, 0);
        Some(Cow::Owned(a.build()))
    }

    fn norm_weights(&self) -> Option<Vec<f64>> {
        let inertial = self
            .disks
            .iter()
            .any(|d| d.spec.coupling != Coupling::MovingForce);
        let mut w = if inertial {
            self.loaded.contact_norm_weights()?
        } else {
            self.loaded.norm_weights()?
        };
        w.resize(self.dim(), 1.0);
        Some(w)
    }

    fn norm_rows(&self) -> Option<crate::ode::ModeRows> {
        self.loaded.norm_rows()
    }

    fn norm_groups(&self) -> Vec<Range<usize>> {
        let vehicles = self.beside.as_ref().map(|b| b.vehicles.own_unknowns());
        let disks = self.n..vehicles.as_ref().map_or(self.dim(), |v| v.start);
        let mut g = vec![0..self.n];
        g.extend(
            [disks]
                .into_iter()
                .chain(vehicles)
                .filter(|r| !r.is_empty()),
        );
        g
    }
}

impl SecondOrderProblem for DiskOnBeam<'_> {
    type Event = DiskEvent;

    /// The averaged track changes over the patch half-width b and no faster, and a crest
    /// there shows in the contact force, not in the motion the error estimate measures: a
    /// step moves a rolling disk by at most b/2, so the contact-loss event sees every crest.
    /// A prescribed load crosses at most one element a step (`LoadedBeam::load_step_bound`).
    /// Beside vehicles, their bound too (`VehiclesOnBeam`'s).
    fn max_step(&self, t: f64, q: &[f64], v: &[f64]) -> f64 {
        let beside = match &self.beside {
            Some(b) => b.vehicles.max_step(t, q, v),
            None => self.loaded.load_step_bound(t),
        };
        self.on()
            .map(|(_, d)| match d.slot {
                Some(i) => 0.5 * d.spec.patch / v[i].abs(),
                None => self.beam().element_length() / d.spec.v0().abs(),
            })
            .fold(beside, f64::min)
    }

    fn breakpoints(&self) -> Vec<f64> {
        match &self.beside {
            Some(b) => b.vehicles.breakpoints(),
            None => self.loaded.breakpoints(),
        }
    }

    fn enter_segment(&self, start: f64, end: f64) {
        match &self.beside {
            Some(b) => b.vehicles.enter_segment(start, end),
            None => self.loaded.enter_segment(start, end),
        }
    }

    fn events(&self) -> &[EventSpec<DiskEvent>] {
        &self.events
    }

    fn event_pace(&self, t: f64, q: &[f64], v: &[f64]) -> f64 {
        self.beside
            .as_ref()
            .map_or(f64::INFINITY, |b| b.vehicles.event_pace(t, q, v))
    }

    fn accepted(&self, t: f64, q: &[f64], v: &[f64]) {
        if let Some(b) = &self.beside {
            b.vehicles.accepted(t, q, v);
        }
    }

    /// Disk k's events, each zero where it is met; a disk that has left meets none. The
    /// vehicles' beside them follow.
    fn event(&self, index: usize, t: f64, q: &[f64], v: &[f64]) -> f64 {
        if let DiskEvent::Wheel(wheel) = self.events[index].reason {
            let b = self
                .beside
                .as_ref()
                .expect("a wheel's event is of vehicles beside");
            return b.vehicles.event(wheel, t, q, v);
        }
        let (k, which) = self.event_of[index];
        let d = &self.disks[k];
        if d.gone.get() {
            return 1.0;
        }
        let s = q[d.slot.expect("events watch rolling disks")];
        let observed = || self.observe_all(t, q, v)[k].expect("on the beam");
        match which {
            0 => self.beam().length - s,
            1 => s,
            2 => observed().rn,
            3 => {
                let at = self.contact_of(d, t, q, v);
                1.0 - d.spec.disk.radius * at.psi_s.v / at.rp.v - FIT_MARGIN
            }
            _ => {
                let o = observed();
                d.spec.mu.unwrap_or(f64::INFINITY) * o.rn - o.rt.abs()
            }
        }
    }
}
