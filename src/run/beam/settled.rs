//! When a free vibration can no longer move an extreme: on a modal beam with no load left to
//! come, each mode's energy e_k = ½(η̇_k² + ω_k² η_k²) only falls (its damping c_k ≥ 0 takes it
//! and nothing feeds it), so from a time on every mode stays within |η_k| ≤ √(2e_k)/ω_k and
//! |η̇_k| ≤ √(2e_k), and every quantity watched, a row over the modes, within the sum of the
//! row's magnitudes times those. Once each watched range already reaches past those bounds on
//! both sides, watching the rest of the run can change nothing it reports, and the exact
//! integration needs no step shorter than the run: a long damped free vibration costs its
//! output rows, not a sixteenth of a period at a time.

use super::modal_probes::{mode_rows, Rows};
use super::sensors;
use super::*;

/// What an extreme may still move by, of its own size, once the vibration is settled: a
/// hundredth of the finest accuracy a scene may ask (10⁻⁷). Without it a quantity that its
/// modes barely move would never settle: its extremes are round-off, and so is its bound.
const SLACK: f64 = 1e-9;

/// The bounds of the free vibration from a state on: per mode, the largest displacement and
/// the largest acceleration its energy allows.
struct ModeBounds {
    displacement: Vec<f64>,
    acceleration: Vec<f64>,
}

impl ModeBounds {
    /// From the modal state (η, η̇), with stiffness ω² and damping c per mode; `None` where a
    /// mode has no stiffness or negative damping (its energy is then not bounded by its start).
    fn new(eta: &[f64], eta_dot: &[f64], omega: &[f64], damping: &[f64]) -> Option<ModeBounds> {
        let mut displacement = Vec::with_capacity(omega.len());
        let mut acceleration = Vec::with_capacity(omega.len());
        for (((x, v), w), c) in eta.iter().zip(eta_dot).zip(omega).zip(damping) {
            if !(*w > 0.0 && *c >= 0.0) {
                return None;
            }
            let speed = (v * v + (w * x).powi(2)).sqrt();
            displacement.push(speed / w);
            // η̈ = −ω² η − c η̇: at most ω² √(2e)/ω + c √(2e).
            acceleration.push(speed * (w + c));
        }
        Some(ModeBounds {
            displacement,
            acceleration,
        })
    }

    fn of(row: &[f64], bounds: &[f64]) -> f64 {
        row.iter().zip(bounds).map(|(r, b)| r.abs() * b).sum()
    }

    /// (u, w, φ, a) at a point whose rows over the modes are `rows`, the acceleration over
    /// the first `kept` modes.
    fn at(&self, rows: &Rows, kept: usize) -> [f64; 4] {
        let kept = kept.min(self.acceleration.len());
        [
            Self::of(&rows[0], &self.displacement),
            Self::of(&rows[1], &self.displacement),
            Self::of(&rows[2], &self.displacement),
            Self::of(&rows[1][..kept], &self.acceleration[..kept]),
        ]
    }
}

impl Recorder<'_> {
    /// Whether the run is settled at (t, y), the end of a step the integrator took exactly:
    /// no load left to come, and no extreme watched that the free vibration from here on can
    /// still move (see the module's note).
    pub(super) fn settles(&mut self, t: f64, y: &[f64]) -> bool {
        let phase = &self.phase;
        let loaded = phase.loaded;
        let to_come = loaded
            .train
            .is_some_and(|train| t < train.gone(loaded.beam.length));
        if to_come || self.means.is_some() || !self.ledger.books_in_closed_form(phase) {
            return false;
        }
        let (Some(modal), Some(probes)) = (loaded.modal, &self.modal_probes) else {
            return false;
        };
        let n = loaded.dim();
        let (z, zd) = phase.split(y);
        let rayleigh = loaded.rayleigh();
        let damping: Vec<f64> = (modal.omega.iter())
            .map(|w| rayleigh.map_or(0.0, |r| r.alpha + r.beta * w * w))
            .collect();
        let Some(bounds) = ModeBounds::new(&z[..n], &zd[..n], &modal.omega, &damping) else {
            return false;
        };
        let kept = self.filter.as_ref().map_or(n, |f| f.kept.min(n));
        let w = &self.watches;
        let probes_held = probes.rows().iter().enumerate().all(|(p, rows)| {
            let b = bounds.at(rows, kept);
            let after = w.after_exit.ranges.get(p);
            (0..4).all(|c| within(&w.probes.ranges[4 * p + c], -b[c], b[c]))
                && (self.exit_t.is_none() || after.is_some_and(|r| within(r, -b[1], b[1])))
        });
        probes_held && self.stations_held(&bounds, kept)
    }

    /// Whether the envelope's stations (when watched) and the stretch through them already
    /// reach past what the free vibration within `bounds` can make of them.
    fn stations_held(&mut self, bounds: &ModeBounds, kept: usize) -> bool {
        if self.watches.along.ranges.is_empty() {
            return true;
        }
        if self.station_rows.is_none() {
            self.station_rows = mode_rows(self.phase.loaded, &self.envelope.x);
        }
        let Some(rows) = &self.station_rows else {
            return false;
        };
        let ranges = &self.watches.along.ranges;
        let each = rows.iter().enumerate().all(|(s, r)| {
            let b = bounds.at(r, kept);
            (0..4).all(|c| within(&ranges[4 * s + c], -b[c], b[c]))
        });
        // The drawing in of a linear beam's sliding end, watched beside the stretch, only
        // sizes a warning: it does not hold the stride back.
        each && self
            .stretch_bounds(rows, bounds)
            .is_some_and(|(lo, hi)| within(&ranges[4 * rows.len()], lo, hi))
    }

    /// The least and largest stretch of the axis through the stations the free vibration can
    /// make, as [`sensors::stretch`] measures it. Where it reads the strain alone, the
    /// difference of u along the axis between the end stations; else each piece of length h
    /// adds (δu(2h + δu) + δw²)/(c + h), c ≥ h − |δu| its chord, δu and δw the differences
    /// along and across the axis. `None` where an axial difference could reach the piece's
    /// length.
    fn stretch_bounds(&self, rows: &[Rows], bounds: &ModeBounds) -> Option<(f64, f64)> {
        let beam = self.phase.beam;
        let x = &self.envelope.x;
        // Per mode, the rows' difference from station i to j along (0) or across (1) the axis.
        let difference = |c: usize, i: usize, j: usize| -> f64 {
            (bounds.displacement.iter().enumerate())
                .map(|(k, d)| {
                    let local = |r: &Rows| beam.to_local([r[0][k], r[1][k]]);
                    (local(&rows[j])[c] - local(&rows[i])[c]).abs() * d
                })
                .sum()
        };
        let last = rows.len().saturating_sub(1);
        if sensors::grows_by_strain_alone(beam) {
            let reach = difference(0, 0, last);
            return Some((-reach, reach));
        }
        let (mut lo, mut hi) = (0.0, 0.0);
        for i in 0..last {
            let (h, du, dw) = (
                x[i + 1] - x[i],
                difference(0, i, i + 1),
                difference(1, i, i + 1),
            );
            if du >= h {
                return None;
            }
            let chord_and_h = 2.0 * h - du;
            lo -= du * (2.0 * h + du) / chord_and_h;
            hi += (du * (2.0 * h + du) + dw * dw) / chord_and_h;
        }
        Some((lo, hi))
    }
}

