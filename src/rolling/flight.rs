//! The disk off a rigid curve: where its centre is against the curve, and where its flight
//! (in closed form, [`crate::disk::flight`]) ends on it.
//!
//! **Gap.** The distance from the centre to the track, minus the radius, measured along the
//! normal of the track's nearest point s*: g = (c − r(s*))·n(s*) − a, with s* found by Newton
//! on (c − r(s))·t(s) = 0 from the last s*. The disk lands where g returns to zero.

use super::Rolling;
use crate::disk::flight::Flight;

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
        // At least the next double: late in a long run a small disk's sample step falls
        // below the times' spacing, where t + step is t again.
        let next = (t + 0.05 * a / speed).min(t_end).max(t.next_up());
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
