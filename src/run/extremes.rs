//! The extremes a run reports, located on the solution rather than read off the output grid.
//!
//! The run's recorder samples every accepted step at its start, its middle and its end on the
//! integrator's dense output. Where the parabola through the three samples turns inside the
//! step and its turning value would set a new extreme, the turning point is taken from the
//! solution: a [`Watch`] of headline quantities asks for the dense output there, refined by
//! successive parabolic interpolation (evaluations that only steps setting a record pay). A
//! watch of many quantities (the envelope's stations) is sampled at the step ends alone and
//! takes the turning value of the parabola through the last three, whose error on a response
//! the steps resolve is of fourth order in the step. Either way no extreme depends on how
//! often the history is written.

use serde::Serialize;

/// The least and the greatest value a quantity took, and when.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Range {
    pub min: f64,
    pub min_t: f64,
    pub max: f64,
    pub max_t: f64,
}

impl Range {
    pub const EMPTY: Range = Range {
        min: f64::INFINITY,
        min_t: f64::NAN,
        max: f64::NEG_INFINITY,
        max_t: f64::NAN,
    };

    /// Take in the value v at t (a NaN is no value).
    pub fn take(&mut self, t: f64, v: f64) {
        if v < self.min {
            (self.min, self.min_t) = (v, t);
        }
        if v > self.max {
            (self.max, self.max_t) = (v, t);
        }
    }

    /// Whether any value was taken.
    pub fn seen(&self) -> bool {
        self.min <= self.max
    }

    /// The largest |value| and when.
    pub fn largest_magnitude(&self) -> (f64, f64) {
        if !self.seen() {
            return (0.0, 0.0);
        }
        if -self.min > self.max {
            (-self.min, self.min_t)
        } else {
            (self.max, self.max_t)
        }
    }

    /// Half the distance from the least to the greatest value: the amplitude of a vibration
    /// about its middle.
    pub fn half_range(&self) -> Option<f64> {
        self.seen().then(|| 0.5 * (self.max - self.min))
    }
}

/// Three times, ascending, with what the parabolas through values at them share: the
/// inverse spacings of Newton's divided differences.
#[derive(Clone, Copy)]
struct Spacing {
    t: [f64; 3],
    inverse: [f64; 3],
}

impl Spacing {
    fn new(t: [f64; 3]) -> Self {
        let [a, b, c] = t;
        Spacing {
            t,
            inverse: [1.0 / (b - a), 1.0 / (c - b), 1.0 / (c - a)],
        }
    }

    /// The turning point of the parabola through the values v at the three times, where it
    /// lies strictly between the outer two: (t, value).
    fn turning(&self, v: [f64; 3]) -> Option<(f64, f64)> {
        let [a, b, c] = self.t;
        let [fa, fb, fc] = v;
        let d1 = (fb - fa) * self.inverse[0];
        let d2 = (fc - fb) * self.inverse[1];
        let k = (d2 - d1) * self.inverse[2];
        // The parabola's slope is linear: it turns between a and c only where its slopes there
        // differ in sign, which most quantities of most steps do not.
        let (slope_a, slope_c) = (d1 - k * (b - a), d2 + k * (c - b));
        if !(slope_a * slope_c < 0.0) {
            return None;
        }
        let x = 0.5 * (a + b) - 0.5 * d1 / k;
        (x > a && x < c).then(|| (x, fa + d1 * (x - a) + k * (x - a) * (x - b)))
    }
}

/// The turning point of the parabola through the three points (t, v), t ascending, where it
/// lies strictly between the outer two: (t, value).
fn turning(t: [f64; 3], v: [f64; 3]) -> Option<(f64, f64)> {
    Spacing::new(t).turning(v)
}

/// Successive parabolic interpolation on `value` from the samples `points` (ascending in t)
/// and the first guess `t`: each new point replaces the sample farthest from it, until the
/// turning point moves by less than [`TURNING_TOL`] of the step. Where it settles is not
/// evaluated: at a turning point the value moves as the square of the time, about
/// [`TURNING_TOL`]² of the quantity's swing over a step a quarter period long, and each
/// evaluation is a whole snapshot of the run (evaluated there, the HSLM sweep's extremes differ
/// by at most 7·10⁻¹³).
fn refine(mut points: [(f64, f64); 3], mut t: f64, mut value: impl FnMut(f64) -> f64) {
    let width = points[2].0 - points[0].0;
    for _ in 0..MAX_REFINEMENTS {
        let v = value(t);
        let far = (0..3)
            .max_by(|&i, &j| (points[i].0 - t).abs().total_cmp(&(points[j].0 - t).abs()))
            .unwrap_or(0);
        points[far] = (t, v);
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        let Some((next, _)) = turning(points.map(|p| p.0), points.map(|p| p.1)) else {
            return;
        };
        if (next - t).abs() <= TURNING_TOL * width {
            return;
        }
        t = next;
    }
}