/// Whether a range already holds [lo, hi], within [`SLACK`]; never one that has seen nothing.
fn within(range: &Range, lo: f64, hi: f64) -> bool {
    if !(range.seen() && range.min.is_finite() && range.max.is_finite()) {
        return false;
    }
    let slack = SLACK * range.min.abs().max(range.max.abs());
    range.min <= lo + slack && range.max >= hi - slack
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three damped modes in free vibration, in closed form, and a point whose rows over them
    /// mix them: from every state on, its displacement and acceleration stay within the bounds
    /// formed at that state (checked at 4000 later times), and the bounds are not loose by more
    /// than the rows' mixing (the largest value seen reaches a fifth of them).
    #[test]
    fn a_free_vibration_stays_within_its_bounds() {
        let omega: [f64; 3] = [31.3, 124.0, 275.0];
        let damping: [f64; 3] = [0.9, 0.9 + 2.4e-4 * 124.0 * 124.0, 2.0];
        let start = [(1.0e-3, -0.05), (-2.0e-4, 0.3), (5.0e-5, 0.01)];
        let rows: Rows = [vec![0.0; 3], vec![1.0, -0.7, 0.4], vec![0.2, 0.5, -0.3]];
        let motion = |k: usize, t: f64| -> (f64, f64, f64) {
            let (w, c) = (omega[k], damping[k]);
            let wd = (w * w - 0.25 * c * c).sqrt();
            let (x0, v0) = start[k];
            let b = (v0 + 0.5 * c * x0) / wd;
            let e = (-0.5 * c * t).exp();
            let (s, co) = (wd * t).sin_cos();
            let x = e * (x0 * co + b * s);
            let v = -0.5 * c * x + e * wd * (b * co - x0 * s);
            (x, v, -w * w * x - c * v)
        };
        for t0 in [0.0, 0.05, 0.4] {
            let state: Vec<(f64, f64, f64)> = (0..3).map(|k| motion(k, t0)).collect();
            let eta: Vec<f64> = state.iter().map(|s| s.0).collect();
            let eta_dot: Vec<f64> = state.iter().map(|s| s.1).collect();
            let bounds = ModeBounds::new(&eta, &eta_dot, &omega, &damping).expect("bounded");
            let b = bounds.at(&rows, 3);
            let (mut w_seen, mut a_seen) = (0.0_f64, 0.0_f64);
            for i in 0..4000 {
                let t = t0 + 1e-3 * i as f64;
                let (w, a) = (0..3).fold((0.0, 0.0), |(w, a), k| {
                    let (x, _, acc) = motion(k, t);
                    (w + rows[1][k] * x, a + rows[1][k] * acc)
                });
                assert!(
                    w.abs() <= b[1] && a.abs() <= b[3],
                    "t {t}: w {w:e} of {:e}",
                    b[1]
                );
                (w_seen, a_seen) = (w_seen.max(w.abs()), a_seen.max(a.abs()));
            }
            assert!(
                w_seen > 0.2 * b[1] && a_seen > 0.2 * b[3],
                "{w_seen:e} of {:e}",
                b[1]
            );
        }
        assert!(ModeBounds::new(&[1.0], &[0.0], &[10.0], &[-0.1]).is_none());
        assert!(ModeBounds::new(&[1.0], &[0.0], &[0.0], &[0.1]).is_none());
    }

    /// A range settles a bound it reaches past on both sides, or within the slack of its own
    /// size; never one it falls short of, and never while it has seen nothing.
    #[test]
    fn a_range_holds_what_it_reaches_past() {
        let range = Range {
            min: -2.0,
            min_t: 0.0,
            max: 1.0,
            max_t: 1.0,
        };
        assert!(within(&range, -1.0, 1.0));
        assert!(within(&range, -2.0, 1.0 + 1e-10));
        assert!(!within(&range, -1.0, 1.0 + 1e-6));
        assert!(!within(&range, -2.1, 0.5));
        assert!(!within(&Range::EMPTY, -1.0, 1.0));
    }
}
