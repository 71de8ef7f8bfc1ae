//! TR-BDF2 (Bank et al. 1985; Hosea & Shampine 1996, Matlab's ode23tb): a trapezoidal stage to
//! t + γh and a BDF2 stage to t + h, with γ = 2 − √2 so that both stages share the iteration
//! matrix M − d h J (d = γ/2). One-step, L-stable, second order; the error estimate is the
//! method's leading truncation term C h³ y''' with y''' from the three stage derivatives.
//!
//! The implicit stages are solved by the shared stage solver (`stage_solver.rs`).

use super::stage_solver::{DirkMethod, DirkState};
use super::{Ctx, Dynamics, SolveError};

const GAMMA: f64 = 2.0 - std::f64::consts::SQRT_2;
const D: f64 = GAMMA / 2.0;
/// Local error constant of TR-BDF2: (−3γ² + 4γ − 2) / (12 (2 − γ)) ≈ −0.0404.
const ERR_CONST: f64 = (-3.0 * GAMMA * GAMMA + 4.0 * GAMMA - 2.0) / (12.0 * (2.0 - GAMMA));

pub struct TrBdf2 {
    y_gamma: Vec<f64>,
    yp_gamma: Vec<f64>,
}

impl TrBdf2 {
    pub fn new(n: usize) -> Self {
        TrBdf2 {
            y_gamma: vec![0.0; n],
            yp_gamma: vec![0.0; n],
        }
    }
}

impl DirkMethod for TrBdf2 {
    fn error_order(&self) -> u32 {
        2
    }

    fn stages(
        &mut self,
        s: &mut DirkState,
        p: &dyn Dynamics,
        t: f64,
        y: &[f64],
        h: f64,
        ctx: &mut Ctx,
    ) -> Result<bool, SolveError> {
        let n = y.len();
        let dh = D * h;
        s.newton.factor(p, t, y, dh, ctx)?;
        // Trapezoidal stage: z = y + d h (y'_n + y'_γ).
        let base: Vec<f64> = (0..n).map(|i| y[i] + dh * s.ends.yp[i]).collect();
        let mut z: Vec<f64> = (0..n).map(|i| y[i] + GAMMA * h * s.ends.yp[i]).collect();
        if !s.newton.solve(p, t + GAMMA * h, &base, &mut z, dh, ctx) {
            return Ok(false);
        }
        for i in 0..n {
            self.yp_gamma[i] = (z[i] - base[i]) / dh;
        }
        self.y_gamma.copy_from_slice(&z);
        // BDF2 stage through y_n, y_γ, y_{n+1}.
        let w1 = 1.0 / (GAMMA * (2.0 - GAMMA));
        let w0 = (1.0 - GAMMA).powi(2) / (GAMMA * (2.0 - GAMMA));
        let base: Vec<f64> = (0..n).map(|i| w1 * self.y_gamma[i] - w0 * y[i]).collect();
        for i in 0..n {
            z[i] = self.y_gamma[i] + (1.0 - GAMMA) * h * self.yp_gamma[i];
        }
        if !s.newton.solve(p, t + h, &base, &mut z, dh, ctx) {
            return Ok(false);
        }
        for i in 0..n {
            s.yp_new[i] = (z[i] - base[i]) / dh;
        }
        s.y_new.copy_from_slice(&z);
        Ok(true)
    }

    fn estimate(&mut self, s: &DirkState, _p: &dyn Dynamics, _t: f64, h: f64) -> Vec<f64> {
        (0..s.y_new.len())
            .map(|i| {
                let upper = (s.yp_new[i] - self.yp_gamma[i]) / (1.0 - GAMMA);
                let lower = (self.yp_gamma[i] - s.ends.yp[i]) / GAMMA;
                2.0 * ERR_CONST * h * (upper - lower)
            })
            .collect()
    }
}
