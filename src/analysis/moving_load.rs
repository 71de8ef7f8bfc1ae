//! The closed form a moving force on a bridge is checked against: Frýba (Vibration of Solids
//! and Structures under Moving Loads, 3rd ed., 1999, §1.3, eq. 1.25, undamped). A force P
//! moving at v over a simply supported Euler–Bernoulli beam (EI, mass μ per length, span L),
//! from rest, drives each mode j as q_j'' + ω_j² q_j = (2P/(μL)) sin(jπvt/L) while it is on the
//! beam; after it leaves, each mode vibrates freely.

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
