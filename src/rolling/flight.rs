//! The disk off the track: a free rigid body under gravity, in closed form, and the impact
//! that ends its flight.
//!
//! **Flight.** With no contact force the centre moves on the parabola
//! x(t) = x₀ + vₓ τ, y(t) = y₀ + v_y τ − g τ²/2 (τ = t − t₀) and the spin Ω stays constant.
//! Nothing is integrated, so a flight costs no steps and cannot lose energy.
//!
//! **Gap.** The distance from the centre to the track, minus the radius, measured along the
//! normal of the track's nearest point s*: g = (c − r(s*))·n(s*) − a, with s* found by Newton
//! on (c − r(s))·t(s) = 0 from the last s*. The disk lands where g returns to zero.
//!
//! **Landing.** The contact impulse J = Jₙ n + Jₜ t acts at the contact point P = c − a n.
//! Gravity is finite and does no impulse, so the angular momentum about P is conserved:
//! L = m (c − P) × v + C Ω = −m a vₜ + C Ω. The contact sticks (no slip), so after the impact
//! the disk rolls tangentially, vₜ' + a Ω' = 0, which with L' = L gives
//!   vₜ' = (m a vₜ − C Ω) / (m a + C / a),   Ω' = −vₜ' / a,
//! for a uniform disk (C = m a²/2) vₜ' = (2/3)(vₜ − aΩ/2). Normally the relative speed is
//! reversed and scaled by the restitution e: vₙ' = −e vₙ. The kinetic energy lost is what the
//! impact takes; it is booked so the energy balance still closes.

use super::Rolling;
use crate::curve::CurvePoint;
use crate::disk::Disk;

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

/// Where the centre is against the track.
#[derive(Clone, Copy, Debug)]
pub struct Gap {
    /// The track's nearest point.
    pub s: f64,
    /// Distance along the normal there, minus the radius.
    pub gap: f64,
    /// The nearest point is an end of a finite track and the centre lies past it.
    pub past_end: bool,
}

/// Newton iterations for the nearest point; each step is limited to a radius along the track,
/// so the iteration walks rather than jumps.
const NEAREST_ITERATIONS: usize = 50;

/// The gap of the centre `c` against the track, its nearest point searched from `s`.
pub fn gap(rolling: &Rolling, c: [f64; 2], s: f64) -> Gap {
    let (lo, hi) = rolling
        .curve
        .domain()
        .unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
    let a = rolling.disk.radius;
    let mut s = s.clamp(lo, hi);
    for _ in 0..NEAREST_ITERATIONS {
        let p = rolling.curve.at(s);
        let d = [c[0] - p.r[0], c[1] - p.r[1]];
        let t = p.tangent();
        let n = p.normal();
        let f = d[0] * t[0] + d[1] * t[1];
        let df = -p.speed() + p.psi_prime() * (d[0] * n[0] + d[1] * n[1]);
        let limit = a / p.speed().max(f64::MIN_POSITIVE);
        let step = if df < 0.0 {
            (-f / df).clamp(-limit, limit)
        } else {
            // Past the centre of curvature the distance has no minimum nearby: walk downhill.
            (f / p.speed().max(f64::MIN_POSITIVE)).clamp(-limit, limit)
        };
        let next = (s + step).clamp(lo, hi);
        let done = (next - s).abs() <= 1e-14 * (1.0 + s.abs());
        s = next;
        if done {
            break;
        }
    }
    let p = rolling.curve.at(s);
    let d = [c[0] - p.r[0], c[1] - p.r[1]];
    let n = p.normal();
    let t = p.tangent();
    let along = d[0] * t[0] + d[1] * t[1];
    let past_end = (s <= lo && along < 0.0) || (s >= hi && along > 0.0);
    Gap {
        s,
        gap: d[0] * n[0] + d[1] * n[1] - a,
        past_end,
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

/// The impact of the disk moving at `v`, spinning at `omega`, on the track at `p`.
pub fn impact(disk: &Disk, p: &CurvePoint, v: [f64; 2], omega: f64, restitution: f64) -> Impact {
    let (m, a, c) = (disk.mass, disk.radius, disk.inertia());
    let t = p.tangent();
    let n = p.normal();
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

/// How a flight ends.
#[derive(Clone, Copy, Debug)]
pub enum FlightEnd {
    /// Back on the track at `t`, touching at `s`.
    Lands { t: f64, s: f64 },
    /// Past the end of a finite track without landing.
    LeavesTrack { t: f64, s: f64 },
    /// Still in the air at the end of the run.
    Airborne,
}

/// A gap smaller than this share of the radius is contact: below it the gap is round-off of
/// the nearest-point search (1e-14 relative) times the scene's lengths.
const CONTACT: f64 = 1e-10;

/// Where the flight from `start` (at the track point `s0`) meets the track again before
/// `t_end`. The gap is sampled with steps over which the centre moves at most a twentieth of
/// the radius, and a crossing is bisected to round-off. The gap leaves zero slowly after a
/// lift-off (it grows as the cube of the time when the normal force falls through zero), so a
/// landing is a return to zero after the gap has opened, or a dip below zero by more than
/// round-off before it has.
pub fn land(rolling: &Rolling, flight: &Flight, s0: f64, t_end: f64) -> (FlightEnd, f64) {
    let a = rolling.disk.radius;
    let g = rolling.gravity.abs();
    let mut t = flight.t0;
    let mut s = s0;
    let mut opened = false;
    // The highest sample and its neighbours, refined at the end.
    let mut highest = (0.0_f64, t, t, t);
    while t < t_end {
        let v = flight.velocity(t);
        let speed = v[0].hypot(v[1]).max((g * a).sqrt()).max(f64::MIN_POSITIVE);
        let next = (t + 0.05 * a / speed).min(t_end);
        let here = gap(rolling, flight.centre(next), s);
        if here.past_end {
            return (
                FlightEnd::LeavesTrack { t: next, s: here.s },
                max_gap(rolling, flight, highest, s),
            );
        }
        if here.gap > highest.0 {
            highest = (here.gap, t, next, next + (next - t));
        }
        let touches = if opened {
            here.gap <= 0.0
        } else {
            here.gap < -CONTACT * a
        };
        if touches {
            let (mut lo, mut hi) = (t, next);
            let mut s_hit = here.s;
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                let m = gap(rolling, flight.centre(mid), s_hit);
                if m.gap > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                    s_hit = m.s;
                }
            }
            let at = gap(rolling, flight.centre(hi), s_hit);
            // A flight shorter than a sample has its top between the lift-off and the landing.
            if highest.0 <= 0.0 {
                highest = (0.0, flight.t0, hi, hi);
            }
            return (
                FlightEnd::Lands { t: hi, s: at.s },
                max_gap(rolling, flight, highest, s),
            );
        }
        opened |= here.gap > CONTACT * a;
        t = next;
        s = here.s;
    }
    (FlightEnd::Airborne, max_gap(rolling, flight, highest, s))
}

/// The largest gap of a flight: the highest sample (gap, and the times before, at and after
/// it) refined by golden-section search between its neighbours; for a flight no sample fell
/// in, between its lift-off and landing.
fn max_gap(rolling: &Rolling, flight: &Flight, highest: (f64, f64, f64, f64), s: f64) -> f64 {
    let (best, lo, _, hi) = highest;
    if hi <= lo {
        return best.max(0.0);
    }
    let g = |t: f64| gap(rolling, flight.centre(t), s).gap;
    best.max(g(super::golden_max(&g, lo, hi)))
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
        let i = impact(&disk, &p, v, omega, 0.0);
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
