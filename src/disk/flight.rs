//! The disk off the track, whatever the track: a free rigid body under gravity, in closed
//! form, and the impact on a rigid track that ends its flight. Where the flight ends depends
//! on the track: `rolling::flight` on a rigid curve, `coupling::landing` on a beam.
//!
//! **Flight.** With no contact force the centre moves on the parabola
//! x(t) = x₀ + vₓ τ, y(t) = y₀ + v_y τ − g τ²/2 (τ = t − t₀) and the spin Ω stays constant.
//! Nothing is integrated, so a flight costs no steps and cannot lose energy.
//!
//! **Landing.** The contact impulse J = Jₙ n + Jₜ t acts at the contact point P = c − a n.
//! Gravity is finite and does no impulse, so the angular momentum about P is conserved:
//! L = m (c − P) × v + C Ω = −m a vₜ + C Ω. The contact sticks (no slip), so after the impact
//! the disk rolls tangentially, vₜ' + a Ω' = 0, which with L' = L gives
//!   vₜ' = (m a vₜ − C Ω) / (m a + C / a),   Ω' = −vₜ' / a,
//! for a uniform disk (C = m a²/2) vₜ' = (2/3)(vₜ − aΩ/2). Normally the relative speed is
//! reversed and scaled by the restitution e: vₙ' = −e vₙ. The kinetic energy lost is what the
//! impact takes; it is booked so the energy balance still closes.

use super::Disk;

/// A free flight, from its start.
#[derive(Clone, Copy, Debug)]
pub struct Flight {
    pub t0: f64,
    pub centre: [f64; 2],
    pub velocity: [f64; 2],
    pub omega: f64,
    pub gravity: f64,
}

impl Flight {
    pub fn centre(&self, t: f64) -> [f64; 2] {
        let tau = t - self.t0;
        [
            self.centre[0] + self.velocity[0] * tau,
            self.centre[1] + self.velocity[1] * tau - 0.5 * self.gravity * tau * tau,
        ]
    }

    pub fn velocity(&self, t: f64) -> [f64; 2] {
        [
            self.velocity[0],
            self.velocity[1] - self.gravity * (t - self.t0),
        ]
    }
}

/// What an impact does to the disk.
#[derive(Clone, Copy, Debug)]
pub struct Impact {
    pub velocity: [f64; 2],
    pub omega: f64,
    /// Normal and tangential impulse on the disk (N s).
    pub jn: f64,
    pub jt: f64,
    /// Kinetic energy the impact took (J).
    pub energy_lost: f64,
    /// Normal speed after the impact (m/s, away from the track).
    pub vn: f64,
}

/// The impact of the disk moving at `v`, spinning at `omega`, on a rigid track whose tangent
/// and normal at the contact are `t` and `n`.
pub fn impact(
    disk: &Disk,
    [t, n]: [[f64; 2]; 2],
    v: [f64; 2],
    omega: f64,
    restitution: f64,
) -> Impact {
    let (m, a, c) = (disk.mass, disk.radius, disk.inertia());
    let vt = v[0] * t[0] + v[1] * t[1];
    let vn = v[0] * n[0] + v[1] * n[1];
    let vt_after = (m * a * vt - c * omega) / (m * a + c / a);
    let vn_after = -restitution * vn.min(0.0);
    let omega_after = -vt_after / a;
    let kinetic = |vt: f64, vn: f64, w: f64| 0.5 * m * (vt * vt + vn * vn) + 0.5 * c * w * w;
    Impact {
        velocity: [
            vt_after * t[0] + vn_after * n[0],
            vt_after * t[1] + vn_after * n[1],
        ],
        omega: omega_after,
        jn: m * (vn_after - vn),
        jt: m * (vt_after - vt),
        energy_lost: kinetic(vt, vn, omega) - kinetic(vt_after, vn_after, omega_after),
        vn: vn_after,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::Curve;

    /// Plastic landing of a uniform disk: vₜ' = (2/3)(vₜ − aΩ/2), the contact point at rest
    /// after, and the energy lost equal to the kinetic energy of the jump in velocity (the
    /// impulse does work ½ J·(v + v')).
    #[test]
    fn plastic_landing_conserves_angular_momentum_about_the_contact() {
        let disk = Disk {
            mass: 2.0,
            radius: 0.3,
        };
        let flat = Curve::Line {
            from: [0.0, 0.0],
            to: [10.0, 0.0],
        };
        let p = flat.at(1.0);
        let (v, omega) = ([3.0, -2.0], 4.0);
        let i = impact(&disk, [p.tangent(), p.normal()], v, omega, 0.0);
        let expect = 2.0 / 3.0 * (v[0] - disk.radius * omega / 2.0);
        assert!((i.velocity[0] - expect).abs() < 1e-14);
        assert!(i.velocity[1].abs() < 1e-15);
        assert!((i.velocity[0] + disk.radius * i.omega).abs() < 1e-14);
        let dv = [i.velocity[0] - v[0], i.velocity[1] - v[1]];
        let jump = 0.5 * disk.mass * (dv[0] * dv[0] + dv[1] * dv[1])
            + 0.5 * disk.inertia() * (i.omega - omega).powi(2);
        assert!(
            (i.energy_lost - jump).abs() < 1e-12 * jump,
            "{} vs {jump}",
            i.energy_lost
        );
    }
}