/// Evaluations of the solution a turning point may take.
const MAX_REFINEMENTS: usize = 4;
/// A turning point is found when it moves by less than this share of its step.
const TURNING_TOL: f64 = 1e-6;

/// How a watch finds a turning point inside a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Turning {
    /// Evaluate the solution where the parabola turns.
    OnTheSolution,
    /// Take the parabola's turning value: for many quantities at once, where an evaluation of
    /// the solution for each would cost more than the run.
    OnTheParabola,
}

/// The extremes of a fixed list of quantities over the steps it is shown.
#[derive(Clone, Debug)]
pub struct Watch {
    pub ranges: Vec<Range>,
    turning: Turning,
}

impl Watch {
    pub fn new(count: usize, turning: Turning) -> Self {
        Watch {
            ranges: vec![Range::EMPTY; count],
            turning,
        }
    }

    /// Take in the quantities `v` at three times `t` (ascending: a step's start, middle and
    /// end, or the ends of two steps), and where a turning point between them would set a new
    /// extreme, the quantities `at` it (or the parabola's value, per the watch's [`Turning`]).
    pub fn record_step(
        &mut self,
        t: [f64; 3],
        v: [&[f64]; 3],
        mut at: impl FnMut(f64) -> Vec<f64>,
    ) {
        let mut asked: Vec<(usize, f64)> = Vec::new();
        let spacing = Spacing::new(t);
        for (k, range) in self.ranges.iter_mut().enumerate() {
            let v = [v[0][k], v[1][k], v[2][k]];
            for (&t, &v) in t.iter().zip(&v) {
                range.take(t, v);
            }
            let Some((tt, value)) = spacing.turning(v) else {
                continue;
            };
            if !(value < range.min || value > range.max) {
                continue;
            }
            match self.turning {
                Turning::OnTheSolution => asked.push((k, tt)),
                Turning::OnTheParabola => range.take(tt, value),
            }
        }
        for (k, guess) in asked {
            let samples = [(t[0], v[0][k]), (t[1], v[1][k]), (t[2], v[2][k])];
            let range = &mut self.ranges[k];
            refine(samples, guess, |tt| {
                let value = at(tt)[k];
                range.take(tt, value);
                value
            });
        }
    }

    /// Take in the quantities `v` at three times `t` (ascending), with the turning value of
    /// the parabola through them where it turns between them, whatever the watch's
    /// [`Turning`]: for samples of steps far shorter than what they resolve, whose dense
    /// output holds only the last.
    pub fn record_parabola(&mut self, t: [f64; 3], v: [&[f64]; 3]) {
        let spacing = Spacing::new(t);
        for (k, range) in self.ranges.iter_mut().enumerate() {
            let v = [v[0][k], v[1][k], v[2][k]];
            range.take(t[2], v[2]);
            if let Some((tt, value)) = spacing.turning(v) {
                range.take(tt, value);
            }
        }
    }

    /// Take in one value of each quantity at t.
    pub fn record_point(&mut self, t: f64, values: &[f64]) {
        for (range, &v) in self.ranges.iter_mut().zip(values) {
            range.take(t, v);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sine sampled at twelve steps a period: its samples miss the peak by up to
    /// 1 − cos(π/12) = 3.4 %, the turning points found on the solution by nothing, and the
    /// parabola's by its fourth-order error, (π/12)⁴/… of the amplitude.
    #[test]
    fn a_sine_between_its_samples_peaks_at_one() {
        let omega = 2.0 * std::f64::consts::PI;
        let h = 1.0 / 12.0;
        for turning in [Turning::OnTheSolution, Turning::OnTheParabola] {
            let mut w = Watch::new(1, turning);
            let sine = |t: f64| vec![(omega * t).sin()];
            for i in 0..36 {
                let t0 = 0.013 + i as f64 * h;
                let t = [t0, t0 + 0.5 * h, t0 + h];
                w.record_step(t, [&sine(t[0]), &sine(t[1]), &sine(t[2])], sine);
            }
            let r = w.ranges[0];
            let tol = if turning == Turning::OnTheSolution {
                1e-11
            } else {
                2e-4
            };
            assert!((r.max - 1.0).abs() < tol, "{turning:?}: {r:?}");
            assert!((r.min + 1.0).abs() < tol, "{turning:?}: {r:?}");
            // The peak's time from the nearest of 0.25 + k, on either side of it.
            let off_peak = (r.max_t - 0.25 + 0.5).rem_euclid(1.0) - 0.5;
            assert!(off_peak.abs() < 1e-3, "{turning:?}: {r:?}");
        }
    }
}
