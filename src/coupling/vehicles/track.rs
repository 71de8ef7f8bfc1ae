//! The wheels at one instant: where each is on the deck, the track under it (the deck's
//! patch-averaged axis through the model's unknowns, the profile, and on a modal beam the
//! static correction of the modes left out), and its rates as the wheel travels.

use std::rc::Rc;

use super::disk_wheel::DiskContact;
use super::{Row, VehiclesOnBeam};
use crate::beam::PastFreeEnd;
use crate::vehicle::Wheel;

/// The k-th derivative along the axis of w under a patch, as a row over the mesh's unknowns.
fn mesh_row(basis: &[crate::beam::NodeBasis], k: usize) -> Row {
    basis
        .iter()
        .filter_map(|nb| nb.w.map(|i| (i, nb.d[k])))
        .collect()
}

/// One wheel at one instant.
pub struct Contact {
    pub vehicle: usize,
    pub axle: usize,
    /// Its index among all the vehicles' wheels.
    pub wheel: usize,
    /// Where it is on the deck (m), its speed and acceleration.
    pub x: f64,
    pub speed: f64,
    pub accel: f64,
    /// gᵀ, g'ᵀ and g''ᵀ over the model's beam unknowns; empty off the deck.
    pub rows: [Row; 3],
    /// r, r', r'' of the profile under it.
    pub r: [f64; 3],
    /// On a modal beam, the static response of the modes left out to the point wheels' static
    /// loads, read under this one, and its first two rates in time (the second only where an
    /// unsprung mass feels it): the wheel rides on it as on a profile (zero on the mesh, and
    /// for disk wheels).
    pub settled: [f64; 3],
    /// A disk wheel's contact: how fast its centre rises per metre it travels, ∂H/∂X, with
    /// H(X) = max over the contact x of the track there plus √(a² − (x − X)²), and the part of
    /// its centre's rise not in gᵀq (the profile and the disk's shape at the contact, less a).
    pub disk: Option<DiskContact>,
}

/// The track under a wheel: d, ḋ and d̈ less gᵀq̈ (which the mass matrix carries).
pub(super) struct Track {
    pub(super) d: f64,
    pub(super) rate: f64,
    pub(super) convective: f64,
}

