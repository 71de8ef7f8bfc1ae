//! A disk wheel with an unsprung mass off the track: its axle's height an unknown of its own
//! while it flies, its gap watched, and its plastic landing.

use super::VehiclesOnBeam;
use crate::ode::second_order::Structure;
use crate::vehicle::Wheel;

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
        self.forces_at.forget();
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
        let m = self.vehicles[c.vehicle].axles[c.axle].mass;
        let still = vec![0.0; self.n];
        let convective = self.track(c, &z[..self.n], &still).rate;
        let deck = |v: &[f64]| -> f64 { c.rows[0].iter().map(|&(i, g)| g * v[i]).sum() };
        let (fall, approach) = (zd[h], zd[h] - deck(zd) - convective);
        c.rows[0]
            .iter()
            .for_each(|&(i, g)| p[i] += g * m * (fall - convective));
        self.airborne.borrow_mut()[k] = false;
        self.forces_at.forget();
        p[h] = 0.0;
        self.solve_mass(t, z, &mut p);
        zd.copy_from_slice(&p);
        let impulse = m * (deck(zd) + convective - fall);
        (z[h], zd[h]) = (0.0, 0.0);
        let lost = -0.5 * impulse * approach;
        (lost, energy(y) - before + lost)
    }
}
