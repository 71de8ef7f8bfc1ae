//! A disk wheel with an unsprung mass off the track: its axle's height an unknown of its own
//! while it flies, its gap watched, and its plastic landing.

use super::disk_wheel::Resting;
use super::VehiclesOnBeam;
use crate::ode::second_order::Structure;
use crate::vehicle::Wheel;

/// How far, in radii, the crest ahead rises above the one a disk wheel rests on before the
/// wheel meets it: far below any accuracy, far above the round-off of the two heights.
const CREST_TIE: f64 = 1e-12;

impl VehiclesOnBeam<'_> {
    /// How many wheels the vehicles have.
    pub fn wheels(&self) -> usize {
        self.hops.len()
    }

    /// Whether wheel k can fly: a disk wheel with an unsprung mass (a massless axle has no
    /// motion of its own to fly with).
    pub fn can_fly(&self, k: usize) -> bool {
        self.hops[k].is_some()
    }

    /// The unknown of wheel k's axle height while it flies; `None` on the track.
    pub(super) fn flying(&self, k: usize) -> Option<usize> {
        self.hops[k].filter(|_| self.airborne.borrow()[k])
    }

    /// Whether wheel k flies now.
    pub fn flies(&self, k: usize) -> bool {
        self.flying(k).is_some()
    }

    /// Wheel k's gap to the track in radii (its axle at z[h] above where the disk would rest
    /// at t), less a billionth: the landing is watched for from just below the lift-off's
    /// zero, so that round-off at the lift-off does not land the wheel again at once.
    pub(super) fn gap(&self, k: usize, t: f64, z: &[f64], h: usize) -> f64 {
        let c = &self.contacts(t, &z[..self.n])[k];
        let Wheel::Disk { radius } = self.vehicles[c.vehicle].wheel else {
            return 1.0;
        };
        let still = vec![0.0; self.n];
        let rest = self.track(c, &z[..self.n], &still).d;
        (z[h] - rest) / radius + 1e-9
    }

    /// Wheel k lifts off at t from y = (z, ż): its axle moves on as the track moved it.
    pub fn lift(&self, k: usize, t: f64, y: &mut [f64]) {
        let Some(h) = self.hops[k] else { return };
        let (z, zd) = y.split_at_mut(self.dim);
        let c = &self.contacts(t, &z[..self.n])[k];
        let track = self.track(c, &z[..self.n], &zd[..self.n]);
        (z[h], zd[h]) = (track.d, track.rate);
        self.airborne.borrow_mut()[k] = true;
        self.resting.borrow_mut()[k] = None;
        self.forces_at.forget();
        self.contacts_at.forget();
    }

    /// The wheel of a crest event ([`super::bridging`]'s), if `index` is one.
    pub fn crest_event(&self, index: usize) -> Option<usize> {
        index.checked_sub(self.wheels())
    }

    /// Wheel k's disk at t above the crest ahead that comes level with the one it rests on,
    /// in radii, and that crest (`crest_margin`); 1 in the air. −1, with the crest the disk
    /// has come onto, where the crest it rested on has merged into a hollow
    /// (`DiskContact::crest_gone`): another rose above it before, so between then and now
    /// the value has crossed zero, which the driver then finds.
    fn crest_ahead_of(&self, k: usize, t: f64, q: &[f64]) -> (f64, Option<f64>) {
        if self.flies(k) {
            return (1.0, None);
        }
        let c = &self.contacts(t, q)[k];
        let v = &self.vehicles[c.vehicle];
        let (Wheel::Disk { radius }, Some(disk)) = (v.wheel, c.disk) else {
            return (1.0, None);
        };
        if disk.crest_gone {
            return (-1.0, Some(c.x));
        }
        let centre = v.travel(t).0 - v.axles[c.axle].x;
        self.crest_margin(centre, radius, &self.loaded.to_mesh(q), c.x)
    }

    /// Wheel k's disk at t rests on the crest its contact is on.
    fn resting_at(&self, k: usize, t: f64, q: &[f64], crest: f64) -> Resting {
        let c = &self.contacts(t, q)[k];
        let v = &self.vehicles[c.vehicle];
        Resting {
            centre: v.travel(t).0 - v.axles[c.axle].x,
            crest,
        }
    }

    /// The run has reached t (its start, or an accepted step's end): each wheel that bridges
    /// the road's hollows, on the track, remembers the crest it rests on, which the next
    /// step's contacts follow from (`disk_contact`). Only there: a crest remembered from a
    /// trial, or from a look ahead inside a step, would leave the contacts the step's stages
    /// saw (a wheel then read the crest its disk had not yet reached, 1.9·10⁻⁵ m below the one
    /// it rested on).
    pub fn remember_crests(&self, t: f64, q: &[f64]) {
        let wheels: Vec<usize> = (0..self.wheels())
            .filter(|&k| self.bridges(k) && !self.flies(k))
            .collect();
        if wheels.is_empty() {
            return;
        }
        let crests: Vec<Resting> = {
            let contacts = self.contacts(t, &q[..self.n]);
            wheels
                .iter()
                .map(|&k| self.resting_at(k, t, &q[..self.n], contacts[k].x))
                .collect()
        };
        let mut resting = self.resting.borrow_mut();
        for (&k, crest) in wheels.iter().zip(crests) {
            resting[k] = Some(crest);
        }
        drop(resting);
        self.forces_at.forget();
        self.contacts_at.forget();
    }

    /// Whether wheel k's disk bridges the road's hollows (it has a crest event).
    fn bridges(&self, k: usize) -> bool {
        self.events
            .iter()
            .any(|e| self.crest_event(e.reason) == Some(k))
    }

    /// The crest event's value (`crest_ahead_of`), crossing zero where the crest ahead has
    /// risen [`CREST_TIE`] radii above the one the disk rests on: at the crossing the two lie
    /// level to round-off, and without that margin the crest met could read lower at once and
    /// be left again.
    pub(super) fn crest_ahead(&self, k: usize, t: f64, z: &[f64]) -> f64 {
        self.crest_ahead_of(k, t, &z[..self.n]).0 + CREST_TIE
    }

    /// Wheel k's disk meets the crest ahead at t: it leaves the crest it rested on for that
    /// one, and an axle with a mass lands on it plastically ([`Self::land`], from the motion
    /// it had on the crest left). Returns (what the impact took, the drive's work).
    pub fn meet_crest(&self, k: usize, t: f64, y: &mut [f64]) -> (f64, f64) {
        let (_, ahead) = self.crest_ahead_of(k, t, &y[..self.n]);
        let lands = self.can_fly(k);
        if lands {
            self.lift(k, t, y);
        }
        let ahead = ahead.map(|x| self.resting_at(k, t, &y[..self.n], x));
        self.resting.borrow_mut()[k] = ahead;
        self.forces_at.forget();
        self.contacts_at.forget();
        if lands {
            return self.land(k, t, y);
        }
        (0.0, 0.0)
    }

    /// Wheel k lands at t on y = (z, ż): a plastic impact. The generalized momentum the
    /// wheel's contact holds is kept: with g the track's row under the wheel and c its
    /// convective rate, M⁺ ż⁺ = M⁻ ż⁻ + g m (ḣ − c), M⁺ the mass with the wheel on the track;
    /// the axle's unknown is at rest again. The impulse Λ = m (ḣ⁺ − ḣ⁻) stops the wheel's
    /// approach w⁻ = ḣ − gᵀq̇ − c at a rate linear in it, so it takes −Λ w⁻ / 2; the rest of
    /// the change of energy is the drive's work against the impulse's horizontal part.
    /// Returns (what the impact took, the drive's work).
    pub fn land(&self, k: usize, t: f64, y: &mut [f64]) -> (f64, f64) {
        let Some(h) = self.flying(k) else {
            return (0.0, 0.0);
        };
        let energy = |y: &[f64]| -> f64 {
            let (z, zd) = y.split_at(self.dim);
            let (kinetic, spring, potential) = self.energies(t, z, zd);
            kinetic + spring + potential + self.loaded.energies(&z[..self.n], &zd[..self.n]).0
        };
        let before = energy(y);
        let (z, zd) = y.split_at_mut(self.dim);
        let mut p = vec![0.0; self.dim];
        self.mass_mul(t, z, zd, &mut p);
        let c = &self.contacts(t, &z[..self.n])[k];
        let touched = c.x;
        let m = self.vehicles[c.vehicle].axles[c.axle].mass;
        let still = vec![0.0; self.n];
        let convective = self.track(c, &z[..self.n], &still).rate;
        let deck = |v: &[f64]| -> f64 { c.rows[0].iter().map(|&(i, g)| g * v[i]).sum() };
        let (fall, approach) = (zd[h], zd[h] - deck(zd) - convective);
        c.rows[0]
            .iter()
            .for_each(|&(i, g)| p[i] += g * m * (fall - convective));
        self.airborne.borrow_mut()[k] = false;
        // A disk that bridges the hollows holds to the crest it landed on from here, as from
        // every accepted step: searched afresh at each stage of the next step, its contact
        // could pass to a crest rising ahead without the impact the crest event finds, and
        // the energy of that jump would be booked nowhere.
        if self.bridges(k) && self.resting.borrow()[k].is_none() {
            self.resting.borrow_mut()[k] = Some(self.resting_at(k, t, &z[..self.n], touched));
        }
        self.forces_at.forget();
        self.contacts_at.forget();
        p[h] = 0.0;
        self.solve_mass(t, z, &mut p);
        zd.copy_from_slice(&p);
        let impulse = m * (deck(zd) + convective - fall);
        (z[h], zd[h]) = (0.0, 0.0);
        let lost = -0.5 * impulse * approach;
        (lost, energy(y) - before + lost)
    }
}
