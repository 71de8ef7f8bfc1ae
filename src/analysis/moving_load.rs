//! The closed form a moving force on a bridge is checked against: Frýba (Vibration of Solids
//! and Structures under Moving Loads, 3rd ed., 1999, §1.3, eq. 1.25, undamped). A force P
//! moving at v over a simply supported Euler–Bernoulli beam (EI, mass μ per length, span L),
//! from rest, drives each mode j as q_j'' + ω_j² q_j = (2P/(μL)) sin(jπvt/L) while it is on the
//! beam; after it leaves, each mode vibrates freely. With Rayleigh damping C = αM + βK each
//! mode is damped by its own ratio ζ_j = α/(2ω_j) + βω_j/2 (Frýba §1.3 with modal damping):
//! q_j'' + 2ζ_jω_j q_j' + ω_j² q_j = (2P/(μL)) sin(jπvt/L), the forced response from rest while
//! the force is on the beam and the damped free vibration after. A mode damped past critical
//! (ζ_j ≥ 1, the highest ones under stiffness-proportional damping) follows the force
//! quasi-statically: its steady response, whose transients die within a fraction of its
//! own period.

use std::f64::consts::PI;

#[derive(Clone, Copy, Debug)]
pub struct MovingForce {
    pub p: f64,
    pub span: f64,
    pub ei: f64,
    pub mu: f64,
    pub v: f64,
}

impl MovingForce {
    /// Deflection (positive in the force's direction) at x and time t, from `modes` modes.
    pub fn deflection(&self, x: f64, t: f64, modes: usize) -> f64 {
        let (l, v) = (self.span, self.v);
        let exit = l / v;
        (1..=modes)
            .map(|j| {
                let j = j as f64;
                let wj = (j * PI / l).powi(2) * (self.ei / self.mu).sqrt();
                let om = j * PI * v / l;
                let amp = 2.0 * self.p / (self.mu * l) / (wj * wj - om * om);
                let q = |t: f64| amp * ((om * t).sin() - om / wj * (wj * t).sin());
                let qd = |t: f64| amp * om * ((om * t).cos() - (wj * t).cos());
                let qj = if t <= exit {
                    q(t)
                } else {
                    let d = t - exit;
                    q(exit) * (wj * d).cos() + qd(exit) / wj * (wj * d).sin()
                };
                qj * (j * PI * x / l).sin()
            })
            .sum()
    }

    /// The same with Rayleigh damping C = αM + βK.
    pub fn deflection_damped(&self, x: f64, t: f64, modes: usize, alpha: f64, beta: f64) -> f64 {
        let (l, v) = (self.span, self.v);
        let exit = l / v;
        let f = 2.0 * self.p / (self.mu * l);
        (1..=modes)
            .map(|j| {
                let j = j as f64;
                let w = (j * PI / l).powi(2) * (self.ei / self.mu).sqrt();
                let zeta = alpha / (2.0 * w) + beta * w / 2.0;
                let om = j * PI * v / l;
                let d = (w * w - om * om).powi(2) + (2.0 * zeta * w * om).powi(2);
                let (a, b) = (f * (w * w - om * om) / d, -f * 2.0 * zeta * w * om / d);
                if zeta >= 1.0 {
                    let steady = if t <= exit {
                        a * (om * t).sin() + b * (om * t).cos()
                    } else {
                        0.0
                    };
                    return steady * (j * PI * x / l).sin();
                }
                let wd = w * (1.0 - zeta * zeta).sqrt();
                let c1 = -b;
                let c2 = (zeta * w * c1 - a * om) / wd;
                let decay = |t: f64| (-zeta * w * t).exp();
                let q = |t: f64| {
                    a * (om * t).sin()
                        + b * (om * t).cos()
                        + decay(t) * (c1 * (wd * t).cos() + c2 * (wd * t).sin())
                };
                let qd = |t: f64| {
                    a * om * (om * t).cos() - b * om * (om * t).sin()
                        + decay(t)
                            * ((-zeta * w * c1 + wd * c2) * (wd * t).cos()
                                + (-zeta * w * c2 - wd * c1) * (wd * t).sin())
                };
                let qj = if t <= exit {
                    q(t)
                } else {
                    let (q0, v0, s) = (q(exit), qd(exit), t - exit);
                    decay(s) * (q0 * (wd * s).cos() + (v0 + zeta * w * q0) / wd * (wd * s).sin())
                };
                qj * (j * PI * x / l).sin()
            })
            .sum()
    }

    /// The static midspan deflection under P at midspan, P L³ / (48 EI).
    pub fn static_midspan(&self) -> f64 {
        self.p * self.span.powi(3) / (48.0 * self.ei)
    }

    /// Largest midspan deflection over [0, t_end] divided by the static one, sampled every
    /// `dt`: the dynamic amplification.
    pub fn amplification(&self, t_end: f64, dt: f64) -> f64 {
        let steps = (t_end / dt).ceil() as usize;
        (0..=steps)
            .map(|k| self.deflection(0.5 * self.span, k as f64 * dt, 101).abs())
            .fold(0.0, f64::max)
            / self.static_midspan()
    }
}