impl VehiclesOnBeam<'_> {
    /// Every wheel at t, the beam at q (where a disk wheel touches depends on its shape).
    pub fn contacts(&self, t: f64, q: &[f64]) -> Rc<Vec<Contact>> {
        let stretch = [self.segment.get()];
        let shape: &[f64] = if self.disks() { q } else { &[] };
        self.contacts_at
            .at(t, &[&stretch, shape], || self.contacts_now(t, q))
    }

    fn disks(&self) -> bool {
        self.vehicles
            .iter()
            .any(|v| matches!(v.wheel, Wheel::Disk { .. }))
    }

    fn contacts_now(&self, t: f64, q: &[f64]) -> Vec<Contact> {
        let mesh = if self.disks() {
            self.loaded.to_mesh(q).into_owned()
        } else {
            Vec::new()
        };
        let beam = self.loaded.beam;
        let (b, length) = (self.patch, beam.length);
        let side_t = if self.segment.get().is_nan() {
            t
        } else {
            self.segment.get()
        };
        let mut out = Vec::new();
        let mut on_mesh = Vec::new();
        for (i, v) in self.vehicles.iter().enumerate() {
            let (x_first, speed, accel) = v.travel(t);
            let x_side = v.travel(side_t).0;
            for (a, axle) in v.axles.iter().enumerate() {
                let centre = x_first - axle.x;
                let side = x_side - axle.x + if speed >= 0.0 { 1e-9 } else { -1e-9 };
                let (x, disk) = match v.wheel {
                    Wheel::Point => (centre, None),
                    Wheel::Disk { radius } => {
                        let toward = if side >= centre { 1.0 } else { -1.0 };
                        let resting = self.resting.borrow()[out.len()];
                        let (x, d) = self.disk_contact(centre, toward, radius, &mesh, resting);
                        (x, Some(d))
                    }
                };
                let basis = if x > -b && x < length + b {
                    beam.patch_basis_at(x, b, PastFreeEnd::Slab)
                } else {
                    Vec::new()
                };
                let rows = std::array::from_fn(|k| self.model_row(&basis, k));
                if self.loaded.modal.is_some() {
                    on_mesh.push(std::array::from_fn(|k| mesh_row(&basis, k)));
                }
                out.push(Contact {
                    vehicle: i,
                    axle: a,
                    wheel: out.len(),
                    x,
                    speed,
                    accel,
                    rows,
                    r: self.profile.at(x, side),
                    settled: [0.0; 3],
                    disk,
                });
            }
        }
        if !self.disks() && self.loaded.modal.is_some() {
            self.settle(&mut out, &on_mesh);
        }
        out
    }

    /// Fill each point wheel's `settled` on a modal beam. What the modes left out hold under a
    /// wheel is, as in the outputs (`ModalBasis::add_static_correction`), their static
    /// response R F to the loads; the wheels' forces are taken at their static loads P_b, so
    /// that the track stays a given function of time and the springs see no loop through it
    /// (what the bodies' and wheels' inertia add to R_b stays on the modes kept alone). With
    /// u⁽ᵏ⁾ = R Σ_b (−P_b) dᵏ/dtᵏ g_b, the wheel at X_a reads gₐᵀu⁽⁰⁾, its rate
    /// Vₐ gₐ'ᵀu⁽⁰⁾ + gₐᵀu⁽¹⁾ and its acceleration
    /// Vₐ² gₐ''ᵀu⁽⁰⁾ + Aₐ gₐ'ᵀu⁽⁰⁾ + 2 Vₐ gₐ'ᵀu⁽¹⁾ + gₐᵀu⁽²⁾.
    fn settle(&self, contacts: &mut [Contact], on_mesh: &[[Row; 3]]) {
        let Some(modal) = self.loaded.modal else {
            return;
        };
        let n = self.loaded.beam.dim();
        // Per unknown a wheel loads, the force there and its first two rates, summed over
        // the wheels (several wheels' patches share unknowns); the wheels read u at those
        // unknowns alone.
        let mut sums = vec![[0.0; 3]; n];
        let mut seen = vec![false; n];
        let mut under: Vec<usize> = Vec::new();
        for (c, rows) in contacts.iter().zip(on_mesh) {
            let p = -self.vehicles[c.vehicle].static_loads[c.axle];
            let (v, a) = (c.speed, c.accel);
            for (k, row) in rows.iter().enumerate() {
                for &(i, g) in row {
                    if !std::mem::replace(&mut seen[i], true) {
                        under.push(i);
                    }
                    let f = &mut sums[i];
                    match k {
                        0 => f[0] += p * g,
                        1 => (f[1], f[2]) = (f[1] + p * v * g, f[2] + p * a * g),
                        _ => f[2] += p * v * v * g,
                    }
                }
            }
        }
        let loads: Vec<(usize, [f64; 3])> = under.iter().map(|&i| (i, sums[i])).collect();
        let mut u = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        match modal.static_corrections_at(&loads, &under) {
            Some(values) => {
                for (&i, v) in under.iter().zip(values) {
                    (0..3).for_each(|k| u[k][i] = v[k]);
                }
            }
            None => {
                for (k, u) in u.iter_mut().enumerate() {
                    let mut dense = vec![0.0; n];
                    loads.iter().for_each(|&(i, f)| dense[i] += f[k]);
                    modal.add_static_correction(&dense, u);
                }
            }
        }
        let [u0, u1, u2] = u;
        // The track's acceleration enters only through an unsprung mass's inertia.
        let u2 = self.unsprung().then_some(u2);
        let read = |row: &Row, u: &[f64]| -> f64 { row.iter().map(|&(i, g)| g * u[i]).sum() };
        for (c, rows) in contacts.iter_mut().zip(on_mesh) {
            let (v, a) = (c.speed, c.accel);
            let slope0 = read(&rows[1], &u0);
            c.settled = [
                read(&rows[0], &u0),
                v * slope0 + read(&rows[0], &u1),
                u2.as_ref().map_or(0.0, |u2| {
                    v * v * read(&rows[2], &u0)
                        + a * slope0
                        + 2.0 * v * read(&rows[1], &u1)
                        + read(&rows[0], u2)
                }),
            ];
        }
    }

    /// The k-th derivative along the axis of w under a patch, as a row over the model's
    /// beam unknowns (on a modal beam, Φᵀ of the mesh's row).
    fn model_row(&self, basis: &[crate::beam::NodeBasis], k: usize) -> Row {
        match self.loaded.modal {
            None => mesh_row(basis, k),
            Some(_) if basis.is_empty() => Vec::new(),
            Some(m) => {
                let mut dense = vec![0.0; m.dim()];
                for (i, g) in mesh_row(basis, k) {
                    m.add_row(i, g, &mut dense);
                }
                dense.into_iter().enumerate().collect()
            }
        }
    }

    pub(super) fn track(&self, c: &Contact, q: &[f64], v: &[f64]) -> Track {
        let dot = |row: &Row, y: &[f64]| -> f64 { row.iter().map(|&(i, g)| g * y[i]).sum() };
        if let (Some(d), Wheel::Disk { radius }) = (c.disk, self.vehicles[c.vehicle].wheel) {
            // H = f(x*) + √(a² − (x* − X)²) at the contact x*, where H' = 0. By that, Ḣ =
            // gᵀq̇ + V ∂H/∂X, and Ḣ's rate adds the contact's travel ẋ* along g' and the
            // change of ∂H/∂X = u/√(1 − u²), u = (x* − X)/a, by (ẋ* − V)/(a (1 − u²)^{3/2}).
            // Differentiating H' = 0 gives ẋ* (f'' − κ) = −g'ᵀq̇ − V κ, κ = 1/(a (1 − u²)^{3/2});
            // a disk pivoting on a corner holds its contact there (ẋ* = 0).
            let (vel, acc) = (c.speed, c.accel);
            let kappa = (1.0 + d.rise * d.rise).powf(1.5) / radius;
            let turning = dot(&c.rows[1], v);
            let travel = if d.pivot {
                0.0
            } else {
                let bend = dot(&c.rows[2], q) + c.r[2];
                (turning + vel * kappa) / (kappa - bend)
            };
            return Track {
                d: dot(&c.rows[0], q) + d.rest,
                rate: dot(&c.rows[0], v) + vel * d.rise,
                convective: travel * turning + acc * d.rise + vel * kappa * (travel - vel),
            };
        }
        let (slope, vs) = (dot(&c.rows[1], q), dot(&c.rows[1], v));
        let (vel, a) = (c.speed, c.accel);
        Track {
            d: dot(&c.rows[0], q) + c.r[0] + c.settled[0],
            rate: dot(&c.rows[0], v) + vel * (slope + c.r[1]) + c.settled[1],
            convective: 2.0 * vel * vs
                + vel * vel * dot(&c.rows[2], q)
                + a * slope
                + vel * vel * c.r[2]
                + a * c.r[1]
                + c.settled[2],
        }
    }
}
